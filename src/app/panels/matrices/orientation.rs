//! The tool's orientation in four forms (ZYX Euler, XYZ fixed, angle-axis, Euler
//! parameters). Apart from the panel: a fold of its own that reads only the orientation.

use armlab_core::Orientation;
use armlab_text::{Key, Lang, text};

use crate::app::widgets::style;
use crate::app::widgets::style::NameRow;
use armlab_session::format::fixed;

pub(super) fn orientation_block(
    ui: &mut egui::Ui,
    lang: Lang,
    o: &Orientation,
    degrees: bool,
    decimals: usize,
) {
    let t = |key| text(lang, key);
    let note = |degenerate: bool, key| {
        if degenerate {
            format!("  {}", text(lang, key))
        } else {
            String::new()
        }
    };
    let ang = |v: f64| {
        if degrees {
            format!("{}°", fixed(v.to_degrees(), decimals.min(4)))
        } else {
            fixed(v, decimals.max(3))
        }
    };
    egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
        ui,
        t(Key::ToolOrientation),
    ))
    .id_salt("tool_orientation")
    .default_open(true)
    .show(ui, |ui| {
        let e = o.zyx_euler;
        let f = o.xyz_fixed;
        let a = o.angle_axis;
        let q = o.euler_parameters;
        let row = |key: Key, value: String| NameRow {
            name: t(key).to_owned(),
            hint: None,
            values: vec![value],
        };
        let rows = [
            row(
                Key::ZyxEuler,
                format!(
                    "{}  {}  {}{}",
                    ang(e.alpha),
                    ang(e.beta),
                    ang(e.gamma),
                    note(e.degenerate, Key::ZyxDegenerate)
                ),
            ),
            row(
                Key::XyzFixed,
                format!("{}  {}  {}", ang(f.gamma), ang(f.beta), ang(f.alpha)),
            ),
            row(
                Key::AngleAxis,
                format!(
                    "{}  ({}, {}, {}){}",
                    ang(a.angle),
                    fixed(a.axis.x, 4),
                    fixed(a.axis.y, 4),
                    fixed(a.axis.z, 4),
                    note(a.degenerate, Key::AngleAxisDegenerate)
                ),
            ),
            row(
                Key::EulerParameters,
                [q.e1, q.e2, q.e3, q.e4].map(|v| fixed(v, 5)).join("  "),
            ),
        ];
        style::fold_rows(ui, "orientation", &[], &rows);
    });
}
