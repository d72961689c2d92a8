//! The Motion panel's "Paths and waypoints" part (docs/kinematics.md §19): how
//! the arm goes from A to B (joint space or a straight line), both planned paths drawn
//! side by side in 3D with a legend, the straight line's problems as sentences (and
//! marked in the view), and the waypoints: add the target, edit x, y, z, remove, visit.
//!
//! A typed coordinate that is not a number, or a pose the core refuses, gets a sentence
//! under its row and the last good value stays in force.

use armlab_text::Sentence;
use egui::Stroke;

use armlab_core::path::PathKind;
use armlab_text::{Key, echo};

use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::view3d::paths::{JOINT_COLOR, LINE_COLOR, problem_path};
use crate::app::widgets::draft::Draft;
use crate::app::widgets::style;
use armlab_session::format::number;

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
                .add(style::choice(model.paths().kind() == kind, tr(model, key)))
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
