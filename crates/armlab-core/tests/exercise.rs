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
            row: 3,
            found: student.joints[2].dh.alpha
        })
    );
}

#[test]
fn a_missing_offset_is_named() {
    let standard = preset("ur10-standard").unwrap();
    let mut student = standard.clone();
    student.joints[1].dh.theta = 0.0; // the published table has 180° here
    match check_table(&standard, &student) {
        Verdict::Wrong(Diagnosis::MissingOffset {
            at, row, offset, ..
        }) => {
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
            offset: FRAC_PI_2,
            found: -FRAC_PI_2
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
        found: FRAC_PI_2,
    });
    assert_eq!(
        d.sentence(Lang::En),
        "Joint 4's frame is the first to disagree: the twist α in row 3 has the wrong sign; \
         change it from 90° to -90°."
    );
    assert_eq!(
        d.sentence(Lang::Fi),
        "Nivelen 4 koordinaatisto poikkeaa ensimmäisenä: rivin 3 kiertymän α etumerkki on \
         väärä; muuta se arvosta 90° arvoon -90°."
    );
    // A student who typed 90° where the robot has 0° is told both numbers.
    let m = Verdict::Wrong(Diagnosis::MissingOffset {
        at: Where::Tool,
        row: 2,
        offset: -FRAC_PI_2,
        found: FRAC_PI_2,
    });
    assert_eq!(
        m.sentence(Lang::En),
        "Every joint axis is right but the tool frame disagrees: change θ in row 2 from 90° \
         to 0°."
    );
    let wrapped = Verdict::Wrong(Diagnosis::MissingOffset {
        at: Where::Joint(3),
        row: 1,
        offset: std::f64::consts::PI,
        found: FRAC_PI_2,
    });
    assert!(
        wrapped.sentence(Lang::En).ends_with("from 90° to -90°."),
        "{}",
        wrapped.sentence(Lang::En)
    );
    assert!(Verdict::Correct.sentence(Lang::Fi).starts_with("Oikein"));
}

#[test]
fn length_sentences_say_what_to_change_from_what_to_what() {
    let v = Verdict::Wrong(Diagnosis::LengthValue {
        at: Where::Joint(2),
        row: 1,
        field: LengthField::D,
        found: 120.0,
        expected: 100.90000000001,
    });
    assert_eq!(
        v.sentence(Lang::En),
        "Joint 2's frame is the first to disagree: change d in row 1 from 120 to 100.9."
    );
    assert_eq!(
        v.sentence(Lang::Fi),
        "Nivelen 2 koordinaatisto poikkeaa ensimmäisenä: muuta rivin 1 d arvosta 120 arvoon \
         100.9."
    );
    let s = Verdict::Wrong(Diagnosis::LengthSign {
        at: Where::Joint(2),
        row: 1,
        field: LengthField::D,
        found: -100.9,
    });
    assert!(
        s.sentence(Lang::En)
            .ends_with("change it from -100.9 to 100.9.")
    );
}

/// The RRR's table with one cell changed.
fn rrr_with(edit: impl Fn(&mut armlab_core::Robot)) -> Verdict {
    let rrr = preset("rrr").expect("the RRR preset");
    let mut student = rrr.clone();
    edit(&mut student);
    check_table(&rrr, &student)
}

/// The length a [`Diagnosis::LengthValue`] asks for, after checking the rest of it.
fn asked_length(verdict: Verdict, at: Where, row: usize, field: LengthField, found: f64) -> f64 {
    match verdict {
        Verdict::Wrong(Diagnosis::LengthValue {
            at: a,
            row: r,
            field: f,
            found: v,
            expected,
        }) if (a, r, f) == (at, row, field) && v == found => expected,
        other => panic!("{other:?}"),
    }
}

#[test]
fn one_wrong_length_is_named_with_the_value_it_needs() {
    // d1 = 100.9 typed as 120 or left at 0: joint 2's axis is the first to move.
    for typed in [120.0, 0.0, 100.8] {
        let v = rrr_with(|r| r.joints[0].dh.d = typed);
        let expected = asked_length(v, Where::Joint(2), 1, LengthField::D, typed);
        assert!((expected - 100.9).abs() < 1e-6, "{typed}: {expected}");
    }
    // a2 = 222.1 typed as 200, or the near miss 222.0: joint 3's axis moves.
    for typed in [200.0, 222.0] {
        let v = rrr_with(|r| r.joints[1].dh.a = typed);
        let expected = asked_length(v, Where::Joint(3), 2, LengthField::A, typed);
        assert!((expected - 222.1).abs() < 1e-6, "{typed}: {expected}");
    }
    // a3 moves only the tool.
    let v = rrr_with(|r| r.joints[2].dh.a = 136.0);
    let expected = asked_length(v, Where::Tool, 3, LengthField::A, 136.0);
    assert!((expected - 136.2).abs() < 1e-6);
    // A length the robot does not have: d2 = 30 must go back to 0.
    let v = rrr_with(|r| r.joints[1].dh.d = 30.0);
    match v {
        Verdict::Wrong(Diagnosis::LengthValue {
            row: 2,
            field: LengthField::D,
            expected,
            ..
        }) => assert!(expected.abs() < 1e-6, "{expected}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_length_of_the_wrong_sign_is_named() {
    assert_eq!(
        rrr_with(|r| r.joints[0].dh.d = -100.9),
        Verdict::Wrong(Diagnosis::LengthSign {
            at: Where::Joint(2),
            row: 1,
            field: LengthField::D,
            found: -100.9
        })
    );
}

#[test]
fn two_wrong_cells_name_the_first_frame_or_the_tool() {
    // Two lengths of row 1 wrong at once: no one change explains joint 2's axis.
    assert_eq!(
        rrr_with(|r| {
            r.joints[0].dh.d = 120.0;
            r.joints[0].dh.a = 50.0;
        }),
        Verdict::Wrong(Diagnosis::FrameDisagrees { joint: 2 })
    );
    // Both lengths of the last row wrong: every axis is right, the tool is not.
    assert_eq!(
        rrr_with(|r| {
            r.joints[2].dh.a = 130.0;
            r.joints[2].dh.d = 10.0;
        }),
        Verdict::Wrong(Diagnosis::ToolDisagrees)
    );
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
