//! Joint-angle bookkeeping (SPEC §2): wrapping to (−π, π] and keeping an angle as the
//! 2π-equivalent inside a joint's limits nearest the current value.

use std::f64::consts::{PI, TAU};

use super::robot::JointLimits;

/// `x` wrapped to the half-open interval (−π, π].
///
/// ```
/// use armlab::kinematics::angles::wrap_to_pi;
/// use std::f64::consts::PI;
/// assert_eq!(wrap_to_pi(-PI), PI);
/// assert!((wrap_to_pi(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
/// ```
pub fn wrap_to_pi(x: f64) -> f64 {
    if x > -PI && x <= PI {
        return x;
    }
    let r = x.rem_euclid(TAU); // [0, 2π)
    if r > PI { r - TAU } else { r }
}

/// The 2π-equivalent of `value` (value + 2πk) that lies inside `limits` and is nearest
/// to `current`. When no equivalent lies inside (limits narrower than a turn), the
/// limit nearest to any equivalent is returned, so the result is always inside.
pub fn nearest_equivalent_within(value: f64, current: f64, limits: &JointLimits) -> f64 {
    // The equivalent nearest `current`, then its neighbours one turn either side.
    let base = current + wrap_to_pi(value - current);
    let mut best: Option<(f64, f64)> = None; // (distance to current, candidate)
    let mut k_lo = ((limits.min - base) / TAU).floor() as i64;
    let mut k_hi = ((limits.max - base) / TAU).ceil() as i64;
    // Guard against absurd spans: at most a few turns matter.
    k_lo = k_lo.max(-8);
    k_hi = k_hi.min(8);
    for k in k_lo..=k_hi {
        let candidate = base + TAU * k as f64;
        if limits.contains(candidate, 1e-12) {
            let dist = (candidate - current).abs();
            if best.is_none_or(|(d, _)| dist < d) {
                best = Some((dist, limits.clamp(candidate)));
            }
        }
    }
    if let Some((_, candidate)) = best {
        return candidate;
    }
    // No equivalent inside: clamp to the limit closest to the wrapped value's circle.
    let to_min = wrap_to_pi(limits.min - value).abs();
    let to_max = wrap_to_pi(limits.max - value).abs();
    if to_min <= to_max {
        limits.min
    } else {
        limits.max
    }
}

/// sin x and cos x together, for forward kinematics' hot loop: one shared argument
/// reduction and two short polynomials instead of two library calls (about twice as fast
/// natively, more on wasm where the library's sin and cos are software). Within 2 ulp of
/// `f64::sin_cos` for |x| < 10⁶; beyond that it calls the library.
///
/// Reduction: `x = k·π/2 + r`, |r| ≤ π/4, with π/2 split in three parts (33 + 33 + 53 bits)
/// so that `k·part` is exact; then the minimax polynomials of degree 13 (sin) and 14 (cos)
/// on [−π/4, π/4] (the coefficients of Sun's fdlibm kernels) and the quadrant's signs.
///
/// ```
/// use armlab::kinematics::angles::sin_cos;
/// let (s, c) = sin_cos(1.0);
/// assert!((s - 1f64.sin()).abs() < 1e-15 && (c - 1f64.cos()).abs() < 1e-15);
/// ```
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    const TWO_OVER_PI: f64 = std::f64::consts::FRAC_2_PI;
    const PIO2_1: f64 = 1.570_796_326_734_125_614_17; // first 33 bits of π/2
    const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11; // next 33 bits
    const PIO2_3: f64 = 2.022_266_248_795_950_631_54e-21; // the rest
    if !(x.abs() < 1e6) {
        return x.sin_cos(); // huge or not finite: the library handles it
    }
    // Round to nearest by adding and removing 1.5·2⁵² (no library call, unlike `round`).
    const ROUNDER: f64 = 6_755_399_441_055_744.0;
    let k = (x * TWO_OVER_PI + ROUNDER) - ROUNDER;
    let r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3;
    let z = r * r;
    let s = r + r
        * z
        * (-1.666_666_666_666_663_243_48e-1
            + z * (8.333_333_333_322_489_461_24e-3
                + z * (-1.984_126_982_985_794_931_34e-4
                    + z * (2.755_731_370_707_006_767_89e-6
                        + z * (-2.505_076_025_340_686_341_95e-8
                            + z * 1.589_690_995_211_550_102_21e-10)))));
    let c = 1.0 - 0.5 * z
        + z * z
            * (4.166_666_666_666_660_190_37e-2
                + z * (-1.388_888_888_887_410_957_49e-3
                    + z * (2.480_158_728_947_672_941_78e-5
                        + z * (-2.755_731_435_139_066_330_35e-7
                            + z * (2.087_572_321_298_174_827_90e-9
                                + z * -1.135_964_755_778_819_482_65e-11)))));
    match (k as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}
