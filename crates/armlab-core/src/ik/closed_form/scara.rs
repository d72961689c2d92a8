//! The SCARA closed form (docs/kinematics.md §9.4): revolute, revolute, prismatic,
//! revolute, every axis parallel (α ∈ {0, π}), the prismatic row without a link length.

use crate::angles::atan2;
use nalgebra::IsometryMatrix3;

use super::canonical::Canonical;
use super::planar::{Planar, elbow_of, planar_2r};
use super::raw::Raw;
use crate::ik::branch::Branch;

/// Solves position and yaw. With `c_i = cos α_i` (±1) the frame-4 origin (the last
/// row's a and α moved into the tool transform) is
///
/// ```text
/// x, y = a1·(cos θ1, sin θ1) + a2·(cos(θ1 + c1θ2), sin(θ1 + c1θ2))   (a planar 2R)
/// z    = d1 + c1·(d2 + c2·(d3 + c3·d4))                               (d3 the stroke)
/// ```
///
/// and `R = Rot_z(θ1 + c1θ2 + c1c2θ3⁰ + c1c2c3θ4)·Rot_x(α1 + α2 + α3)`: θ4 is read from
/// `R_03ᵀ·R = Rot_z(θ4)`. A target whose tool axis is not along the joint axes is not
/// reached exactly (the clamped stand-in keeps the yaw).
pub(super) fn solve(
    c: &Canonical,
    target: &IsometryMatrix3<f64>,
    seed_theta: &[f64; 6],
    raws: &mut Vec<Raw>,
    planar: &mut Vec<Planar>,
) {
    let r = &c.rows;
    let (t, row4) = c.without_last_link(target);
    let p = t.translation.vector;
    let [c1, c2, c3] = [0, 1, 2].map(|i| r[i].alpha_sin_cos().1);
    // The stroke variable (d3 with its offset) from the height.
    let d3 = (p.z - r[0].d - c1 * r[1].d) / (c1 * c2) - c3 * row4.d;
    planar_2r(p.x, p.y, r[0].a, r[1].a, seed_theta[0], planar);
    for pl in planar.iter() {
        let t2 = c1 * pl.tb;
        let r03 = r[0].transform(pl.ta) * r[1].transform(t2) * r[2].transform(d3);
        let n = r03.rotation.matrix().transpose() * t.rotation.matrix();
        let t4 = atan2(n[(1, 0)], n[(0, 0)]);
        let vertical = (n[(2, 2)] - 1.0).abs() <= 1e-9;
        let branch = Branch {
            elbow: Some(elbow_of(1.0, r[0].a, r[1].a, pl.sign)),
            ..Branch::default()
        };
        let mut raw = Raw::new([pl.ta, t2, d3, t4, 0.0, 0.0], branch);
        raw.exact = pl.exact && vertical && d3.is_finite();
        raw.singular = pl.singular;
        raw.merged.elbow = pl.singular && !pl.free_a;
        raw.free[0] = pl.free_a;
        raws.push(raw);
    }
}
