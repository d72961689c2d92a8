//! Text drawn over the 3D picture: the grid's scale and the controls, the IK status in
//! its colour, and the highlighted joint.

use egui::{Color32, Rect};

use crate::app::format::number;
use crate::app::model::Model;
use crate::app::style;
use crate::kinematics::ik::Reach;

/// Draws the labels over the picture.
pub fn draw(model: &Model, painter: &egui::Painter, rect: Rect, grid_step: f64) {
    let presentation = model.settings().presentation;
    let unit = model.robot().length_unit.symbol();
    let small = egui::FontId::proportional(if presentation { 15.0 } else { 12.0 });
    let text_color = if presentation {
        Color32::WHITE
    } else {
        Color32::from_gray(200)
    };
    painter.text(
        rect.left_bottom() + egui::vec2(10.0, -10.0),
        egui::Align2::LEFT_BOTTOM,
        format!(
            "grid {} {unit}   ·   drag: orbit   right-drag: pan   wheel: zoom",
            number(grid_step, 4)
        ),
        small.clone(),
        text_color,
    );
    let reach = model.ik().reach;
    let status = match reach {
        Reach::Reached => "target reached",
        Reach::OutOfReach => "target out of reach: the arm stretches toward it",
        Reach::Pending => "drag the target ball, its arrows or rings",
    };
    painter.text(
        rect.left_top() + egui::vec2(10.0, 10.0),
        egui::Align2::LEFT_TOP,
        status,
        small.clone(),
        style::reach_color(reach),
    );
    if let Some(link) = model.hovered_link()
        && let Some(joint) = model.robot().joints.get(link.wrapping_sub(1))
    {
        painter.text(
            rect.right_top() + egui::vec2(-10.0, 10.0),
            egui::Align2::RIGHT_TOP,
            format!(
                "joint {link}: {} — A_{link} and T_0{link} highlighted",
                joint.name
            ),
            small,
            style::HIGHLIGHT,
        );
    }
}
