//! The JSON API over the core: JSON text in, JSON text out. The `js` feature exposes
//! these functions to JavaScript through wasm-bindgen (see `js.rs` and docs/js-api.md); they
//! are plain Rust here so that native tests cover them too.
//!
//! Every request names a robot — a preset id (`"ur10"`) or a whole robot file object —
//! and a joint vector `q` in the core's units (radians, the robot's length unit).

use std::collections::BTreeMap;

use nalgebra::{IsometryMatrix3, Matrix3};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize};
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

/// A request field as serde read it: its value, or, when the JSON holds another type, that
/// JSON as given. A wrong type is not an error of the whole request here: the function that
/// reads the field answers with the sentence naming it (serde's own message names
/// neither the field nor what a person should write).
enum Field<T> {
    /// The field has the type asked for.
    Given(T),
    /// The field holds something else.
    Wrong(Value),
}

impl<'de, T: DeserializeOwned> Deserialize<'de> for Field<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        Ok(match T::deserialize(&value) {
            Ok(given) => Field::Given(given),
            Err(_) => Field::Wrong(value),
        })
    }
}

/// For `deserialize_with`: a field that is there, `null` included. Without it serde reads
/// `null` as an absent `Option`, and `"q": null` would quietly mean the home pose.
fn present<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<Option<T>, D::Error> {
    T::deserialize(deserializer).map(Some)
}

/// The value of an optional field, or the field's sentence when it holds another type.
fn read<T>(
    field: Option<Field<T>>,
    wrong: impl FnOnce(&Value) -> ApiError,
) -> Result<Option<T>, ApiError> {
    match field {
        None => Ok(None),
        Some(Field::Given(value)) => Ok(Some(value)),
        Some(Field::Wrong(value)) => Err(wrong(&value)),
    }
}

/// A request's sentence that does not depend on the value given.
fn says(sentence: &'static str) -> impl FnOnce(&Value) -> ApiError {
    move |_| ApiError::Request(sentence.into())
}

/// The fields of a request; each function reads those it takes, and ignores the others
/// (and fields it does not know).
#[derive(Deserialize)]
struct RequestFields {
    /// A preset id or a robot file object; checked by the robot's own parser.
    #[serde(default, deserialize_with = "present")]
    robot: Option<Value>,
    #[serde(default, deserialize_with = "present")]
    q: Option<Field<Vec<f64>>>,
    #[serde(default, deserialize_with = "present")]
    task: Option<Field<String>>,
    /// 4×4 rows, `{"position", "rotation"}` or `{"q"}` ([`ik_target`]).
    #[serde(default, deserialize_with = "present")]
    target: Option<Value>,
    #[serde(default, deserialize_with = "present")]
    method: Option<Field<String>>,
    /// `null` reads as absent (the adaptive step).
    #[serde(default)]
    alpha: Option<Field<f64>>,
    #[serde(default, deserialize_with = "present")]
    jacobian: Option<Field<String>>,
    #[serde(default, deserialize_with = "present")]
    drag: Option<Field<bool>>,
    #[serde(default, deserialize_with = "present")]
    settings: Option<Field<SettingsFields>>,
}

/// The `settings` of an `ik` request ([`ik`] lists them).
#[derive(Deserialize)]
struct SettingsFields {
    #[serde(default, deserialize_with = "present")]
    position_tolerance: Option<Field<f64>>,
    #[serde(default, deserialize_with = "present")]
    orientation_tolerance: Option<Field<f64>>,
    #[serde(default, deserialize_with = "present")]
    max_iterations: Option<Field<u64>>,
    #[serde(default, deserialize_with = "present")]
    budget: Option<Field<u64>>,
    #[serde(default, deserialize_with = "present")]
    restarts: Option<Field<u64>>,
    #[serde(default, deserialize_with = "present")]
    seed: Option<Field<u64>>,
    /// `null` is taken: no limit of its own (a drag then keeps its default step).
    #[serde(default, deserialize_with = "present")]
    max_joint_change: Option<Field<Option<f64>>>,
    #[serde(default, deserialize_with = "present")]
    trace: Option<Field<bool>>,
    #[serde(default, deserialize_with = "present")]
    wrap: Option<Field<bool>>,
    #[serde(default, deserialize_with = "present")]
    objective: Option<Field<String>>,
    /// Every other key: each is refused with the list of known settings.
    #[serde(flatten)]
    unknown: BTreeMap<String, Value>,
}

/// A parsed request: the robot, the joint vector and the other fields, unread.
struct Request {
    fields: RequestFields,
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
    // Serde would read a list as the fields in their order; a request names its fields.
    if !value.is_object() {
        return Err(ApiError::Request("the field \"robot\" is missing".into()));
    }
    // Every field is a `Field` or a JSON value, which take any JSON: this cannot fail, and
    // a wrong type is answered by the field's reader below.
    let mut fields = RequestFields::deserialize(value)
        .map_err(|e| ApiError::Request(echo::text_within(&e.to_string(), 80)))?;
    let robot = match fields.robot.take() {
        Some(Value::String(id)) => preset(&id)?,
        Some(obj @ Value::Object(_)) => robot_from_value(&obj)?,
        Some(_) => {
            return Err(ApiError::Request(
                "\"robot\" must be a preset id or a robot file object".into(),
            ));
        }
        None => return Err(ApiError::Request("the field \"robot\" is missing".into())),
    };
    let q = match read(fields.q.take(), says("\"q\" must be a list of numbers"))? {
        Some(q) => q,
        None => robot.home(),
    };
    robot.check_q(&q)?;
    Ok(Request { fields, robot, q })
}

/// Rows of a matrix.
type Rows = Vec<Vec<f64>>;

/// Rows of a pose's 4×4 homogeneous matrix.
pub fn pose_rows(pose: &IsometryMatrix3<f64>) -> Value {
    json!(homogeneous_rows(pose))
}

fn homogeneous_rows(pose: &IsometryMatrix3<f64>) -> Rows {
    matrix_rows(&homogeneous(pose))
}

fn matrix_rows<R: nalgebra::Dim, C: nalgebra::Dim, S: nalgebra::RawStorage<f64, R, C>>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Rows {
    (0..m.nrows())
        .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect())
        .collect()
}

/// The four orientation forms (angles in radians).
#[derive(Serialize)]
struct OrientationForms {
    zyx_euler: EulerAngles,
    xyz_fixed: EulerAngles,
    angle_axis: AngleAxis,
    /// e1, e2, e3, e4 (the scalar last).
    euler_parameters: [f64; 4],
}

/// Three angles about three axes; `degenerate` at a gimbal lock.
#[derive(Serialize)]
struct EulerAngles {
    alpha: f64,
    beta: f64,
    gamma: f64,
    degenerate: bool,
}

/// A rotation angle about a unit axis; `degenerate` when the angle is 0 or π.
#[derive(Serialize)]
struct AngleAxis {
    angle: f64,
    axis: [f64; 3],
    degenerate: bool,
}

impl OrientationForms {
    fn new(r: &Matrix3<f64>) -> Self {
        let o = Orientation::from_rotation(r);
        OrientationForms {
            zyx_euler: EulerAngles {
                alpha: o.zyx_euler.alpha,
                beta: o.zyx_euler.beta,
                gamma: o.zyx_euler.gamma,
                degenerate: o.zyx_euler.degenerate,
            },
            xyz_fixed: EulerAngles {
                alpha: o.xyz_fixed.alpha,
                beta: o.xyz_fixed.beta,
                gamma: o.xyz_fixed.gamma,
                degenerate: o.xyz_fixed.degenerate,
            },
            angle_axis: AngleAxis {
                angle: o.angle_axis.angle,
                axis: [
                    o.angle_axis.axis.x,
                    o.angle_axis.axis.y,
                    o.angle_axis.axis.z,
                ],
                degenerate: o.angle_axis.degenerate,
            },
            euler_parameters: [
                o.euler_parameters.e1,
                o.euler_parameters.e2,
                o.euler_parameters.e3,
                o.euler_parameters.e4,
            ],
        }
    }
}

/// The four orientation forms as JSON (angles in radians).
pub fn orientation_json(r: &Matrix3<f64>) -> Value {
    serde_json::to_value(OrientationForms::new(r)).unwrap_or(Value::Null)
}

/// A response as JSON text. Writing these structs cannot fail (their maps have text keys);
/// were it to, the caller gets a sentence, not a panic.
fn answer(response: &impl Serialize) -> Result<String, ApiError> {
    serde_json::to_string(response).map_err(|e| ApiError::Request(e.to_string()))
}

/// One preset in the list of [`presets`].
#[derive(Serialize)]
struct PresetSummary<'a> {
    id: &'a str,
    name: &'a str,
    dof: usize,
    convention: &'static str,
    length_unit: &'static str,
}

/// The presets: `[{"id", "name", "dof", "convention", "length_unit"}]`.
pub fn presets() -> String {
    let robots: Vec<(&str, Robot)> = preset_names()
        .iter()
        .filter_map(|(id, _)| preset(id).ok().map(|r| (*id, r)))
        .collect();
    let list: Vec<PresetSummary> = robots
        .iter()
        .map(|(id, r)| PresetSummary {
            id,
            name: &r.name,
            dof: r.dof(),
            convention: r.convention.as_str(),
            length_unit: r.length_unit.symbol(),
        })
        .collect();
    answer(&list).unwrap_or_else(|_| "[]".into())
}

/// The robot file of a preset (or the normalised file of a robot object), as JSON text.
pub fn robot(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    Ok(robot_to_json(&req.robot))
}

/// The answer of [`fk`].
#[derive(Serialize)]
struct FkResponse<'a> {
    robot: &'a str,
    length_unit: &'static str,
    q: &'a [f64],
    /// T_0n (tool included) as 4 rows.
    tool: Rows,
    position: [f64; 3],
    orientation: OrientationForms,
    /// Every A_i.
    links: Vec<Rows>,
    /// Every T_0i.
    frames: Vec<Rows>,
}

/// Forward kinematics. Request `{"robot", "q"}` (q defaults to the robot's home).
/// Response: `tool` (4×4 rows of T_0n), `position`, `orientation` (the four forms),
/// `links` (every A_i) and `frames` (every T_0i), plus the robot's name and length unit.
pub fn fk(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    let fk = ForwardKinematics::new(&req.robot, &req.q)?;
    let p = fk.tool_position();
    answer(&FkResponse {
        robot: &req.robot.name,
        length_unit: req.robot.length_unit.symbol(),
        q: &req.q,
        tool: homogeneous_rows(&fk.base_from_tool),
        position: [p.x, p.y, p.z],
        orientation: OrientationForms::new(fk.tool_rotation()),
        links: fk.link_transforms.iter().map(homogeneous_rows).collect(),
        frames: fk.base_from_frames.iter().map(homogeneous_rows).collect(),
    })
}

fn task_of(fields: &mut RequestFields) -> Result<Task, ApiError> {
    let Some(name) = read(fields.task.take(), says("\"task\" must be a text"))? else {
        return Ok(Task::FullPose);
    };
    Task::from_id(&name).ok_or_else(|| {
        ApiError::Request(format!(
            "unknown task \"{}\": use one of {}",
            echo::text(&name),
            Task::id_list()
        ))
    })
}

/// The answer of [`jacobian`].
#[derive(Serialize)]
struct JacobianResponse<'a> {
    robot: &'a str,
    geometric: Rows,
    numerical: Rows,
    task_rows: Rows,
    singular_values: &'a [f64],
    manipulability: f64,
    determinant: Option<f64>,
    condition_number: Option<f64>,
    near_singular: bool,
    length_scale: f64,
    displayed: DisplayedResponse,
}

/// The measures of the unscaled task rows, in the robot's units.
#[derive(Serialize)]
struct DisplayedResponse {
    manipulability: f64,
    determinant: Option<f64>,
    condition_number: Option<f64>,
}

/// Jacobians and measures. Request `{"robot", "q", "task"}` (task defaults to `"full"`).
/// Response: `geometric` and `numerical` (6×n rows; linear rows first), `task_rows`
/// (the unscaled task Jacobian) and the scaled measures: `singular_values`,
/// `manipulability`, `determinant` (null unless square), `condition_number` (null when
/// exactly singular), `near_singular`, `length_scale`; and `displayed`: the
/// manipulability, determinant and condition number of the unscaled task rows, in the
/// robot's units.
pub fn jacobian(request: &str) -> Result<String, ApiError> {
    let mut req = parse_request(request)?;
    let task = task_of(&mut req.fields)?;
    let fk = ForwardKinematics::new(&req.robot, &req.q)?;
    let analysis = JacobianAnalysis::new(&req.robot, &fk, &req.q, task);
    let rows = task_jacobian(&analysis.geometric, task, fk.tool_rotation(), 1.0);
    let m = &analysis.measures;
    answer(&JacobianResponse {
        robot: &req.robot.name,
        geometric: matrix_rows(&analysis.geometric),
        numerical: matrix_rows(&analysis.numerical),
        task_rows: matrix_rows(&rows),
        singular_values: &m.singular_values,
        manipulability: m.manipulability,
        determinant: m.determinant,
        condition_number: m.condition_number,
        near_singular: m.near_singular,
        length_scale: m.length_scale,
        displayed: DisplayedResponse {
            manipulability: m.displayed.manipulability,
            determinant: m.displayed.determinant,
            condition_number: m.displayed.condition_number,
        },
    })
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

/// The object forms of an `ik` request's target: `{"q"}`, or `{"position", "rotation"}`.
#[derive(Deserialize, Default)]
struct TargetFields {
    #[serde(default, deserialize_with = "present")]
    q: Option<Field<Vec<f64>>>,
    #[serde(default, deserialize_with = "present")]
    position: Option<Field<Vec<f64>>>,
    /// 3×3 rows, read by [`rows_matrix`].
    #[serde(default, deserialize_with = "present")]
    rotation: Option<Value>,
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
    // Anything but an object has none of the fields (every field takes any JSON).
    let fields = TargetFields::deserialize(value).unwrap_or_default();
    if let Some(q) = read(fields.q, says("\"target.q\" must be a list of numbers"))? {
        robot.check_q(&q)?;
        return Ok(armlab_core::tool_pose(robot, &q));
    }
    let list = says("\"target.position\" must be a list of numbers");
    let position = read(fields.position, list)?.ok_or_else(|| {
        ApiError::Request(
            "\"target\" must be 4×4 rows, {\"position\", \"rotation\"} or {\"q\"}".into(),
        )
    })?;
    if position.len() != 3 {
        return Err(ApiError::Request(
            "\"target.position\" must be 3 numbers".into(),
        ));
    }
    let rotation = match fields.rotation {
        None => Matrix3::identity(),
        Some(rows) => {
            let r = rows_matrix::<3>(&rows, "target.rotation")?;
            Matrix3::from_fn(|i, j| r[i][j])
        }
    };
    Ok(armlab_core::ik::target_pose(
        nalgebra::Vector3::new(position[0], position[1], position[2]),
        rotation,
    ))
}

fn ik_method(fields: &mut RequestFields) -> Result<IkMethod, ApiError> {
    let positive = says("\"alpha\" must be a positive number");
    let alpha = match read(fields.alpha.take(), positive)? {
        None => None,
        Some(a) if a.is_finite() && a > 0.0 => Some(a),
        Some(_) => {
            return Err(ApiError::Request(
                "\"alpha\" must be a positive number".into(),
            ));
        }
    };
    let id = read(fields.method.take(), |_| {
        ApiError::Request(format!(
            "\"method\" must be a text: one of {}",
            IkMethod::id_list()
        ))
    })?;
    let Some(id) = id else {
        return Ok(IkMethod::DampedLeastSquares);
    };
    match IkMethod::from_id(&id) {
        Some(IkMethod::JacobianTranspose { .. }) => Ok(IkMethod::JacobianTranspose { alpha }),
        Some(method) => Ok(method),
        None => Err(ApiError::Request(format!(
            "unknown method \"{}\": use one of {} (or closed-form)",
            echo::text(&id),
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

fn ik_settings(
    fields: &mut RequestFields,
    drag: bool,
) -> Result<armlab_core::IkSettings, ApiError> {
    use armlab_core::{IkSettings, JacobianSource, Objective};
    let mut s = if drag {
        IkSettings::drag()
    } else {
        IkSettings::default()
    };
    let source = says("\"jacobian\" must be \"geometric\" or \"numerical\"");
    s.jacobian = match read(fields.jacobian.take(), source)?.as_deref() {
        None | Some("geometric") => JacobianSource::Geometric,
        Some("numerical") => JacobianSource::CentralDifference,
        Some(_) => {
            return Err(ApiError::Request(
                "\"jacobian\" must be \"geometric\" or \"numerical\"".into(),
            ));
        }
    };
    let settings = read(
        fields.settings.take(),
        says("\"settings\" must be an object"),
    )?;
    let Some(given) = settings else {
        return Ok(s);
    };
    if let Some(other) = given.unknown.keys().next() {
        return Err(ApiError::Request(format!(
            "\"settings.{}\" is not known; the known settings are: position_tolerance, orientation_tolerance, max_iterations, budget, restarts, seed, max_joint_change, trace, wrap, objective",
            echo::text(other)
        )));
    }
    let number = |name: &'static str| {
        move |_: &Value| ApiError::Request(format!("\"settings.{name}\" must be a number"))
    };
    let count = |name: &'static str| {
        move |_: &Value| {
            ApiError::Request(format!("\"settings.{name}\" must be a whole number ≥ 0"))
        }
    };
    let size = |n: u64| usize::try_from(n).unwrap_or(usize::MAX);
    if let Some(v) = read(given.position_tolerance, number("position_tolerance"))? {
        s.position_tolerance = v;
    }
    if let Some(v) = read(given.orientation_tolerance, number("orientation_tolerance"))? {
        s.orientation_tolerance = v;
    }
    if let Some(n) = read(given.max_iterations, count("max_iterations"))? {
        s.max_iterations = size(n);
    }
    if let Some(n) = read(given.budget, count("budget"))? {
        s.budget = size(n);
    }
    if let Some(n) = read(given.restarts, count("restarts"))? {
        s.restarts = size(n).min(MAX_RESTARTS);
    }
    if let Some(n) = read(given.seed, count("seed"))? {
        s.seed = n;
    }
    if let Some(limit) = read(given.max_joint_change, number("max_joint_change"))? {
        s.max_joint_change = limit;
    }
    let switch = says("\"settings.trace\" must be true or false");
    if let Some(trace) = read(given.trace, switch)? {
        s.record_trace = trace;
    }
    if let Some(wrap) = read(given.wrap, |v| {
        setting_choice("wrap", v, "true, false".into())
    })? {
        s.wrap = wrap;
    }
    let objective = read(given.objective, |v| {
        setting_choice("objective", v, Objective::id_list())
    })?;
    if let Some(id) = objective {
        s.objective = Objective::from_id(&id)
            .ok_or_else(|| setting_choice("objective", &Value::String(id), Objective::id_list()))?;
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
