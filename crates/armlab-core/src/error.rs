//! Typed errors of the core, as data: each names the joint (counted from 1, as in the DH
//! table), the field and the value, so that the text catalogue (`armlab_text`) can make a
//! whole sentence a student can act on, in English or Finnish. `Display` shows the
//! variant for logs and developers, not for people.

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
    /// A prismatic joint's value outside its stroke (more than [`crate::robot::STROKE_SLACK`]).
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
    /// What kind of error this is, for logs; `{:?}` shows its data, and a person reads the
    /// sentence the text catalogue makes of it (`armlab_text::Sentence`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a robot description or its joint values are not valid")
    }
}

impl std::error::Error for RobotError {}
