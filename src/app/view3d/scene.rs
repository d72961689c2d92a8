//! Builds the 3D scene from the core's frames: the arm's parts as the core derives them
//! (`kinematics::parts`: a base, a cylinder at each joint along its axis, a box for
//! prismatic joints, links along the DH offsets, a gripper at the tool), the DH frames,
//! the ground grid and the target marker with its handles. Pure geometry: no kinematics
//! is computed here.

use nalgebra::{Matrix4, Point3, Rotation3, Vector3};

use crate::render::camera::OrbitCamera;
use crate::render::{Instance, Line, Scene, Shape};
pub(crate) use armlab_core::parts::rotation_to;
use armlab_core::parts::{Part, PartKind, PartShape, Proportions, robot_parts};
use armlab_core::{ForwardKinematics, Robot};

use crate::app::view3d::marker::handle_px;

const LINK: [u8; 4] = [196, 202, 210, 255];
const JOINT: [u8; 4] = [52, 120, 196, 255];
const PRISMATIC: [u8; 4] = [220, 140, 40, 255];
const BASE: [u8; 4] = [88, 92, 100, 255];
const GRIPPER: [u8; 4] = [70, 74, 80, 255];
const HIGHLIGHT: [u8; 4] = [255, 210, 60, 255];
/// The x, y and z axis colours of every drawn frame.
pub(crate) const AXIS: [[u8; 4]; 3] = [[230, 60, 50, 255], [60, 190, 70, 255], [60, 110, 240, 255]];

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
    pub active: Option<crate::app::view3d::marker::Handle>,
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

/// The robot, frames and grid, plus the target marker; also returns the grid spacing.
pub fn build(input: &SceneInput<'_>) -> (Scene, f64) {
    let sizes = Proportions::of(input.robot);
    let mut instances = Vec::with_capacity(64);
    for part in robot_parts(input.robot, input.fk) {
        instances.push(part_instance(&part, input.highlighted_link));
    }
    let (lines, step) = ground_grid(sizes.reach);
    marker(input, &mut instances);
    // After the marker: a frame at the target is drawn over it.
    if input.show_frames {
        dh_frames(input, &sizes, &mut instances);
    }
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

/// A part of the arm (from the core's [`robot_parts`]) as a drawn instance, coloured by
/// its kind; the highlighted link's link parts and housing in the highlight colour.
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

/// A ghost arm: the moving parts of `robot` at the frames `fk` (not its base), every part
/// in `color` (translucent: another IK solution of the same target, drawn beside the arm).
pub fn ghost_instances(robot: &Robot, fk: &ForwardKinematics, color: [u8; 4]) -> Vec<Instance> {
    robot_parts(robot, fk)
        .iter()
        .filter(|p| p.kind != PartKind::Base)
        .map(|p| Instance {
            color,
            ..part_instance(p, None)
        })
        .collect()
}

fn part_instance(part: &Part, highlighted_link: Option<usize>) -> Instance {
    let highlighted = highlighted_link == Some(part.body);
    let color = match part.kind {
        PartKind::Base => BASE,
        PartKind::Link | PartKind::Housing if highlighted => HIGHLIGHT,
        PartKind::Link | PartKind::Flange => LINK,
        PartKind::Housing => match part.shape {
            PartShape::Cylinder => JOINT,
            PartShape::Box => PRISMATIC,
        },
        PartKind::Palm | PartKind::Finger => GRIPPER,
    };
    let shape = match part.shape {
        PartShape::Box => Shape::Box,
        PartShape::Cylinder => Shape::Cylinder,
    };
    instance(shape, &part.centre, &part.rotation, part.size, color)
}

/// A DH frame's axis length, drawn and labelled: 9 % of the reach.
pub(crate) fn frame_axis_length(reach: f64) -> f64 {
    reach * 0.09
}

/// Every DH frame (base, each joint's, tool) as three axis cylinders; the highlighted
/// link's frame drawn thicker. A frame within the target marker's rings (the wrist's and
/// the tool's once the target is reached) is drawn on top of the marker, not hidden
/// under it.
fn dh_frames(input: &SceneInput<'_>, sizes: &Proportions, out: &mut Vec<Instance>) {
    let len = frame_axis_length(sizes.reach);
    let fk = input.fk;
    let camera = input.camera;
    let target = Point3::from(input.target.translation.vector);
    let px = camera.world_per_pixel(input.viewport_px[1]) * (camera.eye() - target).norm()
        / camera.distance;
    let near_target = |o: &Point3<f64>| (o - target).norm() <= handle_px::RING * px * 1.3;
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
        let on_top = near_target(&o);
        for (c, color) in AXIS.iter().enumerate() {
            let dir = f.rotation.matrix().column(c).into_owned();
            out.extend(
                segment(Shape::Cylinder, &o, &(o + dir * len), width, *color).map(|mut i| {
                    i.on_top = on_top;
                    i
                }),
            );
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
    use crate::app::view3d::marker::Handle;
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
            // Thin, so the wrist's and the tool's frames show through them.
            let width = if active { 3.5 * px } else { 1.5 * px };
            let pts = crate::app::view3d::marker::ring_points(&centre, dir, handle_px::RING * px);
            for pair in pts.windows(2) {
                out.extend(segment(Shape::Cylinder, &pair[0], &pair[1], width, color).map(on_top));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tool's frame, at a reached target, is drawn over the target's marker.
    #[test]
    fn the_tool_frame_at_the_target_is_drawn_over_the_marker() {
        let robot = armlab_core::preset("ur10").expect("a preset");
        let q: Vec<f64> = robot.joints.iter().map(|j| j.home).collect();
        let fk = ForwardKinematics::new(&robot, &q).expect("a pose");
        let mut camera = OrbitCamera::default();
        camera.fit(Point3::origin(), robot.reach(), 1.0);
        let target = fk.base_from_tool;
        let marker = MarkerLook {
            color: [0, 200, 0, 255],
            axes: [0, 1, 2].map(|c| target.rotation.matrix().column(c).into_owned()),
            rings: true,
            active: None,
        };
        let (scene, _) = build(&SceneInput {
            robot: &robot,
            fk: &fk,
            camera: &camera,
            viewport_px: [700.0, 700.0],
            show_frames: true,
            highlighted_link: None,
            target: &target,
            marker: &marker,
            background: [0, 0, 0],
        });
        let len = frame_axis_length(robot.reach());
        let o = target.translation.vector;
        for (c, color) in AXIS.iter().enumerate() {
            let mid = o + target.rotation.matrix().column(c) * (len * 0.5);
            let axis = scene.instances.iter().find(|i| {
                i.shape == Shape::Cylinder
                    && i.color == *color
                    && (i.model.column(3).xyz().cast::<f64>() - mid).norm() < len * 1e-3
            });
            let axis = axis.expect("the tool frame's axis is drawn");
            assert!(
                axis.on_top,
                "axis {c} of the tool frame is drawn over the marker"
            );
        }
        // The base's frame, far from the target, keeps the depth test.
        let base_z = scene.instances.iter().find(|i| {
            i.shape == Shape::Cylinder
                && i.color == AXIS[2]
                && (i.model.column(3).xyz().cast::<f64>() - Vector3::new(0.0, 0.0, len * 0.5))
                    .norm()
                    < len * 1e-3
        });
        assert!(!base_z.expect("the base's z axis").on_top);
    }
}
