//! Reading a request: its fields as serde reads them (a wrong type kept, to be answered
//! with the field's own sentence), the robot and the joint vector every request names,
//! and the readers of the fields several verbs share. Apart from the verbs so that each
//! verb only reads what it takes.

use std::collections::BTreeMap;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer};
use serde_json::Value;

use crate::ApiError;
use armlab_core::{Robot, Task, preset, robot_from_value};
use armlab_text::echo;

/// A request field as serde read it: its value, or, when the JSON holds another type, that
/// JSON as given. A wrong type is not an error of the whole request here: the function that
/// reads the field answers with the sentence naming it (serde's own message names
/// neither the field nor what a person should write).
pub(crate) enum Field<T> {
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
pub(crate) fn present<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<Option<T>, D::Error> {
    T::deserialize(deserializer).map(Some)
}

/// The value of an optional field, or the field's sentence when it holds another type.
pub(crate) fn read<T>(
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
pub(crate) fn says(sentence: &'static str) -> impl FnOnce(&Value) -> ApiError {
    move |_| ApiError::Request(sentence.into())
}

/// The fields of a request; each function reads those it takes, and ignores the others
/// (and fields it does not know).
#[derive(Deserialize)]
pub(crate) struct RequestFields {
    /// A preset id or a robot file object; checked by the robot's own parser.
    #[serde(default, deserialize_with = "present")]
    pub(crate) robot: Option<Value>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) q: Option<Field<Vec<f64>>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) task: Option<Field<String>>,
    /// 4×4 rows, `{"position", "rotation"}` or `{"q"}` ([`ik_target`]).
    #[serde(default, deserialize_with = "present")]
    pub(crate) target: Option<Value>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) method: Option<Field<String>>,
    /// `null` reads as absent (the adaptive step).
    #[serde(default)]
    pub(crate) alpha: Option<Field<f64>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) jacobian: Option<Field<String>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) drag: Option<Field<bool>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) settings: Option<Field<SettingsFields>>,
}

/// The `settings` of an `ik` request ([`ik`] lists them).
#[derive(Deserialize)]
pub(crate) struct SettingsFields {
    #[serde(default, deserialize_with = "present")]
    pub(crate) position_tolerance: Option<Field<f64>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) orientation_tolerance: Option<Field<f64>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) max_iterations: Option<Field<u64>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) budget: Option<Field<u64>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) restarts: Option<Field<u64>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) seed: Option<Field<u64>>,
    /// `null` is taken: no limit of its own (a drag then keeps its default step).
    #[serde(default, deserialize_with = "present")]
    pub(crate) max_joint_change: Option<Field<Option<f64>>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) trace: Option<Field<bool>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) wrap: Option<Field<bool>>,
    #[serde(default, deserialize_with = "present")]
    pub(crate) objective: Option<Field<String>>,
    /// Every other key: each is refused with the list of known settings.
    #[serde(flatten)]
    pub(crate) unknown: BTreeMap<String, Value>,
}

/// A parsed request: the robot, the joint vector and the other fields, unread.
pub(crate) struct Request {
    pub(crate) fields: RequestFields,
    pub(crate) robot: Robot,
    pub(crate) q: Vec<f64>,
}

pub(crate) fn parse_request(text: &str) -> Result<Request, ApiError> {
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

pub(crate) fn task_of(fields: &mut RequestFields) -> Result<Task, ApiError> {
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

pub(crate) fn number_list(value: &Value, what: &str) -> Result<Vec<f64>, ApiError> {
    value
        .as_array()
        .and_then(|list| list.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>())
        .ok_or_else(|| ApiError::Request(format!("\"{what}\" must be a list of numbers")))
}

pub(crate) fn rows_matrix<const R: usize>(
    value: &Value,
    what: &str,
) -> Result<[[f64; 3]; R], ApiError> {
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
