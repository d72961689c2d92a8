//! The lecture notebook's IK runs reproduced exactly (SPEC §1.3, docs/kinematics.md §8.7):
//! Newton–Raphson without wrapping and gradient descent on ‖e‖² with α = 0.01, to the
//! notebook's printed precision, with the wrapped equivalents beside them; and the
//! settings through the JSON API with typed errors.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_api::{ApiError, ik};
use armlab_core::ik::target_pose;
use armlab_core::{
    IkError, IkMethod, IkSettings, Objective, Task, preset, solve, wrapped_equivalent,
};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::{PI, TAU};

/// Asserts `got` rounds to the notebook's printed digits: |got − printed| ≤ half a unit
/// of the last printed digit.
fn assert_printed(what: &str, got: f64, printed: f64, decimals: i32) {
    let half = 0.5 * 10f64.powi(-decimals);
    assert!(
        (got - printed).abs() <= half,
        "{what}: {got} does not print as {printed}"
    );
}

fn newton_settings() -> IkSettings {
    IkSettings {
        position_tolerance: 1e-10,
        max_iterations: 1000,
        budget: 1000,
        restarts: 0,
        record_trace: true,
        wrap: false,
        ..IkSettings::default()
    }
}

#[test]
fn newton_raphson_without_wrapping_prints_the_notebooks_numbers() {
    let robot = preset("planar-2r").unwrap();
    let target = target_pose(Vector3::new(1.5, 1.5, 0.0), Matrix3::identity());
    let r = solve(
        &robot,
        &target,
        Task::Position,
        &[0.1, 0.1],
        IkMethod::PseudoInverse,
        &newton_settings(),
    )
    .unwrap();
    assert!(r.success, "{r:?}");
    assert!(r.position_error < 1e-10);
    // The notebook prints [-5.9844821 20.54568008].
    assert_printed("θ1", r.q[0], -5.9844821, 7);
    assert_printed("θ2", r.q[1], 20.54568008, 8);
    // Every step accumulated: the trace's q is its raw q, never wrapped.
    for step in &r.trace {
        assert_eq!(step.q, step.raw_q);
    }
    // The wrapped equivalents: the same arm, a whole number of turns away.
    let w = wrapped_equivalent(&robot, &r.q);
    for (raw, wrapped) in r.q.iter().zip(&w) {
        assert!(*wrapped > -PI && *wrapped <= PI);
        let turns = (raw - wrapped) / TAU;
        assert!((turns - turns.round()).abs() < 1e-12, "{turns}");
    }
    assert_printed("wrapped θ1", w[0], -5.9844821 + TAU, 6);
    assert_printed("wrapped θ2", w[1], 20.54568008 - 3.0 * TAU, 6);
    // With wrapping (the default) the run ends at the wrapped equivalent of some
    // solution of the same target, inside (−π, π].
    let wrapped = solve(
        &robot,
        &target,
        Task::Position,
        &[0.1, 0.1],
        IkMethod::PseudoInverse,
        &IkSettings {
            wrap: true,
            ..newton_settings()
        },
    )
    .unwrap();
    assert!(wrapped.success);
    assert!(wrapped.q.iter().all(|v| *v > -PI && *v <= PI));
}

#[test]
fn gradient_descent_on_the_squared_error_prints_the_notebooks_numbers() {
    let robot = preset("planar-2r").unwrap();
    let target = target_pose(Vector3::new(1.0, 1.5, 0.0), Matrix3::identity());
    let method = IkMethod::JacobianTranspose { alpha: Some(0.01) };
    let class = IkSettings {
        position_tolerance: 1e-10,
        max_iterations: 1000,
        budget: 1000,
        restarts: 0,
        record_trace: true,
        wrap: false,
        objective: Objective::Squared,
        ..IkSettings::default()
    };
    let r = solve(&robot, &target, Task::Position, &[0.1, 0.1], method, &class).unwrap();
    // 1000 iterations and it stops short: the notebook prints [0.46058393 2.0236129].
    assert_eq!(r.iterations, 1000);
    assert!(!r.success);
    assert_printed("θ1", r.q[0], 0.46058393, 8);
    assert_printed("θ2", r.q[1], 2.0236129, 7);
    // The error per iteration is there for the plot: the seed and 1000 steps, falling.
    assert_eq!(r.trace.len(), 1001);
    assert!(r.trace[1000].position_error < r.trace[0].position_error);
    // The angles stay inside (−π, π] here, so wrapping changes nothing.
    let wrapped = solve(
        &robot,
        &target,
        Task::Position,
        &[0.1, 0.1],
        method,
        &IkSettings {
            wrap: true,
            ..class.clone()
        },
    )
    .unwrap();
    assert_eq!(wrapped.q, r.q);
    assert_eq!(wrapped_equivalent(&robot, &r.q), r.q);
    // The default objective ½‖e‖² takes half the step: another answer after 1000.
    let half = solve(
        &robot,
        &target,
        Task::Position,
        &[0.1, 0.1],
        method,
        &IkSettings {
            objective: Objective::HalfSquared,
            ..class.clone()
        },
    )
    .unwrap();
    assert!((half.q[1] - 2.0236129).abs() > 1e-4, "{:?}", half.q);
    // Let it run on to the tolerance: it gets there.
    let on = solve(
        &robot,
        &target,
        Task::Position,
        &[0.1, 0.1],
        method,
        &IkSettings {
            max_iterations: 100_000,
            budget: 100_000,
            record_trace: false,
            ..class
        },
    )
    .unwrap();
    assert!(on.success && on.iterations > 1000, "{on:?}");
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).expect("the API answers JSON")
}

#[test]
fn the_json_api_takes_wrap_and_objective_and_rejects_bad_values_with_typed_errors() {
    let newton = r#"{"robot": "planar-2r", "q": [0.1, 0.1], "task": "position",
        "target": {"position": [1.5, 1.5, 0]}, "method": "pinv",
        "settings": {"wrap": false, "position_tolerance": 1e-10, "restarts": 0, "trace": true}}"#;
    let out = json(&ik(newton).unwrap());
    let q: Vec<f64> = serde_json::from_value(out["q"].clone()).unwrap();
    assert_printed("API θ1", q[0], -5.9844821, 7);
    assert_printed("API θ2", q[1], 20.54568008, 8);
    let wrapped: Vec<f64> = serde_json::from_value(out["wrapped_q"].clone()).unwrap();
    assert!((wrapped[0] - (q[0] + TAU)).abs() < 1e-9, "{wrapped:?}");
    let gradient = r#"{"robot": "planar-2r", "q": [0.1, 0.1], "task": "position",
        "target": {"position": [1.0, 1.5, 0]}, "method": "gradient", "alpha": 0.01,
        "settings": {"objective": "squared", "max_iterations": 1000, "budget": 1000,
                     "position_tolerance": 1e-10,
                     "restarts": 0, "wrap": false}}"#;
    let out = json(&ik(gradient).unwrap());
    let q: Vec<f64> = serde_json::from_value(out["q"].clone()).unwrap();
    assert_printed("API gradient θ1", q[0], 0.46058393, 8);
    assert_printed("API gradient θ2", q[1], 2.0236129, 7);
    // Bad values: typed errors naming the setting and the allowed values.
    for (settings, name, value) in [
        (r#"{"objective": "cubed"}"#, "objective", "\"cubed\""),
        (r#"{"objective": 2}"#, "objective", "2"),
        (r#"{"wrap": "yes"}"#, "wrap", "\"yes\""),
    ] {
        let request = format!(
            r#"{{"robot": "planar-2r", "target": {{"position": [1, 1, 0]}}, "settings": {settings}}}"#
        );
        match ik(&request) {
            Err(ApiError::Ik(IkError::SettingChoice {
                name: got_name,
                value: got_value,
                allowed,
            })) => {
                assert_eq!(got_name, name);
                assert_eq!(got_value, value);
                assert!(!allowed.is_empty());
            }
            other => panic!("{settings}: {other:?}"),
        }
    }
}
