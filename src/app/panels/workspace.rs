//! The IK panel's workspace fold (docs/kinematics.md §12): whether the cloud of reachable
//! tool positions is drawn, its measure and its sample count.

use armlab_text::Key;

use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::view3d::workspace;
use crate::app::widgets::style;
use crate::app::widgets::toggles::overlay_checkbox;
use armlab_session::format::number;
use armlab_session::settings::Overlay;

/// The workspace section of the IK panel: the switches, the filling, where the target
/// lies, and which joint holds a stalled drag at its limit.
pub fn workspace_ui(model: &mut Model, ui: &mut egui::Ui) {
    held_at_limit(model, ui);
    egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
        ui,
        tr(model, Key::Workspace),
    ))
    .id_salt("workspace")
    .default_open(false)
    .show(ui, |ui| {
        let switches = [
            (
                Overlay::Workspace,
                Key::WorkspaceCloud,
                Key::WorkspaceCloudHint,
            ),
            (
                Overlay::WorkspaceSlice,
                Key::WorkspaceSlice,
                Key::WorkspaceSliceHint,
            ),
            (
                Overlay::WorkspaceSigma,
                Key::WorkspaceSigma,
                Key::WorkspaceSigmaHint,
            ),
        ];
        for (overlay, label, hint) in switches {
            overlay_checkbox(model, ui, overlay, label, hint);
        }
        overlay_checkbox(
            model,
            ui,
            Overlay::Directions,
            Key::ToolDirections,
            Key::ToolDirectionsHint,
        );
        if let Some(sphere) = model
            .directions()
            .filter(|_| model.settings().overlays.contains(Overlay::Directions))
        {
            let reached = sphere.near.iter().filter(|n| **n).count();
            let degrees = number(sphere.tolerance.to_degrees(), 0);
            ui.label(trf(
                model,
                Key::ToolDirectionsCount,
                &[&reached, &sphere.directions.len(), &degrees],
            ));
        }
        let Some(cloud) = model.workspace() else {
            return;
        };
        ui.label(trf(
            model,
            Key::WorkspaceFilling,
            &[&cloud.len(), &workspace::SAMPLES],
        ));
        colours_line(model, ui, cloud.largest_value());
        let target = model.target().translation.vector;
        if let Some(near) = cloud.nearest(&target) {
            let key = if cloud.contains(&target) {
                Key::WorkspaceInside
            } else {
                Key::WorkspaceOutside
            };
            let unit = model.robot().length_unit.symbol();
            ui.label(trf(model, key, &[&number(near.distance, 1), &unit]));
        }
    });
}

/// While the cloud shows: the measure it is coloured by and the range of its colours, as
/// the legend in the view draws them.
fn colours_line(model: &Model, ui: &mut egui::Ui, largest: f64) {
    if model.settings().overlays.contains(Overlay::Workspace) {
        let sigma = model.settings().overlays.contains(Overlay::WorkspaceSigma);
        let name = tr(model, crate::app::view3d::overlay::legend_name(sigma));
        let largest = number(largest, 3);
        ui.label(trf(model, Key::WorkspaceColours, &[&name, &largest]));
    }
}

/// When the drag stalls short of the target: the joint that holds it at a limit, if one
/// does, and either a button to the start that reaches the target or the verdict that
/// none does.
fn held_at_limit(model: &mut Model, ui: &mut egui::Ui) {
    let Some(rescue) = model.rescue().cloned() else {
        return;
    };
    let held = rescue.held.map(|(j, at_max)| {
        let side = tr(model, if at_max { Key::LimitMax } else { Key::LimitMin });
        (j + 1, side.to_owned())
    });
    if rescue.reach.is_some() {
        let text = match &held {
            Some((joint, side)) => trf(model, Key::HeldAtLimit, &[joint, side]),
            None => tr(model, Key::StalledOtherStart).to_owned(),
        };
        ui.colored_label(style::PENDING, text);
        if ui
            .button(tr(model, Key::HeldAtLimitGo))
            .on_hover_text(tr(model, Key::HeldAtLimitGoHint))
            .clicked()
        {
            model.take_rescue();
        }
    } else if let Some((joint, side)) = &held {
        ui.colored_label(
            style::UNREACHABLE,
            trf(model, Key::HeldAtLimitNone, &[joint, side, &rescue.tried]),
        );
    } else {
        ui.colored_label(
            style::UNREACHABLE,
            trf(model, Key::StalledNoStart, &[&rescue.tried]),
        );
    }
}
