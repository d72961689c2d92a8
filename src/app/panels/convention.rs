//! Standard and modified DH side by side (docs/kinematics.md §14): the robot's table in
//! both conventions and how well their T_0n agree (the 3D view draws the other
//! convention's frames).

use armlab_core::convention::frames_in_both_conventions;
use armlab_core::{Convention, Robot};
use armlab_text::Key;

use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::dh_table::{column_order, header};
use crate::app::widgets::math;
use crate::app::widgets::toggles::overlay_checkbox;
use armlab_session::format::{error_value, number};
use armlab_session::settings::Overlay;

/// The Robot panel's section: both tables and the agreement of their T_0n.
pub fn both_conventions_ui(model: &mut Model, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
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

/// A read-only DH table: θ offset, d, a, α per row (a, α, d, θ in modified DH).
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
            // Headers in the body font (a formula's subscripts are smaller still), in the
            // convention's order: a_{i−1}, α_{i−1}, d_i, θ_i for modified DH.
            ui.label("");
            let order = column_order(robot.convention);
            for &c in order.iter().take(4) {
                math::label(ui, header(robot.convention, c, false));
            }
            ui.end_row();
            for (i, j) in robot.joints.iter().enumerate() {
                ui.label(format!("{}", i + 1));
                let cells = [
                    angle(j.dh.theta),
                    number(j.dh.d, 1),
                    number(j.dh.a, 1),
                    angle(j.dh.alpha),
                ];
                for &c in order.iter().take(4) {
                    ui.monospace(&cells[c]);
                }
                ui.end_row();
            }
        });
}
