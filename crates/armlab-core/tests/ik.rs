//! Inverse kinematics (docs/kinematics.md §8–9): round trips FK(IK(T)) = T, the closed forms, the
//! class examples, unreachable and singular targets, and dragging.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::ik::{joint_distance, target_pose};
use armlab_core::{
    ClosedFormFamily, IkMethod, IkSettings, IkSolver, JacobianSource, Robot, Task, ToolAxis,
    closed_form_family, closed_form_solutions, drag_step, preset, solve, tool_pose,
};
use common::task_error as pose_error;
use nalgebra::{IsometryMatrix3, Matrix3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI};

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
                assert!(d <= 1e-9, "{id}: solution {} off by {d}", s.label());
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
            assert!(
                found <= 1e-6,
                "{id}: q = {q:?} not among the solutions ({found})"
            );
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

/// Distinct joint vectors up to whole turns, as sorted wrapped keys.
fn distinct_mod_turns(list: &[Vec<f64>], tol: f64) -> Vec<Vec<f64>> {
    let mut out: Vec<Vec<f64>> = Vec::new();
    for q in list {
        let w: Vec<f64> = q
            .iter()
            .map(|v| armlab_core::angles::wrap_to_pi(*v))
            .collect();
        let same = out.iter().any(|o| {
            o.iter()
                .zip(&w)
                .all(|(a, b)| armlab_core::angles::wrap_to_pi(a - b).abs() < tol)
        });
        if !same {
            out.push(w);
        }
    }
    out
}

#[test]
fn ur10_branch_count_matches_an_independent_numeric_count() {
    // Independent count: damped least squares from many random seeds, distinct answers
    // up to whole turns. Three poses with all eight branches and three with fewer.
    let robot = preset("ur10").unwrap();
    let mut rng = common::rng(99);
    let mut seeds_rng = common::rng(1234);
    let (mut full, mut fewer) = (0, 0);
    let settings = IkSettings {
        restarts: 0,
        max_iterations: 150,
        budget: 150,
        ..IkSettings::default()
    };
    let mut solver = IkSolver::new();
    while full < 3 || fewer < 3 {
        let q = rng.joint_vector(&robot);
        let target = tool_pose(&robot, &q);
        let set = closed_form_solutions(&robot, &target, &q).unwrap();
        let n = set.solutions.len();
        if (n == 8 && full >= 3) || (n < 8 && fewer >= 3) {
            continue;
        }
        if n == 8 {
            full += 1;
        } else {
            fewer += 1;
        }
        let mut found = Vec::new();
        for _ in 0..64 {
            let seed = seeds_rng.joint_vector(&robot);
            let r = solver
                .solve(
                    &robot,
                    &target,
                    Task::FullPose,
                    &seed,
                    IkMethod::DampedLeastSquares,
                    &settings,
                )
                .unwrap();
            if r.success {
                found.push(r.q);
            }
        }
        let numeric = distinct_mod_turns(&found, 1e-3);
        let closed: Vec<Vec<f64>> = set.solutions.iter().map(|s| s.q.clone()).collect();
        let closed = distinct_mod_turns(&closed, 1e-3);
        assert_eq!(closed.len(), n, "closed-form solutions are distinct");
        assert_eq!(
            numeric.len(),
            n,
            "q = {q:?}: numeric search found {} branches, closed form {n}",
            numeric.len()
        );
        // Every numeric answer is one of the closed-form ones.
        for a in &numeric {
            assert!(
                closed.iter().any(|b| a
                    .iter()
                    .zip(b)
                    .all(|(x, y)| armlab_core::angles::wrap_to_pi(x - y).abs() < 1e-4)),
                "numeric answer {a:?} is not a closed-form branch"
            );
        }
    }
}

#[test]
fn rrr_closed_form_gives_four_solutions_that_verify() {
    let robot = preset("rrr").unwrap();
    assert_eq!(closed_form_family(&robot), Some(ClosedFormFamily::Rrr));
    let mut rng = common::rng(5);
    for _ in 0..200 {
        let q = rng.joint_vector(&robot);
        let target = tool_pose(&robot, &q);
        let set = closed_form_solutions(&robot, &target, &q).unwrap();
        assert_eq!(set.solutions.len(), 4, "q = {q:?}");
        for s in &set.solutions {
            let p = tool_pose(&robot, &s.q).translation.vector;
            assert!(
                (p - target.translation.vector).abs().max() <= 1e-9,
                "{}",
                s.label()
            );
        }
        // The RRR's FK formula (docs/kinematics.md §9.2) agrees.
        let (l1, l2, l3) = (100.9, 222.1, 136.2);
        for s in &set.solutions {
            let (c1, s1) = (s.q[0].cos(), s.q[0].sin());
            let r = l2 * s.q[1].cos() + l3 * (s.q[1] + s.q[2]).cos();
            let z = l1 + l2 * s.q[1].sin() + l3 * (s.q[1] + s.q[2]).sin();
            let p = Vector3::new(c1 * r, s1 * r, z);
            assert!((p - target.translation.vector).norm() <= 1e-9);
        }
    }
}

#[test]
fn planar_2r_closed_form_both_elbows_by_the_law_of_cosines() {
    let robot = preset("planar-2r").unwrap();
    assert_eq!(closed_form_family(&robot), Some(ClosedFormFamily::Planar2R));
    let target = target_pose(Vector3::new(1.5, 1.5, 0.0), Matrix3::identity());
    let set = closed_form_solutions(&robot, &target, &[0.0, 0.0]).unwrap();
    assert_eq!(set.solutions.len(), 2);
    let (x, y, l1, l2): (f64, f64, f64, f64) = (1.5, 1.5, 2.0, 1.0);
    let c2 = (x * x + y * y - l1 * l1 - l2 * l2) / (2.0 * l1 * l2);
    for (s, t2) in set.solutions.iter().zip([c2.acos(), -c2.acos()]) {
        let t1 = y.atan2(x) - (l2 * t2.sin()).atan2(l1 + l2 * t2.cos());
        assert!((s.q[1] - t2).abs() < 1e-12 && (s.q[0] - t1).abs() < 1e-12);
        let p = tool_pose(&robot, &s.q).translation.vector;
        assert!((p - target.translation.vector).norm() <= 1e-9);
    }
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
fn closed_form_picks_the_branch_nearest_the_seed() {
    let robot = preset("ur10").unwrap();
    let mut rng = common::rng(21);
    for _ in 0..50 {
        let q = rng.joint_vector(&robot);
        let target = tool_pose(&robot, &q);
        // A seed near q: the answer is q itself (up to whole turns, kept near the seed).
        let seed: Vec<f64> = q.iter().map(|v| v + rng.uniform(-0.05, 0.05)).collect();
        let r = solve(
            &robot,
            &target,
            Task::FullPose,
            &seed,
            IkMethod::ClosedForm,
            &IkSettings::default(),
        )
        .unwrap();
        let worst =
            r.q.iter()
                .zip(&q)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
        assert!(worst < 1e-6, "{worst}");
        assert!(joint_distance(&robot, &seed, &r.q) < 6.0 * 0.05f64.powi(2) + 1e-9);
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

#[test]
fn solutions_outside_the_limits_are_marked_not_dropped() {
    let mut robot = preset("rrr").unwrap();
    robot.joints[0].limits.min = -FRAC_PI_2;
    robot.joints[0].limits.max = FRAC_PI_2;
    let q = [0.3, 0.4, 0.5];
    let target = tool_pose(&robot, &q);
    let set = closed_form_solutions(&robot, &target, &q).unwrap();
    assert_eq!(set.solutions.len(), 4);
    let outside = set.solutions.iter().filter(|s| !s.within_limits).count();
    assert_eq!(
        outside, 2,
        "the two shoulder-back branches turn the base by 0.3 + π"
    );
    let r = solve(
        &robot,
        &target,
        Task::Position,
        &[-1.5, 0.0, 0.0],
        IkMethod::ClosedForm,
        &IkSettings::default(),
    )
    .unwrap();
    assert!(r.success && r.within_limits, "{r:?}");
}

#[test]
fn singular_configurations_give_flagged_finite_solutions() {
    ur10_wrist_singular_solutions_are_flagged();
    rrr_tool_on_the_base_axis_is_flagged();
    planar_2r_stretched_and_folded_is_flagged();
    numeric_methods_leave_singular_seeds();
}

/// The UR10 with its wrist at θ5 = 0 (q = 0 is also stretched): every closed-form
/// solution finite and on the target, the set and the solve flagged singular.
fn ur10_wrist_singular_solutions_are_flagged() {
    for id in ["ur10", "ur10-standard"] {
        let robot = preset(id).expect("a preset");
        for q in [[0.0; 6], [0.3, -1.0, 1.2, 0.4, 0.0, -0.7]] {
            let target = tool_pose(&robot, &q);
            let set = closed_form_solutions(&robot, &target, &q).expect("closed-form solutions");
            assert!(!set.solutions.is_empty());
            assert!(set.singular, "{id} {q:?}");
            for s in &set.solutions {
                assert!(all_finite(&s.q));
                let d = pose_diff(&tool_pose(&robot, &s.q), &target, 1.0);
                assert!(d <= 1e-9, "{id} {q:?}: {} off by {d}", s.label());
            }
            let r = solve(
                &robot,
                &target,
                Task::FullPose,
                &q,
                IkMethod::ClosedForm,
                &IkSettings::default(),
            )
            .expect("a solution");
            assert!(r.success && r.singular);
        }
    }
}

/// The RRR's tool on the base axis (L2 c2 + L3 c23 = 0): flagged, every solution on it.
fn rrr_tool_on_the_base_axis_is_flagged() {
    let robot = preset("rrr").expect("a preset");
    let t2: f64 = 1.2;
    let t3 = (-222.1 * t2.cos() / 136.2).acos() - t2;
    let q = [0.7, t2, t3];
    let target = tool_pose(&robot, &q);
    assert!(target.translation.vector.xy().norm() < 1e-9);
    let set = closed_form_solutions(&robot, &target, &q).expect("closed-form solutions");
    assert!(set.singular && !set.solutions.is_empty());
    for s in &set.solutions {
        assert!(all_finite(&s.q));
        assert!(
            (tool_pose(&robot, &s.q).translation.vector - target.translation.vector).norm() <= 1e-9
        );
    }
}

/// The 2R stretched and folded: one solution each, flagged.
fn planar_2r_stretched_and_folded_is_flagged() {
    let robot = preset("planar-2r").expect("a preset");
    for q in [[0.4, 0.0], [0.4, PI]] {
        let target = tool_pose(&robot, &q);
        let set = closed_form_solutions(&robot, &target, &q).expect("closed-form solutions");
        assert_eq!(set.solutions.len(), 1, "{q:?}");
        assert!(set.singular && set.solutions[0].exact);
        assert!(
            (tool_pose(&robot, &set.solutions[0].q).translation.vector - target.translation.vector)
                .norm()
                <= 1e-9
        );
    }
}

/// Numeric methods seeded exactly at a singularity: the 2R stretched, and the UR10's
/// stretched, wrist-singular q = 0 with damped least squares to a full pose.
fn numeric_methods_leave_singular_seeds() {
    let robot = preset("planar-2r").expect("a preset");
    let target = target_pose(Vector3::new(1.0, 1.5, 0.0), Matrix3::identity());
    for method in [
        IkMethod::DampedLeastSquares,
        IkMethod::PseudoInverse,
        IkMethod::JacobianTranspose { alpha: None },
    ] {
        let r = solve(
            &robot,
            &target,
            Task::Position,
            &[0.0, 0.0],
            method,
            &IkSettings::default(),
        )
        .expect("a solution");
        assert!(all_finite(&r.q), "{method:?}");
        // Not only finite: each method leaves the stretched seed and reaches the target
        // (restarts included), checked by the test's own FK difference.
        common::assert_reaches(
            &format!("2R from the stretched pose, {method:?}"),
            &robot,
            &r.q,
            &target,
            Task::Position,
            1e-6,
            0.0,
        );
    }
    // Damped least squares from the UR10's stretched, wrist-singular q = 0 to a full pose.
    let ur10 = preset("ur10").expect("a preset");
    let goal = tool_pose(&ur10, &[0.5, -1.1, 1.3, -1.6, -1.4, 0.2]);
    let r = solve(
        &ur10,
        &goal,
        Task::FullPose,
        &[0.0; 6],
        IkMethod::DampedLeastSquares,
        &IkSettings::default(),
    )
    .expect("a solution");
    common::assert_reaches(
        "UR10 from q = 0",
        &ur10,
        &r.q,
        &goal,
        Task::FullPose,
        1e-3,
        1e-6,
    );
    common::assert_within_limits("UR10 from q = 0", &ur10, &r.q);
}

#[test]
fn unreachable_targets_give_the_closest_pose_flagged_without_nan() {
    // 2R: (5, 0) is beyond l1 + l2 = 3: the arm stretches toward it.
    let robot = preset("planar-2r").unwrap();
    let target = target_pose(Vector3::new(5.0, 0.0, 0.0), Matrix3::identity());
    let set = closed_form_solutions(&robot, &target, &[0.1, 0.1]).unwrap();
    assert!(set.unreachable && !set.solutions.is_empty());
    for method in [
        IkMethod::ClosedForm,
        IkMethod::DampedLeastSquares,
        IkMethod::PseudoInverse,
        IkMethod::JacobianTranspose { alpha: Some(0.01) },
    ] {
        let r = solve(
            &robot,
            &target,
            Task::Position,
            &[0.1, 0.1],
            method,
            &IkSettings::default(),
        )
        .unwrap();
        assert!(
            all_finite(&r.q) && r.position_error.is_finite(),
            "{method:?}: {r:?}"
        );
        assert!(!r.success);
        if method == IkMethod::ClosedForm || method == IkMethod::DampedLeastSquares {
            assert!(r.unreachable, "{method:?}");
            assert!(
                (r.position_error - 2.0).abs() < 1e-3,
                "{method:?}: {}",
                r.position_error
            );
        }
    }
    every_preset_flags_a_target_far_outside_its_reach();
    // UR10 closed form out of reach falls back to the closest pose.
    let robot = preset("ur10").unwrap();
    let far = target_pose(Vector3::new(3000.0, 0.0, 500.0), Matrix3::identity());
    let r = solve(
        &robot,
        &far,
        Task::FullPose,
        &[0.0; 6],
        IkMethod::ClosedForm,
        &IkSettings::default(),
    )
    .unwrap();
    assert!(r.unreachable && !r.success && all_finite(&r.q));
}

/// Every preset, a target far outside its reach, every task: damped least squares
/// flags it unreachable within the limits, and a drag step stays finite.
fn every_preset_flags_a_target_far_outside_its_reach() {
    for (id, robot) in common::all_presets() {
        let far = target_pose(
            Vector3::new(3.0, -2.0, 2.5) * robot.reach(),
            Matrix3::identity(),
        );
        for task in TASKS {
            let light = IkSettings {
                budget: 300,
                restarts: 3,
                ..IkSettings::default()
            };
            let r = solve(
                &robot,
                &far,
                task,
                &robot.mid_limits(),
                IkMethod::DampedLeastSquares,
                &light,
            )
            .expect("a solution");
            assert!(
                all_finite(&r.q) && !r.success && r.unreachable,
                "{id} {task:?}: {r:?}"
            );
            assert!(r.within_limits);
            let d = drag_step(
                &robot,
                &robot.mid_limits(),
                &far,
                task,
                IkMethod::DampedLeastSquares,
                &IkSettings::drag(),
            )
            .expect("a drag step");
            assert!(all_finite(&d.q));
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
