//! The rules: only the lecturer drives, bad messages are dropped and counted (never a
//! crash, never forwarded), rate limits per connection, failed joins limited per address,
//! wrong tokens refused, classes expire without a lecturer.

use crate::support::{Client, config, count, lecturer, server, state, student};
use armlab_classroom::Config;
use armlab_room::{Answer, ClientMessage, DropReason, MAX_CLIENT_BYTES, Refusal, ServerMessage};
use std::time::Duration;

#[tokio::test]
async fn a_students_commands_are_dropped_counted_and_not_forwarded() {
    let running = server(config()).await;
    let (mut lecturer, code, _) = lecturer(&running).await;
    let (mut rogue, _) = student(&running.ws_url(), &code).await;
    let (mut other, _) = student(&running.ws_url(), &code).await;
    let question = armlab_room::Question::Point {
        id: 1,
        prompt: "p".into(),
    };
    for message in [
        ClientMessage::State { state: state(66) },
        ClientMessage::Ask { question },
        ClientMessage::Reveal {
            question: 1,
            truth: Answer::Number { value: 1.0 },
        },
        ClientMessage::End {},
    ] {
        rogue.send(&message).await;
        assert_eq!(
            rogue.recv().await,
            ServerMessage::Dropped {
                reason: DropReason::NotAllowed
            }
        );
    }
    assert_eq!(running.server.stats.dropped(DropReason::NotAllowed), 4);
    let (_, stats) = crate::support::get(&running, "/classroom/stats").await;
    assert!(stats.contains(r#""NotAllowed":4"#), "{stats}");
    assert_eq!(other.drain(Duration::from_millis(300)).await, []);
    let heard = lecturer.drain(Duration::from_millis(300)).await;
    assert!(
        heard
            .iter()
            .all(|m| matches!(m, ServerMessage::Count { .. })),
        "{heard:?}"
    );
    assert_eq!(running.server.class_count(), 1, "the class did not end");
    // A visitor (not in a class) may not answer either.
    let mut visitor = Client::connect(&running.ws_url()).await;
    visitor
        .send(&ClientMessage::Answer {
            question: 1,
            value: Answer::Choice { index: 0 },
        })
        .await;
    assert_eq!(
        visitor.recv().await,
        ServerMessage::Dropped {
            reason: DropReason::NotAllowed
        }
    );
    running.stop();
}

#[tokio::test]
async fn oversized_and_malformed_messages_are_dropped_and_the_connection_lives() {
    let running = server(Config {
        student_rate: 100.0,
        ..config()
    })
    .await;
    let mut client = Client::connect(&running.ws_url()).await;
    let cases = [
        (
            format!(
                r#"{{"type":"Create","pad":"{}"}}"#,
                "x".repeat(MAX_CLIENT_BYTES)
            ),
            DropReason::TooLarge,
        ),
        ("\u{7b}".to_owned(), DropReason::Malformed),
        (
            r#"{"type":"Create","admin":true}"#.to_owned(),
            DropReason::Malformed,
        ),
        (
            r#"{"type":"Join","code":"ABCD234O"}"#.to_owned(),
            DropReason::Invalid,
        ),
        (
            format!("{}{}", "[".repeat(5000), "]".repeat(5000)),
            DropReason::Malformed,
        ),
    ];
    for (text, reason) in cases {
        client.send_raw(text).await;
        assert_eq!(client.recv().await, ServerMessage::Dropped { reason });
        assert!(running.server.stats.dropped(reason) >= 1);
    }
    client.send(&ClientMessage::Create {}).await;
    assert!(
        matches!(client.recv().await, ServerMessage::Created { .. }),
        "the connection still works"
    );
    // Beyond the frame limit (1 MiB) the connection closes; the server serves on.
    let mut huge = Client::connect(&running.ws_url()).await;
    huge.send_raw("x".repeat(2 * 1024 * 1024)).await;
    assert!(huge.closed().await);
    let (_, code, _) = lecturer(&running).await;
    assert_eq!(code.len(), 8);
    running.stop();
}

#[tokio::test]
async fn connections_are_rate_limited() {
    let running = server(Config {
        port: 0,
        ..Config::default()
    })
    .await;
    let (mut lecturer, code, _) = lecturer(&running).await;
    let (mut s, _) = student(&running.ws_url(), &code).await;
    for n in 0..60 {
        lecturer
            .send(&ClientMessage::State { state: state(n) })
            .await;
    }
    let got = s.drain(Duration::from_millis(300)).await;
    // A burst of 30 passes, then 30 a second: on a slow machine a few more pass.
    let limited = running.server.stats.dropped(DropReason::RateLimited);
    assert!(
        (15..=30).contains(&limited),
        "30 a second for the lecturer: {limited} of 60 dropped"
    );
    let forwarded = 60 - limited as usize;
    assert!(
        got.len() <= forwarded,
        "{} states forwarded of {forwarded}",
        got.len()
    );
    for _ in 0..20 {
        s.send(&ClientMessage::Answer {
            question: 1,
            value: Answer::Choice { index: 0 },
        })
        .await;
    }
    let replies = s.drain(Duration::from_millis(300)).await;
    let student_limited = running.server.stats.dropped(DropReason::RateLimited) - limited;
    assert!(
        (8..=15).contains(&student_limited),
        "5 a second for a student: {student_limited} of 20 dropped"
    );
    let rate_replies = replies
        .iter()
        .filter(|m| {
            **m == ServerMessage::Dropped {
                reason: DropReason::RateLimited,
            }
        })
        .count();
    assert!(
        (1..=2).contains(&rate_replies),
        "one RateLimited reply a second, not one per message: {rate_replies}"
    );
    running.stop();
}

#[tokio::test]
async fn failed_joins_are_limited_per_address() {
    let running = server(Config {
        student_rate: 100.0,
        ..config()
    })
    .await;
    let (_lecturer, code, _) = lecturer(&running).await;
    let mut guesser = Client::connect(&running.ws_url()).await;
    for _ in 0..20 {
        guesser
            .send(&ClientMessage::Join {
                code: "ZZZZ2345".into(),
                nickname: None,
            })
            .await;
        assert_eq!(
            guesser.recv().await,
            ServerMessage::Refused {
                reason: Refusal::UnknownCode
            }
        );
    }
    guesser
        .send(&ClientMessage::Join {
            code: code.clone(),
            nickname: None,
        })
        .await;
    assert_eq!(
        guesser.recv().await,
        ServerMessage::Refused {
            reason: Refusal::TooManyAttempts
        }
    );
    // A new connection from the same address is limited too.
    let (_, refused) = student(&running.ws_url(), &code).await;
    assert_eq!(
        refused,
        ServerMessage::Refused {
            reason: Refusal::TooManyAttempts
        }
    );
    assert_eq!(running.server.stats.refused(Refusal::UnknownCode), 20);
    running.stop();
}

#[tokio::test]
async fn successful_joins_are_not_limited() {
    let running = server(config()).await;
    let (mut lecturer, code, _) = lecturer(&running).await;
    let mut students = Vec::new();
    for _ in 0..60 {
        let (s, joined) = student(&running.ws_url(), &code).await;
        assert!(
            matches!(joined, ServerMessage::Joined { .. }),
            "a lecture hall behind one address"
        );
        students.push(s);
    }
    lecturer
        .recv_until(|m| (*m == ServerMessage::Count { students: 60 }).then_some(()))
        .await;
    running.stop();
}

#[tokio::test]
async fn a_wrong_token_is_refused() {
    let running = server(config()).await;
    let (_lecturer, code, token) = lecturer(&running).await;
    let mut other = Client::connect(&running.ws_url()).await;
    let mut wrong = token.into_bytes();
    wrong[31] = if wrong[31] == b'0' { b'1' } else { b'0' };
    let wrong = String::from_utf8(wrong).expect("hex");
    other
        .send(&ClientMessage::Resume {
            code,
            token: wrong,
            state: state(0),
        })
        .await;
    assert_eq!(
        other.recv().await,
        ServerMessage::Refused {
            reason: Refusal::WrongToken
        }
    );
    other.send(&ClientMessage::State { state: state(1) }).await;
    assert_eq!(
        other.recv().await,
        ServerMessage::Dropped {
            reason: DropReason::NotAllowed
        }
    );
    running.stop();
}

#[tokio::test]
async fn a_class_expires_without_its_lecturer_only() {
    let running = server(Config {
        expiry: Duration::from_millis(400),
        ..config()
    })
    .await;
    let (mut kept, kept_code, _) = lecturer(&running).await;
    let (lecturer, code, _) = lecturer(&running).await;
    let (mut s, _) = student(&running.ws_url(), &code).await;
    drop(lecturer);
    assert_eq!(
        s.try_recv(Duration::from_millis(200)).await,
        None,
        "not before the expiry"
    );
    assert_eq!(s.recv().await, ServerMessage::Ended {});
    let (_, again) = student(&running.ws_url(), &code).await;
    assert_eq!(
        again,
        ServerMessage::Refused {
            reason: Refusal::UnknownCode
        }
    );
    let (_, joined) = student(&running.ws_url(), &kept_code).await;
    assert!(
        matches!(joined, ServerMessage::Joined { .. }),
        "a class with its lecturer stays"
    );
    assert!(count(&mut kept).await <= 1);
    running.stop();
}
