//! Text labels over the 3D picture that never cover one another: each goes at its anchor
//! if the place is free, else at the nearest free place around it, with a leader line
//! back to the anchor.

use egui::{Color32, Pos2, Rect, Vec2};

/// The gap (points) kept between two labels and between a label and the view's edge.
const GAP: f32 = 2.0;
/// The rings of candidate places around an anchor: their spacing and count (points).
const RING_STEP: f32 = 7.0;
const RINGS: usize = 26;
/// Candidate directions on each ring.
const DIRECTIONS: usize = 16;
/// A label this far (points) from its anchor or more gets a leader line.
const LEADER_FROM: f32 = 4.0;

/// A label placed by [`Placer`].
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// The text.
    pub text: String,
    /// Where it is drawn (with its background).
    pub rect: Rect,
    /// The point it labels.
    pub anchor: Pos2,
}

/// Places labels one by one in a view, each where no earlier one is.
pub struct Placer {
    view: Rect,
    placed: Vec<Placed>,
    /// Lines a label should leave visible where it can (the dimensions it names).
    lines: Vec<[Pos2; 2]>,
}

impl Placer {
    /// An empty view `view`; labels keep inside it.
    pub fn new(view: Rect) -> Self {
        Placer {
            view,
            placed: Vec::new(),
            lines: Vec::new(),
        }
    }

    /// Asks labels to keep off the line `a`–`b` where they can.
    pub fn keep_clear(&mut self, a: Pos2, b: Pos2) {
        self.lines.push([a, b]);
    }

    /// Whether a label at `rect` overlaps none placed and lies inside the view (and, when
    /// `clear`, crosses none of the lines kept clear).
    fn free(&self, rect: Rect, clear: bool) -> bool {
        self.view.shrink(GAP).contains_rect(rect)
            && self
                .placed
                .iter()
                .all(|p| !p.rect.expand(GAP).intersects(rect))
            && !(clear && self.lines.iter().any(|&l| crosses(l, rect)))
    }

    /// Places a label of `size` for `anchor`: centred on `anchor + shift` when free, else
    /// at the nearest free place on rings around it; where nothing is free (a crowded
    /// phone screen), at the place that overlaps the placed labels least.
    pub fn place(&mut self, text: String, size: Vec2, anchor: Pos2, shift: Vec2) -> Rect {
        let at = |c: Pos2| Rect::from_center_size(c, size);
        let candidates = around(anchor + shift, RINGS).map(at);
        let rect = candidates
            .clone()
            .find(|&r| self.free(r, true))
            .or_else(|| candidates.clone().find(|&r| self.free(r, false)))
            .unwrap_or_else(|| {
                candidates
                    .map(|r| (self.overlap(r), r))
                    .fold((f32::INFINITY, at(anchor + shift)), |a, b| {
                        if b.0 < a.0 { b } else { a }
                    })
                    .1
            });
        self.placed.push(Placed { text, rect, anchor });
        rect
    }

    /// Places a label of `size` for `anchor` centred on `anchor + shift` or within
    /// `reach` points of it, only where it covers no placed label and no line kept
    /// clear; `None` (nothing placed) where the view has no such room.
    pub fn try_place(
        &mut self,
        text: String,
        size: Vec2,
        (anchor, shift): (Pos2, Vec2),
        reach: f32,
    ) -> Option<Rect> {
        let rings = (reach / RING_STEP).floor() as usize;
        let rect = around(anchor + shift, rings)
            .map(|c| Rect::from_center_size(c, size))
            .find(|&r| self.free(r, true))?;
        self.placed.push(Placed { text, rect, anchor });
        Some(rect)
    }

    /// How much of `rect` the placed labels and the view's outside cover (points²).
    fn overlap(&self, rect: Rect) -> f32 {
        let inside = rect.intersect(self.view).area().max(0.0);
        let outside = rect.area() - inside;
        let covered: f32 = self
            .placed
            .iter()
            .map(|p| {
                let i = p.rect.intersect(rect);
                if i.is_positive() { i.area() } else { 0.0 }
            })
            .sum();
        covered + outside
    }

    /// Consumes the placer, giving its labels.
    pub fn into_placed(self) -> Vec<Placed> {
        self.placed
    }
}

/// Candidate centres: `home`, then [`DIRECTIONS`] points on each of `rings` rings
/// around it, nearest first.
fn around(home: Pos2, rings: usize) -> impl Iterator<Item = Pos2> + Clone {
    (0..=rings).flat_map(move |ring| {
        let count = if ring == 0 { 1 } else { DIRECTIONS };
        (0..count).map(move |k| {
            let angle = k as f32 / DIRECTIONS as f32 * std::f32::consts::TAU;
            home + Vec2::angled(angle) * (ring as f32 * RING_STEP)
        })
    })
}

/// Whether the segment `a`–`b` passes through `rect` (clipped to it, Liang–Barsky).
fn crosses([a, b]: [Pos2; 2], rect: Rect) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f32, 1.0_f32);
    for (p, q) in [
        (-d.x, a.x - rect.min.x),
        (d.x, rect.max.x - a.x),
        (-d.y, a.y - rect.min.y),
        (d.y, rect.max.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    t0 <= t1
}

/// Draws a label's background and `galley` in `rect`, and a leader line in `color` from
/// its edge to the anchor when it sits away from it.
pub fn draw(
    painter: &egui::Painter,
    rect: Rect,
    anchor: Pos2,
    galley: std::sync::Arc<egui::Galley>,
    color: Color32,
) {
    let edge = rect.clamp(anchor);
    if edge.distance(anchor) >= LEADER_FROM {
        let stroke = egui::Stroke::new(1.0, color.gamma_multiply(0.8));
        painter.line_segment([edge, anchor], stroke);
        painter.circle_filled(anchor, 2.5, color);
    }
    painter.rect_filled(rect, 3.0, Color32::from_black_alpha(190));
    let text_at = rect.center() - galley.size() * 0.5;
    painter.galley(text_at, galley, color);
}
