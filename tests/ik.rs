//! Inverse kinematics (SPEC §1–2): round trips FK(IK(T)) = T, the closed forms, the
//! class examples, unreachable and singular targets, and dragging.

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

mod common;

use armlab::kinematics::ik::{joint_distance, pose_error, target_pose};
use armlab::kinematics::{
    ClosedFormFamily, IkMethod, IkSettings, IkSolver, JacobianSource, Robot, Task, ToolAxis,
    closed_form_family, closed_form_solutions, drag_step, preset, solve, tool_pose,
};
use nalgebra::{IsometryMatrix3, Matrix3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

const TASKS: [Task; 5] = [
    Task::Position,
    Task::PositionAndAxis(ToolAxis::X),
    Task::PositionAndAxis(ToolAxis::Y),
    Task::PositionAndAxis(ToolAxis::Z),
    Task::FullPose,
];

/// The largest entry difference of two poses, translation divided by `length`.
fn pose_diff(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>, length: f64) -> f64 {
    let dt = (a.translation.vector - b.translation.vector).abs().max() / length;
    let dr = (a.rotation.matrix() - b.rotation.matrix()).abs().max();
    dt.max(dr)
}

fn tolerance_in_units(robot: &Robot, settings: &IkSettings) -> f64 {
    settings.position_tolerance / robot.length_unit.in_metres()
}

fn all_finite(q: &[f64]) -> bool {
    q.iter().all(|v| v.is_finite())
}

#[test]
fn damped_least_squares_round_trips_every_preset_and_task() {
    let settings = IkSettings::default();
    let mut solver = IkSolver::new();
    for (id, robot) in common::all_presets() {
        let mut rng = common::rng(3);
        let seed = robot.mid_limits();
        for task in TASKS {
            let mut failures = 0;
            let trials = 12;
            for _ in 0..trials {
                let q = rng.joint_vector(&robot);
                let target = tool_pose(&robot, &q);
                let r = solver
                    .solve(&robot, &target, task, &seed, IkMethod::DampedLeastSquares, &settings)
                    .unwrap();
                assert!(all_finite(&r.q), "{id} {task:?}: NaN in {:?}", r.q);
                assert!(r.within_limits, "{id} {task:?}: {:?} outside the limits", r.q);
                if !r.success {
                    failures += 1;
                    continue;
                }
                // Independent check by a separate FK call.
                let (pe, oe) = pose_error(&robot, &r.q, &target, task);
                assert!(pe <= tolerance_in_units(&robot, &settings) * 1.0001, "{id} {task:?}: {pe}");
                assert!(oe <= settings.orientation_tolerance * 1.0001, "{id} {task:?}: {oe}");
            }
            assert!(
                failures == 0,
                "{id} {task:?}: {failures} of {trials} round trips failed"
            );
        }
    }
}

#[test]
fn ur10_closed_form_finds_every_branch_both_conventions() {
    for id in ["ur10", "ur10-standard"] {
        let robot = preset(id).unwrap();
        assert_eq!(closed_form_family(&robot), Some(ClosedFormFamily::UrFamily));
        let mut rng = common::rng(11);
        let mut eights = 0;
        let trials = 200;
        for _ in 0..trials {
            let q = rng.joint_vector(&robot);
            let target = tool_pose(&robot, &q);
            let set = closed_form_solutions(&robot, &target, &q).unwrap();
            assert!(!set.unreachable, "{id}: reachable target flagged");
            for s in &set.solutions {
                let d = pose_diff(&tool_pose(&robot, &s.q), &target, 1.0);
                assert!(d <= 1e-9, "{id}: solution {} off by {d}", s.label);
                assert!(s.within_limits);
            }
            // The original q is among them.
            let found = set
                .solutions
                .iter()
                .map(|s| {
                    s.q.iter()
                        .zip(&q)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max)
                })
                .fold(f64::INFINITY, f64::min);
            assert!(found <= 1e-6, "{id}: q = {q:?} not among the solutions ({found})");
            if set.solutions.len() == 8 {
                eights += 1;
            }
        }
        let share = eights as f64 / trials as f64;
        assert!(
            (0.6..=0.95).contains(&share),
            "{id}: eight solutions in {share} of poses"
        );
    }
}

#[test]
fn metrover_reaches_600_0_520_position_only_from_zero() {
    let robot = preset("metrover").unwrap();
    let target = target_pose(Vector3::new(600.0, 0.0, 520.0), Matrix3::identity());
    for (method, jacobian) in [
        (IkMethod::DampedLeastSquares, JacobianSource::Geometric),
        (IkMethod::PseudoInverse, JacobianSource::CentralDifference),
        (IkMethod::PseudoInverse, JacobianSource::Geometric),
    ] {
        let settings = IkSettings {
            jacobian,
            ..IkSettings::default()
        };
        let r = solve(&robot, &target, Task::Position, &[0.0; 5], method, &settings).unwrap();
        assert!(r.success, "{method:?} {jacobian:?}: {r:?}");
        assert!(
            (0.0..=PI).contains(&r.q[1]),
            "joint 2 = {} outside 0…180°",
            r.q[1]
        );
        let p = tool_pose(&robot, &r.q).translation.vector;
        assert!((p - Vector3::new(600.0, 0.0, 520.0)).norm() <= 1e-3);
    }
}

#[test]
fn planar_2r_newton_first_step_jumps_far_then_converges() {
    let robot = preset("planar-2r").unwrap();
    let target = target_pose(Vector3::new(1.5, 1.5, 0.0), Matrix3::identity());
    let settings = IkSettings {
        record_trace: true,
        restarts: 0,
        ..IkSettings::default()
    };
    let r = solve(
        &robot,
        &target,
        Task::Position,
        &[0.1, 0.1],
        IkMethod::PseudoInverse,
        &settings,
    )
    .unwrap();
    assert!(r.success, "{r:?}");
    let first = &r.trace[1].raw_q;
    eprintln!("first Newton step: {first:?}, iterations {}", r.iterations);
    assert!((first[0] - (-6.0)).abs() < 1.0 && (first[1] - 20.0).abs() < 1.5, "{first:?}");
    let p = tool_pose(&robot, &r.q).translation.vector;
    assert!((p - Vector3::new(1.5, 1.5, 0.0)).norm() <= 1e-6);
}

#[test]
fn planar_2r_gradient_descent_is_slow_but_gets_there() {
    let robot = preset("planar-2r").unwrap();
    let target = target_pose(Vector3::new(1.0, 1.5, 0.0), Matrix3::identity());
    let method = IkMethod::JacobianTranspose { alpha: Some(0.01) };
    let class = IkSettings {
        max_iterations: 1000,
        budget: 1000,
        restarts: 0,
        ..IkSettings::default()
    };
    let r = solve(&robot, &target, Task::Position, &[0.1, 0.1], method, &class).unwrap();
    assert_eq!(r.iterations, 1000);
    assert!(!r.success, "1000 iterations should stop short: {r:?}");
    eprintln!("gradient after 1000: {}", r.position_error);
    let on = IkSettings {
        max_iterations: 100_000,
        budget: 100_000,
        restarts: 0,
        ..IkSettings::default()
    };
    let r = solve(&robot, &target, Task::Position, &[0.1, 0.1], method, &on).unwrap();
    eprintln!("gradient to tolerance: {} iterations", r.iterations);
    assert!(r.success, "{r:?}");
    assert!(r.iterations > 1000);
}

#[test]
fn drag_step_never_moves_a_joint_more_than_the_limit() {
    let robot = preset("ur10").unwrap();
    let far = target_pose(Vector3::new(-900.0, 400.0, 300.0), Matrix3::identity());
    let mut q = vec![0.0; 6];
    let settings = IkSettings::drag();
    for _ in 0..100 {
        let r = drag_step(&robot, &q, &far, Task::FullPose, IkMethod::DampedLeastSquares, &settings).unwrap();
        let moved = robot
            .joints
            .iter()
            .zip(q.iter().zip(&r.q))
            .map(|(j, (a, b))| j.change(*a, *b).abs())
            .fold(0.0, f64::max);
        assert!(moved <= 0.1 + 1e-12, "moved {moved}");
        q = r.q;
    }
    let (pe, _) = pose_error(&robot, &q, &far, Task::FullPose);
    assert!(pe < 1e-3, "{pe}");
    let _ = (joint_distance(&robot, &q, &q), FRAC_PI_2, TAU);
}
