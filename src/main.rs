//! ArmLab's entry point: a native window (`cargo run`) or the web page (built by trunk).

#[cfg(not(target_arch = "wasm32"))]
fn main() -> eframe::Result {
    let options = eframe::NativeOptions {
        renderer: eframe::Renderer::Wgpu,
        viewport: egui::ViewportBuilder::default()
            .with_title("ArmLab")
            .with_inner_size([1400.0, 860.0]),
        dithering: armlab::app::DITHERING,
        ..Default::default()
    };
    // A hash on the command line opens that state, like a shared link: `armlab '#robot=ur10'`.
    // Without one, the last session returns (written when the window closes).
    let session_file = armlab_session::session::native_session_file();
    let link = std::env::args().nth(1).unwrap_or_default();
    let stored = session_file
        .as_deref()
        .and_then(armlab::app::platform::native::stored_session);
    eframe::run_native(
        "ArmLab",
        options,
        Box::new(move |cc| {
            let mut app = armlab::app::ArmLabApp::new_with(
                cc,
                &link,
                stored.as_deref(),
                armlab::app::Preferences::default(),
            );
            app.set_session_file(session_file);
            Ok(Box::new(app))
        }),
    )
}

#[cfg(target_arch = "wasm32")]
fn main() {
    armlab::app::page::start();
}
