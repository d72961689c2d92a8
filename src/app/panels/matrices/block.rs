//! One matrix in a framed block: its title and copy buttons, and its numbers fitted to
//! the column (whole, smaller, or cut into blocks of columns), or its clickable entries
//! while predict-and-reveal applies. Apart from the panel so that the panel reads as the
//! list of what it shows.

use nalgebra::DMatrix;

use armlab_text::text as text_of;
use armlab_text::{Key, Lang, fill, text};

use super::export::{number_texts, to_latex, to_numpy, to_plain};
use super::fit::{Fit, fit};
use super::predict::{HIDDEN_BACKGROUND, Hiding, HidingCells, Target, hiding_table};
use crate::app::widgets::numbers::number_table;
use crate::app::widgets::style;
use armlab_session::settings::Hidden;

/// What a matrix's rows and columns stand for: the headers a screen reader says with an
/// entry (the panel shows none, the page's mirror of the accessibility tree has them).
#[derive(Clone, Copy)]
pub(super) enum Axes<'a> {
    /// A homogeneous transform: its columns are a frame's x, y and z axes and its origin,
    /// its rows their x, y and z components and the homogeneous row.
    Pose,
    /// The Jacobian: a row per component of the tool's velocity and angular velocity, a
    /// column per joint.
    Jacobian(&'a [armlab_core::Joint]),
}

impl Axes<'_> {
    /// The row headers and the column headers, each list separated by `|`: the form the
    /// page's mirror reads from the table's node (`row_index_text`, `column_index_text`).
    fn headers(self, lang: Lang) -> (String, String) {
        match self {
            Axes::Pose => (
                text(lang, Key::PoseRowHeaders).into(),
                text(lang, Key::PoseColumnHeaders).into(),
            ),
            Axes::Jacobian(joints) => (
                text(lang, Key::JacobianRowHeaders).into(),
                (joints.iter().enumerate())
                    .map(|(i, j)| crate::app::widgets::math::joint_symbol(i, j.kind))
                    .collect::<Vec<_>>()
                    .join("|"),
            ),
        }
    }
}

/// A matrix with copy buttons; returns true when it is hovered.
///
/// Blocks scrolled out of sight keep their last size without being laid out
/// ([`style::unless_out_of_sight`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn matrix_block(
    ui: &mut egui::Ui,
    lang: Lang,
    title: &str,
    hover: &str,
    m: &DMatrix<f64>,
    decimals: usize,
    (highlighted, axes): (bool, Axes<'_>),
    (target, hiding): (Target, &mut Hiding),
) -> bool {
    let frame = egui::Frame::group(ui.style()).stroke(if highlighted {
        egui::Stroke::new(2.0, style::HIGHLIGHT)
    } else {
        ui.visuals().widgets.noninteractive.bg_stroke
    });
    let id = ui.make_persistent_id(("matrix block", title));
    style::unless_out_of_sight(ui, id, |ui| {
        frame
            .show(ui, |ui| {
                let over_header =
                    matrix_header(ui, lang, (title, hover), m, decimals, target, hiding);
                let over_body = matrix_body(ui, (lang, axes), title, m, decimals, (target, hiding));
                over_header || over_body
            })
            .inner
    })
    .unwrap_or(false)
}

/// A matrix block's title, copy buttons and (while choosing what to hide) its "?"
/// button; returns whether the title row is hovered. Left to right and wrapping: a
/// narrow column puts the copy buttons under the title instead of over it.
fn matrix_header(
    ui: &mut egui::Ui,
    lang: Lang,
    (title, hover): (&str, &str),
    m: &DMatrix<f64>,
    decimals: usize,
    target: Target,
    hiding: &mut Hiding,
) -> bool {
    let header = crate::app::widgets::style::wrapped(ui, |ui| {
        let title = ui.strong(title).on_hover_text(hover);
        ui.label(egui::RichText::new(text(lang, Key::Copy)).weak());
        type Format = fn(&DMatrix<f64>, usize) -> String;
        let formats: [(Key, Key, Format); 3] = [
            (Key::CopyText, Key::CopyAsText, to_plain),
            (Key::CopyLatex, Key::CopyAsLatex, to_latex),
            (Key::CopyNumpy, Key::CopyAsNumpy, to_numpy),
        ];
        for (label, hint, format) in formats {
            if ui
                .small_button(text(lang, label))
                .on_hover_text(text(lang, hint))
                .clicked()
            {
                ui.ctx().copy_text(format(m, decimals));
            }
        }
        if let (true, Target::Matrix(id)) = (hiding.choosing, target) {
            let whole = Hidden::Matrix(id);
            let mut text = egui::RichText::new("?").strong();
            if hiding.hidden.contains(whole) {
                text = text.background_color(HIDDEN_BACKGROUND);
            }
            let button = ui
                .small_button(text)
                .on_hover_text(text_of(lang, Key::HideWhole));
            hiding.point(format!("hide-{}", whole.to_link()), button.rect.center());
            if button.clicked() {
                hiding.toggled.push(whole);
            }
        }
        title.hovered()
    });
    header.inner || header.response.hovered()
}

/// A matrix block's numbers (or, while hiding applies, its clickable entries); returns
/// whether they are hovered. Scrolled out of sight, the block keeps its last size
/// without drawing. The numbers are drawn whole at the largest of [`FIT_SCALES`](super::fit::FIT_SCALES) that
/// fits the column's visible width ([`fit`]). A matrix wider than that even at the
/// smallest (the 6×6 Jacobian in a projector's side column) is cut into blocks of
/// columns, one under the other, each captioned with its columns, as a book prints a wide
/// matrix: a sideways scroll hid columns a lecture hall could not see. Only where not even
/// one column fits does it scroll sideways, with its scroll bar always shown.
fn matrix_body(
    ui: &mut egui::Ui,
    (lang, axes): (Lang, Axes<'_>),
    title: &str,
    m: &DMatrix<f64>,
    decimals: usize,
    (target, hiding): (Target, &mut Hiding),
) -> bool {
    let id = ui.make_persistent_id(("matrix body", title));
    style::unless_out_of_sight(ui, id, |ui| {
        // Each number formatted once a frame, for the fit and for the table.
        let texts = number_texts(m, decimals);
        let full = egui::TextStyle::Monospace.resolve(ui.style());
        let fitted = fit(ui, &texts, m.nrows(), &full);
        // The clickable entries of predict-and-reveal or the plain numbers; a "?" in place
        // of a number is as wide as a digit, so the same fit holds for both. `labelled`:
        // the first block carries the whole matrix's screen-reader text.
        let interactive = hiding.interactive(target);
        let mut table = |ui: &mut egui::Ui, columns, labelled, font, advances| {
            if interactive {
                let cells = HidingCells {
                    m,
                    texts: &texts,
                    columns,
                    font,
                    advances,
                };
                hiding_table(ui, lang, &cells, target, hiding).hovered()
            } else {
                let columns = (columns, labelled);
                let plain = || to_plain(m, decimals);
                let texts = (texts.as_slice(), m.nrows());
                let response = number_table(ui, texts, &plain, columns, font, advances);
                // The matrix's name is the table's caption; its axes, the headers.
                if labelled {
                    ui.ctx().accesskit_node_builder(response.id, |node| {
                        node.set_description(crate::app::widgets::math::plain(title));
                        let (rows, columns) = axes.headers(lang);
                        node.set_row_index_text(rows);
                        node.set_column_index_text(columns);
                    });
                }
                response.hovered()
            }
        };
        match fitted {
            Fit::Blocks(font, advances, blocks) => {
                let cut = blocks.len() > 1;
                let mut hovered = false;
                for (i, columns) in blocks.into_iter().enumerate() {
                    if cut {
                        column_caption(ui, lang, &columns);
                    }
                    hovered |= table(ui, columns, i == 0, font.clone(), advances);
                }
                hovered
            }
            Fit::Scroll(advances) => {
                ui.scope(|ui| {
                    ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
                    egui::ScrollArea::horizontal()
                        .id_salt(("matrix scroll", title))
                        .scroll_bar_visibility(
                            egui::scroll_area::ScrollBarVisibility::AlwaysVisible,
                        )
                        .show(ui, |ui| table(ui, 0..m.ncols(), true, full, advances))
                        .inner
                })
                .inner
            }
        }
    })
    .unwrap_or(false)
}

/// The caption over one block of a matrix cut into blocks of columns ([`Fit::Blocks`]).
pub(super) fn column_caption(ui: &mut egui::Ui, lang: Lang, columns: &std::ops::Range<usize>) {
    let caption = if columns.len() == 1 {
        fill(lang, Key::MatrixColumn, &[&columns.end])
    } else {
        fill(
            lang,
            Key::MatrixColumns,
            &[&(columns.start + 1), &columns.end],
        )
    };
    ui.label(egui::RichText::new(caption).weak());
}
