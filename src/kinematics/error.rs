//! Typed errors of the core. Each message is a whole sentence a student can act on: it
//! names the joint (counted from 1, as in the DH table) and the field.

use thiserror::Error;

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
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Place::Robot => write!(f, "the robot"),
            Place::Joint(n) => write!(f, "joint {n}"),
            Place::Base => write!(f, "the base transform"),
            Place::Tool => write!(f, "the tool transform"),
        }
    }
}

/// Everything that can be wrong with a robot description or with a request on it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RobotError {
    /// The text is not JSON at all.
    #[error("The robot file is not valid JSON (line {line}, column {column}): {reason}.")]
    Syntax {
        /// 1-based line of the problem.
        line: usize,
        /// 1-based column of the problem.
        column: usize,
        /// What the JSON reader said.
        reason: String,
    },
    /// A required field is absent.
    #[error("In {place}, the field \"{field}\" is missing.")]
    MissingField {
        /// Where.
        place: Place,
        /// Which field.
        field: String,
    },
    /// A field that the format does not know (often a typo).
    #[error("In {place}, the field \"{field}\" is not known; the known fields are: {known}.")]
    UnknownField {
        /// Where.
        place: Place,
        /// The unknown field.
        field: String,
        /// The fields allowed there, comma-separated.
        known: String,
    },
    /// A field holds the wrong kind of JSON value.
    #[error("In {place}, the field \"{field}\" must be {expected}.")]
    WrongType {
        /// Where.
        place: Place,
        /// Which field.
        field: String,
        /// What it should be, in words ("a number", "a list of 3 numbers").
        expected: String,
    },
    /// The DH convention is neither "standard" nor "modified".
    #[error(
        "The convention \"{0}\" is not known: use \"standard\" (Denavit–Hartenberg, Spong) or \"modified\" (Craig)."
    )]
    UnknownConvention(String),
    /// The joint type is neither revolute nor prismatic.
    #[error("Joint {joint} has the type \"{found}\": use \"revolute\" or \"prismatic\".")]
    UnknownJointType {
        /// 1-based joint number.
        joint: usize,
        /// What was written.
        found: String,
    },
    /// The length unit is not one the app knows.
    #[error("The length unit \"{0}\" is not known: use \"mm\" or \"m\".")]
    UnknownLengthUnit(String),
    /// NaN or ±infinity.
    #[error("In {place}, the field \"{field}\" is not a finite number ({value}).")]
    NotFinite {
        /// Where.
        place: Place,
        /// Which field.
        field: String,
        /// The offending value, printed.
        value: f64,
    },
    /// No joints at all.
    #[error("The robot has no joints: a chain needs at least one.")]
    EmptyChain,
    /// More joints than the app handles.
    #[error("The robot has {count} joints; ArmLab handles at most {max}.")]
    TooManyJoints {
        /// How many were given.
        count: usize,
        /// The maximum.
        max: usize,
    },
    /// A length or angle whose size makes no physical sense.
    #[error("In {place}, the field \"{field}\" is {value}, larger in size than the limit {limit}.")]
    TooLarge {
        /// Where.
        place: Place,
        /// Which field.
        field: String,
        /// The value.
        value: f64,
        /// The largest allowed magnitude.
        limit: f64,
    },
    /// A drawn part's size below zero.
    #[error("In {place}, the field \"{field}\" holds {value}: a size cannot be negative.")]
    NegativeSize {
        /// Where.
        place: Place,
        /// Which field.
        field: String,
        /// The value.
        value: f64,
    },
    /// A joint's lower limit is above its upper limit.
    #[error("Joint {joint}: the lower limit {min} is above the upper limit {max}.")]
    LimitsReversed {
        /// 1-based joint number.
        joint: usize,
        /// Lower limit as written.
        min: f64,
        /// Upper limit as written.
        max: f64,
    },
    /// A prismatic joint needs a finite stroke.
    #[error(
        "Joint {joint} is prismatic and needs both limits (\"min\" and \"max\", in length units)."
    )]
    PrismaticWithoutLimits {
        /// 1-based joint number.
        joint: usize,
    },
    /// No preset by that name.
    #[error("There is no robot called \"{0}\"; the presets are: {1}.")]
    UnknownPreset(String, String),
    /// A joint vector of the wrong length.
    #[error("The robot has {expected} joints but {found} joint values were given.")]
    WrongJointCount {
        /// The robot's joint count.
        expected: usize,
        /// The given count.
        found: usize,
    },
    /// A joint value that is NaN or infinite.
    #[error("The value of joint {joint} is not a finite number ({value}).")]
    JointValueNotFinite {
        /// 1-based joint number.
        joint: usize,
        /// The value.
        value: f64,
    },
}

impl RobotError {
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
