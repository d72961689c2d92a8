//! The core's typed errors and named things in words: the core returns data (which joint,
//! which field, which value) and this module makes the sentence a person reads, in English
//! or Finnish. Whatever a sentence repeats of the person's text or numbers goes through
//! [`crate::echo`]: at most 40 characters, no control characters, numbers short.

use armlab_core::collision::CollisionReport;
use armlab_core::collision::Obstacle;
use armlab_core::error::{Expected, Place, RobotError};
use armlab_core::exercise::{Diagnosis, LengthField, Verdict, Where};
use armlab_core::ik::{BadTarget, IkError, IkMethod};
use armlab_core::jacobian::{Task, ToolAxis};
use armlab_core::motion::{MotionError, Setting};
use armlab_core::parts::{Part, PartKind};
use armlab_core::path::{PathIssue, PathProblem};
use armlab_core::robot::JointKind;

use crate::echo::{Number, Text};
use crate::{Key, Lang, fill, text};

/// A typed error or verdict as a sentence a student can act on.
pub trait Sentence {
    /// The sentence in `lang`.
    fn sentence(&self, lang: Lang) -> String;
}

/// A named thing of the core (a place in a robot file, a setting, a part) in words, as
/// sentences use it.
pub trait Name {
    /// The name in `lang`.
    fn name(&self, lang: Lang) -> String;
}

/// A choice of a menu (a task, an IK method): the catalogue key of its name.
pub trait Labelled {
    /// The catalogue key of the menu's name.
    fn label_key(self) -> Key;
}

impl Name for Place {
    /// The place in `lang`, as the sentences of [`RobotError`] use it: English "joint 2"
    /// (after "In"), Finnish "Nivelessä 2" (the inflected place opens the sentence).
    fn name(&self, lang: Lang) -> String {
        match self {
            Place::Robot => text(lang, Key::PlaceRobot).to_string(),
            Place::Joint(n) => fill(lang, Key::PlaceJoint, &[n]),
            Place::Base => text(lang, Key::PlaceBase).to_string(),
            Place::Tool => text(lang, Key::PlaceTool).to_string(),
            Place::KeepOut(n) => fill(lang, Key::PlaceKeepOut, &[n]),
        }
    }
}

impl Name for Expected {
    /// What the field should hold, in words ("a number", "a list of 3 numbers").
    fn name(&self, lang: Lang) -> String {
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
        .to_string()
    }
}

impl Sentence for RobotError {
    fn sentence(&self, lang: Lang) -> String {
        file_sentence(self, lang)
            .or_else(|| value_sentence(self, lang))
            .unwrap_or_default()
    }
}

/// The sentence of an error in a robot file's form (its syntax, a field missing, unknown
/// or of the wrong type, an unknown name); `None` for an error in a value.
fn file_sentence(error: &RobotError, lang: Lang) -> Option<String> {
    let at = |place: &Place| place.name(lang);
    Some(match error {
        RobotError::Syntax {
            line,
            column,
            reason,
        } => fill(
            lang,
            Key::ErrSyntax,
            &[line, column, &crate::echo::text_within(reason, 80)],
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
            &[&at(place), field, &expected.name(lang)],
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
        _ => return None,
    })
}

/// The sentence of an error in a robot's values (a number out of range, limits, the joint
/// vector, the pose); `None` for an error in the file's form.
fn value_sentence(error: &RobotError, lang: Lang) -> Option<String> {
    let at = |place: &Place| place.name(lang);
    Some(match error {
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
        _ => return None,
    })
}

impl Sentence for IkError {
    /// The error as a sentence in `lang`.
    fn sentence(&self, lang: Lang) -> String {
        match self {
            IkError::Robot(e) => e.sentence(lang),
            IkError::Target(why) => {
                let why = text(
                    lang,
                    match why {
                        BadTarget::NotFinite => Key::TargetNotFinite,
                        BadTarget::NotRotation => Key::TargetNotRotation,
                    },
                );
                fill(lang, Key::IkBadTarget, &[&why])
            }
            IkError::Settings { name, value } => {
                fill(lang, Key::IkBadSettings, &[name, &Number(*value)])
            }
            IkError::NoClosedForm(robot) => fill(lang, Key::IkNoClosedForm, &[&Text(robot)]),
            IkError::SettingChoice {
                name,
                value,
                allowed,
            } => fill(lang, Key::IkBadChoice, &[name, &Text(value), allowed]),
            IkError::TargetTooFar { distance, limit } => fill(
                lang,
                Key::IkTargetTooFar,
                &[&Number(*distance), &Number(*limit)],
            ),
        }
    }
}

impl Labelled for IkMethod {
    /// The catalogue key of the menu's name.
    fn label_key(self) -> Key {
        match self {
            IkMethod::DampedLeastSquares => Key::MethodDls,
            IkMethod::PseudoInverse => Key::MethodPinv,
            IkMethod::JacobianTranspose { .. } => Key::MethodTranspose,
            IkMethod::ClosedForm => Key::MethodClosedForm,
        }
    }
}

impl Labelled for Task {
    /// The catalogue key of the menu's name.
    fn label_key(self) -> Key {
        match self {
            Task::Position => Key::TaskPosition,
            Task::PositionAndAxis(ToolAxis::X) => Key::TaskAxisX,
            Task::PositionAndAxis(ToolAxis::Y) => Key::TaskAxisY,
            Task::PositionAndAxis(ToolAxis::Z) => Key::TaskAxisZ,
            Task::FullPose => Key::TaskFullPose,
        }
    }
}

impl Sentence for PathProblem {
    /// The problem as a sentence in `lang`.
    fn sentence(&self, lang: Lang) -> String {
        let key = match self.issue {
            PathIssue::OutOfReach => Key::PathOutOfReach,
            PathIssue::Singular => Key::PathSingular,
            PathIssue::Jump => Key::PathJump,
        };
        fill(lang, key, &[&format!("{:.3}", self.s), &self.index])
    }
}

impl Name for PathIssue {
    /// The short name of an issue (a legend, a list).
    fn name(&self, lang: Lang) -> String {
        text(
            lang,
            match self {
                PathIssue::OutOfReach => Key::PathIssueOutOfReach,
                PathIssue::Singular => Key::PathIssueSingular,
                PathIssue::Jump => Key::PathIssueJump,
            },
        )
        .to_string()
    }
}

impl Name for Setting {
    /// The setting's name in `lang`, as sentences use it.
    fn name(&self, lang: Lang) -> String {
        let key = match *self {
            Setting::Gain => Key::SettingGain,
            Setting::Kp => Key::SettingKp,
            Setting::Ki => Key::SettingKi,
            Setting::Kd => Key::SettingKd,
            Setting::DeadBand => Key::SettingDeadBand,
            Setting::TimeScale => Key::SettingTimeScale,
            Setting::FrameTime => Key::SettingFrameTime,
            Setting::TimeConstant => Key::SettingTimeConstant,
            Setting::Inertia => Key::SettingInertia,
            Setting::Friction => Key::SettingFriction,
            Setting::Load => Key::SettingLoad,
            Setting::MaxSpeed => Key::SettingMaxSpeed,
            Setting::MaxAcceleration => Key::SettingMaxAcceleration,
            Setting::Goal(n) => return fill(lang, Key::SettingGoal, &[&n]),
            Setting::Waypoint(n) => return fill(lang, Key::SettingWaypoint, &[&n]),
            Setting::PathSteps => Key::SettingPathSteps,
            Setting::RecordLength => Key::SettingRecordLength,
            Setting::KeepOut(n) => return fill(lang, Key::PartKeepOut, &[&n]),
        };
        text(lang, key).to_string()
    }
}

impl Sentence for MotionError {
    /// The error as a sentence in `lang`.
    fn sentence(&self, lang: Lang) -> String {
        match self {
            MotionError::NotFinite { setting, value } => {
                fill(lang, Key::MotionNotFinite, &[&setting.name(lang), value])
            }
            MotionError::Negative { setting, value } => {
                fill(lang, Key::MotionNegative, &[&setting.name(lang), value])
            }
            MotionError::NotPositive { setting, value } => {
                fill(lang, Key::MotionNotPositive, &[&setting.name(lang), value])
            }
            MotionError::TooLarge {
                setting,
                value,
                max,
            } => fill(
                lang,
                Key::MotionTooLarge,
                &[&setting.name(lang), value, &format!("{max:.6}")],
            ),
            MotionError::WrongJointCount { expected, found } => RobotError::WrongJointCount {
                expected: *expected,
                found: *found,
            }
            .sentence(lang),
            MotionError::Robot(e) => e.sentence(lang),
            MotionError::BadPose { setting, why } => {
                let why = text(
                    lang,
                    match why {
                        BadTarget::NotFinite => Key::TargetNotFinite,
                        BadTarget::NotRotation => Key::TargetNotRotation,
                    },
                );
                fill(lang, Key::MotionBadPose, &[&setting.name(lang), &why])
            }
            MotionError::Ik(e) => e.sentence(lang),
        }
    }
}

/// The first contact as a sentence in `lang` ("link 5 touches the base."), naming
/// parts of `parts` (the list the check was given).
pub fn contact_sentence(report: &CollisionReport, parts: &[Part], lang: Lang) -> Option<String> {
    let c = report.contacts.first()?;
    let name = |i: usize| parts.get(i).map_or_else(String::new, |p| p.name(lang));
    let other = match c.other {
        Obstacle::Part(i) => name(i),
        Obstacle::Floor => text(lang, Key::PartFloor).to_string(),
        Obstacle::KeepOut(k) => fill(lang, Key::PartKeepOut, &[&(k + 1)]),
    };
    Some(fill(lang, Key::CollisionContact, &[&name(c.part), &other]))
}

impl Name for Part {
    /// "the base", "link 3", "joint 3's housing", "the hand".
    fn name(&self, lang: Lang) -> String {
        match self.kind {
            PartKind::Base => text(lang, Key::PartBase).to_string(),
            PartKind::Link => fill(lang, Key::PartLink, &[&self.body]),
            PartKind::Housing => fill(lang, Key::PartHousing, &[&self.body]),
            PartKind::Flange | PartKind::Palm | PartKind::Finger => {
                text(lang, Key::PartHand).to_string()
            }
        }
    }
}

impl Sentence for Where {
    /// "Joint 3's frame is the first to disagree" in `lang`.
    fn sentence(&self, lang: Lang) -> String {
        match self {
            Where::Joint(j) => fill(lang, Key::ExerciseAtJoint, &[j]),
            Where::Tool => text(lang, Key::ExerciseAtTool).to_string(),
        }
    }
}

impl Sentence for Verdict {
    /// The answer as a sentence in `lang` (from the catalogue).
    fn sentence(&self, lang: Lang) -> String {
        match self {
            Verdict::Correct => text(lang, Key::ExerciseCorrect).to_string(),
            Verdict::Wrong(d) => d.sentence(lang),
        }
    }
}

/// An angle of a table cell in degrees in (−180°, 180°], to the table's 0.01 as its lengths.
fn degrees(radians: f64) -> String {
    let d = armlab_core::angles::wrap_to_pi(radians).to_degrees();
    format!("{}°", cell_length(d))
}

/// A length of a table cell to the table's 0.01: a solved length carries rounding noise.
fn cell_length(v: f64) -> String {
    crate::echo::number((v * 100.0).round() / 100.0)
}

/// A sentence of `key` that asks to change an angle of `row` from `from` to `to`.
fn angle_change(lang: Lang, key: Key, (at, row): (Where, usize), from: f64, to: f64) -> String {
    fill(
        lang,
        key,
        &[&at.sentence(lang), &row, &degrees(from), &degrees(to)],
    )
}

/// A sentence of `key` that asks to change the length in `field` of `row` from `from` to
/// `to`.
fn length_change(
    lang: Lang,
    key: Key,
    (at, row, field): (Where, usize, LengthField),
    from: f64,
    to: f64,
) -> String {
    fill(
        lang,
        key,
        &[
            &at.sentence(lang),
            &field.symbol(),
            &row,
            &cell_length(from),
            &cell_length(to),
        ],
    )
}

impl Sentence for Diagnosis {
    /// The diagnosis as a sentence in `lang` (from the catalogue).
    fn sentence(&self, lang: Lang) -> String {
        match *self {
            Diagnosis::JointCount { expected, found } => {
                fill(lang, Key::ExerciseJointCount, &[&expected, &found])
            }
            Diagnosis::JointKind { joint, expected } => {
                let kind = match expected {
                    JointKind::Revolute => text(lang, Key::ExerciseRevolute),
                    JointKind::Prismatic => text(lang, Key::ExercisePrismatic),
                };
                fill(lang, Key::ExerciseJointKind, &[&joint, &kind])
            }
            Diagnosis::AxisReversed { joint } => fill(lang, Key::ExerciseAxisReversed, &[&joint]),
            Diagnosis::FrameDisagrees { joint } => {
                fill(lang, Key::ExerciseFrameDisagrees, &[&joint])
            }
            Diagnosis::ToolDisagrees => text(lang, Key::ExerciseToolDisagrees).to_string(),
            // The diagnoses that name a cell of the table.
            _ => cell_sentence(self, lang).unwrap_or_default(),
        }
    }
}

/// The sentence of a diagnosis that names a cell of the table and what to change it to;
/// `None` for the others.
fn cell_sentence(d: &Diagnosis, lang: Lang) -> Option<String> {
    Some(match *d {
        Diagnosis::TwistSign { at, row, found } => {
            angle_change(lang, Key::ExerciseTwistSign, (at, row), found, -found)
        }
        Diagnosis::MissingOffset {
            at,
            row,
            offset,
            found,
        } => angle_change(
            lang,
            Key::ExerciseMissingOffset,
            (at, row),
            found,
            found + offset,
        ),
        Diagnosis::LengthInWrongRow {
            at,
            row,
            field,
            to_row,
            to_field,
        } => fill(
            lang,
            Key::ExerciseLengthInWrongRow,
            &[
                &at.sentence(lang),
                &field.symbol(),
                &row,
                &to_field.symbol(),
                &to_row,
            ],
        ),
        Diagnosis::LengthSign {
            at,
            row,
            field,
            found,
        } => length_change(
            lang,
            Key::ExerciseLengthSign,
            (at, row, field),
            found,
            -found,
        ),
        Diagnosis::LengthValue {
            at,
            row,
            field,
            found,
            expected,
        } => length_change(
            lang,
            Key::ExerciseLengthValue,
            (at, row, field),
            found,
            expected,
        ),
        _ => return None,
    })
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    use armlab_core::error::Field;
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
