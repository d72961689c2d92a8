//! The robot file format: JSON, human-editable, one robot per file. Angles in degrees,
//! lengths in the file's `length_unit`. The format is documented in
//! `assets/robots/README.md`; every preset in that folder is an example.
//!
//! ```json
//! {
//!   "name": "Planar 2R",
//!   "convention": "standard",
//!   "length_unit": "m",
//!   "joints": [
//!     { "type": "revolute", "theta_deg": 0, "d": 0, "a": 2, "alpha_deg": 0 },
//!     { "type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0 }
//!   ]
//! }
//! ```

use serde_json::{Map, Value, json};

use super::collision::KeepOut;
use super::error::{Expected, Field, Place, RobotError};
use super::orientation::ZyxEuler;
use super::robot::{
    Convention, DhRow, Joint, JointKind, JointLimits, LengthUnit, MAX_JOINTS, PartSizes, Robot,
    RobotParts, isometry_from_xyz_rpy,
};

const ROBOT_FIELDS: &[&str] = &[
    "format",
    "name",
    "description",
    "convention",
    "length_unit",
    "joints",
    "base",
    "tool",
    "base_size",
    "hand_size",
    "keep_out",
];
const BOX_FIELDS: &[&str] = &["centre", "size"];
const JOINT_FIELDS: &[&str] = &[
    "name",
    "type",
    "theta_deg",
    "d",
    "a",
    "alpha_deg",
    "min_deg",
    "max_deg",
    "min",
    "max",
    "home",
    "max_speed",
    "max_acceleration",
    "housing_size",
    "link_size",
];
const TRANSFORM_FIELDS: &[&str] = &["xyz", "rpy_deg"];

/// Reads a robot from the JSON text of a robot file, with a typed error for every
/// problem (the first one found).
pub fn robot_from_json(text: &str) -> Result<Robot, RobotError> {
    let value: Value = serde_json::from_str(text).map_err(|e| RobotError::from_json(&e))?;
    robot_from_value(&value)
}

/// Reads a robot from an already parsed JSON value (used by the JS API and URLs).
pub fn robot_from_value(value: &Value) -> Result<Robot, RobotError> {
    let obj = object(value, &Place::Robot, Field::Robot, Expected::Object)?;
    check_fields(obj, &Place::Robot, ROBOT_FIELDS)?;
    let place = Place::Robot;
    let name = string(obj, &place, Field::Name)?.ok_or_else(|| missing(&place, Field::Name))?;
    let description = string(obj, &place, Field::Description)?.unwrap_or_default();
    let convention = match string(obj, &place, Field::Convention)?.as_deref() {
        Some("standard") => Convention::Standard,
        Some("modified") => Convention::Modified,
        Some(other) => return Err(RobotError::UnknownConvention(other.to_string())),
        None => return Err(missing(&place, Field::Convention)),
    };
    let length_unit = match string(obj, &place, Field::LengthUnit)?.as_deref() {
        Some("mm") => LengthUnit::Millimetre,
        Some("m") => LengthUnit::Metre,
        Some(other) => return Err(RobotError::UnknownLengthUnit(other.to_string())),
        None => return Err(missing(&place, Field::LengthUnit)),
    };
    let list = match obj.get(Field::Joints.name()) {
        None => return Err(missing(&place, Field::Joints)),
        Some(Value::Array(list)) => list,
        Some(_) => {
            return Err(wrong(&place, Field::Joints, Expected::JointList));
        }
    };
    if list.is_empty() {
        return Err(RobotError::EmptyChain);
    }
    if list.len() > MAX_JOINTS {
        return Err(RobotError::TooManyJoints {
            count: list.len(),
            max: MAX_JOINTS,
        });
    }
    let joints = list
        .iter()
        .enumerate()
        .map(|(i, v)| joint_from_value(i + 1, v))
        .collect::<Result<Vec<_>, _>>()?;
    let world_from_base = transform_from_value(obj.get(Field::Base.name()), Place::Base)?;
    let flange_from_tool = transform_from_value(obj.get(Field::Tool.name()), Place::Tool)?;
    let parts = RobotParts {
        base: triple(obj, &place, Field::BaseSize)?,
        hand: triple(obj, &place, Field::HandSize)?,
    };
    Robot {
        name,
        description,
        convention,
        length_unit,
        joints,
        world_from_base,
        flange_from_tool,
        parts,
        keep_outs: keep_outs_from_value(obj.get(Field::KeepOut.name()))?,
    }
    .validated()
}

fn joint_from_value(n: usize, value: &Value) -> Result<Joint, RobotError> {
    let place = Place::Joint(n);
    let obj = object(value, &place, Field::Joint, Expected::Object)?;
    check_fields(obj, &place, JOINT_FIELDS)?;
    let kind = match string(obj, &place, Field::Type)?.as_deref() {
        Some("revolute") => JointKind::Revolute,
        Some("prismatic") => JointKind::Prismatic,
        Some(other) => {
            return Err(RobotError::UnknownJointType {
                joint: n,
                found: other.to_string(),
            });
        }
        None => return Err(missing(&place, Field::Type)),
    };
    let required = |field: Field| number(obj, &place, field)?.ok_or_else(|| missing(&place, field));
    let dh = DhRow {
        theta: required(Field::ThetaDeg)?.to_radians(),
        d: required(Field::D)?,
        a: required(Field::A)?,
        alpha: required(Field::AlphaDeg)?.to_radians(),
    };
    let Motion {
        limits,
        home,
        max_speed,
        max_acceleration,
    } = match kind {
        JointKind::Revolute => revolute_motion(obj, &place)?,
        JointKind::Prismatic => prismatic_motion(obj, &place, n)?,
    };
    let name = string(obj, &place, Field::Name)?.unwrap_or_else(|| format!("joint {n}"));
    let parts = PartSizes {
        housing: triple(obj, &place, Field::HousingSize)?,
        link: triple(obj, &place, Field::LinkSize)?,
    };
    Ok(Joint {
        name,
        kind,
        dh,
        limits,
        max_speed,
        max_acceleration,
        home,
        parts,
    })
}

/// A joint's range of motion as read from its file entry.
struct Motion {
    limits: JointLimits,
    home: f64,
    max_speed: Option<f64>,
    max_acceleration: Option<f64>,
}

/// A revolute joint's limits, home and speeds, in degrees in the file (a full turn
/// without limits, home 0); "min" and "max" are refused, as they would be lengths.
fn revolute_motion(obj: &Map<String, Value>, place: &Place) -> Result<Motion, RobotError> {
    for field in ["min", "max"] {
        if obj.contains_key(field) {
            return Err(RobotError::UnknownField {
                place: place.clone(),
                field: field.to_string(),
                known: "a revolute joint's limits are \"min_deg\" and \"max_deg\"".into(),
            });
        }
    }
    let min = number(obj, place, Field::MinDeg)?.map(f64::to_radians);
    let max = number(obj, place, Field::MaxDeg)?.map(f64::to_radians);
    let limits = JointLimits {
        min: min.unwrap_or(JointLimits::FULL_TURN.min),
        max: max.unwrap_or(JointLimits::FULL_TURN.max),
    };
    let home = number(obj, place, Field::Home)?.map_or(0.0, f64::to_radians);
    let speed = number(obj, place, Field::MaxSpeed)?.map(f64::to_radians);
    let acc = number(obj, place, Field::MaxAcceleration)?.map(f64::to_radians);
    Ok(Motion {
        limits,
        home,
        max_speed: speed,
        max_acceleration: acc,
    })
}

/// A prismatic joint `n`'s limits (required), home (the minimum when absent) and speeds,
/// in length units; "min_deg" and "max_deg" are refused.
fn prismatic_motion(
    obj: &Map<String, Value>,
    place: &Place,
    n: usize,
) -> Result<Motion, RobotError> {
    for field in ["min_deg", "max_deg"] {
        if obj.contains_key(field) {
            return Err(RobotError::UnknownField {
                place: place.clone(),
                field: field.to_string(),
                known: "a prismatic joint's limits are \"min\" and \"max\", in length units".into(),
            });
        }
    }
    let (Some(min), Some(max)) = (
        number(obj, place, Field::Min)?,
        number(obj, place, Field::Max)?,
    ) else {
        return Err(RobotError::PrismaticWithoutLimits { joint: n });
    };
    let home = number(obj, place, Field::Home)?.unwrap_or(min);
    let speed = number(obj, place, Field::MaxSpeed)?;
    let acc = number(obj, place, Field::MaxAcceleration)?;
    Ok(Motion {
        limits: JointLimits { min, max },
        home,
        max_speed: speed,
        max_acceleration: acc,
    })
}

/// The optional `keep_out` list: boxes `{"centre": [x, y, z], "size": [x, y, z]}` in the
/// world frame and the file's length unit (their number and sizes are checked with the
/// robot, [`Robot::validated`]).
fn keep_outs_from_value(value: Option<&Value>) -> Result<Vec<KeepOut>, RobotError> {
    let Some(value) = value else {
        return Ok(Vec::new());
    };
    let list = value
        .as_array()
        .ok_or_else(|| wrong(&Place::Robot, Field::KeepOut, Expected::BoxList))?;
    let mut boxes = Vec::with_capacity(list.len());
    for (i, item) in list.iter().enumerate() {
        let place = Place::KeepOut(i + 1);
        let obj = object(item, &place, Field::KeepOut, Expected::BoxList)?;
        check_fields(obj, &place, BOX_FIELDS)?;
        let centre =
            triple(obj, &place, Field::Centre)?.ok_or_else(|| missing(&place, Field::Centre))?;
        let size = triple(obj, &place, Field::Size)?.ok_or_else(|| missing(&place, Field::Size))?;
        boxes.push(KeepOut {
            centre: nalgebra::Point3::from(centre),
            size: nalgebra::Vector3::from(size),
            rotation: nalgebra::Rotation3::identity(),
        });
    }
    Ok(boxes)
}

fn transform_from_value(
    value: Option<&Value>,
    place: Place,
) -> Result<nalgebra::IsometryMatrix3<f64>, RobotError> {
    let Some(value) = value else {
        return Ok(nalgebra::IsometryMatrix3::identity());
    };
    let obj = object(value, &place, Field::Transform, Expected::Transform)?;
    check_fields(obj, &place, TRANSFORM_FIELDS)?;
    let xyz = triple(obj, &place, Field::Xyz)?.unwrap_or([0.0; 3]);
    let rpy = triple(obj, &place, Field::RpyDeg)?.unwrap_or([0.0; 3]);
    Ok(isometry_from_xyz_rpy(
        xyz,
        [
            rpy[0].to_radians(),
            rpy[1].to_radians(),
            rpy[2].to_radians(),
        ],
    ))
}

/// Writes a robot as the JSON text of a robot file (pretty-printed). Reading it back with
/// [`robot_from_json`] gives the same robot up to rounding of degree conversions.
pub fn robot_to_json(robot: &Robot) -> String {
    let joints: Vec<Value> = robot.joints.iter().map(joint_to_value).collect();
    let mut root = Map::new();
    root.insert("format".into(), json!("armlab-robot/1"));
    root.insert("name".into(), json!(robot.name));
    if !robot.description.is_empty() {
        root.insert("description".into(), json!(robot.description));
    }
    root.insert("convention".into(), json!(robot.convention.as_str()));
    root.insert("length_unit".into(), json!(robot.length_unit.symbol()));
    for (key, size) in [
        ("base_size", robot.parts.base),
        ("hand_size", robot.parts.hand),
    ] {
        if let Some(v) = size {
            root.insert(key.into(), json!(v));
        }
    }
    root.insert("joints".into(), Value::Array(joints));
    if !robot.keep_outs.is_empty() {
        let boxes: Vec<Value> = robot
            .keep_outs
            .iter()
            .map(|b| json!({"centre": [b.centre.x, b.centre.y, b.centre.z], "size": [b.size.x, b.size.y, b.size.z]}))
            .collect();
        root.insert("keep_out".into(), Value::Array(boxes));
    }
    for (key, iso) in [
        ("base", &robot.world_from_base),
        ("tool", &robot.flange_from_tool),
    ] {
        if *iso != nalgebra::IsometryMatrix3::identity() {
            let e = ZyxEuler::from_rotation(iso.rotation.matrix());
            let t = iso.translation.vector;
            root.insert(
                key.into(),
                json!({
                    "xyz": [t.x, t.y, t.z],
                    "rpy_deg": [tidy(e.gamma.to_degrees()), tidy(e.beta.to_degrees()), tidy(e.alpha.to_degrees())],
                }),
            );
        }
    }
    serde_json::to_string_pretty(&Value::Object(root)).unwrap_or_default()
}

/// One joint's entry of a robot file: angles in degrees, lengths in the robot's unit.
fn joint_to_value(j: &Joint) -> Value {
    let mut obj = Map::new();
    obj.insert("name".into(), json!(j.name));
    obj.insert("type".into(), json!(j.kind.as_str()));
    obj.insert("theta_deg".into(), json!(tidy(j.dh.theta.to_degrees())));
    obj.insert("d".into(), json!(j.dh.d));
    obj.insert("a".into(), json!(j.dh.a));
    obj.insert("alpha_deg".into(), json!(tidy(j.dh.alpha.to_degrees())));
    match j.kind {
        JointKind::Revolute => {
            obj.insert("min_deg".into(), json!(tidy(j.limits.min.to_degrees())));
            obj.insert("max_deg".into(), json!(tidy(j.limits.max.to_degrees())));
            obj.insert("home".into(), json!(tidy(j.home.to_degrees())));
            if let Some(s) = j.max_speed {
                obj.insert("max_speed".into(), json!(tidy(s.to_degrees())));
            }
            if let Some(a) = j.max_acceleration {
                obj.insert("max_acceleration".into(), json!(tidy(a.to_degrees())));
            }
        }
        JointKind::Prismatic => {
            obj.insert("min".into(), json!(j.limits.min));
            obj.insert("max".into(), json!(j.limits.max));
            obj.insert("home".into(), json!(j.home));
            if let Some(s) = j.max_speed {
                obj.insert("max_speed".into(), json!(s));
            }
            if let Some(a) = j.max_acceleration {
                obj.insert("max_acceleration".into(), json!(a));
            }
        }
    }
    for (key, size) in [
        ("housing_size", j.parts.housing),
        ("link_size", j.parts.link),
    ] {
        if let Some(v) = size {
            obj.insert(key.into(), json!(v));
        }
    }
    Value::Object(obj)
}

/// Rounds values within 1e−9 of a whole number of degrees, so files stay readable.
fn tidy(deg: f64) -> f64 {
    let r = deg.round();
    if (deg - r).abs() < 1e-9 { r } else { deg }
}

fn missing(place: &Place, field: Field) -> RobotError {
    RobotError::MissingField {
        place: place.clone(),
        field,
    }
}

fn wrong(place: &Place, field: Field, expected: Expected) -> RobotError {
    RobotError::WrongType {
        place: place.clone(),
        field,
        expected,
    }
}

fn object<'a>(
    value: &'a Value,
    place: &Place,
    field: Field,
    expected: Expected,
) -> Result<&'a Map<String, Value>, RobotError> {
    value
        .as_object()
        .ok_or_else(|| wrong(place, field, expected))
}

fn check_fields(obj: &Map<String, Value>, place: &Place, known: &[&str]) -> Result<(), RobotError> {
    match obj.keys().find(|k| !known.contains(&k.as_str())) {
        Some(field) => Err(RobotError::UnknownField {
            place: place.clone(),
            field: field.clone(),
            known: known.join(", "),
        }),
        None => Ok(()),
    }
}

fn string(
    obj: &Map<String, Value>,
    place: &Place,
    field: Field,
) -> Result<Option<String>, RobotError> {
    match obj.get(field.name()) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::String(s)) => Ok(Some(s.clone())),
        Some(_) => Err(wrong(place, field, Expected::Text)),
    }
}

fn number(
    obj: &Map<String, Value>,
    place: &Place,
    field: Field,
) -> Result<Option<f64>, RobotError> {
    match obj.get(field.name()) {
        None => Ok(None),
        Some(Value::Number(n)) => match n.as_f64() {
            Some(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(RobotError::NotFinite {
                place: place.clone(),
                field,
                value: f64::INFINITY,
            }),
        },
        // JSON has no NaN; a string "NaN" or null is a type error, named as such.
        Some(_) => Err(wrong(place, field, Expected::Number)),
    }
}

fn triple(
    obj: &Map<String, Value>,
    place: &Place,
    field: Field,
) -> Result<Option<[f64; 3]>, RobotError> {
    let Some(value) = obj.get(field.name()) else {
        return Ok(None);
    };
    let expected = Expected::Triple;
    let list = value
        .as_array()
        .ok_or_else(|| wrong(place, field, expected))?;
    if list.len() != 3 {
        return Err(wrong(place, field, expected));
    }
    let mut out = [0.0; 3];
    for (slot, v) in out.iter_mut().zip(list) {
        *slot = v.as_f64().ok_or_else(|| wrong(place, field, expected))?;
    }
    Ok(Some(out))
}
