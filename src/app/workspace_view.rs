//! The reachable workspace (docs/kinematics.md §12): a cloud of tool positions from random
//! joint vectors, filled a few milliseconds per frame, coloured by a measure, optionally
//! only its slice through the target; and the IK panel's section that switches it and
//! says where the target lies.

use nalgebra::{Point3, Rotation3, Vector3};

use armlab_core::workspace::WorkspaceMeasure;
use armlab_text::Key;

use super::format::number;
use super::matrices::overlay_checkbox;
use super::model::Model;
use super::scene::instance;
use super::settings::Overlay;
use super::{style, tr, trf};
use crate::render::{Instance, Shape};

/// Samples in the cloud.
pub const SAMPLES: usize = 20_000;
/// Milliseconds a frame may spend filling it.
pub const BUDGET_MS: f64 = 4.0;

/// The measure the cloud is coloured by.
pub fn measure(model: &Model) -> WorkspaceMeasure {
    if model.settings().overlays.contains(Overlay::WorkspaceSigma) {
        WorkspaceMeasure::SigmaMin
    } else {
        WorkspaceMeasure::Manipulability
    }
}

/// Blue (low) to yellow (high).
fn ramp(t: f64) -> [u8; 4] {
    let t = t.clamp(0.0, 1.0);
    let lerp = |a: f64, b: f64| (a + (b - a) * t) as u8;
    [lerp(40.0, 250.0), lerp(90.0, 220.0), lerp(220.0, 60.0), 255]
}

/// The cloud's points as small cubes (only the slice through the target when asked).
pub fn instances(model: &Model, out: &mut Vec<Instance>) {
    let overlays = model.settings().overlays;
    let Some(cloud) = model
        .workspace()
        .filter(|_| overlays.contains(Overlay::Workspace))
    else {
        return;
    };
    let spacing = cloud.spacing();
    let size = Vector3::repeat(spacing * 0.2);
    let largest = cloud.largest_value().max(1e-300);
    let target_z = model.target().translation.vector.z;
    let slice = overlays.contains(Overlay::WorkspaceSlice);
    let rot = Rotation3::identity();
    for (p, v) in cloud.positions.iter().zip(&cloud.values) {
        if slice && (p.z - target_z).abs() > spacing {
            continue;
        }
        out.push(instance(
            Shape::Box,
            &Point3::from(*p),
            &rot,
            size,
            ramp(v / largest),
        ));
    }
}

/// At the target's position, a small sphere of the tool directions tested: green where
/// the arm reaches the position with its tool axis along that direction (to half the
/// lattice's spacing), grey where not.
pub fn direction_instances(model: &Model, out: &mut Vec<Instance>) {
    let Some(sphere) = model
        .directions()
        .filter(|_| model.settings().overlays.contains(Overlay::Directions))
    else {
        return;
    };
    let radius = 0.12 * model.robot().length_scale();
    let size = Vector3::repeat(radius * 0.09);
    let rot = Rotation3::identity();
    for (d, near) in sphere.directions.iter().zip(&sphere.near) {
        let p = Point3::from(sphere.position + d.direction * radius);
        let color = if *near {
            [60, 200, 90, 255]
        } else {
            [110, 110, 120, 255]
        };
        out.push(instance(Shape::Box, &p, &rot, size, color));
    }
    // The sampled directions themselves, smaller: on a 5-axis arm they trace the curve.
    for s in &sphere.samples {
        let p = Point3::from(sphere.position + s * radius);
        out.push(instance(
            Shape::Box,
            &p,
            &rot,
            size * 0.6,
            [150, 240, 120, 255],
        ));
    }
}

/// The workspace section of the IK panel: the switches, the filling, where the target
/// lies, and which joint holds a stalled drag at its limit.
pub fn workspace_ui(model: &mut Model, ui: &mut egui::Ui) {
    held_at_limit(model, ui);
    egui::CollapsingHeader::new(super::style::fold_title(ui, tr(model, Key::Workspace)))
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
            ui.label(trf(model, Key::WorkspaceFilling, &[&cloud.len(), &SAMPLES]));
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
