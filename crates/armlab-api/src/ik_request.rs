//! Reading an `ik` request's own fields: the target, the method and the settings, with
//! the caps that keep every call bounded. Apart from the shared request reading because
//! only [`crate::ik`] takes them.

use nalgebra::{IsometryMatrix3, Matrix3};
use serde_json::Value;

use crate::ApiError;
use serde::Deserialize;

use crate::request::{Field, RequestFields, number_list, present, read, rows_matrix, says};
use armlab_core::{IkError, IkMethod, Robot};
use armlab_text::echo;

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
pub(crate) fn ik_target(
    robot: &Robot,
    value: Option<&Value>,
) -> Result<IsometryMatrix3<f64>, ApiError> {
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

pub(crate) fn ik_method(fields: &mut RequestFields) -> Result<IkMethod, ApiError> {
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

pub(crate) fn ik_settings(
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
