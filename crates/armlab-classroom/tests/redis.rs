//! Two server instances share a class through one Redis: the lecturer on one, students
//! on the other; the state, the question, the answers, the count and the end cross.
//! Needs `redis-server` (Debian's package; tools/test.sh installs it): without it the
//! test fails saying so.

use crate::support::{Client, config, count, lecturer, server, state, student};
use armlab_classroom::Config;
use armlab_room::{Answer, ClientMessage, Question, Refusal, ServerMessage};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// A redis-server on a free loopback port, without persistence, killed when dropped.
struct Redis {
    child: Child,
    port: u16,
}

impl Drop for Redis {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn free_port() -> u16 {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").expect("a free port");
    listener.local_addr().expect("its address").port()
}

async fn redis() -> Redis {
    let port = free_port();
    let child = Command::new("redis-server")
        .args(["--port", &port.to_string(), "--bind", "127.0.0.1", "--save", "", "--appendonly", "no"])
        .stdout(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| {
            panic!("redis-server could not start ({e}): install Debian's redis-server package (tools/test.sh does)")
        });
    let redis = Redis { child, port };
    for _ in 0..100 {
        if tokio::net::TcpStream::connect(("127.0.0.1", port))
            .await
            .is_ok()
        {
            return redis;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    panic!("redis-server did not listen on port {port} within 5 s");
}

#[tokio::test]
async fn a_class_crosses_two_instances_through_redis() {
    let redis = redis().await;
    let shared = || Config {
        redis: Some(format!("redis://127.0.0.1:{}", redis.port)),
        ..config()
    };
    let a = server(shared()).await;
    let b = server(shared()).await;
    let (mut lecturer, code, _) = lecturer(&a).await;
    lecturer
        .send(&ClientMessage::State { state: state(1) })
        .await;
    assert_eq!(count(&mut lecturer).await, 0);
    tokio::time::sleep(Duration::from_millis(100)).await;
    let (mut s1, joined) = student(&b.ws_url(), &code).await;
    let expected = ServerMessage::Joined {
        state: Some(state(1)),
        question: None,
    };
    assert_eq!(joined, expected, "the state stored in Redis");
    let (mut s2, _) = student(&b.ws_url(), &code).await;
    let two = ServerMessage::Count { students: 2 };
    lecturer.recv_until(|m| (*m == two).then_some(())).await;
    lecturer
        .send(&ClientMessage::State { state: state(2) })
        .await;
    let moved = ServerMessage::State { state: state(2) };
    for s in [&mut s1, &mut s2] {
        s.recv_until(|m| (*m == moved).then_some(())).await;
    }
    answers_cross(&mut lecturer, &mut s1, &mut s2).await;
    // The class's code is taken on B too: another token cannot resume it there.
    let mut thief = Client::connect(&b.ws_url()).await;
    let resume = ClientMessage::Resume {
        code: code.clone(),
        token: "e".repeat(32),
        state: state(9),
    };
    thief.send(&resume).await;
    assert_eq!(
        thief.recv().await,
        ServerMessage::Refused {
            reason: Refusal::WrongToken
        }
    );
    lecturer.send(&ClientMessage::End {}).await;
    for s in [&mut s1, &mut s2] {
        s.recv_until(|m| (*m == ServerMessage::Ended {}).then_some(()))
            .await;
    }
    let (_, gone) = student(&b.ws_url(), &code).await;
    assert_eq!(
        gone,
        ServerMessage::Refused {
            reason: Refusal::UnknownCode
        }
    );
    a.stop();
    b.stop();
}

/// A question from the lecturer on A reaches the students on B; their answers reach it.
async fn answers_cross(lecturer: &mut Client, s1: &mut Client, s2: &mut Client) {
    let question = Question::Point {
        id: 7,
        prompt: "Where will the tool be?".into(),
    };
    lecturer
        .send(&ClientMessage::Ask {
            question: question.clone(),
        })
        .await;
    let asked = ServerMessage::Question { question };
    for s in [&mut *s1, &mut *s2] {
        s.recv_until(|m| (*m == asked).then_some(())).await;
    }
    let (p1, p2) = (
        Answer::Point {
            at: [0.5, 0.1, 0.9],
        },
        Answer::Point {
            at: [0.4, 0.2, 1.0],
        },
    );
    s1.send(&ClientMessage::Answer {
        question: 7,
        value: p1,
    })
    .await;
    s2.send(&ClientMessage::Answer {
        question: 7,
        value: p2,
    })
    .await;
    let values = lecturer
        .recv_until(|m| match m {
            ServerMessage::Answers {
                question: 7,
                values,
                count: 2,
            } => Some(values.clone()),
            _ => None,
        })
        .await;
    assert!(values.contains(&p1) && values.contains(&p2), "{values:?}");
}
