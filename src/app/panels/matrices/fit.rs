//! How a matrix's numbers fit the column: the largest of a few text sizes at which the
//! matrix fits whole, else the fewest blocks of columns, else a sideways scroll. Measured
//! without laying the numbers out; apart from the drawing so that it can be tested alone.

use crate::app::widgets::numbers::{Advances, table_width};
use crate::app::widgets::style;

/// The sizes a matrix's numbers may be drawn at, as shares of the monospace text size,
/// largest first: a 1024×768 projector's side column shows T_06 whole at 80 %. Few fixed
/// steps, so that moving numbers do not make a new font size (and new glyphs in egui's
/// font atlas) in every frame.
pub(super) const FIT_SCALES: [f32; 3] = [1.0, 0.9, 0.8];

/// How a matrix's numbers fit the visible room ([`fit`]).
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Fit {
    /// At this font (one of [`FIT_SCALES`]), in these blocks of consecutive columns, one
    /// table under the other: one block when the whole matrix fits.
    Blocks(egui::FontId, Advances, Vec<std::ops::Range<usize>>),
    /// At full size and scrolling sideways: not even one column fits.
    Scroll(Advances),
}

/// How `texts` (`rows` per column) are best drawn in the visible room: in the fewest
/// blocks of columns ([`column_blocks`]) any of [`FIT_SCALES`] gives, at the largest
/// scale that gives that few (T_06 in a projector's side column: whole at 80 %, rather
/// than in two blocks at full size; the 6×6 Jacobian there: two blocks of three at 80 %,
/// rather than three of two), else scrolling. Measured without laying the numbers out: a
/// column is as wide as its widest number, and the gap is two digits (as
/// [`number_table`](crate::app::widgets::numbers::number_table) draws it).
pub(super) fn fit(ui: &egui::Ui, texts: &[String], rows: usize, font: &egui::FontId) -> Fit {
    let room = style::room(ui);
    let rows = rows.max(1);
    let mut best: Option<Fit> = None;
    for scale in FIT_SCALES {
        let scaled = egui::FontId::new(font.size * scale, font.family.clone());
        let a = Advances::new(ui, &scaled);
        let widths: Vec<f32> = texts
            .chunks(rows)
            .map(|column| column.iter().map(|t| a.width(t)).fold(0.0, f32::max))
            .collect();
        let Some(blocks) = column_blocks(&widths, a.gap(), room) else {
            continue;
        };
        let fewer = match &best {
            Some(Fit::Blocks(_, _, fewest)) => blocks.len() < fewest.len(),
            _ => true,
        };
        if fewer {
            let whole = blocks.len() == 1;
            best = Some(Fit::Blocks(scaled, a, blocks));
            if whole {
                break;
            }
        }
    }
    best.unwrap_or_else(|| Fit::Scroll(Advances::new(ui, font)))
}

/// Columns `widths` wide (with `gap` between them) cut into the fewest blocks of
/// consecutive columns that each fit `room`, as even in count as they fit (6 columns of
/// which 4 fit: 3 and 3, not 4 and 2; an odd one over goes to the first blocks); `None`
/// when a column alone is wider than `room`.
pub(super) fn column_blocks(
    widths: &[f32],
    gap: f32,
    room: f32,
) -> Option<Vec<std::ops::Range<usize>>> {
    if widths.is_empty() || widths.iter().any(|w| *w > room) {
        return None;
    }
    let fits = |r: &std::ops::Range<usize>| table_width(&widths[r.clone()], gap) <= room;
    let mut greedy = Vec::new();
    let mut block = 0..0;
    for i in 0..widths.len() {
        let grown = block.start..i + 1;
        if fits(&grown) {
            block = grown;
        } else {
            greedy.push(std::mem::replace(&mut block, i..i + 1));
        }
    }
    greedy.push(block);
    let (n, count) = (widths.len(), greedy.len());
    let start = |k: usize| (k * n).div_ceil(count);
    let even: Vec<_> = (0..count).map(|k| start(k)..start(k + 1)).collect();
    Some(if even.iter().all(fits) { even } else { greedy })
}

#[cfg(test)]
mod tests {
    use nalgebra::DMatrix;

    use super::*;
    use crate::app::panels::matrices::export::{number_texts, to_plain};
    use crate::app::widgets::numbers::number_table;

    /// `f`'s result in a frame whose panel is `width` points wide (two frames: the first
    /// loads the fonts).
    fn in_a_column<R>(width: f32, mut f: impl FnMut(&mut egui::Ui) -> R) -> R {
        let ctx = egui::Context::default();
        style::install_fonts(&ctx);
        let input = || egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(1024.0, 768.0),
            )),
            ..Default::default()
        };
        let mut out = None;
        for _ in 0..2 {
            let mut output = ctx.run_ui(input(), |ui| {
                ui.scope(|ui| {
                    ui.set_max_width(width);
                    out = Some(f(ui));
                });
            });
            // Nothing draws here: the font atlas's uploads are dropped on purpose.
            output.textures_delta.clear();
        }
        out.expect("the frame ran")
    }

    /// The UR10's T_06 at its home pose, in mm.
    fn tool_pose() -> DMatrix<f64> {
        DMatrix::from_row_slice(
            4,
            4,
            &[
                0.0, -1.0, 0.0, 685.770, 1.0, 0.0, 0.0, -163.9, 0.0, 0.0, 1.0, 465.187, 0.0, 0.0,
                0.0, 1.0,
            ],
        )
    }

    /// The font [`fit`] chose when the whole table fits in one block.
    fn whole_font(fit: &Fit) -> Option<egui::FontId> {
        match fit {
            Fit::Blocks(font, _, blocks) if blocks.len() == 1 => Some(font.clone()),
            _ => None,
        }
    }

    #[test]
    fn a_matrix_a_little_too_wide_is_drawn_smaller_and_fits() {
        let full = egui::FontId::monospace(12.0);
        let texts = number_texts(&tool_pose(), 3);
        // Wide enough: full size.
        let font = in_a_column(400.0, |ui| whole_font(&fit(ui, &texts, 4, &full)));
        assert_eq!(font, Some(full.clone()));
        // A projector's right column: smaller, and the table then fits its room.
        let (font, width, room) = in_a_column(209.0, |ui| {
            let room = style::room(ui);
            let chosen = fit(ui, &texts, 4, &full);
            let (Some(font), Fit::Blocks(_, a, _)) = (whole_font(&chosen), &chosen) else {
                panic!("a 4×4 pose fits a side column whole: {chosen:?}");
            };
            let table = (0..4, true);
            let plain = || to_plain(&tool_pose(), 3);
            let width = number_table(ui, (&texts, 4), &plain, table, font.clone(), *a)
                .rect
                .width();
            (font, width, room)
        });
        assert!((12.0 * 0.8..12.0).contains(&font.size), "{}", font.size);
        assert!(width <= room, "{width} drawn in {room}");
    }

    #[test]
    fn a_matrix_much_too_wide_is_shown_in_blocks_of_columns_that_each_fit() {
        let jacobian = DMatrix::from_fn(6, 6, |r, c| -337.187 + (r * 6 + c) as f64);
        let full = egui::FontId::monospace(12.0);
        let texts = number_texts(&jacobian, 3);
        let blocks_of = |width: f32| {
            in_a_column(width, |ui| {
                let room = style::room(ui);
                let chosen = fit(ui, &texts, 6, &full);
                let Fit::Blocks(font, a, blocks) = chosen.clone() else {
                    return (chosen, Vec::new(), room);
                };
                let widths: Vec<f32> = blocks
                    .iter()
                    .map(|b| {
                        let table = (b.clone(), b.start == 0);
                        let plain = || to_plain(&jacobian, 3);
                        number_table(ui, (&texts, 6), &plain, table, font.clone(), a)
                            .rect
                            .width()
                    })
                    .collect();
                (chosen, widths, room)
            })
        };
        // Fewest blocks first, then the largest size: two blocks of three at a smaller size
        // in a narrow column (three blocks of two at full size would be taller), at full
        // size in a wider one, and the whole matrix at a smaller size in a wider one still.
        let two = vec![0..3, 3..6];
        let whole: Vec<_> = std::iter::once(0..6).collect();
        for (width, smaller, want) in [
            (175.0, true, &two),
            (209.0, false, &two),
            (320.0, true, &whole),
        ] {
            let (chosen, widths, room) = blocks_of(width);
            let Fit::Blocks(font, _, blocks) = chosen else {
                panic!("a 6×6 Jacobian {width} wide is cut into blocks: {chosen:?}");
            };
            assert_eq!(&blocks, want, "{width}");
            assert_eq!(font.size < 12.0, smaller, "{width}: {}", font.size);
            for w in widths {
                assert!(w <= room && w > room / 2.0, "a block {w} wide in {room}");
            }
        }
        // Not even one column fits: it scrolls at full size.
        let narrow = in_a_column(40.0, |ui| fit(ui, &texts, 6, &full));
        assert!(matches!(narrow, Fit::Scroll(_)), "{narrow:?}");
    }

    #[test]
    fn columns_are_cut_into_the_fewest_blocks_as_even_as_they_fit() {
        // Seven columns of 10 with gaps of 2; 4 fit in 46.
        let seven = [10.0; 7];
        assert_eq!(column_blocks(&seven, 2.0, 46.0), Some(vec![0..4, 4..7]));
        // Six of which four fit: three and three.
        assert_eq!(
            column_blocks(&seven[..6], 2.0, 46.0),
            Some(vec![0..3, 3..6])
        );
        // Uneven widths where the even cut does not fit: the greedy one.
        let uneven = [30.0, 30.0, 5.0, 5.0];
        assert_eq!(column_blocks(&uneven, 2.0, 46.0), Some(vec![0..1, 1..4]));
        // Everything fits: one block; a column wider than the room: none.
        let whole = std::iter::once(0..7).collect();
        assert_eq!(column_blocks(&seven, 2.0, 1000.0), Some(whole));
        assert_eq!(column_blocks(&[50.0], 2.0, 46.0), None);
        assert_eq!(column_blocks(&[], 2.0, 46.0), None);
    }
}
