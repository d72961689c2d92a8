//! Robustness: every case a quick fuzz of the JSON API found gets a sentence or
//! a bounded answer, and messages stay readable (at most 40 characters of the person's
//! text, no control characters, numbers short).

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

use armlab_text::Sentence;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_api as api;
use armlab_core::ik::target_pose;
use armlab_core::{
    ForwardKinematics, IkError, IkMethod, IkSettings, JacobianSource, MAX_TARGET_DISTANCE,
    RobotError, Task, geometric_jacobian, jacobian_measures, preset, solve,
};
use nalgebra::{Matrix3, Matrix6xX, Vector3};
use serde_json::{Value, json};

/// A robot file with `n` prismatic joints of stroke `0…max` (mm).
fn prismatic_robot(n: usize, max: f64) -> Value {
    let joints: Vec<Value> = (0..n)
        .map(|i| {
            json!({"type": "prismatic", "theta_deg": 0, "d": 0, "a": 10,
                   "alpha_deg": if i % 2 == 0 { 90 } else { -90 }, "min": 0, "max": max})
        })
        .collect();
    json!({"name": "slides", "convention": "standard", "length_unit": "mm", "joints": joints})
}

fn error_of(result: Result<String, api::ApiError>) -> String {
    match result {
        Ok(out) => panic!("expected an error, got {}", &out[..out.len().min(300)]),
        Err(e) => e.to_string(),
    }
}

/// The message holds no control character and no run of more than `max_run` characters
/// from `fill` (the person's text), and no number longer than 20 characters.
fn assert_readable(message: &str, fill: char, max_run: usize) {
    assert!(
        !message.chars().any(char::is_control),
        "control character in {message:?}"
    );
    let longest_run = message
        .split(|c| c != fill)
        .map(|run| run.chars().count())
        .max()
        .unwrap_or(0);
    assert!(
        longest_run <= max_run,
        "{longest_run} × {fill:?} in {message}"
    );
    let longest_number = message
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .map(str::len)
        .max()
        .unwrap_or(0);
    assert!(longest_number <= 20, "a long number in {message}");
    assert!(message.chars().count() < 400, "{message}");
}

#[test]
fn a_jacobian_of_prismatic_joints_at_1_7e308_is_a_sentence_not_a_hang() {
    // The fuzz case: the joint values overflowed the pose to infinity, NaN reached the
    // SVD, which never converged (9 minutes, then a panic).
    let request =
        json!({"robot": prismatic_robot(4, 1000.0), "q": [1.7e308, 1.7e308, 1.7e308, 1.7e308]});
    let message = error_of(api::jacobian(&request.to_string()));
    assert_eq!(
        message,
        "The value 1.7e308 of joint 1 lies outside its stroke 0 … 1000."
    );
    assert_readable(&message, '0', 12);
}

#[test]
fn a_prismatic_value_outside_its_stroke_gets_a_sentence() {
    let robot = prismatic_robot(1, 1.0);
    for (q, want) in [
        (
            5.0,
            Some("The value 5 of joint 1 lies outside its stroke 0 … 1."),
        ),
        (
            -0.5,
            Some("The value -0.5 of joint 1 lies outside its stroke 0 … 1."),
        ),
        (1.0, None),
        (0.0, None),
        // Inside the slack of a link's six decimals.
        (1.0 + 5e-7, None),
    ] {
        let request = json!({"robot": robot, "q": [q]});
        match (api::fk(&request.to_string()), want) {
            (Err(e), Some(want)) => assert_eq!(e.to_string(), want),
            (Ok(out), None) => {
                let out: Value = serde_json::from_str(&out).unwrap();
                // d = q along z0 of the standard table: the tool is at (10, 0, q).
                let z = out["position"][2].as_f64().unwrap();
                assert!((z - q).abs() < 1e-12, "q = {q}: z = {z}");
            }
            (got, want) => panic!("q = {q}: got {got:?}, want {want:?}"),
        }
    }
    // The Stanford arm's d3 travels 0.3048…1.27 m: 5 m is refused, for IK seeds too.
    let stanford = preset("stanford").unwrap();
    let mut q = stanford.home();
    q[2] = 5.0;
    assert_eq!(
        stanford.check_q(&q),
        Err(RobotError::JointOutsideStroke {
            joint: 3,
            value: 5.0,
            min: 0.3048,
            max: 1.27
        })
    );
    let target = target_pose(Vector3::new(0.5, 0.2, 0.6), Matrix3::identity());
    let r = solve(
        &stanford,
        &target,
        Task::Position,
        &q,
        IkMethod::DampedLeastSquares,
        &IkSettings::default(),
    );
    assert!(
        matches!(
            r,
            Err(IkError::Robot(RobotError::JointOutsideStroke {
                joint: 3,
                ..
            }))
        ),
        "{r:?}"
    );
    // A robot file whose prismatic home lies outside the stroke is refused when read.
    let mut file = prismatic_robot(2, 1.0);
    file["joints"][1]["home"] = json!(7);
    let message = error_of(api::robot(&json!({ "robot": file }).to_string()));
    assert_eq!(
        message,
        "The value 7 of joint 2 lies outside its stroke 0 … 1."
    );
}

#[test]
fn revolute_values_outside_the_limits_are_answered_as_the_api_promises() {
    // FK answers for any finite angle: the Metrover's joint 2 (0°…180°) at −90°.
    let out = api::fk(r#"{"robot": "metrover", "q": [0, -1.5707963267948966, 0, 0, 0]}"#).unwrap();
    let out: Value = serde_json::from_str(&out).unwrap();
    let p: Vec<f64> = serde_json::from_value(out["position"].clone()).unwrap();
    // The upper arm (400 mm along x at q2 = 0) turns down: x = 0, z = 70 − 400 + …
    assert!(p.iter().all(|v| v.is_finite()), "{p:?}");
    assert!(p[2] < -300.0, "{p:?}");
    // A huge angle is still a finite pose.
    let out = api::fk(r#"{"robot": "ur10", "q": [1e300, -1e300, 0, 0, 0, 0]}"#).unwrap();
    let out: Value = serde_json::from_str(&out).unwrap();
    let p: Vec<f64> = serde_json::from_value(out["position"].clone()).unwrap();
    assert!(p.iter().all(|v| v.is_finite() && v.abs() < 1400.0), "{p:?}");
}

#[test]
fn a_pose_that_overflows_is_a_typed_error_never_an_svd_input() {
    // A robot built in code (never validated) with lengths near f64::MAX.
    let mut robot = preset("ur10").unwrap();
    for joint in &mut robot.joints {
        joint.dh.a = 1.7e308;
    }
    let q = vec![0.0; 6];
    assert_eq!(
        ForwardKinematics::new(&robot, &q).err(),
        Some(RobotError::PoseNotFinite)
    );
    assert_eq!(
        RobotError::PoseNotFinite.sentence(armlab_text::Lang::En),
        "At these joint values the tool pose is not a finite number (a value overflows): nothing can be computed from it."
    );
    // IK on it ends with the same error, after a bounded number of iterations.
    let target = target_pose(Vector3::new(100.0, 0.0, 0.0), Matrix3::identity());
    for method in [
        IkMethod::DampedLeastSquares,
        IkMethod::PseudoInverse,
        IkMethod::JacobianTranspose { alpha: None },
    ] {
        let r = solve(
            &robot,
            &target,
            Task::FullPose,
            &q,
            method,
            &IkSettings::default(),
        );
        assert_eq!(
            r.err(),
            Some(IkError::Robot(RobotError::PoseNotFinite)),
            "{method:?}"
        );
    }
    // A Jacobian holding NaN is not decomposed: no singular values, flagged singular.
    let mut j = Matrix6xX::from_element(6, 1.0);
    j[(2, 3)] = f64::NAN;
    let m = jacobian_measures(&j, Task::FullPose, &Matrix3::identity(), 1.0);
    assert!(m.singular_values.is_empty());
    assert_eq!(m.manipulability, 0.0);
    assert_eq!((m.determinant, m.condition_number), (None, None));
    assert!(m.near_singular);
    // A finite one still is (the UR10 at home: six singular values, none zero).
    let ur10 = preset("ur10").unwrap();
    let fk = ForwardKinematics::new(&ur10, &ur10.home()).unwrap();
    let m = jacobian_measures(
        &geometric_jacobian(&fk),
        Task::FullPose,
        fk.tool_rotation(),
        ur10.reach(),
    );
    assert_eq!(m.singular_values.len(), 6);
    assert!(m.singular_values[5] > 1e-3, "{:?}", m.singular_values);
}

#[test]
fn an_ik_budget_of_ten_million_is_capped() {
    // The fuzz case blocked for 25 s: budget and max_iterations of 10 000 000. A fixed
    // gradient step too small to arrive uses every iteration it may: exactly the cap.
    let request = json!({
        "robot": "planar-2r", "target": {"position": [1, 1.5, 0]}, "task": "position",
        "method": "gradient", "alpha": 1e-12,
        "settings": {"budget": 10_000_000u64, "max_iterations": 10_000_000u64, "restarts": 10_000_000u64}
    });
    let out: Value = serde_json::from_str(&api::ik(&request.to_string()).unwrap()).unwrap();
    let planar = preset("planar-2r").unwrap();
    let cap = api::iteration_cap(&planar, JacobianSource::Geometric, false);
    assert_eq!(cap, api::MAX_ITERATIONS);
    assert_eq!(out["iterations"].as_u64(), Some(cap as u64), "{out}");
    assert_eq!(out["restarts"].as_u64(), Some(0), "{out}");
    assert_eq!(out["success"], false);
    // Restarts are capped too: an unreachable target, each attempt a few iterations.
    let request = json!({
        "robot": "planar-2r", "target": {"position": [10, 0, 0]}, "task": "position",
        "settings": {"max_iterations": 3, "budget": 10_000_000u64, "restarts": 10_000_000u64}
    });
    let out: Value = serde_json::from_str(&api::ik(&request.to_string()).unwrap()).unwrap();
    let restarts = out["restarts"].as_u64().unwrap() as usize;
    assert!(restarts <= api::MAX_RESTARTS, "{out}");
    assert_eq!(out["unreachable"], true);
    // A 64-joint arm with the central-difference Jacobian gets a smaller cap, the same
    // work: 50 million joint transforms.
    let mut joints = Vec::new();
    for i in 0..64 {
        joints.push(json!({"type": "revolute", "theta_deg": 0, "d": 0, "a": 10, "alpha_deg": if i % 2 == 0 { 90 } else { 0 }}));
    }
    let long = armlab_core::robot_from_value(
        &json!({"name": "snake", "convention": "standard", "length_unit": "mm", "joints": joints}),
    )
    .unwrap();
    assert_eq!(
        api::iteration_cap(&long, JacobianSource::CentralDifference, false),
        6009
    );
    assert_eq!(
        api::iteration_cap(&long, JacobianSource::Geometric, false),
        50_000
    );
    assert_eq!(
        api::iteration_cap(&long, JacobianSource::Geometric, true),
        1851
    );
}

#[test]
fn an_ik_target_1e308_away_is_a_sentence() {
    for position in [[1e308, 0.0, 0.0], [1e308, 1e308, 1e308], [0.0, -2e9, 0.0]] {
        let request = json!({"robot": "ur10", "target": {"position": position}});
        let message = error_of(api::ik(&request.to_string()));
        assert!(
            message.starts_with("The target is ")
                && message.contains("farther than 1000000000, the most ArmLab accepts"),
            "{message}"
        );
        assert_readable(&message, '0', 12);
    }
    let message = error_of(api::ik(
        &json!({"robot": "ur10", "target": {"position": [1e308, 0, 0]}}).to_string(),
    ));
    assert_eq!(
        message,
        "The target is 1e308 from the base, farther than 1000000000, the most ArmLab accepts (in the robot's length unit)."
    );
    // Just inside the limit: an answer, unreachable, with a finite error.
    let request = json!({"robot": "ur10", "target": {"position": [MAX_TARGET_DISTANCE, 0, 0]}, "task": "position"});
    let out: Value = serde_json::from_str(&api::ik(&request.to_string()).unwrap()).unwrap();
    assert_eq!(out["success"], false);
    assert_eq!(out["unreachable"], true);
    let error = out["position_error"].as_f64().unwrap();
    // The arm stretches toward it: the error is the distance less how far the UR10
    // reaches along x (1.32 m today), which its links' lengths bound: 612 + 572.3 + 163.9
    // + 115.7 + 92.2 = 1556.1 mm (d1 is vertical).
    let stretched = MAX_TARGET_DISTANCE - error;
    assert!(stretched > 1000.0 && stretched <= 1556.1, "{error}");
}

#[test]
fn a_thousand_character_name_comes_back_cut_to_forty() {
    let long = "x".repeat(1000);
    let file = json!({"name": "t", "convention": long, "length_unit": "mm",
                      "joints": [{"type": "revolute", "theta_deg": 0, "d": 0, "a": 1, "alpha_deg": 0}]});
    let message = error_of(api::fk(&json!({ "robot": file }).to_string()));
    assert!(
        message.starts_with(&format!(
            "The convention \"{}…\" is not known",
            "x".repeat(39)
        )),
        "{message}"
    );
    assert_readable(&message, 'x', 39);
    // Every place that repeats a person's text cuts it the same way.
    let requests = [
        json!({ "robot": long }),
        json!({"robot": "ur10", "task": long}),
        json!({"robot": "ur10", "target": {"position": [1, 2, 3]}, "method": long}),
        json!({"robot": "ur10", "target": {"position": [1, 2, 3]}, "settings": { long.clone(): 1 }}),
        json!({"robot": {"name": "t", "convention": "standard", "length_unit": long, "joints": []}}),
        json!({"robot": {"name": "t", "convention": "standard", "length_unit": "mm", "joints": [{"type": long}]}}),
        json!({"robot": {"name": "t", "convention": "standard", "length_unit": "mm", long.clone(): 1, "joints": []}}),
    ];
    for request in requests {
        let text = request.to_string();
        let message = error_of(if text.contains("target") {
            api::ik(&text)
        } else {
            api::jacobian(&text)
        });
        assert!(message.contains('…'), "{message}");
        assert_readable(&message, 'x', 39);
    }
}

#[test]
fn control_characters_and_long_numbers_do_not_reach_a_message() {
    let message = error_of(api::fk(r#"{"robot": "ur\u0007\u001b[2J10\n"}"#));
    assert!(
        message.starts_with("There is no robot called \"ur\u{25A1}\u{25A1}[2J10\u{25A1}\""),
        "{message}"
    );
    assert_readable(&message, '\u{7}', 0);
    // A length of 1e300 is written as 1e300, not 301 digits.
    let file = json!({"name": "t", "convention": "standard", "length_unit": "mm",
                      "joints": [{"type": "revolute", "theta_deg": 0, "d": 1e300, "a": 1, "alpha_deg": 0}]});
    let message = error_of(api::fk(&json!({ "robot": file }).to_string()));
    assert_eq!(
        message,
        "In joint 1, the field \"d\" is 1e300, larger in size than the limit 1000000."
    );
    let message = error_of(api::ik(
        &json!({"robot": "ur10", "target": {"position": [1, 2, 3]}, "settings": {"position_tolerance": -1e-300}})
            .to_string(),
    ));
    assert_eq!(
        message,
        "The IK settings are not valid: position_tolerance must be a positive number, not -1e-300."
    );
    // The Finnish sentences use the same helper.
    let e = RobotError::TooLarge {
        place: armlab_core::Place::Joint(1),
        field: armlab_core::Field::D,
        value: -1.7e308,
        limit: 1e6,
    };
    assert_eq!(
        e.sentence(armlab_text::Lang::Fi),
        "Nivelessä 1 kentän \"d\" arvo on -1.7e308, itseisarvoltaan suurempi kuin raja 1000000."
    );
}
