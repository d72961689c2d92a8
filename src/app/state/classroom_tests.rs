#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use super::*;

fn state(link: &str) -> State {
    State {
        link: link.to_string(),
        camera: None,
    }
}

fn lecturer() -> Classroom {
    let mut room = Classroom::default();
    room.set_available(true);
    room.start();
    room.on_open(state("robot=ur10"));
    assert_eq!(room.take_outbox(), vec![ClientMessage::Create {}]);
    let effect = room.receive(ServerMessage::Created {
        code: "K7QH3MXP".into(),
        token: "ab".repeat(16),
    });
    assert!(matches!(effect, Some(Effect::Keep { new: true, .. })));
    room
}

#[test]
fn the_lecturer_sends_the_latest_state_at_most_twenty_times_a_second() {
    let mut room = lecturer();
    // A drag changes the state every frame (60 a second) for one second.
    let mut sent = Vec::new();
    for frame in 0..60 {
        let now = 1000.0 + frame as f64 * 1000.0 / 60.0;
        room.tick(now, || state(&format!("q={frame}")));
        sent.extend(room.take_outbox());
    }
    assert!(
        (18..=21).contains(&sent.len()),
        "{} states sent",
        sent.len()
    );
    // A frame with nothing new sends nothing; the last state goes once its turn comes.
    room.tick(3000.0, || state("q=59"));
    let last = room.take_outbox();
    assert_eq!(
        last,
        vec![ClientMessage::State {
            state: state("q=59")
        }]
    );
    assert_eq!(room.tick(3100.0, || state("q=59")), None);
    assert!(room.take_outbox().is_empty());
    // A change within the interval waits, and says how long.
    room.tick(3200.0, || state("q=60"));
    assert_eq!(room.take_outbox().len(), 1);
    let wait = room.tick(3210.0, || state("q=61")).unwrap_or_default();
    assert!(room.take_outbox().is_empty());
    assert!((wait - 40.0).abs() < 1e-9, "{wait}");
}

#[test]
fn a_reconnected_lecturer_resumes_with_what_the_page_shows() {
    let mut room = lecturer();
    room.tick(0.0, || state("q=1"));
    room.on_close();
    // Nothing goes while the connection is down; a change waits in the page.
    room.tick(500.0, || state("q=2"));
    assert!(room.take_outbox().is_empty());
    room.on_open(state("q=2"));
    let out = room.take_outbox();
    assert!(matches!(
        &out[0],
        ClientMessage::Resume { code, state: s, .. } if code == "K7QH3MXP" && s.link == "q=2"
    ));
    // The server answers with the class again: kept, not announced as new.
    let again = room.receive(ServerMessage::Created {
        code: "K7QH3MXP".into(),
        token: "ab".repeat(16),
    });
    assert!(matches!(again, Some(Effect::Keep { new: false, .. })));
}

#[test]
fn a_student_follows_explores_and_follows_the_latest_state_again() {
    let mut room = Classroom::default();
    room.join("K7QH3MXP".into(), false);
    room.on_open(state("ignored"));
    assert!(
        matches!(&room.take_outbox()[..], [ClientMessage::Join { code, .. }] if code == "K7QH3MXP")
    );
    let effect = room.receive(ServerMessage::Joined {
        state: Some(state("q=1")),
        question: None,
    });
    assert_eq!(effect, Some(Effect::Follow(state("q=1"))));
    room.explore();
    assert_eq!(
        room.receive(ServerMessage::State {
            state: state("q=2")
        }),
        None
    );
    assert_eq!(
        room.receive(ServerMessage::State {
            state: state("q=3")
        }),
        None
    );
    assert_eq!(room.follow_again(), Some(state("q=3")));
    assert_eq!(
        room.receive(ServerMessage::State {
            state: state("q=4")
        }),
        Some(Effect::Follow(state("q=4")))
    );
}

#[test]
fn a_student_answers_the_open_question_until_the_truth_is_revealed() {
    let mut room = Classroom::default();
    room.join("K7QH3MXP".into(), false);
    room.on_open(state(""));
    room.take_outbox();
    let question = Question::Choice {
        id: 3,
        prompt: "Reachable?".into(),
        options: vec!["yes".into(), "no".into()],
    };
    room.receive(ServerMessage::Question {
        question: question.clone(),
    });
    // An answer of another kind, or an option that is not there, is not sent.
    room.answer(Answer::Number { value: 1.0 });
    room.answer(Answer::Choice { index: 2 });
    assert!(room.take_outbox().is_empty());
    room.answer(Answer::Choice { index: 1 });
    assert_eq!(
        room.take_outbox(),
        vec![ClientMessage::Answer {
            question: 3,
            value: Answer::Choice { index: 1 }
        }]
    );
    room.receive(ServerMessage::Revealed {
        question: 3,
        truth: Answer::Choice { index: 0 },
        values: vec![Answer::Choice { index: 1 }, Answer::Choice { index: 0 }],
    });
    assert_eq!(room.truth(), Some(Answer::Choice { index: 0 }));
    assert_eq!(room.answers().len(), 2);
    room.answer(Answer::Choice { index: 0 });
    assert!(room.take_outbox().is_empty(), "no answer after the reveal");
}

#[test]
fn the_lecturers_questions_get_new_ids_and_their_own_answers() {
    let mut room = lecturer();
    room.ask(Question::Number {
        id: 0,
        prompt: "det J".into(),
        unit: None,
    });
    room.ask(Question::Point {
        id: 0,
        prompt: "Where?".into(),
    });
    let ids: Vec<u32> = room
        .take_outbox()
        .iter()
        .filter_map(|m| match m {
            ClientMessage::Ask { question } => Some(question.id()),
            _ => None,
        })
        .collect();
    assert_eq!(ids, vec![1, 2]);
    // Answers to the first question no longer count.
    room.receive(ServerMessage::Answers {
        question: 1,
        values: vec![Answer::Number { value: 2.0 }],
        count: 1,
    });
    assert!(room.answers().is_empty());
    room.receive(ServerMessage::Answers {
        question: 2,
        values: vec![Answer::Point {
            at: [0.1, 0.2, 0.3],
        }],
        count: 1,
    });
    assert_eq!(room.answers().len(), 1);
}

#[test]
fn a_refusal_or_the_end_leaves_the_class_and_asks_for_a_new_connection() {
    let mut room = Classroom::default();
    room.join("AAAAAAAA".into(), true);
    let generation = room.generation();
    room.on_open(state(""));
    assert_eq!(
        room.receive(ServerMessage::Refused {
            reason: Refusal::UnknownCode
        }),
        Some(Effect::Refused(Refusal::UnknownCode))
    );
    assert_eq!(*room.role(), Role::None);
    assert!(!room.wants_connection());
    assert_ne!(room.generation(), generation);
    let mut room = lecturer();
    room.end();
    assert_eq!(room.take_outbox(), vec![ClientMessage::End {}]);
    assert_eq!(room.receive(ServerMessage::Ended {}), Some(Effect::Ended));
    assert_eq!(room.code(), None);
}

#[test]
fn a_links_class_part_is_split_from_the_session() {
    let token = "0123456789abcdef0123456789abcdef";
    assert_eq!(
        split_class_link("#class=new"),
        (Some(ClassLink::New), String::new())
    );
    assert_eq!(
        split_class_link("robot=puma560&class=k7qh-3mxp&q=0,1"),
        (
            Some(ClassLink::Join("K7QH3MXP".into())),
            "robot=puma560&q=0,1".into()
        )
    );
    assert_eq!(
        split_class_link(&format!("class=K7QH3MXP&key={token}")),
        (
            Some(ClassLink::Control {
                code: "K7QH3MXP".into(),
                token: token.into()
            }),
            String::new()
        )
    );
    // A key that is no token joins as a student; a code of the wrong shape is bad.
    assert_eq!(
        split_class_link("class=K7QH3MXP&key=guess").0,
        Some(ClassLink::Join("K7QH3MXP".into()))
    );
    assert_eq!(split_class_link("class=K7Q").0, Some(ClassLink::Bad));
    assert_eq!(split_class_link("robot=ur10").0, None);
    assert_eq!(shown_code("K7QH3MXP"), "K7QH-3MXP");
}

#[test]
fn a_point_question_frees_the_target_until_the_reveal() {
    let mut room = Classroom::default();
    room.join("K7QH3MXP".into(), false);
    room.on_open(state(""));
    room.receive(ServerMessage::Joined {
        state: Some(state("q=1")),
        question: None,
    });
    room.receive(ServerMessage::Question {
        question: Question::Point {
            id: 1,
            prompt: "Where?".into(),
        },
    });
    assert!(!room.following() && room.predicting());
    // The lecturer moves the arm meanwhile: the student's target stays theirs.
    assert_eq!(
        room.receive(ServerMessage::State {
            state: state("q=2")
        }),
        None
    );
    room.answer(Answer::Point {
        at: [0.5, 0.0, 0.25],
    });
    let effect = room.receive(ServerMessage::Revealed {
        question: 1,
        truth: Answer::Point {
            at: [0.4, 0.1, 0.2],
        },
        values: vec![Answer::Point {
            at: [0.5, 0.0, 0.25],
        }],
    });
    assert_eq!(effect, Some(Effect::Follow(state("q=2"))));
    assert!(room.following());
}

#[test]
fn a_student_refused_after_a_restart_asks_again_until_the_class_is_back() {
    let mut room = Classroom::default();
    room.join("K7QH3MXP".into(), false);
    room.on_open(state(""));
    room.take_outbox();
    room.receive(ServerMessage::Joined {
        state: Some(state("q=1")),
        question: None,
    });
    // The server restarts: the student's page is first back, before the lecturer's.
    room.on_close();
    room.on_open(state(""));
    room.take_outbox();
    let refused = ServerMessage::Refused {
        reason: Refusal::UnknownCode,
    };
    assert_eq!(
        room.receive(refused.clone()),
        None,
        "no sentence, no leaving"
    );
    assert!(matches!(room.role(), Role::Student { .. }));
    assert_eq!(room.tick(0.0, || state("")), Some(REJOIN_MS));
    assert!(room.take_outbox().is_empty());
    assert_eq!(room.tick(REJOIN_MS, || state("")), None);
    assert!(matches!(
        &room.take_outbox()[..],
        [ClientMessage::Join { .. }]
    ));
    // A first join that is refused leaves with the sentence.
    let mut fresh = Classroom::default();
    fresh.join("K7QH3MXP".into(), false);
    fresh.on_open(state(""));
    assert_eq!(
        fresh.receive(refused),
        Some(Effect::Refused(Refusal::UnknownCode))
    );
    assert_eq!(*fresh.role(), Role::None);
}
