//! The JSON API over the core: JSON text in, JSON text out. The `js` feature exposes
//! these functions to JavaScript through wasm-bindgen (see `js.rs` and the README); they
//! are plain Rust here so that native tests cover them too.
//!
//! Every request names a robot — a preset id (`"ur10"`) or a whole robot file object —
//! and a joint vector `q` in the core's units (radians, the robot's length unit).

use nalgebra::{IsometryMatrix3, Matrix3, Matrix6xX};
use serde_json::{Value, json};
use thiserror::Error;

use crate::kinematics::{
    ForwardKinematics, NUMERIC_EPSILON, Orientation, Robot, RobotError, Task, ToolAxis,
    geometric_jacobian, jacobian_measures, numerical_jacobian, preset, preset_ids,
    robot_from_value, robot_to_json, task_jacobian,
};

/// What can go wrong with an API request.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ApiError {
    /// The request is not JSON or lacks a field.
    #[error("Bad request: {0}")]
    Request(String),
    /// The robot or the joint vector is invalid.
    #[error(transparent)]
    Robot(#[from] RobotError),
}

/// A parsed request: the robot and the joint vector.
struct Request {
    value: Value,
    robot: Robot,
    q: Vec<f64>,
}

fn parse_request(text: &str) -> Result<Request, ApiError> {
    let value: Value =
        serde_json::from_str(text).map_err(|e| ApiError::Request(format!("not JSON ({e})")))?;
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
    let m = pose.to_homogeneous();
    json!(
        (0..4)
            .map(|r| (0..4).map(|c| m[(r, c)]).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    )
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
    let list: Vec<Value> = preset_ids()
        .filter_map(|id| preset(id).ok().map(|r| (id, r)))
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

/// Parses a task name: `"position"`, `"axis-x"`, `"axis-y"`, `"axis-z"` or `"full"`.
pub fn parse_task(name: &str) -> Option<Task> {
    match name {
        "position" => Some(Task::Position),
        "axis-x" => Some(Task::PositionAndAxis(ToolAxis::X)),
        "axis-y" => Some(Task::PositionAndAxis(ToolAxis::Y)),
        "axis-z" => Some(Task::PositionAndAxis(ToolAxis::Z)),
        "full" => Some(Task::FullPose),
        _ => None,
    }
}

fn task_of(value: &Value) -> Result<Task, ApiError> {
    match value.get("task") {
        None => Ok(Task::FullPose),
        Some(Value::String(name)) => parse_task(name).ok_or_else(|| {
            ApiError::Request(format!(
                "unknown task \"{name}\": use position, axis-x, axis-y, axis-z or full"
            ))
        }),
        Some(_) => Err(ApiError::Request("\"task\" must be a text".into())),
    }
}

/// Jacobians and measures. Request `{"robot", "q", "task"}` (task defaults to `"full"`).
/// Response: `geometric` and `numerical` (6×n rows; linear rows first), `task_rows`
/// (the unscaled task Jacobian) and the scaled measures: `singular_values`,
/// `manipulability`, `determinant` (null unless square), `condition_number` (null when
/// exactly singular), `near_singular`, `length_scale`.
pub fn jacobian(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    let task = task_of(&req.value)?;
    let fk = ForwardKinematics::new(&req.robot, &req.q)?;
    let geometric: Matrix6xX<f64> = geometric_jacobian(&fk);
    let numerical = numerical_jacobian(&req.robot, &req.q, NUMERIC_EPSILON);
    let rows = task_jacobian(&geometric, task, fk.tool_rotation(), 1.0);
    let m = jacobian_measures(&geometric, task, fk.tool_rotation(), req.robot.reach());
    Ok(json!({
        "robot": req.robot.name,
        "geometric": matrix_rows(&geometric),
        "numerical": matrix_rows(&numerical),
        "task_rows": matrix_rows(&rows),
        "singular_values": m.singular_values,
        "manipulability": m.manipulability,
        "determinant": m.determinant,
        "condition_number": m.condition_number,
        "near_singular": m.near_singular,
        "length_scale": m.length_scale,
    })
    .to_string())
}
