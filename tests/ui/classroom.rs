//! The lecture room as a person sees it: the lecturer's bar, join window and question
//! with its live answers; a student's page following, exploring, following again and
//! answering. The server is played by feeding the room its messages.

use armlab::app::ArmLabApp;
use armlab_room::{Answer, ClientMessage, Question, ServerMessage, State};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use super::harness_at;

const TOKEN: &str = "0123456789abcdef0123456789abcdef";

/// The app at `size` on a page from a classroom server, its connection open.
fn room_page(hash: &str, size: [f32; 2]) -> Harness<'static, ArmLabApp> {
    let mut h = harness_at(hash, size);
    h.state_mut().classroom_mut().set_available(true);
    h.run_steps(2);
    h
}

/// What the page sent since the last call.
fn sent(h: &mut Harness<'_, ArmLabApp>) -> Vec<ClientMessage> {
    h.state_mut().classroom_mut().take_outbox()
}

/// A server message arriving (the page applies it as it would from the socket).
fn arrive(h: &mut Harness<'_, ArmLabApp>, message: ServerMessage) {
    if let Some(effect) = h.state_mut().classroom_mut().receive(message) {
        h.state_mut().apply_room_effect(effect, |_, _| {});
    }
    h.run_steps(2);
}

#[test]
fn the_lecturer_starts_a_class_shows_its_code_and_reveals_det_j_beside_the_answers() {
    let mut h = room_page("robot=ur10&q=0.1,-1.2,1.1,-0.4,0.9,0.2", [1024.0, 768.0]);
    h.get_by_label("Start a class").click();
    h.run_steps(2);
    let state = h.state().room_state();
    h.state_mut().classroom_mut().on_open(state);
    assert!(matches!(&sent(&mut h)[..], [ClientMessage::Create {}]));
    arrive(
        &mut h,
        ServerMessage::Created {
            code: "K7QH3MXP".into(),
            token: TOKEN.into(),
        },
    );
    arrive(&mut h, ServerMessage::Count { students: 3 });
    // The join window opened with the code large enough for the back of a lecture hall.
    let code = h.get_by_label("K7QH-3MXP").rect();
    assert!(
        code.height() >= 50.0,
        "the code is {:.0} points tall",
        code.height()
    );
    h.get_by_label("3 students");
    h.snapshot("class_lecturer_1024x768");
    h.get_by_role_and_label(Role::Button, "Join link").click();
    h.run_steps(2);
    // The lecturer's page sends what it shows (the page ticks the room each frame).
    h.state_mut().tick_room(1e6);
    assert!(sent(&mut h).iter().any(|m| matches!(m, ClientMessage::State { state } if state.link.starts_with("robot=ur10&q=0.1,-1.2"))));
    h.get_by_label("Ask the room").click();
    h.run_steps(2);
    h.get_by_label("det J?").click();
    h.run_steps(2);
    let id = match &sent(&mut h)[..] {
        [ClientMessage::Ask { question }] => question.id(),
        other => panic!("sent {other:?}"),
    };
    let values = [0.1, 0.12, -0.3]
        .map(|value| Answer::Number { value })
        .to_vec();
    arrive(
        &mut h,
        ServerMessage::Answers {
            question: id,
            values,
            count: 3,
        },
    );
    h.get_by_label("3 answers");
    h.get_by_label("Reveal").click();
    h.run_steps(2);
    let jacobian = h.state().model().jacobian().clone();
    let det = nalgebra::Matrix6::from_iterator(jacobian.iter().copied()).determinant();
    match &sent(&mut h)[..] {
        [
            ClientMessage::Reveal {
                question,
                truth: Answer::Number { value },
            },
        ] => {
            assert_eq!(*question, id);
            assert!((value - det).abs() < 1e-12, "{value} against det J {det}");
        }
        other => panic!("sent {other:?}"),
    }
}

#[test]
fn a_phone_follows_the_lecturer_explores_and_answers_a_point_question() {
    let mut h = room_page("", [390.0, 844.0]);
    h.state_mut().classroom_mut().join("K7QH3MXP".into(), false);
    let state = h.state().room_state();
    h.state_mut().classroom_mut().on_open(state);
    sent(&mut h);
    let lecturer = |q1: f64| State {
        link: format!("robot=puma560&q={q1},0.2,0.3,0,0.5,0&task=position"),
        camera: None,
    };
    arrive(
        &mut h,
        ServerMessage::Joined {
            state: Some(lecturer(0.5)),
            question: None,
        },
    );
    assert_eq!(h.state().model().robot().name, "Puma 560");
    assert!((h.state().model().q()[0] - 0.5).abs() < 1e-9);
    h.get_by_label("Following the lecturer");
    h.get_by_label("Explore on my own").click();
    h.run_steps(2);
    arrive(
        &mut h,
        ServerMessage::State {
            state: lecturer(0.7),
        },
    );
    assert!(
        (h.state().model().q()[0] - 0.5).abs() < 1e-9,
        "the student explores"
    );
    h.get_by_label("Follow again").click();
    h.run_steps(2);
    assert!((h.state().model().q()[0] - 0.7).abs() < 1e-9);
    arrive(
        &mut h,
        ServerMessage::Question {
            question: Question::Point {
                id: 4,
                prompt: "Where will the tool be?".into(),
            },
        },
    );
    h.snapshot("class_student_point_390x844");
    h.get_by_label("Send the target as my answer").click();
    h.run_steps(2);
    let target = h.state().model().target().translation.vector;
    let metres = h.state().model().robot().length_unit.in_metres();
    match &sent(&mut h)[..] {
        [
            ClientMessage::Answer {
                question: 4,
                value: Answer::Point { at },
            },
        ] => {
            for k in 0..3 {
                assert!((at[k] - target[k] * metres).abs() < 1e-12);
            }
        }
        other => panic!("sent {other:?}"),
    }
}

#[test]
fn the_projector_draws_each_prediction_and_their_spread_in_the_robots_units() {
    let mut h = room_page("robot=ur10", [1366.0, 768.0]);
    h.state_mut()
        .classroom_mut()
        .resume("K7QH3MXP".into(), TOKEN.into());
    let state = h.state().room_state();
    h.state_mut().classroom_mut().on_open(state);
    h.run_steps(2);
    let before = view_colours(&mut h);
    h.get_by_label("Ask the room").click();
    h.run_steps(2);
    h.get_by_label("Where will the tool be?").click();
    h.run_steps(2);
    let id = h
        .state()
        .classroom()
        .question()
        .map(Question::id)
        .expect("asked");
    // Three predictions around the UR10's tool (metres on the wire, millimetres drawn).
    let tool = h.state().model().fk().tool_position() / 1000.0;
    let values = [-0.2, 0.0, 0.2]
        .map(|dx| Answer::Point {
            at: [tool.x + dx, tool.y, tool.z],
        })
        .to_vec();
    arrive(
        &mut h,
        ServerMessage::Answers {
            question: id,
            values,
            count: 3,
        },
    );
    let drawn = h.state().room_predictions();
    assert_eq!(drawn.points.len(), 3);
    assert!((drawn.points[2][0] - (tool.x + 0.2) * 1000.0).abs() < 1e-6);
    // The view now shows the predictions' colour where it had none.
    let after = view_colours(&mut h);
    assert!(
        after > before + 60,
        "{after} pixels of the predictions' magenta, {before} before"
    );
}

/// How many of the 3D view's pixels are near the predictions' magenta (shaded).
fn view_colours(h: &mut Harness<'_, ArmLabApp>) -> usize {
    let [r, g, b, _] = armlab::app::view3d::predictions::COLOUR;
    super::view_pixels(h)
        .chunks(4)
        .filter(|p| {
            (i32::from(p[0]) - i32::from(r)).abs() < 40
                && (i32::from(p[1]) - i32::from(g)).abs() < 40
                && (i32::from(p[2]) - i32::from(b)).abs() < 40
        })
        .count()
}

#[test]
fn a_students_page_hides_the_entries_the_lecturer_hid_without_presentation_mode() {
    let mut h = room_page("robot=ur10", [1366.0, 768.0]);
    h.state_mut().classroom_mut().join("K7QH3MXP".into(), false);
    let state = h.state().room_state();
    h.state_mut().classroom_mut().on_open(state);
    // The lecturer, in presentation mode, hid the tool's x (the link's `hide=`).
    let mut lecturer = armlab::app::ArmLabApp::with_session(
        armlab_session::session::Session::for_preset("ur10").expect("a preset"),
    );
    lecturer.model_mut().set_presentation(true);
    lecturer.open_hash(&format!("{}&hide=Tn.14", lecturer.hash()));
    assert_eq!(
        lecturer.model().settings().hidden.len(),
        1,
        "the link hides one entry"
    );
    let link = lecturer.room_state().link;
    arrive(
        &mut h,
        ServerMessage::Joined {
            state: Some(State { link, camera: None }),
            question: None,
        },
    );
    assert!(!h.state().model().settings().presentation);
    assert!(h.state().model().hides_entries());
    // The student's page shows it as a "?" to predict, then reveal.
    assert_eq!(h.query_all_by_label("?").count(), 1);
}
