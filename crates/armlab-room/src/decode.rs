//! Decoding and validating messages: the size first, then serde, then every field's
//! bounds. Texts are cleaned rather than refused; numbers and shapes are refused.

use crate::ids::{is_code, is_token, normalize_code};
use crate::message::{
    Answer, ClientMessage, MAX_CAMERA_BYTES, MAX_CHOICE_CHARS, MAX_LINK_BYTES, MAX_NICKNAME_CHARS,
    MAX_NUMBER, MAX_OPTIONS, MAX_POINT_METRES, MAX_PROMPT_CHARS, MAX_UNIT_CHARS, Question,
    ServerMessage, State,
};
use armlab_text::echo::text_within;
use std::fmt;

/// The largest client message, in bytes (checked before parsing).
pub const MAX_CLIENT_BYTES: usize = 64 * 1024;
/// The largest server message a page decodes, in bytes: the answers of a few thousand
/// students.
pub const MAX_SERVER_BYTES: usize = 4 * 1024 * 1024;

/// A field whose value is out of its bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    /// A join code that is not a code's shape.
    Code,
    /// A token that is not a token's shape.
    Token,
    /// A state's link: too long, or not printable ASCII.
    Link,
    /// A state's camera: too long, or not printable ASCII.
    Camera,
    /// A choice question's options: fewer than two or more than [`MAX_OPTIONS`].
    Options,
    /// A point: a coordinate beyond ±[`MAX_POINT_METRES`].
    Point,
    /// A number beyond ±[`MAX_NUMBER`].
    Number,
    /// A choice index beyond the most options.
    Choice,
}

impl Field {
    /// The field's name in the protocol's words (the page is built with `{:?}` printing
    /// nothing, so an error's text does not rely on `Debug`).
    pub fn name(self) -> &'static str {
        match self {
            Field::Code => "code",
            Field::Token => "token",
            Field::Link => "link",
            Field::Camera => "camera",
            Field::Options => "options",
            Field::Point => "point",
            Field::Number => "number",
            Field::Choice => "choice",
        }
    }
}

/// Why a message was not decoded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DecodeError {
    /// The message is larger than its limit (`bytes` long).
    TooLarge {
        /// The message's length.
        bytes: usize,
    },
    /// Not a message: not UTF-8 or not JSON, an unknown type or field, a wrong type, a
    /// missing field (serde's category and where, never its English).
    Malformed {
        /// The line of the error (from 1), 0 when unknown.
        line: usize,
        /// The column of the error (from 1), 0 when unknown.
        column: usize,
    },
    /// A field out of its bounds.
    Invalid(Field),
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooLarge { bytes } => write!(f, "message of {bytes} bytes is too large"),
            Self::Malformed { line, column } => {
                write!(f, "malformed message at line {line}, column {column}")
            }
            Self::Invalid(field) => write!(f, "field out of bounds: {}", field.name()),
        }
    }
}

impl std::error::Error for DecodeError {}

pub(crate) fn malformed(e: &serde_json::Error) -> DecodeError {
    DecodeError::Malformed {
        line: e.line(),
        column: e.column(),
    }
}

/// A client message from the bytes of a WebSocket frame (text or binary): at most
/// [`MAX_CLIENT_BYTES`], UTF-8 JSON of a [`ClientMessage`], every field within its bounds.
/// Texts come back cleaned (cut, control characters replaced) and codes normalised.
pub fn decode_client(bytes: &[u8]) -> Result<ClientMessage, DecodeError> {
    if bytes.len() > MAX_CLIENT_BYTES {
        return Err(DecodeError::TooLarge { bytes: bytes.len() });
    }
    let message: ClientMessage = serde_json::from_slice(bytes).map_err(|e| malformed(&e))?;
    clean_client(message)
}

/// A server message from the text of a WebSocket frame (the page's side): at most
/// [`MAX_SERVER_BYTES`], every field within the bounds a client message keeps.
pub fn decode_server(text: &str) -> Result<ServerMessage, DecodeError> {
    if text.len() > MAX_SERVER_BYTES {
        return Err(DecodeError::TooLarge { bytes: text.len() });
    }
    let message: ServerMessage = serde_json::from_str(text).map_err(|e| malformed(&e))?;
    clean_server(message)
}

fn clean_client(message: ClientMessage) -> Result<ClientMessage, DecodeError> {
    Ok(match message {
        ClientMessage::Resume { code, token, state } => ClientMessage::Resume {
            code: code_of(&code)?,
            token: token_of(token)?,
            state: clean_state(state)?,
        },
        ClientMessage::State { state } => ClientMessage::State {
            state: clean_state(state)?,
        },
        ClientMessage::Ask { question } => ClientMessage::Ask {
            question: clean_question(question)?,
        },
        ClientMessage::Reveal { question, truth } => ClientMessage::Reveal {
            question,
            truth: clean_answer(truth)?,
        },
        ClientMessage::Join { code, nickname } => ClientMessage::Join {
            code: code_of(&code)?,
            nickname: nickname.and_then(|n| clean_text(&n, MAX_NICKNAME_CHARS)),
        },
        ClientMessage::Answer { question, value } => ClientMessage::Answer {
            question,
            value: clean_answer(value)?,
        },
        m @ (ClientMessage::Create {} | ClientMessage::End {}) => m,
    })
}

pub(crate) fn clean_server(message: ServerMessage) -> Result<ServerMessage, DecodeError> {
    let answers = |values: Vec<Answer>| -> Result<Vec<Answer>, DecodeError> {
        values.into_iter().map(clean_answer).collect()
    };
    Ok(match message {
        ServerMessage::Created { code, token } => ServerMessage::Created {
            code: code_of(&code)?,
            token: token_of(token)?,
        },
        ServerMessage::Joined { state, question } => ServerMessage::Joined {
            state: state.map(clean_state).transpose()?,
            question: question.map(clean_question).transpose()?,
        },
        ServerMessage::State { state } => ServerMessage::State {
            state: clean_state(state)?,
        },
        ServerMessage::Question { question } => ServerMessage::Question {
            question: clean_question(question)?,
        },
        ServerMessage::Answers {
            question,
            values,
            count,
        } => ServerMessage::Answers {
            question,
            values: answers(values)?,
            count,
        },
        ServerMessage::Revealed {
            question,
            truth,
            values,
        } => ServerMessage::Revealed {
            question,
            truth: clean_answer(truth)?,
            values: answers(values)?,
        },
        m @ (ServerMessage::Refused { .. }
        | ServerMessage::Count { .. }
        | ServerMessage::Ended {}
        | ServerMessage::Dropped { .. }) => m,
    })
}

fn code_of(typed: &str) -> Result<String, DecodeError> {
    normalize_code(typed)
        .filter(|c| is_code(c))
        .ok_or(DecodeError::Invalid(Field::Code))
}

fn token_of(token: String) -> Result<String, DecodeError> {
    if is_token(&token) {
        Ok(token)
    } else {
        Err(DecodeError::Invalid(Field::Token))
    }
}

/// Printable ASCII (space to `~`) of at most `max` bytes.
fn printable(s: &str, max: usize) -> bool {
    s.len() <= max && s.bytes().all(|b| (0x20..=0x7e).contains(&b))
}

fn clean_state(state: State) -> Result<State, DecodeError> {
    if !printable(&state.link, MAX_LINK_BYTES) {
        return Err(DecodeError::Invalid(Field::Link));
    }
    if let Some(camera) = &state.camera
        && !printable(camera, MAX_CAMERA_BYTES)
    {
        return Err(DecodeError::Invalid(Field::Camera));
    }
    Ok(state)
}

/// `s` cut to `max` characters and cleaned (as the app echoes a person's text), trimmed;
/// `None` when nothing is left.
fn clean_text(s: &str, max: usize) -> Option<String> {
    let cleaned = text_within(s.trim(), max);
    let trimmed = cleaned.trim();
    (!trimmed.is_empty()).then(|| trimmed.to_owned())
}

fn clean_question(question: Question) -> Result<Question, DecodeError> {
    let prompt = |p: &str| clean_text(p, MAX_PROMPT_CHARS).unwrap_or_default();
    Ok(match question {
        Question::Point { id, prompt: p } => Question::Point {
            id,
            prompt: prompt(&p),
        },
        Question::Number {
            id,
            prompt: p,
            unit,
        } => Question::Number {
            id,
            prompt: prompt(&p),
            unit: unit.and_then(|u| clean_text(&u, MAX_UNIT_CHARS)),
        },
        Question::Choice {
            id,
            prompt: p,
            options,
        } => {
            if !(2..=MAX_OPTIONS).contains(&options.len()) {
                return Err(DecodeError::Invalid(Field::Options));
            }
            let options = options
                .iter()
                .map(|o| clean_text(o, MAX_CHOICE_CHARS).unwrap_or_else(|| "?".into()))
                .collect();
            Question::Choice {
                id,
                prompt: prompt(&p),
                options,
            }
        }
    })
}

fn clean_answer(answer: Answer) -> Result<Answer, DecodeError> {
    match answer {
        Answer::Point { at }
            if at
                .iter()
                .any(|c| !c.is_finite() || c.abs() > MAX_POINT_METRES) =>
        {
            Err(DecodeError::Invalid(Field::Point))
        }
        Answer::Number { value } if !value.is_finite() || value.abs() > MAX_NUMBER => {
            Err(DecodeError::Invalid(Field::Number))
        }
        Answer::Choice { index } if index as usize >= MAX_OPTIONS => {
            Err(DecodeError::Invalid(Field::Choice))
        }
        a => Ok(a),
    }
}
