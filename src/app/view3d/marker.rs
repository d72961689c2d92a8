//! The target marker's geometry, apart from any input or drawing: which handle lies under
//! a screen point, and where a drag of a handle puts the target. Pure functions of the
//! camera, the view's size and the pointer, unit-tested below.

use nalgebra::{IsometryMatrix3, Point3, Rotation3, Unit, Vector3};

use crate::render::camera::OrbitCamera;

/// The screen-size parameters of the target marker, in pixels.
pub mod handle_px {
    /// Radius of the centre ball.
    pub const BALL: f64 = 11.0;
    /// Length of an axis arrow (centre to tip).
    pub const ARROW: f64 = 80.0;
    /// Radius of a rotation ring.
    pub const RING: f64 = 58.0;
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

/// A grabbable part of the target marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Handle {
    /// The centre ball: moves the target in the view plane.
    Ball,
    /// An arrow: moves the target along that axis (0 = x, 1 = y, 2 = z).
    Axis(usize),
    /// A ring: turns the target about that axis.
    Ring(usize),
}

/// The 3D view's placement on screen and the camera looking through it.
#[derive(Debug, Clone, Copy)]
pub struct ViewGeometry<'a> {
    /// The camera.
    pub camera: &'a OrbitCamera,
    /// The view's size in points.
    pub size: [f64; 2],
    /// The view's top-left corner in window points.
    pub origin: [f64; 2],
    /// World length of one point at the target's depth (constant-size handles).
    pub px: f64,
}

impl ViewGeometry<'_> {
    /// The window point of a world point, if it is in front of the camera.
    pub fn project(&self, p: &Point3<f64>) -> Option<[f64; 2]> {
        self.camera
            .project(p, self.size)
            .map(|s| [self.origin[0] + s[0], self.origin[1] + s[1]])
    }

    /// The ray through a window point: origin and unit direction.
    pub fn ray(&self, at: [f64; 2]) -> (Point3<f64>, Vector3<f64>) {
        self.camera
            .ray([at[0] - self.origin[0], at[1] - self.origin[1]], self.size)
    }

    /// The camera's viewing direction.
    fn forward(&self) -> Vector3<f64> {
        (self.camera.focus - self.camera.eye()).normalize()
    }
}

/// What a marker drag remembers from its start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarkerDrag {
    /// The handle held.
    pub handle: Handle,
    /// The target when the drag started.
    pub start_target: IsometryMatrix3<f64>,
    /// The window point where it started.
    pub start_pointer: [f64; 2],
    /// The world point under the pointer at the start (on the view plane through the
    /// target, or on the dragged axis).
    pub start_hit: Point3<f64>,
}

impl MarkerDrag {
    /// Starts a drag of `handle` at window point `at`.
    pub fn start(
        handle: Handle,
        target: &IsometryMatrix3<f64>,
        axes: &[Vector3<f64>; 3],
        view: &ViewGeometry<'_>,
        at: [f64; 2],
    ) -> Self {
        let centre = Point3::from(target.translation.vector);
        let (o, r) = view.ray(at);
        let start_hit = match handle {
            Handle::Axis(i) => closest_on_line(&centre, &axes[i], &o, &r).unwrap_or(centre),
            _ => plane_hit(&centre, &view.forward(), &o, &r).unwrap_or(centre),
        };
        MarkerDrag {
            handle,
            start_target: *target,
            start_pointer: at,
            start_hit,
        }
    }
}

/// Where the target is when the pointer of `drag` is at window point `at`: the ball moves
/// it in the view plane through its start, an arrow along its axis, a ring turns it about
/// its axis by the angle the pointer swept around the target's screen point (clockwise
/// on screen turns clockwise as seen from the side the axis points to).
pub fn drag_marker(
    drag: &MarkerDrag,
    axes: &[Vector3<f64>; 3],
    view: &ViewGeometry<'_>,
    at: [f64; 2],
) -> IsometryMatrix3<f64> {
    let (o, r) = view.ray(at);
    let start_centre = Point3::from(drag.start_target.translation.vector);
    let mut target = drag.start_target;
    match drag.handle {
        Handle::Ball => {
            if let Some(hit) = plane_hit(&drag.start_hit, &view.forward(), &o, &r) {
                target.translation.vector = start_centre.coords + (hit - drag.start_hit);
            }
        }
        Handle::Axis(i) => {
            if let Some(hit) = closest_on_line(&drag.start_hit, &axes[i], &o, &r) {
                target.translation.vector = start_centre.coords + (hit - drag.start_hit);
            }
        }
        Handle::Ring(i) => {
            if let Some(c) = view.project(&start_centre) {
                let angle_of = |p: [f64; 2]| (p[1] - c[1]).atan2(p[0] - c[0]);
                let swept = angle_of(at) - angle_of(drag.start_pointer);
                let to_eye = (view.camera.eye() - start_centre).normalize();
                let facing = if axes[i].dot(&to_eye) >= 0.0 {
                    1.0
                } else {
                    -1.0
                };
                let rot =
                    Rotation3::from_axis_angle(&Unit::new_normalize(axes[i]), -swept * facing);
                target.rotation = rot * drag.start_target.rotation;
            }
        }
    }
    target
}

/// Distance from `p` to the segment `a`–`b` (window points).
pub fn dist_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let ap = [p[0] - a[0], p[1] - a[1]];
    let t = ((ap[0] * ab[0] + ap[1] * ab[1]) / (ab[0] * ab[0] + ab[1] * ab[1]).max(1e-6))
        .clamp(0.0, 1.0);
    let d = [a[0] + ab[0] * t - p[0], a[1] + ab[1] * t - p[1]];
    d[0].hypot(d[1])
}

/// Points around a ring of `radius` about `dir` through `centre`.
pub fn ring_points(centre: &Point3<f64>, dir: &Vector3<f64>, radius: f64) -> Vec<Point3<f64>> {
    let (u, w) = perpendiculars(dir);
    (0..=48)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 48.0;
            centre + (u * t.cos() + w * t.sin()) * radius
        })
        .collect()
}

/// Which handle of a marker at `target` is under window point `at`, if any: the ball
/// first, then the nearest arrow, then the nearest ring (when drawn).
pub fn pick(
    target: &IsometryMatrix3<f64>,
    axes: &[Vector3<f64>; 3],
    rings: bool,
    view: &ViewGeometry<'_>,
    at: [f64; 2],
) -> Option<Handle> {
    let centre = Point3::from(target.translation.vector);
    let c = view.project(&centre)?;
    if (c[0] - at[0]).hypot(c[1] - at[1]) <= handle_px::BALL + 5.0 {
        return Some(Handle::Ball);
    }
    let mut best: Option<(f64, Handle)> = None;
    for (i, dir) in axes.iter().enumerate() {
        if let Some(tip) = view.project(&(centre + dir * (handle_px::ARROW * view.px))) {
            let d = dist_to_segment(at, c, tip);
            if d < 9.0 && best.is_none_or(|(b, _)| d < b) {
                best = Some((d, Handle::Axis(i)));
            }
        }
    }
    if best.is_some() || !rings {
        return best.map(|(_, h)| h);
    }
    for (i, dir) in axes.iter().enumerate() {
        let pts: Vec<[f64; 2]> = ring_points(&centre, dir, handle_px::RING * view.px)
            .iter()
            .filter_map(|p| view.project(p))
            .collect();
        for pair in pts.windows(2) {
            let d = dist_to_segment(at, pair[0], pair[1]);
            if d < 7.0 && best.is_none_or(|(b, _)| d < b) {
                best = Some((d, Handle::Ring(i)));
            }
        }
    }
    best.map(|(_, h)| h)
}

/// Closest point on the line (p0, dir) to the ray (o, r); none when the line points at
/// the camera (no well-defined motion along it).
pub fn closest_on_line(
    p0: &Point3<f64>,
    dir: &Vector3<f64>,
    o: &Point3<f64>,
    r: &Vector3<f64>,
) -> Option<Point3<f64>> {
    let w = p0 - o;
    let (a, b, c) = (dir.dot(dir), dir.dot(r), r.dot(r));
    let (d, e) = (dir.dot(&w), r.dot(&w));
    let denom = a * c - b * b;
    if denom.abs() < 1e-9 * a * c {
        return None;
    }
    let s = (b * e - c * d) / denom;
    Some(p0 + dir * s)
}

/// Where the ray (o, r) meets the plane through `point` with `normal`, if in front.
pub fn plane_hit(
    point: &Point3<f64>,
    normal: &Vector3<f64>,
    o: &Point3<f64>,
    r: &Vector3<f64>,
) -> Option<Point3<f64>> {
    let denom = normal.dot(r);
    if denom.abs() < 1e-9 {
        return None;
    }
    let t = normal.dot(&(point - o)) / denom;
    (t > 0.0).then(|| o + r * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> OrbitCamera {
        let mut camera = OrbitCamera::default();
        camera.fit(Point3::new(0.0, 0.0, 300.0), 1000.0, 800.0 / 600.0);
        camera
    }

    fn view(camera: &OrbitCamera) -> ViewGeometry<'_> {
        ViewGeometry {
            camera,
            size: [800.0, 600.0],
            origin: [100.0, 50.0],
            px: 2.0,
        }
    }

    fn target() -> IsometryMatrix3<f64> {
        IsometryMatrix3::from_parts(
            nalgebra::Translation3::new(400.0, -100.0, 500.0),
            Rotation3::from_euler_angles(0.3, -0.2, 0.5),
        )
    }

    const WORLD: [Vector3<f64>; 3] = [
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.0, 1.0, 0.0),
        Vector3::new(0.0, 0.0, 1.0),
    ];

    #[test]
    fn the_ball_follows_the_pointer_in_the_view_plane() {
        let camera = camera();
        let view = view(&camera);
        let t = target();
        let at = view
            .project(&Point3::from(t.translation.vector))
            .expect("visible");
        assert_eq!(pick(&t, &WORLD, false, &view, at), Some(Handle::Ball));
        let drag = MarkerDrag::start(Handle::Ball, &t, &WORLD, &view, at);
        let to = [at[0] + 40.0, at[1] - 25.0];
        let moved = drag_marker(&drag, &WORLD, &view, to);
        let p = Point3::from(moved.translation.vector);
        let shown = view.project(&p).expect("visible");
        assert!((shown[0] - to[0]).abs() < 1e-6 && (shown[1] - to[1]).abs() < 1e-6);
        let forward = view.forward();
        let depth = (p - Point3::from(t.translation.vector)).dot(&forward);
        assert!(depth.abs() < 1e-9, "stays in the view plane: {depth}");
        assert_eq!(
            moved.rotation, t.rotation,
            "the ball does not turn the target"
        );
    }

    #[test]
    fn an_arrow_moves_the_target_along_its_axis_only() {
        let camera = camera();
        let view = view(&camera);
        let t = target();
        let centre = Point3::from(t.translation.vector);
        let along = view
            .project(&(centre + WORLD[2] * (60.0 * view.px)))
            .expect("visible");
        assert_eq!(pick(&t, &WORLD, false, &view, along), Some(Handle::Axis(2)));
        let drag = MarkerDrag::start(Handle::Axis(2), &t, &WORLD, &view, along);
        let moved = drag_marker(&drag, &WORLD, &view, [along[0] + 30.0, along[1] - 60.0]);
        let delta = moved.translation.vector - t.translation.vector;
        assert!(delta.z.abs() > 1.0, "it moved along z: {delta:?}");
        assert!(delta.x.abs() < 1e-9 && delta.y.abs() < 1e-9, "{delta:?}");
    }

    #[test]
    fn a_ring_turns_the_target_about_its_axis_in_place() {
        let camera = camera();
        let view = view(&camera);
        let t = target();
        let axes = [0, 1, 2].map(|c| t.rotation.matrix().column(c).into_owned());
        let c = view
            .project(&Point3::from(t.translation.vector))
            .expect("visible");
        let drag = MarkerDrag {
            handle: Handle::Ring(0),
            start_target: t,
            start_pointer: [c[0] + 50.0, c[1]],
            start_hit: Point3::from(t.translation.vector),
        };
        // A quarter turn of the pointer around the target's screen point.
        let turned = drag_marker(&drag, &axes, &view, [c[0], c[1] + 50.0]);
        assert_eq!(turned.translation, t.translation);
        let relative = t.rotation.inverse() * turned.rotation;
        let (axis, angle) = relative.axis_angle().expect("a turn");
        assert!(
            (angle - std::f64::consts::FRAC_PI_2).abs() < 1e-9,
            "{angle}"
        );
        assert!(
            (axis.x.abs() - 1.0).abs() < 1e-9,
            "about the target's own x: {axis:?}"
        );
    }

    #[test]
    fn nothing_is_picked_away_from_the_marker() {
        let camera = camera();
        let view = view(&camera);
        let t = target();
        let c = view
            .project(&Point3::from(t.translation.vector))
            .expect("visible");
        assert_eq!(
            pick(&t, &WORLD, true, &view, [c[0] + 300.0, c[1] + 200.0]),
            None
        );
    }

    #[test]
    fn segment_distance_and_line_geometry() {
        assert!((dist_to_segment([0.0, 1.0], [-1.0, 0.0], [1.0, 0.0]) - 1.0).abs() < 1e-12);
        assert!((dist_to_segment([3.0, 4.0], [0.0, 0.0], [0.0, 0.0]) - 5.0).abs() < 1e-12);
        let hit = plane_hit(
            &Point3::new(0.0, 0.0, 5.0),
            &Vector3::z(),
            &Point3::origin(),
            &Vector3::new(0.0, 0.6, 0.8),
        )
        .expect("in front");
        assert!((hit - Point3::new(0.0, 3.75, 5.0)).norm() < 1e-12);
        let on_line = closest_on_line(
            &Point3::origin(),
            &Vector3::x(),
            &Point3::new(2.0, 0.0, 10.0),
            &-Vector3::z(),
        )
        .expect("not parallel");
        assert!((on_line - Point3::new(2.0, 0.0, 0.0)).norm() < 1e-12);
    }
}
