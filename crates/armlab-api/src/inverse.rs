//! The `ik` verb: inverse kinematics by every method, and its answer. Its request's own
//! fields are read in [`crate::ik_request`].

use serde::Serialize;

use crate::ApiError;
use crate::answer::{Rows, answer, homogeneous_rows};
use crate::ik_request::{ik_method, ik_settings, ik_target, iteration_cap};
use crate::request::{parse_request, read, says, task_of};
use armlab_core::IkMethod;

/// Inverse kinematics. Request:
///
/// ```json
/// { "robot": "ur10", "q": [0, 0, 0, 0, 0, 0],
///   "target": [[1, 0, 0, 1000], [0, 0, -1, -256.1], [0, 1, 0, 400], [0, 0, 0, 1]],
///   "task": "full", "method": "dls", "drag": false,
///   "settings": { "position_tolerance": 1e-6, "trace": true } }
/// ```
///
/// - `q`: the seed (the current joint vector when dragging); defaults to the home pose.
/// - `target`: the tool pose as 4×4 rows, or `{"position": [x, y, z], "rotation": 3×3
///   rows}` (rotation defaults to identity), or `{"q": [...]}` (the pose FK(q)); in the
///   robot's length unit.
/// - `task`: `"position"`, `"axis-x"`, `"axis-y"`, `"axis-z"` or `"full"` (default).
/// - `method`: `"dls"` (default), `"pinv"`, `"gradient"` (with `"alpha"`: a fixed step in
///   the robot's units; without: adaptive) or `"closed"` (also read as `"closed-form"`);
///   the response's `method` is the id (`"closed"`); `"jacobian"`:
///   `"geometric"` (default) or `"numerical"` (central differences).
/// - `drag`: one drag frame (`drag_step`: drag settings, moves at most
///   `max_joint_change`, default 0.1 rad, per call).
/// - `settings`: `position_tolerance` (metres), `orientation_tolerance` (rad),
///   `max_iterations` (per attempt), `budget` (iterations per call), `restarts`, `seed`,
///   `max_joint_change` (rad, or null), `trace` (record every iteration), `wrap`
///   (true by default; false leaves the angles as the steps accumulate them),
///   `objective` (`"half-squared"` by default, or `"squared"`: the fixed-step gradient
///   descends ‖e‖², a step of 2α·Jᵀe). So that no call takes more than about a second,
///   `max_iterations` and `budget` are lowered to [`iteration_cap`] and `restarts` to
///   [`MAX_RESTARTS`](crate::MAX_RESTARTS).
///
/// Response: `q`, `success`, `unreachable`, `singular`, `clipped`, `within_limits`,
/// `position_error` (robot units), `orientation_error` (rad), `iterations`, `restarts`,
/// `tool` (4×4 rows of FK(q)), `wrapped_q` (q's wrapped equivalents), `trace` (list of `{q, raw_q, error, position_error,
/// orientation_error, step, damping, accepted, restart}`; empty unless asked for) and,
/// for the closed form, `solutions` (every branch: `{q, label, within_limits, singular,
/// exact, free_joints, coincident}`; `label` and `coincident` are branch ids such as
/// `"right-up-noflip"`) with `family`.
pub fn ik(request: &str) -> Result<String, ApiError> {
    use armlab_core::{IkSolver, closed_form_solutions, tool_pose};
    let mut req = parse_request(request)?;
    let task = task_of(&mut req.fields)?;
    let target = ik_target(&req.robot, req.fields.target.as_ref())?;
    let method = ik_method(&mut req.fields)?;
    let drag = read(
        req.fields.drag.take(),
        says("\"drag\" must be true or false"),
    )?
    .unwrap_or(false);
    let mut settings = ik_settings(&mut req.fields, drag)?;
    let cap = iteration_cap(&req.robot, settings.jacobian, settings.record_trace);
    settings.max_iterations = settings.max_iterations.min(cap);
    settings.budget = settings.budget.min(cap);
    let mut solver = IkSolver::new();
    let r = if drag {
        solver.drag_step(&req.robot, &req.q, &target, task, method, &settings)
    } else {
        solver.solve(&req.robot, &target, task, &req.q, method, &settings)
    }?;
    let set = if method == IkMethod::ClosedForm {
        Some(closed_form_solutions(&req.robot, &target, &req.q)?)
    } else {
        None
    };
    let (family, solutions) = match &set {
        Some(set) => {
            let solutions = set
                .solutions
                .iter()
                .map(|s| SolutionResponse {
                    q: &s.q,
                    label: s.label(),
                    within_limits: s.within_limits,
                    singular: s.singular,
                    exact: s.exact,
                    free_joints: &s.free_joints,
                    coincident: s.coincident.iter().map(|b| b.id()).collect(),
                })
                .collect();
            (Some(set.family.name()), Some(solutions))
        }
        None => (None, None),
    };
    answer(&IkResponse {
        robot: &req.robot.name,
        method: method.id(),
        q: &r.q,
        success: r.success,
        unreachable: r.unreachable,
        singular: r.singular,
        clipped: r.clipped,
        within_limits: r.within_limits,
        position_error: r.position_error,
        orientation_error: r.orientation_error,
        iterations: r.iterations,
        restarts: r.restarts,
        tool: homogeneous_rows(&tool_pose(&req.robot, &r.q)),
        wrapped_q: armlab_core::wrapped_equivalent(&req.robot, &r.q),
        trace: r.trace.iter().map(StepResponse::from).collect(),
        family,
        solutions,
    })
}

/// The answer of [`ik`] (its documentation lists the fields).
#[derive(Serialize)]
struct IkResponse<'a> {
    robot: &'a str,
    method: &'static str,
    q: &'a [f64],
    success: bool,
    unreachable: bool,
    singular: bool,
    clipped: bool,
    within_limits: bool,
    position_error: f64,
    orientation_error: f64,
    iterations: usize,
    restarts: usize,
    tool: Rows,
    wrapped_q: Vec<f64>,
    trace: Vec<StepResponse<'a>>,
    /// The closed form's family (`"ur"`, …); only for the closed form.
    #[serde(skip_serializing_if = "Option::is_none")]
    family: Option<&'static str>,
    /// Every branch of the closed form; only for the closed form.
    #[serde(skip_serializing_if = "Option::is_none")]
    solutions: Option<Vec<SolutionResponse<'a>>>,
}

/// One iteration of a traced `ik` run.
#[derive(Serialize)]
struct StepResponse<'a> {
    q: &'a [f64],
    raw_q: &'a [f64],
    error: f64,
    position_error: f64,
    orientation_error: f64,
    step: f64,
    damping: f64,
    accepted: bool,
    restart: bool,
}

impl<'a> From<&'a armlab_core::IkStep> for StepResponse<'a> {
    fn from(s: &'a armlab_core::IkStep) -> Self {
        StepResponse {
            q: &s.q,
            raw_q: &s.raw_q,
            error: s.error,
            position_error: s.position_error,
            orientation_error: s.orientation_error,
            step: s.step,
            damping: s.damping,
            accepted: s.accepted,
            restart: s.restart,
        }
    }
}

/// One branch of the closed form in an `ik` answer.
#[derive(Serialize)]
struct SolutionResponse<'a> {
    q: &'a [f64],
    /// The branch id (`"right-up-noflip"`).
    label: String,
    within_limits: bool,
    singular: bool,
    exact: bool,
    free_joints: &'a [usize],
    /// The ids of the branches that coincide with this one here.
    coincident: Vec<String>,
}
