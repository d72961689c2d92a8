//! The DH exercise's verdict as a list of numbers (docs/kinematics.md §15): the page sends
//! the exercise's robot and the student's table to the lazily loaded module
//! (`check_table` of the JS API), which runs [`check_table`](super::exercise::check_table)
//! and answers with the verdict in this form. The page's own wasm thus never links the
//! check and its diagnosis. Numbers keep their f64 bits on the way, so the answer is the
//! one the page would have computed itself.
//!
//! A verdict, all f64: its kind, then that kind's fields in the order
//! [`Diagnosis`] declares them. A [`Where`] is the joint's number, or 0 for the tool; a
//! [`LengthField`] 0 for a, 1 for d; a [`JointKind`] 0 revolute, 1 prismatic; a row or
//! joint its number from 1, as in the table.
//!
//! | kind | what | fields |
//! |---|---|---|
//! | 0 | correct | |
//! | 1 | [`Diagnosis::JointCount`] | expected, found |
//! | 2 | [`Diagnosis::JointKind`] | joint, expected |
//! | 3 | [`Diagnosis::AxisReversed`] | joint |
//! | 4 | [`Diagnosis::TwistSign`] | at, row, found |
//! | 5 | [`Diagnosis::MissingOffset`] | at, row, offset, found |
//! | 6 | [`Diagnosis::LengthInWrongRow`] | at, row, field, to_row, to_field |
//! | 7 | [`Diagnosis::LengthSign`] | at, row, field, found |
//! | 8 | [`Diagnosis::LengthValue`] | at, row, field, found, expected |
//! | 9 | [`Diagnosis::FrameDisagrees`] | joint |
//! | 10 | [`Diagnosis::ToolDisagrees`] | |

use super::exercise::{Diagnosis, LengthField, Verdict, Where};
use super::robot::JointKind;

/// `verdict` as numbers (the table above).
pub fn encode_verdict(verdict: &Verdict) -> Vec<f64> {
    let at = |w: &Where| match w {
        Where::Joint(j) => *j as f64,
        Where::Tool => 0.0,
    };
    let field = |f: &LengthField| match f {
        LengthField::A => 0.0,
        LengthField::D => 1.0,
    };
    let n = |v: &usize| *v as f64;
    let Verdict::Wrong(diagnosis) = verdict else {
        return vec![0.0];
    };
    match diagnosis {
        Diagnosis::JointCount { expected, found } => vec![1.0, n(expected), n(found)],
        Diagnosis::JointKind { joint, expected } => {
            let kind = match expected {
                JointKind::Revolute => 0.0,
                JointKind::Prismatic => 1.0,
            };
            vec![2.0, n(joint), kind]
        }
        Diagnosis::AxisReversed { joint } => vec![3.0, n(joint)],
        Diagnosis::TwistSign { at: w, row, found } => vec![4.0, at(w), n(row), *found],
        Diagnosis::MissingOffset {
            at: w,
            row,
            offset,
            found,
        } => vec![5.0, at(w), n(row), *offset, *found],
        Diagnosis::LengthInWrongRow {
            at: w,
            row,
            field: f,
            to_row,
            to_field,
        } => vec![6.0, at(w), n(row), field(f), n(to_row), field(to_field)],
        Diagnosis::LengthSign {
            at: w,
            row,
            field: f,
            found,
        } => vec![7.0, at(w), n(row), field(f), *found],
        Diagnosis::LengthValue {
            at: w,
            row,
            field: f,
            found,
            expected,
        } => vec![8.0, at(w), n(row), field(f), *found, *expected],
        Diagnosis::FrameDisagrees { joint } => vec![9.0, n(joint)],
        Diagnosis::ToolDisagrees => vec![10.0],
    }
}

/// The verdict `numbers` encode ([`encode_verdict`]); `None` for numbers that encode none
/// (an unknown kind, a field that is not a whole number or a code, too few or too many).
pub fn decode_verdict(numbers: &[f64]) -> Option<Verdict> {
    let (&kind, fields) = numbers.split_first()?;
    if kind.fract() != 0.0 || !(0.0..=10.0).contains(&kind) {
        return None;
    }
    let verdict = match kind as u8 {
        0 => Verdict::Correct,
        kind => Verdict::Wrong(decode_diagnosis(kind, &Fields(fields))?),
    };
    // As many numbers as the kind has fields, no more.
    (encode_verdict(&verdict).len() == numbers.len()).then_some(verdict)
}

/// A verdict's fields, read as the table above says.
struct Fields<'a>(&'a [f64]);

impl Fields<'_> {
    fn real(&self, i: usize) -> Option<f64> {
        self.0.get(i).copied()
    }

    fn n(&self, i: usize) -> Option<usize> {
        let v = self.real(i)?;
        (v.is_finite() && v >= 0.0 && v.fract() == 0.0 && v < 1e9).then_some(v as usize)
    }

    fn at(&self, i: usize) -> Option<Where> {
        self.n(i)
            .map(|j| if j == 0 { Where::Tool } else { Where::Joint(j) })
    }

    fn field(&self, i: usize) -> Option<LengthField> {
        match self.n(i)? {
            0 => Some(LengthField::A),
            1 => Some(LengthField::D),
            _ => None,
        }
    }
}

/// The diagnosis of kind `kind` (1 to 10) with `f`'s fields.
fn decode_diagnosis(kind: u8, f: &Fields<'_>) -> Option<Diagnosis> {
    Some(match kind {
        1 => Diagnosis::JointCount {
            expected: f.n(0)?,
            found: f.n(1)?,
        },
        2 => Diagnosis::JointKind {
            joint: f.n(0)?,
            expected: match f.n(1)? {
                0 => JointKind::Revolute,
                1 => JointKind::Prismatic,
                _ => return None,
            },
        },
        3 => Diagnosis::AxisReversed { joint: f.n(0)? },
        4 => Diagnosis::TwistSign {
            at: f.at(0)?,
            row: f.n(1)?,
            found: f.real(2)?,
        },
        5 => Diagnosis::MissingOffset {
            at: f.at(0)?,
            row: f.n(1)?,
            offset: f.real(2)?,
            found: f.real(3)?,
        },
        6 => Diagnosis::LengthInWrongRow {
            at: f.at(0)?,
            row: f.n(1)?,
            field: f.field(2)?,
            to_row: f.n(3)?,
            to_field: f.field(4)?,
        },
        7 => Diagnosis::LengthSign {
            at: f.at(0)?,
            row: f.n(1)?,
            field: f.field(2)?,
            found: f.real(3)?,
        },
        8 => Diagnosis::LengthValue {
            at: f.at(0)?,
            row: f.n(1)?,
            field: f.field(2)?,
            found: f.real(3)?,
            expected: f.real(4)?,
        },
        9 => Diagnosis::FrameDisagrees { joint: f.n(0)? },
        10 => Diagnosis::ToolDisagrees,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    // On wasm the tests are wasm_bindgen_tests, run in Node like the other core tests.
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    /// One verdict of each kind, with fields that tell a swap apart.
    fn every_kind() -> Vec<Verdict> {
        let at = Where::Joint(3);
        let wrong = |d| Verdict::Wrong(d);
        vec![
            Verdict::Correct,
            wrong(Diagnosis::JointCount {
                expected: 6,
                found: 5,
            }),
            wrong(Diagnosis::JointKind {
                joint: 2,
                expected: JointKind::Prismatic,
            }),
            wrong(Diagnosis::AxisReversed { joint: 4 }),
            wrong(Diagnosis::TwistSign {
                at: Where::Tool,
                row: 2,
                found: -std::f64::consts::FRAC_PI_2,
            }),
            wrong(Diagnosis::MissingOffset {
                at,
                row: 3,
                offset: std::f64::consts::FRAC_PI_2,
                found: 0.1 + 0.2,
            }),
            wrong(Diagnosis::LengthInWrongRow {
                at,
                row: 1,
                field: LengthField::A,
                to_row: 2,
                to_field: LengthField::D,
            }),
            wrong(Diagnosis::LengthSign {
                at,
                row: 2,
                field: LengthField::D,
                found: -163.9,
            }),
            wrong(Diagnosis::LengthValue {
                at,
                row: 4,
                field: LengthField::A,
                found: 571.0,
                expected: 571.6,
            }),
            wrong(Diagnosis::FrameDisagrees { joint: 5 }),
            wrong(Diagnosis::ToolDisagrees),
        ]
    }

    #[test]
    fn every_verdict_comes_back_as_it_went() {
        for verdict in every_kind() {
            let numbers = encode_verdict(&verdict);
            assert_eq!(decode_verdict(&numbers), Some(verdict), "{numbers:?}");
        }
    }

    #[test]
    fn numbers_that_encode_no_verdict_are_refused() {
        for numbers in [
            &[][..],
            &[11.0],
            &[-1.0],
            &[0.5],
            &[f64::NAN],
            &[0.0, 1.0],
            &[1.0, 6.0],
            &[1.0, 6.0, 5.0, 4.0],
            &[1.0, 6.5, 5.0],
            &[1.0, -6.0, 5.0],
            &[2.0, 2.0, 2.0],
            &[6.0, 3.0, 1.0, 2.0, 2.0, 0.0],
            &[3.0, f64::INFINITY],
        ] {
            assert_eq!(decode_verdict(numbers), None, "{numbers:?}");
        }
    }
}
