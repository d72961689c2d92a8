//! Branch labels of the closed forms (docs/kinematics.md §9.6) and keeping a branch while
//! dragging: the arm stays "elbow up" as long as an elbow-up solution exists.

use nalgebra::IsometryMatrix3;

pub use super::branch::{Branch, Elbow, Shoulder, Wrist};
use super::closed_form::{ClosedFormSet, closed_form_solutions, closed_form_solutions_for_task};
use super::error::{IkError, check_target};
use super::{closed_form_family, joint_distance};
use crate::fk::tool_pose;
use crate::jacobian::Task;
use crate::robot::Robot;

/// Which solution of a set continues a branch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BranchChoice {
    /// Index into [`ClosedFormSet::solutions`].
    pub index: usize,
    /// The branch asked for no longer exists (the target crossed a singularity, or no
    /// exact solution has that label): `index` is the solution nearest the current q.
    pub vanished: bool,
}

/// The solution of `set` that continues `previous`: the exact solution whose branch (or
/// one of the branches that coincide with it at a singularity) is `previous`, the
/// nearest `q_current` when several are; else the exact solution nearest `q_current`
/// (by [`joint_distance`]) with `vanished` set. Exact solutions inside the limits are
/// preferred to those outside at every step. `None` only for an empty set.
pub fn follow_branch(
    robot: &Robot,
    set: &ClosedFormSet,
    previous: &Branch,
    q_current: &[f64],
) -> Option<BranchChoice> {
    let exact_only = set.solutions.iter().any(|s| s.exact);
    let candidates = || {
        set.solutions
            .iter()
            .enumerate()
            .filter(move |(_, s)| s.exact || !exact_only)
    };
    let rank = |k: usize| {
        let s = &set.solutions[k];
        (!s.within_limits, joint_distance(robot, q_current, &s.q))
    };
    let best = |it: &mut dyn Iterator<Item = usize>| {
        it.min_by(|&a, &b| {
            rank(a)
                .partial_cmp(&rank(b))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    };
    let same = best(
        &mut candidates()
            .filter(|(_, s)| s.branch == *previous || s.coincident.contains(previous))
            .map(|(k, _)| k),
    );
    if let Some(index) = same {
        return Some(BranchChoice {
            index,
            vanished: false,
        });
    }
    best(&mut candidates().map(|(k, _)| k)).map(|index| BranchChoice {
        index,
        vanished: true,
    })
}

/// The branch the arm is on at `q`: the label of the closed-form solution of its own
/// tool pose that equals `q` (up to turns). `None` when the robot has no closed form.
pub fn branch_of(robot: &Robot, q: &[f64]) -> Result<Option<Branch>, IkError> {
    if closed_form_family(robot).is_none() {
        return Ok(None);
    }
    let target = tool_pose(robot, q);
    let set = closed_form_solutions(robot, &target, q)?;
    Ok(set
        .solutions
        .iter()
        .min_by(|a, b| {
            joint_distance(robot, q, &a.q)
                .partial_cmp(&joint_distance(robot, q, &b.q))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .map(|s| s.branch))
}

/// One frame of branch-keeping drag IK.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchStep {
    /// Every closed-form solution of the target (for drawing the ghosts).
    pub set: ClosedFormSet,
    /// The solution taken: index into `set.solutions`.
    pub index: usize,
    /// The branch to keep asking for next frame: `previous` while it exists, else the
    /// new solution's own branch.
    pub branch: Branch,
    /// The branch asked for vanished and the arm took the nearest solution instead.
    pub vanished: bool,
}

impl BranchStep {
    /// The joint vector of the chosen solution.
    pub fn q(&self) -> &[f64] {
        &self.set.solutions[self.index].q
    }
}

/// The closed-form solutions of `target` for `task` (the free orientation held as in
/// [`super::IkSolver::solve`]) and the one continuing `previous`, seeded at `q_current`.
/// The GUI moves the arm toward [`BranchStep::q`] (by its largest joint change per
/// frame) and keeps [`BranchStep::branch`] for the next frame.
pub fn branch_step(
    robot: &Robot,
    q_current: &[f64],
    previous: &Branch,
    target: &IsometryMatrix3<f64>,
    task: Task,
) -> Result<BranchStep, IkError> {
    robot.check_q(q_current)?;
    check_target(target)?;
    let set = closed_form_solutions_for_task(robot, target, task, q_current)?;
    let choice = follow_branch(robot, &set, previous, q_current)
        .ok_or_else(|| IkError::NoClosedForm(robot.name.clone()))?;
    let branch = if choice.vanished {
        set.solutions[choice.index].branch
    } else {
        *previous
    };
    Ok(BranchStep {
        index: choice.index,
        branch,
        vanished: choice.vanished,
        set,
    })
}
