//! Inverse kinematics (docs/kinematics.md §8–9): round trips FK(IK(T)) = T by every
//! numeric method and through the solver's interface for the closed forms, and the class
//! examples. The closed forms' solutions, singular and unreachable targets, and dragging
//! have files of their own (`ik_closed_form`, `ik_singular`, `ik_drag`).

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::ik::target_pose;
use armlab_core::{
    IkMethod, IkSettings, IkSolver, JacobianSource, Robot, Task, preset, solve, tool_pose,
};
use common::task_error as pose_error;
use common::{TASKS, all_finite, tolerance_in_units};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

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
                    .solve(
                        &robot,
                        &target,
                        task,
                        &seed,
                        IkMethod::DampedLeastSquares,
                        &settings,
                    )
                    .unwrap();
                assert!(all_finite(&r.q), "{id} {task:?}: NaN in {:?}", r.q);
                common::assert_within_limits(&format!("{id} {task:?}"), &robot, &r.q);
                if !r.success {
                    failures += 1;
                    continue;
                }
                // Independent check: FK of the answer against the target by the test's
                // own pose difference, orientation included for 5D and full-pose tasks.
                common::assert_reaches(
                    &format!("{id} {task:?}"),
                    &robot,
                    &r.q,
                    &target,
                    task,
                    tolerance_in_units(&robot, &settings) * 1.0001,
                    settings.orientation_tolerance * 1.0001,
                );
            }
            assert!(
                failures == 0,
                "{id} {task:?}: {failures} of {trials} round trips failed"
            );
        }
    }
}

/// A Cartesian gantry: three prismatic joints along z, then x, then y of frame 0 (strokes
/// 0–500 mm), no link lengths.
fn gantry() -> Robot {
    let joint = |alpha: f64| {
        format!(
            r#"{{"type": "prismatic", "theta_deg": 0, "d": 0, "a": 0, "alpha_deg": {alpha}, "min": 0, "max": 500}}"#
        )
    };
    armlab_core::robot_from_json(&format!(
        r#"{{"name": "gantry", "convention": "standard", "length_unit": "mm", "joints": [{}, {}, {}]}}"#,
        joint(-90.0),
        joint(-90.0),
        joint(0.0)
    ))
    .expect("the gantry's robot file is valid")
}

/// docs/kinematics.md §8: a prismatic joint's value is measured in the linear rows' length
/// L/4. In the robot's own unit its column would be the axis times 4/L (about 0.003 for the
/// gantry), and the damping, sized for revolute columns near 1, would shrink every step to
/// a crawl: damped least squares would reach about half of the gantry's targets, each
/// attempt restarted after six iterations.
#[test]
fn a_prismatic_gantry_round_trips_with_every_numeric_method() {
    let robot = gantry();
    let settings = IkSettings::default();
    let mut solver = IkSolver::new();
    let seed = robot.mid_limits();
    for method in [
        IkMethod::DampedLeastSquares,
        IkMethod::PseudoInverse,
        IkMethod::JacobianTranspose { alpha: None },
    ] {
        let mut rng = common::rng(7);
        for _ in 0..50 {
            let q = rng.joint_vector(&robot);
            let target = tool_pose(&robot, &q);
            let r = solver
                .solve(&robot, &target, Task::Position, &seed, method, &settings)
                .unwrap();
            assert!(r.success, "{method:?}: {q:?} not reached ({r:?})");
            // Newton-like steps solve a linear problem in a few iterations.
            let newton = !matches!(method, IkMethod::JacobianTranspose { .. });
            assert!(
                !newton || r.iterations <= 10,
                "{method:?}: a linear problem took {} iterations",
                r.iterations
            );
            common::assert_reaches(
                &format!("gantry {method:?}"),
                &robot,
                &r.q,
                &target,
                Task::Position,
                tolerance_in_units(&robot, &settings) * 1.0001,
                settings.orientation_tolerance * 1.0001,
            );
        }
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
        let r = solve(
            &robot,
            &target,
            Task::Position,
            &[0.0; 5],
            method,
            &settings,
        )
        .unwrap();
        assert!(r.success, "{method:?} {jacobian:?}: {r:?}");
        common::assert_within_limits("Metrover", &robot, &r.q);
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
    // The first step by hand: θ + J⁻¹·(target − FK(θ)) with the textbook 2R Jacobian
    // (l1 = 2, l2 = 1), J = [[−l1 s1 − l2 s12, −l2 s12], [l1 c1 + l2 c12, l2 c12]].
    let (t1, t2) = (0.1_f64, 0.1_f64);
    let (s1, c1, s12, c12) = (t1.sin(), t1.cos(), (t1 + t2).sin(), (t1 + t2).cos());
    let (x, y) = (2.0 * c1 + c12, 2.0 * s1 + s12);
    let (ex, ey) = (1.5 - x, 1.5 - y);
    let j = [[-2.0 * s1 - s12, -s12], [2.0 * c1 + c12, c12]];
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let step = [
        (j[1][1] * ex - j[0][1] * ey) / det,
        (-j[1][0] * ex + j[0][0] * ey) / det,
    ];
    let want = [t1 + step[0], t2 + step[1]];
    let first = &r.trace[1].raw_q;
    assert!(
        (first[0] - want[0]).abs() < 1e-9 && (first[1] - want[1]).abs() < 1e-9,
        "first Newton step {first:?}, by hand {want:?}"
    );
    assert!(
        (want[0] + 6.0).abs() < 1.0 && (want[1] - 20.0).abs() < 1.5,
        "{want:?}"
    );
    common::assert_reaches(
        "2R Newton",
        &robot,
        &r.q,
        &target,
        Task::Position,
        1e-6,
        0.0,
    );
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
fn closed_form_round_trips_through_the_solver_interface_every_task() {
    let mut solver = IkSolver::new();
    for id in ["planar-2r", "rrr", "ur10", "ur10-standard"] {
        let robot = preset(id).unwrap();
        let mut rng = common::rng(8);
        for task in TASKS {
            for _ in 0..20 {
                let q = rng.joint_vector(&robot);
                let seed = rng.joint_vector(&robot);
                let target = tool_pose(&robot, &q);
                let r = solver
                    .solve(
                        &robot,
                        &target,
                        task,
                        &seed,
                        IkMethod::ClosedForm,
                        &IkSettings::default(),
                    )
                    .unwrap();
                assert!(r.success, "{id} {task:?} q = {q:?}: {r:?}");
                let (pe, oe) = pose_error(&robot, &r.q, &target, task);
                assert!(pe <= 1e-6 / robot.length_unit.in_metres() && oe <= 1e-6);
            }
        }
    }
}

#[test]
fn pseudo_inverse_and_gradient_round_trip_the_ur10() {
    let robot = preset("ur10").unwrap();
    let mut rng = common::rng(77);
    for method in [
        IkMethod::PseudoInverse,
        IkMethod::JacobianTranspose { alpha: None },
    ] {
        for _ in 0..5 {
            let q = rng.joint_vector(&robot);
            let target = tool_pose(&robot, &q);
            // Seeded nearby: these methods are for teaching, not for far starts.
            let seed: Vec<f64> = q.iter().map(|v| v + rng.uniform(-0.2, 0.2)).collect();
            let settings = IkSettings {
                max_iterations: 20_000,
                budget: 20_000,
                restarts: 0,
                ..IkSettings::default()
            };
            let r = solve(&robot, &target, Task::FullPose, &seed, method, &settings).unwrap();
            assert!(r.success, "{method:?}: {r:?}");
            // The pose reached, by the tests' own FK, orientation included: within the
            // tolerances that success claims (1e-6 m, 1e-6 rad).
            common::assert_own_pose_near(
                &format!("UR10 {method:?} from {seed:?}"),
                &robot,
                &r.q,
                &target,
                tolerance_in_units(&robot, &settings) * 1.0001,
                settings.orientation_tolerance * 1.0001,
            );
        }
    }
}
