//! The top bar: the robot's name, the display toggles, the camera buttons, "Copy link",
//! and the message of the moment drawn by its kind.

use crate::render::camera::StandardView;

use super::hook;
use super::model::{Message, MessageKind, Model};
use super::style;

/// What the top bar asks of the 3D view.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewAction {
    /// Frame the arm.
    Fit,
    /// A standard view direction.
    View(StandardView),
}

/// Draws the top bar; returns what it asks of the 3D view.
pub fn ui(model: &mut Model, ui: &mut egui::Ui) -> Option<ViewAction> {
    let mut action = None;
    ui.horizontal_wrapped(|ui| {
        ui.heading("ArmLab");
        ui.label(egui::RichText::new(&model.robot().name).strong());
        ui.separator();
        settings_toggles(model, ui);
        ui.separator();
        if ui.button("Fit").on_hover_text("Frame the robot").clicked() {
            action = Some(ViewAction::Fit);
        }
        for (label, view) in [
            ("Top", StandardView::Top),
            ("Front", StandardView::Front),
            ("Side", StandardView::Side),
            ("3D", StandardView::Iso),
        ] {
            if ui.button(label).clicked() {
                action = Some(ViewAction::View(view));
            }
        }
        ui.separator();
        if ui
            .button("Copy link")
            .on_hover_text("A link that opens this robot, pose and target")
            .clicked()
        {
            ui.ctx().copy_text(hook::share_link(&model.hash()));
        }
    });
    if let Some(message) = model.message().cloned() {
        message_line(model, ui, &message);
    }
    action
}

fn settings_toggles(model: &mut Model, ui: &mut egui::Ui) {
    let mut settings = model.settings().clone();
    ui.toggle_value(&mut settings.degrees, "Degrees")
        .on_hover_text("Show angles in degrees (off: radians)");
    ui.toggle_value(&mut settings.show_frames, "DH frames")
        .on_hover_text("Draw every DH frame: x red, y green, z blue");
    ui.toggle_value(&mut settings.presentation, "Presentation")
        .on_hover_text("Large fonts and high contrast for a projector");
    if &settings != model.settings() {
        model.set_settings(settings);
    }
}

fn message_line(model: &mut Model, ui: &mut egui::Ui, message: &Message) {
    let (sign, color) = match message.kind {
        MessageKind::Info => ("✓", style::INFO),
        MessageKind::Warning => ("⚠", style::WARNING),
        MessageKind::Error => ("⚠", style::ERROR),
    };
    ui.horizontal(|ui| {
        ui.colored_label(color, format!("{sign} {}", message.text));
        if ui.small_button("Dismiss").clicked() {
            model.dismiss_message();
        }
    });
}
