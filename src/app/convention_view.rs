//! Standard and modified DH side by side (docs/kinematics.md §14): the robot's table in
//! both conventions, how well their T_0n agree, and the other convention's frames
//! overlaid in 3D, dashed.

use nalgebra::Point3;

use armlab_core::convention::frames_in_both_conventions;
use armlab_core::{Convention, Robot};
use armlab_text::Key;

use super::format::{error_value, number};
use super::matrices::overlay_checkbox;
use super::model::Model;
use super::scene::{AXIS, segment};
use super::settings::Overlay;
use super::{tr, trf};
use crate::render::{Instance, Shape};

/// The Robot panel's section: both tables and the agreement of their T_0n.
pub fn both_conventions_ui(model: &mut Model, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new(super::style::fold_title(
        ui,
        tr(model, Key::BothConventions),
    ))
    .id_salt("both_conventions")
    .default_open(false)
    .show(ui, |ui| {
        overlay_checkbox(
            model,
            ui,
            Overlay::OtherConvention,
            Key::OverlayOther,
            Key::OverlayOtherHint,
        );
        let Ok(both) = frames_in_both_conventions(model.robot(), model.q()) else {
            return;
        };
        let unit = model.robot().length_unit.symbol();
        let agreement = error_value(both.disagreement, 1);
        ui.label(trf(model, Key::ConventionsAgree, &[&agreement, &unit]));
        // Side by side where the column has room for both, else one under the other.
        let tables = |ui: &mut egui::Ui| {
            for (robot, title) in [
                (&both.standard, Key::StandardTable),
                (&both.modified, Key::ModifiedTable),
            ] {
                ui.vertical(|ui| {
                    ui.strong(tr(model, title));
                    table(ui, robot, model.settings().degrees);
                });
            }
        };
        if ui.available_width() >= 520.0 {
            ui.horizontal_top(tables);
        } else {
            tables(ui);
        }
    });
}

/// A read-only DH table: θ offset, d, a, α per row.
fn table(ui: &mut egui::Ui, robot: &Robot, degrees: bool) {
    let angle = |v: f64| {
        if degrees {
            format!("{}°", number(v.to_degrees(), 1))
        } else {
            number(v, 3)
        }
    };
    // Columns as wide as their numbers (egui's default minimum is 40 points), so the four
    // columns fit a projector's side column.
    egui::Grid::new(("convention_table", robot.convention == Convention::Standard))
        .striped(true)
        .min_col_width(0.0)
        .spacing([8.0, 2.0])
        .show(ui, |ui| {
            for head in ["", "θ", "d", "a", "α"] {
                ui.label(egui::RichText::new(head).small());
            }
            ui.end_row();
            for (i, j) in robot.joints.iter().enumerate() {
                ui.label(format!("{}", i + 1));
                for cell in [
                    angle(j.dh.theta),
                    number(j.dh.d, 1),
                    number(j.dh.a, 1),
                    angle(j.dh.alpha),
                ] {
                    ui.monospace(cell);
                }
                ui.end_row();
            }
        });
}

/// The other convention's frames, each axis dashed (four dashes).
pub fn instances(model: &Model, reach: f64, out: &mut Vec<Instance>) {
    if !model.settings().overlays.contains(Overlay::OtherConvention) {
        return;
    }
    let Ok(both) = frames_in_both_conventions(model.robot(), model.q()) else {
        return;
    };
    let frames = match model.robot().convention {
        Convention::Standard => &both.modified_frames,
        Convention::Modified => &both.standard_frames,
    };
    let len = reach * 0.12;
    for f in frames {
        let o = Point3::from(f.translation.vector);
        for (c, color) in AXIS.iter().enumerate() {
            let dir = f.rotation.matrix().column(c).into_owned();
            for k in 0..4 {
                let a = o + dir * (len * (2 * k) as f64 / 8.0);
                let b = o + dir * (len * (2 * k + 1) as f64 / 8.0);
                out.extend(segment(Shape::Cylinder, &a, &b, len * 0.05, *color));
            }
        }
    }
}
