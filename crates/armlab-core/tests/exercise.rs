//! docs/kinematics.md §15: the DH-table exercise grades by kinematics (any equivalent table
//! is right), names the first joint that goes wrong and how, and draws mystery arms.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

use armlab_text::Sentence;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::convention::convert;
use armlab_core::exercise::{
    Diagnosis, LengthField, MYSTERY_JOINTS, Verdict, Where, check_table, mystery_arm,
};
use armlab_core::{Convention, JointKind, preset};
use armlab_text::Lang;
use std::f64::consts::FRAC_PI_2;

#[test]
fn equivalent_tables_are_correct_in_either_convention() {
    let ur10 = preset("ur10").unwrap();
    let standard = preset("ur10-standard").unwrap();
    assert_eq!(check_table(&ur10, &standard), Verdict::Correct);
    assert_eq!(check_table(&standard, &ur10), Verdict::Correct);
    for (id, robot) in common::all_presets() {
        assert_eq!(check_table(&robot, &robot), Verdict::Correct, "{id}");
        let other = match robot.convention {
            Convention::Standard => Convention::Modified,
            Convention::Modified => Convention::Standard,
        };
        assert_eq!(
            check_table(&robot, &convert(&robot, other)),
            Verdict::Correct,
            "{id}"
        );
    }
}

#[test]
fn a_twist_of_the_wrong_sign_is_named() {
    let puma = preset("puma560").unwrap();
    let mut student = puma.clone();
    student.joints[2].dh.alpha = -student.joints[2].dh.alpha;
    // Standard DH: row 3's α turns z_3, the axis of joint 4.
    assert_eq!(
        check_table(&puma, &student),
        Verdict::Wrong(Diagnosis::TwistSign {
            at: Where::Joint(4),
            row: 3
        })
    );
}

#[test]
fn a_missing_offset_is_named() {
    let standard = preset("ur10-standard").unwrap();
    let mut student = standard.clone();
    student.joints[1].dh.theta = 0.0; // the published table has 180° here
    match check_table(&standard, &student) {
        Verdict::Wrong(Diagnosis::MissingOffset { at, row, offset }) => {
            assert_eq!(at, Where::Joint(3));
            assert_eq!(row, 2);
            assert!((offset.abs() - std::f64::consts::PI).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
    let rrr = preset("rrr").unwrap();
    let mut student = rrr.clone();
    student.joints[1].dh.theta = -FRAC_PI_2;
    assert_eq!(
        check_table(&rrr, &student),
        Verdict::Wrong(Diagnosis::MissingOffset {
            at: Where::Joint(3),
            row: 2,
            offset: FRAC_PI_2
        })
    );
}

#[test]
fn a_length_in_the_wrong_row_is_named() {
    let rrr = preset("rrr").unwrap();
    let mut student = rrr.clone();
    // a2 = 222.1 written into row 3, a3 = 136.2 into row 2: swapped rows.
    student.joints[1].dh.a = 0.0;
    student.joints[0].dh.a = 222.1;
    assert_eq!(
        check_table(&rrr, &student),
        Verdict::Wrong(Diagnosis::LengthInWrongRow {
            at: Where::Joint(2),
            row: 1,
            field: LengthField::A,
            to_row: 2,
            to_field: LengthField::A
        })
    );
    // d of the base written as a.
    let mut student = rrr.clone();
    student.joints[0].dh.d = 0.0;
    student.joints[0].dh.a = 100.9;
    assert_eq!(
        check_table(&rrr, &student),
        Verdict::Wrong(Diagnosis::LengthInWrongRow {
            at: Where::Joint(2),
            row: 1,
            field: LengthField::A,
            to_row: 1,
            to_field: LengthField::D
        })
    );
}

#[test]
fn a_reversed_axis_is_named() {
    // Twisting the base frame by 180° about x reverses joint 2's axis in a planar arm.
    let planar = preset("planar-2r").unwrap();
    let mut student = planar.clone();
    student.joints[0].dh.alpha = std::f64::consts::PI;
    assert_eq!(
        check_table(&planar, &student),
        Verdict::Wrong(Diagnosis::AxisReversed { joint: 2 })
    );
}

#[test]
fn counts_and_kinds_are_checked_first() {
    let scara = preset("scara").unwrap();
    let mut fewer = scara.clone();
    fewer.joints.pop();
    assert_eq!(
        check_table(&scara, &fewer),
        Verdict::Wrong(Diagnosis::JointCount {
            expected: 4,
            found: 3
        })
    );
    let mut kind = scara.clone();
    kind.joints[2].kind = JointKind::Revolute;
    assert_eq!(
        check_table(&scara, &kind),
        Verdict::Wrong(Diagnosis::JointKind {
            joint: 3,
            expected: JointKind::Prismatic
        })
    );
}

#[test]
fn verdicts_read_as_sentences_in_both_languages() {
    let d = Verdict::Wrong(Diagnosis::TwistSign {
        at: Where::Joint(4),
        row: 3,
    });
    assert_eq!(
        d.sentence(Lang::En),
        "Joint 4's frame is the first to disagree: the twist α in row 3 has the wrong sign."
    );
    assert_eq!(
        d.sentence(Lang::Fi),
        "Nivelen 4 koordinaatisto poikkeaa ensimmäisenä: rivin 3 kiertymän α etumerkki on väärä."
    );
    let m = Verdict::Wrong(Diagnosis::MissingOffset {
        at: Where::Tool,
        row: 6,
        offset: -FRAC_PI_2,
    });
    assert!(
        m.sentence(Lang::En)
            .contains("row 6 is missing an offset of -90°")
    );
    assert!(Verdict::Correct.sentence(Lang::Fi).starts_with("Oikein"));
}

#[test]
fn mystery_arms_are_seeded_valid_and_gradable() {
    let mut counts = std::collections::BTreeSet::new();
    let mut conventions = std::collections::BTreeSet::new();
    for seed in 0..40 {
        let arm = mystery_arm(seed);
        assert_eq!(arm, mystery_arm(seed), "seed {seed} is reproducible");
        let arm = arm.validated().unwrap();
        assert!((MYSTERY_JOINTS.0..=MYSTERY_JOINTS.1).contains(&arm.dof()));
        counts.insert(arm.dof());
        conventions.insert(arm.convention.as_str());
        assert_eq!(check_table(&arm, &arm), Verdict::Correct);
        // Its table in the other convention is an equally right answer.
        let other = match arm.convention {
            Convention::Standard => Convention::Modified,
            Convention::Modified => Convention::Standard,
        };
        assert_eq!(check_table(&arm, &convert(&arm, other)), Verdict::Correct);
    }
    assert_eq!(counts.len(), 5, "every joint count from 2 to 6: {counts:?}");
    assert_eq!(conventions.len(), 2);
    assert_ne!(mystery_arm(1), mystery_arm(2));
}
