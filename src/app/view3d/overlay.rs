//! Text drawn over the 3D picture: the grid's scale, the controls and the shortcut keys,
//! the IK status in its colour, and the highlighted joint. Every line wraps within the
//! view, so a phone shows all of it.

use egui::{Color32, Rect};

use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::view3d::workspace;
use crate::app::widgets::style;
use armlab_core::ik::Reach;
use armlab_session::format::number;
use armlab_session::settings::Overlay;
use armlab_text::{Key, Lang, fill, text};

/// Draws the labels over the picture; `touch` names finger gestures instead of the mouse.
pub fn draw(model: &Model, painter: &egui::Painter, rect: Rect, grid_step: f64, touch: bool) {
    let presentation = model.settings().presentation;
    let unit = model.robot().length_unit.symbol();
    let small = egui::FontId::proportional(if presentation { 15.0 } else { 12.0 });
    let text_color = if presentation {
        Color32::WHITE
    } else {
        Color32::from_gray(200)
    };
    let wrap = (rect.width() - 20.0).max(40.0);
    let bottom = controls_text(model.settings().lang, &number(grid_step, 4), unit, touch);
    let galley = painter.layout(bottom, small.clone(), text_color, wrap);
    painter.galley(
        rect.left_bottom() + egui::vec2(10.0, -10.0 - galley.size().y),
        galley,
        text_color,
    );
    let reach = model.shown_reach();
    let status = match reach {
        Reach::Reached => Key::StatusReached,
        Reach::OutOfReach => Key::StatusOutOfReach,
        Reach::Pending => Key::StatusPending,
    };
    let color = style::reach_color(reach);
    let galley = painter.layout(tr(model, status).to_owned(), small.clone(), color, wrap);
    let status_height = galley.size().y;
    painter.galley(rect.left_top() + egui::vec2(10.0, 10.0), galley, color);
    if let Some(link) = model.hovered_link()
        && let Some(joint) = model.robot().joints.get(link.wrapping_sub(1))
    {
        let text = highlight_text(model.settings().lang, link, &joint.name);
        let galley = painter.layout(text, small, style::HIGHLIGHT, wrap);
        let at = rect.right_top() + egui::vec2(-10.0 - galley.size().x, 14.0 + status_height);
        painter.galley(at, galley, style::HIGHLIGHT);
    }
}

/// The workspace cloud's colour scale, at the top right of the view under the line of a
/// highlighted joint: the measure's name, and a bar from blue at 0 to yellow at the
/// cloud's largest value. Its ends go to `points` (`cloud-legend-low`, `-high`).
pub fn cloud_legend(model: &Model, painter: &egui::Painter, rect: Rect, points: &mut ScreenPoints) {
    let Some(cloud) = model.shown_workspace() else {
        return;
    };
    let font = egui::FontId::proportional(if model.settings().presentation {
        15.0
    } else {
        12.0
    });
    let color = Color32::from_gray(220);
    let name = tr(
        model,
        legend_name(model.settings().overlays.contains(Overlay::WorkspaceSigma)),
    );
    let largest = number(cloud.largest_value(), 3);
    let (width, height) = (160.0, 10.0);
    let right = rect.right() - 10.0;
    let title = painter.layout(name.to_owned(), font.clone(), color, rect.width() - 20.0);
    let top = rect.top() + 56.0;
    let title_left = right - title.size().x.max(width);
    let bar_top = top + title.size().y + 4.0;
    painter.galley(egui::pos2(title_left, top), title, color);
    let bar = Rect::from_min_size(
        egui::pos2(right - width, bar_top),
        egui::vec2(width, height),
    );
    let steps = 32;
    for i in 0..steps {
        let t = (i as f32 + 0.5) / steps as f32;
        let [r, g, b, _] = workspace::ramp(f64::from(t));
        let x = bar.left() + bar.width() * i as f32 / steps as f32;
        let cell = Rect::from_min_size(
            egui::pos2(x, bar.top()),
            egui::vec2(width / steps as f32 + 0.5, height),
        );
        painter.rect_filled(cell, 0.0, Color32::from_rgb(r, g, b));
    }
    let below = egui::pos2(bar.left(), bar.bottom() + 2.0);
    painter.text(below, egui::Align2::LEFT_TOP, "0", font.clone(), color);
    let end = egui::pos2(bar.right(), bar.bottom() + 2.0);
    painter.text(end, egui::Align2::RIGHT_TOP, largest, font, color);
    points.insert(
        "cloud-legend-low",
        egui::pos2(bar.left() + 1.0, bar.center().y),
    );
    points.insert(
        "cloud-legend-high",
        egui::pos2(bar.right() - 1.0, bar.center().y),
    );
}

/// The name of the measure the cloud is coloured by: σ_min, or the manipulability.
pub fn legend_name(sigma: bool) -> Key {
    if sigma {
        Key::WorkspaceLegendSigma
    } else {
        Key::WorkspaceLegendW
    }
}

/// The hint at the foot of the view: the grid's step in `unit`, what a drag (or a finger)
/// does, the target ball first (a first-time user does not guess that it moves), and with
/// a mouse the shortcut keys.
fn controls_text(lang: Lang, grid: &str, unit: &str, touch: bool) -> String {
    let controls = text(
        lang,
        if touch {
            Key::TouchControls
        } else {
            Key::MouseControls
        },
    );
    let bottom = fill(lang, Key::GridControls, &[&grid, &unit, &controls]);
    if touch {
        bottom
    } else {
        format!("{bottom}\n{}", text(lang, Key::ShortcutHint))
    }
}

/// The line naming the highlighted joint `link` (1-based) and its matrices. A name that
/// only numbers the joint ("joint 3", the Panda's) is not said twice.
fn highlight_text(lang: Lang, link: usize, name: &str) -> String {
    let name = name.trim();
    if name.is_empty() || name.eq_ignore_ascii_case(&format!("joint {link}")) {
        fill(lang, Key::JointHighlightedUnnamed, &[&link])
    } else {
        fill(lang, Key::JointHighlighted, &[&link, &name])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hint_says_the_ball_moves_the_target_with_a_mouse_and_a_finger() {
        for (lang, said) in [
            (Lang::En, "drag the ball: move the target"),
            (Lang::Fi, "vedä palloa: siirrä kohdetta"),
        ] {
            for touch in [false, true] {
                let hint = controls_text(lang, "500", "mm", touch);
                assert!(hint.contains(said), "{lang:?}, touch {touch}: {hint}");
                assert!(hint.starts_with(&fill(lang, Key::GridControls, &[&"500", &"mm", &""])));
            }
        }
    }

    #[test]
    fn a_joint_is_named_once() {
        for (lang, link, name, want) in [
            (
                Lang::En,
                2,
                "shoulder",
                "joint 2: shoulder — A_2 and T_02 highlighted",
            ),
            (Lang::En, 3, "joint 3", "joint 3 — A_3 and T_03 highlighted"),
            (Lang::Fi, 3, "Joint 3 ", "nivel 3 — A_3 ja T_03 korostettu"),
            (Lang::En, 4, "", "joint 4 — A_4 and T_04 highlighted"),
        ] {
            assert_eq!(highlight_text(lang, link, name), want);
        }
    }
}
