//! The model's IK: a drag's step (on the kept closed-form branch or by the chosen
//! method), a full solve, and the rescue search when a drag stalls short of its target.

use armlab_text::Sentence;

use armlab_core::ik::{
    ClosedFormFamily, IkError, IkResult, IkSettings, REACHED_ORIENTATION_TOLERANCE,
    REACHED_POSITION_TOLERANCE_M, Reach, branch_of, closed_form_family, closed_form_solutions,
    distinct_solutions, joint_distance, pose_error,
};
use armlab_core::workspace::joints_held_at_limits;
use armlab_core::{IkMethod, Task};
use nalgebra::IsometryMatrix3;

use super::{Message, Model};
use crate::app::state::notebook::NotebookDemo;

/// A drag stalled short of its target (often with a joint at its limit), and what other
/// starts make of the target.
#[derive(Debug, Clone, PartialEq)]
pub struct Rescue {
    /// What the search was made for: it is stale once any of these changed.
    pub(super) target: IsometryMatrix3<f64>,
    pub(super) robot_changes: u64,
    pub(super) task: Task,
    /// The joint (from 0) that holds the arm, pulled past its limit by the error, and
    /// whether at its upper limit; `None` when the stall is not at a limit.
    pub held: Option<(usize, bool)>,
    /// A solution within the limits that reaches the target (the closed form's branches
    /// or seeded restarts), nearest the arm; `None` when none was found.
    pub reach: Option<Vec<f64>>,
    /// Starts tried: closed-form branches plus restarts.
    pub tried: usize,
}

/// The last full solve, kept for replay, with the robot it ran on: a run of another
/// robot is never shown or replayed.
#[derive(Debug, Clone, PartialEq)]
pub struct Replay {
    pub(super) robot_changes: u64,
    /// The run, with its trace.
    pub run: IkResult,
    /// The iteration shown.
    pub step: usize,
    /// The notebook run it is, if it is one.
    pub demo: Option<NotebookDemo>,
}

/// Random restarts tried for a target held at a limit: few and short, since the search
/// runs once per target while a drag stalls (about 0.3 ms natively).
const RESCUE_RESTARTS: usize = 4;

/// The iteration budget of each of those restarts.
const RESCUE_BUDGET: usize = 200;

impl Model {
    /// One drag frame: while the target is pending or out of reach, one IK step
    /// warm-started at q (each joint moves at most the per-call limit). Returns whether it
    /// ran. A failure (only a broken target could cause one) becomes the message.
    pub fn drag_step(&mut self) -> bool {
        if self.motion.on() {
            return self.motion_drag();
        }
        if self.ik.reach == Reach::Reached {
            return false;
        }
        if !(self.method == IkMethod::ClosedForm && self.drag_step_on_branch()) {
            let result = self.solver.drag_step(
                &self.robot,
                &self.q,
                &self.target,
                self.task,
                self.method,
                &IkSettings::drag(),
            );
            self.apply_result(result);
        }
        self.stop_at_collision();
        true
    }

    /// A closed-form drag frame that keeps the branch by its label
    /// ([`IkSolver::drag_step_on_branch`]); false when the arm's branch cannot be named
    /// (the plain closed-form step runs instead).
    pub(super) fn drag_step_on_branch(&mut self) -> bool {
        let previous = match self.kept_branch() {
            Some(branch) => branch,
            None => {
                self.branch_switch = None;
                match branch_of(&self.robot, &self.q) {
                    Ok(Some(branch)) => branch,
                    _ => return false,
                }
            }
        };
        let result = self.solver.drag_step_on_branch(
            &self.robot,
            &self.q,
            &self.target,
            self.task,
            &previous,
            &IkSettings::drag(),
        );
        match result {
            Ok((result, step)) => {
                if step.vanished {
                    self.branch_switch = Some((previous, step.branch));
                }
                self.apply_result(Ok(result));
                self.kept_branch = Some((step.branch, self.q.clone()));
            }
            Err(e) => {
                self.apply_result(Err(e));
            }
        }
        true
    }

    /// The last full solve of this robot, if any.
    pub fn replay(&self) -> Option<&Replay> {
        self.replay
            .as_ref()
            .filter(|r| r.robot_changes == self.robot_changes)
    }

    /// Keeps a run for replay, at its last iteration.
    pub fn keep_replay(&mut self, run: IkResult, demo: Option<NotebookDemo>) {
        self.replay = Some(Replay {
            robot_changes: self.robot_changes,
            step: run.trace.len().saturating_sub(1),
            run,
            demo,
        });
    }

    /// Shows iteration `step` of the replay and moves the arm to its q.
    pub fn replay_step(&mut self, step: usize) {
        let Some(q) = self
            .replay()
            .and_then(|r| r.run.trace.get(step))
            .map(|s| s.q.clone())
        else {
            return;
        };
        if let Some(replay) = self.replay.as_mut() {
            replay.step = step;
        }
        self.set_q(q);
    }

    /// Runs the method to convergence from q with every iteration recorded, moves the
    /// arm to its answer and returns the run (for replay).
    pub fn solve_with_trace(&mut self) -> Option<IkResult> {
        self.solve_with_settings(&IkSettings {
            record_trace: true,
            restarts: 0,
            max_iterations: 2000,
            budget: 2000,
            ..IkSettings::default()
        })
    }

    /// Runs the chosen method with these settings from the current q (the notebook's
    /// demos set their own tolerance, wrapping and objective); the arm takes the answer.
    pub fn solve_with_settings(&mut self, settings: &IkSettings) -> Option<IkResult> {
        let result = self.solver.solve(
            &self.robot,
            &self.target,
            self.task,
            &self.q,
            self.method,
            settings,
        );
        self.apply_result(result)
    }

    pub(super) fn apply_result(&mut self, result: Result<IkResult, IkError>) -> Option<IkResult> {
        match result {
            Ok(result) if self.motion.on() => {
                self.drive_to(result.q.clone(), result.unreachable);
                self.ik.iterations = result.iterations;
                Some(result)
            }
            Ok(mut result) => {
                self.set_q(result.q.clone());
                self.ik.iterations = result.iterations;
                // One verdict: a run that stopped short of a target the closed form has
                // no exact solution for found it out of reach.
                result.unreachable |= !result.success && self.no_exact_solution();
                if self.ik.reach != Reach::Reached {
                    self.ik.reach = if result.unreachable {
                        Reach::OutOfReach
                    } else {
                        Reach::Pending
                    };
                }
                if self.ik.reach == Reach::OutOfReach && self.rescue().is_none() {
                    self.rescue = self.find_rescue();
                }
                Some(result)
            }
            Err(e) => {
                self.message = Some(Message::error(e.sentence(self.settings.lang)));
                None
            }
        }
    }

    /// Whether the closed form finds no exact solution for the target (for the full pose,
    /// or the position of a 2R or RRR arm, which is all they solve): then no method
    /// reaches it. Found once per target, task and robot.
    pub(super) fn no_exact_solution(&mut self) -> bool {
        let key = (self.target, self.task, self.robot_changes);
        if let Some((target, task, changes, answer)) = self.no_exact
            && (target, task, changes) == key
        {
            return answer;
        }
        let answers = match closed_form_family(&self.robot) {
            Some(ClosedFormFamily::Planar2R | ClosedFormFamily::Rrr) => true,
            Some(_) => self.task == Task::FullPose,
            None => false,
        };
        let answer = answers
            && closed_form_solutions(&self.robot, &self.target, &self.q)
                .is_ok_and(|set| set.unreachable);
        self.no_exact = Some((key.0, key.1, key.2, answer));
        answer
    }

    /// When the drag stalls short of the target: the joint that holds it at a limit, if
    /// one does, and of every closed-form branch of the target and a few seeded restarts,
    /// the one within the limits that reaches it nearest the arm.
    pub(super) fn find_rescue(&self) -> Option<Rescue> {
        let held = joints_held_at_limits(&self.robot, &self.q, &self.target, self.task, 1e-6)
            .first()
            .map(|h| (h.joint, h.at_max));
        let tolerance = REACHED_POSITION_TOLERANCE_M / self.robot.length_unit.in_metres();
        let reaches = |q: &[f64]| {
            let (p, o) = pose_error(&self.robot, q, &self.target, self.task);
            p <= tolerance && o <= REACHED_ORIENTATION_TOLERANCE
        };
        let mut candidates: Vec<Vec<f64>> = Vec::new();
        if closed_form_family(&self.robot).is_some()
            && let Ok(set) = closed_form_solutions(&self.robot, &self.target, &self.q)
        {
            candidates.extend(
                set.solutions
                    .into_iter()
                    .filter(|s| s.exact && s.within_limits)
                    .map(|s| s.q),
            );
        }
        let branches = candidates.len();
        let settings = IkSettings {
            budget: RESCUE_BUDGET,
            max_iterations: RESCUE_BUDGET,
            ..IkSettings::default()
        };
        if let Ok(found) = distinct_solutions(
            &self.robot,
            &self.target,
            self.task,
            &settings,
            RESCUE_RESTARTS,
        ) {
            candidates.extend(
                found
                    .solutions
                    .into_iter()
                    .filter(|s| s.within_limits)
                    .map(|s| s.q),
            );
        }
        let reach = candidates
            .into_iter()
            .filter(|q| reaches(q))
            .min_by(|a, b| {
                joint_distance(&self.robot, &self.q, a)
                    .partial_cmp(&joint_distance(&self.robot, &self.q, b))
                    .unwrap_or(std::cmp::Ordering::Equal)
            });
        Some(Rescue {
            target: self.target,
            robot_changes: self.robot_changes,
            task: self.task,
            held,
            reach,
            tried: branches + RESCUE_RESTARTS,
        })
    }
}
