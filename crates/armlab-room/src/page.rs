//! The page's decoding of server messages: JSON read into a [`serde_json::Value`] (a reader
//! the page already has) and taken apart by hand, then validated as [`decode_server`]
//! validates. serde's derived reader of the tagged messages would add about 45 kB of code
//! to the page's first load for the same result; the server and the tests keep it, and a
//! test checks that both readers agree on every message kind.
//!
//! Unlike [`decode_server`], unknown fields are ignored (the page reads what it knows).
//!
//! [`decode_server`]: crate::decode_server

use serde_json::{Map, Value};

use crate::decode::{DecodeError, MAX_SERVER_BYTES, clean_server};
use crate::message::{Answer, DropReason, Question, Refusal, ServerMessage, State};

/// A server message from the text of a WebSocket frame: at most [`MAX_SERVER_BYTES`],
/// every field within its bounds (as `decode_server`).
pub fn read_server(text: &str) -> Result<ServerMessage, DecodeError> {
    if text.len() > MAX_SERVER_BYTES {
        return Err(DecodeError::TooLarge { bytes: text.len() });
    }
    let value: Value = serde_json::from_str(text).map_err(|e| crate::decode::malformed(&e))?;
    let message = server(&value).ok_or(DecodeError::Malformed { line: 0, column: 0 })?;
    clean_server(message)
}

fn server(value: &Value) -> Option<ServerMessage> {
    let o = value.as_object()?;
    Some(match text(o, "type")? {
        "Created" => ServerMessage::Created {
            code: text(o, "code")?.into(),
            token: text(o, "token")?.into(),
        },
        "Joined" => ServerMessage::Joined {
            state: optional(o, "state", state)?,
            question: optional(o, "question", question)?,
        },
        "Refused" => ServerMessage::Refused {
            reason: refusal(text(o, "reason")?)?,
        },
        "State" => ServerMessage::State {
            state: state(o.get("state")?)?,
        },
        "Count" => ServerMessage::Count {
            students: number(o, "students")?,
        },
        "Question" => ServerMessage::Question {
            question: question(o.get("question")?)?,
        },
        "Answers" => ServerMessage::Answers {
            question: number(o, "question")?,
            values: answers(o.get("values")?)?,
            count: number(o, "count")?,
        },
        "Revealed" => ServerMessage::Revealed {
            question: number(o, "question")?,
            truth: answer(o.get("truth")?)?,
            values: answers(o.get("values")?)?,
        },
        "Ended" => ServerMessage::Ended {},
        "Dropped" => ServerMessage::Dropped {
            reason: drop_reason(text(o, "reason")?)?,
        },
        _ => return None,
    })
}

/// A text field.
fn text<'a>(o: &'a Map<String, Value>, key: &str) -> Option<&'a str> {
    o.get(key)?.as_str()
}

/// A whole number field that fits a `u32`.
fn number(o: &Map<String, Value>, key: &str) -> Option<u32> {
    u32::try_from(o.get(key)?.as_u64()?).ok()
}

/// An optional field: absent or `null` is `Some(None)`, a value that does not read `None`.
fn optional<T>(
    o: &Map<String, Value>,
    key: &str,
    read: fn(&Value) -> Option<T>,
) -> Option<Option<T>> {
    match o.get(key) {
        None | Some(Value::Null) => Some(None),
        Some(v) => read(v).map(Some),
    }
}

fn state(value: &Value) -> Option<State> {
    let o = value.as_object()?;
    Some(State {
        link: text(o, "link")?.into(),
        camera: optional(o, "camera", |v| v.as_str().map(String::from))?,
    })
}

fn question(value: &Value) -> Option<Question> {
    let o = value.as_object()?;
    let id = number(o, "id")?;
    let prompt = text(o, "prompt")?.to_string();
    Some(match text(o, "kind")? {
        "Point" => Question::Point { id, prompt },
        "Number" => Question::Number {
            id,
            prompt,
            unit: optional(o, "unit", |v| v.as_str().map(String::from))?,
        },
        "Choice" => Question::Choice {
            id,
            prompt,
            options: (o.get("options")?.as_array()?.iter())
                .map(|v| v.as_str().map(String::from))
                .collect::<Option<_>>()?,
        },
        _ => return None,
    })
}

fn answer(value: &Value) -> Option<Answer> {
    let o = value.as_object()?;
    Some(match text(o, "kind")? {
        "Point" => {
            let at = o.get("at")?.as_array()?;
            let at: Vec<f64> = at.iter().map(Value::as_f64).collect::<Option<_>>()?;
            Answer::Point {
                at: at.try_into().ok()?,
            }
        }
        "Number" => Answer::Number {
            value: o.get("value")?.as_f64()?,
        },
        "Choice" => Answer::Choice {
            index: number(o, "index")?,
        },
        _ => return None,
    })
}

fn answers(value: &Value) -> Option<Vec<Answer>> {
    value.as_array()?.iter().map(answer).collect()
}

fn refusal(name: &str) -> Option<Refusal> {
    Refusal::ALL.into_iter().find(|r| r.name() == name)
}

fn drop_reason(name: &str) -> Option<DropReason> {
    DropReason::ALL.into_iter().find(|r| r.name() == name)
}

#[cfg(test)]
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    use super::read_server;
    use crate::decode_server;
    use crate::message::{Answer, DropReason, Question, Refusal, ServerMessage, State};

    /// One message of every kind, with every optional field both ways.
    fn every_kind() -> Vec<ServerMessage> {
        let state = State {
            link: "robot=ur10&q=0,1,2,3,4,5".into(),
            camera: Some("0.5,0.3,2,0,0,0.4".into()),
        };
        let questions = [
            Question::Point {
                id: 1,
                prompt: "Where will the tool be?".into(),
            },
            Question::Number {
                id: 2,
                prompt: "det J?".into(),
                unit: Some("mm".into()),
            },
            Question::Number {
                id: 3,
                prompt: "x?".into(),
                unit: None,
            },
            Question::Choice {
                id: 4,
                prompt: "Reachable?".into(),
                options: vec!["Yes".into(), "No".into()],
            },
        ];
        let answers = vec![
            Answer::Point {
                at: [0.5, -0.25, 1.0],
            },
            Answer::Number { value: -3.5e-4 },
            Answer::Choice { index: 1 },
        ];
        let mut all = vec![
            ServerMessage::Created {
                code: "K7QH3MXP".into(),
                token: "0123456789abcdef0123456789abcdef".into(),
            },
            ServerMessage::Joined {
                state: None,
                question: None,
            },
            ServerMessage::State {
                state: State {
                    camera: None,
                    ..state.clone()
                },
            },
            ServerMessage::Count { students: 300 },
            ServerMessage::Answers {
                question: 2,
                values: answers.clone(),
                count: 3,
            },
            ServerMessage::Revealed {
                question: 2,
                truth: Answer::Number { value: 0.25 },
                values: answers,
            },
            ServerMessage::Ended {},
        ];
        all.extend(Refusal::ALL.map(|reason| ServerMessage::Refused { reason }));
        all.extend(DropReason::ALL.map(|reason| ServerMessage::Dropped { reason }));
        for question in questions {
            all.push(ServerMessage::Joined {
                state: Some(state.clone()),
                question: Some(question.clone()),
            });
            all.push(ServerMessage::Question { question });
        }
        all
    }

    #[test]
    fn the_pages_reader_agrees_with_serdes_on_every_message_kind() {
        for message in every_kind() {
            let text = message.to_json();
            assert_eq!(read_server(&text), decode_server(&text), "{text}");
            assert_eq!(read_server(&text), Ok(message), "{text}");
        }
    }

    #[test]
    fn what_the_pages_reader_refuses() {
        for bad in [
            "",
            "[]",
            r#"{"type":"Nope"}"#,
            r#"{"type":"Count","students":-1}"#,
            r#"{"type":"Count","students":4294967296}"#,
            r#"{"type":"Refused","reason":"Bored"}"#,
            r#"{"type":"Answers","question":1,"values":[{"kind":"Point","at":[1,2]}],"count":1}"#,
            r#"{"type":"Revealed","question":1,"truth":{"kind":"Number","value":1e300},"values":[]}"#,
            r#"{"type":"State","state":{"link":"tab\there"}}"#,
        ] {
            assert!(read_server(bad).is_err(), "{bad:?} was read");
            assert!(decode_server(bad).is_err(), "{bad:?} was decoded");
        }
    }
}
