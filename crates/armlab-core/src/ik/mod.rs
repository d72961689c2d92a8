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
mod error;
mod numeric;
mod seeds;
mod solver;
mod task_error;

use nalgebra::{IsometryMatrix3, Matrix3, Vector3};

use super::fk::tool_pose;
use super::jacobian::Task;
use super::robot::Robot;

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
pub use error::{BadTarget, IkError, MAX_TARGET_DISTANCE};
pub use seeds::{MAX_SEED_TABLE, SeedTable};
pub use solver::{IkSolver, drag_step, solve};
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

/// A target pose from a position and a rotation matrix (rows), for tests and the API.
pub fn target_pose(position: Vector3<f64>, rotation: Matrix3<f64>) -> IsometryMatrix3<f64> {
    IsometryMatrix3::from_parts(
        nalgebra::Translation3::from(position),
        nalgebra::Rotation3::from_matrix_unchecked(rotation),
    )
}
