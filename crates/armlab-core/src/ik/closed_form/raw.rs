//! A solution before it is written in the robot's joint values: the DH variables, the
//! branch and which branch decisions coincide; and how raw solutions become the listed
//! ones (each angle's equivalent near the seed, duplicates at singularities merged).
//! Apart from the solvers, which only fill raw solutions.

use super::ClosedFormSolution;
use crate::angles::wrap_to_pi;
use crate::ik::branch::{Branch, Elbow, Shoulder, Wrist};
use crate::robot::{Joint, JointKind, Robot, nearest_equivalent_within};

/// The joint value for the DH variable `var` of `joint` (θ with its offset, or d with
/// its offset for a prismatic joint): a revolute angle as the 2π-equivalent inside the
/// limits nearest `seed`; and whether it lies inside the limits.
fn represent(joint: &Joint, var: f64, seed: f64) -> (f64, bool) {
    if joint.kind == JointKind::Prismatic {
        let value = var - joint.dh.d;
        return (value, joint.limits.contains(value, 1e-9));
    }
    let value = var - joint.dh.theta;
    if joint.wraps() {
        return (wrap_to_pi(value), true);
    }
    let near = seed + wrap_to_pi(value - seed);
    if joint.limits.contains(near, 0.0) {
        // The equivalent nearest the seed lies inside: it is the answer.
        return (near, true);
    }
    let kept = nearest_equivalent_within(near, seed, &joint.limits);
    if wrap_to_pi(kept - near).abs() < 1e-9 {
        (kept, true)
    } else {
        (near, false)
    }
}

/// Which branch decisions coincide in a raw solution.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Merged {
    pub(super) shoulder: bool,
    pub(super) elbow: bool,
    pub(super) wrist: bool,
}

/// A raw solution: the DH variables (θ with offsets, or d), its branch, exact, singular,
/// the coinciding decisions and the free joints.
#[derive(Debug, Clone)]
pub(super) struct Raw {
    pub(super) theta: [f64; 6],
    pub(super) branch: Branch,
    pub(super) exact: bool,
    pub(super) singular: bool,
    pub(super) merged: Merged,
    pub(super) free: [bool; 6],
}

impl Raw {
    pub(super) fn new(theta: [f64; 6], branch: Branch) -> Self {
        Raw {
            theta,
            branch,
            exact: true,
            singular: false,
            merged: Merged::default(),
            free: [false; 6],
        }
    }

    /// The branches that coincide with this one: every combination of the merged
    /// decisions flipped, except the branch itself.
    pub(super) fn coincident(&self) -> Vec<Branch> {
        let mut out = Vec::new();
        if !(self.merged.shoulder || self.merged.elbow || self.merged.wrist) {
            // Off every singularity (almost every call): no other branch coincides.
            return out;
        }
        let flip_s = |s: Option<Shoulder>| {
            s.map(|s| match s {
                Shoulder::Right => Shoulder::Left,
                Shoulder::Left => Shoulder::Right,
            })
        };
        let flip_e = |e: Option<Elbow>| {
            e.map(|e| match e {
                Elbow::Up => Elbow::Down,
                Elbow::Down => Elbow::Up,
            })
        };
        let flip_w = |w: Option<Wrist>| {
            w.map(|w| match w {
                Wrist::NotFlipped => Wrist::Flipped,
                Wrist::Flipped => Wrist::NotFlipped,
            })
        };
        let b = self.branch;
        for fs in [false, true] {
            for fe in [false, true] {
                for fw in [false, true] {
                    if (fs && !self.merged.shoulder)
                        || (fe && !self.merged.elbow)
                        || (fw && !self.merged.wrist)
                        || !(fs || fe || fw)
                    {
                        continue;
                    }
                    let c = Branch {
                        shoulder: if fs { flip_s(b.shoulder) } else { b.shoulder },
                        elbow: if fe { flip_e(b.elbow) } else { b.elbow },
                        wrist: if fw { flip_w(b.wrist) } else { b.wrist },
                    };
                    if c != b && !out.contains(&c) {
                        out.push(c);
                    }
                }
            }
        }
        out
    }
}

/// Adds `raw` (in joint values near `seed`) to `solutions`, or, when it is a singular
/// one that an earlier solution already is (branches coincide only at singularities),
/// adds its branches to that one's coincident branches instead.
pub(super) fn add_solution(
    robot: &Robot,
    n: usize,
    raw: &Raw,
    seed: &[f64],
    solutions: &mut Vec<ClosedFormSolution>,
) {
    let mut q = Vec::with_capacity(n);
    let mut inside = true;
    for (i, joint) in robot.joints.iter().enumerate() {
        let (v, ok) = represent(joint, raw.theta[i], seed[i]);
        inside &= ok;
        q.push(v);
    }
    let duplicate = if raw.singular {
        solutions.iter().position(|s| {
            s.q.iter()
                .zip(&q)
                .zip(&robot.joints)
                .all(|((a, b), j)| j.change(*a, *b).abs() < 1e-9)
        })
    } else {
        None
    };
    let mut coincident = raw.coincident();
    if let Some(k) = duplicate {
        let kept = &mut solutions[k];
        coincident.push(raw.branch);
        for b in coincident {
            if b != kept.branch && !kept.coincident.contains(&b) {
                kept.coincident.push(b);
            }
        }
        kept.singular = true;
        return;
    }
    solutions.push(ClosedFormSolution {
        q,
        branch: raw.branch,
        coincident,
        free_joints: (0..n).filter(|&i| raw.free[i]).collect(),
        within_limits: inside,
        singular: raw.singular,
        exact: raw.exact,
    });
}
