//! Inverse kinematics (docs/kinematics.md §8–9): one interface over every method.
//!
//! - Numeric: damped least squares / Levenberg–Marquardt with adaptive damping
//!   `Δq = Jᵀ(J·Jᵀ + λ²I)⁻¹·e` (the default, robust near singularities and at unreachable
//!   targets), Newton with the Moore–Penrose pseudo-inverse `Δq = J⁺·e`, and Jacobian
//!   transpose / gradient descent on ½‖e‖², `Δq = α·Jᵀ·e`. Each can use the geometric or
//!   the central-difference Jacobian.
//! - Closed form where the arm allows it: the planar 2R, the RRR arm, the UR family, the
//!   SCARA and spherical-wrist arms (up to eight solutions, each labelled by its
//!   [`Branch`]), see [`closed_form_solutions`]; [`branch_step`] keeps a branch while
//!   dragging. Arms without one: [`distinct_solutions`] from seeded restarts.
//!
//! The error vector `e` has the position error `p_target − p` in its first three rows
//! and, by task: nothing more (position), the rotation turning the chosen tool axis `a`
//! onto the target's (the direction of `a × a_target`, of length the angle between them,
//! in the two directions perpendicular to `a`: a 5D task), or the rotation vector
//! `vee(log(R_target·Rᵀ))` (full pose). The damped and pseudo-inverse methods divide the
//! linear rows by a quarter of the arm's reach so that mm and m give the same steps.
//!
//! [`IkSolver`] holds the workspaces: keep one and call [`IkSolver::solve`] or
//! [`IkSolver::drag_step`] every frame; the hot loop then never allocates. [`solve`] and
//! [`drag_step`] are the one-shot forms. The core has no clock: budgets are iterations.

mod branch;
mod branches;
mod chain;
mod closed_form;
mod distinct;
mod numeric;
mod seeds;
mod task_error;

use nalgebra::{IsometryMatrix3, Matrix3, Vector3};

use super::error::RobotError;
use super::fk::tool_pose;
use super::jacobian::Task;
use super::robot::{JointKind, Robot};

pub use branches::{
    Branch, BranchChoice, BranchStep, Elbow, Shoulder, Wrist, branch_of, branch_step, follow_branch,
};
pub use closed_form::{
    ClosedFormFamily, ClosedFormSet, ClosedFormSolution, closed_form_family, closed_form_solutions,
};
pub use distinct::{
    DistinctSolutions, FoundSolution, MAX_CONTINUUM_SAMPLES, MAX_DISTINCT, SAME_SOLUTION,
    configuration_signs, distinct_solutions,
};
use numeric::Workspace;
pub use seeds::{MAX_SEED_TABLE, SeedTable};
use task_error::{TaskTarget, evaluate};

/// The largest change of any joint per [`drag_step`] call when the settings give none
/// (radians; see [`IkSettings::max_joint_change`] for prismatic joints).
pub const DEFAULT_MAX_JOINT_CHANGE: f64 = 0.1;

/// Which Jacobian the numeric methods use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum JacobianSource {
    /// The geometric Jacobian (docs/kinematics.md §4.1): exact and cheap.
    #[default]
    Geometric,
    /// Central differences with ε = [`crate::NUMERIC_EPSILON`] (the Metrover
    /// calculator's method): 2n forward kinematics per iteration.
    CentralDifference,
}

/// An IK method.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum IkMethod {
    /// Damped least squares / Levenberg–Marquardt, `Δq = Jᵀ(J·Jᵀ + λ²I)⁻¹·e`, with
    /// `λ² = μ·(‖e‖ + 10⁻⁶)`: μ shrinks after a step that lowers the error and grows
    /// after one that does not (the step is then retried). The robust default.
    #[default]
    DampedLeastSquares,
    /// Newton–Raphson with the Moore–Penrose pseudo-inverse, `Δq = J⁺·e`, the undamped
    /// full step (it can jump far: docs/kinematics.md §8.1). Singular values below 10⁻⁶·σ_max are
    /// dropped.
    PseudoInverse,
    /// Jacobian transpose / gradient descent on ½‖e‖²: `Δq = α·Jᵀ·e`. With `Some(α)` the
    /// rows are in the robot's own units (as in class); with `None` the step is Buss's
    /// `α = ⟨e, J·Jᵀe⟩ / ‖J·Jᵀe‖²` on the reach-scaled rows.
    JacobianTranspose {
        /// The fixed step α, or `None` for the adaptive one.
        alpha: Option<f64>,
    },
    /// The closed form of the arm's family (2R, RRR, UR, SCARA, spherical wrist), the
    /// branch nearest the seed.
    ClosedForm,
}

impl IkMethod {
    /// Every method, in menu order (the transpose with its adaptive step).
    pub const ALL: [IkMethod; 4] = [
        IkMethod::DampedLeastSquares,
        IkMethod::PseudoInverse,
        IkMethod::JacobianTranspose { alpha: None },
        IkMethod::ClosedForm,
    ];

    /// The id links, the JSON API and the benchmark use: `dls`, `pinv`, `gradient`,
    /// `closed`.
    pub fn id(self) -> &'static str {
        match self {
            IkMethod::DampedLeastSquares => "dls",
            IkMethod::PseudoInverse => "pinv",
            IkMethod::JacobianTranspose { .. } => "gradient",
            IkMethod::ClosedForm => "closed",
        }
    }

    /// The method of an id (`gradient` with the adaptive step); `closed-form`, the JSON
    /// API's first name for the closed form, is read too.
    pub fn from_id(id: &str) -> Option<IkMethod> {
        match id {
            "closed-form" => Some(IkMethod::ClosedForm),
            _ => IkMethod::ALL.into_iter().find(|m| m.id() == id),
        }
    }

    /// Every id, for messages: `dls, pinv, gradient, closed`.
    pub fn id_list() -> String {
        IkMethod::ALL.map(IkMethod::id).join(", ")
    }
}

/// Where the tool is against the target, as the app shows it: one vocabulary for the
/// marker's colour, the status line and the IK panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Reach {
    /// The tool is at the target within [`REACHED_POSITION_TOLERANCE_M`] and
    /// [`REACHED_ORIENTATION_TOLERANCE`] for the task's rows.
    Reached,
    /// The last solve or drag step found the target out of reach: the arm shows the
    /// closest pose it found.
    OutOfReach,
    /// Not at the target, and not (yet) found out of reach.
    Pending,
}

impl Reach {
    /// The id the test hook reports: `reached`, `out-of-reach`, `pending`.
    pub fn id(self) -> &'static str {
        match self {
            Reach::Reached => "reached",
            Reach::OutOfReach => "out-of-reach",
            Reach::Pending => "pending",
        }
    }
}

/// Position error (metres, converted to the robot's unit) at or below which the app
/// counts the target as reached.
pub const REACHED_POSITION_TOLERANCE_M: f64 = 1e-5;
/// Orientation error (radians) at or below which the app counts the target as reached.
pub const REACHED_ORIENTATION_TOLERANCE: f64 = 1e-4;

/// Settings of one IK call.
#[derive(Debug, Clone, PartialEq)]
pub struct IkSettings {
    /// Success needs the position error at most this, in metres (converted to the robot's
    /// length unit, so it means the same for mm and m robots).
    pub position_tolerance: f64,
    /// Success needs the orientation error (radians) at most this.
    pub orientation_tolerance: f64,
    /// Iteration cap of one attempt (one start point).
    pub max_iterations: usize,
    /// Iteration budget of the whole call, restarts included.
    pub budget: usize,
    /// The most random restarts after a stalled or capped attempt (numeric methods).
    pub restarts: usize,
    /// Seed of the [`crate::SplitMix64`] drawing restart points.
    pub seed: u64,
    /// The largest change of any joint relative to the seed in this call, measured as the
    /// wrapped difference ([`crate::Joint::change`]): the whole change is
    /// scaled down to meet it. Radians for revolute joints; a prismatic joint may move
    /// the same fraction of its stroke as this is of π. `None`: no limit (drag steps then
    /// use [`DEFAULT_MAX_JOINT_CHANGE`]).
    pub max_joint_change: Option<f64>,
    /// The numeric methods' Jacobian.
    pub jacobian: JacobianSource,
    /// Record every iteration in [`IkResult::trace`] (allocates; off for dragging).
    pub record_trace: bool,
    /// Keep every step's joint values as in docs/kinematics.md §3 (wrapped to (−π, π] or
    /// the 2π-equivalent inside the limits). `false` leaves revolute values as the steps
    /// accumulate them (the lecture notebook's `θ += solve(J, e)`: raw angles several
    /// turns away; [`wrapped_equivalent`] gives the wrapped values beside them);
    /// prismatic joints still clamp to their stroke. Default `true` (SPEC §2).
    pub wrap: bool,
    /// The cost whose gradient a fixed-step gradient method follows (docs/kinematics.md
    /// §8.2): ½‖e‖² (`Δq = α·Jᵀe`, the default) or ‖e‖² (`Δq = 2α·Jᵀe`, the notebook's
    /// `θ −= α·∇F` with ∇F = 2·Jᵀ·(f − t)). The adaptive step is the same for both.
    pub objective: Objective,
}

/// The cost a fixed-step gradient method descends (docs/kinematics.md §8.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Objective {
    /// F = ½‖e‖², ∇F = −Jᵀe: the step is `α·Jᵀe`.
    #[default]
    HalfSquared,
    /// F = ‖e‖², ∇F = −2·Jᵀe: the step is `2α·Jᵀe` (the lecture notebook's).
    Squared,
}

impl Objective {
    /// Both objectives, the default first.
    pub const ALL: [Objective; 2] = [Objective::HalfSquared, Objective::Squared];

    /// The id of the JSON API and links: `half-squared`, `squared`.
    pub fn id(self) -> &'static str {
        match self {
            Objective::HalfSquared => "half-squared",
            Objective::Squared => "squared",
        }
    }

    /// The objective of an id.
    pub fn from_id(id: &str) -> Option<Objective> {
        Objective::ALL.into_iter().find(|o| o.id() == id)
    }

    /// Every id, for messages: `half-squared, squared`.
    pub fn id_list() -> String {
        Objective::ALL.map(Objective::id).join(", ")
    }

    /// The factor of `α·Jᵀe` in the step: 1 for ½‖e‖², 2 for ‖e‖².
    pub fn gradient_factor(self) -> f64 {
        match self {
            Objective::HalfSquared => 1.0,
            Objective::Squared => 2.0,
        }
    }
}

/// Each joint value of `q` as the robot keeps it (docs/kinematics.md §3): the wrapped
/// equivalents of a run with [`IkSettings::wrap`] off (−5.98 rad → 0.30 rad).
pub fn wrapped_equivalent(robot: &Robot, q: &[f64]) -> Vec<f64> {
    robot
        .joints
        .iter()
        .zip(q)
        .map(|(j, v)| j.keep(*v, crate::angles::wrap_to_pi(*v)))
        .collect()
}

impl Default for IkSettings {
    fn default() -> Self {
        IkSettings {
            position_tolerance: 1e-6,
            orientation_tolerance: 1e-6,
            max_iterations: 100,
            budget: 2000,
            restarts: 100,
            seed: 0x5EED_1C0D_E5A1_7A1B,
            max_joint_change: None,
            jacobian: JacobianSource::Geometric,
            record_trace: false,
            wrap: true,
            objective: Objective::HalfSquared,
        }
    }
}

impl IkSettings {
    /// Settings for dragging: a short budget, no restarts (they could pick a far branch)
    /// and at most [`DEFAULT_MAX_JOINT_CHANGE`] per call.
    pub fn drag() -> Self {
        IkSettings {
            max_iterations: 30,
            budget: 30,
            restarts: 0,
            max_joint_change: Some(DEFAULT_MAX_JOINT_CHANGE),
            ..IkSettings::default()
        }
    }

    fn check(&self) -> Result<(), IkError> {
        let positive = |v: f64| v.is_finite() && v > 0.0;
        for (name, value) in [
            ("position_tolerance", self.position_tolerance),
            ("orientation_tolerance", self.orientation_tolerance),
        ] {
            if !positive(value) {
                return Err(IkError::Settings { name, value });
            }
        }
        if let Some(limit) = self.max_joint_change
            && !positive(limit)
        {
            return Err(IkError::Settings {
                name: "max_joint_change",
                value: limit,
            });
        }
        Ok(())
    }
}

/// One iteration of a numeric run, for replaying it step by step.
#[derive(Debug, Clone, PartialEq)]
pub struct IkStep {
    /// The joint vector after this iteration (kept inside the limits / wrapped).
    pub q: Vec<f64>,
    /// The joint vector the step asked for, `q_before + Δq`, before wrapping or clamping
    /// (for the seed entry: the seed as given).
    pub raw_q: Vec<f64>,
    /// The solver's error norm ‖e‖ (linear rows divided by a quarter of the reach, except
    /// for the fixed-step gradient method) at `q`.
    pub error: f64,
    /// Position error at `q`, in the robot's length unit.
    pub position_error: f64,
    /// Orientation error at `q` for the task, radians.
    pub orientation_error: f64,
    /// ‖Δq‖ of the step tried.
    pub step: f64,
    /// The damping λ of the step (damped least squares), else 0.
    pub damping: f64,
    /// Whether the step was taken (damped least squares retries rejected steps).
    pub accepted: bool,
    /// Whether this iteration started a new attempt from a random restart point.
    pub restart: bool,
}

/// The answer of an IK call.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct IkResult {
    /// The joint vector (inside the limits where the method could keep it there).
    pub q: Vec<f64>,
    /// Both errors are within the tolerances.
    pub success: bool,
    /// The target could not be reached: the solver stopped at the closest pose it found
    /// (a minimum of the error), or the closed form has no exact solution.
    pub unreachable: bool,
    /// The closed-form solution chosen sits on a singularity (UR wrist at θ5 = 0, RRR
    /// tool on the base axis, 2R stretched or folded); its free joint kept the seed's value.
    pub singular: bool,
    /// The move was scaled down to the largest joint change per call: `q` lies on the
    /// way to the answer (call again to go on).
    pub clipped: bool,
    /// Every joint of `q` lies within its limits.
    pub within_limits: bool,
    /// ‖p_target − p(q)‖ in the robot's length unit.
    pub position_error: f64,
    /// The task's orientation error (radians): 0 for position only, the angle between the
    /// tool axes (5D), the rotation angle of `R_target·Rᵀ` (full pose).
    pub orientation_error: f64,
    /// Iterations used, restarts included (0 for the closed form).
    pub iterations: usize,
    /// Random restarts used.
    pub restarts: usize,
    /// The per-iteration trace, when [`IkSettings::record_trace`] is on; the first entry
    /// is the seed.
    pub trace: Vec<IkStep>,
}

/// What can be wrong with an IK request, as data; `armlab_text` words it for a person.
#[derive(Debug, Clone, PartialEq)]
pub enum IkError {
    /// The seed does not fit the robot.
    Robot(RobotError),
    /// The target pose holds NaN or infinity, or its rotation is not a rotation.
    Target(BadTarget),
    /// A setting is out of range: it must be a positive number.
    Settings {
        /// The setting's name (`position_tolerance`, …).
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The closed form was asked for an arm that has none here.
    NoClosedForm(String),
    /// A setting that takes one of a few values got another (`objective`, `wrap`).
    SettingChoice {
        /// The setting's name.
        name: &'static str,
        /// The value given, as written (JSON text: `"cubed"`, `2`).
        value: String,
        /// The values it takes, comma-separated (`half-squared, squared`).
        allowed: String,
    },
    /// The target lies farther from the base frame's origin than
    /// [`MAX_TARGET_DISTANCE`]: no arm reaches it, and its error would overflow.
    TargetTooFar {
        /// The target's distance from the base frame's origin (robot units).
        distance: f64,
        /// [`MAX_TARGET_DISTANCE`].
        limit: f64,
    },
}

/// The farthest a target may lie from the base frame's origin, in the robot's length unit:
/// a thousand times the longest length a robot file may hold
/// ([`crate::robot::MAX_LENGTH`]), so every arm's reach is far inside it and
/// the squared error of a target at this distance stays finite.
pub const MAX_TARGET_DISTANCE: f64 = 1e9;

/// What is wrong with a target pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BadTarget {
    /// A value is NaN or infinite.
    NotFinite,
    /// The 3×3 part is not orthonormal with determinant +1.
    NotRotation,
}

impl std::fmt::Display for IkError {
    /// What kind of error this is, for logs; `{:?}` shows its data, and a person reads the
    /// sentence the text catalogue makes of it (`armlab_text::Sentence`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("an IK request that cannot run as given")
    }
}

impl std::error::Error for IkError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            IkError::Robot(e) => Some(e),
            _ => None,
        }
    }
}

impl From<RobotError> for IkError {
    fn from(e: RobotError) -> Self {
        IkError::Robot(e)
    }
}

/// Position and task orientation error of `q` against `target` (robot units, radians).
pub fn pose_error(
    robot: &Robot,
    q: &[f64],
    target: &IsometryMatrix3<f64>,
    task: Task,
) -> (f64, f64) {
    let pose = tool_pose(robot, q);
    let ev = evaluate(&TaskTarget::new(target, task), &pose, 1.0);
    (ev.position_error, ev.orientation_error)
}

/// The task error vector e (docs/kinematics.md §5) of the tool at `pose` against
/// `target`, the linear rows multiplied by `linear_scale`: as many rows as the task has,
/// in the order of [`crate::task_jacobian`]'s rows.
pub fn task_error_vector(
    target: &IsometryMatrix3<f64>,
    pose: &IsometryMatrix3<f64>,
    task: Task,
    linear_scale: f64,
) -> nalgebra::DVector<f64> {
    let ev = evaluate(&TaskTarget::new(target, task), pose, linear_scale);
    nalgebra::DVector::from_iterator(task.rows(), ev.e.iter().copied().take(task.rows()))
}

/// The wrapped-difference distance Σ change(a_i, b_i)² between two joint vectors.
pub fn joint_distance(robot: &Robot, a: &[f64], b: &[f64]) -> f64 {
    robot
        .joints
        .iter()
        .zip(a.iter().zip(b))
        .map(|(j, (x, y))| {
            let d = j.change(*x, *y);
            d * d
        })
        .sum()
}

/// Every joint inside its limits (1e−9 slack)?
pub fn within_limits(robot: &Robot, q: &[f64]) -> bool {
    robot
        .joints
        .iter()
        .zip(q)
        .all(|(j, v)| j.limits.contains(*v, 1e-9))
}

pub(crate) fn check_target(target: &IsometryMatrix3<f64>) -> Result<(), IkError> {
    let t = target.translation.vector;
    let r = target.rotation.matrix();
    if !t.iter().chain(r.iter()).all(|v| v.is_finite()) {
        return Err(IkError::Target(BadTarget::NotFinite));
    }
    let err = (r.transpose() * r - Matrix3::identity()).abs().max();
    if err > 1e-6 || r.determinant() < 0.0 {
        return Err(IkError::Target(BadTarget::NotRotation));
    }
    // Scaled by the largest coordinate: the plain norm of (1e308, 0, 0) overflows.
    let largest = t.abs().max();
    let distance = if largest > 0.0 {
        largest * (t / largest).norm()
    } else {
        0.0
    };
    if distance > MAX_TARGET_DISTANCE {
        return Err(IkError::TargetTooFar {
            distance,
            limit: MAX_TARGET_DISTANCE,
        });
    }
    Ok(())
}

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
fn move_of(joint: &super::robot::Joint, a: f64, b: f64) -> f64 {
    if joint.kind == JointKind::Revolute && !joint.wraps() {
        b - a
    } else {
        joint.change(a, b)
    }
}

/// The per-call limit of one joint: `limit` radians, or for a prismatic joint the same
/// fraction of its stroke as `limit` is of π.
fn joint_limit(joint: &super::robot::Joint, limit: f64) -> f64 {
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

/// A target pose from a position and a rotation matrix (rows), for tests and the API.
pub fn target_pose(position: Vector3<f64>, rotation: Matrix3<f64>) -> IsometryMatrix3<f64> {
    IsometryMatrix3::from_parts(
        nalgebra::Translation3::from(position),
        nalgebra::Rotation3::from_matrix_unchecked(rotation),
    )
}
