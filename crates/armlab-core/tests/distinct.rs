//! Distinct solutions from seeded restarts (docs/kinematics.md §9.7): on the UR10 they
//! are exactly the closed form's; on redundant tasks (the Panda's full pose, the
//! Metrover's position) at most eight samples of the continuum, one per sign pattern.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::ik::configuration_signs;
use armlab_core::{
    IkSettings, MAX_CONTINUUM_SAMPLES, Task, closed_form_solutions, distinct_solutions, preset,
    tool_pose,
};

#[test]
fn ur10_restarts_find_exactly_the_closed_form_branches() {
    let robot = preset("ur10").unwrap();
    let q = [0.3, -1.0, 1.2, 0.4, 0.9, -0.7];
    let target = tool_pose(&robot, &q);
    let set = closed_form_solutions(&robot, &target, &q).unwrap();
    assert_eq!(set.solutions.len(), 8);
    let found =
        distinct_solutions(&robot, &target, Task::FullPose, &IkSettings::default(), 400).unwrap();
    assert!(!found.continuum);
    assert_eq!(found.solutions.len(), 8, "after {} starts", found.attempts);
    for f in &found.solutions {
        common::assert_reaches("UR10", &robot, &f.q, &target, Task::FullPose, 1e-3, 1e-6);
        let matches = set
            .solutions
            .iter()
            .filter(|s| {
                robot
                    .joints
                    .iter()
                    .zip(s.q.iter().zip(&f.q))
                    .all(|(j, (a, b))| j.change(*a, *b).abs() < 1e-5)
            })
            .count();
        assert_eq!(matches, 1, "{:?} is not one closed-form branch", f.q);
    }
}

#[test]
fn redundant_tasks_give_at_most_eight_samples_one_per_sign_pattern() {
    for (id, task, q) in [
        (
            "panda",
            Task::FullPose,
            vec![0.1, -0.6, 0.2, -2.0, 0.1, 1.6, 0.5],
        ),
        ("metrover", Task::Position, vec![0.3, 1.0, 0.4, 0.5, 0.2]),
    ] {
        let robot = preset(id).unwrap();
        let target = tool_pose(&robot, &q);
        let found = distinct_solutions(&robot, &target, task, &IkSettings::default(), 60).unwrap();
        assert!(found.continuum, "{id}");
        assert!(
            found.solutions.len() >= 2,
            "{id}: {}",
            found.solutions.len()
        );
        assert!(found.solutions.len() <= MAX_CONTINUUM_SAMPLES);
        let tol = 1e-6 / robot.length_unit.in_metres();
        for (i, f) in found.solutions.iter().enumerate() {
            common::assert_reaches(id, &robot, &f.q, &target, task, tol, 1e-6);
            assert_eq!(f.signs, configuration_signs(&robot, &f.q));
            assert_eq!(f.signs.len(), robot.dof() - 2);
            for g in &found.solutions[i + 1..] {
                assert_ne!(f.signs, g.signs, "{id}: two samples with one sign pattern");
            }
        }
    }
}
