//! The target and the camera from the keyboard, while no control has the keyboard: the
//! arrow keys move the target in the view's plane (right, up as the view shows them),
//! Page Up and Page Down along the view's axis (away, toward), a fiftieth of the arm's
//! reach a press, with Shift a five-hundredth; with Alt, the arrows orbit the camera and
//! Page Up / Page Down zoom it. When the task counts the tool's orientation, letter keys
//! turn the target about the view's axes (five degrees a press, with Shift one): J and L
//! about the up axis (its near side to the left, to the right), I and K about the right
//! axis (near side up, down), U and O about the view's axis (counterclockwise, clockwise as
//! seen). Letters, because a focused canvas keeps them from the browser and a screen
//! reader in focus mode, and the app's other shortcuts (F, P, digits) leave them free. The
//! arm follows the target as it does a drag.

use armlab_core::Task;
use egui::Key;
use nalgebra::{Rotation3, Unit, Vector3};

use crate::app::state::model::Model;
use crate::render::camera::OrbitCamera;

/// A press's step as a share of the arm's reach, coarse and fine (Shift).
const STEP: (f64, f64) = (0.02, 0.002);
/// The camera's turn per press of Alt and an arrow, in orbit units (a pointer pixel's
/// turn; 12 are about 5.5°).
const ORBIT: f64 = 12.0;
/// IK steps a press allows the arm to follow the target.
const FOLLOW_STEPS: usize = 60;
/// The factor a zoom button changes the camera's distance by.
pub const ZOOM_STEP: f64 = 1.25;
/// A turning press's angle in degrees, coarse and fine (Shift).
pub const TURN_DEG: (f64, f64) = (5.0, 1.0);

/// The turning keys: each with the view axis it turns about (right, up, away) and the
/// sign. (right, up, away) is left-handed: a right-hand turn about up swings the near side
/// to the right, about right swings it down, about away turns the picture clockwise.
const TURN_KEYS: [(Key, usize, f64); 6] = [
    (Key::L, 1, 1.0),
    (Key::J, 1, -1.0),
    (Key::K, 0, 1.0),
    (Key::I, 0, -1.0),
    (Key::O, 2, 1.0),
    (Key::U, 2, -1.0),
];

/// The moving keys: each with the view axis it moves along (right, up, away) and the sign.
const MOVE_KEYS: [(Key, usize, f64); 6] = [
    (Key::ArrowRight, 0, 1.0),
    (Key::ArrowLeft, 0, -1.0),
    (Key::ArrowUp, 1, 1.0),
    (Key::ArrowDown, 1, -1.0),
    (Key::PageUp, 2, 1.0),
    (Key::PageDown, 2, -1.0),
];

/// The frame's presses of `keys` summed along their axes, leaving out those with Ctrl or
/// Cmd (the browser's shortcuts) and, with `alt_too`, those with Alt.
fn summed(i: &egui::InputState, keys: &[(Key, usize, f64)], alt_too: bool) -> Vector3<f64> {
    let mut v = Vector3::zeros();
    for e in &i.events {
        if let egui::Event::Key {
            key,
            pressed: true,
            modifiers,
            ..
        } = e
            && !modifiers.command
            && !(alt_too && modifiers.alt)
            && let Some((_, axis, sign)) = keys.iter().find(|(k, ..)| k == key)
        {
            v[*axis] += sign;
        }
    }
    v
}

/// The turning presses of the frame as turns (in presses) about the view's right, up and
/// away axes, signed so that a positive turn is the right-hand rotation about that axis.
fn turns(ctx: &egui::Context) -> Option<(Vector3<f64>, bool)> {
    ctx.input(|i| {
        let t = summed(i, &TURN_KEYS, true);
        (t != Vector3::zeros()).then_some((t, i.modifiers.shift))
    })
}

/// The rotation that a frame's turns make, in the world, about the view's axes.
pub fn turn_rotation(axes: &[Vector3<f64>; 3], t: &Vector3<f64>, shift: bool) -> Rotation3<f64> {
    let step = if shift { TURN_DEG.1 } else { TURN_DEG.0 }.to_radians();
    let mut r = Rotation3::identity();
    for (axis, n) in axes.iter().zip(t.iter()) {
        if *n != 0.0 {
            r = Rotation3::from_axis_angle(&Unit::new_normalize(*axis), n * step) * r;
        }
    }
    r
}

/// The presses of the frame as a move in view axes (right, up, away) and whether Alt
/// (the camera) or Shift (fine) was held.
fn presses(ctx: &egui::Context) -> Option<(Vector3<f64>, bool, bool)> {
    ctx.input(|i| {
        let d = summed(i, &MOVE_KEYS, false);
        (d != Vector3::zeros()).then_some((d, i.modifiers.alt, i.modifiers.shift))
    })
}

/// The view's right, up and away directions in the world.
pub fn view_axes(camera: &OrbitCamera) -> [Vector3<f64>; 3] {
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
    let turn = turns(ctx).filter(|_| model.task() != Task::Position);
    let Some((d, alt, shift)) = presses(ctx) else {
        return turn.is_some_and(|(t, shift)| {
            turn_target(camera, model, &t, shift);
            true
        });
    };
    if let Some((t, shift)) = turn {
        turn_target(camera, model, &t, shift);
    }
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
    follow(model);
    true
}

/// Turns the target about its own position by the frame's turns, and the arm follows.
fn turn_target(camera: &OrbitCamera, model: &mut Model, t: &Vector3<f64>, shift: bool) {
    let r = turn_rotation(&view_axes(camera), t, shift);
    let mut target = *model.target();
    target.rotation = r * target.rotation;
    model.set_target(target);
    follow(model);
}

/// Lets the arm follow a target moved by keys, as it follows a drag.
fn follow(model: &mut Model) {
    for _ in 0..FOLLOW_STEPS {
        if !model.drag_step() {
            break;
        }
    }
}
