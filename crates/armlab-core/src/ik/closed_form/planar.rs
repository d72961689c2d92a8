//! The planar 2R and the base yaw (the shoulder) that every arm family here builds on,
//! with the 2R and RRR arms themselves; apart from the 6-axis families that reuse them.

use std::f64::consts::PI;

use crate::angles::{asin, atan2, sin_cos};
use nalgebra::{IsometryMatrix3, Vector3};

use super::canonical::Canonical;
use super::raw::Raw;
use crate::ik::branch::{Branch, Elbow, Shoulder};

/// A planar 2R branch.
#[derive(Debug, Clone, Copy)]
pub(super) struct Planar {
    /// The first joint's angle.
    pub(super) ta: f64,
    /// The second joint's angle.
    pub(super) tb: f64,
    /// The sign given to `sin θ_b` (+1 or −1; the first entry is +1).
    pub(super) sign: f64,
    /// The point is within reach (not clamped).
    pub(super) exact: bool,
    /// Stretched or folded: the two branches coincide (one returned).
    pub(super) singular: bool,
    /// The point is at the base with equal links: θ_a is free and took the seed's value.
    pub(super) free_a: bool,
}

/// Planar 2R by the law of cosines (docs/kinematics.md §9.1): `c_b = (x² + y² − a1² − a2²)/(2·a1·a2)`,
/// `θ_b = ±acos(c_b)`, `θ_a = atan2(y, x) − atan2(a2·s_b, a1 + a2·c_b)`. Out of reach, c_b
/// is clamped (arm stretched or folded toward the point, `exact` false). Stretched or
/// folded, the two branches coincide (one returned, `singular`); at the origin of an
/// arm with equal links θ_a is free and takes `seed_a`.
pub(super) fn planar_2r(x: f64, y: f64, a1: f64, a2: f64, seed_a: f64, out: &mut Vec<Planar>) {
    let r2 = x * x + y * y;
    let c_raw = (r2 - a1 * a1 - a2 * a2) / (2.0 * a1 * a2);
    let exact = c_raw.abs() <= 1.0 + 1e-10;
    let c = c_raw.clamp(-1.0, 1.0);
    let s = (1.0 - c * c).max(0.0).sqrt();
    let singular = s < 1e-7;
    let scale = a1.abs() + a2.abs();
    let at_base = r2.sqrt() <= 1e-12 * scale;
    // Shared by both elbows; atan2 is odd in y, so the second elbow's θ_b is −θ_b.
    let (phi, tb_up) = (atan2(y, x), atan2(s, c));
    for sign in [1.0, -1.0] {
        let sb = sign * s;
        let tb = sign * tb_up;
        let kx = a1 + a2 * c;
        let ky = a2 * sb;
        let free_a = at_base && kx.hypot(ky) <= 1e-12 * scale;
        let ta = if free_a { seed_a } else { phi - atan2(ky, kx) };
        out.push(Planar {
            ta,
            tb,
            sign,
            exact,
            singular: singular || free_a,
            free_a,
        });
        if singular {
            // The two elbows coincide (to 1e−7 rad): one solution.
            break;
        }
    }
}

/// The elbow of a planar 2R branch with links `l1`, `l2`: up when
/// `side · (−l1·l2·sign(sin θ_b)) > 0`, where `side` is +1 for arms drawn in a
/// horizontal plane and σ1·(±1 for the shoulder) for vertical arm planes (Lee's
/// ELBOW = ARM · sign); −l1·l2·sin θ_b is the cross product of the shoulder→wrist
/// vector with the shoulder→elbow vector.
pub(super) fn elbow_of(side: f64, l1: f64, l2: f64, sign: f64) -> Elbow {
    if side * (-l1 * l2 * sign) > 0.0 {
        Elbow::Up
    } else {
        Elbow::Down
    }
}

pub(super) fn shoulder_of(root: usize) -> Shoulder {
    if root == 0 {
        Shoulder::Right
    } else {
        Shoulder::Left
    }
}

/// The shoulder's sign: +1 for the first root (wrist in front), −1 for the second.
pub(super) fn front_sign(root: usize) -> f64 {
    if root == 0 { 1.0 } else { -1.0 }
}

/// The two base angles that put a point (x, y) at distance `d_sum` along
/// z_1 = σ_1(sin θ, −cos θ, 0): `σ_1(x sin θ − y cos θ) = D`. Returns
/// ([θ, θ'], exact, singular, free); on the base axis with D = 0 the angle is free (the
/// seed's and the seed's + π).
pub(super) fn shoulder(
    x: f64,
    y: f64,
    sigma1: f64,
    d_sum: f64,
    seed: f64,
    scale: f64,
) -> ([f64; 2], bool, bool, bool) {
    let rho = x.hypot(y);
    if rho <= 1e-12 * scale && d_sum.abs() <= 1e-12 * scale {
        return ([seed, seed + PI], true, true, true);
    }
    let phi = atan2(y, x);
    let ratio = if rho > 0.0 {
        sigma1 * d_sum / rho
    } else {
        sigma1 * d_sum.signum() * 2.0
    };
    let exact = ratio.abs() <= 1.0 + 1e-10;
    let mut ratio = ratio.clamp(-1.0, 1.0);
    let singular = (1.0 - ratio.abs()) < 1e-12 || rho <= 1e-9 * scale;
    if (1.0 - ratio.abs()) < 1e-12 {
        // The roots coincide (to 1.5e−6 rad, a position error of ρ·1e−12): one root, so
        // that the branches merge.
        ratio = ratio.signum();
    }
    let t = asin(ratio);
    ([phi + t, phi + PI - t], exact, singular, false)
}

/// The planar 2R's solutions into `raws`.
pub(super) fn planar_2r_family(
    c: &Canonical,
    target: &IsometryMatrix3<f64>,
    seed_theta: &[f64; 6],
    scale: f64,
    raws: &mut Vec<Raw>,
    planar: &mut Vec<Planar>,
) {
    let r = &c.rows;
    let p = c
        .pre
        .inverse_transform_point(&target.translation.vector.into());
    planar_2r(p.x, p.y, r[0].a, r[1].a, seed_theta[0], planar);
    let in_plane = (p.z - r[0].d - r[1].d).abs() <= 1e-9 * scale;
    for pl in planar.iter() {
        let branch = Branch {
            elbow: Some(elbow_of(1.0, r[0].a, r[1].a, pl.sign)),
            ..Branch::default()
        };
        let mut raw = Raw::new([pl.ta, pl.tb, 0.0, 0.0, 0.0, 0.0], branch);
        raw.exact = pl.exact && in_plane;
        raw.singular = pl.singular;
        raw.merged.elbow = pl.singular && !pl.free_a;
        raw.free[0] = pl.free_a;
        raws.push(raw);
    }
}

/// The RRR arm's solutions (base yaw, then a planar 2R) into `raws`.
pub(super) fn rrr_family(
    c: &Canonical,
    target: &IsometryMatrix3<f64>,
    seed_theta: &[f64; 6],
    scale: f64,
    raws: &mut Vec<Raw>,
    planar: &mut Vec<Planar>,
) {
    let r = &c.rows;
    let p = c
        .pre
        .inverse_transform_point(&target.translation.vector.into());
    let sigma1 = r[0].sigma();
    let w = Vector3::new(p.x, p.y, p.z - r[0].d);
    let d_sum = r[1].d + r[2].d;
    let (t1s, ok1, sing1, free1) = shoulder(w.x, w.y, sigma1, d_sum, seed_theta[0], scale);
    for (s, &t1) in t1s.iter().enumerate() {
        let (s1, c1) = sin_cos(t1);
        let x = w.x * c1 + w.y * s1;
        let y = sigma1 * w.z;
        planar.clear();
        planar_2r(x, y, r[1].a, r[2].a, seed_theta[1], planar);
        for pl in planar.iter() {
            let side = sigma1 * front_sign(s);
            let branch = Branch {
                shoulder: Some(shoulder_of(s)),
                elbow: Some(elbow_of(side, r[1].a, r[2].a, pl.sign)),
                wrist: None,
            };
            let mut raw = Raw::new([t1, pl.ta, pl.tb, 0.0, 0.0, 0.0], branch);
            raw.exact = pl.exact && ok1;
            raw.singular = pl.singular || sing1;
            raw.merged.elbow = pl.singular && !pl.free_a;
            raw.merged.shoulder = sing1 && !free1;
            raw.free[0] = free1;
            raw.free[1] = pl.free_a;
            raws.push(raw);
        }
    }
}
