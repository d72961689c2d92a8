//! The JSON API's `ik` (natively and as wasm).

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_api as api;
use armlab_core::ik::target_pose;
use armlab_core::{Task, preset, tool_pose};
use nalgebra::{Matrix3, Vector3};
use serde_json::Value;

#[test]
fn ik_round_trips_through_json() {
    let fk: Value = serde_json::from_str(
        &api::fk(r#"{"robot": "ur10", "q": [0.3, -1.0, 1.2, 0.4, 0.8, -0.7]}"#).unwrap(),
    )
    .unwrap();
    let tool = fk["tool"].clone();
    let robot = preset("ur10").unwrap();
    let target = tool_pose(&robot, &[0.3, -1.0, 1.2, 0.4, 0.8, -0.7]);
    for method in ["dls", "closed-form", "closed", "pinv"] {
        let request = serde_json::json!({
            "robot": "ur10", "q": [0.2, -0.9, 1.0, 0.5, 0.7, -0.6],
            "target": tool, "task": "full", "method": method,
            "settings": {"trace": true}
        });
        let out: Value = serde_json::from_str(&api::ik(&request.to_string()).unwrap()).unwrap();
        assert_eq!(out["success"], true, "{method}: {out}");
        let q: Vec<f64> = serde_json::from_value(out["q"].clone()).unwrap();
        assert_eq!(q.len(), 6);
        // The answer checked by the test's own FK difference and the robot's limits, not
        // by the response's own error fields.
        common::assert_reaches(method, &robot, &q, &target, Task::FullPose, 1e-3, 1e-6);
        common::assert_within_limits(method, &robot, &q);
        assert_eq!(
            out["method"],
            if method == "closed-form" {
                "closed"
            } else {
                method
            }
        );
        if method.starts_with("closed") {
            assert_eq!(out["family"], "ur");
            assert_eq!(out["solutions"].as_array().unwrap().len(), 8);
        } else {
            assert!(out["trace"].as_array().unwrap().len() >= 2, "{method}");
        }
    }
}

#[test]
fn ik_accepts_position_targets_drag_and_reports_errors() {
    let out: Value = serde_json::from_str(
        &api::ik(r#"{"robot": "metrover", "q": [0,0,0,0,0], "target": {"position": [600, 0, 520]}, "task": "position", "method": "pinv", "jacobian": "numerical"}"#)
            .unwrap(),
    )
    .unwrap();
    assert_eq!(out["success"], true, "{out}");
    let metrover = preset("metrover").unwrap();
    let q: Vec<f64> = serde_json::from_value(out["q"].clone()).unwrap();
    let goal = target_pose(Vector3::new(600.0, 0.0, 520.0), Matrix3::identity());
    common::assert_reaches("Metrover", &metrover, &q, &goal, Task::Position, 1e-3, 0.0);
    common::assert_within_limits("Metrover", &metrover, &q);
    let out: Value = serde_json::from_str(
        &api::ik(r#"{"robot": "ur10", "q": [0,0,0,0,0,0], "target": {"q": [1,1,1,1,1,1]}, "drag": true}"#)
            .unwrap(),
    )
    .unwrap();
    assert_eq!(out["clipped"], true, "{out}");
    for q in out["q"].as_array().unwrap() {
        assert!(q.as_f64().unwrap().abs() <= 0.1 + 1e-12);
    }
    // Each bad request gets a sentence that names the field or the value at fault.
    let cases = [
        (r#"{"robot": "ur10"}"#, "\"target\" is missing"),
        (
            r#"{"robot": "ur10", "target": {"position": [1, 2]}}"#,
            "\"target.position\" must be 3 numbers",
        ),
        (
            r#"{"robot": "ur10", "target": {"position": [1, "2", 3]}}"#,
            "\"target.position\" must be a list of numbers",
        ),
        (
            r#"{"robot": "ur10", "target": {"q": null, "position": [1, 2, 3]}}"#,
            "\"target.q\" must be a list of numbers",
        ),
        (
            r#"{"robot": "ur10", "target": "home"}"#,
            "\"target\" must be 4×4 rows, {\"position\", \"rotation\"} or {\"q\"}",
        ),
        (
            r#"{"robot": "ur10", "target": {"position": [1, 2, 3], "rotation": [[1, 0, 0], [0, 1, 0]]}}"#,
            "\"target.rotation\" must be 3 rows of numbers",
        ),
        (
            r#"{"robot": "ur10", "target": {"position": [1, 2, 3]}, "method": "magic"}"#,
            "unknown method \"magic\": use one of dls, pinv, gradient, closed",
        ),
        (
            r#"{"robot": "ur10", "target": {"position": [1, 2, 3]}, "task": "sideways"}"#,
            "unknown task \"sideways\": use one of position, axis-z, axis-x, axis-y, full",
        ),
        (
            r#"{"robot": "ur10", "target": {"position": [1, 2, 3], "rotation": [[2,0,0],[0,1,0],[0,0,1]]}}"#,
            "not a valid pose",
        ),
        (
            r#"{"robot": "panda", "target": {"position": [1, 2, 3]}, "method": "closed-form"}"#,
            "\"Franka Panda\" has no closed-form IK",
        ),
        (
            r#"{"robot": "ur10", "target": {"position": [1, 2, 3]}, "settings": {"budget": -1}}"#,
            "\"settings.budget\" must be a whole number",
        ),
        (
            r#"{"robot": "ur10", "target": {"position": [1, 2, 3]}, "settings": {"position_tolerance": 0}}"#,
            "position_tolerance must be a positive number, not 0",
        ),
    ];
    for (bad, expected) in cases {
        let err = api::ik(bad).unwrap_err().to_string();
        assert!(err.contains(expected), "{bad}: {err}");
    }
    // The API keeps the core's IK error, variant and all.
    assert!(matches!(
        api::ik(r#"{"robot": "panda", "target": {"position": [1, 2, 3]}, "method": "closed"}"#),
        Err(api::ApiError::Ik(armlab_core::IkError::NoClosedForm(_)))
    ));
}

#[test]
fn each_field_of_the_wrong_type_gets_its_own_sentence_null_included() {
    // The request is read through serde; a wrong type (null too: it is not an absent
    // field) must still name the field, in the words a person can act on.
    let target = r#""target": {"position": [800, -200, 400]}"#;
    let cases = [
        (
            r#"["ur10"]"#.to_string(),
            "Bad request: the field \"robot\" is missing",
        ),
        (
            r#"{"robot": null}"#.into(),
            "Bad request: \"robot\" must be a preset id or a robot file object",
        ),
        (
            r#"{"robot": "ur10", "q": null}"#.into(),
            "Bad request: \"q\" must be a list of numbers",
        ),
        (
            r#"{"robot": "ur10", "q": [0, "1", 0, 0, 0, 0]}"#.into(),
            "Bad request: \"q\" must be a list of numbers",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "task": null}}"#),
            "Bad request: \"task\" must be a text",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "drag": null}}"#),
            "Bad request: \"drag\" must be true or false",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "drag": 1}}"#),
            "Bad request: \"drag\" must be true or false",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "method": 3}}"#),
            "Bad request: \"method\" must be a text: one of dls, pinv, gradient, closed",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "method": "gradient", "alpha": -1}}"#),
            "Bad request: \"alpha\" must be a positive number",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "jacobian": "exact"}}"#),
            "Bad request: \"jacobian\" must be \"geometric\" or \"numerical\"",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "settings": [1]}}"#),
            "Bad request: \"settings\" must be an object",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "settings": {{"seed": 1.5}}}}"#),
            "Bad request: \"settings.seed\" must be a whole number ≥ 0",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "settings": {{"trace": null}}}}"#),
            "Bad request: \"settings.trace\" must be true or false",
        ),
        (
            format!(
                r#"{{"robot": "ur10", {target}, "settings": {{"position_tolerance": "small"}}}}"#
            ),
            "Bad request: \"settings.position_tolerance\" must be a number",
        ),
        (
            format!(r#"{{"robot": "ur10", {target}, "settings": {{"tolerance": 1}}}}"#),
            "Bad request: \"settings.tolerance\" is not known; the known settings are: position_tolerance, orientation_tolerance, max_iterations, budget, restarts, seed, max_joint_change, trace, wrap, objective",
        ),
    ];
    for (request, expected) in cases {
        let err = api::ik(&request).unwrap_err().to_string();
        assert_eq!(err, expected, "{request}");
    }
    // Fields the API does not know are ignored at the top level; null is taken where it
    // means something: `alpha` (the adaptive step) and `max_joint_change` (no limit set).
    let out: Value = serde_json::from_str(
        &api::ik(&format!(
            r#"{{"robot": "ur10", "q": [0, -1, 1, -1, -1, 0], {target}, "task": "position",
                "note": "mine", "alpha": null, "settings": {{"max_joint_change": null}}}}"#
        ))
        .unwrap(),
    )
    .unwrap();
    assert_eq!(out["clipped"], false, "{out}");
    assert_eq!(out["success"], true, "{out}");
}
