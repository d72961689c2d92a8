//! Dragging (docs/kinematics.md §8): no joint moves more than the per-frame limit, the
//! tool never moves away from the target, a circle is followed on one branch, and an
//! unreachable target is approached without a jump.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::ik::target_pose;
use armlab_core::{IkMethod, IkSettings, IkSolver, Robot, Task, drag_step, preset, tool_pose};
use common::tolerance_in_units;
use nalgebra::{IsometryMatrix3, Matrix3, Vector3};
use std::f64::consts::PI;

#[test]
fn drag_step_never_moves_a_joint_more_than_the_limit() {
    let robot = preset("ur10").unwrap();
    let far = target_pose(Vector3::new(-900.0, 400.0, 300.0), Matrix3::identity());
    let mut q = vec![0.0; 6];
    let settings = IkSettings::drag();
    for _ in 0..100 {
        let r = drag_step(
            &robot,
            &q,
            &far,
            Task::FullPose,
            IkMethod::DampedLeastSquares,
            &settings,
        )
        .unwrap();
        let moved = robot
            .joints
            .iter()
            .zip(q.iter().zip(&r.q))
            .map(|(j, (a, b))| j.change(*a, *b).abs())
            .fold(0.0, f64::max);
        assert!(moved <= 0.1 + 1e-12, "moved {moved}");
        q = r.q;
    }
    common::assert_reaches("UR10 drag", &robot, &q, &far, Task::FullPose, 1e-3, 1e-6);
}

/// Where a drag goes: the tool point of a joint vector (reachable), or a point.
enum Goal {
    Joints(Vec<f64>),
    Point([f64; 3]),
}

/// The drag's error as the solver weighs it: position over the reach, and the angle.
fn drag_cost(robot: &Robot, q: &[f64], target: &IsometryMatrix3<f64>, task: Task) -> f64 {
    let (p, a) = common::task_error(robot, q, target, task);
    (p / robot.reach()).powi(2) + a * a
}

#[test]
fn drag_steps_never_move_the_tool_away_from_the_target() {
    // Damped least squares, the drag's method: from bent, non-singular poses toward
    // reachable and unreachable targets, each step lowers the error or keeps it. (A start
    // on a singularity may first have to move away to leave it, the test above starts
    // there; undamped Newton may jump away by design, docs/kinematics.md §8.1.)
    // (robot, start, goal: a joint vector whose tool point is the target, or a point)
    let ur10_start = vec![0.3, -1.2, 1.4, -1.0, -1.3, 0.2];
    let cases = [
        (
            "ur10",
            ur10_start.clone(),
            Goal::Joints(vec![0.9, -0.8, 1.0, -1.4, -1.0, 0.5]),
        ),
        ("ur10", ur10_start, Goal::Point([2500.0, 0.0, 300.0])),
        (
            "puma560",
            vec![0.2, 0.4, -0.6, 0.3, 0.5, 0.1],
            Goal::Joints(vec![0.6, 0.7, -0.9, 0.3, 0.5, 0.1]),
        ),
        (
            "panda",
            vec![0.0, -0.7, 0.0, -2.2, 0.0, 1.6, 0.7],
            Goal::Joints(vec![0.4, -0.3, 0.2, -1.8, 0.1, 1.9, 0.7]),
        ),
        (
            "rrr",
            vec![0.3, 0.5, -1.0],
            Goal::Joints(vec![0.9, 0.2, -0.6]),
        ),
        ("rrr", vec![0.3, 0.5, -1.0], Goal::Point([900.0, 0.0, 0.0])),
    ];
    for (id, start, goal) in cases {
        let robot = preset(id).unwrap();
        let rotation = *tool_pose(&robot, &start).rotation.matrix();
        let reachable = matches!(goal, Goal::Joints(_));
        let p = match goal {
            Goal::Joints(q) => tool_pose(&robot, &q).translation.vector,
            Goal::Point(p) => Vector3::from(p),
        };
        let target = target_pose(p, rotation);
        for method in [IkMethod::DampedLeastSquares] {
            let mut q = start.clone();
            for step in 0..300 {
                let r = drag_step(
                    &robot,
                    &q,
                    &target,
                    Task::Position,
                    method,
                    &IkSettings::drag(),
                )
                .unwrap();
                let before = drag_cost(&robot, &q, &target, Task::Position);
                let after = drag_cost(&robot, &r.q, &target, Task::Position);
                assert!(
                    after <= before * (1.0 + 1e-12) + 1e-24,
                    "{id} {method:?} step {step}: the error rose {before} → {after}"
                );
                q = r.q;
            }
            let what = format!("{id} {method:?}");
            if reachable {
                let tolerance = 1e-6 / robot.length_unit.in_metres();
                common::assert_reaches(&what, &robot, &q, &target, Task::Position, tolerance, 0.0);
            } else {
                let (pe, _) = common::task_error(&robot, &q, &target, Task::Position);
                assert!(
                    pe > 0.1 * robot.reach(),
                    "{what}: out of reach, yet {pe} away"
                );
            }
        }
    }
}

/// How far (mm) the tool may be from the circle halfway (in joint space) between two
/// drag frames: the chord of 3° of the 200 mm circle runs 0.07 mm inside it, the arm's
/// joint-space midpoint 0.10 mm; an arm that swung off the circle and back between two
/// frames would be much further.
const HALFWAY_OFF_CIRCLE: f64 = 0.2;

#[test]
fn drag_follows_a_circle_on_one_branch_within_the_joint_limit() {
    let robot = preset("ur10").unwrap();
    let down = Matrix3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
    let (centre, radius, height) = (Vector3::new(700.0, -200.0, 0.0), 200.0, 400.0);
    let point = |k: usize| {
        let a = std::f64::consts::TAU * k as f64 / 120.0;
        target_pose(
            Vector3::new(
                centre.x + radius * a.cos(),
                centre.y + radius * a.sin(),
                height,
            ),
            down,
        )
    };
    // The tool's distance from the circle (mm), by the tests' own FK.
    let off_circle = |q: &[f64]| {
        let p = common::own_fk(&robot, q).tool.translation.vector;
        let across = (p - centre).xy().norm() - radius;
        across.hypot(p.z - height)
    };
    let settings = IkSettings::drag();
    let tol_p = tolerance_in_units(&robot, &settings);
    let mut solver = IkSolver::new();
    for method in [IkMethod::DampedLeastSquares, IkMethod::ClosedForm] {
        let start = solver
            .solve(
                &robot,
                &point(0),
                Task::FullPose,
                &[0.0; 6],
                IkMethod::ClosedForm,
                &IkSettings::default(),
            )
            .unwrap();
        let mut q = start.q.clone();
        for k in 1..=120 {
            let r = solver
                .drag_step(&robot, &q, &point(k), Task::FullPose, method, &settings)
                .unwrap();
            assert!(r.success, "{method:?} step {k}: {r:?}");
            // Every step reaches its own point of the circle, hand down, by the tests'
            // own FK: a step that kept the previous pose or stopped short fails here.
            common::assert_own_pose_near(
                &format!("{method:?} step {k}"),
                &robot,
                &r.q,
                &point(k),
                tol_p * 1.0001,
                settings.orientation_tolerance * 1.0001,
            );
            let moved = robot
                .joints
                .iter()
                .zip(q.iter().zip(&r.q))
                .map(|(j, (a, b))| j.change(*a, *b).abs())
                .fold(0.0, f64::max);
            assert!(moved <= 0.1, "{method:?} step {k}: moved {moved}");
            // On the circle at the step, and near it halfway to the step before.
            let halfway: Vec<f64> = robot
                .joints
                .iter()
                .zip(q.iter().zip(&r.q))
                .map(|(j, (a, b))| a + 0.5 * j.change(*a, *b))
                .collect();
            let at_step = off_circle(&r.q);
            let between = off_circle(&halfway);
            assert!(
                at_step <= tol_p * 1.0001 && between <= HALFWAY_OFF_CIRCLE,
                "{method:?} step {k}: the tool is {at_step} mm off the circle, \
                 {between} mm halfway from the step before"
            );
            q = r.q;
        }
        // Back at the start on the same branch.
        let back = q
            .iter()
            .zip(&start.q)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(back < 1e-4, "{method:?}: ended {back} rad from the start");
    }
}

#[test]
fn drag_toward_unreachable_target_stretches_without_jumping() {
    let robot = preset("metrover").unwrap();
    let far = target_pose(Vector3::new(2000.0, 500.0, 600.0), Matrix3::identity());
    let mut q = vec![0.0, 0.5, 0.0, 0.0, 0.0];
    let mut last = None;
    for _ in 0..200 {
        let r = drag_step(
            &robot,
            &q,
            &far,
            Task::Position,
            IkMethod::DampedLeastSquares,
            &IkSettings::drag(),
        )
        .unwrap();
        let moved = robot
            .joints
            .iter()
            .zip(q.iter().zip(&r.q))
            .map(|(j, (a, b))| j.change(*a, *b).abs())
            .fold(0.0, f64::max);
        assert!(moved <= 0.1);
        assert!((0.0..=PI).contains(&r.q[1]));
        q = r.q.clone();
        last = Some(r);
    }
    let r = last.unwrap();
    assert!(r.unreachable && !r.success, "{r:?}");
    // The closest pose: no random joint vector within the limits comes closer.
    let to_target = (far.translation.vector - tool_pose(&robot, &q).translation.vector).norm();
    let mut rng = common::rng(31);
    let sampled = (0..20_000)
        .map(|_| {
            let s = rng.joint_vector(&robot);
            (far.translation.vector - tool_pose(&robot, &s).translation.vector).norm()
        })
        .fold(f64::INFINITY, f64::min);
    assert!(
        to_target <= sampled + 1e-6,
        "dragged to {to_target} mm from the target; a random pose gets {sampled}"
    );
}
