//! Typed errors of the core. Each message is a whole sentence a student can act on: it
//! names the joint (counted from 1, as in the DH table) and the field. The sentences come
//! from the catalogue ([`crate::i18n`]): [`RobotError::sentence`] in any language, and
//! `Display` in English (the JSON API and the logs keep to English). Whatever a sentence
//! repeats of the person's text or numbers goes through [`crate::i18n::echo`]: at most 40
//! characters, no control characters, numbers short.

use crate::i18n::echo::{Number, Text};
use crate::i18n::{Key, Lang, fill, text};

/// Where in a robot description a value sits, for messages.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Place {
    /// A top-level field of the robot.
    Robot,
    /// A field of joint `n` (1-based, as printed in DH tables).
    Joint(usize),
    /// The base transform.
    Base,
    /// The tool transform.
    Tool,
    /// Keep-out box `n` (1-based) of the robot file's `keep_out` list.
    KeepOut(usize),
}

impl Place {
    /// The place in `lang`, as the sentences of [`RobotError`] use it: English "joint 2"
    /// (after "In"), Finnish "Nivelessä 2" (the inflected place opens the sentence).
    pub fn text(&self, lang: Lang) -> String {
        match self {
            Place::Robot => text(lang, Key::PlaceRobot).to_string(),
            Place::Joint(n) => fill(lang, Key::PlaceJoint, &[n]),
            Place::Base => text(lang, Key::PlaceBase).to_string(),
            Place::Tool => text(lang, Key::PlaceTool).to_string(),
            Place::KeepOut(n) => fill(lang, Key::PlaceKeepOut, &[n]),
        }
    }
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text(Lang::En))
    }
}

/// What a field of a robot file should hold, for [`RobotError::WrongType`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Expected {
    /// A JSON object (a robot, a joint).
    Object,
    /// The list of joints.
    JointList,
    /// A transform object with `xyz` and `rpy_deg`.
    Transform,
    /// A string.
    Text,
    /// A number.
    Number,
    /// A list of three numbers.
    Triple,
    /// The list of keep-out boxes.
    BoxList,
}

impl Expected {
    /// What the field should hold, in words ("a number", "a list of 3 numbers").
    pub fn text(self, lang: Lang) -> &'static str {
        text(
            lang,
            match self {
                Expected::Object => Key::ExpectedObject,
                Expected::JointList => Key::ExpectedJointList,
                Expected::Transform => Key::ExpectedTransform,
                Expected::Text => Key::ExpectedText,
                Expected::Number => Key::ExpectedNumber,
                Expected::Triple => Key::ExpectedTriple,
                Expected::BoxList => Key::ExpectedBoxList,
            },
        )
    }
}

impl std::fmt::Display for Expected {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.text(Lang::En))
    }
}

/// A field of a robot description: each names its JSON key, so messages print exactly
/// the word a person wrote in the file or sees as a DH column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    /// `format`: the file format version.
    Format,
    /// `name`: a name.
    Name,
    /// `description`: the description.
    Description,
    /// `convention`: the DH convention.
    Convention,
    /// `length_unit`: the length unit.
    LengthUnit,
    /// `joints`: the list of joints.
    Joints,
    /// `base`: the base transform.
    Base,
    /// `tool`: the tool transform.
    Tool,
    /// `base_size`: the drawn base block's size.
    BaseSize,
    /// `hand_size`: the drawn hand's size.
    HandSize,
    /// `robot`: the robot object itself.
    Robot,
    /// `joint`: a joint object itself.
    Joint,
    /// `transform`: a transform object itself.
    Transform,
    /// `type`: the joint type.
    Type,
    /// `theta_deg`: θ in degrees (file).
    ThetaDeg,
    /// `theta`: θ (checked in degrees).
    Theta,
    /// `d`: d.
    D,
    /// `a`: a.
    A,
    /// `alpha_deg`: α in degrees (file).
    AlphaDeg,
    /// `alpha`: α (checked in degrees).
    Alpha,
    /// `min_deg`: a revolute lower limit in degrees (file).
    MinDeg,
    /// `max_deg`: a revolute upper limit in degrees (file).
    MaxDeg,
    /// `min`: the lower limit.
    Min,
    /// `max`: the upper limit.
    Max,
    /// `home`: the home value.
    Home,
    /// `max_speed`: the speed limit.
    MaxSpeed,
    /// `max_acceleration`: the acceleration limit.
    MaxAcceleration,
    /// `housing_size`: the joint housing's size (file).
    HousingSize,
    /// `housing`: the joint housing's size.
    Housing,
    /// `link_size`: the link's size (file).
    LinkSize,
    /// `link`: the link's size.
    Link,
    /// `xyz`: a transform's translation.
    Xyz,
    /// `rpy_deg`: a transform's roll-pitch-yaw angles.
    RpyDeg,
    /// `x`: a translation's x.
    X,
    /// `y`: a translation's y.
    Y,
    /// `z`: a translation's z.
    Z,
    /// `rotation`: a rotation matrix entry.
    Rotation,
    /// `keep_out`: the list of keep-out boxes.
    KeepOut,
    /// `centre`: a keep-out box's centre.
    Centre,
    /// `size`: a keep-out box's size.
    Size,
}

impl Field {
    /// The JSON key (or DH column) as written.
    pub fn name(self) -> &'static str {
        match self {
            Field::Format => "format",
            Field::Name => "name",
            Field::Description => "description",
            Field::Convention => "convention",
            Field::LengthUnit => "length_unit",
            Field::Joints => "joints",
            Field::Base => "base",
            Field::Tool => "tool",
            Field::BaseSize => "base_size",
            Field::HandSize => "hand_size",
            Field::Robot => "robot",
            Field::Joint => "joint",
            Field::Transform => "transform",
            Field::Type => "type",
            Field::ThetaDeg => "theta_deg",
            Field::Theta => "theta",
            Field::D => "d",
            Field::A => "a",
            Field::AlphaDeg => "alpha_deg",
            Field::Alpha => "alpha",
            Field::MinDeg => "min_deg",
            Field::MaxDeg => "max_deg",
            Field::Min => "min",
            Field::Max => "max",
            Field::Home => "home",
            Field::MaxSpeed => "max_speed",
            Field::MaxAcceleration => "max_acceleration",
            Field::HousingSize => "housing_size",
            Field::Housing => "housing",
            Field::LinkSize => "link_size",
            Field::Link => "link",
            Field::Xyz => "xyz",
            Field::RpyDeg => "rpy_deg",
            Field::X => "x",
            Field::Y => "y",
            Field::Z => "z",
            Field::Rotation => "rotation",
            Field::KeepOut => "keep_out",
            Field::Centre => "centre",
            Field::Size => "size",
        }
    }

    /// The DH editor's column of this field, for the fields that have one.
    pub fn dh_column(self) -> Option<DhColumn> {
        match self {
            Field::Theta | Field::ThetaDeg => Some(DhColumn::Theta),
            Field::D => Some(DhColumn::D),
            Field::A => Some(DhColumn::A),
            Field::Alpha | Field::AlphaDeg => Some(DhColumn::Alpha),
            Field::Min | Field::MinDeg => Some(DhColumn::Min),
            Field::Max | Field::MaxDeg => Some(DhColumn::Max),
            _ => None,
        }
    }
}

impl std::fmt::Display for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A column of the DH table as the editor shows it: θ, d, a, α, and the limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DhColumn {
    /// θ (the offset of a revolute joint, the value of a prismatic one's fixed angle).
    Theta,
    /// d.
    D,
    /// a.
    A,
    /// α.
    Alpha,
    /// The lower limit.
    Min,
    /// The upper limit.
    Max,
}

impl DhColumn {
    /// The column's position in the editor (0 = θ … 5 = max).
    pub fn index(self) -> usize {
        match self {
            DhColumn::Theta => 0,
            DhColumn::D => 1,
            DhColumn::A => 2,
            DhColumn::Alpha => 3,
            DhColumn::Min => 4,
            DhColumn::Max => 5,
        }
    }
}

/// Everything that can be wrong with a robot description or with a request on it.
#[derive(Debug, Clone, PartialEq)]
pub enum RobotError {
    /// The text is not JSON at all.
    Syntax {
        /// 1-based line of the problem.
        line: usize,
        /// 1-based column of the problem.
        column: usize,
        /// What the JSON reader said.
        reason: String,
    },
    /// A required field is absent.
    MissingField {
        /// Where.
        place: Place,
        /// Which field.
        field: Field,
    },
    /// A field that the format does not know (often a typo).
    UnknownField {
        /// Where.
        place: Place,
        /// The unknown field.
        field: String,
        /// The fields allowed there, comma-separated.
        known: String,
    },
    /// A field holds the wrong kind of JSON value.
    WrongType {
        /// Where.
        place: Place,
        /// Which field.
        field: Field,
        /// What it should be.
        expected: Expected,
    },
    /// The DH convention is neither "standard" nor "modified".
    UnknownConvention(String),
    /// The joint type is neither revolute nor prismatic.
    UnknownJointType {
        /// 1-based joint number.
        joint: usize,
        /// What was written.
        found: String,
    },
    /// The length unit is not one the app knows.
    UnknownLengthUnit(String),
    /// NaN or ±infinity.
    NotFinite {
        /// Where.
        place: Place,
        /// Which field.
        field: Field,
        /// The offending value, printed.
        value: f64,
    },
    /// No joints at all.
    EmptyChain,
    /// More joints than the app handles.
    TooManyJoints {
        /// How many were given.
        count: usize,
        /// The maximum.
        max: usize,
    },
    /// A length or angle whose size makes no physical sense.
    TooLarge {
        /// Where.
        place: Place,
        /// Which field.
        field: Field,
        /// The value.
        value: f64,
        /// The largest allowed magnitude.
        limit: f64,
    },
    /// A drawn part's size below zero.
    NegativeSize {
        /// Where.
        place: Place,
        /// Which field.
        field: Field,
        /// The value.
        value: f64,
    },
    /// A limit that must be above zero (an acceleration limit) is zero or negative.
    NotPositive {
        /// Where.
        place: Place,
        /// Which field.
        field: Field,
        /// The value.
        value: f64,
    },
    /// A joint's lower limit is above its upper limit.
    LimitsReversed {
        /// 1-based joint number.
        joint: usize,
        /// Lower limit as written.
        min: f64,
        /// Upper limit as written.
        max: f64,
    },
    /// A prismatic joint needs a finite stroke.
    PrismaticWithoutLimits {
        /// 1-based joint number.
        joint: usize,
    },
    /// No preset by that name.
    UnknownPreset(String, String),
    /// A joint vector of the wrong length.
    WrongJointCount {
        /// The robot's joint count.
        expected: usize,
        /// The given count.
        found: usize,
    },
    /// A joint value that is NaN or infinite.
    JointValueNotFinite {
        /// 1-based joint number.
        joint: usize,
        /// The value.
        value: f64,
    },
    /// A prismatic joint's value outside its stroke (more than [`crate::kinematics::robot::STROKE_SLACK`]).
    JointOutsideStroke {
        /// 1-based joint number.
        joint: usize,
        /// The value.
        value: f64,
        /// The stroke's lower end.
        min: f64,
        /// The stroke's upper end.
        max: f64,
    },
    /// Forward kinematics gave a pose that is not finite (a length overflowed to
    /// infinity, or NaN): nothing computed from it (a Jacobian, its singular values, an
    /// IK step) would mean anything, so the request stops here.
    PoseNotFinite,
}

impl RobotError {
    /// The error as a sentence in `lang`.
    pub fn sentence(&self, lang: Lang) -> String {
        let at = |place: &Place| place.text(lang);
        match self {
            RobotError::Syntax {
                line,
                column,
                reason,
            } => fill(
                lang,
                Key::ErrSyntax,
                &[line, column, &crate::i18n::echo::text_within(reason, 80)],
            ),
            RobotError::MissingField { place, field } => {
                fill(lang, Key::ErrMissingField, &[&at(place), field])
            }
            RobotError::UnknownField {
                place,
                field,
                known,
            } => fill(
                lang,
                Key::ErrUnknownField,
                &[&at(place), &Text(field), known],
            ),
            RobotError::WrongType {
                place,
                field,
                expected,
            } => fill(
                lang,
                Key::ErrWrongType,
                &[&at(place), field, &expected.text(lang)],
            ),
            RobotError::UnknownConvention(found) => {
                fill(lang, Key::ErrUnknownConvention, &[&Text(found)])
            }
            RobotError::UnknownJointType { joint, found } => {
                fill(lang, Key::ErrUnknownJointType, &[joint, &Text(found)])
            }
            RobotError::UnknownLengthUnit(found) => {
                fill(lang, Key::ErrUnknownLengthUnit, &[&Text(found)])
            }
            RobotError::NotFinite {
                place,
                field,
                value,
            } => fill(
                lang,
                Key::ErrNotFinite,
                &[&at(place), field, &Number(*value)],
            ),
            RobotError::EmptyChain => text(lang, Key::ErrEmptyChain).to_string(),
            RobotError::TooManyJoints { count, max } => {
                fill(lang, Key::ErrTooManyJoints, &[count, max])
            }
            RobotError::TooLarge {
                place,
                field,
                value,
                limit,
            } => fill(
                lang,
                Key::ErrTooLarge,
                &[&at(place), field, &Number(*value), &Number(*limit)],
            ),
            RobotError::NegativeSize {
                place,
                field,
                value,
            } => fill(
                lang,
                Key::ErrNegativeSize,
                &[&at(place), field, &Number(*value)],
            ),
            RobotError::NotPositive {
                place,
                field,
                value,
            } => fill(
                lang,
                Key::ErrNotPositive,
                &[&at(place), field, &Number(*value)],
            ),
            RobotError::LimitsReversed { joint, min, max } => fill(
                lang,
                Key::ErrLimitsReversed,
                &[joint, &Number(*min), &Number(*max)],
            ),
            RobotError::PrismaticWithoutLimits { joint } => {
                fill(lang, Key::ErrPrismaticWithoutLimits, &[joint])
            }
            RobotError::UnknownPreset(name, presets) => {
                fill(lang, Key::ErrUnknownPreset, &[&Text(name), presets])
            }
            RobotError::WrongJointCount { expected, found } => {
                fill(lang, Key::ErrWrongJointCount, &[expected, found])
            }
            RobotError::JointValueNotFinite { joint, value } => {
                fill(lang, Key::ErrJointValueNotFinite, &[joint, &Number(*value)])
            }
            RobotError::JointOutsideStroke {
                joint,
                value,
                min,
                max,
            } => fill(
                lang,
                Key::ErrJointOutsideStroke,
                &[joint, &Number(*value), &Number(*min), &Number(*max)],
            ),
            RobotError::PoseNotFinite => text(lang, Key::ErrPoseNotFinite).to_string(),
        }
    }

    /// The DH table cell an error is about: (joint, 0-based; column), for the editor to
    /// place its sentence beside the cell without reading the text.
    pub fn dh_cell(&self) -> Option<(usize, DhColumn)> {
        match self {
            RobotError::NotFinite {
                place: Place::Joint(n),
                field,
                ..
            }
            | RobotError::TooLarge {
                place: Place::Joint(n),
                field,
                ..
            }
            | RobotError::MissingField {
                place: Place::Joint(n),
                field,
            }
            | RobotError::WrongType {
                place: Place::Joint(n),
                field,
                ..
            } => field.dh_column().map(|c| (n.saturating_sub(1), c)),
            RobotError::LimitsReversed { joint, .. } => {
                Some((joint.saturating_sub(1), DhColumn::Min))
            }
            _ => None,
        }
    }

    /// Turns a serde_json error into a `Syntax` error with its position.
    pub fn from_json(err: &serde_json::Error) -> Self {
        let text = err.to_string();
        // serde_json appends " at line L column C"; keep only the reason.
        let reason = match text.find(" at line ") {
            Some(cut) => text[..cut].to_string(),
            None => text,
        };
        RobotError::Syntax {
            line: err.line(),
            column: err.column(),
            reason,
        }
    }
}

impl std::fmt::Display for RobotError {
    /// The English sentence.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.sentence(Lang::En))
    }
}

impl std::error::Error for RobotError {}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn the_english_sentences_read_as_before_the_catalogue() {
        let cases = [
            (
                RobotError::MissingField {
                    place: Place::Joint(2),
                    field: Field::D,
                },
                "In joint 2, the field \"d\" is missing.",
            ),
            (
                RobotError::WrongType {
                    place: Place::Tool,
                    field: Field::Xyz,
                    expected: Expected::Triple,
                },
                "In the tool transform, the field \"xyz\" must be a list of 3 numbers.",
            ),
            (
                RobotError::TooLarge {
                    place: Place::Robot,
                    field: Field::BaseSize,
                    value: 2.5e9,
                    limit: 1e9,
                },
                "In the robot, the field \"base_size\" is 2500000000, larger in size than the limit 1000000000.",
            ),
            (
                RobotError::LimitsReversed {
                    joint: 3,
                    min: 10.0,
                    max: -1.5,
                },
                "Joint 3: the lower limit 10 is above the upper limit -1.5.",
            ),
            (
                RobotError::WrongJointCount {
                    expected: 6,
                    found: 2,
                },
                "The robot has 6 joints but 2 joint values were given.",
            ),
        ];
        for (error, english) in cases {
            assert_eq!(error.to_string(), english);
            assert_eq!(error.sentence(Lang::En), english);
        }
    }

    #[test]
    fn a_finnish_sentence_opens_with_the_inflected_place() {
        let e = RobotError::NotFinite {
            place: Place::Joint(2),
            field: Field::A,
            value: f64::INFINITY,
        };
        assert_eq!(
            e.sentence(Lang::Fi),
            "Nivelessä 2 kenttä \"a\" ei ole äärellinen luku (inf)."
        );
        let e = RobotError::WrongType {
            place: Place::Base,
            field: Field::Xyz,
            expected: Expected::Number,
        };
        assert_eq!(
            e.sentence(Lang::Fi),
            "Kannan muunnoksessa kentän \"xyz\" on oltava luku."
        );
    }
}
