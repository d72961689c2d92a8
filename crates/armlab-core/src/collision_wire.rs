//! The collision check as a list of numbers (docs/kinematics.md §20.1): the page computes
//! the arm's posed parts itself and sends them, with the floor switch and the keep-out
//! boxes, to the lazily loaded module (`collide_parts` of the JS API), which runs
//! [`CollisionChecker::check_parts`] and answers with the contacts. The page's own wasm
//! thus never links the collision library. Numbers keep their f64 bits on the way, so the
//! module's answer is the one the page would have computed itself.
//!
//! A request, all f64:
//!
//! | at | what |
//! |---|---|
//! | 0 | [`WIRE_VERSION`] |
//! | 1 | the tolerance (each part shrunk by it on every side) |
//! | 2 | the floor: 1 checked, 0 not |
//! | 3, 4 | the number of parts P and of keep-out boxes K |
//! | then P × 18 | per part: body, kind (base 0, link 1, housing 2, flange 3, palm 4, finger 5), shape (box 0, cylinder 1), centre (3), rotation (9, column-major), size (3) |
//! | then K × 15 | per box: centre (3), size (3), rotation (9, column-major) |
//!
//! A report: the exact tests, the number of contacts C, then C × 3: the part, what it
//! touches (another part 0, the floor 1, a keep-out box 2) and that part's or box's index
//! (0 for the floor). Which parts collide follows from the contacts.

use nalgebra::{Matrix3, Point3, Rotation3, Vector3};

use super::collision::{
    CollisionChecker, CollisionReport, Contact, KeepOut, MAX_KEEP_OUTS, Obstacle,
};
use super::parts::{Part, PartKind, PartShape};

/// The encoding's version, the request's first number.
pub const WIRE_VERSION: f64 = 1.0;
/// Numbers per part in a request.
const PART_LEN: usize = 18;
/// Numbers per keep-out box in a request.
const BOX_LEN: usize = 15;
/// Numbers before the parts.
const HEAD_LEN: usize = 5;
/// The most parts a request may hold (far above any arm's: 32 joints make about 70).
pub const MAX_WIRE_PARTS: usize = 1024;

const KINDS: [PartKind; 6] = [
    PartKind::Base,
    PartKind::Link,
    PartKind::Housing,
    PartKind::Flange,
    PartKind::Palm,
    PartKind::Finger,
];

/// What is wrong with a list of numbers given as a request or a report.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WireError {
    /// The list is shorter or longer than its counts say.
    #[error("the collision request or report has {found} numbers, not {expected}")]
    Length {
        /// The length the counts give.
        expected: usize,
        /// The list's length.
        found: usize,
    },
    /// A number that must be a code, count or index is not one.
    #[error(
        "number {at} of the collision request or report ({value}) is not a valid code, count or index"
    )]
    Code {
        /// Its position in the list.
        at: usize,
        /// The number.
        value: f64,
    },
    /// NaN or ±infinity.
    #[error("number {at} of the collision request is not finite")]
    NotFinite {
        /// Its position in the list.
        at: usize,
    },
}

fn push_rotation(out: &mut Vec<f64>, rotation: &Rotation3<f64>) {
    out.extend_from_slice(rotation.matrix().as_slice());
}

/// The request for checking `parts` (each shrunk by `tolerance`) against each other, the
/// floor (when `floor`) and `keep_outs`.
pub fn encode_request(
    parts: &[Part],
    tolerance: f64,
    floor: bool,
    keep_outs: &[KeepOut],
) -> Vec<f64> {
    let mut out = Vec::with_capacity(HEAD_LEN + parts.len() * PART_LEN + keep_outs.len() * BOX_LEN);
    out.extend_from_slice(&[
        WIRE_VERSION,
        tolerance,
        f64::from(u8::from(floor)),
        parts.len() as f64,
        keep_outs.len() as f64,
    ]);
    for p in parts {
        let kind = KINDS.iter().position(|k| *k == p.kind).unwrap_or(0);
        let shape = match p.shape {
            PartShape::Box => 0.0,
            PartShape::Cylinder => 1.0,
        };
        out.extend_from_slice(&[p.body as f64, kind as f64, shape]);
        out.extend_from_slice(p.centre.coords.as_slice());
        push_rotation(&mut out, &p.rotation);
        out.extend_from_slice(p.size.as_slice());
    }
    for k in keep_outs {
        out.extend_from_slice(k.centre.coords.as_slice());
        out.extend_from_slice(k.size.as_slice());
        push_rotation(&mut out, &k.rotation);
    }
    out
}

/// A whole number in `0..=max` at `at`.
fn index(list: &[f64], at: usize, max: usize) -> Result<usize, WireError> {
    let value = list.get(at).copied().unwrap_or(f64::NAN);
    if value.fract() == 0.0 && (0.0..=max as f64).contains(&value) {
        Ok(value as usize)
    } else {
        Err(WireError::Code { at, value })
    }
}

fn triple(list: &[f64], at: usize) -> Vector3<f64> {
    Vector3::new(list[at], list[at + 1], list[at + 2])
}

fn rotation(list: &[f64], at: usize) -> Rotation3<f64> {
    Rotation3::from_matrix_unchecked(Matrix3::from_column_slice(&list[at..at + 9]))
}

/// A decoded request: the parts, the tolerance, and a checker with the floor switch and
/// the keep-out boxes.
pub fn decode_request(list: &[f64]) -> Result<(Vec<Part>, f64, CollisionChecker), WireError> {
    if list.len() < HEAD_LEN {
        return Err(WireError::Length {
            expected: HEAD_LEN,
            found: list.len(),
        });
    }
    if list[0] != WIRE_VERSION {
        return Err(WireError::Code {
            at: 0,
            value: list[0],
        });
    }
    let floor = index(list, 2, 1)? == 1;
    let (n_parts, n_boxes) = (
        index(list, 3, MAX_WIRE_PARTS)?,
        index(list, 4, MAX_KEEP_OUTS)?,
    );
    let expected = HEAD_LEN + n_parts * PART_LEN + n_boxes * BOX_LEN;
    if list.len() != expected {
        return Err(WireError::Length {
            expected,
            found: list.len(),
        });
    }
    if let Some(at) = list.iter().position(|v| !v.is_finite()) {
        return Err(WireError::NotFinite { at });
    }
    let mut parts = Vec::with_capacity(n_parts);
    for i in 0..n_parts {
        let at = HEAD_LEN + i * PART_LEN;
        parts.push(Part {
            body: index(list, at, MAX_WIRE_PARTS)?,
            kind: KINDS[index(list, at + 1, KINDS.len() - 1)?],
            shape: match index(list, at + 2, 1)? {
                0 => PartShape::Box,
                _ => PartShape::Cylinder,
            },
            centre: Point3::from(triple(list, at + 3)),
            rotation: rotation(list, at + 6),
            size: triple(list, at + 15),
        });
    }
    let boxes = (0..n_boxes)
        .map(|k| {
            let at = HEAD_LEN + n_parts * PART_LEN + k * BOX_LEN;
            KeepOut {
                centre: Point3::from(triple(list, at)),
                size: triple(list, at + 3),
                rotation: rotation(list, at + 6),
            }
        })
        .collect();
    let checker = CollisionChecker::new(floor, boxes).map_err(|_| WireError::Code {
        at: 4,
        value: list[4],
    })?;
    Ok((parts, list[1], checker))
}

/// The report as numbers.
pub fn encode_report(report: &CollisionReport) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 + 3 * report.contacts.len());
    out.push(report.exact_tests as f64);
    out.push(report.contacts.len() as f64);
    for c in &report.contacts {
        let (kind, other) = match c.other {
            Obstacle::Part(j) => (0.0, j as f64),
            Obstacle::Floor => (1.0, 0.0),
            Obstacle::KeepOut(k) => (2.0, k as f64),
        };
        out.extend_from_slice(&[c.part as f64, kind, other]);
    }
    out
}

/// The report of a check of `parts` parts, from its numbers.
pub fn decode_report(list: &[f64], parts: usize) -> Result<CollisionReport, WireError> {
    let count = index(list, 1, list.len())?;
    if list.len() != 2 + 3 * count {
        return Err(WireError::Length {
            expected: 2 + 3 * count,
            found: list.len(),
        });
    }
    let last = parts.saturating_sub(1);
    let mut report = CollisionReport {
        contacts: Vec::with_capacity(count),
        colliding: vec![false; parts],
        exact_tests: index(list, 0, usize::MAX >> 11)?,
    };
    for c in 0..count {
        let at = 2 + 3 * c;
        let part = index(list, at, last)?;
        let other = match index(list, at + 1, 2)? {
            0 => Obstacle::Part(index(list, at + 2, last)?),
            1 => Obstacle::Floor,
            _ => Obstacle::KeepOut(index(list, at + 2, MAX_KEEP_OUTS)?),
        };
        if parts == 0 {
            return Err(WireError::Code {
                at,
                value: list[at],
            });
        }
        report.colliding[part] = true;
        if let Obstacle::Part(j) = other {
            report.colliding[j] = true;
        }
        report.contacts.push(Contact { part, other });
    }
    Ok(report)
}

/// The module's side: decodes a request, checks it, encodes the report.
pub fn check_request(list: &[f64]) -> Result<Vec<f64>, WireError> {
    let (parts, tolerance, checker) = decode_request(list)?;
    Ok(encode_report(&checker.check_parts(&parts, tolerance)))
}
