//! The sampled workspace (docs/kinematics.md §10): slices add up to the whole, the
//! determinant-based manipulability and the closed-form σ_min agree with the SVD of the
//! measures, the nearest-point query, and the joints that hold a stalled IK at a limit.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::workspace::smallest_symmetric_eigenvalue;
use armlab_core::{
    ForwardKinematics, IkSettings, JointKind, Robot, Task, ToolAxis, WorkspaceCloud,
    WorkspaceMeasure, direction_reachability, geometric_jacobian, jacobian_measures,
    joints_held_at_limits, linear_manipulability, linear_sigma_min, preset, sphere_directions,
    tool_pose,
};
use nalgebra::{Matrix3, Matrix3xX, Vector3};
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
fn the_sampler_matches_forward_kinematics_and_the_tests_own_numbers() {
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
    // The UR10's mean measures over 20 000 samples of the benchmark's seed, against the
    // same joint vectors (the sampler draws each joint uniformly within its limits, in
    // joint order, from SplitMix64) measured by the tests' own FK and the SVD of the
    // linear Jacobian built from its axes.
    let ur10 = preset("ur10").unwrap();
    let samples = 20_000;
    for measure in [WorkspaceMeasure::Manipulability, WorkspaceMeasure::SigmaMin] {
        let mut cloud = WorkspaceCloud::new(&ur10, measure, samples, 0x00C0_FFEE);
        cloud.fill(samples);
        let mut rng = common::rng(0x00C0_FFEE);
        let mut worst: f64 = 0.0;
        let mut sum = 0.0;
        for value in &cloud.values {
            let want = own_measure(&ur10, &rng.joint_vector(&ur10), measure);
            worst = worst.max((value - want).abs());
            sum += want;
        }
        let want = sum / samples as f64;
        let got = cloud.values.iter().sum::<f64>() / samples as f64;
        // Each sample within 1e-9 (σ_min near a singularity is the square root of an
        // eigenvalue near 0 and keeps fewer digits: 1.3e-12 at worst here), the means
        // within 1e-12.
        assert!(
            (got - want).abs() <= 1e-12 && worst <= 1e-9,
            "{measure:?}: mean {got}, by the tests' own FK {want}; worst sample off by {worst}"
        );
    }
}

/// The linear Jacobian's measure at `q` by the tests' own means: the columns z × (p − o)
/// (z for a prismatic joint) from [`common::own_fk`]'s axes, divided by the arm's length
/// scale, and nalgebra's SVD: the product of the min(3, n) singular values, or the
/// smallest of them.
fn own_measure(robot: &Robot, q: &[f64], measure: WorkspaceMeasure) -> f64 {
    let fk = common::own_fk(robot, q);
    let p = fk.tool.translation.vector;
    let columns: Vec<Vector3<f64>> = fk
        .axes
        .iter()
        .zip(&robot.joints)
        .map(|((o, z), joint)| match joint.kind {
            JointKind::Revolute => z.cross(&(p - o)),
            JointKind::Prismatic => *z,
        } / robot.length_scale())
        .collect();
    let j = Matrix3xX::from_columns(&columns);
    let mut sv: Vec<f64> = j
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    sv.sort_by(|a, b| b.total_cmp(a));
    sv.truncate(3);
    match measure {
        WorkspaceMeasure::Manipulability => sv.iter().product(),
        WorkspaceMeasure::SigmaMin => sv.last().copied().unwrap_or(0.0),
    }
}

#[test]
fn the_planar_2r_cloud_has_the_means_of_uniform_joint_angles() {
    // Joint angles uniform in (−π, π] (the 2R has no limits written, so ±180°): by
    // integration, E|p|² = l1² + l2² + 2·l1·l2·E[cos θ2] = 5, E[p] = 0, and the
    // manipulability l1·l2·|sin θ2| / L² has mean l1·l2·(2/π) / L². The sample means of
    // 20 000 points differ from these by about their standard error σ/√20 000; the bounds
    // are five of those (σ(|p|²) = 4·√½, σ(x) = √((l1² + l2²)/2), σ(|sin|) = √(½ − 4/π²)).
    let robot = preset("planar-2r").unwrap();
    let (l1, l2) = (2.0, 1.0);
    let n = 20_000;
    let mut cloud = WorkspaceCloud::new(&robot, WorkspaceMeasure::Manipulability, n, 5);
    cloud.fill(n);
    let root_n = (n as f64).sqrt();
    let mean = |f: &dyn Fn(usize) -> f64| (0..n).map(f).sum::<f64>() / n as f64;
    let squared = mean(&|i| cloud.positions[i].norm_squared());
    let x = mean(&|i| cloud.positions[i].x);
    let y = mean(&|i| cloud.positions[i].y);
    let z = mean(&|i| cloud.positions[i].z.abs());
    let w = mean(&|i| cloud.values[i]);
    let scale = robot.length_scale();
    let want_w = l1 * l2 * (2.0 / std::f64::consts::PI) / (scale * scale);
    let spread_xy = ((l1 * l1 + l2 * l2) / 2.0_f64).sqrt();
    let spread_w = (0.5 - 4.0 / std::f64::consts::PI.powi(2)).sqrt() * l1 * l2 / (scale * scale);
    assert!(
        (squared - 5.0).abs() <= 5.0 * 4.0 * 0.5_f64.sqrt() / root_n,
        "mean |p|² {squared}, want 5"
    );
    assert!(
        x.abs() <= 5.0 * spread_xy / root_n && y.abs() <= 5.0 * spread_xy / root_n,
        "mean p ({x}, {y}), want 0"
    );
    assert_eq!(z, 0.0, "the planar arm stays in its plane");
    assert!(
        (w - want_w).abs() <= 5.0 * spread_w / root_n,
        "mean manipulability {w}, want {want_w}"
    );
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
