//! The target and the camera from the keyboard, while no control has the keyboard: the
//! arrow keys move the target in the view's plane (right, up as the view shows them),
//! Page Up and Page Down along the view's axis (away, toward), a fiftieth of the arm's
//! reach a press, with Shift a five-hundredth; with Alt, the arrows orbit the camera and
//! Page Up / Page Down zoom it. The arm follows the target as it does a drag.

use egui::Key;
use nalgebra::Vector3;

use crate::app::state::model::Model;
use crate::render::camera::OrbitCamera;

/// A press's step as a share of the arm's reach, coarse and fine (Shift).
const STEP: (f64, f64) = (0.02, 0.002);
/// The camera's turn per press of Alt and an arrow, in orbit units (a pointer pixel's
/// turn; 12 are about 5.5°).
const ORBIT: f64 = 12.0;
/// IK steps a press allows the arm to follow the target.
const FOLLOW_STEPS: usize = 60;

/// The presses of the frame as a move in view axes (right, up, away) and whether Alt
/// (the camera) or Shift (fine) was held.
fn presses(ctx: &egui::Context) -> Option<(Vector3<f64>, bool, bool)> {
    ctx.input(|i| {
        let mut d = Vector3::zeros();
        for e in &i.events {
            if let egui::Event::Key {
                key,
                pressed: true,
                modifiers,
                ..
            } = e
                && !modifiers.command
            {
                match key {
                    Key::ArrowRight => d.x += 1.0,
                    Key::ArrowLeft => d.x -= 1.0,
                    Key::ArrowUp => d.y += 1.0,
                    Key::ArrowDown => d.y -= 1.0,
                    Key::PageUp => d.z += 1.0,
                    Key::PageDown => d.z -= 1.0,
                    _ => {}
                }
            }
        }
        (d != Vector3::zeros()).then_some((d, i.modifiers.alt, i.modifiers.shift))
    })
}

/// The view's right, up and away directions in the world.
fn view_axes(camera: &OrbitCamera) -> [Vector3<f64>; 3] {
    let away = (camera.focus - camera.eye()).normalize();
    let right = away
        .cross(&Vector3::z())
        .try_normalize(1e-9)
        .unwrap_or_else(Vector3::x);
    let up = right.cross(&away);
    [right, up, away]
}

/// Moves the target or the camera by the frame's keys; returns whether anything moved.
/// Nothing happens while a widget has the keyboard (its own arrows) or a text field does.
pub fn handle_keys(camera: &mut OrbitCamera, model: &mut Model, ctx: &egui::Context) -> bool {
    if ctx.memory(|m| m.focused().is_some()) {
        return false;
    }
    let Some((d, alt, shift)) = presses(ctx) else {
        return false;
    };
    if alt {
        camera.orbit(-d.x * ORBIT, d.y * ORBIT);
        camera.zoom(1.1f64.powf(d.z));
        return true;
    }
    let step = model.robot().reach() * if shift { STEP.1 } else { STEP.0 };
    let [right, up, away] = view_axes(camera);
    let mut target = *model.target();
    target.translation.vector += (right * d.x + up * d.y + away * d.z) * step;
    model.set_target(target);
    for _ in 0..FOLLOW_STEPS {
        if !model.drag_step() {
            break;
        }
    }
    true
}
