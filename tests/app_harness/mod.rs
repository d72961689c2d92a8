//! The whole app in egui_kittest, for the UI tests (`tests/ui.rs`, `tests/ui_finnish.rs`).

use armlab::app::ArmLabApp;
use egui_kittest::Harness;

/// The app opened at a link `hash` in a window of `size` points, rendering with wgpu on the
/// machine's Vulkan adapter, after three frames.
pub fn open_app(hash: &str, size: [f32; 2]) -> Harness<'static, ArmLabApp> {
    let hash = hash.to_string();
    let mut h = Harness::builder()
        .with_size(size)
        .wgpu()
        .build_eframe(move |cc| ArmLabApp::new(cc, &hash));
    h.run_steps(3);
    h
}
