//! The app's main-thread time per frame while the UR10 target is dragged, natively and
//! without a GPU: egui layout of every panel plus the IK step, then egui's tessellation.
//! Prints JSON. The browser's figure comes from the page itself (`web/tests/e2e.test.mjs`);
//! this one is for profiling the same frames (`perf record`) on a quiet machine.
//!
//! `cargo run --release --bin framebench [frames]`

use std::time::Instant;

use armlab::app::ArmLabApp;
use armlab::app::widgets::style;
use armlab_bench::stats::Summary;
use armlab_session::session::Session;

/// Median, 95th percentile and maximum of a frame-time list, in milliseconds.
fn summary(mut ms: Vec<f64>) -> serde_json::Value {
    match Summary::of(&mut ms) {
        Some(s) => serde_json::json!({ "median_ms": s.median, "p95_ms": s.p95, "max_ms": s.max }),
        None => serde_json::Value::Null,
    }
}

fn main() {
    let frames: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000);
    let session = match Session::from_hash("robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=position") {
        Ok(Some(session)) => session,
        _ => Session::default_session(),
    };
    let ctx = egui::Context::default();
    style::install_fonts(&ctx);
    style::install(&ctx, false, false, style::Screen::of(&ctx));
    let mut app = ArmLabApp::with_session(session);
    let start = *app.model().target();
    let radius = app.model().robot().reach() * 0.25;
    let screen = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0));
    let (mut ui_ms, mut tessellate_ms) = (Vec::new(), Vec::new());
    for frame in 0..frames + 60 {
        // The target goes round a circle in the y-z plane, as a hand drags it.
        let angle = frame as f64 * 0.02;
        let mut target = start;
        target.translation.vector.y += radius * angle.sin();
        target.translation.vector.z += radius * (1.0 - angle.cos());
        let input = egui::RawInput {
            screen_rect: Some(screen),
            time: Some(frame as f64 / 60.0),
            ..Default::default()
        };
        let t0 = Instant::now();
        app.model_mut().set_target(target);
        app.model_mut().drag_step();
        let output = ctx.run_ui(input, |ui| app.show(ui, None));
        let t1 = Instant::now();
        let meshes = ctx.tessellate(output.shapes, output.pixels_per_point);
        std::hint::black_box(meshes);
        let t2 = Instant::now();
        if frame >= 60 {
            ui_ms.push((t1 - t0).as_secs_f64() * 1e3);
            tessellate_ms.push((t2 - t1).as_secs_f64() * 1e3);
        }
    }
    let report = serde_json::json!({
        "robot": app.model().robot().name,
        "frames": frames,
        "window": [screen.width(), screen.height()],
        "app (IK + egui layout of every panel)": summary(ui_ms),
        "egui tessellation": summary(tessellate_ms),
        "runtime": format!("native {} ({}), no GPU (the 3D view is not drawn)", std::env::consts::ARCH, std::env::consts::OS),
    });
    match serde_json::to_string_pretty(&report) {
        Ok(text) => println!("{text}"),
        Err(e) => eprintln!("cannot print the report: {e}"),
    }
}
