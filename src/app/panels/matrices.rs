//! The matrices panel: every A_i and T_0i, the tool pose, the Jacobian with its measures,
//! and the tool orientation in four forms. Values update live; precision is selectable;
//! every matrix can be copied as plain text, LaTeX or NumPy.

use nalgebra::DMatrix;

use armlab_core::{
    Convention, JacobianAnalysis, JacobianMeasures, JointKind, Orientation, Robot, Task,
};

use armlab_text::text as text_of;
use armlab_text::{Key, Lang, fill, text};

use crate::app::panels::Panel;
use crate::app::panels::symbolic::{SymbolicCache, symbolic_block};
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::{HoverSource, Model};
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::view3d::jacobian::{self, LinearSvd};
use crate::app::widgets::style;
use crate::app::widgets::style::NameRow;
use crate::app::widgets::toggles::overlay_checkbox;
use armlab_core::symbolic::SymbolicChain;
use armlab_session::format::{fixed, number};
use armlab_session::settings::{Hidden, HiddenSet, MatrixId, Overlay};

/// Plain text rows, space-aligned.
pub fn to_plain(m: &DMatrix<f64>, decimals: usize) -> String {
    (0..m.nrows())
        .map(|r| {
            (0..m.ncols())
                .map(|c| format!("{:>w$}", fixed(m[(r, c)], decimals), w = decimals + 7))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A LaTeX `bmatrix`.
pub fn to_latex(m: &DMatrix<f64>, decimals: usize) -> String {
    let rows: Vec<String> = (0..m.nrows())
        .map(|r| {
            (0..m.ncols())
                .map(|c| fixed(m[(r, c)], decimals))
                .collect::<Vec<_>>()
                .join(" & ")
        })
        .collect();
    format!(
        "\\begin{{bmatrix}}\n{}\n\\end{{bmatrix}}",
        rows.join(" \\\\\n")
    )
}

/// A NumPy array expression.
pub fn to_numpy(m: &DMatrix<f64>, decimals: usize) -> String {
    let rows: Vec<String> = (0..m.nrows())
        .map(|r| {
            let cells: Vec<String> = (0..m.ncols()).map(|c| fixed(m[(r, c)], decimals)).collect();
            format!("[{}]", cells.join(", "))
        })
        .collect();
    format!("np.array([{}])", rows.join(",\n          "))
}

/// A matrix with copy buttons; returns true when it is hovered.
///
/// Blocks scrolled out of sight keep their last size without being laid out
/// ([`style::unless_out_of_sight`]).
#[allow(clippy::too_many_arguments)]
fn matrix_block(
    ui: &mut egui::Ui,
    lang: Lang,
    title: &str,
    hover: &str,
    m: &DMatrix<f64>,
    decimals: usize,
    highlighted: bool,
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
                let over_body = matrix_body(ui, lang, title, m, decimals, (target, hiding));
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
/// without drawing. The numbers are drawn whole at the largest of [`FIT_SCALES`] that
/// fits the column's visible width ([`fit`]). A matrix wider than that even at the
/// smallest (the 6×6 Jacobian in a projector's side column) is cut into blocks of
/// columns, one under the other, each captioned with its columns, as a book prints a wide
/// matrix: a sideways scroll hid columns a lecture hall could not see. Only where not even
/// one column fits does it scroll sideways, with its scroll bar always shown.
fn matrix_body(
    ui: &mut egui::Ui,
    lang: Lang,
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
                number_table(ui, m, decimals, &texts, columns, font, advances).hovered()
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
fn column_caption(ui: &mut egui::Ui, lang: Lang, columns: &std::ops::Range<usize>) {
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

/// The sizes a matrix's numbers may be drawn at, as shares of the monospace text size,
/// largest first: a 1024×768 projector's side column shows T_06 whole at 80 %. Few fixed
/// steps, so that moving numbers do not make a new font size (and new glyphs in egui's
/// font atlas) in every frame.
const FIT_SCALES: [f32; 3] = [1.0, 0.9, 0.8];

/// Each entry's text as the table draws it (column-major, as nalgebra stores them).
fn number_texts(m: &DMatrix<f64>, decimals: usize) -> Vec<String> {
    m.iter().map(|v| fixed(*v, decimals)).collect()
}

/// How a matrix's numbers fit the visible room ([`fit`]).
#[derive(Debug, Clone, PartialEq)]
enum Fit {
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
/// [`number_table`] draws it).
fn fit(ui: &egui::Ui, texts: &[String], rows: usize, font: &egui::FontId) -> Fit {
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

/// The width of a table of columns `widths` wide with `gap` between them.
fn table_width(widths: &[f32], gap: f32) -> f32 {
    widths.iter().sum::<f32>() + gap * widths.len().saturating_sub(1) as f32
}

/// Columns `widths` wide (with `gap` between them) cut into the fewest blocks of
/// consecutive columns that each fit `room`, as even in count as they fit (6 columns of
/// which 4 fit: 3 and 3, not 4 and 2; an odd one over goes to the first blocks); `None`
/// when a column alone is wider than `room`.
fn column_blocks(widths: &[f32], gap: f32, room: f32) -> Option<Vec<std::ops::Range<usize>>> {
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

/// The advances of a number's characters in a font (points), each rounded to whole
/// pixels. egui puts each glyph of a laid-out text on a whole pixel; copies placed at the
/// sum of the exact advances (7.44 points for a digit at the panel's monospace size, 5.95
/// at 80 %) would each be rounded on their own, and the digits would be unevenly spaced.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Advances {
    digit: f32,
    minus: f32,
    point: f32,
}

impl Advances {
    fn new(ui: &egui::Ui, font: &egui::FontId) -> Self {
        let ppp = ui.ctx().pixels_per_point();
        let snap = |c: char| {
            let advance = ui.fonts_mut(|f| f.glyph_width(font, c));
            (advance * ppp).round().max(1.0) / ppp
        };
        Self {
            digit: snap('0'),
            minus: snap('-'),
            point: snap('.'),
        }
    }

    /// The advance of one of [`NUMBER_CHARS`] (the digits share one: the font's digits
    /// are tabular).
    fn of(&self, c: char) -> f32 {
        match c {
            '-' => self.minus,
            '.' => self.point,
            _ => self.digit,
        }
    }

    /// The width of a number's text.
    fn width(&self, text: &str) -> f32 {
        text.chars().map(|c| self.of(c)).sum()
    }

    /// The gap between a table's columns: two digits.
    fn gap(&self) -> f32 {
        2.0 * self.digit
    }
}

/// The characters a formatted number can hold.
const NUMBER_CHARS: &str = "0123456789-.";

/// The matrix's numbers in right-aligned columns, in the monospace text style.
///
/// While an arm moves every number of every visible matrix changes each frame, and egui
/// shapes and lays out changed text from scratch: that would be most of this panel's
/// frame time. Numbers use a dozen characters, so those are laid out once as one text (egui
/// caches it) and each number is drawn by copying its characters' glyph quads into one
/// mesh (egui builds each glyph as one quad: four vertices, two triangles). The mesh is
/// put in place by [`finish_numbers`] at the end of the frame.
///
/// `(columns, labelled)`: the columns drawn (all, or one block of [`Fit::Blocks`]), and
/// whether this table carries the screen-reader and test label, the "Text" copy of the
/// whole matrix (the first block of a cut matrix does, so the matrix is read once).
fn number_table(
    ui: &mut egui::Ui,
    m: &DMatrix<f64>,
    decimals: usize,
    texts: &[String],
    (columns, labelled): (std::ops::Range<usize>, bool),
    font: egui::FontId,
    advances: Advances,
) -> egui::Response {
    let color = ui.visuals().text_color();
    let glyphs = ui
        .painter()
        .layout_no_wrap(NUMBER_CHARS.to_owned(), font, color);
    let Some(row) = glyphs.rows.first() else {
        return ui.label(plain_text(m, decimals));
    };
    let quads = glyph_quads(row);
    let rows = m.nrows().max(1);
    let shown = texts
        .get(columns.start * rows..columns.end * rows)
        .unwrap_or(&[]);
    let Some(cells) = number_cells(shown, &quads, &advances) else {
        // A number this table cannot draw (NaN, infinity): plain text instead, once.
        return if labelled {
            ui.label(plain_text(m, decimals))
        } else {
            ui.allocate_response(egui::Vec2::ZERO, egui::Sense::hover())
        };
    };
    let gap = advances.gap();
    let column_widths: Vec<f32> = cells
        .chunks(rows)
        .map(|column| column.iter().map(|(_, w)| *w).fold(0.0, f32::max))
        .collect();
    let row_height = row.size.y;
    let size = egui::vec2(
        table_width(&column_widths, gap),
        row_height * m.nrows() as f32,
    );
    let (rect, response) = ui.allocate_exact_size(size, egui::Sense::hover());
    if labelled {
        response.widget_info(|| {
            egui::WidgetInfo::labeled(egui::Role::Label, true, to_plain(m, decimals))
        });
    }
    if !ui.is_rect_visible(rect) {
        return response;
    }
    let layout = TableLayout {
        rect,
        row_height,
        advances,
        gap,
        rows,
        column_widths: &column_widths,
    };
    let mesh = numbers_mesh(
        &row.visuals.mesh,
        &cells,
        &layout,
        ui.ctx().pixels_per_point(),
    );
    let painter = ui.painter().clone();
    let place = painter.add(egui::Shape::Noop);
    ui.ctx().data_mut(|d| {
        d.get_temp_mut_or_default::<PendingNumbers>(pending_numbers_id())
            .0
            .push((painter, place, mesh));
    });
    response
}

/// A glyph of [`NUMBER_CHARS`] and the vertices of its quad in the laid-out row's mesh.
type GlyphQuad<'a> = (&'a egui::epaint::text::Glyph, std::ops::Range<usize>);

/// A number as its characters' glyph quads, and its width.
type NumberCell<'a, 'b> = (Vec<&'b GlyphQuad<'a>>, f32);

/// For each of [`NUMBER_CHARS`]: its glyph and its quad's vertex range in the row's mesh.
fn glyph_quads(row: &egui::epaint::text::Row) -> Vec<GlyphQuad<'_>> {
    (0..row.glyphs.len())
        .map(|i| {
            let end = row
                .glyphs
                .get(i + 1)
                .map_or(row.visuals.glyph_vertex_range.end, |next| {
                    next.first_vertex as usize
                });
            (&row.glyphs[i], row.glyphs[i].first_vertex as usize..end)
        })
        .collect()
}

/// Each number (column-major, as nalgebra stores them) as its quads and its width; none
/// when a number has a character outside [`NUMBER_CHARS`].
fn number_cells<'a, 'b>(
    texts: &[String],
    quads: &'b [GlyphQuad<'a>],
    advances: &Advances,
) -> Option<Vec<NumberCell<'a, 'b>>> {
    texts
        .iter()
        .map(|text| {
            let chars = text
                .chars()
                .map(|c| quads.iter().find(|(g, _)| g.chr == c))
                .collect::<Option<Vec<_>>>()?;
            Some((chars, advances.width(text)))
        })
        .collect()
}

/// Where a table's numbers go.
struct TableLayout<'a> {
    rect: egui::Rect,
    row_height: f32,
    /// The characters' advances, on whole pixels.
    advances: Advances,
    gap: f32,
    rows: usize,
    column_widths: &'a [f32],
}

/// One mesh of every number's glyph quads, copied from the laid-out row and moved into
/// place, each column right-aligned.
fn numbers_mesh(
    source: &egui::Mesh,
    cells: &[NumberCell<'_, '_>],
    layout: &TableLayout<'_>,
    ppp: f32,
) -> egui::Mesh {
    let mut mesh = egui::Mesh::default();
    let mut left = layout.rect.left();
    for (column, column_width) in cells.chunks(layout.rows).zip(layout.column_widths) {
        for (r, (chars, width)) in column.iter().enumerate() {
            let mut x = left + column_width - width;
            let y = layout.rect.top() + layout.row_height * r as f32;
            for (glyph, vertices) in chars {
                // The row's mesh is relative to the row's top left and the glyph's pen
                // position is `glyph.pos.x`; whole pixels keep the copy as crisp as the text.
                let shift = egui::vec2(
                    ((x - glyph.pos.x) * ppp).round() / ppp,
                    (y * ppp).round() / ppp,
                );
                let first = mesh.vertices.len() as u32;
                mesh.vertices
                    .extend(source.vertices[vertices.clone()].iter().map(|v| {
                        egui::epaint::Vertex {
                            pos: v.pos + shift,
                            ..*v
                        }
                    }));
                for quad_start in (first..mesh.vertices.len() as u32).step_by(4) {
                    mesh.add_triangle(quad_start, quad_start + 1, quad_start + 2);
                    mesh.add_triangle(quad_start + 2, quad_start + 1, quad_start + 3);
                }
                x += layout.advances.of(glyph.chr);
            }
        }
        left += column_width + layout.gap;
    }
    mesh
}

/// The matrix as one monospace text, for what [`number_table`] cannot draw.
fn plain_text(m: &DMatrix<f64>, decimals: usize) -> egui::RichText {
    egui::RichText::new(to_plain(m, decimals)).monospace()
}

fn pending_numbers_id() -> egui::Id {
    egui::Id::unique("armlab_matrix_numbers")
}

/// This frame's number meshes, with texture coordinates still in font-atlas texels.
#[derive(Clone, Default)]
struct PendingNumbers(Vec<(egui::Painter, egui::layers::ShapeIdx, egui::Mesh)>);

/// Puts this frame's matrix numbers in place. Their texture coordinates are scaled to the
/// font atlas as it is now, at the end of the frame: the atlas grows when text drawn
/// later in the frame needs new glyphs (egui scales its own text the same way, when it
/// tessellates it).
pub fn finish_numbers(ctx: &egui::Context) {
    let Some(PendingNumbers(meshes)) =
        ctx.data_mut(|d| d.remove_temp::<PendingNumbers>(pending_numbers_id()))
    else {
        return;
    };
    let atlas = ctx.fonts(|f| f.font_image_size());
    let scale = egui::vec2(1.0 / atlas[0] as f32, 1.0 / atlas[1] as f32);
    for (painter, place, mut mesh) in meshes {
        for v in &mut mesh.vertices {
            v.uv = (v.uv.to_vec2() * scale).to_pos2();
        }
        painter.set(place, mesh);
    }
}

fn homogeneous(pose: &nalgebra::IsometryMatrix3<f64>) -> DMatrix<f64> {
    let h = armlab_core::fk::homogeneous(pose);
    DMatrix::from_fn(4, 4, |r, c| h[(r, c)])
}

/// The matrices panel. It keeps the Jacobian analysis of the pose it last showed (the
/// central-difference check and an SVD, recomputed only when the robot, q or the task
/// changes); its layout caches (each block's size while scrolled out of sight, the glyph
/// quads of the numbers) live in egui's memory for the frame.
#[derive(Debug, Clone, Default)]
pub struct MatricesPanel {
    analysis: Option<AnalysisCache>,
    /// Show A_i and T_0i symbolically instead of as numbers.
    symbolic: bool,
    chain: SymbolicCache,
    /// Predict, then reveal: the lecturer is choosing what to hide.
    choosing: bool,
    /// What a click revealed during the lecture ("Hide again" puts it back).
    revealed: Vec<Hidden>,
}

/// A Jacobian analysis and what it was computed for.
#[derive(Debug, Clone)]
struct AnalysisCache {
    robot: Robot,
    q: Vec<f64>,
    task: Task,
    analysis: JacobianAnalysis,
}

impl MatricesPanel {
    /// The analysis of the model's pose, from the cache when nothing it depends on changed.
    fn analysis(&mut self, model: &Model) -> &JacobianAnalysis {
        let fresh = self.analysis.as_ref().is_some_and(|c| {
            c.task == model.task() && c.q.as_slice() == model.q() && &c.robot == model.robot()
        });
        if !fresh {
            self.analysis = None;
        }
        let cache = self.analysis.get_or_insert_with(|| AnalysisCache {
            robot: model.robot().clone(),
            q: model.q().to_vec(),
            task: model.task(),
            analysis: JacobianAnalysis::new(model.robot(), model.fk(), model.q(), model.task()),
        });
        &cache.analysis
    }
}

impl Panel for MatricesPanel {
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        if model.table_hidden() {
            // Every number here (A_i, T_0i, J, even T_0n at a chosen q) would give the
            // exercise's table away.
            ui.label(tr(model, Key::ExerciseHidden));
            return;
        }
        precision_row(model, ui);
        let mut hiding = self.hiding(model, ui);
        let decimals = model.settings().precision;
        let n = model.robot().dof();
        let unit = model.robot().length_unit.symbol();
        let lang = model.settings().lang;
        matrix_block(
            ui,
            lang,
            &trf(model, Key::ToolPoseTitle, &[&n, &unit]),
            tr(model, Key::ToolPoseHint),
            &homogeneous(&model.fk().base_from_tool),
            decimals,
            false,
            (Target::Matrix(MatrixId::Tool), &mut hiding),
        );
        orientation_block(
            ui,
            lang,
            &Orientation::from_rotation(model.fk().tool_rotation()),
            model.settings().degrees,
            decimals,
        );
        egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::Jacobian),
        ))
        .id_salt("jacobian")
        .default_open(true)
        .show(ui, |ui| {
            let analysis = self.analysis(model);
            jacobian_block(model, analysis, ui, decimals, &mut hiding)
        });
        let symbolic = self
            .symbolic
            .then(|| self.chain.chain(model.robot(), model.robot_changes()));
        let hovered = egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::LinkTransforms),
        ))
        .id_salt("link_transforms")
        .default_open(true)
        .show(ui, |ui| {
            ui.checkbox(&mut self.symbolic, tr(model, Key::ShowSymbolic))
                .on_hover_text(tr(model, Key::ShowSymbolicHint));
            link_blocks(model, ui, decimals, symbolic, &mut hiding)
        })
        .body_returned
        .flatten();
        model.set_hovered_link(hovered, HoverSource::Matrices);
        self.finish_hiding(model, hiding, points);
    }
}

// --- Predict, then reveal (presentation mode) ---------------------------------------------

/// The background of an entry the lecturer chose to hide (while choosing).
const HIDDEN_BACKGROUND: egui::Color32 = egui::Color32::from_rgb(120, 70, 20);

/// A matrix block entries can be hidden in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Target {
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
struct Hiding {
    /// Presentation mode: hiding applies.
    on: bool,
    /// The lecturer is choosing: clicks hide and show instead of revealing.
    choosing: bool,
    hidden: HiddenSet,
    revealed: Vec<Hidden>,
    /// Items clicked while choosing, to toggle in the settings.
    toggled: Vec<Hidden>,
    /// Screen points of the entries and buttons, for the tests.
    points: Vec<(String, egui::Pos2)>,
}

impl Hiding {
    /// Whether a block draws its entries one by one (clickable): while choosing, or when
    /// something in it is hidden.
    fn interactive(&self, target: Target) -> bool {
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
    fn concealed_whole(&self, id: MatrixId) -> Option<Hidden> {
        let whole = Hidden::Matrix(id);
        (self.on
            && !self.choosing
            && self.hidden.contains(whole)
            && !self.revealed.contains(&whole))
        .then_some(whole)
    }

    fn point(&mut self, name: String, at: egui::Pos2) {
        self.points.push((name, at));
    }

    /// A whole matrix behind one "?" (the symbolic view's blocks); a click reveals it.
    fn concealed_block(
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
struct HidingCells<'a> {
    m: &'a DMatrix<f64>,
    /// Every entry's text ([`number_texts`], column-major).
    texts: &'a [String],
    columns: std::ops::Range<usize>,
    font: egui::FontId,
    /// The font's advances, as [`fit`] measured them (the gap between columns).
    advances: Advances,
}

/// The matrix entry by entry (its columns `cells.columns`), each clickable: "?" for a
/// concealed entry (a click reveals it); while choosing, every number, the hidden ones on a
/// dark orange background (a click hides or shows the entry, or the Jacobian's column).
fn hiding_table(
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
    fn hiding(&mut self, model: &Model, ui: &mut egui::Ui) -> Hiding {
        let on = model.settings().presentation;
        let hidden = model.settings().hidden.clone();
        self.revealed.retain(|h| hidden.contains(*h));
        if on {
            crate::app::widgets::style::wrapped(ui, |ui| {
                ui.toggle_value(&mut self.choosing, tr(model, Key::HideMode))
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
            choosing: on && self.choosing,
            hidden,
            revealed: std::mem::take(&mut self.revealed),
            toggled: Vec::new(),
            points: Vec::new(),
        }
    }

    /// Keeps what was revealed, and writes what was chosen into the settings (the link).
    fn finish_hiding(&mut self, model: &mut Model, hiding: Hiding, points: &mut ScreenPoints) {
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

fn precision_row(model: &mut Model, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        let label = ui.label(tr(model, Key::Decimals));
        let mut precision = model.settings().precision;
        if ui
            .add(egui::DragValue::new(&mut precision).range(0..=8))
            .labelled_by(label.id)
            .changed()
        {
            let mut settings = model.settings().clone();
            settings.precision = precision;
            model.set_settings(settings);
        }
    });
}

/// Every A_i and T_0i; returns the link whose matrix is under the pointer.
fn link_blocks(
    model: &Model,
    ui: &mut egui::Ui,
    decimals: usize,
    symbolic: Option<&SymbolicChain>,
    hiding: &mut Hiding,
) -> Option<usize> {
    let convention = match model.robot().convention {
        Convention::Standard => Key::StandardFormula,
        Convention::Modified => Key::ModifiedFormula,
    };
    ui.label(tr(model, convention));
    let lang = model.settings().lang;
    let mut hovered = None;
    // The joint under the pointer (its slider, its link in 3D, its matrices): symbolic
    // entries that depend on it are highlighted.
    let joint_under = model.hovered_link().and_then(|l| l.checked_sub(1));
    for (i, joint) in model.robot().joints.iter().enumerate() {
        let highlighted = model.hovered_link() == Some(i + 1);
        let variable = match joint.kind {
            JointKind::Revolute => "θ",
            JointKind::Prismatic => "d",
        };
        if let Some(chain) = symbolic {
            let title = trf(model, Key::LinkTitle, &[&(i + 1), &joint.name, &variable]);
            let a = &chain.link_transforms[i];
            let t = &chain.base_from_frames[i];
            // A whole matrix hidden for the lecture stays a "?" here too.
            let over_a = match hiding.concealed_whole(MatrixId::Link(i + 1)) {
                Some(item) => hiding.concealed_block(ui, lang, &title, item),
                None => symbolic_block(ui, lang, &title, a, joint_under, highlighted),
            };
            let title = format!("T_0{}", i + 1);
            let over_t = match hiding.concealed_whole(MatrixId::Frame(i + 1)) {
                Some(item) => hiding.concealed_block(ui, lang, &title, item),
                None => symbolic_block(ui, lang, &title, t, joint_under, highlighted),
            };
            if over_a || over_t {
                hovered = Some(i + 1);
            }
            continue;
        }
        let a = homogeneous(&model.fk().link_transforms[i]);
        let title = trf(model, Key::LinkTitle, &[&(i + 1), &joint.name, &variable]);
        if matrix_block(
            ui,
            lang,
            &title,
            tr(model, Key::FrameInPrevious),
            &a,
            decimals,
            highlighted,
            (Target::Matrix(MatrixId::Link(i + 1)), &mut *hiding),
        ) {
            hovered = Some(i + 1);
        }
        let t = homogeneous(&model.fk().base_from_frames[i]);
        let title = format!("T_0{}", i + 1);
        let hover = tr(model, Key::FrameInBase);
        let target = (Target::Matrix(MatrixId::Frame(i + 1)), &mut *hiding);
        if matrix_block(ui, lang, &title, hover, &t, decimals, highlighted, target) {
            hovered = Some(i + 1);
        }
    }
    hovered
}

fn jacobian_block(
    model: &mut Model,
    analysis: &JacobianAnalysis,
    ui: &mut egui::Ui,
    decimals: usize,
    hiding: &mut Hiding,
) {
    let j = &analysis.geometric;
    let jm = DMatrix::from_fn(6, j.ncols(), |r, c| j[(r, c)]);
    matrix_block(
        ui,
        model.settings().lang,
        tr(model, Key::JacobianTitle),
        tr(model, Key::JacobianHint),
        &jm,
        decimals,
        false,
        (Target::Jacobian, hiding),
    );
    let text = trf(
        model,
        Key::CentralDifferences,
        &[&number(analysis.max_difference, 1)],
    );
    if analysis.agrees {
        ui.label(text);
    } else {
        let tolerance = number(analysis.tolerance, 1);
        ui.colored_label(
            style::ERROR,
            trf(model, Key::AboveTolerance, &[&text, &tolerance]),
        );
    }
    measures_grid(model, &analysis.measures, ui);
    overlay_switches(model, ui);
    if model.settings().overlays.contains(Overlay::JacobianColumns)
        || model.settings().overlays.contains(Overlay::AngularColumns)
    {
        column_legend(model, ui);
    } else {
        model.set_hovered_column(None, HoverSource::Matrices);
    }
    if let Some(lost) = LinearSvd::of(model.jacobian()).and_then(|s| s.lost_direction()) {
        let d = [lost.x, lost.y, lost.z].map(|v| fixed(v, 2)).join(", ");
        ui.colored_label(style::UNREACHABLE, trf(model, Key::LostDirection, &[&d]));
    }
}

/// The switches of the Jacobian's drawings in the 3D view.
fn overlay_switches(model: &mut Model, ui: &mut egui::Ui) {
    crate::app::widgets::style::wrapped(ui, |ui| {
        ui.label(tr(model, Key::DrawIn3d));
        let switches = [
            (
                Overlay::JacobianColumns,
                Key::DrawColumns,
                Key::DrawColumnsHint,
            ),
            (
                Overlay::AngularColumns,
                Key::DrawAngular,
                Key::DrawAngularHint,
            ),
            (
                Overlay::VelocityEllipsoid,
                Key::DrawVelocityEllipsoid,
                Key::DrawVelocityEllipsoidHint,
            ),
            (
                Overlay::ForceEllipsoid,
                Key::DrawForceEllipsoid,
                Key::DrawForceEllipsoidHint,
            ),
        ];
        for (overlay, label, hint) in switches {
            overlay_checkbox(model, ui, overlay, label, hint);
        }
    });
}

/// The columns' colours and numbers, as the arrows have them; hovering one highlights its
/// arrow (and hovering an arrow highlights its entry).
fn column_legend(model: &mut Model, ui: &mut egui::Ui) {
    let mut hovered = None;
    crate::app::widgets::style::wrapped(ui, |ui| {
        ui.label(tr(model, Key::ColumnLegend));
        for i in 0..model.robot().dof() {
            let [r, g, b] = jacobian::column_color(i);
            let mut text =
                egui::RichText::new(format!("■ {}", i + 1)).color(egui::Color32::from_rgb(r, g, b));
            if model.hovered_column() == Some(i) {
                text = text.strong().underline();
            }
            let name = &model.robot().joints[i].name;
            let response = ui
                .add(egui::Label::new(text).sense(egui::Sense::hover()))
                .on_hover_text(trf(model, Key::ColumnHint, &[&(i + 1), name]));
            if response.hovered() {
                hovered = Some(i);
            }
        }
    });
    model.set_hovered_column(hovered, HoverSource::Matrices);
}

/// The measures of the task rows: as displayed (in the robot's units, what a student
/// computes from the matrix above) beside the unit-free versions (linear rows ÷ L).
fn measures_grid(model: &Model, m: &JacobianMeasures, ui: &mut egui::Ui) {
    let sv: Vec<String> = m.singular_values.iter().map(|s| number(*s, 4)).collect();
    let unit = model.robot().length_unit.symbol();
    let scale = number(m.length_scale, 1);
    // det J and √det(J·Jᵀ) carry a length cubed (three linear rows); √det(Jᵀ·J) of an arm
    // with fewer joints than task rows mixes lengths and angles.
    let cubed = format!(" {unit}³");
    let rows = model.task().rows();
    let w_unit = if rows <= model.robot().dof() {
        cubed.as_str()
    } else {
        ""
    };
    let infinite = |c: Option<f64>, d| c.map_or("∞".to_string(), |c| number(c, d));
    ui.label(format!("{}  {rows}", tr(model, Key::TaskRows)))
        .on_hover_text(tr(model, Key::TaskRowsHint));
    let headers = [
        (
            tr(model, Key::MeasuresDisplayed).to_owned(),
            trf(model, Key::MeasuresDisplayedHint, &[&unit]),
        ),
        (
            tr(model, Key::MeasuresUnitFree).to_owned(),
            trf(model, Key::MeasuresUnitFreeHint, &[&scale, &unit]),
        ),
    ];
    let row = |name: &str, hint: Option<String>, values: [String; 2]| NameRow {
        name: name.to_owned(),
        hint,
        values: values.to_vec(),
    };
    let mut table = vec![
        row(
            tr(model, Key::SingularValues),
            Some(trf(model, Key::SingularValuesHint, &[&scale, &unit])),
            [String::new(), sv.join("  ")],
        ),
        row(
            tr(model, Key::Manipulability),
            Some(tr(model, Key::ManipulabilityHint).to_owned()),
            [
                format!("{}{w_unit}", number(m.displayed.manipulability, 5)),
                number(m.manipulability, 5),
            ],
        ),
    ];
    if let (Some(shown), Some(det)) = (m.displayed.determinant, m.determinant) {
        table.push(row(
            "det J",
            None,
            [format!("{}{cubed}", number(shown, 5)), number(det, 5)],
        ));
    }
    table.push(row(
        tr(model, Key::ConditionNumber),
        None,
        [
            infinite(m.displayed.condition_number, 2),
            infinite(m.condition_number, 2),
        ],
    ));
    style::fold_rows(ui, "measures", &headers, &table);
    if m.near_singular {
        ui.colored_label(style::UNREACHABLE, tr(model, Key::NearSingular));
    }
}

fn orientation_block(
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

#[cfg(test)]
mod tests {
    use super::*;

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
            let width = number_table(ui, &tool_pose(), 3, &texts, table, font.clone(), *a)
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
                        number_table(ui, &jacobian, 3, &texts, table, font.clone(), a)
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
