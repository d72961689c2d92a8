//! IK at singular and unreachable targets (docs/kinematics.md §8–9): flagged, finite
//! solutions, and the closest pose where no exact one exists.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::ik::target_pose;
use armlab_core::{
    IkMethod, IkSettings, Task, closed_form_solutions, drag_step, preset, solve, tool_pose,
};
use common::{TASKS, all_finite, pose_diff};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

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
