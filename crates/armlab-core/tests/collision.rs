//! The arm's parts and their collision check (docs/kinematics.md §20) on constructed
//! poses: a folded UR10 whose wrist touches its base, the floor (checked against the
//! parts' lowest points computed by hand), keep-out boxes, and the sizes the Metrover's
//! file gives.

#![cfg_attr(target_arch = "wasm32", allow(clippy::unwrap_used))]

use armlab_text::Sentence;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::collision::{CollisionChecker, KeepOut, Obstacle, TOUCH_TOLERANCE, body_ranks};
use armlab_core::parts::{Part, PartKind, PartShape, robot_parts};
use armlab_core::{ForwardKinematics, MotionError, Robot, Setting, preset};
use armlab_text::Lang;
use nalgebra::{Point3, Vector3};

fn parts_at(robot: &Robot, q: &[f64]) -> Vec<Part> {
    let fk = ForwardKinematics::new(robot, q).expect("a valid pose");
    robot_parts(robot, &fk)
}

/// The lowest z of a part shrunk by `shrink` on every side (as the check shrinks it,
/// never below half its size), by hand: a box's half extents projected on z, a
/// cylinder's half length along its axis plus its radius across it.
fn lowest_z(part: &Part, shrink: f64) -> f64 {
    let r = part.rotation.matrix();
    let h = part.size.map(|v| (v - 2.0 * shrink).max(0.5 * v)) * 0.5;
    let reach_z = match part.shape {
        PartShape::Box => (0..3).map(|k| r[(2, k)].abs() * h[k]).sum::<f64>(),
        PartShape::Cylinder => {
            let az = r[(2, 2)];
            az.abs() * h.z + h.x * (1.0 - az * az).max(0.0).sqrt()
        }
    };
    part.centre.z - reach_z
}

#[test]
fn every_preset_is_free_of_collisions_at_home() {
    for (id, robot) in common::all_presets() {
        let floor = id != "planar-2r";
        let mut checker = CollisionChecker::new(floor, vec![]).unwrap();
        let fk = ForwardKinematics::new(&robot, &robot.home()).unwrap();
        let report = checker.check(&robot, &fk);
        assert!(
            report.is_free(),
            "{id}: {:?}",
            armlab_text::contact_sentence(&report, checker.parts(), Lang::En)
        );
        assert_eq!(report.colliding.len(), checker.parts().len());
    }
}

#[test]
fn a_folded_ur10_touches_its_base_with_its_wrist() {
    let robot = preset("ur10").unwrap();
    // Upper arm level (θ2 = 0), elbow folded back by 150°: the forearm comes back over
    // the shoulder and the wrist comes down onto the base block.
    let mut q = robot.home();
    q[1] = 0.0;
    q[2] = (-150f64).to_radians();
    let mut checker = CollisionChecker::new(false, vec![]).unwrap();
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    let report = checker.check(&robot, &fk);
    let parts = checker.parts();
    let base_wrist: Vec<_> = report
        .contacts
        .iter()
        .filter_map(|c| match c.other {
            Obstacle::Part(j) if parts[c.part].kind == PartKind::Base => Some(parts[j].body),
            _ => None,
        })
        .collect();
    assert!(!base_wrist.is_empty(), "{:?}", report.contacts);
    assert!(
        base_wrist.iter().all(|b| *b >= 5),
        "the wrist (bodies 5 and 6) touches the base: {base_wrist:?}"
    );
    assert!(report.colliding[0]);
    let sentence = armlab_text::contact_sentence(&report, parts, Lang::En).unwrap();
    assert!(
        sentence.starts_with("Contact: the base touches"),
        "{sentence}"
    );
    let fi = armlab_text::contact_sentence(&report, parts, Lang::Fi).unwrap();
    assert!(fi.starts_with("Kosketus: jalusta ja"), "{fi}");
    // Unfolded by 40° the same arm is free.
    q[2] = (-110f64).to_radians();
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    assert!(checker.check(&robot, &fk).is_free());
}

#[test]
fn the_floor_is_touched_exactly_where_a_part_reaches_below_it() {
    let robot = preset("ur10").unwrap();
    let checker = CollisionChecker::new(true, vec![]).unwrap();
    let tolerance = TOUCH_TOLERANCE * robot.reach();
    let mut touched = 0;
    let mut free = 0;
    for q2 in (0..=180).step_by(30) {
        for q3 in (-150..=150).step_by(30) {
            let q = [
                0.3,
                (q2 as f64).to_radians(),
                (q3 as f64).to_radians(),
                0.5,
                1.2,
                0.0,
            ];
            let parts = parts_at(&robot, &q);
            let ranks = body_ranks(&parts);
            let report = checker.check_parts(&parts, tolerance);
            for (i, part) in parts.iter().enumerate() {
                let on_floor = report
                    .contacts
                    .iter()
                    .any(|c| c.part == i && c.other == Obstacle::Floor);
                if ranks[part.body] < 2 {
                    assert!(!on_floor);
                    continue;
                }
                // The shrunk part reaches below z = 0 by the hand formula.
                let low = lowest_z(part, tolerance);
                if low.abs() < 1e-6 {
                    continue; // exactly on the floor: either answer is right
                }
                assert_eq!(
                    on_floor,
                    low < 0.0,
                    "q2 {q2} q3 {q3} part {i} ({:?} of body {}), lowest z {low}",
                    part.kind,
                    part.body
                );
                if on_floor {
                    touched += 1;
                } else {
                    free += 1;
                }
            }
        }
    }
    assert!(touched > 20 && free > 20, "{touched} touching, {free} free");
}

#[test]
fn keep_out_boxes_stop_the_hand_and_bad_ones_get_typed_errors() {
    let robot = preset("ur10").unwrap();
    let q = robot.home();
    let fk = ForwardKinematics::new(&robot, &q).unwrap();
    let tool = fk.base_from_tool.translation.vector;
    let around = KeepOut::new(1, Point3::from(tool), Vector3::new(150.0, 150.0, 150.0)).unwrap();
    let away = KeepOut::new(
        2,
        Point3::new(-900.0, -900.0, 300.0),
        Vector3::new(200.0, 200.0, 600.0),
    )
    .unwrap();
    let mut checker = CollisionChecker::new(true, vec![away, around]).unwrap();
    let report = checker.check(&robot, &fk);
    assert!(!report.is_free());
    for c in &report.contacts {
        assert_eq!(c.other, Obstacle::KeepOut(1));
        assert!(checker.parts()[c.part].body >= 4, "the wrist and the hand");
    }
    let sentence = armlab_text::contact_sentence(&report, checker.parts(), Lang::En).unwrap();
    assert!(sentence.ends_with("touches keep-out box 2."), "{sentence}");
    let mut checker = CollisionChecker::new(true, vec![away]).unwrap();
    assert!(checker.check(&robot, &fk).is_free());

    assert_eq!(
        KeepOut::new(3, Point3::origin(), Vector3::new(1.0, -2.0, 1.0)),
        Err(MotionError::NotPositive {
            setting: Setting::KeepOut(3),
            value: -2.0
        })
    );
    let e = KeepOut::new(1, Point3::new(f64::NAN, 0.0, 0.0), Vector3::repeat(1.0)).unwrap_err();
    assert!(matches!(e, MotionError::NotFinite { .. }));
    assert_eq!(
        e.sentence(Lang::En),
        "Not a valid value for keep-out box 1: it must be a finite number, not NaN."
    );
    assert!(KeepOut::new(1, Point3::origin(), Vector3::repeat(1e7)).is_err());
}

#[test]
fn parts_follow_the_robot_file_and_the_frames() {
    // The Metrover's file gives the base block 600 × 300 × 340 mm, its top at z = 0.
    let robot = preset("metrover").unwrap();
    let parts = parts_at(&robot, &robot.home());
    let base = &parts[0];
    assert_eq!(base.kind, PartKind::Base);
    assert_eq!(base.size, Vector3::new(600.0, 300.0, 340.0));
    assert!((base.centre.z + 170.0).abs() < 1e-9);
    // One housing per joint at its origin, one hand (flange, palm, two fingers).
    let housings = parts.iter().filter(|p| p.kind == PartKind::Housing).count();
    assert_eq!(housings, robot.dof());
    let hand: Vec<_> = parts.iter().filter(|p| p.body == robot.dof()).collect();
    assert!(hand.iter().filter(|p| p.kind == PartKind::Finger).count() == 2);
    // The fingers reach past the tool point: its position lies between them.
    let fk = ForwardKinematics::new(&robot, &robot.home()).unwrap();
    let tool = fk.base_from_tool.translation.vector;
    let fingers: Vec<_> = parts
        .iter()
        .filter(|p| p.kind == PartKind::Finger)
        .collect();
    let mid = (fingers[0].centre.coords + fingers[1].centre.coords) * 0.5;
    let along = fk.base_from_tool.rotation.matrix().column(2).into_owned();
    assert!((mid - tool).cross(&along).norm() < 1e-6);
}

/// The numbers the page sends to the collision module (`collision_wire`) give, checked on
/// the module's side, the same report as the direct check: the UR10 folded onto its base,
/// standing in a rotated keep-out box and reaching through the floor, and the Panda at 200
/// random poses with the floor and two boxes; bad lists get an error, not a panic.
#[test]
fn the_collision_module_encoding_answers_as_the_direct_check() {
    let mut tilted = KeepOut::new(
        1,
        Point3::new(400.0, 300.0, 500.0),
        Vector3::new(300.0, 200.0, 900.0),
    )
    .unwrap();
    tilted.rotation = nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.9);
    let low = KeepOut::new(
        2,
        Point3::new(-600.0, 0.0, 100.0),
        Vector3::new(300.0, 300.0, 200.0),
    )
    .unwrap();
    let (mut contacts, mut kinds) = (0, std::collections::HashSet::new());
    for (robot, q) in &wire_cases() {
        // The Panda is in metres: its boxes scaled down.
        let scale = if robot.length_unit.symbol() == "m" {
            1e-3
        } else {
            1.0
        };
        let boxes: Vec<KeepOut> = [tilted, low]
            .iter()
            .map(|k| KeepOut {
                centre: k.centre * scale,
                size: k.size * scale,
                rotation: k.rotation,
            })
            .collect();
        let direct = assert_wire_gives_the_direct_report(robot, q, &boxes);
        contacts += direct.contacts.len();
        kinds.extend(
            direct
                .contacts
                .iter()
                .map(|c| std::mem::discriminant(&c.other)),
        );
    }
    assert!(contacts > 10, "the cases touch: {contacts} contacts");
    assert_eq!(
        kinds.len(),
        3,
        "parts, the floor and a box are among the contacts"
    );
    assert_bad_wire_lists_get_errors(low);
}

/// The cases of the wire test: the UR10 folded onto its base and reaching through the
/// floor, and the Panda at 200 random poses.
fn wire_cases() -> Vec<(Robot, Vec<f64>)> {
    use armlab_core::rng::SplitMix64;
    let mut cases: Vec<(Robot, Vec<f64>)> = Vec::new();
    let ur10 = preset("ur10").expect("a preset");
    let mut folded = ur10.home();
    folded[1] = 0.0;
    folded[2] = (-150f64).to_radians();
    cases.push((ur10.clone(), folded));
    cases.push((ur10.clone(), vec![0.0, 0.6, 1.4, 0.0, 0.0, 0.0]));
    let panda = preset("panda").expect("a preset");
    let mut rng = SplitMix64::new(14);
    for _ in 0..200 {
        cases.push((panda.clone(), rng.joint_vector(&panda)));
    }
    cases
}

/// Checks that `robot` at `q` with `boxes` goes through the wire and back unchanged and
/// that the module's answer is the direct check's report; returns that report.
fn assert_wire_gives_the_direct_report(
    robot: &Robot,
    q: &[f64],
    boxes: &[KeepOut],
) -> armlab_core::collision::CollisionReport {
    use armlab_core::collision_wire::{
        check_request, decode_report, decode_request, encode_report, encode_request,
    };
    let parts = parts_at(robot, q);
    let tolerance = TOUCH_TOLERANCE * robot.reach();
    let direct = CollisionChecker::new(true, boxes.to_vec())
        .expect("a valid checker")
        .check_parts(&parts, tolerance);
    let request = encode_request(&parts, tolerance, true, boxes);
    let (back, tol_back, checker) = decode_request(&request).expect("a valid request");
    assert_eq!(back, parts, "the parts come back bit for bit");
    assert_eq!(tol_back, tolerance);
    assert_eq!(checker.keep_outs(), boxes);
    let answer = check_request(&request).expect("a valid request");
    assert_eq!(answer, encode_report(&direct));
    assert_eq!(
        decode_report(&answer, parts.len()).expect("a valid report"),
        direct
    );
    direct
}

/// Cut, non-finite and badly coded wire lists get their errors (the UR10 at home with
/// the box `low`).
fn assert_bad_wire_lists_get_errors(low: KeepOut) {
    use armlab_core::collision_wire::{WireError, decode_report, decode_request, encode_request};
    let ur10 = preset("ur10").expect("a preset");
    let parts = parts_at(&ur10, &ur10.home());
    let good = encode_request(&parts, 1.0, false, &[low]);
    assert!(matches!(
        decode_request(&good[..good.len() - 1]),
        Err(WireError::Length { .. })
    ));
    let mut bad = good.clone();
    bad[20] = f64::NAN;
    assert!(matches!(
        decode_request(&bad),
        Err(WireError::NotFinite { at: 20 })
    ));
    let mut bad = good.clone();
    bad[5 + 1] = 9.0; // the first part's kind
    assert!(matches!(
        decode_request(&bad),
        Err(WireError::Code { at: 6, .. })
    ));
    assert!(matches!(
        decode_request(&[2.0, 0.0, 0.0, 0.0, 0.0]),
        Err(WireError::Code { at: 0, .. })
    ));
    assert!(
        decode_report(&[0.0, 1.0, 7.0, 1.0, 0.0], 3).is_err(),
        "part 7 of 3"
    );
    assert!(
        decode_report(&[0.0, 2.0, 0.0, 1.0, 0.0], 3).is_err(),
        "two contacts announced, one given"
    );
}
