//! A checkbox that switches one of the 3D view's overlays, shared by the panels whose
//! folds each switch their own.

use armlab_session::settings::Overlay;
use armlab_text::Key;

use crate::app::state::model::Model;
use crate::app::state::tr;

/// A checkbox that turns one overlay on or off.
pub fn overlay_checkbox(
    model: &mut Model,
    ui: &mut egui::Ui,
    overlay: Overlay,
    label: Key,
    hint: Key,
) {
    let mut on = model.settings().overlays.contains(overlay);
    if ui
        .checkbox(&mut on, tr(model, label))
        .on_hover_text(tr(model, hint))
        .changed()
    {
        model.set_overlay(overlay, on);
    }
}
