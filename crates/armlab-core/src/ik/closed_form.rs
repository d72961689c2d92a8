//! Closed-form IK (docs/kinematics.md §9): the planar 2R, the RRR arm, the UR family, the
//! SCARA and Pieper's spherical-wrist arms (Puma 560, Stanford arm), derived from the
//! loaded robot's DH table in either convention, every branch labelled ([`Branch`]).
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

use crate::angles::{asin, atan2, sin_cos};
use nalgebra::{IsometryMatrix3, Rotation3, Translation3, Vector3};

mod pieper;
mod scara;

use super::IkError;
use super::branch::{Branch, Elbow, Shoulder, Wrist};
use crate::angles::wrap_to_pi;
use crate::jacobian::Task;
use crate::robot::nearest_equivalent_within;
use crate::robot::{Convention, Joint, JointKind, Robot};

/// The arm families with a closed form here.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClosedFormFamily {
    /// Two revolute joints with parallel axes (docs/kinematics.md §9.1): up to two solutions (elbows).
    Planar2R,
    /// Base yaw and a planar 2R above it (docs/kinematics.md §9.2): up to four solutions.
    Rrr,
    /// The Universal Robots geometry (docs/kinematics.md §9.3): up to eight solutions.
    UrFamily,
    /// Two parallel revolute joints, a prismatic joint and a roll, every axis parallel
    /// (docs/kinematics.md §9.4): up to two solutions (elbows).
    Scara,
    /// Pieper's case: a spherical wrist on a Puma-like (revolute elbow) or Stanford-like
    /// (prismatic boom) arm (docs/kinematics.md §9.5): up to eight solutions.
    SphericalWrist,
}

impl ClosedFormFamily {
    /// A short name for the UI and the JSON API.
    pub fn name(self) -> &'static str {
        match self {
            ClosedFormFamily::Planar2R => "planar-2r",
            ClosedFormFamily::Rrr => "rrr",
            ClosedFormFamily::UrFamily => "ur",
            ClosedFormFamily::Scara => "scara",
            ClosedFormFamily::SphericalWrist => "spherical-wrist",
        }
    }

    /// Whether the family solves a whole pose (the 6-axis families and the SCARA's
    /// position and yaw) rather than a position (2R, RRR).
    pub fn solves_pose(self) -> bool {
        matches!(
            self,
            ClosedFormFamily::UrFamily | ClosedFormFamily::Scara | ClosedFormFamily::SphericalWrist
        )
    }
}

/// One closed-form solution.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedFormSolution {
    /// The joint vector: each revolute angle as the 2π-equivalent inside the limits
    /// nearest the seed (or nearest the seed when none lies inside).
    pub q: Vec<f64>,
    /// The branch as data.
    pub branch: Branch,
    /// Other branches that coincide with this solution at a singularity (the elbow
    /// stretched: both elbows; the wrist at θ5 = 0: both wrists): a drag that asked for
    /// one of them keeps it through the singularity.
    pub coincident: Vec<Branch>,
    /// The joints (indices from 0) the target leaves free here (a continuum of
    /// solutions): their value was chosen — the seed's, or the nearest value for which
    /// the rest of the chain reaches the target — and the other joints follow from it.
    pub free_joints: Vec<usize>,
    /// Every joint lies within its limits (solutions outside are marked, not dropped).
    pub within_limits: bool,
    /// The solution sits on a singularity (branches coincide or a joint is free).
    pub singular: bool,
    /// The solution reaches the target exactly; `false` for the clamped stand-ins given
    /// when the target is out of reach (then every solution is such a stand-in).
    pub exact: bool,
}

impl ClosedFormSolution {
    /// The branch as an id ([`Branch::id`], `"right-up-noflip"`), for the JSON API and
    /// the solutions list. Written when asked for: a drag frame solves every branch but
    /// names none.
    pub fn label(&self) -> String {
        self.branch.id()
    }
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

/// A standard-DH row: the constant parts; the joint variable is θ (revolute, the
/// offset `theta0` included in it) or d (prismatic, the offset `d` included in it).
#[derive(Debug, Clone, Copy, Default)]
struct Row {
    d: f64,
    a: f64,
    alpha: f64,
    /// The fixed θ of a prismatic row.
    theta0: f64,
    prismatic: bool,
}

impl Row {
    /// `sin α`, `cos α` once, for [`Row::transform_with`].
    fn alpha_sin_cos(&self) -> (f64, f64) {
        sin_cos(self.alpha)
    }

    /// The standard DH transform `Rot_z(θ)·Trans_z(d)·Trans_x(a)·Rot_x(α)` of this row
    /// for the joint variable `var` (θ, or d for a prismatic row), with `sin α`, `cos α`
    /// given.
    fn transform_with(&self, var: f64, (sa, ca): (f64, f64)) -> IsometryMatrix3<f64> {
        let (theta, d) = if self.prismatic {
            (self.theta0, var)
        } else {
            (var, self.d)
        };
        let (st, ct) = sin_cos(theta);
        IsometryMatrix3::from_parts(
            Translation3::new(self.a * ct, self.a * st, d),
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

    /// [`Row::transform_with`] computing `sin α`, `cos α`.
    fn transform(&self, var: f64) -> IsometryMatrix3<f64> {
        self.transform_with(var, self.alpha_sin_cos())
    }

    /// σ = the sign of sin α (for quarter-turn rows).
    fn sigma(&self) -> f64 {
        sin_cos(self.alpha).0.signum()
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

impl Canonical {
    /// The pose `pre⁻¹·target·post'⁻¹` with the last row's `a` and `α` moved into `post'`,
    /// so that the last link is `Rot_z(θ_n)·Trans_z(d_n)` (or `Trans_z(d_n)` prismatic).
    fn without_last_link(&self, target: &IsometryMatrix3<f64>) -> (IsometryMatrix3<f64>, Row) {
        let last = self.rows[self.n - 1];
        let post = rot_x_trans_x(last.alpha, last.a) * self.post;
        let row = Row {
            a: 0.0,
            alpha: 0.0,
            ..last
        };
        (self.pre.inverse() * target * post.inverse(), row)
    }
}

fn rot_x_trans_x(alpha: f64, a: f64) -> IsometryMatrix3<f64> {
    let (s, c) = sin_cos(alpha);
    IsometryMatrix3::from_parts(
        Translation3::new(a, 0.0, 0.0),
        Rotation3::from_matrix_unchecked(nalgebra::Matrix3::new(
            1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c,
        )),
    )
}

fn canonical(robot: &Robot) -> Option<Canonical> {
    let n = robot.dof();
    if !(2..=6).contains(&n) {
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
                    theta0: j.dh.theta,
                    prismatic: j.kind == JointKind::Prismatic,
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
                    theta0: joint.dh.theta,
                    prismatic: joint.kind == JointKind::Prismatic,
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
    sin_cos(alpha).1.abs() < 1e-9
}

/// α = 0 or π: the next axis is parallel to this one.
fn parallel(alpha: f64) -> bool {
    sin_cos(alpha).0.abs() < 1e-9
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
    let revolute = |i: usize| !r[i].prismatic;
    let all_revolute = r[..c.n].iter().all(|row| !row.prismatic);
    match c.n {
        2 if all_revolute
            && angle_is(r[0].alpha, 0.0)
            && r[0].a.abs() > tiny
            && r[1].a.abs() > tiny
            && tool_at_frame =>
        {
            Some(ClosedFormFamily::Planar2R)
        }
        3 if all_revolute
            && quarter_turn(r[0].alpha)
            && r[0].a.abs() <= tiny
            && angle_is(r[1].alpha, 0.0)
            && r[1].a.abs() > tiny
            && r[2].a.abs() > tiny
            && tool_at_frame =>
        {
            Some(ClosedFormFamily::Rrr)
        }
        4 if revolute(0)
            && revolute(1)
            && r[2].prismatic
            && revolute(3)
            && parallel(r[0].alpha)
            && parallel(r[1].alpha)
            && parallel(r[2].alpha)
            && r[0].a.abs() > tiny
            && r[1].a.abs() > tiny
            && r[2].a.abs() <= tiny =>
        {
            Some(ClosedFormFamily::Scara)
        }
        6 if all_revolute
            && quarter_turn(r[0].alpha)
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
        6 if revolute(0)
            && revolute(1)
            && revolute(3)
            && revolute(4)
            && revolute(5)
            && quarter_turn(r[0].alpha)
            && r[0].a.abs() <= tiny
            && quarter_turn(r[3].alpha)
            && quarter_turn(r[4].alpha)
            && r[3].a.abs() <= tiny
            && r[4].a.abs() <= tiny
            && r[4].d.abs() <= tiny
            && pieper::position_kind(r, tiny).is_some() =>
        {
            Some(ClosedFormFamily::SphericalWrist)
        }
        _ => None,
    }
}

/// The joint value for the DH variable `var` of `joint` (θ with its offset, or d with
/// its offset for a prismatic joint): a revolute angle as the 2π-equivalent inside the
/// limits nearest `seed`; and whether it lies inside the limits.
fn represent(joint: &Joint, var: f64, seed: f64) -> (f64, bool) {
    if joint.kind == JointKind::Prismatic {
        let value = var - joint.dh.d;
        return (value, joint.limits.contains(value, 1e-9));
    }
    let value = var - joint.dh.theta;
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

/// A planar 2R branch.
#[derive(Debug, Clone, Copy)]
struct Planar {
    /// The first joint's angle.
    ta: f64,
    /// The second joint's angle.
    tb: f64,
    /// The sign given to `sin θ_b` (+1 or −1; the first entry is +1).
    sign: f64,
    /// The point is within reach (not clamped).
    exact: bool,
    /// Stretched or folded: the two branches coincide (one returned).
    singular: bool,
    /// The point is at the base with equal links: θ_a is free and took the seed's value.
    free_a: bool,
}

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
fn elbow_of(side: f64, l1: f64, l2: f64, sign: f64) -> Elbow {
    if side * (-l1 * l2 * sign) > 0.0 {
        Elbow::Up
    } else {
        Elbow::Down
    }
}

fn shoulder_of(root: usize) -> Shoulder {
    if root == 0 {
        Shoulder::Right
    } else {
        Shoulder::Left
    }
}

/// The shoulder's sign: +1 for the first root (wrist in front), −1 for the second.
fn front_sign(root: usize) -> f64 {
    if root == 0 { 1.0 } else { -1.0 }
}

/// The two base angles that put a point (x, y) at distance `d_sum` along
/// z_1 = σ_1(sin θ, −cos θ, 0): `σ_1(x sin θ − y cos θ) = D`. Returns
/// ([θ, θ'], exact, singular, free); on the base axis with D = 0 the angle is free (the
/// seed's and the seed's + π).
fn shoulder(
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

/// Which branch decisions coincide in a raw solution.
#[derive(Debug, Clone, Copy, Default)]
struct Merged {
    shoulder: bool,
    elbow: bool,
    wrist: bool,
}

/// A raw solution: the DH variables (θ with offsets, or d), its branch, exact, singular,
/// the coinciding decisions and the free joints.
#[derive(Debug, Clone)]
struct Raw {
    theta: [f64; 6],
    branch: Branch,
    exact: bool,
    singular: bool,
    merged: Merged,
    free: [bool; 6],
}

impl Raw {
    fn new(theta: [f64; 6], branch: Branch) -> Self {
        Raw {
            theta,
            branch,
            exact: true,
            singular: false,
            merged: Merged::default(),
            free: [false; 6],
        }
    }

    /// The branches that coincide with this one: every combination of the merged
    /// decisions flipped, except the branch itself.
    fn coincident(&self) -> Vec<Branch> {
        let mut out = Vec::new();
        if !(self.merged.shoulder || self.merged.elbow || self.merged.wrist) {
            // Off every singularity (almost every call): no other branch coincides.
            return out;
        }
        let flip_s = |s: Option<Shoulder>| {
            s.map(|s| match s {
                Shoulder::Right => Shoulder::Left,
                Shoulder::Left => Shoulder::Right,
            })
        };
        let flip_e = |e: Option<Elbow>| {
            e.map(|e| match e {
                Elbow::Up => Elbow::Down,
                Elbow::Down => Elbow::Up,
            })
        };
        let flip_w = |w: Option<Wrist>| {
            w.map(|w| match w {
                Wrist::NotFlipped => Wrist::Flipped,
                Wrist::Flipped => Wrist::NotFlipped,
            })
        };
        let b = self.branch;
        for fs in [false, true] {
            for fe in [false, true] {
                for fw in [false, true] {
                    if (fs && !self.merged.shoulder)
                        || (fe && !self.merged.elbow)
                        || (fw && !self.merged.wrist)
                        || !(fs || fe || fw)
                    {
                        continue;
                    }
                    let c = Branch {
                        shoulder: if fs { flip_s(b.shoulder) } else { b.shoulder },
                        elbow: if fe { flip_e(b.elbow) } else { b.elbow },
                        wrist: if fw { flip_w(b.wrist) } else { b.wrist },
                    };
                    if c != b && !out.contains(&c) {
                        out.push(c);
                    }
                }
            }
        }
        out
    }
}

/// Every closed-form solution of `target` (the tool pose in the world frame). `seed`
/// chooses each angle's 2π-equivalent (nearest it, inside the limits) and the value of a
/// free joint at a singularity. 2R and RRR solve the tool position (their orientation
/// follows from it); the UR family, the spherical-wrist arms and the SCARA solve the
/// pose.
///
/// Every solution marked `exact` reproduces the target (FK to rounding), singular
/// targets included: where the target leaves joints free (a continuum of solutions),
/// one representative is listed with [`ClosedFormSolution::free_joints`] naming them.
pub fn closed_form_solutions(
    robot: &Robot,
    target: &IsometryMatrix3<f64>,
    seed: &[f64],
) -> Result<ClosedFormSet, IkError> {
    // A full pose keeps its target as it is (`target_for_task`).
    closed_form_solutions_for_task(robot, target, Task::FullPose, seed)
}

/// [`closed_form_solutions`] for `task`: a position or 5D target first gets the
/// orientation [`target_for_task`] gives it (the robot's chain is recognised once, not
/// once for the family and again for the solutions: a drag frame calls this).
pub(crate) fn closed_form_solutions_for_task(
    robot: &Robot,
    target: &IsometryMatrix3<f64>,
    task: Task,
    seed: &[f64],
) -> Result<ClosedFormSet, IkError> {
    robot.check_q(seed)?;
    let (family, c, scale) =
        detect(robot).ok_or_else(|| IkError::NoClosedForm(robot.name.clone()))?;
    let target = &target_for_task(robot, family, target, task, seed);
    let seed_theta = dh_variables(robot, seed);
    let mut raws: Vec<Raw> = Vec::with_capacity(8);
    let mut planar: Vec<Planar> = Vec::with_capacity(2);
    match family {
        ClosedFormFamily::Planar2R => {
            planar_2r_family(&c, target, &seed_theta, scale, &mut raws, &mut planar);
        }
        ClosedFormFamily::Rrr => {
            rrr_family(&c, target, &seed_theta, scale, &mut raws, &mut planar);
        }
        ClosedFormFamily::UrFamily => {
            ur_family(&c, target, &seed_theta, scale, &mut raws, &mut planar);
        }
        ClosedFormFamily::Scara => {
            scara::solve(&c, target, &seed_theta, &mut raws, &mut planar);
        }
        ClosedFormFamily::SphericalWrist => {
            pieper::solve(
                &c,
                robot,
                target,
                &seed_theta,
                scale,
                &mut raws,
                &mut planar,
            );
        }
    }
    let any_exact = raws.iter().any(|s| s.exact);
    let mut solutions: Vec<ClosedFormSolution> = Vec::with_capacity(raws.len());
    for raw in raws.iter().filter(|s| s.exact == any_exact) {
        add_solution(robot, c.n, raw, seed, &mut solutions);
    }
    let singular = solutions.iter().any(|s| s.singular);
    Ok(ClosedFormSet {
        family,
        solutions,
        unreachable: !any_exact,
        singular,
    })
}

/// The DH variables of `seed` (offsets included), for free joints.
fn dh_variables(robot: &Robot, seed: &[f64]) -> [f64; 6] {
    let mut seed_theta = [0.0; 6];
    for (i, j) in robot.joints.iter().enumerate() {
        seed_theta[i] = seed[i]
            + match j.kind {
                JointKind::Revolute => j.dh.theta,
                JointKind::Prismatic => j.dh.d,
            };
    }
    seed_theta
}

/// The planar 2R's solutions into `raws`.
fn planar_2r_family(
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
fn rrr_family(
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

/// Adds `raw` (in joint values near `seed`) to `solutions`, or, when it is a singular
/// one that an earlier solution already is (branches coincide only at singularities),
/// adds its branches to that one's coincident branches instead.
fn add_solution(
    robot: &Robot,
    n: usize,
    raw: &Raw,
    seed: &[f64],
    solutions: &mut Vec<ClosedFormSolution>,
) {
    let mut q = Vec::with_capacity(n);
    let mut inside = true;
    for (i, joint) in robot.joints.iter().enumerate() {
        let (v, ok) = represent(joint, raw.theta[i], seed[i]);
        inside &= ok;
        q.push(v);
    }
    let duplicate = if raw.singular {
        solutions.iter().position(|s| {
            s.q.iter()
                .zip(&q)
                .zip(&robot.joints)
                .all(|((a, b), j)| j.change(*a, *b).abs() < 1e-9)
        })
    } else {
        None
    };
    let mut coincident = raw.coincident();
    if let Some(k) = duplicate {
        let kept = &mut solutions[k];
        coincident.push(raw.branch);
        for b in coincident {
            if b != kept.branch && !kept.coincident.contains(&b) {
                kept.coincident.push(b);
            }
        }
        kept.singular = true;
        return;
    }
    solutions.push(ClosedFormSolution {
        q,
        branch: raw.branch,
        coincident,
        free_joints: (0..n).filter(|&i| raw.free[i]).collect(),
        within_limits: inside,
        singular: raw.singular,
        exact: raw.exact,
    });
}

/// The smallest `sin θ5` (UR family) below which the wrist counts as singular: θ6 and
/// θ2 + θ3 + θ4 are then no longer separable.
const WRIST_SINGULAR: f64 = 1e-9;

/// The UR-family closed form (module doc, docs/kinematics.md §9.3) into `raws`.
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
    let (t, row6) = c.without_last_link(target);
    let (sc1, sc5) = (r[0].alpha_sin_cos(), r[4].alpha_sin_cos());
    let p = t.translation.vector;
    let rot = t.rotation.matrix();
    let x6 = rot.column(0).into_owned();
    let y6 = rot.column(1).into_owned();
    let z6 = rot.column(2).into_owned();
    let sigma1 = r[0].sigma();
    let sigma4 = r[3].sigma();
    let sigma45 = sigma4 * r[4].sigma();
    let w = p - z6 * r[5].d;
    let d_sum = r[1].d + r[2].d + r[3].d;
    let (t1s, ok1, sing1, free1) = shoulder(w.x, w.y, sigma1, d_sum, seed_theta[0], scale);
    for (s, &t1) in t1s.iter().enumerate() {
        let (s1, c1) = sin_cos(t1);
        let z1 = Vector3::new(s1, -c1, 0.0) * sigma1;
        let cz = z6.dot(&z1);
        let sx = x6.dot(&z1);
        let sy = y6.dot(&z1);
        let s5 = sx.hypot(sy);
        let wrist_singular = s5 < WRIST_SINGULAR;
        let t5_plus = atan2(s5, -sigma45 * cz);
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
/// The pose the closed form should solve for `task`: 2R and RRR solve positions, so the
/// target is used as it is; the other families need a whole pose, so the orientation the task
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
    if !family.solves_pose() {
        return *target;
    }
    // The arm's present orientation, for the tasks that leave some of it free (a full
    // pose, every drag frame's task on a UR arm, needs no FK).
    let current = || crate::fk::tool_pose(robot, seed);
    let rotation = match task {
        Task::FullPose => return *target,
        Task::Position => current().rotation,
        Task::PositionAndAxis(axis) => {
            let current = current();
            let k = axis.index();
            let a = current.rotation.matrix().column(k).into_owned();
            let b = target.rotation.matrix().column(k).into_owned();
            let cross = a.cross(&b);
            let s = cross.norm();
            let angle = atan2(s, a.dot(&b));
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
