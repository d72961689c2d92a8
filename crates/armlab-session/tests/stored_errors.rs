//! Bad stored JSON gives the typed error a link's bad value gives (or, for JSON that is
//! not a session's, `LinkError::UnreadableSession`), never a panic; serde's own message
//! never reaches a person.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_core::motion::{MotionError, Setting};
use armlab_core::{Field, Place, RobotError};
use armlab_session::motion::MotionLinkError;
use armlab_session::session::{LinkError, Session};
use armlab_text::{Key, Lang};
use serde_json::{Value, json};

/// A stored session of the UR10 with every part present, as a JSON value to spoil.
fn stored() -> Value {
    let mut session = Session::default_session();
    session.target = Some(nalgebra::IsometryMatrix3::identity());
    session.camera =
        armlab_session::settings::CameraPose::from_array([0.5, 0.3, 3000.0, 0.0, 0.0, 500.0]);
    session.display.lang = Some(Lang::Fi);
    serde_json::from_str(&session.to_json()).expect("JSON")
}

/// `stored()` with `path` (keys from the top) set to `value`, or removed for `None`.
fn spoiled(path: &[&str], value: Option<Value>) -> String {
    let mut root = stored();
    let (last, parents) = path.split_last().expect("a path");
    let mut node = &mut root;
    for key in parents {
        node = node.get_mut(*key).expect("a key");
    }
    let obj = node.as_object_mut().expect("an object");
    match value {
        Some(v) => obj.insert(last.to_string(), v),
        None => obj.remove(*last),
    };
    root.to_string()
}

#[test]
fn json_that_is_not_a_session_s_is_unreadable_in_plain_words() {
    for text in [
        "",
        "{",
        "[]",
        "null",
        "\"ur10\"",
        "{}",
        &spoiled(&["q"], Some(json!("0,0,0"))),
        &spoiled(&["q"], None),
        &spoiled(&["task"], Some(json!(3))),
        &spoiled(&["target"], Some(json!([1, 2, 3]))),
        &spoiled(&["display"], Some(json!("deg"))),
        &spoiled(&["display", "precision"], Some(json!(-1))),
        &spoiled(&["motion", "time_scale"], Some(json!("fast"))),
        &spoiled(&["robot"], None),
    ] {
        assert_eq!(
            Session::from_json(text),
            Err(LinkError::UnreadableSession),
            "{text}"
        );
    }
    let e = LinkError::UnreadableSession;
    assert_eq!(e.to_string(), "the stored session could not be read");
    assert_eq!(e.sentence(Lang::Fi), "tallennettua istuntoa ei voitu lukea");
}

#[test]
fn a_bad_stored_value_gives_the_link_s_typed_error() {
    let mut cases = bad_robots_and_ids();
    cases.extend(bad_display_camera_and_motion());
    for (text, expected) in cases {
        assert_eq!(Session::from_json(&text), Err(expected), "{text}");
    }
}

/// A stored session and the error it must give.
type Case = (String, LinkError);

/// A bad robot file, joint vector, source, task, method or exercise.
fn bad_robots_and_ids() -> Vec<Case> {
    vec![
        (
            // The robot comes first, and its first joint's "d" first of its fields.
            stored().to_string().replacen("\"d\":", "\"d_mm\":", 1),
            LinkError::Robot(RobotError::UnknownField {
                place: Place::Joint(1),
                field: "d_mm".into(),
                known: "name, type, theta_deg, d, a, alpha_deg, min_deg, max_deg, min, max, home, max_speed, max_acceleration, housing_size, link_size".into(),
            }),
        ),
        (
            spoiled(&["robot", "name"], Some(json!(7))),
            LinkError::Robot(RobotError::WrongType {
                place: Place::Robot,
                field: Field::Name,
                expected: armlab_core::Expected::Text,
            }),
        ),
        (
            spoiled(&["q"], Some(json!([0, 0]))),
            LinkError::Robot(RobotError::WrongJointCount {
                expected: 6,
                found: 2,
            }),
        ),
        (
            spoiled(&["source"], Some(json!("r2d2"))),
            LinkError::Robot(armlab_core::preset("r2d2").expect_err("no such preset")),
        ),
        (
            spoiled(&["task"], Some(json!("sideways"))),
            LinkError::UnknownTask("sideways".into()),
        ),
        (
            spoiled(&["method"], Some(json!("magic"))),
            LinkError::UnknownMethod("magic".into()),
        ),
        (
            spoiled(&["exercise"], Some(json!("ur11"))),
            LinkError::UnknownExercise("ur11".into()),
        ),
        (
            spoiled(&["exercise"], Some(json!("rrr"))),
            LinkError::ExerciseWithRobot,
        ),
    ]
}

/// A bad display field, camera or motion lab field.
fn bad_display_camera_and_motion() -> Vec<Case> {
    vec![
        (
            spoiled(&["display", "lang"], Some(json!("sv"))),
            LinkError::BadValue {
                field: "lang".into(),
                text: "sv".into(),
                allowed: Key::AllowedLang,
            },
        ),
        (
            spoiled(&["display", "precision"], Some(json!(9))),
            LinkError::BadValue {
                field: "decimals".into(),
                text: "9".into(),
                allowed: Key::AllowedDecimals,
            },
        ),
        (
            spoiled(&["display", "panels"], Some(json!(["joints", "arms"]))),
            LinkError::BadValue {
                field: "panels".into(),
                text: "arms".into(),
                allowed: Key::AllowedPanels,
            },
        ),
        (
            spoiled(&["display", "hidden"], Some(json!(["A2", "X2"]))),
            LinkError::BadHidden("X2".into()),
        ),
        (
            spoiled(&["camera"], Some(json!([0, 0, 0, 0, 0, 0]))),
            LinkError::BadCamera,
        ),
        (
            spoiled(&["motion", "controller"], Some(json!("bang"))),
            LinkError::Motion(MotionLinkError::UnknownController("bang".into())),
        ),
        (
            spoiled(&["motion", "keep_outs"], Some(json!([[0, 0, 0, 1, 0, 1]]))),
            LinkError::Motion(MotionLinkError::Value(MotionError::NotPositive {
                setting: Setting::KeepOut(1),
                value: 0.0,
            })),
        ),
    ]
}

#[test]
fn no_cut_or_changed_byte_of_a_stored_session_panics() {
    let text = stored().to_string();
    let mut read = 0;
    for end in 0..text.len() {
        // Each cut and each byte changed to a digit, a quote or a bracket: an error or a
        // session, never a panic.
        let cut = text.get(..end).unwrap_or_default();
        assert!(Session::from_json(cut).is_err(), "{cut}");
        for b in [b'9', b'"', b'['] {
            let mut bytes = text.clone().into_bytes();
            bytes[end] = b;
            if let Ok(changed) = String::from_utf8(bytes) {
                read += usize::from(Session::from_json(&changed).is_ok());
            }
        }
    }
    assert!(read > 0, "some changed digits still read");
}
