//! Every IK solution of the target (docs/kinematics.md §9.6–9.7): the closed form's
//! branches named in words, or for an arm without one the distinct solutions of seeded
//! restarts; a click moves the arm to a solution, and the 3D view draws the others as
//! ghosts.

use armlab_core::{
    Branch, Elbow, IkSettings, Shoulder, Wrist, closed_form_solutions, distinct_solutions,
    ik::joint_distance,
};
use armlab_text::Key;

use super::format::number;
use super::matrices::overlay_checkbox;
use super::model::{BranchRow, Model};
use super::settings::Overlay;
use super::{style, tr, trf};

/// Restarts for the distinct solutions of an arm without a closed form.
const ATTEMPTS: usize = 48;

/// A branch in words: "shoulder right, elbow up, wrist not flipped".
pub fn branch_words(model: &Model, branch: &Branch) -> String {
    let shoulder = branch.shoulder.map(|s| match s {
        Shoulder::Right => Key::ShoulderRight,
        Shoulder::Left => Key::ShoulderLeft,
    });
    let elbow = branch.elbow.map(|e| match e {
        Elbow::Up => Key::ElbowUp,
        Elbow::Down => Key::ElbowDown,
    });
    let wrist = branch.wrist.map(|w| match w {
        Wrist::NotFlipped => Key::WristNotFlipped,
        Wrist::Flipped => Key::WristFlipped,
    });
    [shoulder, elbow, wrist]
        .into_iter()
        .flatten()
        .map(|k| tr(model, k))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The solutions section of the IK panel.
pub fn solutions_ui(model: &mut Model, ui: &mut egui::Ui) {
    // The closed form's rows (microseconds) every frame while the list is open; the
    // ghosts' rows otherwise come from [`ghost_rows`].
    egui::CollapsingHeader::new(super::style::fold_title(ui, tr(model, Key::Solutions)))
        .id_salt("ik_solutions")
        .default_open(false)
        .show(ui, |ui| {
            let unreachable = model.has_closed_form() && closed_form_rows(model);
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

/// The closed form's rows for the 3D view's ghosts when they are on and no rows are kept
/// for this target and robot: whether or not the IK panel, where the list is, is shown
/// (a phone's link with `show=ghosts` draws them with no sheet open).
pub fn ghost_rows(model: &mut Model) {
    if model.settings().overlays.contains(Overlay::Ghosts)
        && model.has_closed_form()
        && model.branches().is_none()
    {
        closed_form_rows(model);
    }
}

/// The closed form's solutions for the target (every frame: microseconds); true when
/// none is exact.
fn closed_form_rows(model: &mut Model) -> bool {
    let Ok(set) = closed_form_solutions(model.robot(), model.target(), model.q()) else {
        model.set_branches(Vec::new(), false);
        return false;
    };
    let rows = set
        .solutions
        .iter()
        .map(|s| BranchRow {
            q: s.q.clone(),
            label: branch_words(model, &s.branch),
            within_limits: s.within_limits,
        })
        .collect();
    model.set_branches(rows, false);
    set.unreachable
}

/// The distinct solutions of seeded restarts (on demand: tens of milliseconds).
fn found_rows(model: &mut Model) {
    let settings = IkSettings::default();
    let found = distinct_solutions(
        model.robot(),
        model.target(),
        model.task(),
        &settings,
        ATTEMPTS,
    );
    let Ok(found) = found else {
        model.set_branches(Vec::new(), false);
        return;
    };
    let rows = found
        .solutions
        .iter()
        .map(|s| {
            let signs: String = s
                .signs
                .iter()
                .map(|v| if *v > 0 { '+' } else { '−' })
                .collect();
            BranchRow {
                q: s.q.clone(),
                label: trf(model, Key::ConfigurationSigns, &[&signs]),
                within_limits: s.within_limits,
            }
        })
        .collect();
    model.set_branches(rows, found.continuum);
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
