//! The messages and their fields, as serde types: `#[serde(tag = "type")]` makes each a
//! JSON object whose `type` names the variant; unknown fields are errors.

use serde::{Deserialize, Serialize};

/// The longest share-link fragment a [`State`] carries, in bytes.
pub const MAX_LINK_BYTES: usize = 8192;
/// The longest camera part a [`State`] carries, in bytes.
pub const MAX_CAMERA_BYTES: usize = 256;
/// A question's prompt is cut to this many characters.
pub const MAX_PROMPT_CHARS: usize = 200;
/// A student's nickname is cut to this many characters.
pub const MAX_NICKNAME_CHARS: usize = 24;
/// A number question's unit is cut to this many characters.
pub const MAX_UNIT_CHARS: usize = 12;
/// Each option of a choice question is cut to this many characters.
pub const MAX_CHOICE_CHARS: usize = 40;
/// The most options a choice question has (and the fewest is two).
pub const MAX_OPTIONS: usize = 8;
/// The largest coordinate of a point answer, in metres (either sign): far beyond any
/// arm's reach, near enough that a histogram of the answers stays readable.
pub const MAX_POINT_METRES: f64 = 1000.0;
/// The largest magnitude of a number answer (or truth).
pub const MAX_NUMBER: f64 = 1e12;

/// What the lecturer's page shows, as the students' pages follow it. The server never
/// reads it: it stores the latest and forwards it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct State {
    /// The page's share-link fragment (without `#`): robot, joints, target, task, method,
    /// display settings, overlays and presentation's hidden entries. Printable ASCII, at
    /// most [`MAX_LINK_BYTES`].
    pub link: String,
    /// The camera part of the link, for students who follow the camera too. Printable
    /// ASCII, at most [`MAX_CAMERA_BYTES`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<String>,
}

/// A question the lecturer asks the room. `id` is the lecturer's (a new question has a
/// new id); answers name it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", deny_unknown_fields)]
pub enum Question {
    /// "Where will the tool be?": answered with a point in metres.
    Point {
        /// The question's id.
        id: u32,
        /// The question as the students read it (cut to [`MAX_PROMPT_CHARS`], cleaned).
        prompt: String,
    },
    /// A number (an entry of T or J, det J, a joint angle): answered with a number.
    Number {
        /// The question's id.
        id: u32,
        /// The question as the students read it.
        prompt: String,
        /// The unit the answer is in (cut to [`MAX_UNIT_CHARS`]), if any.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        unit: Option<String>,
    },
    /// A choice among 2 to [`MAX_OPTIONS`] options: answered with an option's index.
    Choice {
        /// The question's id.
        id: u32,
        /// The question as the students read it.
        prompt: String,
        /// The options, each cut to [`MAX_CHOICE_CHARS`].
        options: Vec<String>,
    },
}

impl Question {
    /// The question's id.
    pub fn id(&self) -> u32 {
        match self {
            Self::Point { id, .. } | Self::Number { id, .. } | Self::Choice { id, .. } => *id,
        }
    }

    /// Whether `answer` answers this question: the same kind, and for a choice an index
    /// among the options.
    pub fn fits(&self, answer: &Answer) -> bool {
        match (self, answer) {
            (Self::Point { .. }, Answer::Point { .. })
            | (Self::Number { .. }, Answer::Number { .. }) => true,
            (Self::Choice { options, .. }, Answer::Choice { index }) => {
                (*index as usize) < options.len()
            }
            _ => false,
        }
    }

    /// The kind's name as the CSV writes it: `Point`, `Number` or `Choice`.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Self::Point { .. } => "Point",
            Self::Number { .. } => "Number",
            Self::Choice { .. } => "Choice",
        }
    }
}

/// An answer (a student's, or the lecturer's truth).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", deny_unknown_fields)]
pub enum Answer {
    /// A point in the base frame, metres; finite, each coordinate within
    /// ±[`MAX_POINT_METRES`].
    Point {
        /// x, y, z in metres.
        at: [f64; 3],
    },
    /// A number; finite, within ±[`MAX_NUMBER`].
    Number {
        /// The number.
        value: f64,
    },
    /// The index of an option (from 0).
    Choice {
        /// The option's index.
        index: u32,
    },
}

/// What a page sends the server.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", deny_unknown_fields)]
pub enum ClientMessage {
    /// Lecturer: create a new class (answered by `Created`). A struct variant (`{}`), so
    /// that serde refuses unknown fields beside the type as it does everywhere else.
    Create {},
    /// Lecturer: take control of the class `code` with `token` again (a reload, a second
    /// device, or after a server restart: the server re-creates the class when the code is
    /// free), showing `state`.
    Resume {
        /// The class's join code.
        code: String,
        /// The lecturer's token from `Created`.
        token: String,
        /// What the lecturer's page shows now.
        state: State,
    },
    /// Lecturer: what the page shows now.
    State {
        /// The state.
        state: State,
    },
    /// Lecturer: ask the room a question (answers to the previous one close).
    Ask {
        /// The question.
        question: Question,
    },
    /// Lecturer: show the truth beside the answers of question `question`.
    Reveal {
        /// The question's id.
        question: u32,
        /// The right answer.
        truth: Answer,
    },
    /// Lecturer: end the class for everyone.
    End {},
    /// Student: join the class `code`.
    Join {
        /// The join code (case and separators ignored, see [`normalize_code`](crate::normalize_code)).
        code: String,
        /// An optional nickname (cut to [`MAX_NICKNAME_CHARS`], cleaned; never stored
        /// with the answers).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        nickname: Option<String>,
    },
    /// Student: answer question `question` (the last answer counts).
    Answer {
        /// The question's id.
        question: u32,
        /// The answer.
        value: Answer,
    },
}

/// Why the server refused a `Create`, `Resume` or `Join`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Refusal {
    /// No class has this code (never created, expired or ended).
    UnknownCode,
    /// The code is not a join code's shape.
    BadCode,
    /// `Resume` with a token that is not the class's.
    WrongToken,
    /// `Resume` of a code another lecturer's class holds.
    CodeTaken,
    /// Too many join attempts from this address: wait a minute.
    TooManyAttempts,
    /// The server holds as many classes (or students) as it may.
    Full,
    /// This connection is already in a class.
    AlreadyInClass,
}

/// Why the server dropped a message (it is counted, never forwarded).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum DropReason {
    /// Larger than [`MAX_CLIENT_BYTES`](crate::MAX_CLIENT_BYTES).
    TooLarge,
    /// Not a message: not JSON, an unknown type or field, a wrong type.
    Malformed,
    /// A field out of its bounds (a non-finite or huge number, a bad code, too many options).
    Invalid,
    /// Not this connection's to send (a student driving, a message before `Join`).
    NotAllowed,
    /// Faster than the connection's rate limit.
    RateLimited,
    /// An answer to a question that is not open, or of another kind.
    NotOpen,
}

/// A list of kinds, each named as the JSON writes it (the page's reader finds a kind by
/// its name; a test checks the names against serde's).
macro_rules! named {
    ($type:ident: $($variant:ident),* $(,)?) => {
        impl $type {
            /// Every kind.
            pub const ALL: [$type; [$(stringify!($variant)),*].len()] = [$($type::$variant),*];

            /// The kind's name in the JSON.
            pub fn name(self) -> &'static str {
                match self {
                    $($type::$variant => stringify!($variant),)*
                }
            }
        }
    };
}

named!(Refusal: UnknownCode, BadCode, WrongToken, CodeTaken, TooManyAttempts, Full, AlreadyInClass);
named!(DropReason: TooLarge, Malformed, Invalid, NotAllowed, RateLimited, NotOpen);

/// What the server sends a page.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", deny_unknown_fields)]
pub enum ServerMessage {
    /// To the lecturer: the class exists; `token` is the control (keep it).
    Created {
        /// The join code.
        code: String,
        /// The lecturer's token.
        token: String,
    },
    /// To a student: in the class; the lecturer's latest state and the open question.
    Joined {
        /// The lecturer's latest state (none before the first).
        #[serde(default)]
        state: Option<State>,
        /// The open question, if any.
        #[serde(default)]
        question: Option<Question>,
    },
    /// A `Create`, `Resume` or `Join` refused.
    Refused {
        /// Why.
        reason: Refusal,
    },
    /// To students: the lecturer's latest state.
    State {
        /// The state.
        state: State,
    },
    /// To the lecturer: the number of students connected.
    Count {
        /// Students connected (on every server instance).
        students: u32,
    },
    /// To students: a new question (answers to the previous one close).
    Question {
        /// The question.
        question: Question,
    },
    /// To the lecturer: the answers so far (one per student, the last counts; coalesced).
    Answers {
        /// The question's id.
        question: u32,
        /// The answers, in no particular order.
        values: Vec<Answer>,
        /// How many (`values.len()`).
        count: u32,
    },
    /// To everyone: the truth beside the answers.
    Revealed {
        /// The question's id.
        question: u32,
        /// The right answer.
        truth: Answer,
        /// Every answer given.
        values: Vec<Answer>,
    },
    /// To everyone: the lecturer ended the class.
    Ended {},
    /// A message of this connection was dropped.
    Dropped {
        /// Why.
        reason: DropReason,
    },
}

impl ClientMessage {
    /// The message as JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }
}

impl ServerMessage {
    /// The message as JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }
}
