//! Standard ↔ modified DH (docs/kinematics.md §14): the same arm written in the other
//! convention, with the same tool pose at every q, and both sets of frames for
//! overlaying them.
//!
//! A standard chain is `B · Π Rz(θ_i) Tz(d_i) [Tx(a_i) Rx(α_i)] · F` and a modified one
//! `B · Π [Rx(α_{i−1}) Tx(a_{i−1})] Rz(θ_i) Tz(d_i) · F`. Tx and Rx commute, so both are the
//! same alternating product of "joint" parts `Rz(θ) Tz(d)` and "link" parts `Tx(a) Rx(α)`;
//! they differ only in which joint each link part is written with. Converting moves every
//! link part one row along; the one left over at an end goes into the base or tool
//! transform (and is taken back out of it when it is exactly such a part, so converting
//! twice returns the original table).

use nalgebra::{IsometryMatrix3, Rotation3, Translation3, Vector3};

use super::error::RobotError;
use super::fk::ForwardKinematics;
use super::robot::{Convention, Robot};

/// Tolerance for recognising a base or tool transform as a pure link part
/// `Tx(a)·Rx(α)`: its translation along x only and its rotation about x only, to this.
const PURE_LINK_TOLERANCE: f64 = 1e-12;

/// The link part `Tx(a)·Rx(α)` (= `Rx(α)·Tx(a)`).
pub fn link_part(a: f64, alpha: f64) -> IsometryMatrix3<f64> {
    IsometryMatrix3::from_parts(
        Translation3::new(a, 0.0, 0.0),
        Rotation3::from_axis_angle(&Vector3::x_axis(), alpha),
    )
}

/// `(a, α)` when `pose` is exactly a link part `Tx(a)·Rx(α)` (to 1e−12), else `None`.
fn as_link_part(pose: &IsometryMatrix3<f64>) -> Option<(f64, f64)> {
    let t = pose.translation.vector;
    let r = pose.rotation.matrix();
    let scale = t.norm().max(1.0);
    let pure = t.y.abs() <= PURE_LINK_TOLERANCE * scale
        && t.z.abs() <= PURE_LINK_TOLERANCE * scale
        && (r[(0, 0)] - 1.0).abs() <= PURE_LINK_TOLERANCE
        && r[(0, 1)].abs() <= PURE_LINK_TOLERANCE
        && r[(0, 2)].abs() <= PURE_LINK_TOLERANCE
        && r[(1, 0)].abs() <= PURE_LINK_TOLERANCE
        && r[(2, 0)].abs() <= PURE_LINK_TOLERANCE;
    pure.then(|| (t.x, r[(2, 1)].atan2(r[(1, 1)])))
}

/// The same arm written in `to` (docs/kinematics.md §14); a copy when it already is.
/// Names, kinds, offsets θ⁰ and d⁰, limits, homes and drawn sizes stay with their joints;
/// every q gives the same tool pose ([`tool_pose`](super::fk::tool_pose)) in both.
///
/// - standard → modified: row i's (a_i, α_i) becomes row i+1's (a_i, α_i); the last
///   row's goes into the tool, `F' = Tx(a_n)Rx(α_n)·F`; row 1's (a_0, α_0) is taken out
///   of the base when the base is exactly a link part, else 0.
/// - modified → standard: row i+1's (a_i, α_i) becomes row i's; row 1's (a_0, α_0) goes
///   into the base, `B' = B·Rx(α_0)Tx(a_0)`; the last row's (a_n, α_n) is taken out of the
///   tool when the tool is exactly a link part, else 0.
pub fn convert(robot: &Robot, to: Convention) -> Robot {
    if robot.convention == to {
        return robot.clone();
    }
    let n = robot.dof();
    let mut out = robot.clone();
    out.convention = to;
    // The link parts (a, α) in chain order: n + 1 slots, between the base, the joints and
    // the tool. Slot 0 is before joint 1, slot n after joint n.
    let mut parts = vec![(0.0, 0.0); n + 1];
    match robot.convention {
        Convention::Standard => {
            for (i, j) in robot.joints.iter().enumerate() {
                parts[i + 1] = (j.dh.a, j.dh.alpha);
            }
        }
        Convention::Modified => {
            for (i, j) in robot.joints.iter().enumerate() {
                parts[i] = (j.dh.a, j.dh.alpha);
            }
        }
    }
    let mut base = robot.world_from_base;
    let mut tool = robot.flange_from_tool;
    match to {
        Convention::Modified => {
            // Slot 0 from the base when it is a pure link part; slot n into the tool.
            if let Some(p) = as_link_part(&base) {
                parts[0] = p;
                base = IsometryMatrix3::identity();
            }
            let (a, alpha) = parts[n];
            tool = link_part(a, alpha) * tool;
            for (i, j) in out.joints.iter_mut().enumerate() {
                (j.dh.a, j.dh.alpha) = parts[i];
            }
        }
        Convention::Standard => {
            let (a, alpha) = parts[0];
            base *= link_part(a, alpha);
            if let Some(p) = as_link_part(&tool) {
                parts[n] = p;
                tool = IsometryMatrix3::identity();
            }
            for (i, j) in out.joints.iter_mut().enumerate() {
                (j.dh.a, j.dh.alpha) = parts[i + 1];
            }
        }
    }
    out.world_from_base = base;
    out.flange_from_tool = tool;
    out
}

/// The arm's frames in both conventions at one q, for overlaying them.
#[derive(Debug, Clone, PartialEq)]
pub struct ConventionFrames {
    /// The robot written in standard DH (a copy when it already is).
    pub standard: Robot,
    /// The robot written in modified DH.
    pub modified: Robot,
    /// Frames 0..n of the standard table in the world (frame 0 is its base).
    pub standard_frames: Vec<IsometryMatrix3<f64>>,
    /// Frames 0..n of the modified table in the world.
    pub modified_frames: Vec<IsometryMatrix3<f64>>,
    /// The tool pose of each (the same pose, up to rounding).
    pub standard_tool: IsometryMatrix3<f64>,
    /// The tool pose of the modified table.
    pub modified_tool: IsometryMatrix3<f64>,
    /// The largest entry difference of the two tool poses as 4×4 matrices (robot units
    /// for the translation column): the agreement of T_0n as one number.
    pub disagreement: f64,
}

/// Both tables and both sets of frames of `robot` at `q` (docs/kinematics.md §14).
pub fn frames_in_both_conventions(
    robot: &Robot,
    q: &[f64],
) -> Result<ConventionFrames, RobotError> {
    let standard = convert(robot, Convention::Standard);
    let modified = convert(robot, Convention::Modified);
    let fs = ForwardKinematics::new(&standard, q)?;
    let fm = ForwardKinematics::new(&modified, q)?;
    let frames = |r: &Robot, fk: &ForwardKinematics| {
        std::iter::once(r.world_from_base)
            .chain(fk.base_from_frames.iter().copied())
            .collect::<Vec<_>>()
    };
    let disagreement = (fs.base_from_tool.to_homogeneous() - fm.base_from_tool.to_homogeneous())
        .abs()
        .max();
    Ok(ConventionFrames {
        standard_frames: frames(&standard, &fs),
        modified_frames: frames(&modified, &fm),
        standard_tool: fs.base_from_tool,
        modified_tool: fm.base_from_tool,
        standard,
        modified,
        disagreement,
    })
}
