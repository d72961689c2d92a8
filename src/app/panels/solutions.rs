//! Every IK solution of the target (docs/kinematics.md §9.6–9.7): the closed form's
//! branches named in words, or for an arm without one the distinct solutions of seeded
//! restarts; a click moves the arm to a solution, and the 3D view draws the others as
//! ghosts.

use armlab_core::ik::joint_distance;
use armlab_text::Key;

use crate::app::state::branches::{closed_form_rows, found_rows};
use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::widgets::style;
use crate::app::widgets::toggles::overlay_checkbox;
use armlab_session::format::number;
use armlab_session::settings::Overlay;

/// The solutions section of the IK panel.
pub fn solutions_ui(model: &mut Model, ui: &mut egui::Ui) {
    // The closed form's rows (microseconds) every frame while the list is open; the
    // ghosts' rows otherwise come from [`ghost_rows`].
    egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
        ui,
        tr(model, Key::Solutions),
    ))
    .id_salt("ik_solutions")
    .default_open(false)
    .show(ui, |ui| {
        // The sentence only with the model's own verdict, so that the fold, the IK status
        // and the ball never disagree.
        let unreachable = model.has_closed_form()
            && closed_form_rows(model)
            && model.shown_reach() == armlab_core::ik::Reach::OutOfReach;
        ui.label(egui::RichText::new(tr(model, Key::SolutionsHint)).small());
        if !model.has_closed_form()
            && ui
                .button(tr(model, Key::FindSolutions))
                .on_hover_text(tr(model, Key::FindSolutionsHint))
                .clicked()
        {
            found_rows(model);
        }
        overlay_checkbox(
            model,
            ui,
            Overlay::Ghosts,
            Key::ShowGhosts,
            Key::ShowGhostsHint,
        );
        if unreachable {
            ui.colored_label(style::UNREACHABLE, tr(model, Key::SolutionsUnreachable));
        }
        rows_ui(model, ui);
    });
}

/// One selectable row per solution: its name, its joint values, whether it is the arm's
/// pose now; a click moves the arm there.
fn rows_ui(model: &mut Model, ui: &mut egui::Ui) {
    let Some(branches) = model.branches().cloned() else {
        return;
    };
    if branches.continuum {
        ui.label(egui::RichText::new(tr(model, Key::SolutionsContinuum)).small());
    }
    let degrees = model.settings().degrees;
    let mut chosen = None;
    for (i, row) in branches.rows.iter().enumerate() {
        let current = joint_distance(model.robot(), &row.q, model.q()) < 1e-12;
        let values: Vec<String> = row
            .q
            .iter()
            .zip(&model.robot().joints)
            .map(|(v, j)| match j.kind {
                armlab_core::JointKind::Revolute if degrees => {
                    format!("{}°", rounded(v.to_degrees(), 1))
                }
                _ => rounded(*v, 3),
            })
            .collect();
        let mut text = format!("{}. {}", i + 1, row.label);
        if current {
            text = format!("{text} {}", tr(model, Key::SolutionCurrent));
        }
        if !row.within_limits {
            text = format!("{text} — {}", tr(model, Key::SolutionOutsideLimits));
        }
        let color = if row.within_limits {
            ui.visuals().text_color()
        } else {
            style::UNREACHABLE
        };
        let response = ui.selectable_label(current, egui::RichText::new(text).color(color));
        // At the monospace size, not small: a phone's and a projector's readers need the
        // joint values (a narrow column wraps them).
        ui.label(egui::RichText::new(values.join("  ")).monospace());
        if response.clicked() {
            chosen = Some(row.q.clone());
        }
    }
    if let Some(q) = chosen {
        model.set_q_exact(q);
    }
}

/// A joint value rounded to the decimals shown first: a closed form's 3e-15 rad is 0 to
/// the eye, and the list shows "0°", not "3.2e-15°".
fn rounded(v: f64, decimals: usize) -> String {
    let scale = 10f64.powi(decimals as i32);
    number((v * scale).round() / scale, decimals)
}
