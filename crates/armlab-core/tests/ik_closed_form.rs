//! Closed-form IK (docs/kinematics.md §9): every branch of the UR10 in both conventions and
//! their count against an independent numeric one, the RRR arm and the planar 2R, the
//! branch nearest the seed, and solutions outside the limits marked, not dropped.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::ik::{joint_distance, target_pose};
use armlab_core::{
    ClosedFormFamily, IkMethod, IkSettings, IkSolver, Task, closed_form_family,
    closed_form_solutions, preset, solve, tool_pose,
};
use common::pose_diff;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::FRAC_PI_2;

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
