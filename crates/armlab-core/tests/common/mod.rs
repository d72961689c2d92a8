//! Helpers shared by the core's test files (native and wasm).
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
#![allow(dead_code)]

use armlab_core::{Robot, SplitMix64, Task, ToolAxis, preset, preset_ids, tool_pose};
use nalgebra::{IsometryMatrix3, Matrix3, Vector3};

/// Every preset, loaded.
pub fn all_presets() -> Vec<(String, Robot)> {
    preset_ids()
        .map(|id| (id.to_string(), preset(id).expect("preset loads")))
        .collect()
}

/// The largest absolute entry difference of two 3×3 matrices.
pub fn max_diff3(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).abs().max()
}

/// Asserts two vectors agree within `tol` per component, with a message.
pub fn assert_vec_near(what: &str, got: &Vector3<f64>, want: [f64; 3], tol: f64) {
    let want = Vector3::from(want);
    assert!(
        (got - want).abs().max() <= tol,
        "{what}: got {got:?}, want {want:?} (tolerance {tol})"
    );
}

/// Asserts a rotation matrix equals the rows given, within `tol`.
pub fn assert_rot_near(what: &str, got: &Matrix3<f64>, rows: [[f64; 3]; 3], tol: f64) {
    let want = Matrix3::from_fn(|r, c| rows[r][c]);
    assert!(
        max_diff3(got, &want) <= tol,
        "{what}: got {got}, want {want} (tolerance {tol})"
    );
}

/// A seeded generator, the same on every target.
pub fn rng(seed: u64) -> SplitMix64 {
    SplitMix64::new(seed)
}

/// The tests' own error of the tool at `q` against `target` for `task`, independent of the
/// solver's error function: the position distance (robot units) and the rotation angle
/// (radians) — of R_targetᵀ·R for a full pose, between the chosen tool axis and the
/// target's for a 5D task, 0 for position only. Angles come from
/// ‖R − R_target‖_F = 2√2·sin(θ/2) and atan2(|a × b|, a·b), exact near 0.
pub fn task_error(
    robot: &Robot,
    q: &[f64],
    target: &IsometryMatrix3<f64>,
    task: Task,
) -> (f64, f64) {
    let pose = tool_pose(robot, q);
    let position = (target.translation.vector - pose.translation.vector).norm();
    let (r, rt) = (pose.rotation.matrix(), target.rotation.matrix());
    let angle = match task {
        Task::Position => 0.0,
        Task::FullPose => {
            let chord = (r - rt).norm() / (2.0 * std::f64::consts::SQRT_2);
            2.0 * chord.min(1.0).asin()
        }
        Task::PositionAndAxis(axis) => {
            let k = match axis {
                ToolAxis::X => 0,
                ToolAxis::Y => 1,
                ToolAxis::Z => 2,
            };
            let (a, b) = (r.column(k), rt.column(k));
            a.cross(&b).norm().atan2(a.dot(&b))
        }
    };
    (position, angle)
}

/// Asserts the tool at `q` reaches `target` for `task` within `position` (robot units)
/// and `angle` (radians), by [`task_error`].
pub fn assert_reaches(
    what: &str,
    robot: &Robot,
    q: &[f64],
    target: &IsometryMatrix3<f64>,
    task: Task,
    position: f64,
    angle: f64,
) {
    let (pe, oe) = task_error(robot, q, target, task);
    assert!(
        pe <= position && oe <= angle,
        "{what}: q = {q:?} misses the target by {pe} (limit {position}) and {oe} rad (limit {angle})"
    );
}

/// Asserts every joint value lies within its joint's limits (1e−9 slack), read from the
/// robot directly.
pub fn assert_within_limits(what: &str, robot: &Robot, q: &[f64]) {
    assert_eq!(q.len(), robot.dof(), "{what}");
    for (i, (v, joint)) in q.iter().zip(&robot.joints).enumerate() {
        assert!(
            *v >= joint.limits.min - 1e-9 && *v <= joint.limits.max + 1e-9,
            "{what}: joint {} = {v} outside [{}, {}]",
            i + 1,
            joint.limits.min,
            joint.limits.max
        );
    }
}
