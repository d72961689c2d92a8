//! Orientation forms (docs/kinematics.md §7): R → angles → R returns R, degenerate cases included.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::{AngleAxis, EulerParameters, Orientation, XyzFixed, ZyxEuler, rotation_log};
use common::max_diff3;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use std::f64::consts::{FRAC_PI_2, PI};

fn random_rotation(rng: &mut armlab_core::SplitMix64) -> Matrix3<f64> {
    // Uniform on SO(3) from a uniform unit quaternion (Shoemake).
    let (u1, u2, u3) = (rng.next_f64(), rng.next_f64(), rng.next_f64());
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    let q = nalgebra::Quaternion::new(
        b * (2.0 * PI * u3).cos(),
        a * (2.0 * PI * u2).sin(),
        a * (2.0 * PI * u2).cos(),
        b * (2.0 * PI * u3).sin(),
    );
    nalgebra::UnitQuaternion::from_quaternion(q)
        .to_rotation_matrix()
        .into_inner()
}

fn check_all_forms(r: &Matrix3<f64>, what: &str) {
    let tol = 1e-12;
    let o = Orientation::from_rotation(r);
    assert!(
        max_diff3(&o.zyx_euler.to_rotation(), r) < tol,
        "{what}: Z-Y-X Euler {:?}",
        o.zyx_euler
    );
    assert!(
        max_diff3(&o.xyz_fixed.to_rotation(), r) < tol,
        "{what}: X-Y-Z fixed"
    );
    assert!(
        max_diff3(&o.angle_axis.to_rotation(), r) < tol,
        "{what}: angle-axis {:?}",
        o.angle_axis
    );
    assert!(
        max_diff3(&o.euler_parameters.to_rotation(), r) < tol,
        "{what}: Euler parameters"
    );
    let e = o.euler_parameters;
    assert!(((e.e1 * e.e1 + e.e2 * e.e2 + e.e3 * e.e3 + e.e4 * e.e4) - 1.0).abs() < 1e-14);
    let v = rotation_log(r);
    let back = Rotation3::from_scaled_axis(v).into_inner();
    assert!(max_diff3(&back, r) < tol, "{what}: rotation log");
    for x in [
        o.zyx_euler.alpha,
        o.zyx_euler.beta,
        o.zyx_euler.gamma,
        o.angle_axis.angle,
    ] {
        assert!(x.is_finite(), "{what}: not finite");
    }
}

#[test]
fn random_rotations_round_trip() {
    let mut rng = common::rng(11);
    for i in 0..1000 {
        let r = random_rotation(&mut rng);
        check_all_forms(&r, &format!("random #{i}"));
    }
}

#[test]
fn gimbal_lock_round_trips() {
    for beta in [FRAC_PI_2, -FRAC_PI_2] {
        for (alpha, gamma) in [(0.0, 0.0), (0.3, -1.2), (2.5, 2.9), (-3.0, 0.1)] {
            let r = ZyxEuler {
                alpha,
                beta,
                gamma,
                degenerate: false,
            }
            .to_rotation();
            check_all_forms(&r, &format!("β = {beta}, α = {alpha}, γ = {gamma}"));
            let e = ZyxEuler::from_rotation(&r);
            assert!(e.degenerate, "β = ±90° is flagged");
            assert!((e.beta - beta).abs() < 1e-9);
            // Only α ∓ γ is defined; the stored γ carries it.
            let want = if beta > 0.0 {
                gamma - alpha
            } else {
                gamma + alpha
            };
            let diff = armlab_core::angles::wrap_to_pi(e.gamma - want);
            assert!(diff.abs() < 1e-9, "γ = {} want {want}", e.gamma);
        }
    }
    // Just off the lock: still exact.
    for tiny in [1e-7, 1e-10, 1e-13] {
        let r = ZyxEuler {
            alpha: 0.4,
            beta: FRAC_PI_2 - tiny,
            gamma: -0.7,
            degenerate: false,
        }
        .to_rotation();
        check_all_forms(&r, &format!("β = 90° − {tiny}"));
    }
}

#[test]
fn identity_and_half_turns_round_trip() {
    let id = Matrix3::identity();
    check_all_forms(&id, "identity");
    let aa = AngleAxis::from_rotation(&id);
    assert_eq!(aa.angle, 0.0);
    assert!(aa.degenerate);
    assert_eq!(rotation_log(&id), Vector3::zeros());

    let mut rng = common::rng(12);
    let mut axes = vec![
        Vector3::x(),
        Vector3::y(),
        Vector3::z(),
        Vector3::new(1.0, 1.0, 1.0),
    ];
    axes.extend((0..50).map(|_| {
        Vector3::new(
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
        )
    }));
    for axis in axes {
        let k = Unit::new_normalize(axis);
        for angle in [PI, PI - 1e-9, 1e-9, 1e-15] {
            let r = Rotation3::from_axis_angle(&k, angle).into_inner();
            check_all_forms(&r, &format!("{angle} about {axis:?}"));
            let aa = AngleAxis::from_rotation(&r);
            assert!(
                (aa.angle - angle).abs() < 1e-9,
                "angle {} want {angle}",
                aa.angle
            );
            if angle > 1e-6 {
                // At π the axis is defined up to sign.
                assert!(aa.axis.dot(&k).abs() > 1.0 - 1e-9);
            }
        }
    }
}

#[test]
fn fixed_angles_are_euler_angles_read_backwards() {
    let r = ZyxEuler {
        alpha: 0.3,
        beta: -0.4,
        gamma: 1.1,
        degenerate: false,
    }
    .to_rotation();
    let f = XyzFixed::from_rotation(&r);
    assert!(
        (f.alpha - 0.3).abs() < 1e-12
            && (f.beta + 0.4).abs() < 1e-12
            && (f.gamma - 1.1).abs() < 1e-12
    );
    // Fixed X then Y then Z: R = Rz·Ry·Rx.
    let rx = Rotation3::from_axis_angle(&Vector3::x_axis(), 1.1).into_inner();
    let ry = Rotation3::from_axis_angle(&Vector3::y_axis(), -0.4).into_inner();
    let rz = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.3).into_inner();
    assert!(max_diff3(&(rz * ry * rx), &r) < 1e-12);
}

#[test]
fn euler_parameters_match_craig_for_known_rotation() {
    // 90° about z: ε = (0, 0, sin 45°), ε4 = cos 45°.
    let r = Rotation3::from_axis_angle(&Vector3::z_axis(), FRAC_PI_2).into_inner();
    let e = EulerParameters::from_rotation(&r);
    let h = (0.5_f64).sqrt();
    assert!(e.e1.abs() < 1e-15 && e.e2.abs() < 1e-15);
    assert!((e.e3 - h).abs() < 1e-15 && (e.e4 - h).abs() < 1e-15);
}
