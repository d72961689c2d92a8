//! ArmLab's entry point: a native window (`cargo run`) or the web page (built by trunk).

#[cfg(not(target_arch = "wasm32"))]
fn main() -> eframe::Result {
    let options = eframe::NativeOptions {
        renderer: eframe::Renderer::Wgpu,
        viewport: egui::ViewportBuilder::default()
            .with_title("ArmLab")
            .with_inner_size([1400.0, 860.0]),
        ..Default::default()
    };
    // A hash on the command line opens that state, like a shared link: `armlab '#robot=ur10'`.
    let hash = std::env::args().nth(1).unwrap_or_default();
    eframe::run_native(
        "ArmLab",
        options,
        Box::new(move |cc| Ok(Box::new(armlab::app::ArmLabApp::new(cc, &hash)))),
    )
}

#[cfg(target_arch = "wasm32")]
fn main() {
    armlab::app::web::start();
}
