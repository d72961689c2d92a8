//! The arm's solid parts (docs/kinematics.md §20): one list of boxes and cylinders derived
//! from the robot file and the current frames, shared by the renderer (which draws them)
//! and the collision check (which tests them).
//!
//! - the base: a block under frame 0 with its top at z = 0 of the base frame;
//! - each link i: along its DH offsets from the previous frame's origin (standard DH: d
//!   along z_{i−1}, then a along x_i; modified DH: a along x_{i−1}, then d along z_i) —
//!   two thin cylinders, or, when the file gives `link_size`, a box of that size along the
//!   longer offset and a thin cylinder along the other;
//! - each joint's housing at its origin along its axis: a cylinder (revolute) or a box
//!   (prismatic);
//! - the hand: a flange cylinder from the last frame to the tool point, a palm behind the
//!   tool point and two fingers reaching past it (outer size `hand_size` when given).
//!
//! Sizes the file does not give follow the arm's reach (see [`Proportions`]).

use nalgebra::{Point3, Rotation3, Vector3};

use super::fk::ForwardKinematics;
use super::robot::{Convention, JointKind, Robot};

/// The solid a part is: a unit shape scaled by [`Part::size`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PartShape {
    /// A box with edges `size` along the part's local x, y, z.
    Box,
    /// A cylinder along the part's local z, `size.z` long, of diameter `size.x`
    /// (`size.x == size.y`).
    Cylinder,
}

/// What a part is, for its colour and its name in messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PartKind {
    /// The base block.
    Base,
    /// A link along the DH offsets.
    Link,
    /// A joint's housing along its axis.
    Housing,
    /// The flange from the last frame to the tool point.
    Flange,
    /// The gripper's palm.
    Palm,
    /// A gripper finger.
    Finger,
}

/// One solid part of the arm in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Part {
    /// The rigid body the part moves with: 0 is the base, i (1-based) moves with joint i
    /// (its link and its housing); the hand moves with the last joint, n.
    pub body: usize,
    /// What the part is.
    pub kind: PartKind,
    /// Box or cylinder.
    pub shape: PartShape,
    /// The part's centre in the world.
    pub centre: Point3<f64>,
    /// The part's orientation: its local z is the long axis.
    pub rotation: Rotation3<f64>,
    /// Full extents along the part's local x, y and z.
    pub size: Vector3<f64>,
}

/// Sizes of the parts that have no size in the robot file, from the arm's reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Proportions {
    /// The arm's reach ([`Robot::reach`]).
    pub reach: f64,
    /// A link's diameter: 3.5 % of the reach.
    pub link_width: f64,
    /// A housing's diameter: 7 % of the reach.
    pub joint_diameter: f64,
    /// A housing's length along its axis: 9 % of the reach.
    pub joint_length: f64,
}

impl Proportions {
    /// The proportions of `robot`.
    pub fn of(robot: &Robot) -> Proportions {
        let reach = robot.reach();
        Proportions {
            reach,
            link_width: reach * 0.035,
            joint_diameter: reach * 0.07,
            joint_length: reach * 0.09,
        }
    }
}

/// The rotation taking z to the unit vector `dir` (a half turn about x for −z).
pub fn rotation_to(dir: &Vector3<f64>) -> Rotation3<f64> {
    Rotation3::rotation_between(&Vector3::z(), dir)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI))
}

/// A part stretched from `a` to `b` with a square (box) or round (cylinder) cross-section
/// of `width`; `None` when `a` and `b` coincide.
fn segment(
    body: usize,
    kind: PartKind,
    shape: PartShape,
    a: &Point3<f64>,
    b: &Point3<f64>,
    width: f64,
) -> Option<Part> {
    let v = b - a;
    let len = v.norm();
    if len < 1e-9 {
        return None;
    }
    Some(Part {
        body,
        kind,
        shape,
        centre: a + v * 0.5,
        rotation: rotation_to(&(v / len)),
        size: Vector3::new(width, width, len),
    })
}

/// Every part of `robot` at the frames `fk`, in drawing order: the base, then per joint
/// its link part(s) and its housing, then the flange, palm and two fingers.
pub fn robot_parts(robot: &Robot, fk: &ForwardKinematics) -> Vec<Part> {
    let mut out = Vec::with_capacity(4 + 3 * robot.dof());
    robot_parts_into(robot, fk, &mut out);
    out
}

/// [`robot_parts`] into a reused list (cleared first).
pub fn robot_parts_into(robot: &Robot, fk: &ForwardKinematics, out: &mut Vec<Part>) {
    out.clear();
    let sizes = Proportions::of(robot);
    out.push(base_block(robot, &sizes));
    for i in 0..robot.dof().min(fk.base_from_frames.len()) {
        link_parts(robot, fk, i, &sizes, out);
    }
    hand(robot, fk, &sizes, out);
}

fn base_block(robot: &Robot, sizes: &Proportions) -> Part {
    let base = &robot.world_from_base;
    let reach = sizes.reach;
    let size = robot.parts.base.map_or(
        Vector3::new(reach * 0.22, reach * 0.22, reach * 0.06),
        Vector3::from,
    );
    Part {
        body: 0,
        kind: PartKind::Base,
        shape: PartShape::Box,
        centre: base * Point3::new(0.0, 0.0, -size.z * 0.5),
        rotation: base.rotation,
        size,
    }
}

/// Link `i`'s parts (0-based) and its joint's housing.
fn link_parts(
    robot: &Robot,
    fk: &ForwardKinematics,
    i: usize,
    sizes: &Proportions,
    out: &mut Vec<Part>,
) {
    let body = i + 1;
    let joint = &robot.joints[i];
    let prev = if i == 0 {
        robot.world_from_base
    } else {
        fk.base_from_frames[i - 1]
    };
    let frame = fk.base_from_frames[i];
    let o_prev = Point3::from(prev.translation.vector);
    let o = Point3::from(frame.translation.vector);
    let column = match robot.convention {
        Convention::Standard => 2,
        Convention::Modified => 0,
    };
    let along = prev.rotation.matrix().column(column).into_owned();
    let corner = o_prev + along * along.dot(&(o - o_prev));
    let (first, second) = ((o_prev, corner), (corner, o));
    let thin = |a: &Point3<f64>, b: &Point3<f64>| {
        segment(
            body,
            PartKind::Link,
            PartShape::Cylinder,
            a,
            b,
            sizes.link_width,
        )
    };
    match joint.parts.link {
        Some([l, w, h]) => {
            let (long, short) = if (first.1 - first.0).norm() >= (second.1 - second.0).norm() {
                (first, second)
            } else {
                (second, first)
            };
            let dir = long.1 - long.0;
            if dir.norm() > 1e-9 {
                out.push(Part {
                    body,
                    kind: PartKind::Link,
                    shape: PartShape::Box,
                    centre: long.0 + dir * 0.5,
                    rotation: rotation_to(&dir.normalize()),
                    size: Vector3::new(w, h, l),
                });
            }
            out.extend(thin(&short.0, &short.1));
        }
        None => {
            out.extend(thin(&first.0, &first.1));
            out.extend(thin(&second.0, &second.1));
        }
    }
    let (shape, width) = match joint.kind {
        JointKind::Revolute => (PartShape::Cylinder, sizes.joint_diameter),
        JointKind::Prismatic => (PartShape::Box, sizes.joint_diameter * 0.8),
    };
    out.push(Part {
        body,
        kind: PartKind::Housing,
        shape,
        centre: Point3::from(fk.joint_origins[i]),
        rotation: rotation_to(&fk.joint_axes[i]),
        size: Vector3::new(width, width, sizes.joint_length),
    });
}

/// The flange and a U-shaped gripper around the tool point.
fn hand(robot: &Robot, fk: &ForwardKinematics, sizes: &Proportions, out: &mut Vec<Part>) {
    let body = robot.dof();
    let tool = fk.base_from_tool;
    let last = fk
        .base_from_frames
        .last()
        .copied()
        .unwrap_or(robot.world_from_base);
    let o_last = Point3::from(last.translation.vector);
    let o_tool = Point3::from(tool.translation.vector);
    out.extend(segment(
        body,
        PartKind::Flange,
        PartShape::Cylinder,
        &o_last,
        &o_tool,
        sizes.link_width * 0.8,
    ));
    let [hand_l, hand_w, hand_h] = robot.parts.hand.unwrap_or([
        sizes.link_width * 0.9,
        sizes.reach * 0.065,
        sizes.reach * 0.1,
    ]);
    let finger = hand_h * 0.5;
    let z = tool.rotation.matrix().column(2).into_owned();
    let y = tool.rotation.matrix().column(1).into_owned();
    let palm = o_tool - z * finger;
    out.push(Part {
        body,
        kind: PartKind::Palm,
        shape: PartShape::Box,
        centre: palm,
        rotation: tool.rotation,
        size: Vector3::new(hand_l, hand_w, hand_h * 0.2),
    });
    let thickness = hand_w * 0.18;
    for side in [-1.0, 1.0] {
        let a = palm + y * (side * (hand_w - thickness) * 0.5);
        let b = a + z * (finger * 1.4);
        out.extend(segment(
            body,
            PartKind::Finger,
            PartShape::Box,
            &a,
            &b,
            thickness,
        ));
    }
}
