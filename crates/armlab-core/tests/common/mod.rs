//! Helpers shared by the core's test files (native and wasm).
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
#![allow(dead_code)]

use armlab_core::{
    Convention, IkSettings, JointKind, Robot, SplitMix64, Task, ToolAxis, preset, preset_ids,
    tool_pose,
};
use nalgebra::{IsometryMatrix3, Matrix3, Matrix4, Rotation3, Translation3, Vector3};

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

/// The tests' own forward kinematics: the link transforms written out from the DH
/// formulas (docs/kinematics.md §2) as 4×4 matrices and multiplied, where the core runs a
/// recurrence on the frame's columns. It reads only the robot's data (rows, convention,
/// base and tool transforms), so a test that checks the core's answers with it does not
/// check the core against itself.
#[derive(Debug, Clone)]
pub struct OwnFk {
    /// Per joint, in the world: a point on its axis and the axis' unit direction.
    pub axes: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// The tool pose in the world.
    pub tool: IsometryMatrix3<f64>,
}

/// [`OwnFk`] of `robot` at `q`.
pub fn own_fk(robot: &Robot, q: &[f64]) -> OwnFk {
    assert_eq!(q.len(), robot.dof(), "one value per joint");
    let axis_of = |t: &Matrix4<f64>| {
        (
            Vector3::new(t[(0, 3)], t[(1, 3)], t[(2, 3)]),
            Vector3::new(t[(0, 2)], t[(1, 2)], t[(2, 2)]),
        )
    };
    let mut t = robot.world_from_base.to_homogeneous();
    let mut axes = Vec::with_capacity(q.len());
    for (joint, &v) in robot.joints.iter().zip(q) {
        let dh = joint.dh;
        let (theta, d) = match joint.kind {
            JointKind::Revolute => (dh.theta + v, dh.d),
            JointKind::Prismatic => (dh.theta, dh.d + v),
        };
        let (st, ct, sa, ca, a) = (
            theta.sin(),
            theta.cos(),
            dh.alpha.sin(),
            dh.alpha.cos(),
            dh.a,
        );
        match robot.convention {
            // Rot_z(θ)·Trans_z(d)·Trans_x(a)·Rot_x(α); the joint turns about z_{i−1}.
            Convention::Standard => {
                axes.push(axis_of(&t));
                #[rustfmt::skip]
                let link = Matrix4::new(
                    ct, -st * ca, st * sa, a * ct,
                    st, ct * ca, -ct * sa, a * st,
                    0.0, sa, ca, d,
                    0.0, 0.0, 0.0, 1.0,
                );
                t *= link;
            }
            // Rot_x(α)·Trans_x(a)·Rot_z(θ)·Trans_z(d); the joint turns about z_i.
            Convention::Modified => {
                #[rustfmt::skip]
                let link = Matrix4::new(
                    ct, -st, 0.0, a,
                    st * ca, ct * ca, -sa, -sa * d,
                    st * sa, ct * sa, ca, ca * d,
                    0.0, 0.0, 0.0, 1.0,
                );
                t *= link;
                axes.push(axis_of(&t));
            }
        }
    }
    t *= robot.flange_from_tool.to_homogeneous();
    let rotation = Rotation3::from_matrix_unchecked(t.fixed_view::<3, 3>(0, 0).into_owned());
    let translation = Translation3::new(t[(0, 3)], t[(1, 3)], t[(2, 3)]);
    OwnFk {
        axes,
        tool: IsometryMatrix3::from_parts(translation, rotation),
    }
}

/// The position distance and the rotation angle between two poses, the angle of
/// R_aᵀ·R_b from ‖R_a − R_b‖_F = 2√2·sin(θ/2) (exact near 0, where acos of the trace
/// loses half the digits).
pub fn pose_distance(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>) -> (f64, f64) {
    let position = (a.translation.vector - b.translation.vector).norm();
    let chord =
        (a.rotation.matrix() - b.rotation.matrix()).norm() / (2.0 * std::f64::consts::SQRT_2);
    (position, 2.0 * chord.min(1.0).asin())
}

/// Asserts that the tool at `q`, by the tests' own forward kinematics ([`own_fk`]), is
/// within `position` (robot units) and `angle` (radians) of the full pose `target`.
pub fn assert_own_pose_near(
    what: &str,
    robot: &Robot,
    q: &[f64],
    target: &IsometryMatrix3<f64>,
    position: f64,
    angle: f64,
) {
    let (pe, oe) = pose_distance(&own_fk(robot, q).tool, target);
    assert!(
        pe <= position && oe <= angle,
        "{what}: by the tests' own FK, q = {q:?} is {pe} from the target (limit {position}) \
         and turned {oe} rad from it (limit {angle})"
    );
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

/// Every task: position, the three 5D tasks, the full pose.
pub const TASKS: [Task; 5] = [
    Task::Position,
    Task::PositionAndAxis(ToolAxis::X),
    Task::PositionAndAxis(ToolAxis::Y),
    Task::PositionAndAxis(ToolAxis::Z),
    Task::FullPose,
];

/// The largest entry difference of two poses, translation divided by `length`.
pub fn pose_diff(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>, length: f64) -> f64 {
    let dt = (a.translation.vector - b.translation.vector).abs().max() / length;
    let dr = (a.rotation.matrix() - b.rotation.matrix()).abs().max();
    dt.max(dr)
}

/// The position tolerance of `settings` in the robot's length unit.
pub fn tolerance_in_units(robot: &Robot, settings: &IkSettings) -> f64 {
    settings.position_tolerance / robot.length_unit.in_metres()
}

/// Every value finite (no NaN, no infinity).
pub fn all_finite(q: &[f64]) -> bool {
    q.iter().all(|v| v.is_finite())
}
