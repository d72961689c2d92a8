//! The top bar: the robot's name, the display toggles, the language, the camera buttons,
//! "Copy link", the shortcut keys, and the message of the moment drawn by its kind. On a
//! narrow screen everything but the name and "Fit" goes into a menu.

use crate::app::view3d::ViewAction;
use crate::render::camera::StandardView;
use armlab_text::{Key, Lang};

use crate::app::platform;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::{Message, MessageKind, Model};
use crate::app::state::tr;
use crate::app::widgets::style;

/// Draws the top bar; returns what it asks of the 3D view. `narrow`: the narrow layout's
/// bar (its controls in a menu); `drag_pans`: the view's drag mode, which the View menu
/// switches. The language menu and its choices go to `points` for the test hook.
pub fn ui(
    model: &mut Model,
    ui: &mut egui::Ui,
    narrow: bool,
    drag_pans: bool,
    points: &mut ScreenPoints,
) -> Option<ViewAction> {
    let mut action = None;
    crate::app::widgets::style::wrapped(ui, |ui| {
        if !narrow {
            ui.heading(tr(model, Key::AppName));
        }
        // An exercise's robot has no name (it would give the table away); an empty label
        // in a wrapping row makes egui draw the next button over the heading.
        if !model.robot().name.is_empty() {
            ui.label(egui::RichText::new(&model.robot().name).strong());
        }
        ui.separator();
        if ui
            .button(tr(model, Key::Fit))
            .on_hover_text(tr(model, Key::FitHint))
            .clicked()
        {
            action = Some(ViewAction::Fit);
        }
        action = action.or(zoom_buttons(model, ui));
        if narrow {
            ui.menu_button(tr(model, Key::Menu), |ui| {
                action = action.or(controls(model, ui, drag_pans, points));
            });
        } else {
            action = action.or(controls(model, ui, drag_pans, points));
        }
    });
    if let Some(message) = model.message().cloned() {
        message_line(model, ui, &message);
    }
    action
}

/// Zoom in and out, one press each: pinch's alternative for one finger or a mouse
/// without a wheel. Out of the narrow layout's menu, so a phone reaches them in one tap.
fn zoom_buttons(model: &Model, ui: &mut egui::Ui) -> Option<ViewAction> {
    let mut action = None;
    for (sign, key, zoom) in [
        ("+", Key::ZoomIn, ViewAction::Zoom(1)),
        ("\u{2212}", Key::ZoomOut, ViewAction::Zoom(-1)),
    ] {
        if ui
            .button(sign)
            .on_hover_text(tr(model, key))
            .accessible_name(tr(model, key))
            .clicked()
        {
            action = Some(zoom);
        }
    }
    action
}

/// The toggles, the language, the View menu (the standard views and the drag mode) and
/// "Copy link".
fn controls(
    model: &mut Model,
    ui: &mut egui::Ui,
    drag_pans: bool,
    points: &mut ScreenPoints,
) -> Option<ViewAction> {
    let mut action = None;
    settings_toggles(model, ui, points);
    ui.separator();
    ui.menu_button(tr(model, Key::ViewMenu), |ui| {
        for (key, view) in [
            (Key::ViewTop, StandardView::Top),
            (Key::ViewFront, StandardView::Front),
            (Key::ViewSide, StandardView::Side),
            (Key::View3d, StandardView::Iso),
        ] {
            if ui.button(tr(model, key)).clicked() {
                action = Some(ViewAction::View(view));
            }
        }
        ui.separator();
        // Panning otherwise takes two fingers (or a mouse's right button).
        let mut pans = drag_pans;
        if ui.checkbox(&mut pans, tr(model, Key::DragPans)).changed() {
            action = Some(ViewAction::DragPans(pans));
        }
    });
    ui.separator();
    if ui
        .button(tr(model, Key::CopyLink))
        .on_hover_text(tr(model, Key::CopyLinkHint))
        .clicked()
    {
        ui.ctx().copy_text(platform::share_link(&model.hash()));
        model.set_message(Message::info(tr(model, Key::LinkCopied)));
    }
    action
}

/// A model method that switches one setting.
type Writer = fn(&mut Model, bool);

fn settings_toggles(model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
    let toggles: [(bool, Key, Key, Writer); 3] = [
        (
            model.settings().degrees,
            Key::Degrees,
            Key::DegreesHint,
            Model::set_degrees,
        ),
        (
            model.settings().show_frames,
            Key::DhFrames,
            Key::DhFramesHint,
            Model::set_show_frames,
        ),
        (
            model.settings().presentation,
            Key::Presentation,
            Key::PresentationHint,
            Model::set_presentation,
        ),
    ];
    for (mut on, label, hint, set) in toggles {
        if style::switch(ui, &mut on, tr(model, label))
            .on_hover_text(tr(model, hint))
            .changed()
        {
            set(model, on);
        }
    }
    let mut lang = model.settings().lang;
    let menu = egui::ComboBox::from_id_salt("language")
        .selected_text(lang.name())
        .width(80.0)
        .show_ui(ui, |ui| {
            for choice in Lang::ALL {
                let item = ui.selectable_value(&mut lang, choice, choice.name());
                points.insert(format!("language-{}", choice.id()), item.rect.center());
            }
        })
        .response
        .on_hover_text(tr(model, Key::LanguageHint));
    points.insert("language", menu.rect.center());
    if lang != model.settings().lang {
        model.set_lang(lang);
    }
}

fn message_line(model: &mut Model, ui: &mut egui::Ui, message: &Message) {
    let (sign, color) = match message.kind {
        MessageKind::Info => ("✓", style::INFO),
        MessageKind::Warning => ("⚠", style::WARNING),
        MessageKind::Error => ("⚠", style::ERROR),
    };
    crate::app::widgets::style::wrapped(ui, |ui| {
        ui.colored_label(color, format!("{sign} {}", message.text));
        if ui.small_button(tr(model, Key::Dismiss)).clicked() {
            model.dismiss_message();
        }
    });
}
