//! The reference values of docs/kinematics.md §10: forward kinematics of every robot it gives numbers for.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::{ForwardKinematics, preset};
use common::{assert_rot_near, assert_vec_near, rng};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

#[test]
fn metrover_at_zero() {
    let robot = preset("metrover").unwrap();
    let fk = ForwardKinematics::new(&robot, &[0.0; 5]).unwrap();
    assert_vec_near("Metrover p", &fk.tool_position(), [400.0, 0.0, 520.0], 1e-9);
    assert_rot_near("Metrover R", fk.tool_rotation(), IDENTITY, 1e-12);
}

#[test]
fn ur10_at_zero_both_conventions() {
    for id in ["ur10", "ur10-standard"] {
        let robot = preset(id).unwrap();
        let fk = ForwardKinematics::new(&robot, &[0.0; 6]).unwrap();
        assert_vec_near(id, &fk.tool_position(), [1184.5, -256.1, 243.7], 1e-9);
        assert_rot_near(
            id,
            fk.tool_rotation(),
            [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
            1e-12,
        );
    }
}

#[test]
fn puma560_at_zero() {
    let robot = preset("puma560").unwrap();
    let fk = ForwardKinematics::new(&robot, &[0.0; 6]).unwrap();
    assert_vec_near(
        "Puma p",
        &fk.tool_position(),
        [0.4521, -0.15005, 1.10363],
        1e-12,
    );
    assert_rot_near("Puma R", fk.tool_rotation(), IDENTITY, 1e-12);
}

#[test]
#[allow(clippy::approx_constant)] // The published 0.7071, kept as printed.
fn panda_at_ready_pose() {
    let robot = preset("panda").unwrap();
    let q = [
        0.0,
        -FRAC_PI_4,
        0.0,
        -3.0 * FRAC_PI_4,
        0.0,
        FRAC_PI_2,
        FRAC_PI_4,
    ];
    assert_eq!(robot.home().len(), 7);
    for (h, want) in robot.home().iter().zip(q) {
        assert!((h - want).abs() < 1e-12, "Panda home is the ready pose");
    }
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    // The published values have four decimals.
    assert_vec_near("Panda p", &fk.tool_position(), [0.3069, 0.0, 0.5903], 5e-5);
    assert_rot_near(
        "Panda R",
        fk.tool_rotation(),
        [
            [0.7071, -0.7071, 0.0],
            [-0.7071, -0.7071, 0.0],
            [0.0, 0.0, -1.0],
        ],
        5e-5,
    );
}

#[test]
fn planar_2r_matches_closed_formula() {
    let robot = preset("planar-2r").unwrap();
    let (l1, l2) = (2.0, 1.0);
    let mut r = rng(2);
    let mut qs = vec![
        [0.0, 0.0],
        [0.1, 0.1],
        [FRAC_PI_2, -FRAC_PI_2],
        [PI, 0.5],
        [-2.0, 3.0],
    ];
    qs.extend((0..20).map(|_| [r.uniform(-PI, PI), r.uniform(-PI, PI)]));
    for [t1, t2] in qs {
        let fk = ForwardKinematics::new(&robot, &[t1, t2]).unwrap();
        let want = [
            l1 * t1.cos() + l2 * (t1 + t2).cos(),
            l1 * t1.sin() + l2 * (t1 + t2).sin(),
            0.0,
        ];
        assert_vec_near("2R", &fk.tool_position(), want, 1e-12);
    }
}

#[test]
fn rrr_matches_closed_formula() {
    let robot = preset("rrr").unwrap();
    let (l1, l2, l3) = (100.9, 222.1, 136.2);
    let mut r = rng(3);
    let mut qs = vec![
        [0.0, 0.0, 0.0],
        [0.3, 0.7, -1.1],
        [PI, FRAC_PI_2, FRAC_PI_2],
    ];
    qs.extend((0..20).map(|_| [r.uniform(-PI, PI), r.uniform(-PI, PI), r.uniform(-PI, PI)]));
    for [t1, t2, t3] in qs {
        let fk = ForwardKinematics::new(&robot, &[t1, t2, t3]).unwrap();
        let reach = l2 * t2.cos() + l3 * (t2 + t3).cos();
        let want = [
            t1.cos() * reach,
            t1.sin() * reach,
            l1 + l2 * t2.sin() + l3 * (t2 + t3).sin(),
        ];
        assert_vec_near("RRR", &fk.tool_position(), want, 1e-9);
    }
}

#[test]
fn running_products_are_products_of_link_transforms() {
    for (id, robot) in common::all_presets() {
        let q = rng(5).joint_vector(&robot);
        let fk = ForwardKinematics::new(&robot, &q).unwrap();
        let mut acc = robot.world_from_base;
        for (i, a) in fk.link_transforms.iter().enumerate() {
            acc *= a;
            let diff = (acc.to_homogeneous() - fk.base_from_frames[i].to_homogeneous())
                .abs()
                .max();
            assert!(diff < 1e-12, "{id}: T_0{} differs by {diff}", i + 1);
        }
        let tool = armlab_core::tool_pose(&robot, &q);
        let diff = (tool.to_homogeneous() - fk.base_from_tool.to_homogeneous())
            .abs()
            .max();
        assert!(diff < 1e-12, "{id}: tool_pose differs by {diff}");
    }
}

#[test]
fn prismatic_joint_moves_along_its_axis() {
    // Stanford arm: joint 3 slides d3; the tool moves by Δd along z_2.
    let robot = preset("stanford").unwrap();
    let mut q = robot.home();
    let a = ForwardKinematics::new(&robot, &q).unwrap();
    q[2] += 0.25;
    let b = ForwardKinematics::new(&robot, &q).unwrap();
    let moved = b.tool_position() - a.tool_position();
    let z2 = a.base_from_frames[1]
        .rotation
        .matrix()
        .column(2)
        .into_owned();
    assert!(
        (moved - z2 * 0.25).norm() < 1e-12,
        "moved {moved:?} along z2 {z2:?}"
    );
}

#[test]
fn link_transform_matrices_match_spec_formulas() {
    use armlab_core::{modified_dh_transform, standard_dh_transform};
    let (t, d, a, al) = (0.7_f64, 12.0, 34.0, -0.4_f64);
    let (st, ct, sa, ca) = (t.sin(), t.cos(), al.sin(), al.cos());
    let std = standard_dh_transform(t, d, a, al).to_homogeneous();
    #[rustfmt::skip]
    let want_std = nalgebra::Matrix4::new(
        ct, -st * ca, st * sa, a * ct,
        st, ct * ca, -ct * sa, a * st,
        0.0, sa, ca, d,
        0.0, 0.0, 0.0, 1.0);
    assert!((std - want_std).abs().max() < 1e-12);
    let modi = modified_dh_transform(al, a, t, d).to_homogeneous();
    #[rustfmt::skip]
    let want_mod = nalgebra::Matrix4::new(
        ct, -st, 0.0, a,
        st * ca, ct * ca, -sa, -sa * d,
        st * sa, ct * sa, ca, ca * d,
        0.0, 0.0, 0.0, 1.0);
    assert!((modi - want_mod).abs().max() < 1e-12);
}

#[test]
fn the_tests_own_forward_kinematics_agrees_with_the_core_on_every_preset() {
    // Other test files check the core's answers with common::own_fk; it must be right.
    let mut robots = common::all_presets();
    let mut moved = armlab_core::preset("puma560").unwrap();
    moved.world_from_base = nalgebra::IsometryMatrix3::from_parts(
        nalgebra::Translation3::new(0.3, -0.2, 0.5),
        nalgebra::Rotation3::from_euler_angles(0.4, -0.3, 1.2),
    );
    moved.flange_from_tool = nalgebra::IsometryMatrix3::from_parts(
        nalgebra::Translation3::new(0.01, 0.02, 0.15),
        nalgebra::Rotation3::from_euler_angles(-0.2, 0.5, 0.1),
    );
    robots.push(("moved puma560".into(), moved));
    for (id, robot) in &robots {
        let mut rng = rng(9);
        for _ in 0..50 {
            let q = rng.joint_vector(robot);
            let own = common::own_fk(robot, &q);
            let fk = ForwardKinematics::new(robot, &q).unwrap();
            let (dp, dr) = common::pose_distance(&own.tool, &fk.base_from_tool);
            assert!(
                dp <= 1e-12 * robot.reach() && dr <= 1e-12,
                "{id} {q:?}: {dp}, {dr} rad"
            );
        }
    }
    // The frames by hand for the planar 2R (l1 = 2, l2 = 1): joint 2's axis passes
    // through the end of link 1.
    let robot = armlab_core::preset("planar-2r").unwrap();
    let own = common::own_fk(&robot, &[FRAC_PI_2, -FRAC_PI_2]);
    assert_vec_near("2R joint 2 axis", &own.axes[1].0, [0.0, 2.0, 0.0], 1e-12);
    assert_vec_near("2R axis", &own.axes[1].1, [0.0, 0.0, 1.0], 1e-12);
    assert_vec_near(
        "2R tool",
        &own.tool.translation.vector,
        [1.0, 2.0, 0.0],
        1e-12,
    );
}
