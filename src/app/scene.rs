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
    pub active: Option<super::viewport::Handle>,
}

/// A unit-shape instance stretched from `a` to `b` with this cross-section.
fn segment(
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

/// The rotation taking z to `dir`.
fn rotation_to(dir: &Vector3<f64>) -> Rotation3<f64> {
    Rotation3::rotation_between(&Vector3::z(), dir).unwrap_or_else(|| {
        // dir = −z: any half turn about a horizontal axis.
        Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
    })
}

fn instance(
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
    let SceneInput {
        robot,
        fk,
        camera,
        viewport_px,
        show_frames,
        highlighted_link,
        target,
        marker,
        background,
    } = *input;
    let reach = robot.reach();
    let mut instances = Vec::with_capacity(64);
    let link_w = reach * 0.035;
    let joint_d = reach * 0.07;
    let joint_len = reach * 0.09;

    // Base: a block under frame 0 with its top at z = 0 of the base frame.
    let base = &robot.world_from_base;
    let base_size = robot.parts.base.map_or(
        Vector3::new(reach * 0.22, reach * 0.22, reach * 0.06),
        Vector3::from,
    );
    let centre = base * Point3::new(0.0, 0.0, -base_size.z * 0.5);
    instances.push(instance(
        Shape::Box,
        &centre,
        &base.rotation,
        base_size,
        BASE,
    ));

    // Links along the DH offsets between consecutive frame origins.
    let mut prev = *base;
    for (i, joint) in robot.joints.iter().enumerate() {
        let frame = fk.base_from_frames[i];
        let color = if highlighted_link == Some(i + 1) {
            HIGHLIGHT
        } else {
            LINK
        };
        let o_prev = Point3::from(prev.translation.vector);
        let o = Point3::from(frame.translation.vector);
        // The corner: standard DH goes d along z_{i−1} then a along x_i; modified DH goes a
        // along x_{i−1} then d along z_i.
        let corner = match robot.convention {
            Convention::Standard => {
                let z_prev = prev.rotation.matrix().column(2).into_owned();
                o_prev + z_prev * (z_prev.dot(&(o - o_prev)))
            }
            Convention::Modified => {
                let x_prev = prev.rotation.matrix().column(0).into_owned();
                o_prev + x_prev * (x_prev.dot(&(o - o_prev)))
            }
        };
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
                    instances.push(instance(
                        Shape::Box,
                        &mid,
                        &rotation_to(&dir.normalize()),
                        Vector3::new(w, h, l),
                        color,
                    ));
                }
                instances.extend(segment(Shape::Cylinder, &short.0, &short.1, link_w, color));
            }
            None => {
                instances.extend(segment(Shape::Cylinder, &first.0, &first.1, link_w, color));
                instances.extend(segment(
                    Shape::Cylinder,
                    &second.0,
                    &second.1,
                    link_w,
                    color,
                ));
            }
        }
        // The joint housing along its axis.
        let axis = fk.joint_axes[i];
        let at = Point3::from(fk.joint_origins[i]);
        let rot = rotation_to(&axis);
        match joint.kind {
            JointKind::Revolute => {
                let c = if highlighted_link == Some(i + 1) {
                    HIGHLIGHT
                } else {
                    JOINT
                };
                instances.push(instance(
                    Shape::Cylinder,
                    &at,
                    &rot,
                    Vector3::new(joint_d, joint_d, joint_len),
                    c,
                ));
            }
            JointKind::Prismatic => {
                let c = if highlighted_link == Some(i + 1) {
                    HIGHLIGHT
                } else {
                    PRISMATIC
                };
                instances.push(instance(
                    Shape::Box,
                    &at,
                    &rot,
                    Vector3::new(joint_d * 0.8, joint_d * 0.8, joint_len),
                    c,
                ));
            }
        }
        prev = frame;
    }
    // Tool: a flange disc and a two-finger gripper around the tool point.
    let tool = fk.base_from_tool;
    let last = prev;
    let o_last = Point3::from(last.translation.vector);
    let o_tool = Point3::from(tool.translation.vector);
    instances.extend(segment(
        Shape::Cylinder,
        &o_last,
        &o_tool,
        link_w * 0.8,
        LINK,
    ));
    // A U-shaped gripper around the tool point: a palm behind it and two fingers
    // reaching past it (outer size from the robot file when given).
    let [hand_l, hand_w, hand_h] =
        robot
            .parts
            .hand
            .unwrap_or([link_w * 0.9, reach * 0.065, reach * 0.1]);
    let finger = hand_h * 0.5;
    let z = tool.rotation.matrix().column(2).into_owned();
    let y = tool.rotation.matrix().column(1).into_owned();
    let palm = o_tool - z * finger;
    instances.push(instance(
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
        instances.extend(segment(Shape::Box, &a, &b, thickness, GRIPPER));
    }

    // DH frames.
    if show_frames {
        let len = reach * 0.09;
        let mut frames = vec![*base];
        frames.extend(fk.base_from_frames.iter().copied());
        frames.push(tool);
        for (k, f) in frames.iter().enumerate() {
            let width = if highlighted_link == Some(k) {
                len * 0.08
            } else {
                len * 0.045
            };
            let o = Point3::from(f.translation.vector);
            for (c, color) in AXIS.iter().enumerate() {
                let dir = f.rotation.matrix().column(c).into_owned();
                instances.extend(segment(
                    Shape::Cylinder,
                    &o,
                    &(o + dir * len),
                    width,
                    *color,
                ));
            }
        }
    }

    // Ground grid at z = 0 with a "nice" spacing; returned for the scale label.
    let step = nice_step(reach / 4.0);
    let half = (reach * 1.3 / step).ceil() as i32;
    let mut lines = Vec::with_capacity((4 * half + 4) as usize);
    let extent = half as f64 * step;
    for k in -half..=half {
        let v = k as f64 * step;
        let color = if k == 0 {
            [120, 124, 132, 255]
        } else {
            [70, 74, 82, 255]
        };
        lines.push(Line {
            ends: [
                [v as f32, -extent as f32, 0.0],
                [v as f32, extent as f32, 0.0],
            ],
            color,
        });
        lines.push(Line {
            ends: [
                [-extent as f32, v as f32, 0.0],
                [extent as f32, v as f32, 0.0],
            ],
            color,
        });
    }

    // Target marker: constant size on screen.
    let px = camera.world_per_pixel(viewport_px[1])
        * (camera.eye() - Point3::from(target.translation.vector)).norm()
        / camera.distance;
    let centre = Point3::from(target.translation.vector);
    let mut ball = instance(
        Shape::Sphere,
        &centre,
        &Rotation3::identity(),
        Vector3::repeat(2.0 * handle_px::BALL * px),
        marker.color,
    );
    ball.on_top = true;
    instances.push(ball);
    use super::viewport::Handle;
    for (c, dir) in marker.axes.iter().enumerate() {
        let active = marker.active == Some(Handle::Axis(c));
        let color = if active { HIGHLIGHT } else { AXIS[c] };
        let tip = centre + dir * (handle_px::ARROW * px);
        let cone_len = 16.0 * px;
        let shaft_end = tip - dir * cone_len;
        if let Some(mut s) = segment(
            Shape::Cylinder,
            &(centre + dir * (handle_px::BALL * px)),
            &shaft_end,
            if active { 6.0 * px } else { 4.0 * px },
            color,
        ) {
            s.on_top = true;
            instances.push(s);
        }
        let mut cone = instance(
            Shape::Cone,
            &shaft_end,
            &rotation_to(dir),
            Vector3::new(12.0 * px, 12.0 * px, cone_len),
            color,
        );
        cone.on_top = true;
        instances.push(cone);
        if marker.rings {
            let active = marker.active == Some(Handle::Ring(c));
            let color = if active { HIGHLIGHT } else { AXIS[c] };
            let (u, w) = perpendiculars(dir);
            let n = 48;
            let pts: Vec<Point3<f64>> = (0..=n)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / n as f64;
                    centre + (u * t.cos() + w * t.sin()) * (handle_px::RING * px)
                })
                .collect();
            for pair in pts.windows(2) {
                if let Some(mut s) = segment(
                    Shape::Cylinder,
                    &pair[0],
                    &pair[1],
                    if active { 5.0 * px } else { 3.0 * px },
                    color,
                ) {
                    s.on_top = true;
                    instances.push(s);
                }
            }
        }
    }

    let aspect = viewport_px[0] / viewport_px[1].max(1.0);
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
            background,
            instances,
            lines,
        },
        step,
    )
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
