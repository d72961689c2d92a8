//! A small hand-drawn plot, shared by the IK panel's error per iteration and the Motion
//! panel's time series: a box, data lines mapped from data ranges to the box, dashed
//! horizontal lines (goals), a shaded band (a dead band) and a caption in the corner.
//! Painted with egui's painter: egui_plot does not fit the page's download budget.

use egui::{Color32, Pos2, Rect, Stroke};

/// The caption's font size (points).
pub const CAPTION_SIZE: f32 = 11.0;

/// One plot's box and the data ranges it maps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotBox {
    /// The box on screen.
    pub rect: Rect,
    /// The data's x range (left, right).
    pub x: (f64, f64),
    /// The data's y range (bottom, top).
    pub y: (f64, f64),
    /// Its node in the accessibility tree.
    id: egui::Id,
}

impl PlotBox {
    /// Takes a box of `size` from `ui`, up to 300 points wide, and strokes its edge; the
    /// ranges are the data's (an empty range is widened so nothing divides by zero).
    pub fn allocate(ui: &mut egui::Ui, height: f32, x: (f64, f64), y: (f64, f64)) -> PlotBox {
        let (rect, response) = ui.allocate_exact_size(
            egui::vec2(crate::app::widgets::style::room(ui).min(300.0), height),
            egui::Sense::hover(),
        );
        ui.painter_at(rect).rect_stroke(
            rect,
            2.0,
            ui.visuals().widgets.noninteractive.bg_stroke,
            egui::StrokeKind::Inside,
        );
        PlotBox {
            rect,
            x: widen(x),
            y: widen(y),
            id: response.id,
        }
    }

    /// The screen point of data point `(x, y)`.
    pub fn to_screen(&self, x: f64, y: f64) -> Pos2 {
        let r = self.rect;
        egui::pos2(
            r.left() + r.width() * ((x - self.x.0) / (self.x.1 - self.x.0)) as f32,
            r.bottom() - r.height() * ((y - self.y.0) / (self.y.1 - self.y.0)) as f32,
        )
    }

    /// A data line through `points` (`[x, y]`), clipped to the box.
    pub fn line(&self, ui: &egui::Ui, points: impl Iterator<Item = [f64; 2]>, stroke: Stroke) {
        let points: Vec<Pos2> = points
            .filter(|[x, y]| x.is_finite() && y.is_finite())
            .map(|[x, y]| self.to_screen(x, y))
            .collect();
        if points.len() >= 2 {
            ui.painter_at(self.rect)
                .add(egui::Shape::line(points, stroke));
        }
    }

    /// A dashed horizontal line at `y` (a goal).
    pub fn goal(&self, ui: &egui::Ui, y: f64, color: Color32) {
        if !y.is_finite() {
            return;
        }
        let a = self.to_screen(self.x.0, y);
        let b = self.to_screen(self.x.1, y);
        ui.painter_at(self.rect).extend(egui::Shape::dashed_line(
            &[a, b],
            Stroke::new(1.0, color),
            4.0,
            3.0,
        ));
    }

    /// A shaded band between `lo` and `hi` (a dead band or a settling band).
    pub fn band(&self, ui: &egui::Ui, lo: f64, hi: f64, color: Color32) {
        if !(lo.is_finite() && hi.is_finite()) {
            return;
        }
        let a = self.to_screen(self.x.0, hi);
        let b = self.to_screen(self.x.1, lo);
        ui.painter_at(self.rect).rect_filled(
            Rect::from_two_pos(a, b).intersect(self.rect),
            0.0,
            color,
        );
    }

    /// A dot at a data point (the replayed iteration).
    pub fn dot(&self, ui: &egui::Ui, x: f64, y: f64, color: Color32) {
        ui.painter_at(self.rect)
            .circle_filled(self.to_screen(x, y), 3.5, color);
    }

    /// The caption in the box's top-left corner.
    pub fn caption(&self, ui: &egui::Ui, text: String) {
        ui.painter_at(self.rect).text(
            self.rect.left_top() + egui::vec2(4.0, 2.0),
            egui::Align2::LEFT_TOP,
            text,
            egui::FontId::proportional(CAPTION_SIZE),
            ui.visuals().text_color(),
        );
    }

    /// Gives the plot to a screen reader as a picture whose name says its data in words:
    /// `words` is called only when the accessibility tree is being built, so frames that do
    /// not build it pay nothing for the text.
    pub fn describe(&self, ui: &egui::Ui, words: impl FnOnce() -> String) {
        ui.ctx().accesskit_node_builder(self.id, |node| {
            node.set_role(egui::accesskit::Role::Image);
            node.set_label(words());
        });
    }
}

/// A series in words: its name, its first and last value, its least and most (the values
/// as `number` writes them), or `None` without a finite value.
pub fn series_words(
    lang: armlab_text::Lang,
    name: &str,
    values: impl Iterator<Item = f64>,
    number: impl Fn(f64) -> String,
) -> Option<String> {
    let values: Vec<f64> = values.filter(|v| v.is_finite()).collect();
    let (first, last) = (values.first()?, values.last()?);
    let (lo, hi) = range_of(values.iter().copied());
    Some(armlab_text::fill(
        lang,
        armlab_text::Key::PlotSeries,
        &[
            &name,
            &number(*first),
            &number(*last),
            &number(lo),
            &number(hi),
        ],
    ))
}

/// The smallest and largest finite value (`(0, 1)` when there is none).
pub fn range_of(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi { (0.0, 1.0) } else { (lo, hi) }
}

/// A range at least 1e−9 wide (a flat line sits at the bottom, as in the IK error plot).
fn widen((lo, hi): (f64, f64)) -> (f64, f64) {
    (lo, lo + (hi - lo).max(1e-9))
}
