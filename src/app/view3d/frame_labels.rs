//! The DH frames' axis names over the 3D picture: x_i and z_i at the tips of frame i's
//! axes (y follows from them), where the view has room for them.

use egui::{Color32, Pos2};
use nalgebra::Point3;

use super::labels::{self, Placed, Placer};
use super::scene::{AXIS, frame_axis_length};
use crate::app::state::model::Model;
use crate::app::widgets::math;

/// How far (points) a name may move from its axis's tip to find room.
const ROOM: f32 = 14.0;

/// Names the x and z axes of every DH frame drawn (the base's 0, each joint frame's
/// number, the tool's "t" where it is apart from the last frame), each beside its axis's
/// tip, in the axis's colour; a name that would cover another, or an axis, is left out.
/// Gives the names as placed.
pub fn draw_in_view(
    model: &Model,
    painter: &egui::Painter,
    view: egui::Rect,
    project: &dyn Fn(&Point3<f64>) -> Option<Pos2>,
) -> Vec<Placed> {
    let robot = model.robot();
    let fk = model.fk();
    let len = frame_axis_length(robot.reach());
    let size = if model.settings().presentation {
        16.0
    } else {
        13.0
    };
    let font = egui::FontId::proportional(size);
    let n = fk.base_from_frames.len();
    let last = fk.base_from_frames.last().copied();
    let tool_apart = last.is_none_or(|f| {
        (f.translation.vector - fk.base_from_tool.translation.vector).norm() > len * 0.2
    });
    let mut frames: Vec<(String, _)> = std::iter::once(robot.world_from_base)
        .chain(fk.base_from_frames.iter().copied())
        .enumerate()
        .map(|(k, f)| (k.to_string(), f))
        .collect();
    if tool_apart || n == 0 {
        frames.push(("t".into(), fk.base_from_tool));
    }
    let mut placer = Placer::new(view);
    // The axes themselves are kept clear, so that no name hides a frame.
    let mut tips = Vec::new();
    for (name, f) in &frames {
        let o = Point3::from(f.translation.vector);
        let Some(origin) = project(&o) else { continue };
        for c in [0, 1, 2] {
            let dir = f.rotation.matrix().column(c).into_owned();
            if let Some(tip) = project(&(o + dir * len)) {
                placer.keep_clear(origin, tip);
                if c != 1 {
                    tips.push((name.clone(), c, origin, tip));
                }
            }
        }
    }
    for (name, c, origin, tip) in tips {
        let [r, g, b, _] = AXIS[c];
        let color = Color32::from_rgb(r, g, b);
        // x_{name}, z_{name}: the braces as escapes, apart from the format string.
        let axis = if c == 0 { "x_" } else { "z_" };
        let source = [axis, "\u{7b}", &name, "\u{7d}"].concat();
        let galley = painter.layout_job(math::job(&source, &font, color));
        let box_size = galley.size() + egui::vec2(6.0, 2.0);
        let out = (tip - origin).normalized() * (box_size.length() * 0.5 + 2.0);
        let text = math::plain(&source);
        if let Some(rect) = placer.try_place(text, box_size, (tip, out), ROOM) {
            labels::draw(painter, rect, tip, galley, color);
        }
    }
    placer.into_placed()
}
