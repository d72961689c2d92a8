//! Pieper's case (docs/kinematics.md §9.5): six joints whose last three axes meet in one
//! point (a spherical wrist: a4 = a5 = 0, d5 = 0, α4, α5 = ±π/2). The wrist centre
//! `c = p − d6·z6` depends on the first three joints only, which are solved for it; the
//! wrist then solves the orientation `R_03ᵀ·R`.
//!
//! The first three joints: base yaw (α1 = ±π/2, a1 = 0) and either
//! - an elbow (Puma 560): joint 3 revolute, axes 2 and 3 parallel (α2 = 0); the wrist
//!   centre sits at `(a3, −sin α3·d4)` turned by θ3 in frame 2, so joints 2–3 are a
//!   planar 2R with links a2 and `L = √(a3² + (sin α3·d4)²)`, `θ_b = θ3 + β`,
//!   `β = atan2(−sin α3·d4, a3)`; the offset along z1 is `D = d2 + d3 + cos α3·d4`;
//! - a boom (Stanford arm): joint 3 prismatic, α2 = ±π/2, α3 = 0; in frame 1 the wrist
//!   centre is `Rot_z(θ2)·(k, −σ2·(d3 + d4))` with `k = a2 + a3·cos θ3⁰`, so
//!   `(d3 + d4)² = ρ1² − k²` and θ2 follows; the offset is `D = d2 + σ2·a3·sin θ3⁰`.

use crate::angles::{atan2, sin_cos};
use nalgebra::{IsometryMatrix3, Matrix3, Vector3};

use super::canonical::{Canonical, Row, parallel, quarter_turn};
use super::planar::{Planar, elbow_of, front_sign, planar_2r, shoulder, shoulder_of};
use super::raw::{Merged, Raw};
use crate::ik::branch::{Branch, Wrist};
use crate::robot::{Joint, Robot};

/// The first three joints' structure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PositionKind {
    /// Revolute joint 3 parallel to joint 2 (Puma).
    Elbow,
    /// Prismatic joint 3 (Stanford).
    Boom,
}

/// The structure of rows 2–3, if it is one of the two solved here.
pub(super) fn position_kind(r: &[Row; 6], tiny: f64) -> Option<PositionKind> {
    if r[1].prismatic {
        return None;
    }
    if !r[2].prismatic
        && parallel(r[1].alpha)
        && r[1].alpha_sin_cos().1 > 0.0
        && r[1].a.abs() > tiny
        && r[2].a.hypot(r[2].alpha_sin_cos().0 * r[3].d) > tiny
    {
        return Some(PositionKind::Elbow);
    }
    if r[2].prismatic
        && quarter_turn(r[1].alpha)
        && parallel(r[2].alpha)
        && r[2].alpha_sin_cos().1 > 0.0
    {
        return Some(PositionKind::Boom);
    }
    None
}

/// One solution of the first three joints.
struct Arm {
    /// θ2.
    t2: f64,
    /// Joint 3's DH variable (θ3, or the stroke d3).
    v3: f64,
    /// The elbow (none for a boom).
    elbow: Option<crate::ik::branch::Elbow>,
    /// The wrist centre is reached.
    exact: bool,
    /// Elbow stretched or folded (or the boom through the wrist centre).
    singular: bool,
    /// Both elbows coincide here.
    merged_elbow: bool,
    /// θ2 is free (took the seed's value).
    free_t2: bool,
}

/// The wrist's singular threshold on sin θ5.
const WRIST_SINGULAR: f64 = 1e-10;

/// All solutions into `raws` (see the module doc).
pub(super) fn solve(
    c: &Canonical,
    robot: &Robot,
    target: &IsometryMatrix3<f64>,
    seed_theta: &[f64; 6],
    scale: f64,
    raws: &mut Vec<Raw>,
    planar: &mut Vec<Planar>,
) {
    let r = &c.rows;
    let tiny = 1e-12 * scale;
    let Some(kind) = position_kind(r, tiny) else {
        return;
    };
    let (t, row6) = c.without_last_link(target);
    let rot = *t.rotation.matrix();
    let z6 = rot.column(2).into_owned();
    let centre = t.translation.vector - z6 * row6.d;
    let w = Vector3::new(centre.x, centre.y, centre.z - r[0].d);
    let sigma1 = r[0].sigma();
    // sin α₂, cos α₂ once: the elbow's offset along z and its link in the arm's plane.
    let (sa2, ca2) = r[2].alpha_sin_cos();
    let d_sum = match kind {
        PositionKind::Elbow => r[1].d + r[2].d + ca2 * r[3].d,
        PositionKind::Boom => r[1].d + r[1].sigma() * r[2].a * sin_cos(r[2].theta0).0,
    };
    let (t1s, ok1, sing1, free1) = shoulder(w.x, w.y, sigma1, d_sum, seed_theta[0], scale);
    for (s, &t1) in t1s.iter().enumerate() {
        let (s1, c1) = sin_cos(t1);
        let x1 = w.x * c1 + w.y * s1;
        let y1 = sigma1 * w.z;
        let mut arms: Vec<Arm> = Vec::with_capacity(2);
        match kind {
            PositionKind::Elbow => {
                let side = sigma1 * front_sign(s);
                elbow_arms(r, sa2, (x1, y1), side, seed_theta[1], planar, &mut arms);
            }
            PositionKind::Boom => {
                boom_arms(r, &robot.joints[2], (x1, y1), scale, &mut arms);
            }
        }
        let base = Base {
            index: s,
            t1,
            exact: ok1,
            singular: sing1,
            free: free1,
        };
        for arm in arms {
            wrist_solutions(c, &rot, seed_theta[3], &base, arm, raws);
        }
    }
}

/// The elbow's arms (joints 2–3 a planar 2R) reaching `(x1, y1)` in frame 1, on `side`.
fn elbow_arms(
    r: &[Row; 6],
    sa2: f64,
    (x1, y1): (f64, f64),
    side: f64,
    seed2: f64,
    planar: &mut Vec<Planar>,
    arms: &mut Vec<Arm>,
) {
    let ux = r[2].a;
    let uy = -sa2 * r[3].d;
    let len = ux.hypot(uy);
    let beta = atan2(uy, ux);
    planar.clear();
    planar_2r(x1, y1, r[1].a, len, seed2, planar);
    for pl in planar.iter() {
        arms.push(Arm {
            t2: pl.ta,
            v3: pl.tb - beta,
            elbow: Some(elbow_of(side, r[1].a, len, pl.sign)),
            exact: pl.exact,
            singular: pl.singular,
            merged_elbow: pl.singular && !pl.free_a,
            free_t2: pl.free_a,
        });
    }
}

/// The boom's arms (θ2 and the stroke d3 of `joint`) reaching `(x1, y1)` in frame 1.
fn boom_arms(r: &[Row; 6], joint: &Joint, (x1, y1): (f64, f64), scale: f64, arms: &mut Vec<Arm>) {
    let k = r[1].a + r[2].a * sin_cos(r[2].theta0).1;
    let rho2 = x1 * x1 + y1 * y1;
    let e2 = rho2 - k * k;
    let exact = e2 >= -1e-10 * scale * scale;
    let e = e2.max(0.0).sqrt();
    let singular = e <= 1e-9 * scale;
    let sigma2 = r[1].sigma();
    // The stroke d3 = ±e − d4: the roots inside the limits, else the longer.
    let mut roots: Vec<f64> = [e, -e]
        .iter()
        .map(|ev| ev - r[3].d)
        .filter(|d3| joint.limits.contains(d3 - joint.dh.d, 1e-9))
        .collect();
    if roots.is_empty() {
        roots.push(e - r[3].d);
    }
    if singular {
        roots.truncate(1);
    }
    for d3 in roots {
        // θ2 turns v = (k, −σ2·(d3 + d4)) onto the point (x1, y1).
        let vy = -sigma2 * (d3 + r[3].d);
        let t2 = atan2(y1, x1) - atan2(vy, k);
        arms.push(Arm {
            t2,
            v3: d3,
            elbow: None,
            exact,
            singular,
            merged_elbow: false,
            free_t2: false,
        });
    }
}

/// One base angle θ1 of [`shoulder`]: which of its two, and what `shoulder` said of it.
struct Base {
    /// 0 or 1 (the shoulder branch).
    index: usize,
    t1: f64,
    exact: bool,
    singular: bool,
    /// θ1 is free (took the seed's value).
    free: bool,
}

/// The wrist's solutions for the target rotation `rot` on `base` and `arm`, into `raws`.
fn wrist_solutions(
    c: &Canonical,
    rot: &Matrix3<f64>,
    seed4: f64,
    base: &Base,
    arm: Arm,
    raws: &mut Vec<Raw>,
) {
    let r = &c.rows;
    let Arm {
        t2,
        v3,
        elbow,
        exact: ok2,
        singular: sing2,
        merged_elbow,
        free_t2: free2,
    } = arm;
    let t1 = base.t1;
    let r03 = r[0].transform(t1) * r[1].transform(t2) * r[2].transform(v3);
    let m = r03.rotation.matrix().transpose() * rot;
    wrist(
        c,
        [t1, t2, v3],
        &m,
        seed4,
        |wrist_branch, theta, wrist_singular, free4| {
            let branch = Branch {
                shoulder: Some(shoulder_of(base.index)),
                elbow,
                wrist: Some(wrist_branch),
            };
            let mut raw = Raw::new(theta, branch);
            raw.exact = base.exact && ok2;
            raw.singular = base.singular || sing2 || wrist_singular;
            raw.merged = Merged {
                shoulder: base.singular && !base.free,
                elbow: merged_elbow,
                wrist: wrist_singular,
            };
            raw.free[0] = base.free;
            raw.free[1] = free2;
            raw.free[3] = free4;
            raws.push(raw);
        },
    );
}

/// The spherical wrist: `M = R_03ᵀ·R = Rot_z(θ4)·Rot_x(α4)·Rot_z(θ5)·Rot_x(α5)·Rot_z(θ6)`,
/// whose third column is `(σ5 s5 c4, σ5 s5 s4, −σ4σ5 c5)`: θ5 = ±atan2(s5, −σ4σ5·m33)
/// with s5 = √(m13² + m23²), θ4 = atan2(σ5·m23, σ5·m13) (+π when flipped), and θ6 from
/// `(R_03·R_34·R_45)ᵀ·R = Rot_z(θ6)`. At s5 = 0 θ4 is free (the seed's) and only θ4 ± θ6
/// is fixed.
fn wrist(
    c: &Canonical,
    first: [f64; 3],
    m: &nalgebra::Matrix3<f64>,
    seed4: f64,
    mut emit: impl FnMut(Wrist, [f64; 6], bool, bool),
) {
    let r = &c.rows;
    let (sigma4, sigma5) = (r[3].sigma(), r[4].sigma());
    let s5 = m[(0, 2)].hypot(m[(1, 2)]);
    let singular = s5 < WRIST_SINGULAR;
    let t5_plus = atan2(s5, -sigma4 * sigma5 * m[(2, 2)]);
    let t4_plus = if singular {
        seed4
    } else {
        atan2(sigma5 * m[(1, 2)], sigma5 * m[(0, 2)])
    };
    for (wi, (t4, t5)) in [
        (t4_plus, t5_plus),
        (t4_plus + std::f64::consts::PI, -t5_plus),
    ]
    .into_iter()
    .enumerate()
    {
        if wi == 1 && singular {
            break;
        }
        let r45 = r[3].transform(t4).rotation * r[4].transform(t5).rotation;
        let n = r45.matrix().transpose() * m;
        let t6 = atan2(n[(1, 0)], n[(0, 0)]);
        let branch = if wi == 0 {
            Wrist::NotFlipped
        } else {
            Wrist::Flipped
        };
        emit(
            branch,
            [first[0], first[1], first[2], t4, t5, t6],
            singular,
            singular,
        );
    }
}
