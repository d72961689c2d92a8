//! Joint-angle bookkeeping (docs/kinematics.md §3).
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::angles::wrap_to_pi;
use armlab_core::robot::nearest_equivalent_within;
use armlab_core::{JointLimits, preset};
use std::f64::consts::{PI, TAU};

#[test]
fn wrap_covers_interval_ends() {
    assert_eq!(wrap_to_pi(PI), PI);
    assert_eq!(wrap_to_pi(-PI), PI);
    assert!((wrap_to_pi(7.0) - (7.0 - TAU)).abs() < 1e-12);
    assert!((wrap_to_pi(-7.0) - (-7.0 + TAU)).abs() < 1e-12);
    let mut rng = common::rng(4);
    for _ in 0..1000 {
        let x = rng.uniform(-100.0, 100.0);
        let w = wrap_to_pi(x);
        assert!(w > -PI && w <= PI);
        assert!(((x - w) / TAU - ((x - w) / TAU).round()).abs() < 1e-9);
    }
}

/// Within a turn or so of (−π, π], wrapping subtracts or adds exactly one 2π (without the
/// remainder loop) and agrees with the remainder `rem_euclid` gives to its last bit.
#[test]
fn wrapping_a_turn_off_is_one_exact_turn() {
    let by_remainder = |x: f64| {
        let r = x.rem_euclid(TAU);
        if r > PI { r - TAU } else { r }
    };
    let mut rng = common::rng(41);
    for k in 0..20_000 {
        let x = match k {
            0 => 3.0 * PI,
            1 => -3.0 * PI,
            2 => TAU,
            3 => -TAU,
            4 => 4.0 * PI,
            5 => -4.0 * PI,
            _ => rng.uniform(-4.0 * PI, 4.0 * PI),
        };
        let w = wrap_to_pi(x);
        assert!(w > -PI && w <= PI, "wrap({x}) = {w}");
        let turns = x - w;
        assert!(
            [0.0, TAU, -TAU, 2.0 * TAU, -2.0 * TAU].contains(&turns),
            "wrap({x}) = {w}: off by {turns}, not whole turns"
        );
        let r = by_remainder(x);
        // Bit for bit, but for the remainder's −0 at x = −2π.
        if r != 0.0 {
            assert_eq!(
                w.to_bits(),
                r.to_bits(),
                "wrap({x}) = {w}, by the remainder {r}"
            );
        }
    }
}

#[test]
fn nearest_equivalent_prefers_the_current_side() {
    let wide = JointLimits {
        min: -TAU,
        max: TAU,
    };
    let v = 350f64.to_radians();
    assert!((nearest_equivalent_within(v, 340f64.to_radians(), &wide) - v).abs() < 1e-12);
    let near_zero = nearest_equivalent_within(v, -5f64.to_radians(), &wide);
    assert!((near_zero - (-10f64).to_radians()).abs() < 1e-12);
}

#[test]
fn narrow_limits_clamp_to_the_nearest_limit() {
    let half = JointLimits { min: 0.0, max: PI };
    assert_eq!(nearest_equivalent_within(-0.1, 0.0, &half), 0.0);
    assert_eq!(nearest_equivalent_within(PI + 0.1, 3.0, &half), PI);
    assert!((nearest_equivalent_within(1.0 + TAU, 0.0, &half) - 1.0).abs() < 1e-12);
}

#[test]
fn joints_keep_angles_as_spec_says() {
    let metrover = preset("metrover").unwrap();
    // Joint 1 (±180°) wraps; joint 2 (0…180°) clamps.
    assert!((metrover.joints[0].keep(4.0, 0.0) - (4.0 - TAU)).abs() < 1e-12);
    assert_eq!(metrover.joints[1].keep(-0.2, 0.1), 0.0);
    // Puma joint 6 is ±266°: 250° stays 250° when the joint is near 200°.
    let puma = preset("puma560").unwrap();
    let j6 = &puma.joints[5];
    assert!(!j6.wraps());
    let v = 250f64.to_radians();
    assert!((j6.keep(v, 200f64.to_radians()) - v).abs() < 1e-12);
    assert!((j6.keep(v, 0.0) - (v - TAU)).abs() < 1e-12);
    // A joint's change is the wrapped difference.
    assert!((j6.change(3.0, -3.0) - (TAU - 6.0)).abs() < 1e-12);
    // Prismatic joints clamp to their stroke.
    let stanford = preset("stanford").unwrap();
    assert_eq!(stanford.joints[2].keep(5.0, 0.5), 1.27);
    assert_eq!(stanford.joints[2].change(0.4, 0.9), 0.5);
}

#[test]
fn fast_sin_cos_agrees_with_the_library() {
    use armlab_core::angles::sin_cos;
    let mut rng = common::rng(8);
    let mut worst: f64 = 0.0;
    let mut xs: Vec<f64> = (0..20000).map(|_| rng.uniform(-50.0, 50.0)).collect();
    xs.extend((0..2000).map(|_| rng.uniform(-1e5, 1e5)));
    xs.extend([
        0.0,
        -0.0,
        PI,
        -PI,
        PI / 2.0,
        PI / 4.0,
        3.0 * PI / 4.0,
        1e-300,
        2e6,
        f64::NAN,
    ]);
    for x in xs {
        let (s, c) = sin_cos(x);
        let (s0, c0) = x.sin_cos();
        if x.is_nan() {
            assert!(s.is_nan() && c.is_nan());
            continue;
        }
        worst = worst.max((s - s0).abs()).max((c - c0).abs());
    }
    assert!(worst <= 4.5e-16, "largest difference {worst:e}");
}

#[test]
fn two_angles_at_once_are_the_one_angle_sin_cos_bit_for_bit() {
    use armlab_core::angles::{sin_cos, sin_cos_2};
    let mut rng = common::rng(9);
    let mut xs: Vec<f64> = (0..20000).map(|_| rng.uniform(-50.0, 50.0)).collect();
    xs.extend((0..2000).map(|_| rng.uniform(-1e6, 1e6)));
    // Quadrant edges, both signs of zero, the range's end and what the library takes.
    xs.extend([
        0.0,
        -0.0,
        PI / 4.0,
        -PI / 4.0,
        PI / 2.0,
        -PI,
        3.0 * PI,
        1e-300,
    ]);
    xs.extend([999_999.9, 1e6, -1e6, 2e6, f64::INFINITY, f64::NAN]);
    let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
    for pair in xs.chunks_exact(2).chain(xs.windows(2).rev().take(20)) {
        let (s, c) = sin_cos_2([pair[0], pair[1]]);
        for k in 0..2 {
            let (s1, c1) = sin_cos(pair[k]);
            assert!(
                same(s[k], s1) && same(c[k], c1),
                "x = {}: ({}, {}) vs ({s1}, {c1})",
                pair[k],
                s[k],
                c[k]
            );
        }
    }
}

#[test]
fn polynomial_atan2_is_within_two_ulp_of_the_library() {
    use armlab_core::angles::atan2_poly as atan2;
    let ulps = |a: f64, b: f64| -> u64 {
        if a == b {
            return 0;
        }
        // Same sign here (the results share y's sign), so the bit distance counts ulps.
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    };
    let mut rng = common::rng(10);
    let mut worst = 0u64;
    let mut pairs: Vec<(f64, f64)> = (0..200_000)
        .map(|_| (rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)))
        .collect();
    // Ratios near the eighths' switching points and the octant edges, scales far apart.
    for k in 0..=16 {
        let t = k as f64 / 16.0;
        for d in [-1e-12, 0.0, 1e-12] {
            for (sy, sx) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                pairs.push((sy * (t + d), sx * 1.0));
                pairs.push((sy * 1.0, sx * (t + d)));
            }
        }
    }
    pairs.extend((0..20_000).map(|_| {
        let e = rng.uniform(-280.0, 280.0);
        (
            rng.uniform(-1.0, 1.0) * 10f64.powf(e),
            rng.uniform(-1.0, 1.0),
        )
    }));
    for &(y, x) in &pairs {
        let (got, want) = (atan2(y, x), y.atan2(x));
        assert_eq!(
            got.is_sign_negative(),
            want.is_sign_negative(),
            "({y}, {x})"
        );
        worst = worst.max(ulps(got, want));
    }
    assert!(worst <= 2, "largest difference {worst} ulp");
    // What the library answers: zeros of both signs, infinities, NaN, extreme magnitudes.
    let special = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e300,
        -1e-300,
    ];
    for &y in &special {
        for &x in &special {
            assert_eq!(atan2(y, x).to_bits(), y.atan2(x).to_bits(), "({y}, {x})");
        }
    }
    assert!(atan2(f64::NAN, 1.0).is_nan() && atan2(1.0, f64::NAN).is_nan());
}

#[test]
fn polynomial_asin_is_within_two_ulp_of_the_library() {
    use armlab_core::angles::asin_poly;
    let mut rng = common::rng(11);
    let mut xs: Vec<f64> = (0..100_000).map(|_| rng.uniform(-1.0, 1.0)).collect();
    // Near ±1 (where the root is small), near 0 and tiny, and the ends.
    xs.extend((0..2_000).map(|_| 1.0 - 10f64.powf(rng.uniform(-16.0, -1.0))));
    xs.extend((0..2_000).map(|_| 10f64.powf(rng.uniform(-300.0, -1.0))));
    xs.extend([0.0, 0.5, 1.0, 1.0 - f64::EPSILON / 2.0]);
    let mut worst = 0u64;
    for x in xs.iter().flat_map(|&x| [x, -x]) {
        let (got, want) = (asin_poly(x), x.asin());
        assert_eq!(got.is_sign_negative(), want.is_sign_negative(), "{x}");
        worst = worst.max((got.to_bits() as i64 - want.to_bits() as i64).unsigned_abs());
    }
    assert!(worst <= 2, "largest difference {worst} ulp");
    assert!(asin_poly(1.5).is_nan() && asin_poly(f64::NAN).is_nan());
}
