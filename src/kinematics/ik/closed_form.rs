//! Closed-form IK (docs/kinematics.md §9): the planar 2R, the RRR arm and the UR family,
//! derived from the loaded robot's DH table in either convention.
//!
//! Every table is first written as a standard-DH chain `T = pre·A_1⋯A_n·post` with
//! `A_i = Rot_z(θ_i)·Trans_z(d_i)·Trans_x(a_i)·Rot_x(α_i)`, `θ_i = q_i + offset_i`: a
//! modified (Craig) row `(α_{i−1}, a_{i−1}, θ_i, d_i)` becomes the standard row
//! `(θ_i, d_i, a_i, α_i)` (Rot_x and Trans_x commute), with `Rot_x(α_0)·Trans_x(a_0)`
//! moved into `pre`. The family is then recognised from the rows' structure:
//!
//! - planar 2R: two revolute joints with parallel axes (α_1 = 0), tool at frame 2;
//! - RRR: α_1 = ±π/2, a_1 = 0, α_2 = 0 (axes 2 and 3 parallel), tool at frame 3;
//! - UR family: α_1 = ±π/2, a_1 = a_4 = a_5 = 0, α_2 = α_3 = 0 (axes 2–4 parallel),
//!   α_4 = ±π/2, α_5 = ±π/2 (any d's, any signs of a_2, a_3 and the α's, any offsets).
//!
//! UR-family derivation (σ_i = sign sin α_i, z_1 = σ_1(sin θ_1, −cos θ_1, 0) the common
//! direction of axes 2–4, D = d_2 + d_3 + d_4): the wrist point `o_5 = p − d_6·z_6` has
//! `o_5·z_1 = D`, so `θ_1 = φ + asin(σ_1·D/ρ)` or `φ + π − asin(σ_1·D/ρ)` with
//! `(ρ, φ)` the polar form of o_5's x, y; the tool axis gives `z_6·z_1 = −σ_4σ_5·cos θ_5`
//! and `x_6·z_1 = σ_4 sin θ_5 cos θ_6`, `y_6·z_1 = −σ_4 sin θ_5 sin θ_6`, so θ_5 = ±atan2(
//! √((x_6·z_1)² + (y_6·z_1)²), −σ_4σ_5 z_6·z_1) and θ_6 follows; then
//! `A_2A_3A_4 = A_1⁻¹·T·(A_5A_6)⁻¹` is a planar 2R (a_2, a_3) plus θ_2+θ_3+θ_4 read from
//! its rotation. Up to 2 × 2 × 2 = 8 solutions.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::{IsometryMatrix3, Rotation3, Translation3, Vector3};

use super::IkError;
use crate::kinematics::angles::{nearest_equivalent_within, wrap_to_pi};
use crate::kinematics::jacobian::Task;
use crate::kinematics::robot::{Convention, Joint, JointKind, Robot};

/// The arm families with a closed form here.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClosedFormFamily {
    /// Two revolute joints with parallel axes (docs/kinematics.md §9.1): up to two solutions (elbows).
    Planar2R,
    /// Base yaw and a planar 2R above it (docs/kinematics.md §9.2): up to four solutions.
    Rrr,
    /// The Universal Robots geometry (docs/kinematics.md §9.3): up to eight solutions.
    UrFamily,
}

impl ClosedFormFamily {
    /// A short name for the UI and the JSON API.
    pub fn name(self) -> &'static str {
        match self {
            ClosedFormFamily::Planar2R => "planar-2r",
            ClosedFormFamily::Rrr => "rrr",
            ClosedFormFamily::UrFamily => "ur",
        }
    }
}

/// One closed-form solution.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedFormSolution {
    /// The joint vector: each revolute angle as the 2π-equivalent inside the limits
    /// nearest the seed (or nearest the seed when none lies inside).
    pub q: Vec<f64>,
    /// The branch in words ("shoulder front, elbow up").
    pub label: &'static str,
    /// Every joint lies within its limits (solutions outside are marked, not dropped).
    pub within_limits: bool,
    /// The solution sits on a singularity; its free joint took the seed's value.
    pub singular: bool,
    /// The solution reaches the target exactly; `false` for the clamped stand-ins given
    /// when the target is out of reach (then every solution is such a stand-in).
    pub exact: bool,
}

/// All closed-form solutions of one target.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedFormSet {
    /// Which closed form was used.
    pub family: ClosedFormFamily,
    /// The distinct solutions (duplicates at singularities are merged). Never empty.
    pub solutions: Vec<ClosedFormSolution>,
    /// No exact solution exists: `solutions` holds clamped stand-ins (arm stretched or
    /// folded toward the target).
    pub unreachable: bool,
    /// Some solution sits on a singularity.
    pub singular: bool,
}

/// A standard-DH row (the θ offsets stay with the joints).
#[derive(Debug, Clone, Copy, Default)]
struct Row {
    d: f64,
    a: f64,
    alpha: f64,
}

impl Row {
    /// `sin α`, `cos α` once, for [`Row::transform_with`].
    fn alpha_sin_cos(&self) -> (f64, f64) {
        self.alpha.sin_cos()
    }

    /// The standard DH transform `Rot_z(θ)·Trans_z(d)·Trans_x(a)·Rot_x(α)` of this row,
    /// with `sin α`, `cos α` given.
    fn transform_with(&self, theta: f64, (sa, ca): (f64, f64)) -> IsometryMatrix3<f64> {
        let (st, ct) = theta.sin_cos();
        IsometryMatrix3::from_parts(
            Translation3::new(self.a * ct, self.a * st, self.d),
            Rotation3::from_matrix_unchecked(nalgebra::Matrix3::new(
                ct,
                -st * ca,
                st * sa,
                st,
                ct * ca,
                -ct * sa,
                0.0,
                sa,
                ca,
            )),
        )
    }
}

/// `T = pre·A_1⋯A_n·post` in standard DH (see the module doc).
#[derive(Debug, Clone)]
struct Canonical {
    pre: IsometryMatrix3<f64>,
    post: IsometryMatrix3<f64>,
    rows: [Row; 6],
    n: usize,
}

fn rot_x_trans_x(alpha: f64, a: f64) -> IsometryMatrix3<f64> {
    IsometryMatrix3::from_parts(
        Translation3::new(a, 0.0, 0.0),
        Rotation3::from_axis_angle(&Vector3::x_axis(), alpha),
    )
}

fn canonical(robot: &Robot) -> Option<Canonical> {
    let n = robot.dof();
    if n > 6 || robot.joints.iter().any(|j| j.kind != JointKind::Revolute) {
        return None;
    }
    let mut rows = [Row::default(); 6];
    let pre;
    match robot.convention {
        Convention::Standard => {
            pre = robot.world_from_base;
            for (row, j) in rows.iter_mut().zip(&robot.joints) {
                *row = Row {
                    d: j.dh.d,
                    a: j.dh.a,
                    alpha: j.dh.alpha,
                };
            }
        }
        Convention::Modified => {
            let first = robot.joints.first()?.dh;
            pre = robot.world_from_base * rot_x_trans_x(first.alpha, first.a);
            for (i, (row, joint)) in rows.iter_mut().zip(&robot.joints).enumerate() {
                let (a, alpha) = match robot.joints.get(i + 1) {
                    Some(next) => (next.dh.a, next.dh.alpha),
                    None => (0.0, 0.0),
                };
                *row = Row {
                    d: joint.dh.d,
                    a,
                    alpha,
                };
            }
        }
    }
    Some(Canonical {
        pre,
        post: robot.flange_from_tool,
        rows,
        n,
    })
}

fn angle_is(x: f64, y: f64) -> bool {
    wrap_to_pi(x - y).abs() < 1e-9
}

fn quarter_turn(alpha: f64) -> bool {
    alpha.cos().abs() < 1e-9
}

/// Which closed form the robot has, if any.
pub fn closed_form_family(robot: &Robot) -> Option<ClosedFormFamily> {
    detect(robot).map(|(family, ..)| family)
}

/// The family, the canonical chain and the reach.
fn detect(robot: &Robot) -> Option<(ClosedFormFamily, Canonical, f64)> {
    let c = canonical(robot)?;
    let reach = robot.reach();
    let family = family_of(&c, reach)?;
    Some((family, c, reach))
}

fn family_of(c: &Canonical, reach: f64) -> Option<ClosedFormFamily> {
    let tiny = 1e-12 * reach;
    let r = &c.rows;
    let tool_at_frame = c.post.translation.vector.norm() <= tiny;
    match c.n {
        2 if angle_is(r[0].alpha, 0.0)
            && r[0].a.abs() > tiny
            && r[1].a.abs() > tiny
            && tool_at_frame =>
        {
            Some(ClosedFormFamily::Planar2R)
        }
        3 if quarter_turn(r[0].alpha)
            && r[0].a.abs() <= tiny
            && angle_is(r[1].alpha, 0.0)
            && r[1].a.abs() > tiny
            && r[2].a.abs() > tiny
            && tool_at_frame =>
        {
            Some(ClosedFormFamily::Rrr)
        }
        6 if quarter_turn(r[0].alpha)
            && r[0].a.abs() <= tiny
            && angle_is(r[1].alpha, 0.0)
            && angle_is(r[2].alpha, 0.0)
            && r[1].a.abs() > tiny
            && r[2].a.abs() > tiny
            && quarter_turn(r[3].alpha)
            && r[3].a.abs() <= tiny
            && quarter_turn(r[4].alpha)
            && r[4].a.abs() <= tiny =>
        {
            Some(ClosedFormFamily::UrFamily)
        }
        _ => None,
    }
}

/// The joint value for the DH angle `theta` of `joint`, as the 2π-equivalent inside the
/// limits nearest `seed`, and whether one lies inside.
fn represent(joint: &Joint, theta: f64, seed: f64) -> (f64, bool) {
    let value = theta - joint.dh.theta;
    if joint.wraps() {
        return (wrap_to_pi(value), true);
    }
    let near = seed + wrap_to_pi(value - seed);
    if joint.limits.contains(near, 0.0) {
        // The equivalent nearest the seed lies inside: it is the answer.
        return (near, true);
    }
    let kept = nearest_equivalent_within(near, seed, &joint.limits);
    if wrap_to_pi(kept - near).abs() < 1e-9 {
        (kept, true)
    } else {
        (near, false)
    }
}

/// A planar 2R branch: (θ_a, θ_b, exact, singular).
type Planar = (f64, f64, bool, bool);

/// Planar 2R by the law of cosines (docs/kinematics.md §9.1): `c_b = (x² + y² − a1² − a2²)/(2·a1·a2)`,
/// `θ_b = ±acos(c_b)`, `θ_a = atan2(y, x) − atan2(a2·s_b, a1 + a2·c_b)`. Out of reach, c_b
/// is clamped (arm stretched or folded toward the point, `exact` false). Stretched or
/// folded, the two branches coincide (one returned, `singular`); at the origin of an
/// arm with equal links θ_a is free and takes `seed_a`.
fn planar_2r(x: f64, y: f64, a1: f64, a2: f64, seed_a: f64, out: &mut Vec<Planar>) {
    let r2 = x * x + y * y;
    let c_raw = (r2 - a1 * a1 - a2 * a2) / (2.0 * a1 * a2);
    let exact = c_raw.abs() <= 1.0 + 1e-10;
    let c = c_raw.clamp(-1.0, 1.0);
    let s = (1.0 - c * c).max(0.0).sqrt();
    let singular = s < 1e-7;
    let scale = a1.abs() + a2.abs();
    for sign in [1.0, -1.0] {
        let sb = sign * s;
        let tb = sb.atan2(c);
        let kx = a1 + a2 * c;
        let ky = a2 * sb;
        let ta = if r2.sqrt() <= 1e-12 * scale && kx.hypot(ky) <= 1e-12 * scale {
            seed_a
        } else {
            y.atan2(x) - ky.atan2(kx)
        };
        out.push((ta, tb, exact, singular));
        if singular {
            // The two elbows coincide (to 1e−7 rad): one solution.
            break;
        }
    }
}

/// The two base angles that put a point (x, y) at distance `d_sum` along
/// z_1 = σ_1(sin θ, −cos θ, 0): `σ_1(x sin θ − y cos θ) = D`. Returns
/// ([θ, θ'], exact, singular); on the base axis with D = 0 the angle is free (the seed's
/// and the seed's + π).
fn shoulder(
    x: f64,
    y: f64,
    sigma1: f64,
    d_sum: f64,
    seed: f64,
    scale: f64,
) -> ([f64; 2], bool, bool) {
    let rho = x.hypot(y);
    if rho <= 1e-12 * scale && d_sum.abs() <= 1e-12 * scale {
        return ([seed, seed + PI], true, true);
    }
    let phi = y.atan2(x);
    let ratio = if rho > 0.0 {
        sigma1 * d_sum / rho
    } else {
        sigma1 * d_sum.signum() * 2.0
    };
    let exact = ratio.abs() <= 1.0 + 1e-10;
    let ratio = ratio.clamp(-1.0, 1.0);
    let t = ratio.asin();
    let singular = (1.0 - ratio.abs()) < 1e-12 || rho <= 1e-9 * scale;
    ([phi + t, phi + PI - t], exact, singular)
}

const RRR_LABELS: [&str; 4] = [
    "shoulder front, elbow down",
    "shoulder front, elbow up",
    "shoulder back, elbow down",
    "shoulder back, elbow up",
];

const UR_LABELS: [&str; 8] = [
    "shoulder 1, wrist +, elbow +",
    "shoulder 1, wrist +, elbow −",
    "shoulder 1, wrist −, elbow +",
    "shoulder 1, wrist −, elbow −",
    "shoulder 2, wrist +, elbow +",
    "shoulder 2, wrist +, elbow −",
    "shoulder 2, wrist −, elbow +",
    "shoulder 2, wrist −, elbow −",
];

/// A raw solution: DH angles θ_i (offsets included), label, exact, singular.
struct Raw {
    theta: [f64; 6],
    label: &'static str,
    exact: bool,
    singular: bool,
}

/// Every closed-form solution of `target` (the tool pose in the world frame). `seed`
/// chooses each angle's 2π-equivalent (nearest it, inside the limits) and the value of a
/// free joint at a singularity. 2R and RRR solve the tool position (their orientation
/// follows from it); the UR family solves the full pose.
pub fn closed_form_solutions(
    robot: &Robot,
    target: &IsometryMatrix3<f64>,
    seed: &[f64],
) -> Result<ClosedFormSet, IkError> {
    robot.check_q(seed)?;
    let (family, c, scale) =
        detect(robot).ok_or_else(|| IkError::NoClosedForm(robot.name.clone()))?;
    // DH angles of the seed (offsets included), for free joints.
    let mut seed_theta = [0.0; 6];
    for (i, j) in robot.joints.iter().enumerate() {
        seed_theta[i] = seed[i] + j.dh.theta;
    }
    let mut raws: Vec<Raw> = Vec::with_capacity(8);
    let mut planar: Vec<Planar> = Vec::with_capacity(2);
    let r = &c.rows;
    match family {
        ClosedFormFamily::Planar2R => {
            let p = c
                .pre
                .inverse_transform_point(&target.translation.vector.into());
            planar_2r(p.x, p.y, r[0].a, r[1].a, seed_theta[0], &mut planar);
            let in_plane = (p.z - r[0].d - r[1].d).abs() <= 1e-9 * scale;
            for (k, &(t1, t2, exact, singular)) in planar.iter().enumerate() {
                raws.push(Raw {
                    theta: [t1, t2, 0.0, 0.0, 0.0, 0.0],
                    label: ["elbow down", "elbow up"][k],
                    exact: exact && in_plane,
                    singular,
                });
            }
        }
        ClosedFormFamily::Rrr => {
            let p = c
                .pre
                .inverse_transform_point(&target.translation.vector.into());
            let sigma1 = r[0].alpha.sin().signum();
            let w = Vector3::new(p.x, p.y, p.z - r[0].d);
            let d_sum = r[1].d + r[2].d;
            let (t1s, ok1, sing1) = shoulder(w.x, w.y, sigma1, d_sum, seed_theta[0], scale);
            for (s, &t1) in t1s.iter().enumerate() {
                let (s1, c1) = t1.sin_cos();
                let x = w.x * c1 + w.y * s1;
                let y = sigma1 * w.z;
                planar.clear();
                planar_2r(x, y, r[1].a, r[2].a, seed_theta[1], &mut planar);
                for (k, &(t2, t3, exact, singular)) in planar.iter().enumerate() {
                    raws.push(Raw {
                        theta: [t1, t2, t3, 0.0, 0.0, 0.0],
                        label: RRR_LABELS[2 * s + k],
                        exact: exact && ok1,
                        singular: singular || sing1,
                    });
                }
            }
        }
        ClosedFormFamily::UrFamily => {
            ur_family(&c, target, &seed_theta, scale, &mut raws, &mut planar);
        }
    }
    let any_exact = raws.iter().any(|s| s.exact);
    let mut solutions: Vec<ClosedFormSolution> = Vec::with_capacity(raws.len());
    for raw in raws.iter().filter(|s| s.exact == any_exact) {
        let mut q = Vec::with_capacity(c.n);
        let mut inside = true;
        for (i, joint) in robot.joints.iter().enumerate() {
            let (v, ok) = represent(joint, raw.theta[i], seed[i]);
            inside &= ok;
            q.push(v);
        }
        // Branches coincide only at singularities.
        let duplicate = raw.singular
            && solutions.iter().any(|s| {
                s.q.iter()
                    .zip(&q)
                    .all(|(a, b)| wrap_to_pi(a - b).abs() < 1e-9)
            });
        if !duplicate {
            solutions.push(ClosedFormSolution {
                q,
                label: raw.label,
                within_limits: inside,
                singular: raw.singular,
                exact: raw.exact,
            });
        }
    }
    let singular = solutions.iter().any(|s| s.singular);
    Ok(ClosedFormSet {
        family,
        solutions,
        unreachable: !any_exact,
        singular,
    })
}

/// The UR-family closed form (module doc) into `raws`.
fn ur_family(
    c: &Canonical,
    target: &IsometryMatrix3<f64>,
    seed_theta: &[f64; 6],
    scale: f64,
    raws: &mut Vec<Raw>,
    planar: &mut Vec<Planar>,
) {
    let r = &c.rows;
    // The last row's a and α go into `post`, so that A_6 = Rot_z(θ_6)·Trans_z(d_6).
    let post = rot_x_trans_x(r[5].alpha, r[5].a) * c.post;
    let row6 = Row {
        a: 0.0,
        alpha: 0.0,
        ..r[5]
    };
    let (sc1, sc5) = (r[0].alpha_sin_cos(), r[4].alpha_sin_cos());
    let t = c.pre.inverse() * target * post.inverse();
    let p = t.translation.vector;
    let rot = t.rotation.matrix();
    let x6 = rot.column(0).into_owned();
    let y6 = rot.column(1).into_owned();
    let z6 = rot.column(2).into_owned();
    let sigma1 = r[0].alpha.sin().signum();
    let sigma45 = r[3].alpha.sin().signum() * r[4].alpha.sin().signum();
    let sigma4 = r[3].alpha.sin().signum();
    let w = p - z6 * r[5].d;
    let d_sum = r[1].d + r[2].d + r[3].d;
    let (t1s, ok1, sing1) = shoulder(w.x, w.y, sigma1, d_sum, seed_theta[0], scale);
    for (s, &t1) in t1s.iter().enumerate() {
        let (s1, c1) = t1.sin_cos();
        let z1 = Vector3::new(s1, -c1, 0.0) * sigma1;
        let cz = z6.dot(&z1);
        let sx = x6.dot(&z1);
        let sy = y6.dot(&z1);
        let s5 = sx.hypot(sy);
        let wrist_singular = s5 < 1e-9;
        let t5_plus = s5.atan2(-sigma45 * cz);
        let a1_inv = r[0].transform_with(t1, sc1).inverse();
        for (wi, t5) in [t5_plus, -t5_plus].into_iter().enumerate() {
            if wi == 1 && s5 == 0.0 {
                break;
            }
            let sin5 = t5.sin();
            let t6 = if s5 > 1e-12 {
                let k = sigma4 * sin5.signum();
                (-k * sy).atan2(k * sx)
            } else {
                seed_theta[5]
            };
            let a56 = r[4].transform_with(t5, sc5) * row6.transform_with(t6, (0.0, 1.0));
            let t14 = a1_inv * t * a56.inverse();
            let x = t14.translation.vector.x;
            let y = t14.translation.vector.y;
            let m = t14.rotation.matrix();
            let t234 = m[(1, 0)].atan2(m[(0, 0)]);
            planar.clear();
            planar_2r(x, y, r[1].a, r[2].a, seed_theta[1], planar);
            for (k, &(t2, t3, exact, singular)) in planar.iter().enumerate() {
                raws.push(Raw {
                    theta: [t1, t2, t3, t234 - t2 - t3, t5, t6],
                    label: UR_LABELS[4 * s + 2 * wi + k],
                    exact: exact && ok1,
                    singular: singular || sing1 || wrist_singular,
                });
            }
        }
    }
}

/// The pose the closed form should solve for `task`: 2R and RRR solve positions, so the
/// target is used as it is; a 6R arm needs a whole pose, so the orientation the task
/// leaves free is held at the seed's (position only: the seed's rotation; 5D: the
/// seed's rotation turned by the least rotation that brings its tool axis onto the
/// target's).
pub(crate) fn target_for_task(
    robot: &Robot,
    family: ClosedFormFamily,
    target: &IsometryMatrix3<f64>,
    task: Task,
    seed: &[f64],
) -> IsometryMatrix3<f64> {
    if family != ClosedFormFamily::UrFamily {
        return *target;
    }
    let current = crate::kinematics::fk::tool_pose(robot, seed);
    let rotation = match task {
        Task::FullPose => return *target,
        Task::Position => current.rotation,
        Task::PositionAndAxis(axis) => {
            let k = axis.index();
            let a = current.rotation.matrix().column(k).into_owned();
            let b = target.rotation.matrix().column(k).into_owned();
            let cross = a.cross(&b);
            let s = cross.norm();
            let angle = s.atan2(a.dot(&b));
            let turn = if s > 1e-12 {
                Rotation3::new(cross * (angle / s))
            } else if angle > FRAC_PI_2 {
                let u = current.rotation.matrix().column((k + 1) % 3).into_owned();
                Rotation3::new(u * angle)
            } else {
                Rotation3::identity()
            };
            turn * current.rotation
        }
    };
    IsometryMatrix3::from_parts(target.translation, rotation)
}
