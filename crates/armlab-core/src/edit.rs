//! Editing a robot without losing it (docs/kinematics.md §14.3): switching a table's
//! convention keeps the arm's kinematics, and adding or removing a joint keeps the other
//! joints' values.

use super::convention::convert;
use super::robot::{Convention, Joint, Robot};

/// The robot written in `convention` with the same tool pose at every q (the DH editor's
/// convention switch): [`convert`], so the arm keeps its shape instead of reading the same
/// numbers under the other convention.
pub fn switch_convention(robot: &Robot, convention: Convention) -> Robot {
    convert(robot, convention)
}

/// The robot with `joint` inserted before joint `at` (from 0; `at` ≥ the joint count
/// appends), and the joint vector `q` with the new joint at its home value and every
/// other joint at its value in `q` (missing values take the joint's home).
pub fn insert_joint(robot: &Robot, q: &[f64], at: usize, joint: Joint) -> (Robot, Vec<f64>) {
    let at = at.min(robot.dof());
    let mut out = robot.clone();
    let mut new_q: Vec<f64> = robot
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| q.get(i).copied().unwrap_or(j.home))
        .collect();
    new_q.insert(at, joint.home);
    out.joints.insert(at, joint);
    (out, new_q)
}

/// The robot without joint `at` (from 0), and `q` without its value: every other joint
/// keeps its value (missing values take the joint's home). `None` when there is no such
/// joint.
pub fn remove_joint(robot: &Robot, q: &[f64], at: usize) -> Option<(Robot, Vec<f64>)> {
    if at >= robot.dof() {
        return None;
    }
    let mut out = robot.clone();
    out.joints.remove(at);
    let new_q = robot
        .joints
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != at)
        .map(|(i, j)| q.get(i).copied().unwrap_or(j.home))
        .collect();
    Some((out, new_q))
}
