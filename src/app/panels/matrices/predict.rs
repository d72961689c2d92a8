//! Predict, then reveal (presentation mode): the lecturer hides entries, whole matrices or
//! the Jacobian's columns, the class predicts them, a click reveals them. Apart from the
//! panel because it is a mode of its own with its own state and clicks.

use nalgebra::DMatrix;

use armlab_text::text as text_of;
use armlab_text::{Key, Lang};

use super::MatricesPanel;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::numbers::Advances;
use crate::app::widgets::style;
use armlab_session::settings::{Hidden, HiddenSet, MatrixId};

/// The background of an entry the lecturer chose to hide (while choosing).
pub(super) const HIDDEN_BACKGROUND: egui::Color32 = egui::Color32::from_rgb(120, 70, 20);

/// A matrix block entries can be hidden in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Target {
    /// T_0n, A_i or T_0i: entries or the whole matrix.
    Matrix(MatrixId),
    /// The Jacobian: whole columns.
    Jacobian,
}

impl Target {
    /// The item a click on entry (row, column), from 0, hides or shows while choosing.
    fn item(self, row: usize, column: usize) -> Hidden {
        match self {
            Target::Matrix(id) => Hidden::Entry(id, row + 1, column + 1),
            Target::Jacobian => Hidden::JacobianColumn(column + 1),
        }
    }

    /// The items that hide entry (row, column).
    fn items(self, row: usize, column: usize) -> impl Iterator<Item = Hidden> {
        let whole = match self {
            Target::Matrix(id) => Some(Hidden::Matrix(id)),
            Target::Jacobian => None,
        };
        whole
            .into_iter()
            .chain(std::iter::once(self.item(row, column)))
    }
}

/// One frame's view of what presentation mode hides: the settings' set, the panel's
/// revealed items, and the clicks to apply when the frame's blocks are drawn.
pub(super) struct Hiding {
    /// Presentation mode: hiding applies.
    pub(super) on: bool,
    /// The lecturer is choosing: clicks hide and show instead of revealing.
    pub(super) choosing: bool,
    pub(super) hidden: HiddenSet,
    revealed: Vec<Hidden>,
    /// Items clicked while choosing, to toggle in the settings.
    pub(super) toggled: Vec<Hidden>,
    /// Screen points of the entries and buttons, for the tests.
    points: Vec<(String, egui::Pos2)>,
}

impl Hiding {
    /// Whether a block draws its entries one by one (clickable): while choosing, or when
    /// something in it is hidden.
    pub(super) fn interactive(&self, target: Target) -> bool {
        self.on
            && (self.choosing
                || self.hidden.items().iter().any(|h| match (target, *h) {
                    (Target::Matrix(id), Hidden::Matrix(m) | Hidden::Entry(m, _, _)) => m == id,
                    (Target::Jacobian, Hidden::JacobianColumn(_)) => true,
                    _ => false,
                }))
    }

    /// The hidden item that hides entry (row, column), if any.
    fn hiding_item(&self, target: Target, row: usize, column: usize) -> Option<Hidden> {
        target.items(row, column).find(|h| self.hidden.contains(*h))
    }

    /// The item that conceals entry (row, column) now (hidden and not revealed).
    fn concealing(&self, target: Target, row: usize, column: usize) -> Option<Hidden> {
        (self.on && !self.choosing)
            .then(|| {
                target
                    .items(row, column)
                    .find(|h| self.hidden.contains(*h) && !self.revealed.contains(h))
            })
            .flatten()
    }

    /// The whole-matrix item concealing `id` now, if any.
    pub(super) fn concealed_whole(&self, id: MatrixId) -> Option<Hidden> {
        let whole = Hidden::Matrix(id);
        (self.on
            && !self.choosing
            && self.hidden.contains(whole)
            && !self.revealed.contains(&whole))
        .then_some(whole)
    }

    pub(super) fn point(&mut self, name: String, at: egui::Pos2) {
        self.points.push((name, at));
    }

    /// A whole matrix behind one "?" (the symbolic view's blocks); a click reveals it.
    pub(super) fn concealed_block(
        &mut self,
        ui: &mut egui::Ui,
        lang: Lang,
        title: &str,
        item: Hidden,
    ) -> bool {
        let frame = egui::Frame::group(ui.style()).show(ui, |ui| {
            ui.strong(title);
            let button = ui
                .button(egui::RichText::new("?").strong().size(24.0))
                .on_hover_text(text_of(lang, Key::RevealHint));
            self.point(format!("reveal-{}", item.to_link()), button.rect.center());
            if button.clicked() {
                self.revealed.push(item);
            }
        });
        frame.response.hovered()
    }
}

/// The numbers of a matrix (or of some of its columns) that [`hiding_table`] draws.
pub(super) struct HidingCells<'a> {
    pub(super) m: &'a DMatrix<f64>,
    /// Every entry's text ([`number_texts`](super::export::number_texts), column-major).
    pub(super) texts: &'a [String],
    pub(super) columns: std::ops::Range<usize>,
    pub(super) font: egui::FontId,
    /// The font's advances, as [`fit`](super::fit::fit) measured them (the gap between columns).
    pub(super) advances: Advances,
}

/// The matrix entry by entry (its columns `cells.columns`), each clickable: "?" for a
/// concealed entry (a click reveals it); while choosing, every number, the hidden ones on a
/// dark orange background (a click hides or shows the entry, or the Jacobian's column).
pub(super) fn hiding_table(
    ui: &mut egui::Ui,
    lang: Lang,
    cells: &HidingCells<'_>,
    target: Target,
    hiding: &mut Hiding,
) -> egui::Response {
    let name = match target {
        Target::Matrix(id) => Hidden::Matrix(id).to_link(),
        Target::Jacobian => "J".to_string(),
    };
    let rows = cells.m.nrows();
    let grid = egui::Grid::new(("hiding", name.clone(), cells.columns.start))
        .spacing([cells.advances.gap(), 0.0])
        .min_col_width(0.0)
        .show(ui, |ui| {
            for r in 0..rows {
                for c in cells.columns.clone() {
                    let value = cells.texts.get(c * rows + r).map_or("", String::as_str);
                    let concealed = hiding.concealing(target, r, c);
                    let mut text = match concealed {
                        Some(_) => egui::RichText::new("?").strong().color(style::HIGHLIGHT),
                        None => egui::RichText::new(value),
                    }
                    .font(cells.font.clone());
                    if hiding.choosing && hiding.hiding_item(target, r, c).is_some() {
                        text = text.background_color(HIDDEN_BACKGROUND);
                    }
                    // Right-aligned in its column, as the numbers are everywhere else.
                    let right = egui::Layout::right_to_left(egui::Align::Center);
                    let mut cell = ui
                        .with_layout(right, |ui| {
                            ui.add(egui::Label::new(text).sense(egui::Sense::click()))
                        })
                        .inner;
                    if concealed.is_some() {
                        cell = cell.on_hover_text(text_of(lang, Key::RevealHint));
                    }
                    hiding.point(
                        format!("cell-{name}-{}-{}", r + 1, c + 1),
                        cell.rect.center(),
                    );
                    if cell.clicked() {
                        match (hiding.choosing, concealed) {
                            (true, _) => hiding.toggled.push(target.item(r, c)),
                            (false, Some(item)) => hiding.revealed.push(item),
                            (false, None) => {}
                        }
                    }
                }
                ui.end_row();
            }
        });
    grid.response
}

impl MatricesPanel {
    /// Presentation mode's row (choose what to hide, how many are hidden, hide again) and
    /// this frame's view of the hidden set.
    pub(super) fn hiding(&mut self, model: &Model, ui: &mut egui::Ui) -> Hiding {
        let on = model.hides_entries();
        // Choosing is the lecturer's (presentation mode); a student's page in a class
        // only hides and reveals.
        let presenting = model.settings().presentation;
        let hidden = model.settings().hidden.clone();
        self.revealed.retain(|h| hidden.contains(*h));
        if presenting {
            crate::app::widgets::style::wrapped(ui, |ui| {
                crate::app::widgets::style::switch(
                    ui,
                    &mut self.choosing,
                    tr(model, Key::HideMode),
                )
                .on_hover_text(tr(model, Key::HideModeHint));
                if !hidden.is_empty() {
                    ui.label(trf(model, Key::HiddenCount, &[&hidden.len()]));
                    if ui
                        .button(tr(model, Key::HideAgain))
                        .on_hover_text(tr(model, Key::HideAgainHint))
                        .clicked()
                    {
                        self.revealed.clear();
                    }
                }
            });
        }
        Hiding {
            on,
            choosing: presenting && self.choosing,
            hidden,
            revealed: std::mem::take(&mut self.revealed),
            toggled: Vec::new(),
            points: Vec::new(),
        }
    }

    /// Keeps what was revealed, and writes what was chosen into the settings (the link).
    pub(super) fn finish_hiding(
        &mut self,
        model: &mut Model,
        hiding: Hiding,
        points: &mut ScreenPoints,
    ) {
        self.revealed = hiding.revealed;
        for (name, at) in hiding.points {
            points.insert(name, at);
        }
        if !hiding.toggled.is_empty() {
            let mut settings = model.settings().clone();
            for item in hiding.toggled {
                settings.hidden.toggle(item);
            }
            model.set_settings(settings);
        }
    }

    /// Whether the lecturer is choosing what to hide.
    pub fn choosing(&self) -> bool {
        self.choosing
    }
}
