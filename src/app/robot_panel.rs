//! Robots: the preset chooser, a DH table editor that applies live (an invalid cell shows
//! the core's sentence beside it and the last valid robot stays drawn), and saving and
//! loading robot files. Every way of loading a robot goes through
//! [`RobotPanel::load_robot`].

use armlab_core::edit::{insert_joint, remove_joint, switch_convention};
use armlab_core::{
    Convention, DhRow, Joint, JointKind, JointLimits, Robot, RobotError, preset, preset_names,
    robot_from_json, robot_to_json,
};
use armlab_text::Sentence;

use armlab_text::{Key, Lang, fill};

use super::format::number;
use super::hook::ScreenPoints;
use super::model::{Message, Model};
use super::session::RobotSource;
use super::{Panel, style, tr, trf};

/// Decimals of a DH cell: enough to show every preset's value whole.
const CELL_DECIMALS: usize = 6;

/// Column names of the editable DH cells.
pub const COLUMNS: [&str; 6] = ["θ (°)", "d", "a", "α (°)", "min", "max"];
/// The cells' names beside them in a narrow table's blocks, where the units would not fit
/// (the caption above the table gives them).
const BLOCK_NAMES: [&str; 6] = ["θ", "d", "a", "α", "min", "max"];

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

/// The robot panel: the preset chooser, the DH editor's texts and, natively, the file
/// dialog while it is open.
pub struct RobotPanel {
    editor: DhEditor,
    /// The DH-table exercise's answer table (while an exercise is open).
    exercise: super::exercise_view::ExercisePanel,
    /// The model's robot-load count the editor's texts were taken at.
    editor_loads: u64,
    /// The native file dialog, while it is open.
    #[cfg(not(target_arch = "wasm32"))]
    file_dialog: Option<super::files::FileDialog>,
}

impl RobotPanel {
    /// The panel for a robot: the editor holds its table.
    pub fn new(robot: &Robot) -> Self {
        RobotPanel {
            editor: DhEditor::from_robot(robot),
            exercise: super::exercise_view::ExercisePanel::default(),
            editor_loads: 0,
            #[cfg(not(target_arch = "wasm32"))]
            file_dialog: None,
        }
    }

    /// The DH editor's texts and error.
    pub fn editor(&self) -> &DhEditor {
        &self.editor
    }

    /// The DH-table exercise's answer table.
    pub fn exercise(&self) -> &super::exercise_view::ExercisePanel {
        &self.exercise
    }

    /// The native file dialog, while it is open.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn file_dialog(&self) -> Option<&super::files::FileDialog> {
        self.file_dialog.as_ref()
    }

    /// Opens the native file dialog (the buttons do; tests too).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn open_file_dialog(&mut self, dialog: super::files::FileDialog) {
        self.file_dialog = Some(dialog);
    }

    /// The one way a robot is loaded (a preset, a file): the model starts it at its home
    /// pose with the target on its tool, and the editor takes its table.
    pub fn load_robot(&mut self, model: &mut Model, robot: Robot, source: RobotSource) {
        model.load_robot(robot, source);
        self.sync_editor(model);
    }

    /// Loads a robot file's text; a bad file leaves the robot as it is and says why.
    /// Returns whether the robot was loaded.
    pub fn load_robot_text(&mut self, model: &mut Model, text: &str) -> bool {
        match robot_from_json(text) {
            Ok(robot) => {
                self.load_robot(model, robot, RobotSource::Custom);
                model.dismiss_message();
                true
            }
            Err(e) => {
                let reason = e.sentence(model.settings().lang);
                model.set_message(Message::error(trf(model, Key::FileNotLoaded, &[&reason])));
                false
            }
        }
    }

    /// What a picked or dropped file, or a URDF download, gave (the browser). A URDF file
    /// arrives as the robot file the URDF module made of it and takes a robot file's way
    /// in; a bad one gets the robot file's message with the core's sentence, and the
    /// robot stays.
    #[cfg(target_arch = "wasm32")]
    fn file_event(&mut self, model: &mut Model, event: super::web::FileEvent) {
        use super::web::FileEvent;
        let message = match event {
            FileEvent::Robot(text) => {
                self.load_robot_text(model, &text);
                return;
            }
            FileEvent::UrdfLoading => Message::info(tr(model, Key::UrdfLoading)),
            FileEvent::Urdf { robot, meshes } => {
                if !self.load_robot_text(model, &robot) || meshes == 0 {
                    return;
                }
                let name = model.robot().name.clone();
                Message::info(trf(model, Key::UrdfMeshesNotDrawn, &[&name, &meshes]))
            }
            FileEvent::UrdfRejected(sentence) => {
                Message::error(trf(model, Key::FileNotLoaded, &[&sentence]))
            }
            FileEvent::UrdfUnavailable(why) => {
                Message::error(trf(model, Key::UrdfUnavailable, &[&why]))
            }
            FileEvent::UrdfSaved(name) => Message::info(trf(model, Key::SavedUrdf, &[&name])),
            FileEvent::UrdfSaveFailed(why) => {
                Message::error(trf(model, Key::DownloadFailed, &[&why]))
            }
        };
        model.set_message(message);
    }

    /// Takes the model's table when a robot was loaded from elsewhere (a link).
    fn sync_editor(&mut self, model: &Model) {
        if self.editor_loads != model.robot_loads() {
            self.editor = DhEditor::from_robot(model.robot());
            self.editor_loads = model.robot_loads();
        }
    }

    fn preset_chooser(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let current = match model.source() {
            RobotSource::Preset(id) => Some(id.clone()),
            RobotSource::Custom => None,
        };
        let mut chosen = None;
        let name = match current {
            Some(_) => model.robot().name.clone(),
            None => trf(model, Key::Edited, &[&model.robot().name]),
        };
        style::fitted_menu(
            ui,
            "preset_chooser",
            tr(model, Key::Preset),
            &name,
            Some(230.0),
            |ui| {
                for (id, name) in preset_names() {
                    if ui
                        .selectable_label(current.as_deref() == Some(*id), name.as_str())
                        .clicked()
                    {
                        chosen = Some(*id);
                    }
                }
            },
        );
        if let Some(id) = chosen {
            match preset(id) {
                Ok(robot) => self.load_robot(model, robot, RobotSource::Preset(id.to_string())),
                Err(e) => model.set_message(Message::error(e.sentence(model.settings().lang))),
            }
        }
    }

    fn file_buttons(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        super::style::wrapped(ui, |ui| {
            #[cfg(target_arch = "wasm32")]
            {
                let save = ui.button(tr(model, Key::SaveRobotDownload));
                points.insert("robot-save", save.rect.center());
                if save.clicked() {
                    let text = robot_to_json(model.robot());
                    let name = robot_file_name(model.robot());
                    let message = match super::web::download(&name, &text) {
                        Ok(()) => Message::info(trf(model, Key::SavedDownload, &[&name])),
                        Err(e) => Message::error(trf(model, Key::DownloadFailed, &[&e])),
                    };
                    model.set_message(message);
                }
                // URDF support is a module of its own, fetched on the first use.
                let urdf = ui
                    .button(tr(model, Key::SaveRobotUrdf))
                    .on_hover_text(tr(model, Key::SaveRobotUrdfHint));
                points.insert("robot-urdf", urdf.rect.center());
                if urdf.clicked() {
                    let name = robot_file_name(model.robot()).replace(".json", ".urdf");
                    super::web::download_urdf(name, robot_to_json(model.robot()));
                }
                let load = ui.button(tr(model, Key::LoadRobotFile));
                points.insert("robot-load", load.rect.center());
                if load.clicked() {
                    super::web::open_file_chooser();
                }
            }
            #[cfg(not(target_arch = "wasm32"))]
            {
                use super::files::{FileDialog, Mode};
                let here = || std::env::current_dir().unwrap_or_else(|_| ".".into());
                if ui.button(tr(model, Key::SaveRobotFile)).clicked() {
                    let name = robot_file_name(model.robot());
                    self.file_dialog = Some(FileDialog::new(Mode::Save, &name, here()));
                }
                if ui.button(tr(model, Key::OpenRobotFile)).clicked() {
                    self.file_dialog = Some(FileDialog::new(Mode::Open, "", here()));
                }
            }
        });
        #[cfg(not(target_arch = "wasm32"))]
        let _ = points;
        #[cfg(target_arch = "wasm32")]
        let hint = Key::DropHintUrdf;
        #[cfg(not(target_arch = "wasm32"))]
        let hint = Key::DropHint;
        ui.label(egui::RichText::new(tr(model, hint)).small());
    }

    /// Robot files dropped on the window or picked in the browser's chooser.
    fn receive_files(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let dropped = ui.ctx().input(|i| i.raw.dropped_files.clone());
        for file in dropped {
            #[cfg(not(target_arch = "wasm32"))]
            match file.bytes() {
                Ok(bytes) => {
                    self.load_robot_text(model, &String::from_utf8_lossy(&bytes));
                }
                Err(e) => {
                    let text = trf(model, Key::DroppedUnreadable, &[&e]);
                    model.set_message(Message::error(text));
                }
            }
            #[cfg(target_arch = "wasm32")]
            super::web::read_dropped_file(file);
        }
        #[cfg(target_arch = "wasm32")]
        for event in super::web::take_file_events() {
            self.file_event(model, event);
        }
    }

    /// Shows the native file dialog while it is open, and loads or saves what it chose.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn show_file_dialog(&mut self, model: &mut Model, ctx: &egui::Context) {
        use super::files::Choice;
        let Some(dialog) = self.file_dialog.as_mut() else {
            return;
        };
        let mut open = true;
        let choice = dialog.show(ctx, model.settings().lang, &mut open);
        if !open {
            self.file_dialog = None;
        }
        match choice {
            Some(Choice::Open(path)) => match std::fs::read_to_string(&path) {
                Ok(text) => {
                    self.load_robot_text(model, &text);
                }
                Err(e) => {
                    let text = trf(model, Key::FileUnreadable, &[&path.display(), &e]);
                    model.set_message(Message::error(text));
                }
            },
            Some(Choice::Save(path)) => {
                let text = robot_to_json(model.robot());
                let message = match std::fs::write(&path, text) {
                    Ok(()) => Message::info(trf(model, Key::SavedAs, &[&path.display()])),
                    Err(e) => Message::error(trf(model, Key::SaveFailed, &[&path.display(), &e])),
                };
                model.set_message(message);
            }
            None => {}
        }
    }
}

impl Panel for RobotPanel {
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        if model.exercise().is_some() {
            // Only the exercise: the editor, presets, both conventions and files would
            // show the hidden table or end the exercise.
            self.exercise.ui(model, ui, points);
            return;
        }
        self.sync_editor(model);
        self.preset_chooser(model, ui);
        let description = match model.source() {
            RobotSource::Preset(id) => preset_description(id).map(|key| tr(model, key)),
            RobotSource::Custom => None,
        }
        .unwrap_or(model.robot().description.as_str());
        if !description.is_empty() {
            ui.label(egui::RichText::new(description).small());
        }
        let header =
            egui::CollapsingHeader::new(super::style::fold_title(ui, tr(model, Key::DhTable)))
                .id_salt("dh_editor")
                .default_open(false)
                // Unindented: a projector's column has room for the table's blocks only
                // with the indent's 18 points.
                .show_unindented(ui, |ui| dh_table(&mut self.editor, model, ui, points));
        points.insert("dh-header", header.header_response.rect.center());
        super::convention_view::both_conventions_ui(model, ui);
        self.file_buttons(model, ui, points);
        self.receive_files(model, ui);
        super::exercise_view::start_ui(model, ui, points);
    }
}

/// The editor: convention, the table, add a joint; applies a valid table live.
fn dh_table(
    editor: &mut DhEditor,
    model: &mut Model,
    ui: &mut egui::Ui,
    points: &mut ScreenPoints,
) {
    let mut edited = editor.clone();
    let mut changed = convention_row(&mut edited, model, ui);
    // Switching the convention rewrites the table so the arm keeps its shape
    // (docs/kinematics.md §14.3), instead of reading the same numbers the other way.
    let mut converted = None;
    if let Some(to) = edited.convention.filter(|&c| c != model.robot().convention) {
        let robot = switch_convention(model.robot(), to);
        edited = DhEditor::from_robot(&robot);
        converted = Some(robot);
        changed = false;
    }
    let TableEdit {
        changed: cells_changed,
        remove,
    } = dh_rows(
        ui,
        model,
        "dh_grid",
        &mut edited.rows,
        editor.error.as_ref(),
        points,
    );
    changed |= cells_changed;
    if let Some(i) = remove {
        edited.kept_q = kept_q(editor, model, |robot, q| {
            remove_joint(robot, q, i).map(|(_, q)| q)
        });
        edited.rows.remove(i);
        changed = true;
    }
    if ui.button(tr(model, Key::AddJoint)).clicked() {
        let at = edited.rows.len();
        edited.kept_q = kept_q(editor, model, |robot, q| {
            Some(insert_joint(robot, q, at, new_joint(at)).1)
        });
        edited.rows.push(RowText::blank());
        changed = true;
    }
    if let Some(robot) = converted {
        // Not through `to_robot`: the conversion may move a link part into the base or
        // tool transform, which the table's texts do not hold.
        *editor = edited;
        model.edit_robot(robot, RobotSource::Custom);
    } else if changed {
        apply_edit(editor, edited, model);
    }
    if editor.rows.is_empty() {
        ui.colored_label(style::ERROR, tr(model, Key::ErrEmptyChain));
    }
}

/// The joint vector after adding or removing a joint (`edit`, from the core): from the
/// model's robot and q when the table's rows are that robot, or from the vector a
/// previous, not yet applied add or remove kept; `None` (the home pose) otherwise.
fn kept_q(
    editor: &DhEditor,
    model: &Model,
    edit: impl Fn(&Robot, &[f64]) -> Option<Vec<f64>>,
) -> Option<Vec<f64>> {
    let rows = editor.rows.len();
    let robot = model.robot();
    match &editor.kept_q {
        Some(q) if q.len() == rows => {
            // Only the count matters here: the kept values stand for the rows.
            let mut stand_in = robot.clone();
            stand_in.joints.resize(rows, new_joint(0));
            edit(&stand_in, q)
        }
        _ if robot.dof() == rows => edit(robot, model.q()),
        _ => None,
    }
}

/// The joint the "add a joint" button adds: revolute, all zeros, ±180°, home 0.
fn new_joint(i: usize) -> Joint {
    Joint {
        name: format!("joint {}", i + 1),
        kind: JointKind::Revolute,
        dh: DhRow {
            theta: 0.0,
            d: 0.0,
            a: 0.0,
            alpha: 0.0,
        },
        limits: JointLimits::FULL_TURN,
        max_speed: None,
        max_acceleration: None,
        home: 0.0,
        parts: Default::default(),
    }
}

/// The convention's radio buttons; returns whether it changed.
pub(super) fn convention_row(editor: &mut DhEditor, model: &Model, ui: &mut egui::Ui) -> bool {
    let mut changed = false;
    super::style::wrapped(ui, |ui| {
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
pub(super) struct TableEdit {
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
/// A cell's frame around its text: the text edit's margins and room for the cursor.
const CELL_FRAME: f32 = 14.0;
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
pub(super) fn dh_rows(
    ui: &mut egui::Ui,
    model: &Model,
    id_salt: &str,
    rows: &mut [RowText],
    error: Option<&CellError>,
    points: &mut ScreenPoints,
) -> TableEdit {
    let unit = model.robot().length_unit.symbol();
    ui.label(egui::RichText::new(trf(model, Key::LengthsIn, &[&unit])).small());
    let widths = TableWidths::measure(ui, model, rows);
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
                dh_header_row(model, ui);
                for (i, row) in rows.iter_mut().enumerate() {
                    let number = ui.label(format!("{}", i + 1));
                    edit.changed |= kind_menu(ui, model, i, row, number.id);
                    for c in 0..COLUMNS.len() {
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
                    for pair in [[0, 1], [2, 3], [4, 5]] {
                        for c in pair {
                            ui.label(BLOCK_NAMES[c]);
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
    fn measure(ui: &egui::Ui, model: &Model, rows: &[RowText]) -> Self {
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
            *width = cell(texts[c], CELL_MIN_WIDTH).max(text_width(COLUMNS[c]));
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
    let mut edit = egui::TextEdit::singleline(&mut row.cells[c])
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
fn apply_edit(editor: &mut DhEditor, mut edited: DhEditor, model: &mut Model) {
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

/// The catalogue's description of a preset (its robot file holds the English one).
fn preset_description(id: &str) -> Option<Key> {
    Some(match id {
        "ur10" => Key::DescUr10,
        "ur10-standard" => Key::DescUr10Standard,
        "metrover" => Key::DescMetrover,
        "planar-2r" => Key::DescPlanar2r,
        "rrr" => Key::DescRrr,
        "puma560" => Key::DescPuma560,
        "panda" => Key::DescPanda,
        "stanford" => Key::DescStanford,
        "scara" => Key::DescScara,
        _ => return None,
    })
}

/// The file name a robot is saved under: its name in lower case, spaces as dashes.
pub fn robot_file_name(robot: &Robot) -> String {
    format!("{}.json", robot.name.to_lowercase().replace(' ', "-"))
}

/// The DH table's header row: #, type, the columns, and room for the remove button (the
/// editor and the exercise's answer table share it).
fn dh_header_row(model: &Model, ui: &mut egui::Ui) {
    ui.label("#");
    ui.label(tr(model, Key::ColumnType));
    for c in COLUMNS {
        ui.label(c);
    }
    ui.label("");
    ui.end_row();
}

#[cfg(test)]
mod tests {
    use super::*;
    use armlab_core::preset_ids;

    #[test]
    fn every_preset_has_its_description_in_the_catalogue() {
        for id in preset_ids() {
            let robot = preset(id).expect("presets load");
            let key = preset_description(id).expect("a description");
            assert_eq!(armlab_text::text(Lang::En, key), robot.description, "{id}");
        }
    }

    #[test]
    fn a_bad_cell_is_named_in_the_language_asked_for() {
        let robot = preset("rrr").expect("a preset");
        let mut editor = DhEditor::from_robot(&robot);
        editor.rows[1].cells[2] = "12x".into();
        let error = editor.to_robot(&robot).expect_err("not a number");
        assert_eq!(
            error.sentence(Lang::En),
            "Joint 2, a: \"12x\" is not a number."
        );
        assert_eq!(error.sentence(Lang::Fi), "Nivel 2, a: \"12x\" ei ole luku.");
        editor.rows[1].cells[2] = " ".into();
        let error = editor.to_robot(&robot).expect_err("empty");
        assert_eq!(error.sentence(Lang::En), "Joint 2, a: is empty.");
        editor.rows[1].cells[2] = "1".into();
        editor.rows[0].cells[4] = "90".into();
        editor.rows[0].cells[5] = "-90".into();
        let error = editor.to_robot(&robot).expect_err("reversed limits");
        assert_eq!((error.row, error.column), (0, 4));
        assert!(error.sentence(Lang::Fi).starts_with("Nivel 1: alaraja"));
        // Limits that are not numbers at all are the core's sentence too, not a panic.
        editor.rows[0].cells[4] = "NaN".into();
        let error = editor.to_robot(&robot).expect_err("not finite");
        assert_eq!((error.row, error.column), (0, 4));
        assert_eq!(
            error.sentence(Lang::En),
            "In joint 1, the field \"min\" is not a finite number (NaN)."
        );
    }
}
