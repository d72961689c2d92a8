//! The JSON API over the core: JSON text in, JSON text out. The `js` feature exposes
//! these functions to JavaScript through wasm-bindgen (see `js.rs` and docs/js-api.md); they
//! are plain Rust here so that native tests cover them too.
//!
//! Every request names a robot — a preset id (`"ur10"`) or a whole robot file object —
//! and a joint vector `q` in the core's units (radians, the robot's length unit).

use nalgebra::{IsometryMatrix3, Matrix3};
use serde_json::{Value, json};
use thiserror::Error;

use armlab_core::fk::homogeneous;
use armlab_core::{
    ForwardKinematics, IkError, IkMethod, JacobianAnalysis, Orientation, Robot, RobotError, Task,
    preset, preset_names, robot_from_value, robot_to_json, task_jacobian,
};
use armlab_text::{Lang, Sentence, echo};

/// What can go wrong with an API request. `Display` is the English sentence the caller
/// reads (the JSON API keeps to English).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ApiError {
    /// The request is not JSON or lacks a field.
    #[error("Bad request: {0}")]
    Request(String),
    /// The robot or the joint vector is invalid.
    #[error("{}", .0.sentence(Lang::En))]
    Robot(#[from] RobotError),
    /// The IK could not run (no closed form for this robot, a target that is not finite,
    /// …); the core's own error, variant and all.
    #[error("{}", .0.sentence(Lang::En))]
    Ik(IkError),
}

impl From<IkError> for ApiError {
    /// A robot error inside an IK error is the robot's; the rest stay IK errors.
    fn from(e: IkError) -> Self {
        match e {
            IkError::Robot(r) => ApiError::Robot(r),
            other => ApiError::Ik(other),
        }
    }
}

/// A parsed request: the robot and the joint vector.
struct Request {
    value: Value,
    robot: Robot,
    q: Vec<f64>,
}

fn parse_request(text: &str) -> Result<Request, ApiError> {
    let value: Value = serde_json::from_str(text).map_err(|e| {
        ApiError::Request(format!(
            "not JSON ({})",
            echo::text_within(&e.to_string(), 80)
        ))
    })?;
    let robot = match value.get("robot") {
        Some(Value::String(id)) => preset(id)?,
        Some(obj @ Value::Object(_)) => robot_from_value(obj)?,
        Some(_) => {
            return Err(ApiError::Request(
                "\"robot\" must be a preset id or a robot file object".into(),
            ));
        }
        None => return Err(ApiError::Request("the field \"robot\" is missing".into())),
    };
    let q = match value.get("q") {
        None => robot.home(),
        Some(Value::Array(list)) => list
            .iter()
            .map(|v| v.as_f64())
            .collect::<Option<Vec<f64>>>()
            .ok_or_else(|| ApiError::Request("\"q\" must be a list of numbers".into()))?,
        Some(_) => return Err(ApiError::Request("\"q\" must be a list of numbers".into())),
    };
    robot.check_q(&q)?;
    Ok(Request { value, robot, q })
}

/// Rows of a pose's 4×4 homogeneous matrix.
pub fn pose_rows(pose: &IsometryMatrix3<f64>) -> Value {
    matrix_rows(&homogeneous(pose))
}

fn matrix_rows<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Value {
    json!(
        (0..m.nrows())
            .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    )
}

/// The four orientation forms as JSON (angles in radians).
pub fn orientation_json(r: &Matrix3<f64>) -> Value {
    let o = Orientation::from_rotation(r);
    json!({
        "zyx_euler": { "alpha": o.zyx_euler.alpha, "beta": o.zyx_euler.beta, "gamma": o.zyx_euler.gamma, "degenerate": o.zyx_euler.degenerate },
        "xyz_fixed": { "gamma": o.xyz_fixed.gamma, "beta": o.xyz_fixed.beta, "alpha": o.xyz_fixed.alpha, "degenerate": o.xyz_fixed.degenerate },
        "angle_axis": { "angle": o.angle_axis.angle, "axis": [o.angle_axis.axis.x, o.angle_axis.axis.y, o.angle_axis.axis.z], "degenerate": o.angle_axis.degenerate },
        "euler_parameters": [o.euler_parameters.e1, o.euler_parameters.e2, o.euler_parameters.e3, o.euler_parameters.e4],
    })
}

/// The presets: `[{"id", "name", "dof", "convention", "length_unit"}]`.
pub fn presets() -> String {
    let list: Vec<Value> = preset_names()
        .iter()
        .filter_map(|(id, _)| preset(id).ok().map(|r| (id, r)))
        .map(|(id, r)| {
            json!({ "id": id, "name": r.name, "dof": r.dof(), "convention": r.convention.as_str(), "length_unit": r.length_unit.symbol() })
        })
        .collect();
    Value::Array(list).to_string()
}

/// The robot file of a preset (or the normalised file of a robot object), as JSON text.
pub fn robot(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    Ok(robot_to_json(&req.robot))
}

/// Forward kinematics. Request `{"robot", "q"}` (q defaults to the robot's home).
/// Response: `tool` (4×4 rows of T_0n), `position`, `orientation` (the four forms),
/// `links` (every A_i) and `frames` (every T_0i), plus the robot's name and length unit.
pub fn fk(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    let fk = ForwardKinematics::new(&req.robot, &req.q)?;
    let p = fk.tool_position();
    Ok(json!({
        "robot": req.robot.name,
        "length_unit": req.robot.length_unit.symbol(),
        "q": req.q,
        "tool": pose_rows(&fk.base_from_tool),
        "position": [p.x, p.y, p.z],
        "orientation": orientation_json(fk.tool_rotation()),
        "links": fk.link_transforms.iter().map(pose_rows).collect::<Vec<_>>(),
        "frames": fk.base_from_frames.iter().map(pose_rows).collect::<Vec<_>>(),
    })
    .to_string())
}

fn task_of(value: &Value) -> Result<Task, ApiError> {
    match value.get("task") {
        None => Ok(Task::FullPose),
        Some(Value::String(name)) => Task::from_id(name).ok_or_else(|| {
            ApiError::Request(format!(
                "unknown task \"{}\": use one of {}",
                echo::text(name),
                Task::id_list()
            ))
        }),
        Some(_) => Err(ApiError::Request("\"task\" must be a text".into())),
    }
}

/// Jacobians and measures. Request `{"robot", "q", "task"}` (task defaults to `"full"`).
/// Response: `geometric` and `numerical` (6×n rows; linear rows first), `task_rows`
/// (the unscaled task Jacobian) and the scaled measures: `singular_values`,
/// `manipulability`, `determinant` (null unless square), `condition_number` (null when
/// exactly singular), `near_singular`, `length_scale`; and `displayed`: the
/// manipulability, determinant and condition number of the unscaled task rows, in the
/// robot's units.
pub fn jacobian(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    let task = task_of(&req.value)?;
    let fk = ForwardKinematics::new(&req.robot, &req.q)?;
    let analysis = JacobianAnalysis::new(&req.robot, &fk, &req.q, task);
    let rows = task_jacobian(&analysis.geometric, task, fk.tool_rotation(), 1.0);
    let m = &analysis.measures;
    Ok(json!({
        "robot": req.robot.name,
        "geometric": matrix_rows(&analysis.geometric),
        "numerical": matrix_rows(&analysis.numerical),
        "task_rows": matrix_rows(&rows),
        "singular_values": m.singular_values,
        "manipulability": m.manipulability,
        "determinant": m.determinant,
        "condition_number": m.condition_number,
        "near_singular": m.near_singular,
        "length_scale": m.length_scale,
        "displayed": {
            "manipulability": m.displayed.manipulability,
            "determinant": m.displayed.determinant,
            "condition_number": m.displayed.condition_number,
        },
    })
    .to_string())
}

fn number_list(value: &Value, what: &str) -> Result<Vec<f64>, ApiError> {
    value
        .as_array()
        .and_then(|list| list.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>())
        .ok_or_else(|| ApiError::Request(format!("\"{what}\" must be a list of numbers")))
}

fn rows_matrix<const R: usize>(value: &Value, what: &str) -> Result<[[f64; 3]; R], ApiError> {
    let bad = || ApiError::Request(format!("\"{what}\" must be {R} rows of numbers"));
    let rows = value.as_array().ok_or_else(bad)?;
    if rows.len() != R {
        return Err(bad());
    }
    let mut out = [[0.0; 3]; R];
    for (r, row) in rows.iter().enumerate() {
        let row = number_list(row, what)?;
        if row.len() < 3 {
            return Err(bad());
        }
        out[r].copy_from_slice(&row[..3]);
    }
    Ok(out)
}

/// The target of an `ik` request: 4×4 rows, `{"position", "rotation"}` or `{"q"}`.
fn ik_target(robot: &Robot, value: Option<&Value>) -> Result<IsometryMatrix3<f64>, ApiError> {
    let value = value.ok_or_else(|| ApiError::Request("the field \"target\" is missing".into()))?;
    if let Some(rows) = value.as_array() {
        if rows.len() != 4 {
            return Err(ApiError::Request(
                "\"target\" must be 4 rows of 4 numbers".into(),
            ));
        }
        let last = number_list(&rows[3], "target")?;
        if last.len() != 4 || last != [0.0, 0.0, 0.0, 1.0] {
            return Err(ApiError::Request(
                "the last row of \"target\" must be [0, 0, 0, 1]".into(),
            ));
        }
        let mut r = [[0.0; 3]; 3];
        let mut t = [0.0; 3];
        for k in 0..3 {
            let row = number_list(&rows[k], "target")?;
            if row.len() != 4 {
                return Err(ApiError::Request(
                    "\"target\" must be 4 rows of 4 numbers".into(),
                ));
            }
            r[k].copy_from_slice(&row[..3]);
            t[k] = row[3];
        }
        return Ok(armlab_core::ik::target_pose(
            t.into(),
            Matrix3::from_fn(|i, j| r[i][j]),
        ));
    }
    if let Some(q) = value.get("q") {
        let q = number_list(q, "target.q")?;
        robot.check_q(&q)?;
        return Ok(armlab_core::tool_pose(robot, &q));
    }
    let position = value
        .get("position")
        .ok_or_else(|| {
            ApiError::Request(
                "\"target\" must be 4×4 rows, {\"position\", \"rotation\"} or {\"q\"}".into(),
            )
        })
        .and_then(|p| number_list(p, "target.position"))?;
    if position.len() != 3 {
        return Err(ApiError::Request(
            "\"target.position\" must be 3 numbers".into(),
        ));
    }
    let rotation = match value.get("rotation") {
        None => Matrix3::identity(),
        Some(rows) => {
            let r = rows_matrix::<3>(rows, "target.rotation")?;
            Matrix3::from_fn(|i, j| r[i][j])
        }
    };
    Ok(armlab_core::ik::target_pose(
        nalgebra::Vector3::new(position[0], position[1], position[2]),
        rotation,
    ))
}

fn ik_method(value: &Value) -> Result<IkMethod, ApiError> {
    let alpha = match value.get("alpha") {
        None | Some(Value::Null) => None,
        Some(v) => Some(
            v.as_f64()
                .filter(|a| a.is_finite() && *a > 0.0)
                .ok_or_else(|| ApiError::Request("\"alpha\" must be a positive number".into()))?,
        ),
    };
    match value.get("method") {
        None => Ok(IkMethod::DampedLeastSquares),
        Some(Value::String(id)) => match IkMethod::from_id(id) {
            Some(IkMethod::JacobianTranspose { .. }) => Ok(IkMethod::JacobianTranspose { alpha }),
            Some(method) => Ok(method),
            None => Err(ApiError::Request(format!(
                "unknown method \"{}\": use one of {} (or closed-form)",
                echo::text(id),
                IkMethod::id_list()
            ))),
        },
        Some(_) => Err(ApiError::Request(format!(
            "\"method\" must be a text: one of {}",
            IkMethod::id_list()
        ))),
    }
}

/// The typed error of a setting that takes one of a few values.
fn setting_choice(name: &'static str, value: &Value, allowed: String) -> ApiError {
    ApiError::Ik(IkError::SettingChoice {
        name,
        value: value.to_string(),
        allowed,
    })
}

/// The most iterations an `ik` request may ask for, per attempt (`max_iterations`) and per
/// call (`budget`); larger values are lowered to it (or to [`iteration_cap`]'s smaller
/// figure for a large arm).
pub const MAX_ITERATIONS: usize = 50_000;
/// The most random restarts an `ik` request may ask for; larger values are lowered to it.
pub const MAX_RESTARTS: usize = 1_000;
/// The work one `ik` call may do, counted in joint transforms (one joint of one forward
/// kinematics): 50 million take about a second natively for the slowest arm and method
/// measured (64 joints, the central-difference Jacobian). [`MAX_ITERATIONS`] bounds the
/// small arms, whose iteration costs more than its joint transforms (the pseudo-inverse's
/// eigen-decomposition: 100 000 iterations took 1.6 s on the RRR arm, on a loaded machine).
pub const MAX_JOINT_TRANSFORMS: usize = 50_000_000;
/// The most numbers a recorded trace may hold (each entry holds 2n + 7): it bounds the
/// response's size (about 5 MB of JSON) and the time its recording takes (the fuzzer's
/// slowest inputs were traced runs: 2.5 s with a million numbers).
pub const MAX_TRACE_NUMBERS: usize = 250_000;

/// The iteration cap of one `ik` call for `robot`: [`MAX_ITERATIONS`], lowered so that the
/// call stays within [`MAX_JOINT_TRANSFORMS`] (an iteration costs about 2n joint
/// transforms with the geometric Jacobian, 2n² + 2n with central differences) and, with a
/// trace, within [`MAX_TRACE_NUMBERS`]. At least 1000.
pub fn iteration_cap(robot: &Robot, jacobian: armlab_core::JacobianSource, trace: bool) -> usize {
    let n = robot.dof().max(1);
    let per_iteration = match jacobian {
        armlab_core::JacobianSource::Geometric => 2 * n,
        armlab_core::JacobianSource::CentralDifference => 2 * n * n + 2 * n,
    };
    let mut cap = MAX_ITERATIONS.min(MAX_JOINT_TRANSFORMS / per_iteration);
    if trace {
        cap = cap.min(MAX_TRACE_NUMBERS / (2 * n + 7));
    }
    cap.max(1000)
}

fn ik_settings(value: &Value, drag: bool) -> Result<armlab_core::IkSettings, ApiError> {
    use armlab_core::{IkSettings, JacobianSource};
    let mut s = if drag {
        IkSettings::drag()
    } else {
        IkSettings::default()
    };
    s.jacobian = match value.get("jacobian").map(|v| v.as_str()) {
        None | Some(Some("geometric")) => JacobianSource::Geometric,
        Some(Some("numerical")) => JacobianSource::CentralDifference,
        _ => {
            return Err(ApiError::Request(
                "\"jacobian\" must be \"geometric\" or \"numerical\"".into(),
            ));
        }
    };
    let Some(obj) = value.get("settings") else {
        return Ok(s);
    };
    let obj = obj
        .as_object()
        .ok_or_else(|| ApiError::Request("\"settings\" must be an object".into()))?;
    for (key, v) in obj {
        let number = || {
            v.as_f64().ok_or_else(|| {
                ApiError::Request(format!("\"settings.{}\" must be a number", echo::text(key)))
            })
        };
        let count = || {
            v.as_u64()
                .map(|n| usize::try_from(n).unwrap_or(usize::MAX))
                .ok_or_else(|| {
                    ApiError::Request(format!(
                        "\"settings.{}\" must be a whole number ≥ 0",
                        echo::text(key)
                    ))
                })
        };
        match key.as_str() {
            "position_tolerance" => s.position_tolerance = number()?,
            "orientation_tolerance" => s.orientation_tolerance = number()?,
            "max_iterations" => s.max_iterations = count()?,
            "budget" => s.budget = count()?,
            "restarts" => s.restarts = count()?.min(MAX_RESTARTS),
            "seed" => {
                s.seed = v.as_u64().ok_or_else(|| {
                    ApiError::Request("\"settings.seed\" must be a whole number ≥ 0".into())
                })?
            }
            "max_joint_change" => {
                s.max_joint_change = if v.is_null() { None } else { Some(number()?) }
            }
            "trace" => {
                s.record_trace = v.as_bool().ok_or_else(|| {
                    ApiError::Request("\"settings.trace\" must be true or false".into())
                })?
            }
            "wrap" => {
                s.wrap = v
                    .as_bool()
                    .ok_or_else(|| setting_choice("wrap", v, "true, false".into()))?
            }
            "objective" => {
                s.objective = v
                    .as_str()
                    .and_then(armlab_core::Objective::from_id)
                    .ok_or_else(|| {
                        setting_choice("objective", v, armlab_core::Objective::id_list())
                    })?
            }
            other => {
                return Err(ApiError::Request(format!(
                    "\"settings.{}\" is not known; the known settings are: position_tolerance, orientation_tolerance, max_iterations, budget, restarts, seed, max_joint_change, trace, wrap, objective",
                    echo::text(other)
                )));
            }
        }
    }
    Ok(s)
}

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
///   [`MAX_RESTARTS`].
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
    let req = parse_request(request)?;
    let task = task_of(&req.value)?;
    let target = ik_target(&req.robot, req.value.get("target"))?;
    let method = ik_method(&req.value)?;
    let drag = match req.value.get("drag") {
        None => false,
        Some(v) => v
            .as_bool()
            .ok_or_else(|| ApiError::Request("\"drag\" must be true or false".into()))?,
    };
    let mut settings = ik_settings(&req.value, drag)?;
    let cap = iteration_cap(&req.robot, settings.jacobian, settings.record_trace);
    settings.max_iterations = settings.max_iterations.min(cap);
    settings.budget = settings.budget.min(cap);
    let mut solver = IkSolver::new();
    let r = if drag {
        solver.drag_step(&req.robot, &req.q, &target, task, method, &settings)
    } else {
        solver.solve(&req.robot, &target, task, &req.q, method, &settings)
    }?;
    let trace: Vec<Value> = r
        .trace
        .iter()
        .map(|s| {
            json!({
                "q": s.q, "raw_q": s.raw_q, "error": s.error,
                "position_error": s.position_error, "orientation_error": s.orientation_error,
                "step": s.step, "damping": s.damping, "accepted": s.accepted, "restart": s.restart,
            })
        })
        .collect();
    let mut out = json!({
        "robot": req.robot.name,
        "method": method.id(),
        "q": r.q,
        "success": r.success,
        "unreachable": r.unreachable,
        "singular": r.singular,
        "clipped": r.clipped,
        "within_limits": r.within_limits,
        "position_error": r.position_error,
        "orientation_error": r.orientation_error,
        "iterations": r.iterations,
        "restarts": r.restarts,
        "tool": pose_rows(&tool_pose(&req.robot, &r.q)),
        "wrapped_q": armlab_core::wrapped_equivalent(&req.robot, &r.q),
        "trace": trace,
    });
    if method == IkMethod::ClosedForm {
        let set = closed_form_solutions(&req.robot, &target, &req.q)?;
        if let Some(obj) = out.as_object_mut() {
            obj.insert("family".into(), json!(set.family.name()));
            obj.insert(
                "solutions".into(),
                json!(
                    set.solutions
                        .iter()
                        .map(|s| json!({
                            "q": s.q, "label": s.label(), "within_limits": s.within_limits,
                            "singular": s.singular, "exact": s.exact,
                            "free_joints": s.free_joints,
                            "coincident": s.coincident.iter().map(|b| b.id()).collect::<Vec<_>>(),
                        }))
                        .collect::<Vec<_>>()
                ),
            );
        }
    }
    Ok(out.to_string())
}
