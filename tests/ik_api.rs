//! The JSON API's `ik` (natively and as wasm).

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

mod common;

use armlab::api;
use serde_json::Value;

#[test]
fn ik_round_trips_through_json() {
    let fk: Value = serde_json::from_str(
        &api::fk(r#"{"robot": "ur10", "q": [0.3, -1.0, 1.2, 0.4, 0.8, -0.7]}"#).unwrap(),
    )
    .unwrap();
    let tool = fk["tool"].clone();
    for method in ["dls", "closed-form", "pinv"] {
        let request = serde_json::json!({
            "robot": "ur10", "q": [0.2, -0.9, 1.0, 0.5, 0.7, -0.6],
            "target": tool, "task": "full", "method": method,
            "settings": {"trace": true}
        });
        let out: Value = serde_json::from_str(&api::ik(&request.to_string()).unwrap()).unwrap();
        assert_eq!(out["success"], true, "{method}: {out}");
        assert!(out["position_error"].as_f64().unwrap() <= 1e-3);
        let q: Vec<f64> = serde_json::from_value(out["q"].clone()).unwrap();
        assert_eq!(q.len(), 6);
        if method == "closed-form" {
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
    let out: Value = serde_json::from_str(
        &api::ik(r#"{"robot": "ur10", "q": [0,0,0,0,0,0], "target": {"q": [1,1,1,1,1,1]}, "drag": true}"#)
            .unwrap(),
    )
    .unwrap();
    assert_eq!(out["clipped"], true, "{out}");
    for q in out["q"].as_array().unwrap() {
        assert!(q.as_f64().unwrap().abs() <= 0.1 + 1e-12);
    }
    for bad in [
        r#"{"robot": "ur10"}"#,
        r#"{"robot": "ur10", "target": {"position": [1, 2]}}"#,
        r#"{"robot": "ur10", "target": {"position": [1, 2, 3]}, "method": "magic"}"#,
        r#"{"robot": "ur10", "target": {"position": [1, 2, 3], "rotation": [[2,0,0],[0,1,0],[0,0,1]]}}"#,
        r#"{"robot": "panda", "target": {"position": [1, 2, 3]}, "method": "closed-form"}"#,
        r#"{"robot": "ur10", "target": {"position": [1, 2, 3]}, "settings": {"budget": -1}}"#,
        r#"{"robot": "ur10", "target": {"position": [1, 2, 3]}, "settings": {"position_tolerance": 0}}"#,
    ] {
        let err = api::ik(bad).unwrap_err().to_string();
        assert!(!err.is_empty(), "{bad}");
    }
}
