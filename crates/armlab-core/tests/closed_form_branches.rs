//! Closed forms of the SCARA and the spherical-wrist arms (Puma 560, Stanford arm) over
//! random poses, and branch labels: the same arm in both DH conventions gets the same
//! labels, every listed solution carries its own label, and a drag keeps its branch
//! until that branch vanishes (docs/kinematics.md §9.4–9.6).

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::ik::joint_distance;
use armlab_core::{
    Branch, ClosedFormFamily, Elbow, ForwardKinematics, IkMethod, IkSettings, Robot, Shoulder,
    Task, Wrist, branch_of, branch_step, closed_form_family, closed_form_solutions, follow_branch,
    preset, solve, tool_pose,
};
use nalgebra::{IsometryMatrix3, Translation3};

/// The largest entry difference of two poses, translation divided by `length`.
fn pose_diff(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>, length: f64) -> f64 {
    let dt = (a.translation.vector - b.translation.vector).abs().max() / length;
    let dr = (a.rotation.matrix() - b.rotation.matrix()).abs().max();
    dt.max(dr)
}

/// The largest joint difference (wrapped for revolute joints).
fn joint_gap(robot: &Robot, a: &[f64], b: &[f64]) -> f64 {
    robot
        .joints
        .iter()
        .zip(a.iter().zip(b))
        .map(|(j, (x, y))| j.change(*x, *y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn scara_puma_and_stanford_round_trip_every_branch() {
    for (id, family, most) in [
        ("scara", ClosedFormFamily::Scara, 2),
        ("puma560", ClosedFormFamily::SphericalWrist, 8),
        ("stanford", ClosedFormFamily::SphericalWrist, 4),
    ] {
        let robot = preset(id).unwrap();
        assert_eq!(closed_form_family(&robot), Some(family), "{id}");
        let mut rng = common::rng(21);
        let mut counts = vec![0usize; most + 1];
        let trials = 300;
        for _ in 0..trials {
            let q = rng.joint_vector(&robot);
            let seed = rng.joint_vector(&robot);
            let target = tool_pose(&robot, &q);
            let set = closed_form_solutions(&robot, &target, &seed).unwrap();
            assert!(!set.unreachable, "{id}: {q:?} flagged unreachable");
            assert!(set.solutions.len() <= most, "{id}: {}", set.solutions.len());
            counts[set.solutions.len()] += 1;
            for s in &set.solutions {
                let d = pose_diff(&tool_pose(&robot, &s.q), &target, robot.reach());
                assert!(d <= 1e-9, "{id}: {} = {:?} off by {d}", s.label(), s.q);
            }
            let found = set
                .solutions
                .iter()
                .map(|s| joint_gap(&robot, &s.q, &q))
                .fold(f64::INFINITY, f64::min);
            assert!(
                found <= 1e-6,
                "{id}: {q:?} not among the solutions ({found})"
            );
            // Branch labels are distinct within a set.
            for (i, a) in set.solutions.iter().enumerate() {
                for b in &set.solutions[i + 1..] {
                    assert_ne!(
                        a.branch,
                        b.branch,
                        "{id}: two solutions labelled {}",
                        a.label()
                    );
                }
            }
        }
        // The full count is the common case (the Stanford arm's boom keeps one root).
        assert!(counts[most] * 2 > trials, "{id}: counts {counts:?}");
    }
}

#[test]
fn the_closed_form_method_solves_the_new_families_through_the_solver() {
    for id in ["scara", "puma560", "stanford"] {
        let robot = preset(id).unwrap();
        let mut rng = common::rng(5);
        for task in [Task::FullPose, Task::Position] {
            for _ in 0..20 {
                let q = rng.joint_vector(&robot);
                let target = tool_pose(&robot, &q);
                let seed = rng.joint_vector(&robot);
                let r = solve(
                    &robot,
                    &target,
                    task,
                    &seed,
                    IkMethod::ClosedForm,
                    &IkSettings::default(),
                )
                .unwrap();
                assert!(r.success, "{id} {task:?}: {r:?}");
                common::assert_reaches(
                    id,
                    &robot,
                    &r.q,
                    &target,
                    task,
                    1e-6 / robot.length_unit.in_metres(),
                    1e-6,
                );
            }
        }
    }
}

#[test]
fn labels_are_data_the_same_in_both_ur10_conventions_and_match_branch_of() {
    let modified = preset("ur10").unwrap();
    let standard = preset("ur10-standard").unwrap();
    let mut rng = common::rng(8);
    for _ in 0..100 {
        let q = rng.joint_vector(&modified);
        let a = branch_of(&modified, &q).unwrap().unwrap();
        let b = branch_of(&standard, &q).unwrap().unwrap();
        assert_eq!(a, b, "{q:?}");
        assert!(a.shoulder.is_some() && a.elbow.is_some() && a.wrist.is_some());
        assert_eq!(Branch::from_id(&a.id()), Some(a));
        // Every listed solution is on the branch it is labelled with.
        let set = closed_form_solutions(&modified, &tool_pose(&modified, &q), &q).unwrap();
        for s in &set.solutions {
            assert_eq!(
                branch_of(&modified, &s.q).unwrap(),
                Some(s.branch),
                "{}",
                s.label()
            );
        }
    }
    // By hand: the wrist flip is the sign of sin θ5, the shoulder the side of the wrist.
    let q = [0.3, -1.0, 1.2, 0.4, 0.9, -0.7];
    let b = branch_of(&modified, &q).unwrap().unwrap();
    assert_eq!(b.wrist, Some(Wrist::NotFlipped));
    let q_flip = [0.3, -1.0, 1.2, 0.4, -0.9, -0.7];
    assert_eq!(
        branch_of(&modified, &q_flip).unwrap().unwrap().wrist,
        Some(Wrist::Flipped)
    );
    // The RRR reaching forward with the elbow above the line shoulder → tool: right, up.
    let rrr = preset("rrr").unwrap();
    let b = branch_of(&rrr, &[0.0, 0.6, -0.9]).unwrap().unwrap();
    assert_eq!(
        (b.shoulder, b.elbow),
        (Some(Shoulder::Right), Some(Elbow::Up))
    );
    let fk = ForwardKinematics::new(&rrr, &[0.0, 0.6, -0.9]).unwrap();
    let (elbow, tool) = (fk.joint_origins[2], fk.tool_position());
    // The elbow lies above the straight line from the shoulder (0, 0, L1) to the tool.
    let shoulder_z = 100.9;
    let line_z = shoulder_z + (tool.z - shoulder_z) * elbow.x / tool.x;
    assert!(elbow.z > line_z, "{elbow:?} {tool:?}");
    // The planar 2R: θ2 = −acos(c2) is elbow up (SPEC §1.3).
    let planar = preset("planar-2r").unwrap();
    assert_eq!(
        branch_of(&planar, &[0.3, -1.0]).unwrap().unwrap().elbow,
        Some(Elbow::Up)
    );
    assert_eq!(
        branch_of(&planar, &[0.3, 1.0]).unwrap().unwrap().elbow,
        Some(Elbow::Down)
    );
    // No closed form, no branch.
    assert_eq!(
        branch_of(
            &preset("panda").unwrap(),
            &[0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0]
        )
        .unwrap(),
        None
    );
}

#[test]
fn a_drag_keeps_its_branch_and_says_when_it_vanishes() {
    let robot = preset("ur10").unwrap();
    // Along a small circle the branch persists: every step keeps it and moves little.
    let mut q = vec![0.3, -1.0, 1.2, 0.4, 0.9, -0.7];
    let start = tool_pose(&robot, &q);
    let branch = branch_of(&robot, &q).unwrap().unwrap();
    let previous = branch;
    for k in 0..=60 {
        let a = k as f64 / 60.0 * std::f64::consts::TAU;
        let target = Translation3::new(80.0 * a.cos() - 80.0, 80.0 * a.sin(), 0.0) * start;
        let step = branch_step(&robot, &q, &previous, &target, Task::FullPose).unwrap();
        assert!(!step.vanished, "step {k}");
        assert_eq!(step.branch, branch);
        assert_eq!(step.set.solutions[step.index].branch, branch);
        assert!(joint_gap(&robot, step.q(), &q) < 0.2, "step {k} jumps");
        q = step.q().to_vec();
    }
    // At a stretched elbow (θ3 = 0) both elbows of its shoulder and wrist coincide:
    // asking for either keeps it. Pulled 5 mm further along the stretched arm, that
    // shoulder and wrist cannot reach: the branch vanishes, and the nearest exact
    // solution is taken.
    let q0 = [0.3, -1.0, 0.0, 0.4, 0.9, -0.7];
    let t0 = tool_pose(&robot, &q0);
    let set0 = closed_form_solutions(&robot, &t0, &q0).unwrap();
    let own = branch_of(&robot, &q0).unwrap().unwrap();
    for elbow in [Elbow::Up, Elbow::Down] {
        let asked = Branch {
            elbow: Some(elbow),
            ..own
        };
        let choice = follow_branch(&robot, &set0, &asked, &q0).unwrap();
        assert!(!choice.vanished);
        assert!(joint_gap(&robot, &set0.solutions[choice.index].q, &q0) < 1e-6);
    }
    let fk = ForwardKinematics::new(&robot, &q0).unwrap();
    let along = (fk.joint_origins[3] - fk.joint_origins[1]).normalize();
    let t1 = Translation3::from(along * 5.0) * t0;
    let set1 = closed_form_solutions(&robot, &t1, &q0).unwrap();
    assert!(!set1.unreachable, "other branches still reach");
    assert!(
        set1.solutions
            .iter()
            .all(|s| s.branch.shoulder != own.shoulder || s.branch.wrist != own.wrist)
    );
    let choice = follow_branch(&robot, &set1, &own, &q0).unwrap();
    assert!(choice.vanished);
    let nearest = set1
        .solutions
        .iter()
        .map(|s| joint_distance(&robot, &q0, &s.q))
        .fold(f64::INFINITY, f64::min);
    assert_eq!(
        joint_distance(&robot, &q0, &set1.solutions[choice.index].q),
        nearest
    );
    let step = branch_step(&robot, &q0, &own, &t1, Task::FullPose).unwrap();
    assert!(step.vanished && step.branch == step.set.solutions[step.index].branch);
}
