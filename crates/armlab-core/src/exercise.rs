//! The DH-table exercise (docs/kinematics.md §15): grading a student's table against a
//! reference by the kinematics they describe, a typed diagnosis of the first joint that
//! goes wrong, and seeded mystery arms to draw.
//!
//! DH tables are not unique, so a table is right when it gives the reference's tool pose
//! at every q ([`CHECK_SAMPLES`] random joint vectors within the reference's limits, to
//! [`CHECK_TOLERANCE`] relative to the arm's reach). When it does not, the joints' axes
//! are compared in the base frame (a revolute joint's axis line and a prismatic joint's
//! direction are fixed by the kinematics, whatever table or convention describes them);
//! the first joint whose axis differs is where the table goes wrong, and single edits of
//! the student's table (a twist's sign, a θ offset, a length moved to the neighbouring
//! row, a length's sign) tell how.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::{IsometryMatrix3, Vector3};

use super::fk::{ForwardKinematics, tool_pose};
use super::rng::SplitMix64;
use super::robot::{
    Convention, DhRow, Joint, JointKind, JointLimits, LengthUnit, PartSizes, Robot, RobotParts,
};

/// How many random joint vectors a check compares.
pub const CHECK_SAMPLES: usize = 100;

/// The largest difference of the two tool poses a right table may have: rotation entries
/// absolutely, positions relative to the reference arm's reach.
pub const CHECK_TOLERANCE: f64 = 1e-9;

/// The seed of the check's joint vectors (fixed: the same table always gets the same
/// answer).
const CHECK_SEED: u64 = 0x0D_4713;

/// A DH length column, for diagnoses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LengthField {
    /// The link length a.
    A,
    /// The offset d.
    D,
}

impl LengthField {
    /// The symbol as written in the table.
    pub fn symbol(self) -> &'static str {
        match self {
            LengthField::A => "a",
            LengthField::D => "d",
        }
    }
}

/// Where a table first disagrees with the reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Where {
    /// The axis of this joint (from 1) is the first that differs.
    Joint(usize),
    /// Every joint axis agrees; the tool frame differs.
    Tool,
}

/// What is wrong with a student's table. Joints and rows count from 1, as in the table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Diagnosis {
    /// The table has the wrong number of joints.
    JointCount {
        /// The reference's joint count.
        expected: usize,
        /// The student's.
        found: usize,
    },
    /// A joint is revolute where it should be prismatic, or the other way round.
    JointKind {
        /// The joint.
        joint: usize,
        /// What it should be.
        expected: JointKind,
    },
    /// The joint's axis lies where it should but points the other way (the joint turns
    /// or slides the wrong way).
    AxisReversed {
        /// The joint.
        joint: usize,
    },
    /// A twist α has the wrong sign.
    TwistSign {
        /// Where the first disagreement is.
        at: Where,
        /// The row whose α should have the other sign.
        row: usize,
        /// The student's α in radians (the right one is its negative).
        found: f64,
    },
    /// A θ offset is missing (or wrong) by `offset` radians.
    MissingOffset {
        /// Where the first disagreement is.
        at: Where,
        /// The row whose θ needs `offset` added.
        row: usize,
        /// The missing offset (±π/2 or π).
        offset: f64,
        /// The student's θ in radians (the right one is `found + offset`).
        found: f64,
    },
    /// A length is written in the wrong row (or the wrong column of its row).
    LengthInWrongRow {
        /// Where the first disagreement is.
        at: Where,
        /// The row the length is written in.
        row: usize,
        /// The column it is written in.
        field: LengthField,
        /// The row it belongs in.
        to_row: usize,
        /// The column it belongs in.
        to_field: LengthField,
    },
    /// A length has the wrong sign.
    LengthSign {
        /// Where the first disagreement is.
        at: Where,
        /// The row.
        row: usize,
        /// The column.
        field: LengthField,
        /// The student's length (the right one is its negative).
        found: f64,
    },
    /// One length has a wrong value, and `expected` in its place makes the table right.
    LengthValue {
        /// Where the first disagreement is.
        at: Where,
        /// The row.
        row: usize,
        /// The column.
        field: LengthField,
        /// The student's length.
        found: f64,
        /// The length that makes the whole table right.
        expected: f64,
    },
    /// Joint `joint`'s axis differs and no single edit explains it.
    FrameDisagrees {
        /// The first joint whose axis disagrees.
        joint: usize,
    },
    /// Every joint axis agrees but the tool frame does not, and no single edit explains it.
    ToolDisagrees,
}

/// The answer of a check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// The table gives the reference's tool pose at every compared q.
    Correct,
    /// It does not; what is wrong.
    Wrong(Diagnosis),
}

/// The joint vectors a check compares: [`CHECK_SAMPLES`] drawn within the reference's
/// limits from a fixed seed.
fn check_samples(reference: &Robot) -> Vec<Vec<f64>> {
    let mut rng = SplitMix64::new(CHECK_SEED);
    (0..CHECK_SAMPLES)
        .map(|_| rng.joint_vector(reference))
        .collect()
}

/// The largest difference of the two tool poses over `samples`: rotation entries as they
/// are, translations divided by `length`.
pub fn tool_disagreement(a: &Robot, b: &Robot, samples: &[Vec<f64>], length: f64) -> f64 {
    samples
        .iter()
        .map(|q| pose_difference(&tool_pose(a, q), &tool_pose(b, q), length))
        .fold(0.0, f64::max)
}

fn pose_difference(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>, length: f64) -> f64 {
    let dt = (a.translation.vector - b.translation.vector).abs().max() / length;
    let dr = (a.rotation.matrix() - b.rotation.matrix()).abs().max();
    dt.max(dr)
}

/// How joint `i`'s axis in `b` compares with `a`'s at one q.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum AxisMatch {
    Same,
    Reversed,
    Different,
}

fn compare_axis(
    a: &ForwardKinematics,
    b: &ForwardKinematics,
    i: usize,
    kind: JointKind,
    length: f64,
) -> AxisMatch {
    let (za, zb) = (a.joint_axes[i], b.joint_axes[i]);
    let tol = 1e-7;
    let parallel = za.cross(&zb).norm() <= tol;
    let on_line = |p: Vector3<f64>| (p.cross(&za)).norm() / length <= tol;
    let same_line = match kind {
        JointKind::Revolute => on_line(b.joint_origins[i] - a.joint_origins[i]),
        JointKind::Prismatic => true,
    };
    if !(parallel && same_line) {
        AxisMatch::Different
    } else if za.dot(&zb) > 0.0 {
        AxisMatch::Same
    } else {
        AxisMatch::Reversed
    }
}

/// The first joint (from 0) whose axis differs from the reference's at any sample, and
/// whether it is only reversed; `None` when every axis agrees.
fn first_axis_disagreement(
    reference: &Robot,
    student: &Robot,
    samples: &[Vec<f64>],
    length: f64,
) -> Option<(usize, bool)> {
    let mut first: Option<(usize, bool)> = None;
    for q in samples {
        let (Ok(fa), Ok(fb)) = (
            ForwardKinematics::new(reference, q),
            ForwardKinematics::new(student, q),
        ) else {
            return Some((0, false));
        };
        for (i, joint) in reference.joints.iter().enumerate() {
            if first.is_some_and(|(f, _)| f < i) {
                break;
            }
            match compare_axis(&fa, &fb, i, joint.kind, length) {
                AxisMatch::Same => {}
                AxisMatch::Reversed => {
                    if first.is_none_or(|(f, _)| i < f) {
                        first = Some((i, true));
                    }
                    break;
                }
                AxisMatch::Different => {
                    // A different line at any sample outranks "reversed" at this joint.
                    if first.is_none_or(|(f, _)| i <= f) {
                        first = Some((i, false));
                    }
                    break;
                }
            }
        }
    }
    first
}

/// One single edit of a table, and the diagnosis it stands for.
fn single_edits(student: &Robot, joint: usize) -> Vec<(Robot, Diagnosis)> {
    let n = student.dof();
    let mut edits = Edits {
        student,
        at: if joint < n {
            Where::Joint(joint + 1)
        } else {
            Where::Tool
        },
        out: Vec::new(),
    };
    for k in rows_nearest(n, joint) {
        edits.angles(k);
        edits.lengths_moved(k);
        edits.length_signs(k);
    }
    edits.out
}

/// The rows of an `n`-row table, those nearest the disagreeing `joint` first.
fn rows_nearest(n: usize, joint: usize) -> Vec<usize> {
    let mut rows: Vec<usize> = (0..n).collect();
    rows.sort_by_key(|&k| (k as i64 - joint as i64).abs());
    rows
}

/// The one length cell whose value alone makes `student` right, nearest the first
/// disagreeing `joint` (from 0); the diagnosis names it at that joint. Offsets along
/// parallel axes can stand for each other, so the lengths the student wrote are tried
/// before the empty cells.
fn one_length_value(
    reference: &Robot,
    student: &Robot,
    samples: &[Vec<f64>],
    joint: usize,
) -> Option<Diagnosis> {
    let length = reference.reach().max(1e-12);
    let at = if joint < student.dof() {
        Where::Joint(joint + 1)
    } else {
        Where::Tool
    };
    for written in [true, false] {
        for k in rows_nearest(student.dof(), joint) {
            for field in [LengthField::A, LengthField::D] {
                if (get(&student.joints[k].dh, field) != 0.0) != written {
                    continue;
                }
                let cell = (k, field);
                if let Some(d) = length_value(reference, student, samples, length, cell, at) {
                    return Some(d);
                }
            }
        }
    }
    None
}

/// The value of one length cell (`row` from 0, `field`) that makes `student` give the
/// reference's tool pose, as [`Diagnosis::LengthValue`] at `at`; `None` when no value
/// does. The tool position moves linearly with any one length, so a unit step gives the
/// direction and the best value follows from one division.
fn length_value(
    reference: &Robot,
    student: &Robot,
    samples: &[Vec<f64>],
    length: f64,
    (row, field): (usize, LengthField),
    at: Where,
) -> Option<Diagnosis> {
    let found = get(&student.joints.get(row)?.dh, field);
    let mut stepped = student.clone();
    set(&mut stepped.joints[row].dh, field, found + 1.0);
    let (mut along, mut squared) = (0.0, 0.0);
    for q in samples {
        let p0 = tool_pose(student, q).translation.vector;
        let g = tool_pose(&stepped, q).translation.vector - p0;
        along += g.dot(&(tool_pose(reference, q).translation.vector - p0));
        squared += g.norm_squared();
    }
    if squared <= 1e-12 {
        return None;
    }
    let expected = found + along / squared;
    let mut edited = student.clone();
    set(&mut edited.joints[row].dh, field, expected);
    (tool_disagreement(reference, &edited, samples, length) <= CHECK_TOLERANCE).then_some(
        Diagnosis::LengthValue {
            at,
            row: row + 1,
            field,
            found,
            expected,
        },
    )
}

/// The single edits of [`single_edits`] as they are made: each a copy of the student's
/// table with one change, and its diagnosis at `at`.
struct Edits<'a> {
    student: &'a Robot,
    at: Where,
    out: Vec<(Robot, Diagnosis)>,
}

impl Edits<'_> {
    /// Adds the student's table changed by `f`, diagnosed as `d`.
    fn edit(&mut self, f: &dyn Fn(&mut [Joint]), d: Diagnosis) {
        let mut r = self.student.clone();
        f(&mut r.joints);
        self.out.push((r, d));
    }

    /// Row `k`'s twist with the other sign (unless 0 or π), and its θ with a missing
    /// offset of ±90° or 180°.
    fn angles(&mut self, k: usize) {
        let row = self.student.joints[k].dh;
        let at = self.at;
        if row.alpha.abs() > 1e-12 && (row.alpha.abs() - PI).abs() > 1e-12 {
            self.edit(
                &|js| js[k].dh.alpha = -js[k].dh.alpha,
                Diagnosis::TwistSign {
                    at,
                    row: k + 1,
                    found: row.alpha,
                },
            );
        }
        for offset in [FRAC_PI_2, -FRAC_PI_2, PI] {
            self.edit(
                &|js| js[k].dh.theta += offset,
                Diagnosis::MissingOffset {
                    at,
                    row: k + 1,
                    offset,
                    found: row.theta,
                },
            );
        }
    }

    /// A length of row `k` moved where it is zero: to the same field of the next row (or
    /// from it), then to the other field of row `k`.
    fn lengths_moved(&mut self, k: usize) {
        let student = self.student;
        let at = self.at;
        if k + 1 < student.dof() {
            for field in [LengthField::A, LengthField::D] {
                for (src, dst) in [(k, k + 1), (k + 1, k)] {
                    if get(&student.joints[src].dh, field) != 0.0
                        && get(&student.joints[dst].dh, field) == 0.0
                    {
                        self.edit(
                            &|js| {
                                let v = get(&js[src].dh, field);
                                set(&mut js[src].dh, field, 0.0);
                                set(&mut js[dst].dh, field, v);
                            },
                            Diagnosis::LengthInWrongRow {
                                at,
                                row: src + 1,
                                field,
                                to_row: dst + 1,
                                to_field: field,
                            },
                        );
                    }
                }
            }
        }
        let row = student.joints[k].dh;
        for (from, to) in [
            (LengthField::A, LengthField::D),
            (LengthField::D, LengthField::A),
        ] {
            if get(&row, from) != 0.0 && get(&row, to) == 0.0 {
                self.edit(
                    &|js| {
                        let v = get(&js[k].dh, from);
                        set(&mut js[k].dh, from, 0.0);
                        set(&mut js[k].dh, to, v);
                    },
                    Diagnosis::LengthInWrongRow {
                        at,
                        row: k + 1,
                        field: from,
                        to_row: k + 1,
                        to_field: to,
                    },
                );
            }
        }
    }

    /// Each non-zero length of row `k` with the other sign.
    fn length_signs(&mut self, k: usize) {
        let row = self.student.joints[k].dh;
        let at = self.at;
        for field in [LengthField::A, LengthField::D] {
            if get(&row, field) != 0.0 {
                self.edit(
                    &|js| {
                        let v = get(&js[k].dh, field);
                        set(&mut js[k].dh, field, -v);
                    },
                    Diagnosis::LengthSign {
                        at,
                        row: k + 1,
                        field,
                        found: get(&row, field),
                    },
                );
            }
        }
    }
}

fn get(row: &DhRow, field: LengthField) -> f64 {
    match field {
        LengthField::A => row.a,
        LengthField::D => row.d,
    }
}

fn set(row: &mut DhRow, field: LengthField, v: f64) {
    match field {
        LengthField::A => row.a = v,
        LengthField::D => row.d = v,
    }
}

/// Grades `student` against `reference` (docs/kinematics.md §15): [`Verdict::Correct`]
/// when the tool poses agree at [`CHECK_SAMPLES`] random q to [`CHECK_TOLERANCE`];
/// otherwise the diagnosis of the first joint whose axis disagrees. The two may be
/// written in different conventions and with different base and tool transforms.
pub fn check_table(reference: &Robot, student: &Robot) -> Verdict {
    if reference.dof() != student.dof() {
        return Verdict::Wrong(Diagnosis::JointCount {
            expected: reference.dof(),
            found: student.dof(),
        });
    }
    for (i, (r, s)) in reference.joints.iter().zip(&student.joints).enumerate() {
        if r.kind != s.kind {
            return Verdict::Wrong(Diagnosis::JointKind {
                joint: i + 1,
                expected: r.kind,
            });
        }
    }
    let samples = check_samples(reference);
    let length = reference.reach().max(1e-12);
    if tool_disagreement(reference, student, &samples, length) <= CHECK_TOLERANCE {
        return Verdict::Correct;
    }
    let first = first_axis_disagreement(reference, student, &samples, length);
    let joint = first.map_or(student.dof(), |(i, _)| i);
    let edits = single_edits(student, joint);
    // An edit that makes the whole table right says exactly what is wrong (a twist of
    // the wrong sign usually shows as a reversed axis, and is named as the twist).
    for (edited, diagnosis) in &edits {
        if tool_disagreement(reference, edited, &samples, length) <= CHECK_TOLERANCE {
            return Verdict::Wrong(*diagnosis);
        }
    }
    if let Some(d) = one_length_value(reference, student, &samples, joint) {
        return Verdict::Wrong(d);
    }
    if let Some((i, true)) = first {
        return Verdict::Wrong(Diagnosis::AxisReversed { joint: i + 1 });
    }
    // Otherwise the edit that moves the first disagreement furthest, if any moves it.
    let mut best: Option<(usize, Diagnosis)> = None;
    for (edited, diagnosis) in &edits {
        let reached = first_axis_disagreement(reference, edited, &samples, length)
            .map_or(student.dof(), |(i, _)| i);
        if reached > joint && best.is_none_or(|(b, _)| reached > b) {
            best = Some((reached, *diagnosis));
        }
    }
    Verdict::Wrong(match (best, first) {
        (Some((_, d)), _) => d,
        (None, Some((i, _))) => Diagnosis::FrameDisagrees { joint: i + 1 },
        (None, None) => Diagnosis::ToolDisagrees,
    })
}

/// The fewest and most joints of a mystery arm.
pub const MYSTERY_JOINTS: (usize, usize) = (2, 6);

/// A random arm for the exercise, the same for the same seed: 2–6 joints (about one in
/// six prismatic), twists of 0 or ±90°, lengths in round millimetres, sometimes a θ offset
/// of ±90°, written in standard or modified DH. Its limits are ±180° (revolute) and
/// 0…200 mm (prismatic); its home is a non-zero pose.
pub fn mystery_arm(seed: u64) -> Robot {
    let mut rng = SplitMix64::new(seed);
    let mut pick = |n: usize| (rng.next_u64() % n as u64) as usize;
    let count = MYSTERY_JOINTS.0 + pick(MYSTERY_JOINTS.1 - MYSTERY_JOINTS.0 + 1);
    let convention = if pick(2) == 0 {
        Convention::Standard
    } else {
        Convention::Modified
    };
    const TWISTS: [f64; 4] = [0.0, FRAC_PI_2, -FRAC_PI_2, 0.0];
    const LENGTHS: [f64; 8] = [0.0, 0.0, 0.0, 50.0, 100.0, 150.0, 200.0, 250.0];
    const OFFSETS: [f64; 6] = [0.0, 0.0, 0.0, 0.0, FRAC_PI_2, -FRAC_PI_2];
    let mut joints = Vec::with_capacity(count);
    for i in 0..count {
        let prismatic = i > 0 && pick(6) == 0;
        let kind = if prismatic {
            JointKind::Prismatic
        } else {
            JointKind::Revolute
        };
        let mut a = LENGTHS[pick(LENGTHS.len())];
        let d = LENGTHS[pick(LENGTHS.len())];
        // Every joint moves the next one somewhere: at least one length per row.
        if a == 0.0 && d == 0.0 {
            a = 100.0;
        }
        let (limits, home) = match kind {
            JointKind::Revolute => (JointLimits::FULL_TURN, [0.5, -0.5, 0.8][i % 3]),
            JointKind::Prismatic => (
                JointLimits {
                    min: 0.0,
                    max: 200.0,
                },
                100.0,
            ),
        };
        joints.push(Joint {
            name: format!("joint {}", i + 1),
            kind,
            dh: DhRow {
                theta: OFFSETS[pick(OFFSETS.len())],
                d,
                a,
                alpha: TWISTS[pick(TWISTS.len())],
            },
            limits,
            max_speed: None,
            max_acceleration: None,
            home,
            parts: PartSizes::default(),
        });
    }
    Robot {
        name: format!("Mystery arm {seed}"),
        description: String::new(),
        convention,
        length_unit: LengthUnit::Millimetre,
        joints,
        world_from_base: IsometryMatrix3::identity(),
        flange_from_tool: IsometryMatrix3::identity(),
        parts: RobotParts::default(),
        keep_outs: Vec::new(),
    }
}
