//! Closed forms at their singular poses (docs/kinematics.md §9): every solution listed
//! reproduces its target (FK to 1e−9 of the reach and 1e−9 rad), and where the target
//! leaves joints free the solution names them. Poses of each kind are constructed here
//! from joint values (θ3 = 0, θ5 = 0 or π, the wrist point on the shoulder's singular
//! cylinder found by bisection) and the seed is always somewhere else.

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_core::ik::joint_distance;
use armlab_core::{
    ClosedFormSet, ClosedFormSolution, IkMethod, IkSettings, Robot, Task, closed_form_solutions,
    preset, solve, tool_pose,
};
use nalgebra::{IsometryMatrix3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI};

/// The largest entry difference of two poses, translation divided by `length`.
fn pose_diff(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>, length: f64) -> f64 {
    let dt = (a.translation.vector - b.translation.vector).abs().max() / length;
    let dr = (a.rotation.matrix() - b.rotation.matrix()).abs().max();
    dt.max(dr)
}

/// Solves the closed form of FK(`q`) from `seed` and checks that the target is found
/// reachable, singular, and reproduced by every listed solution; returns the set.
fn check(what: &str, robot: &Robot, q: &[f64], seed: &[f64], position_only: bool) -> ClosedFormSet {
    let target = tool_pose(robot, q);
    let set = closed_form_solutions(robot, &target, seed).expect("a closed form");
    assert!(
        !set.unreachable,
        "{what}: reachable target flagged unreachable"
    );
    assert!(set.singular, "{what}: singular pose not flagged");
    assert!(!set.solutions.is_empty(), "{what}");
    let reach = robot.reach();
    for s in &set.solutions {
        assert!(s.exact, "{what}: {} not exact", s.label());
        let got = tool_pose(robot, &s.q);
        let d = if position_only {
            (got.translation.vector - target.translation.vector)
                .abs()
                .max()
                / reach
        } else {
            pose_diff(&got, &target, reach)
        };
        assert!(
            d <= 1e-9,
            "{what}: solution {} = {:?} misses the target by {d} (relative)",
            s.label(),
            s.q
        );
    }
    set
}

/// The listed solution nearest `q` (wrapped distance).
fn nearest<'a>(robot: &Robot, set: &'a ClosedFormSet, q: &[f64]) -> &'a ClosedFormSolution {
    set.solutions
        .iter()
        .min_by(|a, b| joint_distance(robot, q, &a.q).total_cmp(&joint_distance(robot, q, &b.q)))
        .expect("solutions listed")
}

/// The wrist point o5 = p − d6·z6 of a UR10 (d6 = 92.2 mm) against the arm plane's x axis
/// (cos θ1, sin θ1, 0): zero on the shoulder singularity.
fn ur_shoulder_gap(robot: &Robot, q: &[f64]) -> f64 {
    let t = tool_pose(robot, q);
    let z6 = t.rotation.matrix().column(2).into_owned();
    let o5 = t.translation.vector - z6 * 92.2;
    o5.dot(&Vector3::new(q[0].cos(), q[0].sin(), 0.0))
}

/// The spherical wrist's centre (d6 = 0 for the Puma and the Stanford arm: the tool
/// point) against the arm plane's x axis.
fn wrist_centre_gap(robot: &Robot, q: &[f64]) -> f64 {
    let p = tool_pose(robot, q).translation.vector;
    p.dot(&Vector3::new(q[0].cos(), q[0].sin(), 0.0))
}

/// `q` with joint `k` moved so that `gap(q) = 0`, by a scan for a sign change over
/// [lo, hi] and bisection.
fn root_in_joint(
    robot: &Robot,
    q: &[f64],
    k: usize,
    lo: f64,
    hi: f64,
    gap: fn(&Robot, &[f64]) -> f64,
) -> Vec<f64> {
    let mut q = q.to_vec();
    let f = |q: &mut Vec<f64>, v: f64| {
        q[k] = v;
        gap(robot, q)
    };
    let steps = 720;
    let mut a = lo;
    let mut fa = f(&mut q, a);
    for i in 1..=steps {
        let b = lo + (hi - lo) * i as f64 / steps as f64;
        let fb = f(&mut q, b);
        if fa.signum() != fb.signum() {
            let (mut x0, mut x1, mut f0) = (a, b, fa);
            for _ in 0..200 {
                let m = 0.5 * (x0 + x1);
                let fm = f(&mut q, m);
                if fm.signum() == f0.signum() {
                    x0 = m;
                    f0 = fm;
                } else {
                    x1 = m;
                }
            }
            q[k] = 0.5 * (x0 + x1);
            return q;
        }
        a = b;
        fa = fb;
    }
    panic!("no sign change of the gap in joint {k}");
}

#[test]
fn ur10_elbow_wrist_and_both_reproduce_the_target_from_a_far_seed() {
    let seed = [0.1, -0.5, 0.5, 0.2, 0.3, 1.5];
    for id in ["ur10", "ur10-standard"] {
        let robot = preset(id).unwrap();
        // Elbow stretched: on the pose's own shoulder and wrist both elbows coincide
        // (the other shoulder and wrist put the elbow elsewhere).
        let q = [0.3, -1.0, 0.0, 0.4, 0.9, -0.7];
        let set = check(&format!("{id} θ3 = 0"), &robot, &q, &seed, false);
        let own = nearest(&robot, &set, &q);
        assert!(
            own.coincident.len() == 1 && own.q[2].abs() < 1e-6,
            "{id}: {own:?}"
        );
        assert!(set.solutions.iter().all(|s| s.free_joints.is_empty()));
        // Wrist singular, θ5 = 0 and π: on the pose's shoulder one wrist, θ6 free at the
        // seed's value, two elbows.
        for t5 in [0.0, PI] {
            let what = format!("{id} θ5 = {t5}");
            let q = [0.3, -1.0, 1.2, 0.4, t5, -0.7];
            let set = check(&what, &robot, &q, &seed, false);
            let free: Vec<_> = set
                .solutions
                .iter()
                .filter(|s| !s.free_joints.is_empty())
                .collect();
            assert_eq!(free.len(), 2, "{what}");
            for s in free {
                assert_eq!(s.free_joints, vec![5], "{what}");
                assert!((s.q[5] - seed[5]).abs() < 1e-12, "{what}: θ6 = {}", s.q[5]);
                assert_eq!(s.coincident.len(), 1, "{what}: both wrists coincide");
            }
        }
        // Both: θ3 = 0 and θ5 = 0 or π (the case: tens of mm off before). With
        // θ6 at the seed's value the elbow cannot reach, so θ6 moves to the nearest
        // value where it does.
        for t5 in [0.0, PI] {
            for q in [
                [0.3, -1.0, 0.0, 0.4, t5, -0.7],
                [0.0, 0.0, 0.0, 0.0, t5, 0.0],
            ] {
                let what = format!("{id} θ3 = 0, θ5 = {t5}, q = {q:?}");
                let set = check(&what, &robot, &q, &seed, false);
                let own = nearest(&robot, &set, &q);
                assert_eq!(own.free_joints, vec![5], "{what}");
                // Seeds with θ6 just either side of the pose's: turning θ6 (and with it
                // θ2 + θ3 + θ4) one way folds the elbow, the other way would need a
                // longer arm. One seed keeps its θ6; for the other θ6 moves back to
                // the nearest value where the elbow reaches: the pose's own, stretched.
                let mut moved = 0;
                for delta in [0.01, -0.01] {
                    let mut near_seed = q.to_vec();
                    near_seed[5] += delta;
                    let set = check(&what, &robot, &q, &near_seed, false);
                    let own = nearest(&robot, &set, &q);
                    if (own.q[5] - near_seed[5]).abs() > 1e-12 {
                        moved += 1;
                        assert!((own.q[5] - q[5]).abs() < 1e-6, "{what}: {own:?}");
                        assert!(own.q[2].abs() < 1e-6, "{what}: elbow not stretched {own:?}");
                    }
                }
                assert_eq!(moved, 1, "{what}");
                // The solver's closed form succeeds on it too.
                let r = solve(
                    &robot,
                    &tool_pose(&robot, &q),
                    Task::FullPose,
                    &seed,
                    IkMethod::ClosedForm,
                    &IkSettings::default(),
                )
                .unwrap();
                assert!(r.success && r.singular, "{what}: {r:?}");
            }
        }
    }
}

#[test]
fn ur10_shoulder_singularity_alone_and_with_elbow_and_wrist() {
    let seed = [1.0, -0.5, 0.5, 0.2, 0.3, 1.5];
    for id in ["ur10", "ur10-standard"] {
        let robot = preset(id).unwrap();
        for (name, base) in [
            ("shoulder", [0.3, 0.0, 0.9, 0.4, 0.8, -0.7]),
            ("shoulder + elbow", [0.3, 0.0, 0.0, 0.4, 0.8, -0.7]),
            ("shoulder + wrist", [0.3, 0.0, 0.9, 0.4, 0.0, -0.7]),
            ("shoulder + elbow + wrist", [0.3, 0.0, 0.0, 0.4, 0.0, -0.7]),
        ] {
            let q = root_in_joint(&robot, &base, 1, -PI, PI, ur_shoulder_gap);
            assert!(ur_shoulder_gap(&robot, &q).abs() < 1e-9);
            let what = format!("{id} {name} at {q:?}");
            let set = check(&what, &robot, &q, &seed, false);
            // The two base angles coincide: at most 4 distinct solutions.
            assert!(set.solutions.len() <= 4, "{what}: {:#?}", set.solutions);
            assert!(
                set.solutions.iter().any(|s| !s.coincident.is_empty()),
                "{what}: no coinciding branches recorded"
            );
        }
    }
}

#[test]
fn rrr_base_axis_and_elbow_stretched_or_folded_reproduce() {
    let robot = preset("rrr").unwrap();
    let seed = [-1.0, 0.4, -0.3];
    // Tool on the base axis: L2 c2 + L3 c23 = 0; θ1 free at the seed's value.
    let t2: f64 = 1.2;
    let t3 = (-222.1 * t2.cos() / 136.2).acos() - t2;
    let set = check("RRR base axis", &robot, &[0.7, t2, t3], &seed, true);
    for s in &set.solutions {
        assert_eq!(s.free_joints, vec![0]);
    }
    assert!(
        set.solutions
            .iter()
            .any(|s| (s.q[0] - seed[0]).abs() < 1e-12)
    );
    // Elbow stretched and folded: one elbow per shoulder.
    for t3 in [0.0, PI] {
        let what = format!("RRR θ3 = {t3}");
        let set = check(&what, &robot, &[0.7, 0.5, t3], &seed, true);
        assert_eq!(set.solutions.len(), 2, "{what}");
        assert!(
            set.solutions.iter().all(|s| s.coincident.len() == 1),
            "{what}"
        );
    }
    // Both: stretched straight up (θ2 = π/2, θ3 = 0) is on the base axis too.
    let set = check(
        "RRR straight up",
        &robot,
        &[0.7, FRAC_PI_2, 0.0],
        &seed,
        true,
    );
    assert!(set.solutions.iter().all(|s| s.free_joints == vec![0]));
}

#[test]
fn planar_2r_stretched_and_folded_reproduce_from_any_seed() {
    let robot = preset("planar-2r").unwrap();
    for q in [[0.4, 0.0], [0.4, PI], [-2.5, 0.0], [2.0, PI]] {
        for seed in [[0.0, 0.0], [1.0, -2.0], [-3.0, 3.0]] {
            let set = check(&format!("2R {q:?} from {seed:?}"), &robot, &q, &seed, true);
            assert_eq!(set.solutions.len(), 1);
            assert_eq!(set.solutions[0].coincident.len(), 1);
        }
    }
}

#[test]
fn puma_and_stanford_wrist_shoulder_and_elbow_singularities_reproduce() {
    let puma = preset("puma560").unwrap();
    let seed = [0.2, 0.9, -2.5, 0.3, 0.6, -0.4];
    // Wrist: θ5 = 0, θ4 free at the seed's value.
    let q = [0.3, 0.7, -2.8, 0.5, 0.0, 0.2];
    let set = check("Puma θ5 = 0", &puma, &q, &seed, false);
    let own = nearest(&puma, &set, &q);
    assert_eq!(own.free_joints, vec![3]);
    assert!((own.q[3] - seed[3]).abs() < 1e-12);
    // Elbow stretched: θ3 + β = 0 with β = atan2(−sin α3·d4, a3) = atan2(0.4318, 0.0203).
    let beta = 0.4318_f64.atan2(0.0203);
    let set = check(
        "Puma elbow",
        &puma,
        &[0.3, 0.7, -beta, 0.5, 0.8, 0.2],
        &seed,
        false,
    );
    assert!(set.solutions.len() <= 4);
    // Shoulder: the wrist centre on the singular cylinder, alone and with the wrist.
    for t5 in [0.8, 0.0] {
        let q = root_in_joint(
            &puma,
            &[0.3, 0.0, -2.8, 0.5, t5, 0.2],
            1,
            -PI,
            PI,
            wrist_centre_gap,
        );
        check(&format!("Puma shoulder θ5 = {t5}"), &puma, &q, &seed, false);
    }
    let stanford = preset("stanford").unwrap();
    let seed = [0.2, 0.4, 0.6, 0.3, 0.6, -0.4];
    let q = [0.3, 0.7, 0.8, 0.5, 0.0, 0.2];
    let set = check("Stanford θ5 = 0", &stanford, &q, &seed, false);
    let own = nearest(&stanford, &set, &q);
    assert_eq!(own.free_joints, vec![3]);
    assert!((own.q[3] - seed[3]).abs() < 1e-12);
    for t5 in [0.8, 0.0] {
        let q = root_in_joint(
            &stanford,
            &[0.3, 0.0, 0.8, 0.5, t5, 0.2],
            1,
            -PI,
            PI,
            wrist_centre_gap,
        );
        check(
            &format!("Stanford shoulder θ5 = {t5}"),
            &stanford,
            &q,
            &seed,
            false,
        );
    }
}

#[test]
fn scara_stretched_and_folded_reproduce() {
    let robot = preset("scara").unwrap();
    let seed = [0.3, -0.5, 0.1, 0.2];
    for q in [[0.4, 0.0, 0.1, 0.5], [0.4, PI, 0.05, -1.0]] {
        let set = check(&format!("SCARA {q:?}"), &robot, &q, &seed, false);
        assert_eq!(set.solutions.len(), 1);
    }
}
