//! docs/kinematics.md §14: every preset written in the other convention gives the same
//! tool pose at every q, converting back returns the original table, and the editor's
//! joint insertion and removal keep the other joints' values.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::convention::{convert, frames_in_both_conventions, link_part};
use armlab_core::edit::{insert_joint, remove_joint, switch_convention};
use armlab_core::{Convention, Robot, preset, tool_pose};
use nalgebra::{IsometryMatrix3, Translation3, UnitQuaternion, Vector3};

fn other(c: Convention) -> Convention {
    match c {
        Convention::Standard => Convention::Modified,
        Convention::Modified => Convention::Standard,
    }
}

/// The largest T_0n difference of two robots over 1000 random q.
fn worst_tool_difference(a: &Robot, b: &Robot, seed: u64) -> f64 {
    let mut rng = common::rng(seed);
    let mut worst: f64 = 0.0;
    for _ in 0..1000 {
        let q = rng.joint_vector(a);
        let d = tool_pose(a, &q).to_homogeneous() - tool_pose(b, &q).to_homogeneous();
        worst = worst.max(d.abs().max());
    }
    worst
}

/// The largest difference of two tables (rows, base and tool).
fn table_difference(a: &Robot, b: &Robot) -> f64 {
    assert_eq!(a.convention, b.convention);
    assert_eq!(a.dof(), b.dof());
    let rows = a.joints.iter().zip(&b.joints).fold(0.0_f64, |m, (x, y)| {
        assert_eq!(x.kind, y.kind);
        m.max((x.dh.theta - y.dh.theta).abs())
            .max((x.dh.d - y.dh.d).abs())
            .max((x.dh.a - y.dh.a).abs())
            .max((x.dh.alpha - y.dh.alpha).abs())
    });
    let base = (a.world_from_base.to_homogeneous() - b.world_from_base.to_homogeneous())
        .abs()
        .max();
    let tool = (a.flange_from_tool.to_homogeneous() - b.flange_from_tool.to_homogeneous())
        .abs()
        .max();
    rows.max(base).max(tool)
}

#[test]
fn every_preset_converted_both_ways_keeps_t0n_at_1000_random_q() {
    for (id, robot) in common::all_presets() {
        let converted = convert(&robot, other(robot.convention));
        assert_eq!(converted.convention, other(robot.convention), "{id}");
        let d = worst_tool_difference(&robot, &converted, 21);
        assert!(d <= 1e-9, "{id}: converted differs by {d}");
        let back = convert(&converted, robot.convention);
        let d = worst_tool_difference(&robot, &back, 22);
        assert!(d <= 1e-9, "{id}: converted back differs by {d}");
        let t = table_difference(&robot, &back);
        assert!(t <= 1e-12, "{id}: the table came back changed by {t}");
    }
}

#[test]
fn the_converted_ur10_agrees_with_ur10_standard() {
    let ur10 = preset("ur10").unwrap();
    let standard = preset("ur10-standard").unwrap();
    let converted = convert(&ur10, Convention::Standard);
    let d = worst_tool_difference(&converted, &standard, 23);
    assert!(d <= 1e-9, "differs by {d} mm");
    // Not row by row: the converted table moves a_{i−1} to row i−1 without the π
    // offsets of the published standard table.
    let a: Vec<f64> = converted.joints.iter().map(|j| j.dh.a).collect();
    assert_eq!(a, vec![0.0, 612.9, 571.6, 0.0, 0.0, 0.0]);
    let alpha: Vec<f64> = converted
        .joints
        .iter()
        .map(|j| j.dh.alpha.to_degrees().round())
        .collect();
    assert_eq!(alpha, vec![90.0, 0.0, 0.0, -90.0, 90.0, 0.0]);
}

#[test]
fn a_robot_with_base_and_tool_transforms_converts_and_returns() {
    // A base and tool that are not pure link parts stay where they are.
    let mut robot = preset("puma560").unwrap();
    robot.world_from_base = IsometryMatrix3::from_parts(
        Translation3::new(0.1, -0.2, 0.3),
        UnitQuaternion::from_euler_angles(0.2, -0.4, 0.9).to_rotation_matrix(),
    );
    robot.flange_from_tool = link_part(0.05, 0.3)
        * IsometryMatrix3::from_parts(
            Translation3::new(0.0, 0.02, 0.1),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.5).to_rotation_matrix(),
        );
    for to in [Convention::Modified, Convention::Standard] {
        let converted = convert(&robot, to);
        let d = worst_tool_difference(&robot, &converted, 24);
        assert!(d <= 1e-9, "{to:?}: differs by {d}");
    }
    let back = convert(&convert(&robot, Convention::Modified), Convention::Standard);
    assert!(worst_tool_difference(&robot, &back, 25) <= 1e-9);
}

#[test]
fn both_sets_of_frames_end_at_the_same_tool() {
    for (id, robot) in common::all_presets() {
        let q = robot.home();
        let frames = frames_in_both_conventions(&robot, &q).unwrap();
        assert_eq!(frames.standard_frames.len(), robot.dof() + 1, "{id}");
        assert_eq!(frames.modified_frames.len(), robot.dof() + 1, "{id}");
        assert!(frames.disagreement <= 1e-9, "{id}: {}", frames.disagreement);
        assert_eq!(frames.standard.convention, Convention::Standard);
        assert_eq!(frames.modified.convention, Convention::Modified);
    }
    // The UR10's modified frame 2 sits at the shoulder axis, its standard frame 1 too
    // (the same point, 128 mm up), while their frame 3 differ (elbow vs. the next axis).
    let ur10 = preset("ur10").unwrap();
    let f = frames_in_both_conventions(&ur10, &[0.0; 6]).unwrap();
    let p = |iso: &IsometryMatrix3<f64>| iso.translation.vector;
    common::assert_vec_near(
        "modified o2",
        &p(&f.modified_frames[2]),
        [0.0, 0.0, 128.0],
        1e-9,
    );
    common::assert_vec_near(
        "standard o1",
        &p(&f.standard_frames[1]),
        [0.0, 0.0, 128.0],
        1e-9,
    );
    common::assert_vec_near(
        "modified o3",
        &p(&f.modified_frames[3]),
        [612.9, 0.0, 128.0],
        1e-9,
    );
    assert!(frames_in_both_conventions(&ur10, &[0.0; 5]).is_err());
}

#[test]
fn switching_the_convention_keeps_the_arm() {
    let robot = preset("metrover").unwrap();
    let switched = switch_convention(&robot, Convention::Modified);
    assert_eq!(switched.convention, Convention::Modified);
    assert!(worst_tool_difference(&robot, &switched, 26) <= 1e-9);
    // The old editor's mistake, the same numbers under the other convention, is another arm.
    let mut same_numbers = robot.clone();
    same_numbers.convention = Convention::Modified;
    assert!(worst_tool_difference(&robot, &same_numbers, 27) > 1.0);
}

#[test]
fn adding_and_removing_a_joint_keeps_the_other_values() {
    let robot = preset("ur10").unwrap();
    let q = [0.1, -0.2, 0.3, -0.4, 0.5, -0.6];
    let mut extra = robot.joints[5].clone();
    extra.home = 0.25;
    let (more, q_more) = insert_joint(&robot, &q, 2, extra.clone());
    assert_eq!(more.dof(), 7);
    assert_eq!(q_more, vec![0.1, -0.2, 0.25, 0.3, -0.4, 0.5, -0.6]);
    let (appended, q_app) = insert_joint(&robot, &q, 99, extra);
    assert_eq!(appended.joints.last().unwrap().home, 0.25);
    assert_eq!(q_app, vec![0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.25]);
    let (fewer, q_fewer) = remove_joint(&robot, &q, 1).unwrap();
    assert_eq!(fewer.dof(), 5);
    assert_eq!(fewer.joints[1].name, robot.joints[2].name);
    assert_eq!(q_fewer, vec![0.1, 0.3, -0.4, 0.5, -0.6]);
    assert!(remove_joint(&robot, &q, 6).is_none());
}
