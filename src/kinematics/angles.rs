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
