//! Where the panels go for the screen, so that the arm always shows.
//!
//! - **Wide** (a landscape screen at least [`NARROW_BELOW_CSS_PX`] CSS pixels wide): side
//!   columns beside the 3D view, each with a strip of edge tabs that open and close its
//!   panels. Normally the joints, IK and robot panels go left and the matrices right, and
//!   the columns and their strips together take at most half of the width; in
//!   presentation mode every panel goes right and they take at most 40 %.
//! - **Narrow** (portrait tablets, phones): the 3D view fills the width; a tab bar at the
//!   bottom opens one panel at a time as a sheet below the view (the view keeps the rest
//!   of the height and reframes the arm).
//!
//! The plan is a pure function of the screen's size and the settings; the widths it gives
//! bound what a user can drag a column to, and what any content (a long number typed into
//! a DH cell) can push it to.

use armlab_session::settings::{PanelKind, PanelSet, Settings};

/// Below this width (CSS pixels) the layout is narrow.
pub const NARROW_BELOW_CSS_PX: f32 = 900.0;
/// The width of a strip of edge tabs (points).
pub const EDGE_TAB_WIDTH: f32 = 30.0;
/// The narrowest a side column gets (points), when there is room.
pub const MIN_COLUMN: f32 = 200.0;
/// The share of the screen's height a narrow layout's sheet takes.
pub const SHEET_SHARE: f32 = 0.45;

/// Wide or narrow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Side columns beside the view.
    Wide,
    /// The view over a bottom sheet.
    Narrow,
}

/// Which side a column is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The left edge.
    Left,
    /// The right edge.
    Right,
}

/// One side column of the wide layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// Its edge (its tabs sit on the screen's edge, the column between them and the view).
    pub side: Side,
    /// Every panel that lives in this column: one edge tab each.
    pub tabs: Vec<PanelKind>,
    /// The open ones, drawn one under the other.
    pub open: Vec<PanelKind>,
    /// The width it opens at (points).
    pub default_width: f32,
    /// The narrowest it can be dragged to (points).
    pub min_width: f32,
    /// The widest it can be dragged or pushed to, whatever the other column does (points).
    pub max_width: f32,
}

/// The layout for a screen.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Wide or narrow.
    pub mode: Mode,
    /// The wide layout's columns (empty when narrow); a column with no tabs is left out.
    pub columns: Vec<Column>,
    /// The share of the width the side columns and their tab strips may take together.
    pub side_share: f32,
    /// The narrow layout's sheet height (points; 0 when wide).
    pub sheet_height: f32,
    /// The screen's width (points).
    pub width: f32,
}

/// The plan for a screen of `size` points, `css_width` CSS pixels wide.
pub fn plan(size: egui::Vec2, css_width: f32, settings: &Settings) -> Plan {
    if css_width < NARROW_BELOW_CSS_PX || size.x < size.y * 0.9 {
        return Plan {
            mode: Mode::Narrow,
            columns: Vec::new(),
            side_share: 0.0,
            sheet_height: (size.y * SHEET_SHARE).round(),
            width: size.x,
        };
    }
    let open = settings.open_panels();
    let (side_share, sides) = sides(settings.presentation);
    let strips = EDGE_TAB_WIDTH * sides.len() as f32;
    let budget = (size.x * side_share - strips).max(0.0);
    let open_sides: Vec<Side> = sides
        .iter()
        .filter(|(_, tabs)| tabs.iter().any(|k| open.contains(*k)))
        .map(|(side, _)| *side)
        .collect();
    let open_columns = open_sides.len().max(1) as f32;
    // Each open column may grow to the budget less the others' narrowest.
    let min_width = MIN_COLUMN.min(budget / open_columns);
    let max_width = budget - min_width * (open_columns - 1.0);
    let wish = |side: Side| column_wish(side, settings.presentation, size.x, budget);
    // The open columns' wishes, scaled down together when they exceed the budget.
    let wished: f32 = open_sides.iter().map(|side| wish(*side)).sum();
    let scale = if wished > budget {
        budget / wished
    } else {
        1.0
    };
    let columns = sides
        .into_iter()
        .map(|(side, tabs)| Column {
            side,
            open: tabs.iter().copied().filter(|k| open.contains(*k)).collect(),
            tabs,
            default_width: (wish(side) * scale).clamp(min_width, max_width),
            min_width,
            max_width,
        })
        .collect();
    Plan {
        mode: Mode::Wide,
        columns,
        side_share,
        sheet_height: 0.0,
        width: size.x,
    }
}

/// The wide layout's columns and the share of the width they may take together:
/// presentation mode puts every panel in one right-hand column of at most 40 %; otherwise
/// the matrices go right and the rest left, the two at most half the width.
fn sides(presentation: bool) -> (f32, Vec<(Side, Vec<PanelKind>)>) {
    if presentation {
        return (0.4, vec![(Side::Right, PanelKind::ALL.to_vec())]);
    }
    let left = vec![
        PanelKind::Joints,
        PanelKind::Ik,
        PanelKind::Robot,
        PanelKind::Motion,
    ];
    (
        0.5,
        vec![(Side::Left, left), (Side::Right, vec![PanelKind::Matrices])],
    )
}

/// The width a column would like on a screen `width` points wide, before the columns are
/// scaled into the `budget` together. At 1920 the left column gets 460 points, enough for
/// the UR10's DH table on one line per joint (the textbook's table; narrower, it is a
/// block per joint), and the right one 430, where the 6×6 Jacobian still shows whole.
fn column_wish(side: Side, presentation: bool, width: f32, budget: f32) -> f32 {
    match (side, presentation) {
        (_, true) => budget,
        (Side::Left, false) => (width * 0.24).clamp(220.0, 480.0),
        (Side::Right, false) => (width * 0.30).clamp(240.0, 430.0),
    }
}

impl Plan {
    /// The widest the column at `index` may be when the columns before it took `used`
    /// points: the side share less what is used, the tab strips, and the later columns'
    /// narrowest.
    pub fn max_width_after(&self, index: usize, used: f32) -> f32 {
        let Some(column) = self.columns.get(index) else {
            return 0.0;
        };
        let strips = EDGE_TAB_WIDTH * self.columns.len() as f32;
        let later: f32 = self.columns[index + 1..]
            .iter()
            .filter(|c| !c.open.is_empty())
            .map(|c| c.min_width)
            .sum();
        (self.width * self.side_share - strips - used - later)
            .min(column.max_width)
            .max(column.min_width.min(column.max_width))
    }

    /// The panels a narrow layout offers as tabs (all of them).
    pub fn sheet_tabs(&self) -> PanelSet {
        PanelSet::ALL
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The screens of a lecture, in CSS pixels, with the zoom of each mode.
    const SCREENS: [(f32, f32); 6] = [
        (1024.0, 768.0),
        (1280.0, 720.0),
        (1366.0, 768.0),
        (1920.0, 1080.0),
        (820.0, 1180.0),
        (390.0, 844.0),
    ];

    fn settings(presentation: bool, panels: PanelSet) -> Settings {
        let mut s = Settings {
            presentation,
            ..Settings::default()
        };
        s.panels = panels;
        s.presentation_panels = panels;
        s
    }

    /// Widest the columns can get: each at its bound in turn, left to right.
    fn widest_sides(plan: &Plan) -> f32 {
        let mut used = 0.0;
        for (i, c) in plan.columns.iter().enumerate() {
            if !c.open.is_empty() {
                used += plan.max_width_after(i, used);
            }
        }
        used + EDGE_TAB_WIDTH * plan.columns.len() as f32
    }

    #[test]
    fn the_view_keeps_its_share_at_every_screen_whatever_is_open() {
        for (w, h) in SCREENS {
            for presentation in [false, true] {
                let zoom = if presentation { 1.25 } else { 1.0 };
                let size = egui::vec2(w / zoom, h / zoom);
                for bits in 0..32u8 {
                    let open = PanelSet::of(
                        &PanelKind::ALL
                            .into_iter()
                            .filter(|k| bits & (1 << (*k as u8)) != 0)
                            .collect::<Vec<_>>(),
                    );
                    let p = plan(size, w, &settings(presentation, open));
                    match p.mode {
                        Mode::Narrow => assert!(w < NARROW_BELOW_CSS_PX || w < h, "{w}×{h}"),
                        Mode::Wide => {
                            let share = if presentation { 0.6 } else { 0.5 };
                            let view = size.x - widest_sides(&p);
                            assert!(
                                view >= size.x * share - 0.5,
                                "{w}×{h} presentation {presentation} open {open:?}: view {view} of {}",
                                size.x
                            );
                            for c in &p.columns {
                                assert!(c.default_width <= c.max_width + 1e-3);
                                assert!(c.default_width >= c.min_width - 1e-3);
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn landscape_screens_are_wide_and_portrait_ones_narrow() {
        let s = Settings::default();
        for (w, h) in SCREENS {
            let p = plan(egui::vec2(w, h), w, &s);
            let want = if w >= 900.0 { Mode::Wide } else { Mode::Narrow };
            assert_eq!(p.mode, want, "{w}×{h}");
        }
        // Presentation at a projector's 1024×768 stays wide, every panel on the right.
        let s = settings(true, PanelSet::ALL);
        let p = plan(egui::vec2(1024.0 / 1.25, 768.0 / 1.25), 1024.0, &s);
        assert_eq!(p.mode, Mode::Wide);
        assert_eq!(p.columns.len(), 1);
        assert_eq!(p.columns[0].side, Side::Right);
    }
}
