//! The 3D view's work that runs over frames before it draws: the motion lab's simulation
//! and collision check, and the overlays that fill a few milliseconds at a time.

use armlab_session::settings::Overlay;

use super::workspace;
use crate::app::platform::clock;
use crate::app::platform::clock::FrameTime;
use crate::app::state::model::Model;

/// The motion lab's frame: the collision check of the pose, and the simulation run for
/// the frame's time (repainting while the arm moves).
pub(super) fn advance_motion(model: &mut Model, ui: &egui::Ui, timing: &mut FrameTime) {
    if model.motion().collisions_on() {
        let t0 = clock::now_ms();
        model.update_collisions();
        timing.motion_ms += clock::now_ms() - t0;
    }
    if model.motion().on() {
        // The simulation runs the frame's real time × the time scale in 1 ms steps
        // (at most 0.1 s a frame: a stalled frame slows the motion, never jumps it).
        let dt = f64::from(ui.input(|i| i.stable_dt).min(0.1));
        let t0 = clock::now_ms();
        timing.motion_steps += model.advance_motion(dt) as f64;
        timing.motion_ms += clock::now_ms() - t0;
        if model.motion().moving() || model.paths().visit().is_some() {
            ui.ctx().request_repaint();
        }
    }
}

/// The overlays that fill over frames: the workspace cloud (a few milliseconds a frame,
/// repainting until full), the sphere of tool directions and the ghosts' solutions
/// (redone when the target moves).
pub(super) fn fill_overlays(model: &mut Model, ui: &egui::Ui, timing: &mut FrameTime) {
    crate::app::state::branches::ghost_rows(model);
    if model.settings().overlays.contains(Overlay::Workspace) {
        let measure = workspace::measure(model);
        let (samples, budget) = (workspace::SAMPLES, workspace::BUDGET_MS);
        let ms = model.fill_workspace(measure, samples, budget, clock::now_ms);
        timing.workspace_ms += ms;
        if model.workspace().is_some_and(|c| !c.is_full()) {
            ui.ctx().request_repaint();
        }
    }
    if model.settings().overlays.contains(Overlay::Directions) {
        timing.workspace_ms += model.fill_directions(clock::now_ms);
    }
    if model.paths().shown() {
        let t0 = clock::now_ms();
        model.update_path_plan();
        timing.motion_ms += clock::now_ms() - t0;
    }
}
