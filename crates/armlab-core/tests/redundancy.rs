//! Self-motion of a redundant arm (docs/kinematics.md §11): the Panda's elbow swings
//! through the null space while the hand stays put.

#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

use armlab_core::redundancy::{SelfMotionError, null_direction, self_motion};
use armlab_core::{
    ForwardKinematics, Task, geometric_jacobian, preset, robot_from_json, task_jacobian,
};

/// Three Panda poses well inside the limits: the ready pose and two others.
const POSES: [[f64; 7]; 3] = [
    [
        0.0,
        -FRAC_PI_4,
        0.0,
        -3.0 * FRAC_PI_4,
        0.0,
        FRAC_PI_2,
        FRAC_PI_4,
    ],
    [0.4, -0.3, -0.5, -1.9, 0.3, 1.9, -0.2],
    [-0.6, 0.2, 0.4, -2.2, -0.4, 2.3, 0.9],
];

#[test]
fn a_panda_self_motion_of_one_radian_each_way_keeps_the_hand_within_1e_6() {
    let robot = preset("panda").unwrap();
    for q0 in POSES {
        let start = ForwardKinematics::new(&robot, &q0).unwrap();
        for s in [1.0, -1.0] {
            let m = self_motion(&robot, &q0, Task::FullPose, s).unwrap();
            assert_eq!(m.stopped_by, None, "{q0:?} {s}: no limit on the way");
            assert!((m.travelled - s).abs() < 1e-12, "travelled {}", m.travelled);
            let end = ForwardKinematics::new(&robot, &m.q).unwrap();
            let dp = (end.base_from_tool.translation.vector
                - start.base_from_tool.translation.vector)
                .norm();
            let dr =
                (end.base_from_tool.rotation.inverse() * start.base_from_tool.rotation).angle();
            assert!(
                dp < 1e-6 && dr < 1e-6,
                "{q0:?} {s}: the hand moved {dp} m, {dr} rad"
            );
            assert!(
                m.max_position_error < 1e-6 && m.max_orientation_error < 1e-6,
                "{m:?}"
            );
            // The joints did move by about the arc length, and the elbow swung.
            let moved: f64 =
                m.q.iter()
                    .zip(&q0)
                    .map(|(a, b)| (a - b).powi(2))
                    .sum::<f64>()
                    .sqrt();
            assert!(
                moved > 0.9 && moved <= 1.0 + 1e-9,
                "{q0:?} {s}: joints moved {moved}"
            );
            let elbow = |fk: &ForwardKinematics| fk.base_from_frames[3].translation.vector;
            let swing = (elbow(&end) - elbow(&start)).norm();
            assert!(swing > 0.02, "{q0:?} {s}: the elbow moved {swing} m");
        }
    }
}

#[test]
fn the_null_direction_is_orthogonal_to_every_task_row_and_has_a_fixed_sign() {
    let robot = preset("panda").unwrap();
    let mut rng = common::rng(11);
    let (mut checked, mut singular) = (0, 0);
    for _ in 0..200 {
        let q = rng.joint_vector(&robot);
        let fk = ForwardKinematics::new(&robot, &q).unwrap();
        let rows = task_jacobian(
            &geometric_jacobian(&fk),
            Task::FullPose,
            fk.tool_rotation(),
            1.0,
        );
        let n = match null_direction(&robot, &q, Task::FullPose) {
            Ok(n) => n,
            // Only a singular pose has none; the count below asserts there is none here.
            Err(SelfMotionError::Singular) => {
                singular += 1;
                continue;
            }
            Err(e) => panic!("{q:?}: {e:?}"),
        };
        assert!((n.norm() - 1.0).abs() < 1e-12);
        assert!((rows * &n).norm() < 1e-9 * robot.length_scale());
        let again = null_direction(&robot, &q, Task::FullPose).unwrap();
        assert_eq!(n, again, "the same pose, the same direction");
        // Independently of the core's Jacobian: moving along it leaves the hand still to
        // first order, by central differences of the tests' own FK.
        let h = 1e-5;
        let moved = |t: f64| {
            let qt: Vec<f64> = q.iter().zip(n.iter()).map(|(a, b)| a + t * b).collect();
            common::own_fk(&robot, &qt).tool
        };
        let (dp, dr) = common::pose_distance(&moved(h), &moved(-h));
        assert!(
            dp / (2.0 * h) < 1e-6 && dr / (2.0 * h) < 1e-6,
            "{q:?}: along the null direction the hand moves {} m and turns {} rad per rad",
            dp / (2.0 * h),
            dr / (2.0 * h)
        );
        checked += 1;
    }
    // Random joint vectors are regular almost surely: every one of them has a direction,
    // so a null_direction that failed everywhere (or often) cannot pass by being skipped.
    assert_eq!(
        (checked, singular),
        (200, 0),
        "poses checked and poses without a direction, of 200"
    );
}

#[test]
fn self_motion_needs_exactly_one_spare_joint_and_a_regular_pose() {
    let ur10 = preset("ur10").unwrap();
    assert_eq!(
        self_motion(&ur10, &[0.0, 1.0, -1.5, 2.0, 1.5, 0.0], Task::FullPose, 0.5),
        Err(SelfMotionError::NotOneDimensional { joints: 6, rows: 6 })
    );
    // A planar 4R arm on a position task: its z row is zero at every pose, so the three
    // rows never have full rank and the self-motion is not one curve.
    let planar = robot_from_json(
        r#"{"format": "armlab-robot/1", "name": "Planar 4R", "convention": "standard",
            "length_unit": "m", "joints": [
            {"name": "1", "type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0},
            {"name": "2", "type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0},
            {"name": "3", "type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0},
            {"name": "4", "type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0}]}"#,
    )
    .unwrap();
    assert_eq!(
        self_motion(&planar, &[0.3, 0.4, -0.5, 0.6], Task::Position, 0.5),
        Err(SelfMotionError::Singular)
    );
}
