//! The UR-family closed form (docs/kinematics.md §9.3), apart from the other families
//! for its size: the wrist's singular case alone takes a third of it.
//!
//! UR-family derivation (σ_i = sign sin α_i, z_1 = σ_1(sin θ_1, −cos θ_1, 0) the common
//! direction of axes 2–4, D = d_2 + d_3 + d_4): the wrist point `o_5 = p − d_6·z_6` has
//! `o_5·z_1 = D`, so `θ_1 = φ + asin(σ_1·D/ρ)` or `φ + π − asin(σ_1·D/ρ)` with
//! `(ρ, φ)` the polar form of o_5's x, y; the tool axis gives `z_6·z_1 = −σ_4σ_5·cos θ_5`
//! and `x_6·z_1 = σ_4 sin θ_5 cos θ_6`, `y_6·z_1 = −σ_4 sin θ_5 sin θ_6`, so θ_5 = ±atan2(
//! √((x_6·z_1)² + (y_6·z_1)²), −σ_4σ_5 z_6·z_1) and θ_6 follows; then
//! `A_2A_3A_4 = A_1⁻¹·T·(A_5A_6)⁻¹` is a planar 2R (a_2, a_3) plus θ_2+θ_3+θ_4 read from
//! its rotation. Up to 2 × 2 × 2 = 8 solutions.

use std::f64::consts::PI;

use crate::angles::{asin, atan2, sin_cos, wrap_to_pi};
use nalgebra::{IsometryMatrix3, Matrix3, Rotation3, Vector3};

use super::canonical::Canonical;
use super::planar::{Planar, elbow_of, front_sign, planar_2r, shoulder, shoulder_of};
use super::raw::{Merged, Raw};
use crate::ik::branch::{Branch, Elbow, Wrist};

/// The smallest `sin θ5` (UR family) below which the wrist counts as singular: θ6 and
/// θ2 + θ3 + θ4 are then no longer separable.
const WRIST_SINGULAR: f64 = 1e-9;

/// The UR-family closed form (module doc, docs/kinematics.md §9.3) into `raws`.
pub(super) fn ur_family(
    c: &Canonical,
    target: &IsometryMatrix3<f64>,
    seed_theta: &[f64; 6],
    scale: f64,
    raws: &mut Vec<Raw>,
    planar: &mut Vec<Planar>,
) {
    let r = &c.rows;
    // The last row's a and α go into `post`, so that A_6 = Rot_z(θ_6)·Trans_z(d_6).
    let (t, row6) = c.without_last_link(target);
    let (sc1, sc5) = (r[0].alpha_sin_cos(), r[4].alpha_sin_cos());
    let p = t.translation.vector;
    let rot = t.rotation.matrix();
    let z6 = rot.column(2).into_owned();
    let sigma1 = r[0].sigma();
    let sigma4 = r[3].sigma();
    let sigma45 = sigma4 * r[4].sigma();
    let w = p - z6 * r[5].d;
    let d_sum = r[1].d + r[2].d + r[3].d;
    let (t1s, ok1, sing1, free1) = shoulder(w.x, w.y, sigma1, d_sum, seed_theta[0], scale);
    for (s, &t1) in t1s.iter().enumerate() {
        let (t5_plus, sx, sy, wrist_singular) = ur_wrist(rot, t1, sigma1, sigma45);
        let a1_inv = r[0].transform_with(t1, sc1).inverse();
        // The target in frame 1.
        let t1_target = a1_inv * t;
        for (wi, t5) in [t5_plus, -t5_plus].into_iter().enumerate() {
            if wi == 1 && wrist_singular {
                break;
            }
            let a5 = r[4].transform_with(t5, sc5);
            // θ6 and, from it, the frame-4 pose in frame 1: the rotation gives
            // θ2 + θ3 + θ4, the translation the planar 2R's point.
            let frame4 = |t6: f64| {
                let a56 = a5 * row6.transform_with(t6, (0.0, 1.0));
                let t14 = t1_target * a56.inverse();
                let m = t14.rotation.matrix();
                let t234 = atan2(m[(1, 0)], m[(0, 0)]);
                (t14.translation.vector.x, t14.translation.vector.y, t234)
            };
            let reachable = |x: f64, y: f64| {
                let c =
                    (x * x + y * y - r[1].a * r[1].a - r[2].a * r[2].a) / (2.0 * r[1].a * r[2].a);
                c.abs() <= 1.0 + 1e-10
            };
            let t6 = if !wrist_singular {
                // sin θ5 has θ5's sign: θ5 = ±atan2(s5, ·) lies in (−π, π) and is not 0
                // off the singular wrist.
                let k = sigma4 * t5.signum();
                atan2(-k * sy, k * sx)
            } else {
                ur_singular_t6(c, &t1_target, t5, seed_theta[5], &frame4, &reachable)
            };
            let (x, y, t234) = frame4(t6);
            planar.clear();
            planar_2r(x, y, r[1].a, r[2].a, seed_theta[1], planar);
            for pl in planar.iter() {
                let side = sigma1 * front_sign(s);
                let mut raw = Raw::new(
                    [t1, pl.ta, pl.tb, t234 - pl.ta - pl.tb, t5, t6],
                    ur_branch(s, wi, elbow_of(side, r[1].a, r[2].a, pl.sign)),
                );
                raw.exact = pl.exact && ok1;
                raw.singular = pl.singular || sing1 || wrist_singular;
                raw.merged = Merged {
                    shoulder: sing1 && !free1,
                    elbow: pl.singular && !pl.free_a,
                    wrist: wrist_singular,
                };
                raw.free[0] = free1;
                raw.free[1] = pl.free_a;
                raw.free[5] = wrist_singular;
                raws.push(raw);
            }
        }
    }
}

/// The wrist for the base angle `t1` (module doc): the tool's axes read along
/// z_1 = σ_1(sin θ_1, −cos θ_1, 0), the common direction of axes 2–4. Returns θ5 of the
/// wrist not flipped (in [0, π]), `x_6·z_1` and `y_6·z_1` (from which θ6 follows), and
/// whether the wrist is singular (sin θ5 below [`WRIST_SINGULAR`]).
fn ur_wrist(rot: &Matrix3<f64>, t1: f64, sigma1: f64, sigma45: f64) -> (f64, f64, f64, bool) {
    let x6 = rot.column(0).into_owned();
    let y6 = rot.column(1).into_owned();
    let z6 = rot.column(2).into_owned();
    let (s1, c1) = sin_cos(t1);
    let z1 = Vector3::new(s1, -c1, 0.0) * sigma1;
    let cz = z6.dot(&z1);
    let sx = x6.dot(&z1);
    let sy = y6.dot(&z1);
    let s5 = sx.hypot(sy);
    (atan2(s5, -sigma45 * cz), sx, sy, s5 < WRIST_SINGULAR)
}

/// A UR-family branch: shoulder `s` and wrist `wi` (0 not flipped, 1 flipped) by index.
fn ur_branch(s: usize, wi: usize, elbow: Elbow) -> Branch {
    Branch {
        shoulder: Some(shoulder_of(s)),
        elbow: Some(elbow),
        wrist: Some(if wi == 0 {
            Wrist::NotFlipped
        } else {
            Wrist::Flipped
        }),
    }
}

/// θ6 at the singular UR wrist, where it is free: the seed's value when the planar 2R
/// then reaches its point, else the nearest value for which it does (docs/kinematics.md
/// §9.3; [`ur_wrist_free_t6`]), else the seed's.
fn ur_singular_t6(
    c: &Canonical,
    t1_target: &IsometryMatrix3<f64>,
    t5: f64,
    seed6: f64,
    frame4: &dyn Fn(f64) -> (f64, f64, f64),
    reachable: &dyn Fn(f64, f64) -> bool,
) -> f64 {
    let (x, y, _) = frame4(seed6);
    if reachable(x, y) {
        seed6
    } else {
        ur_wrist_free_t6(c, t1_target, t5, seed6, frame4, reachable).unwrap_or(seed6)
    }
}

/// With the UR wrist singular (θ5 = 0 or π), θ2 + θ3 + θ4 = ψ and θ6 trade off: the
/// frame-4 origin o4 then runs on a circle of radius |d5| about a fixed centre C in the
/// arm's plane, `o4(ψ) = C − σ4·d5·(sin ψ, −cos ψ)`. The planar 2R reaches o4 when
/// `|a2| − |a3|| ≤ |o4| ≤ |a2| + |a3|`, i.e. when `sin(ψ − φ_C)` lies between
/// `(|C|² + d5² − R²) / (2σ4·d5·|C|)` for R the largest and the smallest reach. The θ6
/// nearest the seed's among the ends of that range where the 2R is reached (the arm
/// stretched or folded there), or `None` when no ψ reaches.
fn ur_wrist_free_t6(
    c: &Canonical,
    t1_target: &IsometryMatrix3<f64>,
    t5: f64,
    seed6: f64,
    frame4: &dyn Fn(f64) -> (f64, f64, f64),
    reachable: &dyn Fn(f64, f64) -> bool,
) -> Option<f64> {
    let r = &c.rows;
    let sigma4 = r[3].sigma();
    let d5 = r[4].d;
    let (x0, y0, psi0) = frame4(seed6);
    // The centre: o4(ψ0) + σ4·d5·(sin ψ0, −cos ψ0).
    let (sp, cp) = sin_cos(psi0);
    let cx = x0 + sigma4 * d5 * sp;
    let cy = y0 - sigma4 * d5 * cp;
    let c_norm = cx.hypot(cy);
    let b = 2.0 * sigma4 * d5 * c_norm;
    if b.abs() < 1e-300 {
        return None;
    }
    let phi_c = atan2(cy, cx);
    let a2 = r[1].a.abs();
    let a3 = r[2].a.abs();
    // θ6 for a given ψ, read from the rotation: Rot_z(θ6) = (Rot_z(ψ)·Rx(α4)·A5ʳᵒᵗ)ᵀ·R.
    let r_target = t1_target.rotation.matrix();
    let rot_to5 = |psi: f64| {
        let z = Rotation3::from_axis_angle(&Vector3::z_axis(), psi);
        let x4 = Rotation3::from_axis_angle(&Vector3::x_axis(), r[3].alpha);
        let a5 = r[4].transform(t5);
        z.matrix() * x4.matrix() * a5.rotation.matrix()
    };
    let mut best: Option<(f64, f64)> = None;
    for reach in [a2 + a3, (a2 - a3).abs()] {
        let k = (c_norm * c_norm + d5 * d5 - reach * reach) / b;
        if k.abs() > 1.0 + 1e-12 {
            continue;
        }
        let root = asin(k.clamp(-1.0, 1.0));
        for psi in [phi_c + root, phi_c + PI - root] {
            let n = rot_to5(psi).transpose() * r_target;
            let t6 = atan2(n[(1, 0)], n[(0, 0)]);
            let (x, y, _) = frame4(t6);
            if !reachable(x, y) {
                continue;
            }
            let dist = wrap_to_pi(t6 - seed6).abs();
            if best.is_none_or(|(d, _)| dist < d) {
                best = Some((dist, t6));
            }
        }
    }
    best.map(|(_, t6)| t6)
}
