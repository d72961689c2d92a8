//! The Motion panel's "Paths and waypoints" part (docs/kinematics.md §19): how
//! the arm goes from A to B (joint space or a straight line), both planned paths drawn
//! side by side in 3D with a legend, the straight line's problems as sentences (and
//! marked in the view), and the waypoints: add the target, edit x, y, z, remove, visit.
//!
//! A typed coordinate that is not a number, or a pose the core refuses, gets a sentence
//! under its row and the last good value stays in force.

use armlab_text::Name;
use armlab_text::Sentence;
use egui::{Color32, Stroke};
use nalgebra::Point3;

use crate::render::{Instance, Line, Shape};
use armlab_core::path::{Path, PathKind};
use armlab_text::{Key, echo};

use super::draft::Draft;
use super::format::number;
use super::model::Model;
use super::screen_points::ScreenPoints;
use super::{style, tr, trf};

/// The joint-space path's colour (blue).
pub const JOINT_COLOR: Color32 = Color32::from_rgb(90, 170, 255);
/// The straight line's colour (magenta).
pub const LINE_COLOR: Color32 = Color32::from_rgb(240, 110, 220);
/// The waypoint markers' colour (teal).
const WAYPOINT_COLOR: Color32 = Color32::from_rgb(60, 210, 190);

/// The part's typed texts: one row of x, y, z per waypoint, and the last button's error.
#[derive(Debug, Clone, Default)]
pub struct PathPanel {
    rows: Vec<[Draft; 3]>,
    error: Option<String>,
}

impl PathPanel {
    /// Draws the part.
    pub fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        let r = egui::CollapsingHeader::new(style::fold_title(ui, tr(model, Key::PathTitle)))
            .id_salt("motion_paths")
            .show(ui, |ui| {
                kind_ui(model, ui, points);
                issues_ui(model, ui);
                self.buttons_ui(model, ui, points);
                self.rows_ui(model, ui);
            });
        points.insert("path-fold", r.header_response.rect.center());
    }

    /// "Add waypoint", "Visit" and how the visit goes.
    fn buttons_ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        let lang = model.settings().lang;
        let count = model.paths().waypoints().len();
        style::wrapped(ui, |ui| {
            let r = ui
                .button(tr(model, Key::PathAddWaypoint))
                .on_hover_text(tr(model, Key::PathAddWaypointHint));
            points.insert("path-add-waypoint", r.rect.center());
            if r.clicked() {
                self.error = model.add_waypoint().err().map(|e| e.sentence(lang));
            }
            let r = ui
                .add_enabled(count > 0, egui::Button::new(tr(model, Key::PathVisit)))
                .on_hover_text(tr(model, Key::PathVisitHint));
            points.insert("path-visit", r.rect.center());
            if r.clicked() {
                self.error = model.visit_waypoints().err().map(|e| e.sentence(lang));
            }
        });
        if let Some(e) = &self.error {
            ui.colored_label(style::ERROR, e);
        }
        if let Some(visit) = model.paths().visit() {
            let at = (visit.passed() + 1).min(count);
            ui.label(trf(model, Key::PathVisiting, &[&at, &count]));
        } else if model.paths().finished() {
            ui.colored_label(style::REACHED, tr(model, Key::PathVisitDone));
        } else if count == 0 {
            ui.label(egui::RichText::new(tr(model, Key::PathNoWaypoints)).small());
        }
    }

    /// One row per waypoint: x, y, z fields and "Remove".
    fn rows_ui(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let poses = model.paths().waypoints().poses().to_vec();
        self.rows.resize_with(poses.len(), Default::default);
        let unit = model.robot().length_unit.symbol();
        let mut remove = None;
        for (i, (row, pose)) in self.rows.iter_mut().zip(&poses).enumerate() {
            let label = ui.label(trf(model, Key::PathWaypointRow, &[&(i + 1), &unit]));
            let p = pose.translation.vector;
            let edited = style::wrapped(ui, |ui| {
                let mut edited = None;
                for (c, draft) in row.iter_mut().enumerate() {
                    let shown = number(p[c], 3);
                    let parsed = draft.text.trim().parse::<f64>().ok();
                    if draft.error.is_none() && parsed.map(|v| number(v, 3)) != Some(shown) {
                        // Changed elsewhere (added, a link): show the value in force.
                        draft.text = number(p[c], 3);
                    }
                    let r = ui
                        .add(
                            egui::TextEdit::singleline(&mut draft.text)
                                .id_salt(("path_wp", i, c))
                                .desired_width(72.0),
                        )
                        .labelled_by(label.id);
                    if r.changed() {
                        edited = Some(c);
                    }
                }
                if ui.small_button(tr(model, Key::MotionRemove)).clicked() {
                    remove = Some(i);
                }
                edited
            })
            .inner;
            if let Some(c) = edited {
                let lang = model.settings().lang;
                let draft = &mut row[c];
                draft.error = match draft.text.trim().parse::<f64>() {
                    Err(_) => Some(armlab_text::fill(
                        lang,
                        Key::MotionNotNumber,
                        &[&echo::text(&draft.text)],
                    )),
                    Ok(v) => {
                        let mut next = *pose;
                        next.translation.vector[c] = v;
                        model.set_waypoint(i, next).err().map(|e| e.sentence(lang))
                    }
                };
            }
            for draft in row.iter().filter(|d| d.error.is_some()) {
                ui.colored_label(style::ERROR, draft.error.as_deref().unwrap_or_default());
            }
        }
        if let Some(i) = remove {
            model.remove_waypoint(i);
            self.rows.remove(i);
        }
    }
}

/// The path kind's choice, "Draw both paths" and the legend.
fn kind_ui(model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
    ui.label(tr(model, Key::PathKindLabel))
        .on_hover_text(tr(model, Key::PathKindHint));
    style::wrapped(ui, |ui| {
        for (kind, key, name) in [
            (PathKind::Joint, Key::PathJointSpace, "path-joint"),
            (PathKind::Cartesian, Key::PathStraightLine, "path-line"),
        ] {
            let r = ui
                .selectable_label(model.paths().kind() == kind, tr(model, key))
                .on_hover_text(tr(model, Key::PathKindHint));
            points.insert(name, r.rect.center());
            if r.clicked() {
                model.set_path_kind(kind);
            }
        }
    });
    let mut shown = model.paths().shown();
    let r = ui
        .checkbox(&mut shown, tr(model, Key::PathShowBoth))
        .on_hover_text(tr(model, Key::PathShowBothHint));
    points.insert("path-show", r.rect.center());
    if r.changed() {
        model.set_paths_shown(shown);
    }
    if shown {
        style::wrapped(ui, |ui| {
            for (color, key) in [
                (JOINT_COLOR, Key::PathLegendJoint),
                (LINE_COLOR, Key::PathLegendLine),
            ] {
                let (rect, _) =
                    ui.allocate_exact_size(egui::vec2(20.0, 10.0), egui::Sense::hover());
                ui.painter().line_segment(
                    [rect.left_center(), rect.right_center()],
                    Stroke::new(3.0, color),
                );
                ui.label(tr(model, key));
            }
        });
    }
}

/// The straight line's problems (of the drawn plan, or of a visit along the line).
fn problem_path(model: &Model) -> Option<&Path> {
    let paths = model.paths();
    paths.plan().map(|p| &p.line).or_else(|| {
        paths
            .visit()
            .filter(|_| paths.kind() == PathKind::Cartesian)
            .map(|v| &v.path)
    })
}

/// The straight line's problems as sentences (the first three), or that it has none.
fn issues_ui(model: &Model, ui: &mut egui::Ui) {
    let Some(path) = problem_path(model) else {
        return;
    };
    let lang = model.settings().lang;
    if path.problems.is_empty() {
        ui.label(tr(model, Key::PathLineClear));
    }
    for p in path.problems.iter().take(3) {
        ui.colored_label(style::WARNING, p.sentence(lang));
    }
    if path.problems.len() > 3 {
        ui.label(trf(
            model,
            Key::PathMoreIssues,
            &[&(path.problems.len() - 3)],
        ));
    }
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
        super::scene::instance(
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
