//! The relay: a class is created, students join and follow, late joiners get the state
//! at once, a burst coalesces to its last state, questions are answered one per student
//! and revealed, the CSV holds the answers, End ends the class, and after a restart the
//! lecturer's Resume re-creates it.

use crate::support::{Client, config, count, get, get_with, lecturer, server, state, student};
use armlab_classroom::Running;
use armlab_room::{Answer, ClientMessage, DropReason, Question, Refusal, ServerMessage};
use std::time::Duration;

#[tokio::test]
async fn students_follow_the_lecturer_and_are_counted() {
    let running = server(config()).await;
    let (mut lecturer, code, token) = lecturer(&running).await;
    assert_eq!(code.len(), 8);
    assert_eq!(token.len(), 32);
    assert_eq!(count(&mut lecturer).await, 0);
    let (mut a, joined) = student(&running.ws_url(), &code.to_lowercase()).await;
    assert_eq!(
        joined,
        ServerMessage::Joined {
            state: None,
            question: None
        }
    );
    assert_eq!(count(&mut lecturer).await, 1);
    let (mut b, _) = student(&running.ws_url(), &code).await;
    assert_eq!(count(&mut lecturer).await, 2);
    lecturer
        .send(&ClientMessage::State { state: state(7) })
        .await;
    for s in [&mut a, &mut b] {
        assert_eq!(s.recv().await, ServerMessage::State { state: state(7) });
    }
    drop(b);
    assert_eq!(count(&mut lecturer).await, 1);
    running.stop();
}

#[tokio::test]
async fn a_late_student_gets_the_state_and_the_open_question_at_once() {
    let running = server(config()).await;
    let (mut lecturer, code, _) = lecturer(&running).await;
    lecturer
        .send(&ClientMessage::State { state: state(1) })
        .await;
    lecturer
        .send(&ClientMessage::State { state: state(2) })
        .await;
    let question = Question::Point {
        id: 5,
        prompt: "Where will the tool be?".into(),
    };
    lecturer
        .send(&ClientMessage::Ask {
            question: question.clone(),
        })
        .await;
    // The lecturer hears its own question once the server has it.
    lecturer
        .recv_until(|m| matches!(m, ServerMessage::Question { .. }).then_some(()))
        .await;
    let (_late, joined) = student(&running.ws_url(), &code).await;
    assert_eq!(
        joined,
        ServerMessage::Joined {
            state: Some(state(2)),
            question: Some(question)
        }
    );
    running.stop();
}

#[tokio::test]
async fn a_burst_of_100_states_ends_on_the_last_one() {
    let running = server(config()).await;
    let (mut lecturer, code, _) = lecturer(&running).await;
    let (mut slow, _) = student(&running.ws_url(), &code).await;
    for n in 0..100 {
        lecturer
            .send(&ClientMessage::State { state: state(n) })
            .await;
    }
    let got = slow.drain(Duration::from_millis(500)).await;
    assert!(!got.is_empty() && got.len() <= 100, "{} states", got.len());
    assert_eq!(got.last(), Some(&ServerMessage::State { state: state(99) }));
    assert_eq!(
        running
            .server
            .stats
            .dropped(armlab_room::DropReason::RateLimited),
        0
    );
    running.stop();
}

fn choice(index: u32) -> ClientMessage {
    ClientMessage::Answer {
        question: 1,
        value: Answer::Choice { index },
    }
}

fn sorted(values: &[Answer]) -> Vec<u32> {
    let mut indices: Vec<u32> = values
        .iter()
        .map(|a| match a {
            Answer::Choice { index } => *index,
            _ => u32::MAX,
        })
        .collect();
    indices.sort_unstable();
    indices
}

/// A class with a choice question of three options and three students who answered it:
/// the first twice (0, then 2), the others 1. Returns once the lecturer saw the answers.
async fn answered(running: &Running) -> (Client, String, String, Vec<Client>) {
    let (mut lecturer, code, token) = lecturer(running).await;
    let options = ["elbow up", "elbow down", "singular"]
        .map(String::from)
        .to_vec();
    let question = Question::Choice {
        id: 1,
        prompt: "Which branch?".into(),
        options,
    };
    lecturer.send(&ClientMessage::Ask { question }).await;
    let mut students = Vec::new();
    for _ in 0..3 {
        let (s, joined) = student(&running.ws_url(), &code).await;
        let asked = matches!(
            joined,
            ServerMessage::Joined {
                question: Some(Question::Choice { id: 1, .. }),
                ..
            }
        );
        assert!(asked, "{joined:?}");
        students.push(s);
    }
    students[0].send(&choice(0)).await;
    students[0].send(&choice(2)).await;
    students[1].send(&choice(1)).await;
    students[2].send(&choice(1)).await;
    // The connections race, so an update may show the first student's first answer; the
    // updates end on the last one, and never count more than one per student.
    lecturer
        .recv_until(|m| match m {
            ServerMessage::Answers {
                question: 1,
                values,
                count,
            } => {
                assert!(*count <= 3 && values.len() == *count as usize, "{m:?}");
                (sorted(values) == [1, 1, 2]).then_some(())
            }
            _ => None,
        })
        .await;
    (lecturer, code, token, students)
}

#[tokio::test]
async fn answers_count_one_per_student_of_the_questions_kind() {
    let running = server(config()).await;
    let (_lecturer, _, _, mut students) = answered(&running).await;
    // An answer of another kind, or to an option beyond the three, is not counted.
    let number = ClientMessage::Answer {
        question: 1,
        value: Answer::Number { value: 1.0 },
    };
    students[1].send(&number).await;
    students[1].send(&choice(3)).await;
    let dropped = students[1].drain(Duration::from_millis(200)).await;
    let not_open = ServerMessage::Dropped {
        reason: DropReason::NotOpen,
    };
    assert_eq!(dropped, [not_open.clone(), not_open]);
    let (question, values) = running.server.all_classes()[0]
        .answers()
        .expect("a question");
    assert_eq!((question, sorted(&values)), (1, vec![1, 1, 2]));
    running.stop();
}

#[tokio::test]
async fn the_reveal_closes_the_answers_and_the_csv_holds_them() {
    let running = server(config()).await;
    let (mut lecturer, code, token, mut students) = answered(&running).await;
    lecturer
        .send(&ClientMessage::Reveal {
            question: 1,
            truth: Answer::Choice { index: 1 },
        })
        .await;
    let revealed = students[2]
        .recv_until(|m| match m {
            ServerMessage::Revealed {
                question: 1,
                truth,
                values,
            } => Some((*truth, sorted(values))),
            _ => None,
        })
        .await;
    assert_eq!(revealed, (Answer::Choice { index: 1 }, vec![1, 1, 2]));
    students[2].send(&choice(0)).await;
    let not_open = ServerMessage::Dropped {
        reason: DropReason::NotOpen,
    };
    assert_eq!(
        students[2].recv().await,
        not_open,
        "answers close at the reveal"
    );
    let csv = |token: String| format!("/classroom/{code}/answers.csv?token={token}");
    assert_eq!(get(&running, &csv("0".repeat(32))).await.0, 403);
    let (status, csv) = get(&running, &csv(token)).await;
    assert_eq!(status, 200);
    let mut lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.remove(0), "question,kind,truth,x,y,z,number,choice");
    lines.sort_unstable();
    let rows = [
        "1,Choice,0,,,,,1",
        "1,Choice,0,,,,,1",
        "1,Choice,0,,,,,2",
        "1,Choice,1,,,,,1",
    ];
    assert_eq!(
        lines, rows,
        "one row per answer and the truth's, nothing about the students"
    );
    running.stop();
}

#[tokio::test]
async fn end_ends_the_class_for_everyone() {
    let running = server(config()).await;
    let (mut lecturer, code, _) = lecturer(&running).await;
    let (mut s, _) = student(&running.ws_url(), &code).await;
    lecturer.send(&ClientMessage::End {}).await;
    assert_eq!(s.recv().await, ServerMessage::Ended {});
    lecturer
        .recv_until(|m| (*m == ServerMessage::Ended {}).then_some(()))
        .await;
    let (_, again) = student(&running.ws_url(), &code).await;
    assert_eq!(
        again,
        ServerMessage::Refused {
            reason: Refusal::UnknownCode
        }
    );
    assert_eq!(running.server.class_count(), 0);
    running.stop();
}

#[tokio::test]
async fn a_second_lecturer_device_follows_the_first() {
    let running = server(config()).await;
    let (mut first, code, token) = lecturer(&running).await;
    let mut tablet = Client::connect(&running.ws_url()).await;
    tablet
        .send(&ClientMessage::Resume {
            code: code.clone(),
            token: token.clone(),
            state: state(1),
        })
        .await;
    assert_eq!(
        tablet.recv().await,
        ServerMessage::Created {
            code: code.clone(),
            token
        }
    );
    first
        .recv_until(|m| (*m == ServerMessage::State { state: state(1) }).then_some(()))
        .await;
    first.send(&ClientMessage::State { state: state(2) }).await;
    tablet
        .recv_until(|m| (*m == ServerMessage::State { state: state(2) }).then_some(()))
        .await;
    running.stop();
}

/// A class on a first server with its lecturer's state and a student; then the server
/// stops. Returns the class's code and token.
async fn a_class_then_a_stop() -> (String, String) {
    let first = server(config()).await;
    let (mut lecturer, code, token) = lecturer(&first).await;
    lecturer
        .send(&ClientMessage::State { state: state(3) })
        .await;
    lecturer
        .recv_until(|m| matches!(m, ServerMessage::Count { .. }).then_some(()))
        .await;
    let (mut s, joined) = student(&first.ws_url(), &code).await;
    assert_eq!(
        joined,
        ServerMessage::Joined {
            state: Some(state(3)),
            question: None
        }
    );
    first.stop();
    assert!(
        s.closed().await && lecturer.closed().await,
        "the stopped server closes its sockets"
    );
    (code, token)
}

#[tokio::test]
async fn after_a_restart_the_lecturers_resume_recreates_the_class() {
    let (code, token) = a_class_then_a_stop().await;
    let second = server(config()).await;
    let (_, unknown) = student(&second.ws_url(), &code).await;
    assert_eq!(
        unknown,
        ServerMessage::Refused {
            reason: Refusal::UnknownCode
        },
        "the new server starts empty"
    );
    let mut lecturer = Client::connect(&second.ws_url()).await;
    lecturer
        .send(&ClientMessage::Resume {
            code: code.clone(),
            token: token.clone(),
            state: state(3),
        })
        .await;
    assert_eq!(
        lecturer.recv().await,
        ServerMessage::Created {
            code: code.clone(),
            token
        }
    );
    let (_, joined) = student(&second.ws_url(), &code).await;
    assert_eq!(
        joined,
        ServerMessage::Joined {
            state: Some(state(3)),
            question: None
        }
    );
    let mut thief = Client::connect(&second.ws_url()).await;
    thief
        .send(&ClientMessage::Resume {
            code,
            token: "f".repeat(32),
            state: state(9),
        })
        .await;
    assert_eq!(
        thief.recv().await,
        ServerMessage::Refused {
            reason: Refusal::WrongToken
        }
    );
    second.stop();
}

#[tokio::test]
async fn the_lecturer_gets_the_answers_coalesced() {
    let running = server(config()).await;
    let (mut lecturer, code, _) = lecturer(&running).await;
    let question = Question::Point {
        id: 2,
        prompt: "Where will the tool be?".into(),
    };
    lecturer.send(&ClientMessage::Ask { question }).await;
    let mut students = Vec::new();
    for _ in 0..40 {
        students.push(student(&running.ws_url(), &code).await.0);
    }
    lecturer
        .recv_until(|m| (*m == ServerMessage::Count { students: 40 }).then_some(()))
        .await;
    // One answer every 10 ms: 40 in 0.4 s.
    for (i, s) in students.iter_mut().enumerate() {
        let at = [0.01 * i as f64, 0.2, 0.5];
        s.send(&ClientMessage::Answer {
            question: 2,
            value: Answer::Point { at },
        })
        .await;
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let mut updates = 0;
    lecturer
        .recv_until(|m| match m {
            ServerMessage::Answers { count, .. } => {
                updates += 1;
                (*count == 40).then_some(())
            }
            _ => None,
        })
        .await;
    assert!(
        (2..=16).contains(&updates),
        "40 answers in 0.4 s: {updates} updates, at most one per 100 ms"
    );
    running.stop();
}

#[tokio::test]
async fn the_server_says_hello_and_serves_the_page() {
    let dist = std::env::temp_dir().join(format!("armlab-classroom-dist-{}", std::process::id()));
    std::fs::create_dir_all(&dist).expect("a temporary folder");
    // Minified, as the build writes it: no <head> tag.
    let html = "<!doctype html><html lang=en><meta charset=utf-8><title>ArmLab</title>";
    std::fs::write(dist.join("index.html"), html).expect("written");
    let running = server(armlab_classroom::Config {
        dist: Some(dist.clone()),
        ..config()
    })
    .await;
    let (status, hello) = get(&running, "/classroom/hello").await;
    let hello: serde_json::Value = serde_json::from_str(&hello).expect("JSON");
    assert_eq!(
        (status, &hello["classroom"]),
        (200, &serde_json::json!(true))
    );
    // The page is marked as a classroom server's, at both its addresses.
    let marked = format!(
        "<!doctype html><html lang=en><meta charset=utf-8>{}<title>ArmLab</title>",
        armlab_classroom::http::PAGE_MARK
    );
    assert_eq!(get(&running, "/").await, (200, marked.clone()));
    assert_eq!(get(&running, "/index.html").await, (200, marked));
    assert_eq!(get(&running, "/missing.js").await.0, 404);
    let (status, stats) = get(&running, "/classroom/stats").await;
    let stats: serde_json::Value = serde_json::from_str(&stats).expect("JSON");
    assert_eq!(
        (status, &stats["classes"], &stats["dropped"]["NotAllowed"]),
        (200, &0.into(), &0.into())
    );
    running.stop();
    let _ = std::fs::remove_dir_all(dist);
}

#[tokio::test]
async fn a_file_compressed_ahead_goes_to_a_browser_that_accepts_it() {
    let dist = std::env::temp_dir().join(format!("armlab-classroom-packed-{}", std::process::id()));
    std::fs::create_dir_all(&dist).expect("a temporary folder");
    // Stand-ins for the build's copies: the server sends them as they are.
    for (name, body) in [
        ("app.js", "plain"),
        ("app.js.br", "brotli"),
        ("app.js.gz", "gzip"),
    ] {
        std::fs::write(dist.join(name), body).expect("written");
    }
    let running = server(armlab_classroom::Config {
        dist: Some(dist.clone()),
        ..config()
    })
    .await;
    let sent = |accepts: &'static str| {
        let running = &running;
        async move {
            let (status, head, body) = get_with(running, "/app.js", accepts).await;
            let encoding = head
                .lines()
                .find_map(|l| l.strip_prefix("content-encoding: "))
                .map(str::to_owned);
            (status, encoding, body)
        }
    };
    let plain = (200, None, "plain".to_owned());
    assert_eq!(sent("").await, plain);
    assert_eq!(sent("Accept-Encoding: identity\r\n").await, plain);
    let gzip = (200, Some("gzip".to_owned()), "gzip".to_owned());
    assert_eq!(sent("Accept-Encoding: gzip\r\n").await, gzip);
    let brotli = (200, Some("br".to_owned()), "brotli".to_owned());
    assert_eq!(sent("Accept-Encoding: gzip, deflate, br\r\n").await, brotli);
    running.stop();
    let _ = std::fs::remove_dir_all(dist);
}

#[tokio::test]
async fn with_a_secret_file_only_the_classs_lecturer_recreates_it_after_a_restart() {
    let file = std::env::temp_dir().join(format!("armlab-classroom-secret-{}", std::process::id()));
    let _ = std::fs::remove_file(&file);
    let kept = || armlab_classroom::Config {
        secret_file: Some(file.clone()),
        ..config()
    };
    let first = server(kept()).await;
    let (_lecturer, code, token) = lecturer(&first).await;
    first.stop();
    let secret = std::fs::read(&file).expect("the secret file was made");
    assert_eq!(secret.len(), 32);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&file)
            .expect("metadata")
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o600, "readable by its owner only");
    }
    let second = server(kept()).await;
    // A student knows the code: the first Resume after the restart is not enough.
    let mut thief = Client::connect(&second.ws_url()).await;
    let stolen = ClientMessage::Resume {
        code: code.clone(),
        token: "a".repeat(32),
        state: state(9),
    };
    thief.send(&stolen).await;
    assert_eq!(
        thief.recv().await,
        ServerMessage::Refused {
            reason: Refusal::WrongToken
        }
    );
    assert_eq!(second.server.class_count(), 0);
    let mut lecturer = Client::connect(&second.ws_url()).await;
    let resume = ClientMessage::Resume {
        code: code.clone(),
        token: token.clone(),
        state: state(3),
    };
    lecturer.send(&resume).await;
    assert_eq!(
        lecturer.recv().await,
        ServerMessage::Created { code, token }
    );
    second.stop();
    let _ = std::fs::remove_file(&file);
}
