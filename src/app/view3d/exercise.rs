//! The DH exercise's joint axes and dimensions drawn over the 3D picture: each distance
//! and angle between neighbouring axes along their common normal, labelled.

use nalgebra::{Point3, Vector3};

use armlab_core::{ForwardKinematics, Robot};
use armlab_text::Key;

use super::labels::{self, Placed, Placer};
use crate::app::state::model::Model;
use crate::app::state::trf;
use crate::app::widgets::style;
use armlab_session::format::number;

/// Angles between axes below this (radians) are drawn as parallel.
const ANGLE_TINY: f64 = 1e-9;

/// What a dimension measures; axes count from 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measures {
    /// From the base's origin to the nearest point of this axis.
    BaseTo(usize),
    /// Along this axis, between the two normals that meet it (a d of any table).
    Along(usize),
    /// The common normal of this axis and the next (an a and α of any table).
    Normal(usize),
    /// From this axis to the tool point.
    ToTool(usize),
}

/// A measured distance or angle of the drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dimension {
    /// What it measures.
    pub measures: Measures,
    /// One end (world).
    pub from: Vector3<f64>,
    /// The other end (world).
    pub to: Vector3<f64>,
    /// Its length (robot units).
    pub length: f64,
    /// For a common normal between two axes: the angle between them (radians, 0…π).
    pub angle: Option<f64>,
}

/// The feet of the common normal of the lines `p1 + s·d1` and `p2 + t·d2` (unit
/// directions): the closest points. Parallel lines have no single normal: the one
/// through `at` (a point on the first line) is taken, so the drawing does not depend on
/// where a table puts its frames.
fn common_normal(
    (p1, d1): (&Vector3<f64>, &Vector3<f64>),
    (p2, d2): (&Vector3<f64>, &Vector3<f64>),
    at: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let b = d1.dot(d2);
    let w = p1 - p2;
    let (d, e) = (d1.dot(&w), d2.dot(&w));
    let denom = 1.0 - b * b;
    if denom < 1e-12 {
        return (*at, p2 + d2 * d2.dot(&(at - p2)));
    }
    let s = (b * e - d) / denom;
    let t = (e - b * d) / denom;
    (p1 + d1 * s, p2 + d2 * t)
}

/// What the exercise draws (docs/kinematics.md §15): along the chain base → axis 1 → … →
/// axis n → tool point, the common normal between neighbouring axes (its length and the
/// angle between the axes: a and α in any DH table) and the distance along each axis
/// between the normals that meet it (d). These do not depend on the convention, nor on q
/// for revolute joints. Lengths below 1e−6 of the reach are left out.
pub fn dimensions(robot: &Robot, fk: &ForwardKinematics) -> Vec<Dimension> {
    let n = fk.joint_axes.len();
    let tiny = robot.reach() * 1e-6;
    let base = robot.world_from_base.translation.vector;
    let tool = fk.base_from_tool.translation.vector;
    let mut out = Vec::new();
    let mut push = |measures, from: Vector3<f64>, to: Vector3<f64>, angle: Option<f64>| {
        let length = (to - from).norm();
        if length > tiny || angle.is_some_and(|a| a > ANGLE_TINY) {
            out.push(Dimension {
                measures,
                from,
                to,
                length,
                angle,
            });
        }
    };
    if n == 0 {
        return out;
    }
    let axis = |i: usize| (fk.joint_origins[i], fk.joint_axes[i]);
    let foot = |p: &Vector3<f64>, (o, z): (Vector3<f64>, Vector3<f64>)| o + z * z.dot(&(p - o));
    // Where each axis meets the normal from the one before (or the base) and the one
    // after (or the tool).
    let mut arrive = foot(&base, axis(0));
    push(Measures::BaseTo(1), base, arrive, None);
    for i in 0..n {
        let (o, z) = axis(i);
        let leave = if i + 1 < n {
            let (o2, z2) = axis(i + 1);
            let (c1, c2) = common_normal((&o, &z), (&o2, &z2), &arrive);
            // atan2 of |z × z2| and z · z2: exact near 0 and π, where acos is not.
            (c1, Some((c2, z.cross(&z2).norm().atan2(z.dot(&z2)))))
        } else {
            (foot(&tool, axis(i)), None)
        };
        push(Measures::Along(i + 1), arrive, leave.0, None);
        match leave.1 {
            Some((next, angle)) => {
                push(Measures::Normal(i + 1), leave.0, next, Some(angle));
                arrive = next;
            }
            None => push(Measures::ToTool(i + 1), leave.0, tool, None),
        }
    }
    out
}

/// Each joint axis as drawn: from behind its origin to its arrowhead (world), sized to
/// the drawing rather than to the reach, so a folded arm's arrows do not dwarf it.
fn axis_ends(robot: &Robot, fk: &ForwardKinematics, dims: &[Dimension]) -> Vec<[Vector3<f64>; 2]> {
    let mut points: Vec<Vector3<f64>> = fk.joint_origins.clone();
    points.extend(dims.iter().flat_map(|d| [d.from, d.to]));
    let (_, extent) = bounds(&points);
    let length = extent.max(robot.reach() * 0.1);
    fk.joint_origins
        .iter()
        .zip(&fk.joint_axes)
        .map(|(o, z)| [o - z * 0.25 * length, o + z * 0.35 * length])
        .collect()
}

/// The centre of the box around `points`, and the farthest point's distance from it.
pub fn bounds(points: &[Vector3<f64>]) -> (Vector3<f64>, f64) {
    let Some(first) = points.first() else {
        return (Vector3::zeros(), 0.0);
    };
    let (lo, hi) = points
        .iter()
        .fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let centre = (lo + hi) * 0.5;
    let radius = points
        .iter()
        .map(|p| (p - centre).norm())
        .fold(0.0, f64::max);
    (centre, radius)
}

/// The points the exercise's drawing spans: the base, every axis with its arrow, the
/// dimensions and the tool point, so Fit shows the arm as large as the view allows
/// whatever its pose.
pub fn drawing_points(robot: &Robot, fk: &ForwardKinematics) -> Vec<Vector3<f64>> {
    let dims = dimensions(robot, fk);
    let mut points = vec![
        robot.world_from_base.translation.vector,
        fk.base_from_tool.translation.vector,
    ];
    points.extend(dims.iter().flat_map(|d| [d.from, d.to]));
    points.extend(axis_ends(robot, fk, &dims).into_iter().flatten());
    points
}

/// A dimension's label: which axes it measures, its length and the angle between them.
fn dimension_text(model: &Model, d: &Dimension) -> String {
    let reach = model.robot().reach();
    let unit = model.robot().length_unit.symbol();
    let mut text = String::new();
    if d.length > reach * 1e-6 {
        text = format!("{} {unit}", number(d.length, 1));
    }
    if let Some(angle) = d.angle.filter(|a| *a > ANGLE_TINY) {
        let angle = format!("{}°", number(angle.to_degrees(), 1));
        text = if text.is_empty() {
            angle
        } else {
            format!("{text}, {angle}")
        };
    }
    match d.measures {
        Measures::BaseTo(i) => trf(model, Key::ExerciseBaseTo, &[&i, &text]),
        Measures::Along(i) => trf(model, Key::ExerciseAlong, &[&i, &text]),
        Measures::Normal(i) => trf(model, Key::ExerciseNormal, &[&i, &(i + 1), &text]),
        Measures::ToTool(i) => trf(model, Key::ExerciseToTool, &[&i, &text]),
    }
}

/// A label to draw once every label is placed: its place, its anchor, its text, colour,
/// and whether it gets a leader line.
type Queued = (
    egui::Rect,
    egui::Pos2,
    std::sync::Arc<egui::Galley>,
    egui::Color32,
    bool,
);

/// Draws each joint axis with its arrowhead and places its name beyond the arrowhead.
fn draw_axes(
    model: &Model,
    painter: &egui::Painter,
    (dims, font): (&[Dimension], &egui::FontId),
    placer: &mut Placer,
    project: &dyn Fn(&Point3<f64>) -> Option<egui::Pos2>,
) -> Vec<Queued> {
    let axis_color = egui::Color32::from_rgb(110, 165, 255);
    let mut queued = Vec::new();
    for (i, [back, front]) in axis_ends(model.robot(), model.fk(), dims)
        .iter()
        .enumerate()
    {
        let (Some(a), Some(b)) = (
            project(&Point3::from(*back)),
            project(&Point3::from(*front)),
        ) else {
            continue;
        };
        painter.line_segment([a, b], egui::Stroke::new(2.0, axis_color));
        let dir = (b - a).normalized();
        let side = egui::vec2(-dir.y, dir.x) * 5.0;
        painter.add(egui::Shape::convex_polygon(
            vec![b, b - dir * 12.0 + side, b - dir * 12.0 - side],
            axis_color,
            egui::Stroke::NONE,
        ));
        let name = trf(model, Key::ExerciseAxis, &[&(i + 1)]);
        let galley = painter.layout_no_wrap(name.clone(), font.clone(), axis_color);
        let size = galley.size() + egui::vec2(8.0, 4.0);
        // Beyond the arrowhead, in line with the axis.
        let shift = dir * (size.x.max(size.y) * 0.5 + 4.0);
        let rect = placer.place(name, size, b, shift);
        queued.push((
            rect,
            b,
            galley,
            axis_color,
            b.distance(rect.center()) > shift.length() + 4.0,
        ));
    }
    queued
}

/// Draws each joint axis (a line with an arrowhead on its positive end, named) and the
/// [`dimensions`] as dashed lines labelled with what they measure, over the 3D view in
/// `view`; `project` maps a world point to the window. No label covers another: the axis
/// names are placed first, then each dimension's label at its middle or, where that is
/// taken, nearby with a leader line to it. Gives the labels as placed.
pub fn draw_in_view(
    model: &Model,
    painter: &egui::Painter,
    view: egui::Rect,
    project: &dyn Fn(&Point3<f64>) -> Option<egui::Pos2>,
) -> Vec<Placed> {
    let robot = model.robot();
    let fk = model.fk();
    let font = egui::FontId::proportional(if model.settings().presentation {
        16.0
    } else {
        13.0
    });
    let dims = dimensions(robot, fk);
    let mut placer = Placer::new(view);
    for d in &dims {
        if let (Some(a), Some(b)) = (project(&Point3::from(d.from)), project(&Point3::from(d.to))) {
            placer.keep_clear(a, b);
        }
    }
    let mut queued = draw_axes(model, painter, (&dims, &font), &mut placer, project);
    for d in &dims {
        let (Some(a), Some(b)) = (project(&Point3::from(d.from)), project(&Point3::from(d.to)))
        else {
            continue;
        };
        let stroke = egui::Stroke::new(1.5, style::HIGHLIGHT);
        painter.extend(egui::Shape::dashed_line(&[a, b], stroke, 6.0, 4.0));
        let text = dimension_text(model, d);
        let galley = painter.layout_no_wrap(text.clone(), font.clone(), style::HIGHLIGHT);
        let size = galley.size() + egui::vec2(8.0, 4.0);
        let mid = a + (b - a) * 0.5;
        let rect = placer.place(text, size, mid, egui::Vec2::ZERO);
        queued.push((rect, mid, galley, style::HIGHLIGHT, true));
    }
    for (rect, anchor, galley, color, leader) in queued {
        let anchor = if leader { anchor } else { rect.center() };
        labels::draw(painter, rect, anchor, galley, color);
    }
    placer.into_placed()
}

#[cfg(test)]
mod tests {
    use super::*;
    use armlab_core::{ForwardKinematics, preset};

    fn lengths(id: &str, q: &[f64]) -> Vec<(f64, Option<f64>)> {
        let robot = preset(id).expect("a preset");
        let fk = ForwardKinematics::new(&robot, q).expect("a pose");
        dimensions(&robot, &fk)
            .iter()
            .map(|d| {
                let round = |v: f64| (v * 10.0).round() / 10.0;
                (round(d.length), d.angle.map(|a| round(a.to_degrees())))
            })
            .collect()
    }

    #[test]
    fn the_rrr_dimensions_are_its_lengths_whatever_the_pose() {
        // Base to axis 2 along axis 1: d1 = 100.9; axes 1 and 2 meet at 90°; a2, a3.
        let expected = vec![
            (100.9, None),
            (0.0, Some(90.0)),
            (222.1, Some(0.0)),
            (136.2, None),
        ];
        assert_eq!(lengths("rrr", &[0.0, 0.0, 0.0]), expected);
        assert_eq!(lengths("rrr", &[0.7, -0.4, 1.1]), expected);
    }

    #[test]
    fn the_standard_and_modified_ur10_draw_the_same_dimensions() {
        let q = [0.3, -1.0, 1.2, -0.8, 0.9, 0.2];
        let mut a = lengths("ur10", &q);
        let mut b = lengths("ur10-standard", &q);
        let key = |x: &(f64, Option<f64>)| (x.0 * 10.0) as i64;
        a.sort_by_key(key);
        b.sort_by_key(key);
        assert_eq!(a, b);
        assert!(a.iter().any(|d| d.0 == 612.9) && a.iter().any(|d| d.0 == 571.6));
    }
}
