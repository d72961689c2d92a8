//! Decoding: every message survives `to_json` → `decode_*`; texts are cleaned; sizes,
//! unknown fields, wrong types and out-of-bounds numbers give typed errors.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_room::{
    Answer, ClientMessage, DecodeError, DropReason, Field, MAX_CLIENT_BYTES, MAX_LINK_BYTES,
    Question, Refusal, ServerMessage, State, decode_client, decode_server,
};

const TOKEN: &str = "0123456789abcdef0123456789abcdef";

fn state() -> State {
    State {
        link: "robot=ur10&q=0,-1.57,1.2,0,0.5,0&task=pose".into(),
        camera: Some("cam=0.5,0.3,3,0,0,0.5".into()),
    }
}

fn client_messages() -> Vec<ClientMessage> {
    vec![
        ClientMessage::Create {},
        ClientMessage::Resume {
            code: "ABCD2345".into(),
            token: TOKEN.into(),
            state: state(),
        },
        ClientMessage::State {
            state: State {
                link: "robot=puma".into(),
                camera: None,
            },
        },
        ClientMessage::Ask {
            question: Question::Point {
                id: 1,
                prompt: "Where will the tool go?".into(),
            },
        },
        ClientMessage::Ask {
            question: Question::Number {
                id: 2,
                prompt: "det J?".into(),
                unit: Some("m³".into()),
            },
        },
        ClientMessage::Ask {
            question: Question::Choice {
                id: 3,
                prompt: "Which branch?".into(),
                options: vec!["up".into(), "down".into()],
            },
        },
        ClientMessage::Reveal {
            question: 1,
            truth: Answer::Point {
                at: [0.5, -0.25, 1.0],
            },
        },
        ClientMessage::End {},
        ClientMessage::Join {
            code: "ABCD2345".into(),
            nickname: Some("Aino".into()),
        },
        ClientMessage::Join {
            code: "ABCD2345".into(),
            nickname: None,
        },
        ClientMessage::Answer {
            question: 2,
            value: Answer::Number { value: -0.125 },
        },
        ClientMessage::Answer {
            question: 3,
            value: Answer::Choice { index: 1 },
        },
    ]
}

#[test]
fn every_client_message_round_trips() {
    for message in client_messages() {
        let json = message.to_json();
        assert_eq!(decode_client(json.as_bytes()), Ok(message), "{json}");
    }
    assert_eq!(
        decode_client(br#"{"type":"Create"}"#),
        Ok(ClientMessage::Create {})
    );
}

#[test]
fn every_server_message_round_trips() {
    for message in server_messages() {
        let json = message.to_json();
        assert_eq!(decode_server(&json), Ok(message), "{json}");
    }
    assert_eq!(ServerMessage::Ended {}.to_json(), r#"{"type":"Ended"}"#);
    let refused = ServerMessage::Refused {
        reason: Refusal::TooManyAttempts,
    };
    assert_eq!(
        refused.to_json(),
        r#"{"type":"Refused","reason":"TooManyAttempts"}"#
    );
}

fn server_messages() -> Vec<ServerMessage> {
    let values = vec![
        Answer::Point {
            at: [0.1, 0.2, 0.3],
        },
        Answer::Point {
            at: [0.0, 0.0, -1.0],
        },
    ];
    vec![
        ServerMessage::Created {
            code: "ABCD2345".into(),
            token: TOKEN.into(),
        },
        ServerMessage::Joined {
            state: Some(state()),
            question: None,
        },
        ServerMessage::Joined {
            state: None,
            question: Some(Question::Point {
                id: 4,
                prompt: "p".into(),
            }),
        },
        ServerMessage::Refused {
            reason: Refusal::UnknownCode,
        },
        ServerMessage::State { state: state() },
        ServerMessage::Count { students: 300 },
        ServerMessage::Question {
            question: Question::Point {
                id: 4,
                prompt: "p".into(),
            },
        },
        ServerMessage::Answers {
            question: 4,
            values: values.clone(),
            count: 2,
        },
        ServerMessage::Revealed {
            question: 4,
            truth: Answer::Point {
                at: [0.1, 0.2, 0.3],
            },
            values,
        },
        ServerMessage::Ended {},
        ServerMessage::Dropped {
            reason: DropReason::RateLimited,
        },
    ]
}

#[test]
fn size_is_checked_before_parsing() {
    let mut big = br#"{"type":"Create"}"#.to_vec();
    big.resize(MAX_CLIENT_BYTES + 1, b' ');
    assert_eq!(
        decode_client(&big),
        Err(DecodeError::TooLarge {
            bytes: MAX_CLIENT_BYTES + 1
        })
    );
    big.truncate(MAX_CLIENT_BYTES);
    assert_eq!(
        decode_client(&big),
        Ok(ClientMessage::Create {}),
        "trailing spaces are JSON"
    );
}

fn malformed(json: &str) -> bool {
    matches!(
        decode_client(json.as_bytes()),
        Err(DecodeError::Malformed { .. })
    )
}

#[test]
fn unknown_types_fields_and_wrong_types_are_malformed() {
    for json in [
        "",
        "null",
        "[]",
        "{}",
        r#"{"type":"Shout"}"#,
        r#"{"type":"Create","admin":true}"#,
        r#"{"type":"End","x":1}"#,
        r#"{"type":"Join"}"#,
        r#"{"type":"Join","code":7}"#,
        r#"{"type":"Join","code":"ABCD2345","nickname":"a","extra":1}"#,
        r#"{"type":"Answer","question":-1,"value":{"kind":"Choice","index":0}}"#,
        r#"{"type":"Answer","question":1.5,"value":{"kind":"Choice","index":0}}"#,
        r#"{"type":"Answer","question":1,"value":{"kind":"Point","at":[1,2]}}"#,
        r#"{"type":"Answer","question":1,"value":{"kind":"Number","value":1e999}}"#,
        r#"{"type":"Answer","question":1,"value":{"kind":"Number","value":NaN}}"#,
        r#"{"type":"State","state":{"link":"a","camera":null,"x":0}}"#,
        "\u{feff}{\"type\":\"Create\"}",
    ] {
        assert!(
            malformed(json),
            "{json:?} gave {:?}",
            decode_client(json.as_bytes())
        );
    }
    assert!(matches!(
        decode_client(&[0xff, 0xfe, b'\x7b']),
        Err(DecodeError::Malformed { .. })
    ));
    let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
    assert!(matches!(
        decode_client(deep.as_bytes()),
        Err(DecodeError::TooLarge { .. })
    ));
    let deep = format!("{}{}", "[".repeat(30_000), "]".repeat(30_000));
    assert!(
        malformed(&deep),
        "nesting beyond serde_json's limit is an error, not a stack overflow"
    );
}

fn invalid(json: &str) -> Option<Field> {
    match decode_client(json.as_bytes()) {
        Err(DecodeError::Invalid(field)) => Some(field),
        _ => None,
    }
}

#[test]
fn out_of_bounds_fields_are_invalid() {
    let answer = |value: &str| format!(r#"{{"type":"Answer","question":1,"value":{value}}}"#);
    assert_eq!(
        invalid(&answer(r#"{"kind":"Point","at":[0,0,1000.5]}"#)),
        Some(Field::Point)
    );
    assert_eq!(
        invalid(&answer(r#"{"kind":"Point","at":[-1e300,0,0]}"#)),
        Some(Field::Point)
    );
    assert_eq!(
        invalid(&answer(r#"{"kind":"Number","value":1.5e12}"#)),
        Some(Field::Number)
    );
    assert_eq!(
        invalid(&answer(r#"{"kind":"Choice","index":8}"#)),
        Some(Field::Choice)
    );
    assert_eq!(
        invalid(r#"{"type":"Join","code":"ABCD234O"}"#),
        Some(Field::Code)
    );
    let resume = |token: &str| {
        format!(r#"{{"type":"Resume","code":"ABCD2345","token":"{token}","state":{{"link":""}}}}"#)
    };
    assert_eq!(invalid(&resume(&TOKEN.to_uppercase())), Some(Field::Token));
    assert_eq!(decode_client(resume(TOKEN).as_bytes()).map(|_| ()), Ok(()));
    let link = |link: &str| format!(r#"{{"type":"State","state":{{"link":"{link}"}}}}"#);
    assert_eq!(invalid(&link("a\\nb")), Some(Field::Link));
    assert_eq!(invalid(&link("ä")), Some(Field::Link));
    assert_eq!(
        invalid(&link(&"a".repeat(MAX_LINK_BYTES + 1))),
        Some(Field::Link)
    );
    assert_eq!(
        decode_client(link(&"a".repeat(MAX_LINK_BYTES)).as_bytes()).map(|_| ()),
        Ok(())
    );
    assert_eq!(
        invalid(r#"{"type":"State","state":{"link":"a","camera":"\u0007"}}"#),
        Some(Field::Camera)
    );
    let choice = |n: usize| {
        let options = vec!["\"o\""; n].join(",");
        format!(
            r#"{{"type":"Ask","question":{{"kind":"Choice","id":1,"prompt":"p","options":[{options}]}}}}"#
        )
    };
    assert_eq!(invalid(&choice(1)), Some(Field::Options));
    assert_eq!(invalid(&choice(9)), Some(Field::Options));
    assert_eq!(invalid(&choice(2)), None);
    assert_eq!(invalid(&choice(8)), None);
}

#[test]
fn texts_are_cut_and_cleaned() {
    let long = "x".repeat(10_000);
    let json = format!(r#"{{"type":"Join","code":"abcd-2345","nickname":"  Ai\u202eno\n{long}"}}"#);
    let Ok(ClientMessage::Join {
        code,
        nickname: Some(nickname),
    }) = decode_client(json.as_bytes())
    else {
        panic!("a join");
    };
    assert_eq!(code, "ABCD2345");
    assert_eq!(nickname.chars().count(), 24);
    assert!(nickname.starts_with("Ai\u{25A1}no\u{25A1}x"), "{nickname}");
    assert!(nickname.ends_with('…'));
    let blank = decode_client(br#"{"type":"Join","code":"ABCD2345","nickname":"   "}"#);
    assert_eq!(
        blank,
        Ok(ClientMessage::Join {
            code: "ABCD2345".into(),
            nickname: None
        })
    );
    let json = format!(
        r#"{{"type":"Ask","question":{{"kind":"Number","id":9,"prompt":"{long}","unit":"{long}"}}}}"#
    );
    let Ok(ClientMessage::Ask {
        question:
            Question::Number {
                prompt,
                unit: Some(unit),
                ..
            },
    }) = decode_client(json.as_bytes())
    else {
        panic!("a number question");
    };
    assert_eq!((prompt.chars().count(), unit.chars().count()), (200, 12));
}

#[test]
fn answers_fit_their_question() {
    let choice = Question::Choice {
        id: 1,
        prompt: "p".into(),
        options: vec!["a".into(), "b".into(), "c".into()],
    };
    assert!(choice.fits(&Answer::Choice { index: 2 }));
    assert!(!choice.fits(&Answer::Choice { index: 3 }));
    assert!(!choice.fits(&Answer::Number { value: 2.0 }));
    let point = Question::Point {
        id: 2,
        prompt: "p".into(),
    };
    assert!(point.fits(&Answer::Point { at: [0.0; 3] }));
    assert!(!point.fits(&Answer::Choice { index: 0 }));
    assert_eq!(
        (choice.id(), choice.kind_name(), point.kind_name()),
        (1, "Choice", "Point")
    );
}
