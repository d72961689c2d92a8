//! The DH table editor, a widget the robot panel and the DH exercise share: one row of
//! text cells per joint (θ, d, a, α and the limits), applied live; an invalid cell shows
//! the core's sentence beside it and the last valid robot stays drawn.

use armlab_core::{Convention, DhRow, Joint, JointKind, JointLimits, Robot, RobotError};
use armlab_text::{Key, Lang, Sentence, fill};

use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::{math, style};
use armlab_session::format::number;
use armlab_session::session::RobotSource;

/// Decimals of a DH cell: enough to show every preset's value whole.
const CELL_DECIMALS: usize = 6;

/// Column names of the editable DH cells.
pub const COLUMNS: [&str; 6] = ["θ (°)", "d", "a", "α (°)", "min", "max"];

/// A column's header as a formula ([`math`]): θ_i, d_i, a_i, α_i in standard DH; a_{i−1}
/// and α_{i−1} in modified DH, as the convention is taught. With its unit where `units`
/// (a narrow table's blocks leave the units to the caption above the table).
pub(crate) fn header(convention: Convention, c: usize, units: bool) -> &'static str {
    match (convention, c, units) {
        (_, 0, true) => "θ_i (°)",
        (_, 0, false) => "θ_i",
        (_, 1, _) => "d_i",
        (Convention::Standard, 2, _) => "a_i",
        (Convention::Modified, 2, _) => "a_\u{7b}i−1\u{7d}",
        (Convention::Standard, 3, true) => "α_i (°)",
        (Convention::Standard, 3, false) => "α_i",
        (Convention::Modified, 3, true) => "α_\u{7b}i−1\u{7d} (°)",
        (Convention::Modified, 3, false) => "α_\u{7b}i−1\u{7d}",
        (_, 4, _) => "min",
        _ => "max",
    }
}

/// The order the columns are shown in: modified DH reads a_{i−1}, α_{i−1}, d_i, θ_i (the
/// order of its product Rx·Tx·Rz·Tz). The cells keep their column numbers.
pub(crate) fn column_order(convention: Convention) -> [usize; 6] {
    match convention {
        Convention::Standard => [0, 1, 2, 3, 4, 5],
        Convention::Modified => [2, 3, 1, 0, 4, 5],
    }
}

/// A header's width (points) in `font`.
fn header_width(ui: &egui::Ui, source: &str, font: &egui::FontId) -> f32 {
    let job = math::job(source, font, egui::Color32::WHITE);
    ui.fonts_mut(|f| f.layout_job(job)).size().x
}

/// One row of cell texts.
#[derive(Debug, Clone, PartialEq)]
pub struct RowText {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// θ, d, a, α, min, max as typed (angles in degrees, lengths in robot units).
    pub cells: [String; 6],
}

impl RowText {
    /// A new row: revolute, all zeros, ±180°.
    pub fn blank() -> Self {
        RowText {
            kind: JointKind::Revolute,
            cells: ["0", "0", "0", "0", "-180", "180"].map(String::from),
        }
    }
}

/// The editor's texts, kept separately from the robot so that a half-typed number does not
/// disturb the drawn arm.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DhEditor {
    /// Convention of the edited table.
    pub convention: Option<Convention>,
    /// One entry per joint.
    pub rows: Vec<RowText>,
    /// The cell that is wrong, and why.
    pub error: Option<CellError>,
    /// After a joint was added or removed: the joint vector that keeps every other
    /// joint's value, applied with the table once it is valid.
    pub kept_q: Option<Vec<f64>>,
}

/// A cell of the table that does not give a valid robot.
#[derive(Debug, Clone, PartialEq)]
pub struct CellError {
    /// The row (0-based).
    pub row: usize,
    /// The column (0-based, as [`COLUMNS`]).
    pub column: usize,
    /// What is wrong.
    pub problem: CellProblem,
}

/// What is wrong with a cell.
#[derive(Debug, Clone, PartialEq)]
pub enum CellProblem {
    /// Nothing typed.
    Empty,
    /// The text typed, which is not a number.
    NotANumber(String),
    /// The numbers parse but the core rejects the table.
    Robot(RobotError),
}

impl CellError {
    /// The sentence shown beside the cell, in `lang`.
    pub fn sentence(&self, lang: Lang) -> String {
        let (row, column) = (self.row + 1, COLUMNS[self.column]);
        match &self.problem {
            CellProblem::Empty => fill(lang, Key::CellEmpty, &[&row, &column]),
            CellProblem::NotANumber(text) => fill(lang, Key::CellNotNumber, &[&row, &column, text]),
            CellProblem::Robot(e) => e.sentence(lang),
        }
    }
}

fn fmt(v: f64) -> String {
    number(v, CELL_DECIMALS)
}

impl DhEditor {
    /// The texts of a robot's table.
    pub fn from_robot(robot: &Robot) -> Self {
        let rows = robot
            .joints
            .iter()
            .map(|j| {
                let (min, max) = match j.kind {
                    JointKind::Revolute => (j.limits.min.to_degrees(), j.limits.max.to_degrees()),
                    JointKind::Prismatic => (j.limits.min, j.limits.max),
                };
                RowText {
                    kind: j.kind,
                    cells: [
                        fmt(j.dh.theta.to_degrees()),
                        fmt(j.dh.d),
                        fmt(j.dh.a),
                        fmt(j.dh.alpha.to_degrees()),
                        fmt(min),
                        fmt(max),
                    ],
                }
            })
            .collect();
        DhEditor {
            convention: Some(robot.convention),
            rows,
            error: None,
            kept_q: None,
        }
    }

    /// The first error as an English sentence, if any.
    pub fn first_error(&self) -> Option<String> {
        self.error.as_ref().map(|e| e.sentence(Lang::En))
    }

    /// Builds a robot from the texts on top of `base` (names, unit, transforms), or says
    /// which cell is wrong.
    pub fn to_robot(&self, base: &Robot) -> Result<Robot, CellError> {
        let mut joints = Vec::with_capacity(self.rows.len());
        for (i, row) in self.rows.iter().enumerate() {
            let mut v = [0.0; 6];
            for (c, text) in row.cells.iter().enumerate() {
                let trimmed = text.trim();
                v[c] = trimmed.parse::<f64>().map_err(|_| CellError {
                    row: i,
                    column: c,
                    problem: if trimmed.is_empty() {
                        CellProblem::Empty
                    } else {
                        CellProblem::NotANumber(trimmed.to_string())
                    },
                })?;
            }
            let old = base.joints.get(i);
            let limits = match row.kind {
                JointKind::Revolute => JointLimits {
                    min: v[4].to_radians(),
                    max: v[5].to_radians(),
                },
                JointKind::Prismatic => JointLimits {
                    min: v[4],
                    max: v[5],
                },
            };
            // Not `limits.clamp`: it panics on reversed or NaN limits, which the core's
            // check below turns into the sentence beside the cell.
            let within = |v: f64| v.max(limits.min).min(limits.max);
            let home = old
                .filter(|o| o.kind == row.kind)
                .map_or(within(0.0), |o| within(o.home));
            joints.push(Joint {
                name: old.map_or_else(|| format!("joint {}", i + 1), |o| o.name.clone()),
                kind: row.kind,
                dh: DhRow {
                    theta: v[0].to_radians(),
                    d: v[1],
                    a: v[2],
                    alpha: v[3].to_radians(),
                },
                limits,
                max_speed: old.and_then(|o| o.max_speed),
                max_acceleration: old.and_then(|o| o.max_acceleration),
                home,
                parts: old.map(|o| o.parts).unwrap_or_default(),
            });
        }
        let robot = Robot {
            joints,
            convention: self.convention.unwrap_or(base.convention),
            ..base.clone()
        };
        robot.validated().map_err(|e| {
            let (row, column) = locate(&e);
            CellError {
                row,
                column,
                problem: CellProblem::Robot(e),
            }
        })
    }
}

/// Which cell a core error points at (row, column), for placing the message.
fn locate(e: &RobotError) -> (usize, usize) {
    e.dh_cell()
        .map_or((0, 0), |(row, column)| (row, column.index()))
}

/// The convention's radio buttons; returns whether it changed.
pub(crate) fn convention_row(editor: &mut DhEditor, model: &Model, ui: &mut egui::Ui) -> bool {
    let mut changed = false;
    crate::app::widgets::style::wrapped(ui, |ui| {
        ui.label(tr(model, Key::Convention));
        let mut conv = editor.convention.unwrap_or(model.robot().convention);
        changed |= ui
            .radio_value(
                &mut conv,
                Convention::Standard,
                tr(model, Key::ConventionStandard),
            )
            .changed();
        changed |= ui
            .radio_value(
                &mut conv,
                Convention::Modified,
                tr(model, Key::ConventionModified),
            )
            .changed();
        editor.convention = Some(conv);
    });
    changed
}

/// What the user did in a DH table.
pub(crate) struct TableEdit {
    /// A cell or a joint's type changed.
    pub changed: bool,
    /// The row whose × was clicked.
    pub remove: Option<usize>,
}

/// The space between a table's columns and rows (points).
const TABLE_SPACING: egui::Vec2 = egui::vec2(4.0, 2.0);
/// The narrowest cell of the one-line rows (points).
const CELL_MIN_WIDTH: f32 = 50.0;
/// The narrowest cell of the blocks (points): two cells and their names fit a projector's
/// 200-point column.
const BLOCK_CELL_MIN_WIDTH: f32 = 44.0;
/// The widest a cell grows with its text (points); a longer text scrolls inside it.
const CELL_MAX_WIDTH: f32 = 400.0;
/// A cell's text margin left and right (points).
const CELL_MARGIN: i8 = 4;
/// A cell's frame around its text: the text edit's margins and room for the cursor.
const CELL_FRAME: f32 = 2.0 * CELL_MARGIN as f32 + 6.0;
/// The width of a row's R/P menu.
const KIND_MENU_WIDTH: f32 = 36.0;

/// A DH table's caption (the units) and rows with their editable cells: one line per
/// joint when the panel has the room for all of it (#, type, θ, d, a, α, min, max, ×);
/// otherwise a block of four lines per joint (its number, type and ×; then θ and d, a and
/// α, min and max, each cell named beside it: the joint's screw along z, its screw along
/// x, its limits), so that in a narrow column (a projector's, a phone's sheet) no cell is
/// cut or hidden behind a sideways scroll. A wrong cell's text is red, and its sentence
/// goes under the table, wrapped at the panel's edge. The cells' screen points are
/// `dh-ROW-COLUMN` (1-based) in both layouts.
pub(crate) fn dh_rows(
    ui: &mut egui::Ui,
    model: &Model,
    (id_salt, convention): (&str, Convention),
    rows: &mut [RowText],
    error: Option<&CellError>,
    points: &mut ScreenPoints,
) -> TableEdit {
    let unit = model.robot().length_unit.symbol();
    ui.label(egui::RichText::new(trf(model, Key::LengthsIn, &[&unit])).small());
    let widths = TableWidths::measure(ui, model, rows, convention);
    let order = column_order(convention);
    let room = style::room(ui);
    let mut edit = TableEdit {
        changed: false,
        remove: None,
    };
    if widths.one_line <= room {
        egui::Grid::new((id_salt, "lines"))
            .striped(true)
            .spacing(TABLE_SPACING)
            .min_col_width(0.0)
            .max_col_width(widths.widest_column())
            .show(ui, |ui| {
                dh_header_row(model, ui, convention);
                for (i, row) in rows.iter_mut().enumerate() {
                    let number = ui.label(format!("{}", i + 1));
                    edit.changed |= kind_menu(ui, model, i, row, number.id);
                    for c in order {
                        let width = widths.columns[c];
                        edit.changed |= dh_cell(ui, i, c, row, width, error, points);
                    }
                    if remove_button(ui, model, i) {
                        edit.remove = Some(i);
                    }
                    ui.end_row();
                }
            });
    } else {
        // Every other joint's four lines shaded, so that a block reads as one joint.
        let shade = ui.visuals().faint_bg_color;
        egui::Grid::new((id_salt, "blocks"))
            .spacing(TABLE_SPACING)
            .min_col_width(0.0)
            .max_col_width(widths.block_cell)
            .with_row_color(move |line, _| (line / 4 % 2 == 0).then_some(shade))
            .show(ui, |ui| {
                for (i, row) in rows.iter_mut().enumerate() {
                    let number = ui.strong(format!("{}", i + 1));
                    edit.changed |= kind_menu(ui, model, i, row, number.id);
                    ui.label("");
                    if remove_button(ui, model, i) {
                        edit.remove = Some(i);
                    }
                    ui.end_row();
                    for pair in order.chunks(2) {
                        for &c in pair {
                            math::label(ui, header(convention, c, false));
                            edit.changed |=
                                dh_cell(ui, i, c, row, widths.block_cell, error, points);
                        }
                        ui.end_row();
                    }
                }
            });
    }
    if let Some(error) = error {
        let sentence = egui::RichText::new(error.sentence(model.settings().lang));
        style::sentence(ui, sentence.color(style::ERROR));
    }
    edit
}

/// The widths a DH table needs (points), measured from its texts before it is drawn. Its
/// grid is told the widest (`max_col_width`): an egui grid offers a cell only its column's
/// width of the previous frame (at first the default 40 points), so a cell that asks for
/// more would stay cut. Its columns are no wider than their contents (`min_col_width`
/// 0, not egui's 40 points), as measured here.
struct TableWidths {
    /// Each cell column's width in the one-line rows.
    columns: [f32; 6],
    /// The one-line rows' whole width.
    one_line: f32,
    /// Every cell's width in the blocks (one width, so that the blocks line up).
    block_cell: f32,
}

impl TableWidths {
    fn measure(ui: &egui::Ui, model: &Model, rows: &[RowText], convention: Convention) -> Self {
        let font = egui::TextStyle::Body.resolve(ui.style());
        let text_width = |text: &str| style::text_width(ui, text, &font);
        let mut texts = [0.0f32; 6];
        for row in rows {
            for (widest, cell) in texts.iter_mut().zip(&row.cells) {
                *widest = widest.max(text_width(cell));
            }
        }
        let cell = |text: f32, min: f32| (text + CELL_FRAME).clamp(min, CELL_MAX_WIDTH);
        let mut columns = [0.0; 6];
        for (c, width) in columns.iter_mut().enumerate() {
            let head = header_width(ui, header(convention, c, true), &font);
            *width = cell(texts[c], CELL_MIN_WIDTH).max(head);
        }
        let number = text_width(&rows.len().to_string()).max(text_width("#"));
        let kind = (KIND_MENU_WIDTH + 2.0 * ui.spacing().button_padding.x)
            .max(text_width(tr(model, Key::ColumnType)));
        let remove = text_width("×") + 2.0 * ui.spacing().button_padding.x;
        let gaps = TABLE_SPACING.x * (columns.len() + 2) as f32;
        let block_text = texts.iter().copied().fold(0.0, f32::max);
        Self {
            columns,
            one_line: number + kind + columns.iter().sum::<f32>() + remove + gaps,
            block_cell: cell(block_text, BLOCK_CELL_MIN_WIDTH),
        }
    }

    /// The widest cell column of the one-line rows.
    fn widest_column(&self) -> f32 {
        self.columns.iter().copied().fold(0.0, f32::max)
    }
}

/// One editable cell of row `i`, column `c`; returns whether its text changed.
fn dh_cell(
    ui: &mut egui::Ui,
    i: usize,
    c: usize,
    row: &mut RowText,
    width: f32,
    error: Option<&CellError>,
    points: &mut ScreenPoints,
) -> bool {
    let bad = error.is_some_and(|e| e.row == i && e.column == c);
    // The margin fixed rather than the theme's (a touch screen's is wide and would cut the
    // measured numbers), and the text centred in a tall touch cell's height.
    let mut edit = egui::TextEdit::singleline(&mut row.cells[c])
        .margin(egui::Margin::symmetric(CELL_MARGIN, 2))
        .align(egui::Align2::LEFT_CENTER)
        .desired_width(width)
        .id_salt(("dh", i, c))
        .hint_text(COLUMNS[c]);
    if bad {
        edit = edit.text_color(style::ERROR);
    }
    let response = ui.add(edit);
    points.insert(format!("dh-{}-{}", i + 1, c + 1), response.rect.center());
    response.changed()
}

/// Row `i`'s ×, named "Remove joint N" on hover and for screen readers; returns whether
/// it was clicked.
fn remove_button(ui: &mut egui::Ui, model: &Model, i: usize) -> bool {
    let name = trf(model, Key::RemoveJoint, &[&(i + 1)]);
    let response = ui.small_button("×");
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Button, true, &name));
    response.on_hover_text(name.as_str()).clicked()
}

/// The R/P menu of a row; a new type gets limits that make sense for it.
fn kind_menu(
    ui: &mut egui::Ui,
    model: &Model,
    i: usize,
    row: &mut RowText,
    label: egui::Id,
) -> bool {
    let before = row.kind;
    egui::ComboBox::from_id_salt(("kind", i))
        .selected_text(if row.kind == JointKind::Revolute {
            "R"
        } else {
            "P"
        })
        .width(KIND_MENU_WIDTH)
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut row.kind, JointKind::Revolute, tr(model, Key::Revolute));
            ui.selectable_value(
                &mut row.kind,
                JointKind::Prismatic,
                tr(model, Key::Prismatic),
            );
        })
        .response
        .labelled_by(label);
    if row.kind == before {
        return false;
    }
    let (lo, hi) = match row.kind {
        JointKind::Revolute => ("-180", "180"),
        JointKind::Prismatic => ("0", "100"),
    };
    row.cells[4] = lo.into();
    row.cells[5] = hi.into();
    true
}

/// Applies edited texts: a valid table becomes the robot; otherwise the texts stay (so
/// the user can fix them) with the sentence, and the last good robot stays.
pub(crate) fn apply_edit(editor: &mut DhEditor, mut edited: DhEditor, model: &mut Model) {
    match edited.to_robot(model.robot()) {
        Ok(robot) => {
            edited.error = None;
            // A joint added or removed: the other joints keep their values.
            let kept = edited
                .kept_q
                .take()
                .filter(|q| q.len() == robot.dof() && robot.dof() != model.robot().dof());
            *editor = edited;
            if let Some(q) = kept {
                model.edit_robot_with_q(robot, RobotSource::Custom, q);
            } else if &robot != model.robot() {
                model.edit_robot(robot, RobotSource::Custom);
            }
        }
        Err(err) => {
            edited.error = Some(err);
            *editor = edited;
        }
    }
}

/// The DH table's header row: #, type, the columns as formulas in the convention's order,
/// and room for the remove button (the editor and the exercise's answer table share it).
fn dh_header_row(model: &Model, ui: &mut egui::Ui, convention: Convention) {
    ui.label("#");
    ui.label(tr(model, Key::ColumnType));
    for c in column_order(convention) {
        math::label(ui, header(convention, c, true));
    }
    ui.label("");
    ui.end_row();
}
