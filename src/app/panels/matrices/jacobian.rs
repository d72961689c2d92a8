//! The Jacobian's fold in the matrices panel: J with its central-difference check, its
//! measures, the switches of its drawings in the 3D view and their colour legend. Apart
//! from the panel as the one fold that writes the 3D view's overlays and hover.

use nalgebra::DMatrix;

use armlab_core::JacobianAnalysis;
use armlab_text::Key;

use super::block::matrix_block;
use super::measures::measures_grid;
use super::predict::{Hiding, Target};
use crate::app::state::model::{HoverSource, Model};
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::view3d::jacobian;
use crate::app::widgets::style;
use crate::app::widgets::toggles::overlay_checkbox;
use armlab_session::format::{fixed, number};
use armlab_session::settings::Overlay;

/// The title of J in the base frame or, with `tool_frame`, in the tool frame.
pub(super) fn title(tool_frame: bool) -> Key {
    if tool_frame {
        Key::JacobianToolTitle
    } else {
        Key::JacobianTitle
    }
}

/// The switch between J in the base frame and J in the tool frame.
pub(super) fn frame_switch(model: &Model, ui: &mut egui::Ui, tool_frame: &mut bool) {
    let hint = tr(model, Key::JacobianFrameHint);
    crate::app::widgets::style::wrapped(ui, |ui| {
        ui.label(tr(model, Key::JacobianFrame)).on_hover_text(hint);
        for (tool, key) in [(false, Key::JacobianBase), (true, Key::JacobianTool)] {
            let choice = crate::app::widgets::style::choice(*tool_frame == tool, tr(model, key));
            if ui.add(choice).on_hover_text(hint).clicked() {
                *tool_frame = tool;
            }
        }
    });
}

/// J with its check, measures, drawings and legend; `tool_frame`: J shown in the tool
/// frame, `blockdiag(Rᵀ, Rᵀ)·J` (the measures are the same in either frame).
pub(super) fn jacobian_block(
    model: &mut Model,
    analysis: &JacobianAnalysis,
    ui: &mut egui::Ui,
    (decimals, tool_frame): (usize, bool),
    hiding: &mut Hiding,
) {
    let j = &analysis.geometric;
    let turn = if tool_frame {
        model.fk().base_from_tool.rotation.matrix().transpose()
    } else {
        nalgebra::Matrix3::identity()
    };
    let jm = DMatrix::from_fn(6, j.ncols(), |r, c| {
        let part = r / 3 * 3;
        (0..3).map(|k| turn[(r % 3, k)] * j[(part + k, c)]).sum()
    });
    matrix_block(
        ui,
        model.settings().lang,
        tr(model, title(tool_frame)),
        tr(model, Key::JacobianHint),
        &jm,
        decimals,
        (false, super::block::Axes::Jacobian(&model.robot().joints)),
        (Target::Jacobian, hiding),
    );
    let text = trf(
        model,
        Key::CentralDifferences,
        &[&number(analysis.max_difference, 1)],
    );
    if analysis.agrees {
        ui.label(text);
    } else {
        let tolerance = number(analysis.tolerance, 1);
        ui.colored_label(
            style::ERROR,
            trf(model, Key::AboveTolerance, &[&text, &tolerance]),
        );
    }
    measures_grid(model, &analysis.measures, ui);
    overlay_switches(model, ui);
    if model.settings().overlays.contains(Overlay::JacobianColumns)
        || model.settings().overlays.contains(Overlay::AngularColumns)
    {
        column_legend(model, ui);
    } else {
        model.set_hovered_column(None, HoverSource::Matrices);
    }
    if let Some(lost) = model.lost_direction() {
        let d = [lost.x, lost.y, lost.z].map(|v| fixed(v, 2)).join(", ");
        ui.colored_label(style::UNREACHABLE, trf(model, Key::LostDirection, &[&d]));
    }
}

/// The switches of the Jacobian's drawings in the 3D view.
fn overlay_switches(model: &mut Model, ui: &mut egui::Ui) {
    crate::app::widgets::style::wrapped(ui, |ui| {
        ui.label(tr(model, Key::DrawIn3d));
        let switches = [
            (
                Overlay::JacobianColumns,
                Key::DrawColumns,
                Key::DrawColumnsHint,
            ),
            (
                Overlay::AngularColumns,
                Key::DrawAngular,
                Key::DrawAngularHint,
            ),
            (
                Overlay::VelocityEllipsoid,
                Key::DrawVelocityEllipsoid,
                Key::DrawVelocityEllipsoidHint,
            ),
            (
                Overlay::ForceEllipsoid,
                Key::DrawForceEllipsoid,
                Key::DrawForceEllipsoidHint,
            ),
        ];
        for (overlay, label, hint) in switches {
            overlay_checkbox(model, ui, overlay, label, hint);
        }
    });
}

/// The columns' colours and numbers, as the arrows have them; hovering one highlights its
/// arrow (and hovering an arrow highlights its entry).
fn column_legend(model: &mut Model, ui: &mut egui::Ui) {
    let mut hovered = None;
    crate::app::widgets::style::wrapped(ui, |ui| {
        ui.label(tr(model, Key::ColumnLegend));
        for i in 0..model.robot().dof() {
            let [r, g, b] = jacobian::column_color(i);
            let mut text =
                egui::RichText::new(format!("■ {}", i + 1)).color(egui::Color32::from_rgb(r, g, b));
            if model.hovered_column() == Some(i) {
                text = text.strong().underline();
            }
            let name = &model.robot().joints[i].name;
            let response = ui
                .add(egui::Label::new(text).sense(egui::Sense::hover()))
                .on_hover_text(trf(model, Key::ColumnHint, &[&(i + 1), name]));
            if response.hovered() {
                hovered = Some(i);
            }
        }
    });
    model.set_hovered_column(hovered, HoverSource::Matrices);
}
