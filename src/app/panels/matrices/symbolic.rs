//! The symbolic A_i, T_0i and J in the matrices panel (docs/kinematics.md §13): each entry
//! as the robot's constants and the sines and cosines of joint sums (c1, s23, 222.1), the
//! entries that depend on the joint under the pointer (its slider, its link in 3D or its
//! matrix) highlighted, each matrix copyable as LaTeX. A fold of the panel apart from the
//! numbers: its entries are text, built once per robot.

use std::rc::Rc;

use armlab_core::symbolic::EntryText;
use armlab_core::symbolic_tables::{SymbolicTable, SymbolicTables};
use armlab_text::{Key, Lang, fill, text};

use crate::app::platform::symbolic::{Tables, symbolic_tables};
use crate::app::widgets::style;

/// The symbolic tables of the robot last shown, kept until the robot changes.
#[derive(Debug, Clone, Default)]
pub struct SymbolicCache {
    made_for: Option<u64>,
    built: Option<Rc<SymbolicTables>>,
}

impl SymbolicCache {
    /// The tables of the robot with this change count: made once per robot (a few
    /// milliseconds for seven joints); in the page by the lazily loaded module, so they
    /// may still be loading or have failed to.
    pub fn tables(&mut self, robot: &armlab_core::Robot, robot_changes: u64) -> Tables {
        if self.made_for != Some(robot_changes) {
            self.made_for = Some(robot_changes);
            self.built = None;
        }
        if let Some(built) = &self.built {
            return Tables::Ready(built.clone());
        }
        let tables = symbolic_tables(robot);
        if let Tables::Ready(built) = &tables {
            self.built = Some(built.clone());
        }
        tables
    }
}

/// One symbolic matrix in a framed block: its title, a LaTeX copy button and its
/// entries; entries that depend on joint `joint` (from 0) are drawn in the highlight
/// colour. Returns whether the pointer is over the block.
pub fn symbolic_block(
    ui: &mut egui::Ui,
    lang: Lang,
    title: &str,
    m: &SymbolicTable,
    joint: Option<usize>,
    highlighted: bool,
) -> bool {
    let stroke = if highlighted {
        egui::Stroke::new(2.0, style::HIGHLIGHT)
    } else {
        ui.visuals().widgets.noninteractive.bg_stroke
    };
    let frame = egui::Frame::group(ui.style()).stroke(stroke);
    let id = ui.make_persistent_id(("symbolic block", title));
    // Out of sight (below the fold of the side panel), the block keeps its space unlaid.
    style::unless_out_of_sight(ui, id, |ui| {
        let response = frame.show(ui, |ui| {
            crate::app::widgets::style::wrapped(ui, |ui| {
                ui.strong(title);
                if ui
                    .small_button(text(lang, Key::CopyLatex))
                    .on_hover_text(text(lang, Key::CopyAsLatex))
                    .clicked()
                {
                    ui.ctx().copy_text(m.latex.clone());
                }
            });
            symbolic_body(ui, lang, title, m, joint);
        });
        response.response.hovered() || ui.rect_contains_pointer(response.response.rect)
    })
    .unwrap_or(false)
}

/// The gap between a symbolic matrix's columns (points).
const GAP: f32 = 14.0;

/// Each entry's text as drawn, column by column, and whether it is the "too long" note.
fn entry_texts(lang: Lang, m: &SymbolicTable) -> Vec<(String, bool)> {
    (0..m.cols)
        .flat_map(move |c| (0..m.rows).filter_map(move |r| m.entry(r, c)))
        .map(|entry| match &entry.text {
            EntryText::Shown { plain, .. } => (plain.clone(), false),
            EntryText::TooLong { terms } => (fill(lang, Key::SymbolicTooLong, &[terms]), true),
        })
        .collect()
}

/// The cells of (part of) a symbolic matrix: each entry's text column by column, `rows`
/// to a column, and whether the entry in row r, column c depends on the joint under the
/// pointer.
struct Cells<'a> {
    texts: &'a [(String, bool)],
    rows: usize,
    hot: &'a dyn Fn(usize, usize) -> bool,
    font: egui::FontId,
}

/// The entries of [`symbolic_block`] fitted to the visible room as the numeric matrices
/// are: whole at the largest of the fit's text sizes, else in the fewest blocks of
/// columns (the rotation, the position under it), each captioned. A column wider than
/// the room even alone (the position of a six-joint T_06) is a block of its own whose
/// entries break between their terms: a sideways scroll hid it behind a bar few found.
fn symbolic_body(
    ui: &mut egui::Ui,
    lang: Lang,
    title: &str,
    m: &SymbolicTable,
    joint: Option<usize>,
) {
    let texts = entry_texts(lang, m);
    let rows = m.rows;
    let full = egui::TextStyle::Monospace.resolve(ui.style());
    let room = style::room(ui);
    let mut best: Option<(egui::FontId, Vec<std::ops::Range<usize>>)> = None;
    for scale in super::fit::FIT_SCALES {
        let font = egui::FontId::new(full.size * scale, full.family.clone());
        let widths: Vec<f32> = texts
            .chunks(rows)
            .map(|column| {
                let width = |t: &str| style::text_width(ui, t, &font);
                column.iter().map(|(t, _)| width(t)).fold(0.0, f32::max)
            })
            .map(|w| w.min(room))
            .collect();
        if let Some(blocks) = super::fit::column_blocks(&widths, GAP, room)
            && best.as_ref().is_none_or(|(_, b)| blocks.len() < b.len())
        {
            let whole = blocks.len() == 1;
            best = Some((font, blocks));
            if whole {
                break;
            }
        }
    }
    let Some((font, blocks)) = best else {
        return;
    };
    let hot = |c: usize, r: usize| joint.is_some_and(|j| m.depends_on(r, c, j));
    let cells = Cells {
        texts: &texts,
        rows,
        hot: &hot,
        font,
    };
    let cut = blocks.len() > 1;
    for (i, columns) in blocks.into_iter().enumerate() {
        if cut {
            super::block::column_caption(ui, lang, &columns);
        }
        symbolic_grid(ui, (title, i), columns, &cells);
    }
}

/// An entry's text that breaks only between terms: before a sign, never inside a product
/// ("c1 c234 s5" stays whole).
fn breaking_between_terms(text: &str) -> String {
    text.replace(' ', "\u{a0}")
        .replace("\u{a0}+\u{a0}", " +\u{a0}")
        .replace("\u{a0}-\u{a0}", " -\u{a0}")
}

/// The entries of a symbolic matrix's `columns`, those that depend on the joint under the
/// pointer (`hot`) in the highlight colour. A single column's entries wrap at the room
/// (between terms); several columns are a grid, each entry on one line.
fn symbolic_grid(
    ui: &mut egui::Ui,
    id: (&str, usize),
    columns: std::ops::Range<usize>,
    cells: &Cells<'_>,
) {
    let wrap = columns.len() == 1;
    let entry = |ui: &mut egui::Ui, c: usize, r: usize| {
        let (text, too_long) = &cells.texts[c * cells.rows + r];
        let text = if wrap {
            breaking_between_terms(text)
        } else {
            text.clone()
        };
        let mut shown = egui::RichText::new(text).font(cells.font.clone());
        if *too_long {
            shown = shown.weak();
        }
        if (cells.hot)(c, r) {
            shown = shown.color(style::HIGHLIGHT).strong();
        }
        let label = egui::Label::new(shown);
        ui.add(if wrap { label.wrap() } else { label.extend() });
    };
    if wrap {
        // A little space between entries, so that a broken one reads as one.
        ui.scope(|ui| {
            ui.spacing_mut().item_spacing.y += 3.0;
            for r in 0..cells.rows {
                entry(ui, columns.start, r);
            }
        });
        return;
    }
    egui::Grid::new(("symbolic", id.0, id.1))
        .num_columns(columns.len())
        .spacing([GAP, 2.0])
        .show(ui, |ui| {
            for r in 0..cells.rows {
                for c in columns.clone() {
                    entry(ui, c, r);
                }
                ui.end_row();
            }
        });
}
