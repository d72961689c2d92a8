//! The planned paths and waypoints in the 3D view: both paths as lines, the waypoints as
//! balls, and the places where a path fails labelled over the picture.

use armlab_text::Name;
use egui::Color32;
use nalgebra::Point3;

use crate::render::{Instance, Line, Shape};
use armlab_core::path::{Path, PathKind};

use crate::app::state::model::Model;
use crate::app::widgets::style;

/// The joint-space path's colour (blue).
pub const JOINT_COLOR: Color32 = Color32::from_rgb(90, 170, 255);

/// The straight line's colour (magenta).
pub const LINE_COLOR: Color32 = Color32::from_rgb(240, 110, 220);

/// The waypoint markers' colour (teal).
const WAYPOINT_COLOR: Color32 = Color32::from_rgb(60, 210, 190);

/// The straight line's problems (of the drawn plan, or of a visit along the line).
pub fn problem_path(model: &Model) -> Option<&Path> {
    let paths = model.paths();
    paths.plan().map(|p| &p.line).or_else(|| {
        paths
            .visit()
            .filter(|_| paths.kind() == PathKind::Cartesian)
            .map(|v| &v.path)
    })
}

/// A path as line segments of one colour.
fn path_lines(path: &Path, color: Color32, out: &mut Vec<Line>) {
    let f = |p: Point3<f64>| [p.x as f32, p.y as f32, p.z as f32];
    let points: Vec<[f32; 3]> = path.tool_positions().map(f).collect();
    out.extend(points.windows(2).map(|w| Line {
        ends: [w[0], w[1]],
        color: [color.r(), color.g(), color.b(), 255],
    }));
}

/// The planned paths (or the visit's), the waypoints and the straight line's problem
/// places for the 3D view.
pub fn scene_parts(model: &Model, lines: &mut Vec<Line>, instances: &mut Vec<Instance>) {
    let paths = model.paths();
    if let Some(plan) = paths.plan() {
        path_lines(&plan.joint, JOINT_COLOR, lines);
        path_lines(&plan.line, LINE_COLOR, lines);
    } else if let Some(visit) = paths.visit() {
        let color = match paths.kind() {
            PathKind::Joint => JOINT_COLOR,
            PathKind::Cartesian => LINE_COLOR,
        };
        path_lines(&visit.path, color, lines);
    }
    let size = nalgebra::Vector3::repeat(model.robot().reach() * 0.03);
    let ball = |at: &Point3<f64>, c: Color32| {
        crate::app::view3d::scene::instance(
            Shape::Sphere,
            at,
            &nalgebra::Rotation3::identity(),
            size,
            [c.r(), c.g(), c.b(), 255],
        )
    };
    for pose in paths.waypoints().poses() {
        instances.push(ball(&Point3::from(pose.translation.vector), WAYPOINT_COLOR));
    }
    for (at, _) in problem_places(model) {
        instances.push(ball(&at, style::UNREACHABLE));
    }
}

/// Where the straight line's problems are, with their short names (those of one step
/// together: "out of reach, singular").
fn problem_places(model: &Model) -> Vec<(Point3<f64>, String)> {
    let lang = model.settings().lang;
    let mut places: Vec<(usize, Point3<f64>, String)> = Vec::new();
    for p in problem_path(model).map_or(&[][..], |path| &path.problems) {
        let name = p.issue.name(lang);
        match places.last_mut() {
            Some((index, _, names)) if *index == p.index => *names = format!("{names}, {name}"),
            _ => {
                if let Some(point) = problem_path(model).and_then(|path| path.points.get(p.index)) {
                    let at = Point3::from(point.tool.translation.vector);
                    places.push((p.index, at, name.to_string()));
                }
            }
        }
    }
    places
        .into_iter()
        .map(|(_, at, names)| (at, names))
        .collect()
}

/// The waypoints' numbers and the problems' names over the 3D picture.
pub fn draw_in_view(
    model: &Model,
    painter: &egui::Painter,
    project: &dyn Fn(&Point3<f64>) -> Option<egui::Pos2>,
) {
    let font = egui::FontId::proportional(14.0);
    // Labels of nearby places (a singularity and a jump a few steps apart) would overlap:
    // each one moves up a line at a time past those already drawn.
    let mut taken: Vec<egui::Rect> = Vec::new();
    let mut label = |at: &Point3<f64>, text: String, color: Color32| {
        let Some(p) = project(at) else {
            return;
        };
        let galley = painter.layout_no_wrap(text, font.clone(), color);
        let size = galley.size();
        let rect = free_place(
            &taken,
            egui::Rect::from_min_size(p + egui::vec2(8.0, -8.0 - size.y), size),
        );
        taken.push(rect);
        painter.galley(rect.min, galley, color);
    };
    for (i, pose) in model.paths().waypoints().poses().iter().enumerate() {
        let at = Point3::from(pose.translation.vector);
        label(&at, format!("{}", i + 1), WAYPOINT_COLOR);
    }
    for (at, name) in problem_places(model) {
        label(&at, name, style::UNREACHABLE);
    }
}

/// `rect` moved up a line (its height) at a time, at most eight lines, until it overlaps
/// none of `taken`.
fn free_place(taken: &[egui::Rect], mut rect: egui::Rect) -> egui::Rect {
    for _ in 0..8 {
        if !taken.iter().any(|r| r.intersects(rect)) {
            break;
        }
        rect = rect.translate(egui::vec2(0.0, -rect.height()));
    }
    rect
}

/// The waypoints' screen points for the browser tests (`waypoint-1`, …).
pub fn points(model: &Model, mut add: impl FnMut(String, &Point3<f64>)) {
    for (i, pose) in model.paths().waypoints().poses().iter().enumerate() {
        add(
            format!("waypoint-{}", i + 1),
            &Point3::from(pose.translation.vector),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::free_place;
    use egui::{Rect, pos2, vec2};

    #[test]
    fn labels_of_nearby_places_move_up_past_each_other() {
        let line = |x: f32, y: f32| Rect::from_min_size(pos2(x, y), vec2(60.0, 16.0));
        // Nothing in the way: the label stays.
        assert_eq!(free_place(&[], line(100.0, 200.0)), line(100.0, 200.0));
        // Two labels a few pixels apart: the second goes up until clear of the first.
        let first = line(100.0, 200.0);
        let second = free_place(&[first], line(110.0, 205.0));
        assert_eq!(second, line(110.0, 173.0));
        assert!(!second.intersects(first));
        let third = free_place(&[first, second], line(104.0, 198.0));
        assert!(
            !third.intersects(first) && !third.intersects(second),
            "{third:?}"
        );
        // Labels far apart keep their places.
        assert_eq!(free_place(&[first], line(300.0, 200.0)), line(300.0, 200.0));
    }
}
