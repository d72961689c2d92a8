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

/// Turns the mouse wheel by `dy` points over `over` (negative: the content moves up, the
/// view goes down), as a person scrolls a panel, then lets egui's scroll animation end.
pub fn wheel(h: &mut Harness<'_, ArmLabApp>, over: egui::Pos2, dy: f32) {
    h.event(egui::Event::PointerMoved(over));
    h.event(egui::Event::MouseWheel {
        unit: egui::MouseWheelUnit::Point,
        delta: egui::vec2(0.0, dy),
        phase: egui::TouchPhase::Move,
        source: egui::MouseWheelSource::Unknown,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(20);
}
