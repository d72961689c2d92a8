//! The solver's interface: [`IkSolver`] with its reusable workspaces, the one-shot
//! [`solve`] and [`drag_step`], the closed form's choice of branch, and the per-frame
//! clip of a drag. Apart from the settings and results it reads and writes, which the
//! methods share.

use nalgebra::IsometryMatrix3;

use super::branches::{Branch, BranchStep, branch_step};
use super::closed_form;
use super::error::{IkError, check_target};
use super::numeric::Workspace;
use super::task_error::{TaskTarget, evaluate};
use super::{
    DEFAULT_MAX_JOINT_CHANGE, IkMethod, IkResult, IkSettings, joint_distance, within_limits,
};
use crate::error::RobotError;
use crate::fk::tool_pose;
use crate::jacobian::Task;
use crate::robot::{JointKind, Robot};

/// A result whose joint values or errors are not finite (a robot built in code, without
/// [`Robot::validated`], whose pose overflows) is an error, never an answer.
fn check_result(result: IkResult) -> Result<IkResult, IkError> {
    let finite = result.q.iter().all(|v| v.is_finite())
        && result.position_error.is_finite()
        && result.orientation_error.is_finite();
    if finite {
        Ok(result)
    } else {
        Err(IkError::Robot(RobotError::PoseNotFinite))
    }
}

/// The reusable IK solver: its workspaces grow to the robot once and are reused, so
/// repeated calls (dragging, benchmarks) do not allocate in the iteration loop.
#[derive(Debug, Clone, Default)]
pub struct IkSolver {
    ws: Workspace,
    /// The closed form's exact branches in the order they are tried (kept between calls
    /// so that a drag frame allocates no list).
    order: Vec<(bool, f64, usize)>,
}

impl IkSolver {
    /// A solver with empty workspaces (they grow on the first call).
    pub fn new() -> Self {
        IkSolver::default()
    }

    /// Solves IK for `robot` from `seed` toward `target` (the tool pose in the base/world
    /// frame, in the robot's length unit) for `task` with `method`.
    ///
    /// Numeric methods run from the seed (kept inside the limits first), then from random
    /// restart points while the budget lasts, and return the best attempt. The closed
    /// form returns the exact branch nearest the seed (inside the limits when one is);
    /// when it has none (unreachable target) the damped method finds the closest pose.
    /// Tasks the closed form does not fix (a 6R arm asked for position only) hold the
    /// seed's orientation. With [`IkSettings::max_joint_change`] the move is clipped.
    pub fn solve(
        &mut self,
        robot: &Robot,
        target: &IsometryMatrix3<f64>,
        task: Task,
        seed: &[f64],
        method: IkMethod,
        settings: &IkSettings,
    ) -> Result<IkResult, IkError> {
        robot.check_q(seed)?;
        check_target(target)?;
        settings.check()?;
        let mut result = match method {
            IkMethod::ClosedForm => self.closed_form(robot, target, task, seed, settings)?,
            _ => self.ws.run(robot, target, task, seed, method, settings),
        };
        if let Some(limit) = settings.max_joint_change {
            self.clip(robot, target, task, seed, limit, settings, &mut result);
        }
        check_result(result)
    }

    /// One frame of dragging: moves from `q_current` toward `target` and never moves a
    /// joint by more than the largest change per call ([`IkSettings::max_joint_change`],
    /// default [`DEFAULT_MAX_JOINT_CHANGE`], measured as the wrapped difference), so the
    /// arm never jumps. The closed form picks the branch nearest `q_current` (so the
    /// branch stays stable while dragging); numeric methods warm-start from `q_current`.
    /// An unreachable target gives the closest pose found, flagged `unreachable`.
    /// Use [`IkSettings::drag`] for the settings.
    pub fn drag_step(
        &mut self,
        robot: &Robot,
        q_current: &[f64],
        target: &IsometryMatrix3<f64>,
        task: Task,
        method: IkMethod,
        settings: &IkSettings,
    ) -> Result<IkResult, IkError> {
        let limit = settings
            .max_joint_change
            .unwrap_or(DEFAULT_MAX_JOINT_CHANGE);
        robot.check_q(q_current)?;
        check_target(target)?;
        settings.check()?;
        let mut result = match method {
            IkMethod::ClosedForm => self.closed_form(robot, target, task, q_current, settings)?,
            _ => self
                .ws
                .run(robot, target, task, q_current, method, settings),
        };
        self.clip(robot, target, task, q_current, limit, settings, &mut result);
        check_result(result)
    }

    /// One drag frame with the closed form that keeps the arm on the branch `previous`
    /// (by its label: the elbow stays up) as long as the target has an exact solution on
    /// it, and otherwise takes the exact solution nearest the arm ([`branch_step`]). The
    /// arm moves toward that solution by at most the per-frame joint change, as
    /// [`IkSolver::drag_step`] does. Without any exact solution (the target out of reach)
    /// it is [`IkSolver::drag_step`]'s closed-form step, and the branch asked for stays.
    pub fn drag_step_on_branch(
        &mut self,
        robot: &Robot,
        q_current: &[f64],
        target: &IsometryMatrix3<f64>,
        task: Task,
        previous: &Branch,
        settings: &IkSettings,
    ) -> Result<(IkResult, BranchStep), IkError> {
        settings.check()?;
        let step = branch_step(robot, q_current, previous, target, task)?;
        let solution = &step.set.solutions[step.index];
        let tt = TaskTarget::new(target, task);
        let ev = evaluate(&tt, &tool_pose(robot, &solution.q), 1.0);
        let tol_p = settings.position_tolerance / robot.length_unit.in_metres();
        let meets =
            ev.position_error <= tol_p && ev.orientation_error <= settings.orientation_tolerance;
        if !solution.exact || !meets {
            let result = self.drag_step(
                robot,
                q_current,
                target,
                task,
                IkMethod::ClosedForm,
                settings,
            )?;
            let kept = BranchStep {
                branch: *previous,
                vanished: false,
                ..step
            };
            return Ok((result, kept));
        }
        let mut result = IkResult {
            within_limits: solution.within_limits,
            q: solution.q.clone(),
            success: true,
            unreachable: false,
            singular: solution.singular,
            clipped: false,
            position_error: ev.position_error,
            orientation_error: ev.orientation_error,
            iterations: 0,
            restarts: 0,
            trace: Vec::new(),
        };
        let limit = settings
            .max_joint_change
            .unwrap_or(DEFAULT_MAX_JOINT_CHANGE);
        self.clip(robot, target, task, q_current, limit, settings, &mut result);
        Ok((check_result(result)?, step))
    }

    /// The closed form, the branch nearest `seed`, with the damped fallback.
    fn closed_form(
        &mut self,
        robot: &Robot,
        target: &IsometryMatrix3<f64>,
        task: Task,
        seed: &[f64],
        settings: &IkSettings,
    ) -> Result<IkResult, IkError> {
        let mut set = closed_form::closed_form_solutions_for_task(robot, target, task, seed)?;
        let tt = TaskTarget::new(target, task);
        let tol_p = settings.position_tolerance / robot.length_unit.in_metres();
        // Exact branches, inside the limits first, nearest the seed first; the first
        // that meets the task wins (2R and RRR solve positions: for a 5D or full-pose
        // task not every branch has the right orientation).
        let order = &mut self.order;
        order.clear();
        order.extend(
            set.solutions
                .iter()
                .enumerate()
                .filter(|(_, s)| s.exact)
                .map(|(k, s)| (!s.within_limits, joint_distance(robot, seed, &s.q), k)),
        );
        // No two keys are equal (the index is the last), so the unstable sort's order is
        // the stable one.
        order.sort_unstable_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let mut best: Option<(f64, usize, f64, f64)> = None;
        for &(_, _, k) in order.iter() {
            let ev = evaluate(&tt, &tool_pose(robot, &set.solutions[k].q), 1.0);
            let ok = ev.position_error <= tol_p
                && ev.orientation_error <= settings.orientation_tolerance;
            let score = if ok { -1.0 } else { ev.cost };
            if best.is_none_or(|(b, ..)| score < b) {
                best = Some((score, k, ev.position_error, ev.orientation_error));
            }
            if ok {
                break;
            }
        }
        match best {
            Some((score, k, position_error, orientation_error)) => {
                let sol = set.solutions.swap_remove(k);
                let success = score < 0.0;
                Ok(IkResult {
                    within_limits: sol.within_limits,
                    q: sol.q,
                    success,
                    unreachable: !success,
                    singular: sol.singular,
                    clipped: false,
                    position_error,
                    orientation_error,
                    iterations: 0,
                    restarts: 0,
                    trace: Vec::new(),
                })
            }
            None => {
                // No exact branch (out of reach, or a 6R arm whose held orientation cannot
                // be reached here): damped least squares on the real task from the seed.
                let mut r = self.ws.run(
                    robot,
                    target,
                    task,
                    seed,
                    IkMethod::DampedLeastSquares,
                    settings,
                );
                r.unreachable = !r.success;
                r.singular = set.singular;
                Ok(r)
            }
        }
    }

    /// Scales the move from `from` to `result.q` down so that no joint changes by more
    /// than `limit` (wrapped difference), then re-evaluates the errors.
    #[allow(clippy::too_many_arguments)]
    fn clip(
        &mut self,
        robot: &Robot,
        target: &IsometryMatrix3<f64>,
        task: Task,
        from: &[f64],
        limit: f64,
        settings: &IkSettings,
        result: &mut IkResult,
    ) {
        let mut scale: f64 = 1.0;
        for ((joint, a), b) in robot.joints.iter().zip(from).zip(&result.q) {
            let delta = move_of(joint, *a, *b);
            let allowed = joint_limit(joint, limit);
            if delta.abs() > allowed {
                scale = scale.min(allowed / delta.abs());
            }
        }
        if scale >= 1.0 {
            return;
        }
        // A hair below the limit so that rounding never lands above it.
        let scale = scale * (1.0 - 1e-9);
        for ((joint, a), b) in robot.joints.iter().zip(from).zip(result.q.iter_mut()) {
            let delta = move_of(joint, *a, *b);
            *b = joint.keep(a + scale * delta, *a);
        }
        let tt = TaskTarget::new(target, task);
        let ev = evaluate(&tt, &tool_pose(robot, &result.q), 1.0);
        let tol_p = settings.position_tolerance / robot.length_unit.in_metres();
        result.position_error = ev.position_error;
        result.orientation_error = ev.orientation_error;
        result.success =
            ev.position_error <= tol_p && ev.orientation_error <= settings.orientation_tolerance;
        result.within_limits = within_limits(robot, &result.q);
        result.clipped = true;
    }
}

/// The motion of one joint from `a` to `b`: the wrapped difference for joints that wrap
/// (±180°), the plain difference otherwise (both values lie inside the limits, so the
/// straight path does too, and it is never shorter than the wrapped one).
fn move_of(joint: &crate::robot::Joint, a: f64, b: f64) -> f64 {
    if joint.kind == JointKind::Revolute && !joint.wraps() {
        b - a
    } else {
        joint.change(a, b)
    }
}

/// The per-call limit of one joint: `limit` radians, or for a prismatic joint the same
/// fraction of its stroke as `limit` is of π.
fn joint_limit(joint: &crate::robot::Joint, limit: f64) -> f64 {
    match joint.kind {
        JointKind::Revolute => limit,
        JointKind::Prismatic => {
            let stroke = joint.limits.max - joint.limits.min;
            if stroke > 0.0 {
                limit / std::f64::consts::PI * stroke
            } else {
                0.0
            }
        }
    }
}

/// One-shot [`IkSolver::solve`] (allocates its workspaces).
pub fn solve(
    robot: &Robot,
    target: &IsometryMatrix3<f64>,
    task: Task,
    seed: &[f64],
    method: IkMethod,
    settings: &IkSettings,
) -> Result<IkResult, IkError> {
    IkSolver::new().solve(robot, target, task, seed, method, settings)
}

/// One-shot [`IkSolver::drag_step`] (allocates its workspaces): what the GUI calls every
/// frame while the user drags the target.
pub fn drag_step(
    robot: &Robot,
    q_current: &[f64],
    target: &IsometryMatrix3<f64>,
    task: Task,
    method: IkMethod,
    settings: &IkSettings,
) -> Result<IkResult, IkError> {
    IkSolver::new().drag_step(robot, q_current, target, task, method, settings)
}
