//! The Jacobian drawn at the tool (docs/kinematics.md §6.1): each column's linear part as
//! an arrow (the tool's velocity per unit speed of that joint), its angular part on a
//! switch, and the velocity or force manipulability ellipsoid of the linear rows with the
//! lost direction near a singularity. Pure geometry: instances for the renderer.

use nalgebra::{Matrix3, Matrix6xX, Point3, Rotation3, Vector3};

use crate::app::view3d::scene::{arrow, instance, segment};
use crate::render::{Instance, Shape};
use armlab_core::redundancy::null_direction;
use armlab_core::{ForwardKinematics, Robot, Task, tool_velocity};
use armlab_session::settings::{Overlay, OverlaySet};

/// The colours of the Jacobian's columns (joint 1, 2, …; repeating after eight), in the
/// 3D view and the matrices panel's legend alike.
pub const COLUMN_COLORS: [[u8; 3]; 8] = [
    [230, 80, 70],
    [240, 160, 40],
    [200, 200, 60],
    [80, 190, 90],
    [60, 180, 200],
    [90, 120, 240],
    [180, 100, 230],
    [230, 110, 180],
];

/// The colour of column `i`.
pub fn column_color(i: usize) -> [u8; 3] {
    COLUMN_COLORS[i % COLUMN_COLORS.len()]
}

/// The linear rows' principal directions (columns, a right-handed rotation) and their
/// singular values (same order), largest first.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearSvd {
    /// Unit principal directions of the velocity ellipsoid in the base frame.
    pub axes: Matrix3<f64>,
    /// Semi-axes of the velocity ellipsoid (length units per unit joint speed).
    pub sigma: [f64; 3],
}

impl LinearSvd {
    /// The SVD of the 3×n linear rows of `j` (three directions even with fewer joints:
    /// the missing ones have σ = 0).
    pub fn of(j: &Matrix6xX<f64>) -> Option<LinearSvd> {
        // Eigen-decomposition of J_v·J_vᵀ (3×3, symmetric): its eigenvectors are the left
        // singular vectors and its eigenvalues σ².
        let jv = j.fixed_rows::<3>(0);
        let gram: Matrix3<f64> = jv * jv.transpose();
        if !gram.iter().all(|v| v.is_finite()) {
            return None;
        }
        let eigen = gram.symmetric_eigen();
        let mut order = [0usize, 1, 2];
        order.sort_by(|a, b| eigen.eigenvalues[*b].total_cmp(&eigen.eigenvalues[*a]));
        let mut axes =
            Matrix3::from_columns(&order.map(|k| eigen.eigenvectors.column(k).into_owned()));
        if axes.determinant() < 0.0 {
            axes.set_column(2, &(-axes.column(2)));
        }
        let sigma = order.map(|k| eigen.eigenvalues[k].max(0.0).sqrt());
        Some(LinearSvd { axes, sigma })
    }
}

/// Everything the overlays are drawn from.
pub struct JacobianScene<'a> {
    /// The geometric Jacobian (6 × n, base frame).
    pub jacobian: &'a Matrix6xX<f64>,
    /// The tool's position in the base frame.
    pub tool: Point3<f64>,
    /// The arm's reach: sizes are fractions of it.
    pub reach: f64,
    /// Which overlays to draw.
    pub overlays: OverlaySet,
    /// The column under the pointer (drawn thicker and brighter).
    pub hovered: Option<usize>,
    /// The robot, its joint values and the task (for the self-motion's arrows).
    pub robot: &'a Robot,
    /// The joint values.
    pub q: &'a [f64],
    /// The IK task (its rows define the null space).
    pub task: Task,
    /// The joint speeds q̇ (for v and ω).
    pub speeds: Vec<f64>,
    /// The direction the tool cannot move in at this singular pose, if it is one
    /// ([`crate::app::state::model::Model::lost_direction`]).
    pub lost: Option<Vector3<f64>>,
}

/// Arrow tips of the linear columns, in the base frame: the longest column is 0.3 × the
/// reach (the arrows compare the columns; their common scale is not a unit).
pub fn column_tips(scene: &JacobianScene<'_>) -> Vec<Point3<f64>> {
    let jv = scene.jacobian.fixed_rows::<3>(0);
    let longest = jv.column_iter().map(|c| c.norm()).fold(0.0, f64::max);
    let k = if longest > 0.0 {
        0.3 * scene.reach / longest
    } else {
        0.0
    };
    jv.column_iter()
        .map(|c| scene.tool + c.into_owned() * k)
        .collect()
}

/// The overlays' instances: the ellipsoids last (they are translucent).
pub fn instances(scene: &JacobianScene<'_>, out: &mut Vec<Instance>) {
    if scene.overlays.contains(Overlay::JacobianColumns) {
        linear_columns(scene, out);
    }
    if scene.overlays.contains(Overlay::AngularColumns) {
        angular_columns(scene, out);
    }
    let r = scene.reach;
    if scene.overlays.contains(Overlay::NullSpace) {
        for (origin, tip) in null_space_motion(scene) {
            out.extend(arrow(
                &origin,
                &tip,
                r * 0.007,
                [r * 0.025, r * 0.04],
                [240, 240, 240, 255],
            ));
        }
    }
    if scene.overlays.contains(Overlay::Twist) {
        twist(scene, out);
    }
    ellipsoids(scene, out);
}

fn column_rgba(i: usize, alpha: u8) -> [u8; 4] {
    let [r, g, b] = column_color(i);
    [r, g, b, alpha]
}

fn column_width(scene: &JacobianScene<'_>, i: usize) -> f64 {
    let thick = if scene.hovered == Some(i) { 2.0 } else { 1.0 };
    scene.reach * 0.008 * thick
}

fn linear_columns(scene: &JacobianScene<'_>, out: &mut Vec<Instance>) {
    let r = scene.reach;
    for (i, tip) in column_tips(scene).iter().enumerate() {
        let head = [r * 0.03, r * 0.05];
        out.extend(arrow(
            &scene.tool,
            tip,
            column_width(scene, i),
            head,
            column_rgba(i, 255),
        ));
    }
}

/// Unit axes for revolute joints (zero for prismatic ones), 0.15 × the reach long, thin,
/// with a bead to tell them from the linear arrows.
fn angular_columns(scene: &JacobianScene<'_>, out: &mut Vec<Instance>) {
    let r = scene.reach;
    for (i, w) in scene.jacobian.fixed_rows::<3>(3).column_iter().enumerate() {
        let w = w.into_owned();
        let (color, width) = (column_rgba(i, 200), column_width(scene, i) * 0.6);
        out.extend(arrow(
            &scene.tool,
            &(scene.tool + w * (0.15 * r)),
            width,
            [r * 0.02, r * 0.035],
            color,
        ));
        if w.norm() > 0.5 {
            let bead = Vector3::repeat(r * 0.018);
            out.push(instance(
                Shape::Sphere,
                &(scene.tool + w * (0.1 * r)),
                &Rotation3::identity(),
                bead,
                color,
            ));
        }
    }
}

/// v = J_v q̇ (one second of it, at most half the reach; white) and ω = J_ω q̇ (0.15 × the
/// reach per rad/s; magenta).
fn twist(scene: &JacobianScene<'_>, out: &mut Vec<Instance>) {
    let r = scene.reach;
    let twist = tool_velocity(scene.jacobian, &scene.speeds);
    let v = twist.fixed_rows::<3>(0).into_owned();
    let w = twist.fixed_rows::<3>(3).into_owned();
    if v.norm() > 0.0 {
        let tip = scene.tool + v.normalize() * v.norm().min(0.5 * r);
        out.extend(arrow(
            &scene.tool,
            &tip,
            r * 0.012,
            [r * 0.035, r * 0.06],
            [255, 255, 255, 255],
        ));
    }
    let tip = scene.tool + w * (0.15 * r);
    out.extend(arrow(
        &scene.tool,
        &tip,
        r * 0.008,
        [r * 0.025, r * 0.045],
        [255, 120, 255, 255],
    ));
}

/// The velocity and force ellipsoids of the linear rows, and the lost direction (red)
/// near a singularity.
fn ellipsoids(scene: &JacobianScene<'_>, out: &mut Vec<Instance>) {
    let velocity = scene.overlays.contains(Overlay::VelocityEllipsoid);
    let force = scene.overlays.contains(Overlay::ForceEllipsoid);
    let Some(svd) = LinearSvd::of(scene.jacobian).filter(|_| velocity || force) else {
        return;
    };
    let r = scene.reach;
    if let Some(lost) = scene.lost {
        let (a, b) = (
            scene.tool - lost * (0.35 * r),
            scene.tool + lost * (0.35 * r),
        );
        out.extend(segment(
            Shape::Cylinder,
            &a,
            &b,
            r * 0.01,
            [255, 80, 60, 255],
        ));
    }
    if velocity {
        out.push(ellipsoid(
            scene,
            &svd,
            velocity_axes(&svd, r),
            [120, 200, 255, 70],
        ));
    }
    if force {
        out.push(ellipsoid(
            scene,
            &svd,
            force_axes(&svd, r),
            [255, 170, 90, 70],
        ));
    }
}

/// Velocity ellipsoid semi-axes: σ_i, scaled so the largest is 0.25 × the reach.
pub fn velocity_axes(svd: &LinearSvd, reach: f64) -> [f64; 3] {
    let k = if svd.sigma[0] > 0.0 {
        0.25 * reach / svd.sigma[0]
    } else {
        0.0
    };
    svd.sigma.map(|s| s * k)
}

/// Force ellipsoid semi-axes: 1/σ_i (the force the tool can resist per unit joint torque
/// is largest where it moves least), scaled so the smallest is 0.08 × the reach and
/// capped at 0.6 × the reach along a lost direction.
pub fn force_axes(svd: &LinearSvd, reach: f64) -> [f64; 3] {
    let largest = svd.sigma[0];
    svd.sigma.map(|s| {
        if s > 0.0 && largest > 0.0 {
            (0.08 * reach * largest / s).min(0.6 * reach)
        } else {
            0.6 * reach
        }
    })
}

fn ellipsoid(
    scene: &JacobianScene<'_>,
    svd: &LinearSvd,
    semi_axes: [f64; 3],
    color: [u8; 4],
) -> Instance {
    let floor = scene.reach * 0.004;
    let scale = Vector3::from(semi_axes.map(|a| 2.0 * a.max(floor)));
    let rot = Rotation3::from_matrix_unchecked(svd.axes);
    instance(Shape::Sphere, &scene.tool, &rot, scale, color)
}

/// How every joint origin and the tool move along the self-motion's direction: arrows
/// from each origin along its displacement for a step along the null direction, the
/// largest 0.2 × the reach (the tool's is zero up to rounding: it does not move).
pub fn null_space_motion(scene: &JacobianScene<'_>) -> Vec<(Point3<f64>, Point3<f64>)> {
    let Ok(dir) = null_direction(scene.robot, scene.q, scene.task) else {
        return Vec::new();
    };
    let eps = 1e-4;
    let shifted = |sign: f64| -> Option<Vec<Point3<f64>>> {
        let q: Vec<f64> = scene
            .q
            .iter()
            .zip(dir.iter())
            .map(|(q, d)| q + sign * eps * d)
            .collect();
        let fk = ForwardKinematics::new(scene.robot, &q).ok()?;
        Some(
            fk.base_from_frames
                .iter()
                .map(|f| Point3::from(f.translation.vector))
                .collect(),
        )
    };
    let (Some(plus), Some(minus)) = (shifted(1.0), shifted(-1.0)) else {
        return Vec::new();
    };
    let motion: Vec<(Point3<f64>, Vector3<f64>)> = plus
        .iter()
        .zip(&minus)
        .map(|(a, b)| {
            (
                Point3::from((a.coords + b.coords) / 2.0),
                (a - b) / (2.0 * eps),
            )
        })
        .collect();
    let largest = motion.iter().map(|(_, v)| v.norm()).fold(0.0, f64::max);
    if largest <= 0.0 {
        return Vec::new();
    }
    let k = 0.2 * scene.reach / largest;
    motion
        .into_iter()
        .filter(|(_, v)| v.norm() * k > 0.01 * scene.reach)
        .map(|(o, v)| (o, o + v * k))
        .collect()
}
