//! Robot files: every preset loads, saving and loading round-trips, and every kind of
//! bad input gives its own typed error with a sentence naming the joint and the field.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

use armlab_text::Sentence;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::{
    Convention, Field, JointKind, LengthUnit, PRESETS, Place, RobotError, robot_from_json,
    robot_to_json, tool_pose,
};

/// A valid one-joint robot with `joint` as its joint and `top` spliced into the object.
fn robot_text(top: &str, joint: &str) -> String {
    format!(
        r#"{{ "name": "test", "convention": "standard", "length_unit": "mm"{top}, "joints": [ {joint} ] }}"#
    )
}

/// A malformed file: what is wrong, the text, and the error it must give.
type Case = (&'static str, String, fn(&RobotError) -> bool);

const GOOD_JOINT: &str =
    r#"{ "type": "revolute", "theta_deg": 0, "d": 10, "a": 20, "alpha_deg": 90 }"#;

#[test]
fn every_preset_loads_and_round_trips_through_its_file_format() {
    assert_eq!(PRESETS.len(), 9);
    for (id, robot) in common::all_presets() {
        let again = robot_from_json(&robot_to_json(&robot)).unwrap();
        assert_eq!(again.name, robot.name, "{id}");
        assert_eq!(again.dof(), robot.dof());
        let q = common::rng(1).joint_vector(&robot);
        let diff = (tool_pose(&robot, &q).to_homogeneous()
            - tool_pose(&again, &q).to_homogeneous())
        .abs()
        .max();
        assert!(diff < 1e-9, "{id}: saved file changes the pose by {diff}");
        for (a, b) in robot.joints.iter().zip(&again.joints) {
            assert_eq!(a.kind, b.kind);
            assert!(
                (a.limits.min - b.limits.min).abs() < 1e-12
                    && (a.limits.max - b.limits.max).abs() < 1e-12
            );
        }
    }
}

#[test]
fn the_metrover_carries_its_part_sizes_from_spec() {
    let robot = armlab_core::preset("metrover").unwrap();
    assert_eq!(robot.parts.base, Some([600.0, 300.0, 340.0]));
    assert_eq!(robot.parts.hand, Some([80.0, 80.0, 160.0]));
    assert_eq!(robot.joints[1].parts.housing, Some([140.0, 140.0, 110.0]));
    assert_eq!(robot.joints[1].parts.link, Some([480.0, 80.0, 80.0]));
    assert_eq!(robot.joints[2].parts.housing, Some([80.0, 80.0, 110.0]));
    assert_eq!(robot.joints[3].parts.link, Some([490.0, 80.0, 80.0]));
    let again = robot_from_json(&robot_to_json(&robot)).unwrap();
    assert_eq!(again.parts, robot.parts);
    assert_eq!(again.joints[3].parts, robot.joints[3].parts);
}

#[test]
fn a_minimal_file_gets_sensible_defaults() {
    let robot = robot_from_json(&robot_text("", GOOD_JOINT)).unwrap();
    assert_eq!(robot.convention, Convention::Standard);
    assert_eq!(robot.length_unit, LengthUnit::Millimetre);
    let j = &robot.joints[0];
    assert_eq!(j.kind, JointKind::Revolute);
    assert_eq!(j.name, "joint 1");
    assert!((j.limits.max - std::f64::consts::PI).abs() < 1e-15);
    assert!(j.wraps());
}

#[test]
fn base_and_tool_transforms_apply() {
    let text = robot_text(
        r#", "base": { "xyz": [1, 2, 3] }, "tool": { "xyz": [0, 0, 5], "rpy_deg": [0, 0, 90] }"#,
        r#"{ "type": "revolute", "theta_deg": 0, "d": 0, "a": 0, "alpha_deg": 0 }"#,
    );
    let robot = robot_from_json(&text).unwrap();
    let pose = tool_pose(&robot, &[0.0]);
    common::assert_vec_near("tool", &pose.translation.vector, [1.0, 2.0, 8.0], 1e-12);
    common::assert_rot_near(
        "tool",
        pose.rotation.matrix(),
        [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        1e-12,
    );
    let again = robot_from_json(&robot_to_json(&robot)).unwrap();
    assert!(
        (tool_pose(&again, &[0.3]).to_homogeneous() - tool_pose(&robot, &[0.3]).to_homogeneous())
            .abs()
            .max()
            < 1e-12
    );
}

#[test]
fn malformed_files_each_give_their_own_typed_error() {
    let mut cases = malformed_robot_entries();
    cases.extend(malformed_joint_fields());
    cases.extend(bad_values_and_sizes());
    let mut seen = std::collections::HashSet::new();
    for (what, text, is_expected) in &cases {
        let err = robot_from_json(text).expect_err(what);
        assert!(is_expected(&err), "{what}: unexpected error {err:?}");
        let sentence = err.sentence(armlab_text::Lang::En);
        assert!(
            sentence.ends_with('.'),
            "{what}: '{sentence}' is a sentence"
        );
        assert!(
            seen.insert(sentence.clone()),
            "{what}: message repeats another case: {sentence}"
        );
    }
    // The messages name the joint and the field, in words.
    let err = robot_from_json(&cases[7].1).unwrap_err();
    assert_eq!(
        err.sentence(armlab_text::Lang::En),
        "In joint 2, the field \"d\" is missing."
    );
}

/// Malformed files: not JSON, not a robot, its own fields wrong or missing, no joints.
fn malformed_robot_entries() -> Vec<Case> {
    vec![
        ("not JSON", "{ name: ".to_string(), |e| {
            matches!(e, RobotError::Syntax { line: 1, .. })
        }),
        ("not an object", "[1, 2]".to_string(), |e| {
            matches!(
                e,
                RobotError::WrongType {
                    place: Place::Robot,
                    ..
                }
            )
        }),
        (
            "no name",
            r#"{ "convention": "standard", "length_unit": "mm", "joints": [] }"#.to_string(),
            |e| {
                matches!(
                    e,
                    RobotError::MissingField {
                        place: Place::Robot,
                        field: Field::Name
                    }
                )
            },
        ),
        (
            "unknown convention",
            r#"{ "name": "x", "convention": "craig", "length_unit": "mm", "joints": [] }"#
                .to_string(),
            |e| matches!(e, RobotError::UnknownConvention(c) if c == "craig"),
        ),
        (
            "unknown unit",
            r#"{ "name": "x", "convention": "standard", "length_unit": "inch", "joints": [] }"#
                .to_string(),
            |e| matches!(e, RobotError::UnknownLengthUnit(u) if u == "inch"),
        ),
        (
            "empty chain",
            robot_text("", "").replace("[  ]", "[]"),
            |e| matches!(e, RobotError::EmptyChain),
        ),
    ]
}

/// Malformed joints: an unknown type, a field missing, misspelt, text or infinite.
fn malformed_joint_fields() -> Vec<Case> {
    vec![
        (
            "unknown joint type",
            robot_text(
                "",
                r#"{ "type": "spherical", "theta_deg": 0, "d": 0, "a": 0, "alpha_deg": 0 }"#,
            ),
            |e| matches!(e, RobotError::UnknownJointType { joint: 1, found } if found == "spherical"),
        ),
        (
            "missing d",
            robot_text(
                "",
                &format!(
                    r#"{GOOD_JOINT}, {{ "type": "revolute", "theta_deg": 0, "a": 0, "alpha_deg": 0 }}"#
                ),
            ),
            |e| {
                matches!(
                    e,
                    RobotError::MissingField {
                        place: Place::Joint(2),
                        field: Field::D
                    }
                )
            },
        ),
        (
            "misspelt field",
            robot_text(
                "",
                r#"{ "type": "revolute", "theta_deg": 0, "d": 0, "a": 0, "alpha": 90 }"#,
            ),
            |e| matches!(e, RobotError::UnknownField { place: Place::Joint(1), field, .. } if field == "alpha"),
        ),
        (
            "number as text",
            robot_text(
                "",
                r#"{ "type": "revolute", "theta_deg": 0, "d": "NaN", "a": 0, "alpha_deg": 0 }"#,
            ),
            |e| {
                matches!(
                    e,
                    RobotError::WrongType {
                        place: Place::Joint(1),
                        field: Field::D,
                        ..
                    }
                )
            },
        ),
        (
            "infinite number",
            robot_text(
                "",
                r#"{ "type": "revolute", "theta_deg": 0, "d": 1e999, "a": 0, "alpha_deg": 0 }"#,
            ),
            |e| matches!(e, RobotError::Syntax { .. } | RobotError::NotFinite { .. }),
        ),
    ]
}

/// Well-formed files with bad values: reversed limits, no stroke, an absurd length, too
/// many joints, a negative part size, a tool that is not three numbers.
fn bad_values_and_sizes() -> Vec<Case> {
    let many_joints = vec![GOOD_JOINT; 65].join(",");
    vec![
        (
            "reversed limits",
            robot_text(
                "",
                r#"{ "type": "revolute", "theta_deg": 0, "d": 0, "a": 0, "alpha_deg": 0, "min_deg": 90, "max_deg": -90 }"#,
            ),
            |e| matches!(e, RobotError::LimitsReversed { joint: 1, .. }),
        ),
        (
            "prismatic without stroke",
            robot_text(
                "",
                r#"{ "type": "prismatic", "theta_deg": 0, "d": 0, "a": 0, "alpha_deg": 0 }"#,
            ),
            |e| matches!(e, RobotError::PrismaticWithoutLimits { joint: 1 }),
        ),
        (
            "absurd length",
            robot_text(
                "",
                r#"{ "type": "revolute", "theta_deg": 0, "d": 0, "a": 2e6, "alpha_deg": 0 }"#,
            ),
            |e| {
                matches!(
                    e,
                    RobotError::TooLarge {
                        place: Place::Joint(1),
                        field: Field::A,
                        ..
                    }
                )
            },
        ),
        ("too many joints", robot_text("", &many_joints), |e| {
            matches!(e, RobotError::TooManyJoints { count: 65, max: 64 })
        }),
        (
            "negative part size",
            robot_text(r#", "base_size": [600, -300, 340]"#, GOOD_JOINT),
            |e| {
                matches!(
                    e,
                    RobotError::NegativeSize {
                        place: Place::Robot,
                        field: Field::BaseSize,
                        ..
                    }
                )
            },
        ),
        (
            "bad tool",
            robot_text(r#", "tool": { "xyz": [1, 2] }"#, GOOD_JOINT),
            |e| {
                matches!(
                    e,
                    RobotError::WrongType {
                        place: Place::Tool,
                        field: Field::Xyz,
                        ..
                    }
                )
            },
        ),
    ]
}

#[test]
fn nan_and_infinity_from_code_are_rejected_by_validation() {
    let robot = common::all_presets().remove(0).1;
    let mut bad = robot.clone();
    bad.joints[2].dh.a = f64::NAN;
    assert!(matches!(
        bad.validated(),
        Err(RobotError::NotFinite {
            place: Place::Joint(3),
            ..
        })
    ));
    let mut bad = robot.clone();
    bad.joints[0].limits.max = f64::INFINITY;
    assert!(matches!(
        bad.validated(),
        Err(RobotError::NotFinite {
            place: Place::Joint(1),
            ..
        })
    ));
    assert!(matches!(
        robot.check_q(&[0.0; 3]),
        Err(RobotError::WrongJointCount {
            expected: 6,
            found: 3
        })
    ));
    assert!(matches!(
        robot.check_q(&[0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0]),
        Err(RobotError::JointValueNotFinite { joint: 3, .. })
    ));
    assert!(matches!(
        armlab_core::preset("r2d2"),
        Err(RobotError::UnknownPreset(..))
    ));
}

#[test]
fn json_api_answers_fk_and_jacobian_and_names_errors() {
    use armlab_api as api;
    let out: serde_json::Value =
        serde_json::from_str(&api::fk(r#"{"robot": "ur10", "q": [0,0,0,0,0,0]}"#).unwrap())
            .unwrap();
    let p = out["position"].as_array().unwrap();
    assert!((p[0].as_f64().unwrap() - 1184.5).abs() < 1e-9);
    assert_eq!(out["links"].as_array().unwrap().len(), 6);
    assert_eq!(out["tool"][1][2].as_f64().unwrap(), -1.0);
    let j: serde_json::Value = serde_json::from_str(
        &api::jacobian(r#"{"robot": "planar-2r", "q": [0.3, 0.0], "task": "position"}"#).unwrap(),
    )
    .unwrap();
    assert_eq!(j["near_singular"], true);
    assert_eq!(j["geometric"].as_array().unwrap().len(), 6);
    let err = api::fk(r#"{"robot": "ur10", "q": [0, 0]}"#).unwrap_err();
    assert_eq!(
        err.to_string(),
        "The robot has 6 joints but 2 joint values were given."
    );
    assert!(
        api::fk("{")
            .unwrap_err()
            .to_string()
            .starts_with("Bad request")
    );
    assert!(api::jacobian(r#"{"robot": "ur10", "task": "wiggle"}"#).is_err());
    let list: serde_json::Value = serde_json::from_str(&api::presets()).unwrap();
    assert_eq!(list.as_array().unwrap().len(), 9);
}

/// A robot file may bring keep-out boxes (`keep_out`: centre and size in the file's unit,
/// world frame): they load, round-trip, and every bad box gets its own typed error naming
/// the box and the field, in English and Finnish.
#[test]
fn keep_out_boxes_load_round_trip_and_bad_ones_get_typed_errors() {
    keep_out_boxes_load_and_round_trip();
    let cases = bad_keep_out_files();
    for (what, text, sentence) in &cases {
        let err = robot_from_json(text).expect_err(what);
        assert_eq!(&err.sentence(armlab_text::Lang::En), sentence, "{what}");
    }
    let err = robot_from_json(&cases[0].1).unwrap_err();
    assert!(matches!(
        err,
        RobotError::NegativeSize {
            place: Place::KeepOut(2),
            field: Field::Size,
            ..
        }
    ));
    assert_eq!(
        err.sentence(armlab_text::Lang::Fi),
        "Kieltoalueessa 2 kentässä \"size\" on -5: koko ei voi olla negatiivinen."
    );
    let err = robot_from_json(&with_second_box(
        r#"{ "centre": [0, 0, 0], "size": [1, 1, 1], "colour": "red" }"#,
    ))
    .unwrap_err();
    assert!(
        matches!(
            err,
            RobotError::UnknownField {
                place: Place::KeepOut(2),
                ..
            }
        ),
        "{err:?}"
    );
}

/// Two keep-out boxes load as written and round-trip; a file without them has none and
/// writes none.
fn keep_out_boxes_load_and_round_trip() {
    let boxes = r#", "keep_out": [ { "centre": [900, 0, 400], "size": [200, 400, 800] }, { "centre": [-1, 2.5, 3], "size": [1, 1, 1] } ]"#;
    let robot = robot_from_json(&robot_text(boxes, GOOD_JOINT)).expect("a valid robot file");
    assert_eq!(robot.keep_outs.len(), 2);
    assert_eq!(
        robot.keep_outs[0].centre,
        nalgebra::Point3::new(900.0, 0.0, 400.0)
    );
    assert_eq!(
        robot.keep_outs[0].size,
        nalgebra::Vector3::new(200.0, 400.0, 800.0)
    );
    assert_eq!(
        robot.keep_outs[1].centre,
        nalgebra::Point3::new(-1.0, 2.5, 3.0)
    );
    assert_eq!(
        robot_from_json(&robot_to_json(&robot)).expect("a valid robot file"),
        robot
    );
    assert!(
        robot_from_json(&robot_text("", GOOD_JOINT))
            .expect("a valid robot file")
            .keep_outs
            .is_empty()
    );
    assert!(
        !robot_to_json(&robot_from_json(&robot_text("", GOOD_JOINT)).expect("a valid robot file"))
            .contains("keep_out")
    );
}

/// A robot file with a good keep-out box and `b` as the second.
fn with_second_box(b: &str) -> String {
    robot_text(
        &format!(r#", "keep_out": [ {{ "centre": [0, 0, 500], "size": [1, 1, 1] }}, {b} ]"#),
        GOOD_JOINT,
    )
}

/// Files with a bad keep-out list: what is wrong, the file, and its English sentence.
fn bad_keep_out_files() -> Vec<(&'static str, String, &'static str)> {
    let one = with_second_box;
    let many = format!(
        r#", "keep_out": [{}]"#,
        vec![r#"{"centre": [0, 0, 0], "size": [1, 1, 1]}"#; 65].join(",")
    );
    let cases: Vec<(&'static str, String, &'static str)> = vec![
        (
            "negative size",
            one(r#"{ "centre": [0, 0, 0], "size": [200, -5, 800] }"#),
            "In keep-out box 2, the field \"size\" holds -5: a size cannot be negative.",
        ),
        (
            "zero size",
            one(r#"{ "centre": [0, 0, 0], "size": [200, 0, 800] }"#),
            "In keep-out box 2, the field \"size\" holds 0: it must be above zero.",
        ),
        (
            "absurd size",
            one(r#"{ "centre": [0, 0, 0], "size": [1e7, 1, 1] }"#),
            "In keep-out box 2, the field \"size\" is 10000000, larger in size than the limit 1000000.",
        ),
        (
            "absurd centre",
            one(r#"{ "centre": [0, -3e9, 0], "size": [1, 1, 1] }"#),
            "In keep-out box 2, the field \"centre\" is -3000000000, larger in size than the limit 1000000.",
        ),
        (
            "text for a number",
            one(r#"{ "centre": [0, 0, 0], "size": ["NaN", 1, 1] }"#),
            "In keep-out box 2, the field \"size\" must be a list of 3 numbers.",
        ),
        (
            "two numbers",
            one(r#"{ "centre": [0, 0], "size": [1, 1, 1] }"#),
            "In keep-out box 2, the field \"centre\" must be a list of 3 numbers.",
        ),
        (
            "no size",
            one(r#"{ "centre": [0, 0, 0] }"#),
            "In keep-out box 2, the field \"size\" is missing.",
        ),
        (
            "a number for a box",
            one("7"),
            "In keep-out box 2, the field \"keep_out\" must be a list of boxes, each with \"centre\" and \"size\" (3 numbers each).",
        ),
        (
            "not a list",
            robot_text(r#", "keep_out": { "centre": [0, 0, 0] }"#, GOOD_JOINT),
            "In the robot, the field \"keep_out\" must be a list of boxes, each with \"centre\" and \"size\" (3 numbers each).",
        ),
        (
            "too many",
            robot_text(&many, GOOD_JOINT),
            "In the robot, the field \"keep_out\" is 65, larger in size than the limit 64.",
        ),
    ];
    cases
}
