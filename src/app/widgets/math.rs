//! Formulas as egui text, written as in LaTeX's simplest form: `x_i` and `a_{i−1}` are
//! subscripts, `x^2` and `T^{-1}` superscripts (smaller, lowered or raised); a letter
//! standing alone (a variable: `a`, `θ`, `A`) is italic, words (`DH`, `min`) upright.

use armlab_core::JointKind;
use egui::text::{LayoutJob, TextFormat};
use egui::{Align, Color32, FontId};

/// Where a piece of a formula sits.
#[derive(Clone, Copy, PartialEq)]
enum Level {
    Line,
    Sub,
    Sup,
}

/// A subscript's or superscript's size against the line's.
const SCRIPT_SIZE: f32 = 0.72;

/// Lays out `source` in `font` and `color`: `_` and `^` take the next character or the
/// group in braces as a subscript or superscript.
pub fn job(source: &str, font: &FontId, color: Color32) -> LayoutJob {
    let mut job = LayoutJob::default();
    let mut chars = source.chars().peekable();
    let mut line = String::new();
    while let Some(c) = chars.next() {
        let level = match c {
            '_' => Level::Sub,
            '^' => Level::Sup,
            _ => {
                line.push(c);
                continue;
            }
        };
        append(
            &mut job,
            &std::mem::take(&mut line),
            Level::Line,
            font,
            color,
        );
        let mut group = String::new();
        if chars.peek() == Some(&'\u{7b}') {
            chars.next();
            for g in chars.by_ref() {
                if g == '\u{7d}' {
                    break;
                }
                group.push(g);
            }
        } else if let Some(g) = chars.next() {
            group.push(g);
        }
        append(&mut job, &group, level, font, color);
    }
    append(&mut job, &line, Level::Line, font, color);
    job
}

/// Appends `text` at `level`: each run of letters of one letter in italics.
fn append(job: &mut LayoutJob, text: &str, level: Level, font: &FontId, color: Color32) {
    let size = if level == Level::Line {
        font.size
    } else {
        font.size * SCRIPT_SIZE
    };
    let format = |italics: bool| TextFormat {
        font_id: FontId::new(size, font.family.clone()),
        color,
        italics,
        valign: match level {
            Level::Sup => Align::TOP,
            // A subscript hangs below the line's baseline (egui aligns a smaller font's
            // box to the row's bottom, the line's descender).
            Level::Line | Level::Sub => Align::BOTTOM,
        },
        ..Default::default()
    };
    let chars: Vec<char> = text.chars().collect();
    let mut start = 0;
    while start < chars.len() {
        let letter = chars[start].is_alphabetic();
        let mut end = start + 1;
        while end < chars.len() && chars[end].is_alphabetic() == letter {
            end += 1;
        }
        let run: String = chars[start..end].iter().collect();
        job.append(&run, 0.0, format(letter && end - start == 1));
        start = end;
    }
}

/// A label showing `source` as a formula in the body font and text colour.
pub fn label(ui: &mut egui::Ui, source: &str) -> egui::Response {
    let font = egui::TextStyle::Body.resolve(ui.style());
    let color = ui.visuals().text_color();
    let mut job = job(source, &font, color);
    job.wrap.max_width = ui.available_width();
    ui.label(job)
}

/// The text of a formula as a screen reader reads it (the marks taken out).
pub fn plain(source: &str) -> String {
    source
        .chars()
        .filter(|c| !matches!(c, '_' | '^' | '\u{7b}' | '\u{7d}'))
        .collect()
}

/// The letter of a joint's variable: θ for a revolute joint, d for a prismatic one.
pub fn joint_variable(kind: JointKind) -> &'static str {
    match kind {
        JointKind::Revolute => "θ",
        JointKind::Prismatic => "d",
    }
}

/// Joint `i`'s (from 0) variable with its number, as its slider and the Jacobian's column
/// are named: θ2, d3.
pub fn joint_symbol(i: usize, kind: JointKind) -> String {
    format!("{}{}", joint_variable(kind), i + 1)
}
