//! A matrix's numbers drawn fast: the characters a number can hold are laid out once,
//! and each number is drawn by copying their glyph quads into one mesh, put in place at
//! the end of the frame by [`finish_numbers`]. A widget apart from the matrices panel:
//! the app's frame finishes the meshes, and the panel only says what to draw where.

/// The width of a table of columns `widths` wide with `gap` between them.
pub fn table_width(widths: &[f32], gap: f32) -> f32 {
    widths.iter().sum::<f32>() + gap * widths.len().saturating_sub(1) as f32
}

/// The advances of a number's characters in a font (points), each rounded to whole
/// pixels. egui puts each glyph of a laid-out text on a whole pixel; copies placed at the
/// sum of the exact advances (7.44 points for a digit at the panel's monospace size, 5.95
/// at 80 %) would each be rounded on their own, and the digits would be unevenly spaced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Advances {
    digit: f32,
    minus: f32,
    point: f32,
}

impl Advances {
    /// The advances of the number characters in `font`, on whole pixels of `ui`'s screen.
    pub fn new(ui: &egui::Ui, font: &egui::FontId) -> Self {
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
    pub fn of(&self, c: char) -> f32 {
        match c {
            '-' => self.minus,
            '.' => self.point,
            _ => self.digit,
        }
    }

    /// The width of a number's text.
    pub fn width(&self, text: &str) -> f32 {
        text.chars().map(|c| self.of(c)).sum()
    }

    /// The gap between a table's columns: two digits.
    pub fn gap(&self) -> f32 {
        2.0 * self.digit
    }
}

/// The characters a formatted number can hold.
pub const NUMBER_CHARS: &str = "0123456789-.";

/// The matrix's numbers in right-aligned columns, in the monospace text style.
///
/// While an arm moves every number of every visible matrix changes each frame, and egui
/// shapes and lays out changed text from scratch: that would be most of this panel's
/// frame time. Numbers use a dozen characters, so those are laid out once as one text (egui
/// caches it) and each number is drawn by copying its characters' glyph quads into one
/// mesh (egui builds each glyph as one quad: four vertices, two triangles). The mesh is
/// put in place by [`finish_numbers`] at the end of the frame.
///
/// `texts` are every entry's text, column-major with `rows` per column, and `plain` the
/// whole matrix as plain text (made only when needed). `(columns, labelled)`: the columns
/// drawn (all, or one block of a matrix cut into blocks of columns), and whether this
/// table carries the screen-reader and test label, `plain`, the "Text" copy of the whole
/// matrix (the first block of a cut matrix does, so the matrix is read once).
pub fn number_table(
    ui: &mut egui::Ui,
    (texts, rows): (&[String], usize),
    plain: &dyn Fn() -> String,
    (columns, labelled): (std::ops::Range<usize>, bool),
    font: egui::FontId,
    advances: Advances,
) -> egui::Response {
    let color = ui.visuals().text_color();
    let glyphs = ui
        .painter()
        .layout_no_wrap(NUMBER_CHARS.to_owned(), font, color);
    let Some(row) = glyphs.rows.first() else {
        return ui.label(plain_text(plain));
    };
    let quads = glyph_quads(row);
    let height = row.size.y * rows as f32;
    let rows = rows.max(1);
    let shown = texts
        .get(columns.start * rows..columns.end * rows)
        .unwrap_or(&[]);
    let Some(cells) = number_cells(shown, &quads, &advances) else {
        // A number this table cannot draw (NaN, infinity): plain text instead, once.
        return if labelled {
            ui.label(plain_text(plain))
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
    let size = egui::vec2(table_width(&column_widths, gap), height);
    let (rect, response) = ui.allocate_exact_size(size, egui::Sense::hover());
    if labelled {
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Label, true, plain()));
        // Its rows and columns, so that a screen reader reads it as a table, entry by entry.
        let columns = texts.len() / rows;
        ui.ctx().accesskit_node_builder(response.id, |node| {
            node.set_row_count(rows);
            node.set_column_count(columns);
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
fn plain_text(plain: &dyn Fn() -> String) -> egui::RichText {
    egui::RichText::new(plain()).monospace()
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
