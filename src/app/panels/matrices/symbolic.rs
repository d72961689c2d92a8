//! The symbolic A_i and T_0i in the matrices panel (docs/kinematics.md §13): each entry as
//! the robot's constants and the sines and cosines of joint sums (c1, s23, 222.1), the
//! entries that depend on the joint under the pointer (its slider, its link in 3D or its
//! matrix) highlighted, each matrix copyable as LaTeX. A fold of the panel apart from the
//! numbers: its entries are text, built once per robot.

use armlab_core::symbolic::{EntryText, SymbolicChain, SymbolicMatrix, symbolic_chain};
use armlab_text::{Key, Lang, fill, text};

use crate::app::widgets::style;

/// The symbolic chain of the robot last shown, kept until the robot changes.
#[derive(Debug, Clone, Default)]
pub struct SymbolicCache {
    made_for: Option<u64>,
    chain: Option<SymbolicChain>,
}

impl SymbolicCache {
    /// The chain of the robot with this change count (built once per robot: a few
    /// milliseconds for seven joints).
    pub fn chain(&mut self, robot: &armlab_core::Robot, robot_changes: u64) -> &SymbolicChain {
        if self.made_for != Some(robot_changes) {
            self.made_for = Some(robot_changes);
            self.chain = None;
        }
        self.chain.get_or_insert_with(|| symbolic_chain(robot))
    }
}

/// One symbolic matrix in a framed block: its title, a LaTeX copy button and the 4 × 4
/// entries; entries that depend on joint `joint` (from 0) are drawn in the highlight
/// colour. Returns whether the pointer is over the block.
pub fn symbolic_block(
    ui: &mut egui::Ui,
    lang: Lang,
    title: &str,
    m: &SymbolicMatrix,
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
                    ui.ctx().copy_text(m.latex());
                }
            });
            // Sideways in its own scroll area, as the numeric matrices: entries never wrap,
            // and the column does not grow to the widest T_0i.
            egui::ScrollArea::horizontal()
                .id_salt(("symbolic scroll", title))
                .show(ui, |ui| {
                    symbolic_grid(ui, lang, title, m, joint);
                });
        });
        response.response.hovered() || ui.rect_contains_pointer(response.response.rect)
    })
    .unwrap_or(false)
}

/// The 4 × 4 entries of [`symbolic_block`], each on one line.
fn symbolic_grid(
    ui: &mut egui::Ui,
    lang: Lang,
    title: &str,
    m: &SymbolicMatrix,
    joint: Option<usize>,
) {
    egui::Grid::new(("symbolic", title))
        .num_columns(4)
        .spacing([14.0, 2.0])
        .show(ui, |ui| {
            for row in &m.entries {
                for entry in row {
                    let shown = match entry.text() {
                        EntryText::Shown { plain, .. } => egui::RichText::new(plain).monospace(),
                        EntryText::TooLong { terms } => {
                            egui::RichText::new(fill(lang, Key::SymbolicTooLong, &[&terms])).weak()
                        }
                    };
                    let hot = joint.is_some_and(|j| entry.depends_on(j));
                    ui.add(
                        egui::Label::new(if hot {
                            shown.color(style::HIGHLIGHT).strong()
                        } else {
                            shown
                        })
                        .extend(),
                    );
                }
                ui.end_row();
            }
        });
}
