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
//!
//! The file's objects are serde structs: the `…Fields` structs as read, the `…Entry`
//! structs as written. What is read is permissive (each field its value, or a mark that
//! the JSON there has another type), so that every problem becomes the typed
//! [`RobotError`] naming the joint and the field; serde's own message never reaches a
//! person.

use serde::de::{DeserializeOwned, IgnoredAny};
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::{Map, Value};

use super::collision::KeepOut;
use super::error::{Expected, Field, Place, RobotError};
use super::orientation::ZyxEuler;
use super::robot::{
    Convention, DhRow, Joint, JointKind, JointLimits, LengthUnit, MAX_JOINTS, PartSizes, Robot,
    RobotParts, isometry_from_xyz_rpy,
};

/// The top-level fields, in the order the error for an unknown one lists them.
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

/// A field as read: its value, or [`Given::Wrong`] when the JSON there has another type.
/// Reading a `Given` never fails, so a whole file always reads into its structs, and the
/// checks that follow name the first wrong field in the order a person reads the file.
enum Given<T> {
    /// The field has the type asked for.
    Value(T),
    /// The field holds something else.
    Wrong,
}

impl<'de, T: DeserializeOwned> Deserialize<'de> for Given<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        Ok(T::deserialize(&value).map_or(Given::Wrong, Given::Value))
    }
}

/// For `deserialize_with`: a field that is there, `null` included (serde reads `null` as
/// an absent `Option`, and `"d": null` must be a wrong type, not a missing field).
fn present<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<Option<T>, D::Error> {
    T::deserialize(deserializer).map(Some)
}

/// A robot file's top level as read. Text fields read `null` as absent.
#[derive(Deserialize)]
struct RobotFields {
    /// The format's version: any value, not checked.
    #[serde(default, rename = "format")]
    _format: Option<IgnoredAny>,
    #[serde(default)]
    name: Option<Given<String>>,
    #[serde(default)]
    description: Option<Given<String>>,
    #[serde(default)]
    convention: Option<Given<String>>,
    #[serde(default)]
    length_unit: Option<Given<String>>,
    #[serde(default, deserialize_with = "present")]
    joints: Option<Given<Vec<Given<JointFields>>>>,
    #[serde(default, deserialize_with = "present")]
    base: Option<Given<TransformFields>>,
    #[serde(default, deserialize_with = "present")]
    tool: Option<Given<TransformFields>>,
    #[serde(default, deserialize_with = "present")]
    base_size: Option<Given<[f64; 3]>>,
    #[serde(default, deserialize_with = "present")]
    hand_size: Option<Given<[f64; 3]>>,
    #[serde(default, deserialize_with = "present")]
    keep_out: Option<Given<Vec<Given<BoxFields>>>>,
    /// Every other key: the first (alphabetically) is refused.
    #[serde(flatten)]
    unknown: Map<String, Value>,
}

/// One joint's entry as read.
#[derive(Deserialize)]
struct JointFields {
    #[serde(default)]
    name: Option<Given<String>>,
    #[serde(default, rename = "type")]
    kind: Option<Given<String>>,
    #[serde(default, deserialize_with = "present")]
    theta_deg: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    d: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    a: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    alpha_deg: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    min_deg: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    max_deg: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    min: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    max: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    home: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    max_speed: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    max_acceleration: Option<Given<f64>>,
    #[serde(default, deserialize_with = "present")]
    housing_size: Option<Given<[f64; 3]>>,
    #[serde(default, deserialize_with = "present")]
    link_size: Option<Given<[f64; 3]>>,
    #[serde(flatten)]
    unknown: Map<String, Value>,
}

/// The base or the tool transform as read.
#[derive(Deserialize)]
struct TransformFields {
    #[serde(default, deserialize_with = "present")]
    xyz: Option<Given<[f64; 3]>>,
    #[serde(default, deserialize_with = "present")]
    rpy_deg: Option<Given<[f64; 3]>>,
    #[serde(flatten)]
    unknown: Map<String, Value>,
}

/// A keep-out box as read.
#[derive(Deserialize)]
struct BoxFields {
    #[serde(default, deserialize_with = "present")]
    centre: Option<Given<[f64; 3]>>,
    #[serde(default, deserialize_with = "present")]
    size: Option<Given<[f64; 3]>>,
    #[serde(flatten)]
    unknown: Map<String, Value>,
}

/// Reads a robot from the JSON text of a robot file, with a typed error for every
/// problem (the first one found).
pub fn robot_from_json(text: &str) -> Result<Robot, RobotError> {
    let value: Value = serde_json::from_str(text).map_err(|e| RobotError::from_json(&e))?;
    robot_from_value(&value)
}

/// Reads a robot from an already parsed JSON value (used by the JS API and URLs).
pub fn robot_from_value(value: &Value) -> Result<Robot, RobotError> {
    // Every field is a `Given`, which takes any JSON: only a value that is no object fails.
    let fields = RobotFields::deserialize(value)
        .map_err(|_| wrong(&Place::Robot, Field::Robot, Expected::Object))?;
    fields.into_robot()
}

impl RobotFields {
    /// The robot these fields describe, checked field by field in the file's order.
    fn into_robot(self) -> Result<Robot, RobotError> {
        let place = Place::Robot;
        check_fields(&self.unknown, &place, ROBOT_FIELDS)?;
        let name =
            text(self.name, &place, Field::Name)?.ok_or_else(|| missing(&place, Field::Name))?;
        let description = text(self.description, &place, Field::Description)?.unwrap_or_default();
        let convention = match text(self.convention, &place, Field::Convention)?.as_deref() {
            Some("standard") => Convention::Standard,
            Some("modified") => Convention::Modified,
            Some(other) => return Err(RobotError::UnknownConvention(other.to_string())),
            None => return Err(missing(&place, Field::Convention)),
        };
        let length_unit = match text(self.length_unit, &place, Field::LengthUnit)?.as_deref() {
            Some("mm") => LengthUnit::Millimetre,
            Some("m") => LengthUnit::Metre,
            Some(other) => return Err(RobotError::UnknownLengthUnit(other.to_string())),
            None => return Err(missing(&place, Field::LengthUnit)),
        };
        let list = match self.joints {
            None => return Err(missing(&place, Field::Joints)),
            Some(Given::Value(list)) => list,
            Some(Given::Wrong) => return Err(wrong(&place, Field::Joints, Expected::JointList)),
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
            .into_iter()
            .enumerate()
            .map(|(i, joint)| joint_from_fields(i + 1, joint))
            .collect::<Result<Vec<_>, _>>()?;
        Robot {
            name,
            description,
            convention,
            length_unit,
            joints,
            world_from_base: transform_from_fields(self.base, Place::Base)?,
            flange_from_tool: transform_from_fields(self.tool, Place::Tool)?,
            parts: RobotParts {
                base: triple(self.base_size, &place, Field::BaseSize)?,
                hand: triple(self.hand_size, &place, Field::HandSize)?,
            },
            keep_outs: keep_outs_from_fields(self.keep_out)?,
        }
        .validated()
    }
}

/// Joint `n` (1-based) from its entry.
fn joint_from_fields(n: usize, joint: Given<JointFields>) -> Result<Joint, RobotError> {
    let place = Place::Joint(n);
    let Given::Value(f) = joint else {
        return Err(wrong(&place, Field::Joint, Expected::Object));
    };
    check_fields(&f.unknown, &place, JOINT_FIELDS)?;
    let kind = match text(f.kind, &place, Field::Type)?.as_deref() {
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
    let required =
        |given, field| number(given, &place, field)?.ok_or_else(|| missing(&place, field));
    let dh = DhRow {
        theta: required(f.theta_deg, Field::ThetaDeg)?.to_radians(),
        d: required(f.d, Field::D)?,
        a: required(f.a, Field::A)?,
        alpha: required(f.alpha_deg, Field::AlphaDeg)?.to_radians(),
    };
    let given = MotionFields {
        min_deg: f.min_deg,
        max_deg: f.max_deg,
        min: f.min,
        max: f.max,
        home: f.home,
        max_speed: f.max_speed,
        max_acceleration: f.max_acceleration,
    };
    let Motion {
        limits,
        home,
        max_speed,
        max_acceleration,
    } = match kind {
        JointKind::Revolute => revolute_motion(given, &place)?,
        JointKind::Prismatic => prismatic_motion(given, &place, n)?,
    };
    let name = text(f.name, &place, Field::Name)?.unwrap_or_else(|| format!("joint {n}"));
    let parts = PartSizes {
        housing: triple(f.housing_size, &place, Field::HousingSize)?,
        link: triple(f.link_size, &place, Field::LinkSize)?,
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

/// A joint entry's limits, home and speeds as read (degrees or length units).
struct MotionFields {
    min_deg: Option<Given<f64>>,
    max_deg: Option<Given<f64>>,
    min: Option<Given<f64>>,
    max: Option<Given<f64>>,
    home: Option<Given<f64>>,
    max_speed: Option<Given<f64>>,
    max_acceleration: Option<Given<f64>>,
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
fn revolute_motion(f: MotionFields, place: &Place) -> Result<Motion, RobotError> {
    for (field, given) in [("min", &f.min), ("max", &f.max)] {
        if given.is_some() {
            return Err(RobotError::UnknownField {
                place: place.clone(),
                field: field.to_string(),
                known: "a revolute joint's limits are \"min_deg\" and \"max_deg\"".into(),
            });
        }
    }
    let min = number(f.min_deg, place, Field::MinDeg)?.map(f64::to_radians);
    let max = number(f.max_deg, place, Field::MaxDeg)?.map(f64::to_radians);
    let limits = JointLimits {
        min: min.unwrap_or(JointLimits::FULL_TURN.min),
        max: max.unwrap_or(JointLimits::FULL_TURN.max),
    };
    let home = number(f.home, place, Field::Home)?.map_or(0.0, f64::to_radians);
    let speed = number(f.max_speed, place, Field::MaxSpeed)?.map(f64::to_radians);
    let acc = number(f.max_acceleration, place, Field::MaxAcceleration)?.map(f64::to_radians);
    Ok(Motion {
        limits,
        home,
        max_speed: speed,
        max_acceleration: acc,
    })
}

/// A prismatic joint `n`'s limits (required), home (the minimum when absent) and speeds,
/// in length units; "min_deg" and "max_deg" are refused.
fn prismatic_motion(f: MotionFields, place: &Place, n: usize) -> Result<Motion, RobotError> {
    for (field, given) in [("min_deg", &f.min_deg), ("max_deg", &f.max_deg)] {
        if given.is_some() {
            return Err(RobotError::UnknownField {
                place: place.clone(),
                field: field.to_string(),
                known: "a prismatic joint's limits are \"min\" and \"max\", in length units".into(),
            });
        }
    }
    let (Some(min), Some(max)) = (
        number(f.min, place, Field::Min)?,
        number(f.max, place, Field::Max)?,
    ) else {
        return Err(RobotError::PrismaticWithoutLimits { joint: n });
    };
    let home = number(f.home, place, Field::Home)?.unwrap_or(min);
    let speed = number(f.max_speed, place, Field::MaxSpeed)?;
    let acc = number(f.max_acceleration, place, Field::MaxAcceleration)?;
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
fn keep_outs_from_fields(
    given: Option<Given<Vec<Given<BoxFields>>>>,
) -> Result<Vec<KeepOut>, RobotError> {
    let list = match given {
        None => return Ok(Vec::new()),
        Some(Given::Value(list)) => list,
        Some(Given::Wrong) => return Err(wrong(&Place::Robot, Field::KeepOut, Expected::BoxList)),
    };
    let mut boxes = Vec::with_capacity(list.len());
    for (i, item) in list.into_iter().enumerate() {
        let place = Place::KeepOut(i + 1);
        let Given::Value(f) = item else {
            return Err(wrong(&place, Field::KeepOut, Expected::BoxList));
        };
        check_fields(&f.unknown, &place, BOX_FIELDS)?;
        let centre = triple(f.centre, &place, Field::Centre)?
            .ok_or_else(|| missing(&place, Field::Centre))?;
        let size =
            triple(f.size, &place, Field::Size)?.ok_or_else(|| missing(&place, Field::Size))?;
        boxes.push(KeepOut {
            centre: nalgebra::Point3::from(centre),
            size: nalgebra::Vector3::from(size),
            rotation: nalgebra::Rotation3::identity(),
        });
    }
    Ok(boxes)
}

/// The base or the tool transform (the identity when the file has none).
fn transform_from_fields(
    given: Option<Given<TransformFields>>,
    place: Place,
) -> Result<nalgebra::IsometryMatrix3<f64>, RobotError> {
    let f = match given {
        None => return Ok(nalgebra::IsometryMatrix3::identity()),
        Some(Given::Value(f)) => f,
        Some(Given::Wrong) => return Err(wrong(&place, Field::Transform, Expected::Transform)),
    };
    check_fields(&f.unknown, &place, TRANSFORM_FIELDS)?;
    let xyz = triple(f.xyz, &place, Field::Xyz)?.unwrap_or([0.0; 3]);
    let rpy = triple(f.rpy_deg, &place, Field::RpyDeg)?.unwrap_or([0.0; 3]);
    Ok(isometry_from_xyz_rpy(
        xyz,
        [
            rpy[0].to_radians(),
            rpy[1].to_radians(),
            rpy[2].to_radians(),
        ],
    ))
}

/// A robot file's top level as written.
#[derive(Serialize)]
struct RobotEntry<'a> {
    format: &'static str,
    name: &'a str,
    #[serde(skip_serializing_if = "str::is_empty")]
    description: &'a str,
    convention: &'static str,
    length_unit: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    base_size: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    hand_size: Option<[f64; 3]>,
    joints: Vec<JointEntry<'a>>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    keep_out: Vec<BoxEntry>,
    /// Written only when it is not the identity.
    #[serde(skip_serializing_if = "Option::is_none")]
    base: Option<TransformEntry>,
    /// Written only when it is not the identity.
    #[serde(skip_serializing_if = "Option::is_none")]
    tool: Option<TransformEntry>,
}

/// One joint's entry as written: angles in degrees, lengths in the robot's unit; a
/// revolute joint's limits are `min_deg` and `max_deg`, a prismatic one's `min` and `max`.
#[derive(Serialize)]
struct JointEntry<'a> {
    name: &'a str,
    #[serde(rename = "type")]
    kind: &'static str,
    theta_deg: f64,
    d: f64,
    a: f64,
    alpha_deg: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    min_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    min: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max: Option<f64>,
    home: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_speed: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_acceleration: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    housing_size: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    link_size: Option<[f64; 3]>,
}

/// A keep-out box as written.
#[derive(Serialize)]
struct BoxEntry {
    centre: [f64; 3],
    size: [f64; 3],
}

/// The base or the tool transform as written.
#[derive(Serialize)]
struct TransformEntry {
    xyz: [f64; 3],
    rpy_deg: [f64; 3],
}

impl<'a> RobotEntry<'a> {
    fn of(robot: &'a Robot) -> Self {
        let transform = |iso: &nalgebra::IsometryMatrix3<f64>| {
            (*iso != nalgebra::IsometryMatrix3::identity()).then(|| {
                let e = ZyxEuler::from_rotation(iso.rotation.matrix());
                let t = iso.translation.vector;
                TransformEntry {
                    xyz: [t.x, t.y, t.z],
                    rpy_deg: [e.gamma, e.beta, e.alpha].map(|a| tidy(a.to_degrees())),
                }
            })
        };
        RobotEntry {
            format: "armlab-robot/1",
            name: &robot.name,
            description: &robot.description,
            convention: robot.convention.as_str(),
            length_unit: robot.length_unit.symbol(),
            base_size: robot.parts.base,
            hand_size: robot.parts.hand,
            joints: robot.joints.iter().map(JointEntry::of).collect(),
            keep_out: robot
                .keep_outs
                .iter()
                .map(|b| BoxEntry {
                    centre: b.centre.coords.into(),
                    size: b.size.into(),
                })
                .collect(),
            base: transform(&robot.world_from_base),
            tool: transform(&robot.flange_from_tool),
        }
    }
}

impl<'a> JointEntry<'a> {
    fn of(j: &'a Joint) -> Self {
        let degrees = |v: f64| tidy(v.to_degrees());
        let revolute = j.kind == JointKind::Revolute;
        // Revolute values are angles, written in degrees; prismatic ones are lengths.
        let value = |v: f64| if revolute { degrees(v) } else { v };
        JointEntry {
            name: &j.name,
            kind: j.kind.as_str(),
            theta_deg: degrees(j.dh.theta),
            d: j.dh.d,
            a: j.dh.a,
            alpha_deg: degrees(j.dh.alpha),
            min_deg: revolute.then(|| degrees(j.limits.min)),
            max_deg: revolute.then(|| degrees(j.limits.max)),
            min: (!revolute).then_some(j.limits.min),
            max: (!revolute).then_some(j.limits.max),
            home: value(j.home),
            max_speed: j.max_speed.map(value),
            max_acceleration: j.max_acceleration.map(value),
            housing_size: j.parts.housing,
            link_size: j.parts.link,
        }
    }
}

/// A robot's file as a JSON value: the object [`robot_to_json`] writes (its keys in
/// alphabetical order, as a `serde_json` map keeps them).
pub fn robot_to_value(robot: &Robot) -> Value {
    // The entries hold only text, numbers and lists: writing them cannot fail.
    serde_json::to_value(RobotEntry::of(robot)).unwrap_or(Value::Null)
}

/// Writes a robot as the JSON text of a robot file (pretty-printed). Reading it back with
/// [`robot_from_json`] gives the same robot up to rounding of degree conversions.
pub fn robot_to_json(robot: &Robot) -> String {
    serde_json::to_string_pretty(&robot_to_value(robot)).unwrap_or_default()
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

/// The first key of `unknown` (an object's keys that are none of `known`) is an error.
fn check_fields(
    unknown: &Map<String, Value>,
    place: &Place,
    known: &[&str],
) -> Result<(), RobotError> {
    match unknown.keys().next() {
        Some(field) => Err(RobotError::UnknownField {
            place: place.clone(),
            field: field.clone(),
            known: known.join(", "),
        }),
        None => Ok(()),
    }
}

/// A text field's value (absent and `null` alike: `None`).
fn text(
    given: Option<Given<String>>,
    place: &Place,
    field: Field,
) -> Result<Option<String>, RobotError> {
    match given {
        None => Ok(None),
        Some(Given::Value(s)) => Ok(Some(s)),
        Some(Given::Wrong) => Err(wrong(place, field, Expected::Text)),
    }
}

/// A number field's value. JSON has no NaN; a string "NaN" or `null` is a type error,
/// named as such.
fn number(
    given: Option<Given<f64>>,
    place: &Place,
    field: Field,
) -> Result<Option<f64>, RobotError> {
    match given {
        None => Ok(None),
        Some(Given::Value(v)) if v.is_finite() => Ok(Some(v)),
        Some(Given::Value(_)) => Err(RobotError::NotFinite {
            place: place.clone(),
            field,
            value: f64::INFINITY,
        }),
        Some(Given::Wrong) => Err(wrong(place, field, Expected::Number)),
    }
}

/// A field of three numbers.
fn triple(
    given: Option<Given<[f64; 3]>>,
    place: &Place,
    field: Field,
) -> Result<Option<[f64; 3]>, RobotError> {
    match given {
        None => Ok(None),
        Some(Given::Value(v)) => Ok(Some(v)),
        Some(Given::Wrong) => Err(wrong(place, field, Expected::Triple)),
    }
}
