//! Builds the 3D scene from the core's frames: a base, a cylinder at each joint along its
//! axis (a box for prismatic joints), links along the DH offsets (d along z, then a along
//! x), a gripper at the tool, the DH frames, the ground grid and the target marker with
//! its handles. Pure geometry: no kinematics is computed here.

use nalgebra::{Matrix4, Point3, Rotation3, Unit, Vector3};

use crate::kinematics::{Convention, ForwardKinematics, JointKind, Robot};
use crate::render::camera::OrbitCamera;
use crate::render::{Instance, Line, Scene, Shape};

const LINK: [u8; 4] = [196, 202, 210, 255];
const JOINT: [u8; 4] = [52, 120, 196, 255];
const PRISMATIC: [u8; 4] = [220, 140, 40, 255];
const BASE: [u8; 4] = [88, 92, 100, 255];
const GRIPPER: [u8; 4] = [70, 74, 80, 255];
const HIGHLIGHT: [u8; 4] = [255, 210, 60, 255];
const AXIS: [[u8; 4]; 3] = [[230, 60, 50, 255], [60, 190, 70, 255], [60, 110, 240, 255]];

/// The screen-size parameters of the target marker, in pixels.
pub mod handle_px {
    /// Radius of the centre ball.
    pub const BALL: f64 = 11.0;
    /// Length of an axis arrow (centre to tip).
    pub const ARROW: f64 = 80.0;
    /// Radius of a rotation ring.
    pub const RING: f64 = 58.0;
}

/// What the marker looks like this frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarkerLook {
    /// Ball colour (reached / unreachable / pending).
    pub color: [u8; 4],
    /// Axis directions for the arrows and rings (columns: x, y, z).
    pub axes: [Vector3<f64>; 3],
    /// Draw the rotation rings (5D and full-pose tasks).
    pub rings: bool,
    /// The handle under the pointer or being dragged.
    pub active: Option<super::viewport::marker::Handle>,
}

/// A unit-shape instance stretched from `a` to `b` with this cross-section.
pub(crate) fn segment(
    shape: Shape,
    a: &Point3<f64>,
    b: &Point3<f64>,
    width: f64,
    color: [u8; 4],
) -> Option<Instance> {
    let v = b - a;
    let len = v.norm();
    if len < 1e-9 {
        return None;
    }
    let rot = rotation_to(&(v / len));
    let mid = a + v * 0.5;
    Some(instance(
        shape,
        &mid,
        &rot,
        Vector3::new(width, width, len),
        color,
    ))
}

/// An arrow from `start` to `tip`: a cylinder shaft of width `shaft` and a cone head of
/// `head` = [width, length] (shortened to half the arrow when the arrow is short).
pub(crate) fn arrow(
    start: &Point3<f64>,
    tip: &Point3<f64>,
    shaft: f64,
    head: [f64; 2],
    color: [u8; 4],
) -> impl Iterator<Item = Instance> {
    let v = tip - start;
    let len = v.norm();
    let parts = (len > 1e-12).then(|| {
        let dir = v / len;
        let head_len = head[1].min(len * 0.5);
        let neck = tip - dir * head_len;
        let cone = instance(
            Shape::Cone,
            &neck,
            &rotation_to(&dir),
            Vector3::new(head[0], head[0], head_len),
            color,
        );
        segment(Shape::Cylinder, start, &neck, shaft, color)
            .into_iter()
            .chain(std::iter::once(cone))
    });
    parts.into_iter().flatten()
}

/// The rotation taking z to `dir`.
pub(crate) fn rotation_to(dir: &Vector3<f64>) -> Rotation3<f64> {
    Rotation3::rotation_between(&Vector3::z(), dir).unwrap_or_else(|| {
        // dir = −z: any half turn about a horizontal axis.
        Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
    })
}

/// A unit shape placed at `centre`, turned by `rot` and scaled along its own axes.
pub(crate) fn instance(
    shape: Shape,
    centre: &Point3<f64>,
    rot: &Rotation3<f64>,
    scale: Vector3<f64>,
    color: [u8; 4],
) -> Instance {
    let m = Matrix4::new_translation(&centre.coords)
        * rot.to_homogeneous()
        * Matrix4::new_nonuniform_scaling(&scale);
    Instance {
        shape,
        model: m.cast::<f32>(),
        color,
        on_top: false,
    }
}

/// A "nice" grid spacing (1, 2 or 5 × 10^k) near `approx`.
pub fn nice_step(approx: f64) -> f64 {
    let k = approx.max(1e-9).log10().floor();
    let base = 10f64.powf(k);
    let m = approx / base;
    let f = if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    f * base
}

/// Everything a scene is built from.
pub struct SceneInput<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// Its frames at the current q.
    pub fk: &'a ForwardKinematics,
    /// The camera.
    pub camera: &'a OrbitCamera,
    /// Viewport size in points (for constant-size handles).
    pub viewport_px: [f64; 2],
    /// Draw every DH frame.
    pub show_frames: bool,
    /// The link to highlight (1-based; 0 = the base frame).
    pub highlighted_link: Option<usize>,
    /// The IK target pose.
    pub target: &'a nalgebra::IsometryMatrix3<f64>,
    /// The marker's look.
    pub marker: &'a MarkerLook,
    /// sRGB background.
    pub background: [u8; 3],
}

/// Sizes of the drawn parts that have no size in the robot file, from the arm's reach.
struct Proportions {
    reach: f64,
    link_w: f64,
    joint_d: f64,
    joint_len: f64,
}

impl Proportions {
    fn of(robot: &Robot) -> Self {
        let reach = robot.reach();
        Proportions {
            reach,
            link_w: reach * 0.035,
            joint_d: reach * 0.07,
            joint_len: reach * 0.09,
        }
    }
}

/// The robot, frames and grid, plus the target marker; also returns the grid spacing.
pub fn build(input: &SceneInput<'_>) -> (Scene, f64) {
    let sizes = Proportions::of(input.robot);
    let mut instances = Vec::with_capacity(64);
    instances.push(base_block(input.robot, &sizes));
    let arm = Arm {
        robot: input.robot,
        fk: input.fk,
        highlighted_link: input.highlighted_link,
    };
    arm_parts(&arm, &sizes, &mut instances);
    if input.show_frames {
        dh_frames(input, &sizes, &mut instances);
    }
    let (lines, step) = ground_grid(sizes.reach);
    marker(input, &mut instances);
    let camera = input.camera;
    let aspect = input.viewport_px[0] / input.viewport_px[1].max(1.0);
    let eye = camera.eye();
    let forward = (camera.focus - eye).normalize();
    // Key light from above, over the viewer's shoulder.
    let light =
        (forward + Vector3::new(0.0, 0.0, -1.2) + forward.cross(&Vector3::z()) * 0.4).normalize();
    (
        Scene {
            view_proj: camera.view_projection(aspect).cast::<f32>(),
            eye: [eye.x as f32, eye.y as f32, eye.z as f32],
            light_dir: [light.x as f32, light.y as f32, light.z as f32],
            background: input.background,
            instances,
            lines,
        },
        step,
    )
}

/// One arm's moving parts: the robot at the frames `fk`, a link to highlight.
struct Arm<'a> {
    robot: &'a Robot,
    fk: &'a ForwardKinematics,
    highlighted_link: Option<usize>,
}

/// Every link with its joint housing, and the gripper.
fn arm_parts(arm: &Arm<'_>, sizes: &Proportions, out: &mut Vec<Instance>) {
    for i in 0..arm.robot.dof() {
        link_parts(arm, i, sizes, out);
    }
    gripper(arm, sizes, out);
}

/// A ghost arm: the moving parts of `robot` at the frames `fk`, every part in `color`
/// (translucent: another IK solution of the same target, drawn beside the arm).
pub fn ghost_instances(robot: &Robot, fk: &ForwardKinematics, color: [u8; 4]) -> Vec<Instance> {
    let sizes = Proportions::of(robot);
    let mut out = Vec::with_capacity(4 * robot.dof() + 6);
    let arm = Arm {
        robot,
        fk,
        highlighted_link: None,
    };
    arm_parts(&arm, &sizes, &mut out);
    for part in &mut out {
        part.color = color;
    }
    out
}

/// The base: a block under frame 0 with its top at z = 0 of the base frame.
fn base_block(robot: &Robot, sizes: &Proportions) -> Instance {
    let base = &robot.world_from_base;
    let reach = sizes.reach;
    let base_size = robot.parts.base.map_or(
        Vector3::new(reach * 0.22, reach * 0.22, reach * 0.06),
        Vector3::from,
    );
    let centre = base * Point3::new(0.0, 0.0, -base_size.z * 0.5);
    instance(Shape::Box, &centre, &base.rotation, base_size, BASE)
}

/// Link `i`'s parts (0-based): the link along its DH offsets from the previous frame's
/// origin, and its joint's housing along the joint axis.
fn link_parts(input: &Arm<'_>, i: usize, sizes: &Proportions, out: &mut Vec<Instance>) {
    let (robot, fk) = (input.robot, input.fk);
    let joint = &robot.joints[i];
    let highlighted = input.highlighted_link == Some(i + 1);
    let color = if highlighted { HIGHLIGHT } else { LINK };
    let prev = if i == 0 {
        robot.world_from_base
    } else {
        fk.base_from_frames[i - 1]
    };
    let frame = fk.base_from_frames[i];
    let o_prev = Point3::from(prev.translation.vector);
    let o = Point3::from(frame.translation.vector);
    // The corner: standard DH goes d along z_{i−1} then a along x_i; modified DH goes a
    // along x_{i−1} then d along z_i.
    let column = match robot.convention {
        Convention::Standard => 2,
        Convention::Modified => 0,
    };
    let along = prev.rotation.matrix().column(column).into_owned();
    let corner = o_prev + along * along.dot(&(o - o_prev));
    let (first, second) = ((o_prev, corner), (corner, o));
    match joint.parts.link {
        // A link of given size: a box along the longer DH offset, centred on it.
        Some([l, w, h]) => {
            let (long, short) = if (first.1 - first.0).norm() >= (second.1 - second.0).norm() {
                (first, second)
            } else {
                (second, first)
            };
            let dir = long.1 - long.0;
            if dir.norm() > 1e-9 {
                let mid = long.0 + dir * 0.5;
                let rot = rotation_to(&dir.normalize());
                out.push(instance(
                    Shape::Box,
                    &mid,
                    &rot,
                    Vector3::new(w, h, l),
                    color,
                ));
            }
            out.extend(segment(
                Shape::Cylinder,
                &short.0,
                &short.1,
                sizes.link_w,
                color,
            ));
        }
        None => {
            out.extend(segment(
                Shape::Cylinder,
                &first.0,
                &first.1,
                sizes.link_w,
                color,
            ));
            out.extend(segment(
                Shape::Cylinder,
                &second.0,
                &second.1,
                sizes.link_w,
                color,
            ));
        }
    }
    out.push(joint_housing(input, i, sizes));
}

/// Joint `i`'s housing along its axis: a cylinder for revolute, a box for prismatic.
fn joint_housing(input: &Arm<'_>, i: usize, sizes: &Proportions) -> Instance {
    let fk = input.fk;
    let at = Point3::from(fk.joint_origins[i]);
    let rot = rotation_to(&fk.joint_axes[i]);
    let (shape, width, own) = match input.robot.joints[i].kind {
        JointKind::Revolute => (Shape::Cylinder, sizes.joint_d, JOINT),
        JointKind::Prismatic => (Shape::Box, sizes.joint_d * 0.8, PRISMATIC),
    };
    let c = if input.highlighted_link == Some(i + 1) {
        HIGHLIGHT
    } else {
        own
    };
    instance(
        shape,
        &at,
        &rot,
        Vector3::new(width, width, sizes.joint_len),
        c,
    )
}

/// The flange and a U-shaped gripper around the tool point: a palm behind it and two
/// fingers reaching past it (outer size from the robot file when given).
fn gripper(input: &Arm<'_>, sizes: &Proportions, out: &mut Vec<Instance>) {
    let (robot, fk) = (input.robot, input.fk);
    let tool = fk.base_from_tool;
    let last = fk
        .base_from_frames
        .last()
        .copied()
        .unwrap_or(robot.world_from_base);
    let o_last = Point3::from(last.translation.vector);
    let o_tool = Point3::from(tool.translation.vector);
    out.extend(segment(
        Shape::Cylinder,
        &o_last,
        &o_tool,
        sizes.link_w * 0.8,
        LINK,
    ));
    let [hand_l, hand_w, hand_h] =
        robot
            .parts
            .hand
            .unwrap_or([sizes.link_w * 0.9, sizes.reach * 0.065, sizes.reach * 0.1]);
    let finger = hand_h * 0.5;
    let z = tool.rotation.matrix().column(2).into_owned();
    let y = tool.rotation.matrix().column(1).into_owned();
    let palm = o_tool - z * finger;
    out.push(instance(
        Shape::Box,
        &palm,
        &tool.rotation,
        Vector3::new(hand_l, hand_w, hand_h * 0.2),
        GRIPPER,
    ));
    let thickness = hand_w * 0.18;
    for side in [-1.0, 1.0] {
        let a = palm + y * (side * (hand_w - thickness) * 0.5);
        let b = a + z * (finger * 1.4);
        out.extend(segment(Shape::Box, &a, &b, thickness, GRIPPER));
    }
}

/// Every DH frame (base, each joint's, tool) as three axis cylinders; the highlighted
/// link's frame drawn thicker.
fn dh_frames(input: &SceneInput<'_>, sizes: &Proportions, out: &mut Vec<Instance>) {
    let len = sizes.reach * 0.09;
    let fk = input.fk;
    let frames = std::iter::once(input.robot.world_from_base)
        .chain(fk.base_from_frames.iter().copied())
        .chain(std::iter::once(fk.base_from_tool));
    for (k, f) in frames.enumerate() {
        let width = if input.highlighted_link == Some(k) {
            len * 0.08
        } else {
            len * 0.045
        };
        let o = Point3::from(f.translation.vector);
        for (c, color) in AXIS.iter().enumerate() {
            let dir = f.rotation.matrix().column(c).into_owned();
            out.extend(segment(
                Shape::Cylinder,
                &o,
                &(o + dir * len),
                width,
                *color,
            ));
        }
    }
}

/// The ground grid at z = 0 with a "nice" spacing, and that spacing (for the scale label).
fn ground_grid(reach: f64) -> (Vec<Line>, f64) {
    let step = nice_step(reach / 4.0);
    let half = (reach * 1.3 / step).ceil() as i32;
    let mut lines = Vec::with_capacity((4 * half + 4) as usize);
    let extent = (half as f64 * step) as f32;
    for k in -half..=half {
        let v = (k as f64 * step) as f32;
        let color = if k == 0 {
            [120, 124, 132, 255]
        } else {
            [70, 74, 82, 255]
        };
        lines.push(Line {
            ends: [[v, -extent, 0.0], [v, extent, 0.0]],
            color,
        });
        lines.push(Line {
            ends: [[-extent, v, 0.0], [extent, v, 0.0]],
            color,
        });
    }
    (lines, step)
}

/// The target marker, drawn on top at a constant size on screen: the ball, an arrow per
/// axis and, for tasks with an orientation, a ring per axis.
fn marker(input: &SceneInput<'_>, out: &mut Vec<Instance>) {
    use super::viewport::marker::Handle;
    let (camera, target, marker) = (input.camera, input.target, input.marker);
    let centre = Point3::from(target.translation.vector);
    let px = camera.world_per_pixel(input.viewport_px[1]) * (camera.eye() - centre).norm()
        / camera.distance;
    let on_top = |mut inst: Instance| {
        inst.on_top = true;
        inst
    };
    let ball_size = Vector3::repeat(2.0 * handle_px::BALL * px);
    let ball = instance(
        Shape::Sphere,
        &centre,
        &Rotation3::identity(),
        ball_size,
        marker.color,
    );
    out.push(on_top(ball));
    for (c, dir) in marker.axes.iter().enumerate() {
        let active = marker.active == Some(Handle::Axis(c));
        let color = if active { HIGHLIGHT } else { AXIS[c] };
        let tip = centre + dir * (handle_px::ARROW * px);
        let shaft_start = centre + dir * (handle_px::BALL * px);
        let shaft_w = if active { 6.0 * px } else { 4.0 * px };
        let head = [12.0 * px, 16.0 * px];
        out.extend(arrow(&shaft_start, &tip, shaft_w, head, color).map(on_top));
        if marker.rings {
            let active = marker.active == Some(Handle::Ring(c));
            let color = if active { HIGHLIGHT } else { AXIS[c] };
            let width = if active { 5.0 * px } else { 3.0 * px };
            let pts = super::viewport::marker::ring_points(&centre, dir, handle_px::RING * px);
            for pair in pts.windows(2) {
                out.extend(segment(Shape::Cylinder, &pair[0], &pair[1], width, color).map(on_top));
            }
        }
    }
}

/// Two unit vectors perpendicular to `dir` and to each other.
pub fn perpendiculars(dir: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let d = Unit::new_normalize(*dir);
    let helper = if d.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let u = d.cross(&helper).normalize();
    let w = d.cross(&u);
    (u, w)
}
