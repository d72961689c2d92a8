//! The sampled workspace (docs/kinematics.md §10): slices add up to the whole, the
//! determinant-based manipulability and the closed-form σ_min agree with the SVD of the
//! measures, the nearest-point query, and the joints that hold a stalled IK at a limit.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab::kinematics::workspace::smallest_symmetric_eigenvalue;
use armlab::kinematics::{
    ForwardKinematics, IkSettings, Task, ToolAxis, WorkspaceCloud, WorkspaceMeasure,
    direction_reachability, geometric_jacobian, jacobian_measures, joints_held_at_limits,
    linear_manipulability, linear_sigma_min, preset, sphere_directions, tool_pose,
};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::FRAC_PI_4;

#[test]
fn slices_fill_the_same_cloud_as_one_call() {
    let robot = preset("ur10").unwrap();
    let mut whole = WorkspaceCloud::new(&robot, WorkspaceMeasure::Manipulability, 5000, 7);
    assert_eq!(whole.fill(usize::MAX), 5000);
    assert!(whole.is_full() && whole.fill(10) == 0);
    let mut sliced = WorkspaceCloud::new(&robot, WorkspaceMeasure::Manipulability, 5000, 7);
    let mut calls = 0;
    while !sliced.is_full() {
        let added = sliced.fill(333);
        assert!(added <= 333);
        calls += 1;
    }
    assert_eq!(calls, 16);
    assert_eq!(sliced.positions, whole.positions);
    assert_eq!(sliced.values, whole.values);
    assert_eq!(sliced.progress(), 1.0);
    // Every point lies within the arm's reach of the base.
    assert!(whole.outer_reach() <= robot.reach());
    assert!(whole.outer_reach() > 0.8 * 1300.0);
}

#[test]
fn the_sampler_matches_forward_kinematics_and_todays_numbers() {
    // The cloud's own forward kinematics (plain arrays) against ForwardKinematics and
    // tool_pose, on every preset (standard and modified DH, prismatic joints) and on one
    // moved off the origin with a tilted base.
    let mut robots = common::all_presets();
    let mut tilted = preset("puma560").unwrap();
    tilted.world_from_base = nalgebra::IsometryMatrix3::from_parts(
        nalgebra::Translation3::new(0.3, -0.2, 0.5),
        nalgebra::Rotation3::from_euler_angles(0.4, -0.3, 1.2),
    );
    robots.push(("tilted puma560".into(), tilted));
    for (id, robot) in &robots {
        for measure in [WorkspaceMeasure::Manipulability, WorkspaceMeasure::SigmaMin] {
            let mut cloud = WorkspaceCloud::new(robot, measure, 300, 11).keep_joint_vectors();
            cloud.fill(300);
            let inv = 1.0 / robot.length_scale();
            for ((p, value), q) in cloud
                .positions
                .iter()
                .zip(&cloud.values)
                .zip(&cloud.joint_vectors)
            {
                let fk = ForwardKinematics::new(robot, q).unwrap();
                let want = match measure {
                    WorkspaceMeasure::Manipulability => linear_manipulability(&fk, inv),
                    WorkspaceMeasure::SigmaMin => linear_sigma_min(&fk, inv),
                };
                let pose = tool_pose(robot, q).translation.vector;
                assert!(
                    (p - pose).abs().max() <= 1e-12 * robot.reach(),
                    "{id}: {p:?} vs {pose:?}"
                );
                assert!(
                    (value - want).abs() <= 1e-12,
                    "{id} {measure:?}: {value} vs {want}"
                );
            }
        }
    }
    // The UR10's mean measures over 20 000 samples of the benchmark's seed, as a sampler
    // over nalgebra's types computes them: the one over plain arrays must agree.
    let ur10 = preset("ur10").unwrap();
    for (measure, mean) in [
        (WorkspaceMeasure::Manipulability, 0.02838400395003399),
        (WorkspaceMeasure::SigmaMin, 0.1321770250921807),
    ] {
        let mut cloud = WorkspaceCloud::new(&ur10, measure, 20_000, 0x00C0_FFEE);
        cloud.fill(20_000);
        let got = cloud.values.iter().sum::<f64>() / 20_000.0;
        assert!(
            (got - mean).abs() <= 1e-15,
            "{measure:?}: mean {got} vs {mean}"
        );
    }
}

#[test]
fn the_measures_agree_with_the_svd() {
    for id in ["ur10", "puma560", "planar-2r", "scara", "panda", "metrover"] {
        let robot = preset(id).unwrap();
        let mut rng = common::rng(2);
        for _ in 0..50 {
            let q = rng.joint_vector(&robot);
            let fk = ForwardKinematics::new(&robot, &q).unwrap();
            let measures = jacobian_measures(
                &geometric_jacobian(&fk),
                Task::Position,
                fk.tool_rotation(),
                robot.length_scale(),
            );
            let inv = 1.0 / robot.length_scale();
            let w = linear_manipulability(&fk, inv);
            let s = linear_sigma_min(&fk, inv);
            let svd_min = *measures.singular_values.last().unwrap();
            let scale = measures.singular_values[0].max(1e-12);
            assert!(
                (w - measures.manipulability).abs() <= 1e-9 * scale.powi(3).max(1e-12),
                "{id}: det {w} vs svd {}",
                measures.manipulability
            );
            assert!(
                (s - svd_min).abs() <= 1e-7 * scale,
                "{id}: σ_min {s} vs {svd_min}"
            );
        }
    }
    // The closed-form eigenvalue on a matrix with known eigenvalues 1, 2, 5.
    let r = nalgebra::Rotation3::from_euler_angles(0.3, -0.7, 1.1);
    let a =
        r.matrix() * Matrix3::from_diagonal(&Vector3::new(5.0, 1.0, 2.0)) * r.matrix().transpose();
    assert!((smallest_symmetric_eigenvalue(&a) - 1.0).abs() < 1e-12);
}

#[test]
fn nearest_sample_and_inside_the_sampled_workspace() {
    // The planar 2R (l = 2, 1) reaches the annulus 1 ≤ r ≤ 3.
    let robot = preset("planar-2r").unwrap();
    let mut cloud = WorkspaceCloud::new(&robot, WorkspaceMeasure::SigmaMin, 20_000, 3);
    assert!(cloud.nearest(&Vector3::zeros()).is_none());
    cloud.fill(20_000);
    let p = cloud.positions[123];
    let n = cloud.nearest(&p).unwrap();
    assert_eq!((n.index, n.distance), (123, 0.0));
    assert!(
        cloud.spacing() > 0.0 && cloud.spacing() < 0.1,
        "{}",
        cloud.spacing()
    );
    assert!(cloud.contains(&Vector3::new(2.0, 0.5, 0.0)));
    assert!(!cloud.contains(&Vector3::new(3.5, 0.0, 0.0)));
    assert!(!cloud.contains(&Vector3::new(0.2, 0.1, 0.0)));
    let far = cloud.nearest(&Vector3::new(4.0, 0.0, 0.0)).unwrap();
    assert!((far.distance - 1.0).abs() < 0.05, "{}", far.distance);
    // σ_min vanishes toward the stretched rim.
    let (rim, _) = cloud
        .positions
        .iter()
        .zip(&cloud.values)
        .max_by(|a, b| a.0.norm().total_cmp(&b.0.norm()))
        .unwrap();
    let k = cloud.nearest(rim).unwrap().index;
    assert!(cloud.values[k] < 0.05 * cloud.largest_value());
}

#[test]
fn the_joint_holding_a_stalled_puma_at_its_limit_is_named() {
    let robot = preset("puma560").unwrap();
    // Joint 2 at its −45° limit; the target needs it further (−50°).
    let q = [0.3, -FRAC_PI_4, -2.0, 0.2, 0.5, 0.1];
    let beyond = tool_pose(&robot, &[0.3, -FRAC_PI_4 - 0.09, -2.0, 0.2, 0.5, 0.1]);
    let held = joints_held_at_limits(&robot, &q, &beyond, Task::Position, 1e-9);
    assert_eq!(
        held.first().map(|h| (h.joint, h.at_max)),
        Some((1, false)),
        "{held:?}"
    );
    // A target back inside the range pulls joint 2 inward: nothing holds it.
    let inside = tool_pose(&robot, &[0.3, -FRAC_PI_4 + 0.09, -2.0, 0.2, 0.5, 0.1]);
    let held = joints_held_at_limits(&robot, &q, &inside, Task::Position, 1e-9);
    assert!(held.iter().all(|h| h.joint != 1), "{held:?}");
}

#[test]
fn a_five_axis_arm_reaches_only_some_tool_directions_at_one_position() {
    // The Metrover's tool y axis is joint 5's axis, set by joints 1–4, which also set
    // the position: at one position it can only point along a curve of directions (none
    // of 48 spread over the sphere but its own). Joint 5 rolls the hand about it, so the
    // tool's z axis can point anywhere.
    let robot = preset("metrover").unwrap();
    let q0 = [0.3, 1.0, 0.4, 0.5, 0.2];
    let pose = tool_pose(&robot, &q0);
    let position = pose.translation.vector;
    let settings = IkSettings {
        restarts: 8,
        budget: 1000,
        ..IkSettings::default()
    };
    let spread = sphere_directions(48);
    for d in &spread {
        assert!((d.norm() - 1.0).abs() < 1e-12);
    }
    for (axis, k, at_least, at_most) in [(ToolAxis::Y, 1, 0, 3), (ToolAxis::Z, 2, 44, 48)] {
        let mut directions = spread.clone();
        directions.push(pose.rotation.matrix().column(k).into_owned());
        let reach =
            direction_reachability(&robot, &position, axis, &directions, &q0, &settings).unwrap();
        assert_eq!(reach.len(), 49);
        // The arm's own direction is reachable (it is already there).
        assert!(reach[48].reachable, "{axis:?}");
        let reachable = reach[..48].iter().filter(|r| r.reachable).count();
        assert!(
            (at_least..=at_most).contains(&reachable),
            "{axis:?}: {reachable} of 48 reachable"
        );
        for r in reach.iter().filter(|r| r.reachable) {
            let p = tool_pose(&robot, &r.q);
            assert!((p.translation.vector - position).norm() < 1e-3);
            let a = p.rotation.matrix().column(k).into_owned();
            assert!(a.dot(&r.direction) > 1.0 - 1e-9, "{a} vs {}", r.direction);
        }
    }
}
