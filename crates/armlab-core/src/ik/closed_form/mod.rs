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
//! Each family's solver lives in a module of its own ([`ur`], [`scara`], [`pieper`]; the
//! planar 2R and the RRR arm in [`planar`], which the others build on); they read the
//! table through [`canonical`] and fill the raw solutions of [`raw`].

mod canonical;
mod pieper;
mod planar;
mod raw;
mod scara;
mod ur;

use std::f64::consts::FRAC_PI_2;

use crate::angles::atan2;
use nalgebra::{IsometryMatrix3, Rotation3};

use super::branch::Branch;
use super::error::IkError;
use crate::jacobian::Task;
use crate::robot::{JointKind, Robot};
use canonical::{Canonical, angle_is, canonical, parallel, quarter_turn};
use planar::{Planar, planar_2r_family, rrr_family};
use raw::{Raw, add_solution};

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
            ur::ur_family(&c, target, &seed_theta, scale, &mut raws, &mut planar);
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
