//! Robots: the preset chooser, a DH table editor that applies live (an invalid cell shows
//! the core's sentence beside it and the last valid robot stays drawn), and saving and
//! loading robot files. Every way of loading a robot goes through
//! [`RobotPanel::load_robot`].

use crate::kinematics::{
    Convention, DhRow, Joint, JointKind, JointLimits, Robot, RobotError, preset, preset_names,
    robot_from_json, robot_to_json,
};

use super::Panel;
use super::format::number;
use super::hook::ScreenPoints;
use super::model::{Message, Model};
use super::session::RobotSource;
use super::style;

/// Decimals of a DH cell: enough to show every preset's value whole.
const CELL_DECIMALS: usize = 6;

/// Column names of the editable DH cells.
pub const COLUMNS: [&str; 6] = ["θ (°)", "d", "a", "α (°)", "min", "max"];

/// One row of cell texts.
#[derive(Debug, Clone, PartialEq)]
pub struct RowText {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// θ, d, a, α, min, max as typed (angles in degrees, lengths in robot units).
    pub cells: [String; 6],
}

/// The editor's texts, kept separately from the robot so that a half-typed number does not
/// disturb the drawn arm.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DhEditor {
    /// Convention of the edited table.
    pub convention: Option<Convention>,
    /// One entry per joint.
    pub rows: Vec<RowText>,
    /// The sentence for the cell that is wrong: (row, column, message).
    pub error: Option<(usize, usize, String)>,
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
        }
    }

    /// The first error as a sentence, if any.
    pub fn first_error(&self) -> Option<String> {
        self.error.as_ref().map(|(_, _, m)| m.clone())
    }

    /// Builds a robot from the texts on top of `base` (names, unit, transforms), or says
    /// which cell is wrong.
    pub fn to_robot(&self, base: &Robot) -> Result<Robot, (usize, usize, String)> {
        let mut joints = Vec::with_capacity(self.rows.len());
        for (i, row) in self.rows.iter().enumerate() {
            let mut v = [0.0; 6];
            for (c, text) in row.cells.iter().enumerate() {
                let trimmed = text.trim();
                v[c] = trimmed.parse::<f64>().map_err(|_| {
                    let what = if trimmed.is_empty() {
                        "is empty".to_string()
                    } else {
                        format!("\"{trimmed}\" is not a number")
                    };
                    (i, c, format!("Joint {}, {}: {what}.", i + 1, COLUMNS[c]))
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
            let (row, col) = locate(&e);
            (row, col, e.to_string())
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
            editor_loads: 0,
            #[cfg(not(target_arch = "wasm32"))]
            file_dialog: None,
        }
    }

    /// The DH editor's texts and error.
    pub fn editor(&self) -> &DhEditor {
        &self.editor
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
    pub fn load_robot_text(&mut self, model: &mut Model, text: &str) {
        match robot_from_json(text) {
            Ok(robot) => {
                self.load_robot(model, robot, RobotSource::Custom);
                model.dismiss_message();
            }
            Err(e) => model.set_message(Message::error(format!(
                "That robot file was not loaded: {e}"
            ))),
        }
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
        egui::ComboBox::new("preset_chooser", "Preset")
            .selected_text(match current {
                Some(_) => model.robot().name.clone(),
                None => format!("{} (edited)", model.robot().name),
            })
            .width((ui.available_width() - 60.0).clamp(120.0, 230.0))
            .show_ui(ui, |ui| {
                for (id, name) in preset_names() {
                    if ui
                        .selectable_label(current.as_deref() == Some(*id), name.as_str())
                        .clicked()
                    {
                        chosen = Some(*id);
                    }
                }
            });
        if let Some(id) = chosen {
            match preset(id) {
                Ok(robot) => self.load_robot(model, robot, RobotSource::Preset(id.to_string())),
                Err(e) => model.set_message(Message::error(e.to_string())),
            }
        }
    }

    fn file_buttons(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            #[cfg(target_arch = "wasm32")]
            {
                if ui.button("Save robot file").clicked() {
                    let text = robot_to_json(model.robot());
                    let name = robot_file_name(model.robot());
                    model.set_message(match super::web::download(&name, &text) {
                        Ok(()) => Message::info(format!("Saved the robot as a download ({name}).")),
                        Err(e) => Message::error(format!("Could not save the robot file: {e}.")),
                    });
                }
                if ui.button("Load robot file…").clicked() {
                    super::web::open_file_chooser();
                }
            }
            #[cfg(not(target_arch = "wasm32"))]
            {
                use super::files::{FileDialog, Mode};
                let here = || std::env::current_dir().unwrap_or_else(|_| ".".into());
                if ui.button("Save robot file…").clicked() {
                    let name = robot_file_name(model.robot());
                    self.file_dialog = Some(FileDialog::new(Mode::Save, &name, here()));
                }
                if ui.button("Open robot file…").clicked() {
                    self.file_dialog = Some(FileDialog::new(Mode::Open, "", here()));
                }
            }
        });
        ui.label(egui::RichText::new("Or drop a robot file (.json) onto the window.").small());
    }

    /// Robot files dropped on the window or picked in the browser's chooser.
    fn receive_files(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let dropped = ui.ctx().input(|i| i.raw.dropped_files.clone());
        for file in dropped {
            #[cfg(not(target_arch = "wasm32"))]
            match file.bytes() {
                Ok(bytes) => self.load_robot_text(model, &String::from_utf8_lossy(&bytes)),
                Err(e) => model.set_message(Message::error(format!(
                    "Could not read the dropped file: {e}."
                ))),
            }
            #[cfg(target_arch = "wasm32")]
            super::web::read_dropped_file(file);
        }
        #[cfg(target_arch = "wasm32")]
        if let Some(text) = super::web::take_uploaded_file() {
            self.load_robot_text(model, &text);
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
        let choice = dialog.show(ctx, &mut open);
        if !open {
            self.file_dialog = None;
        }
        match choice {
            Some(Choice::Open(path)) => match std::fs::read_to_string(&path) {
                Ok(text) => self.load_robot_text(model, &text),
                Err(e) => model.set_message(Message::error(format!(
                    "Could not read {}: {e}.",
                    path.display()
                ))),
            },
            Some(Choice::Save(path)) => {
                let text = robot_to_json(model.robot());
                model.set_message(match std::fs::write(&path, text) {
                    Ok(()) => Message::info(format!("Saved the robot as {}.", path.display())),
                    Err(e) => Message::error(format!(
                        "Could not save the robot file {}: {e}.",
                        path.display()
                    )),
                });
            }
            None => {}
        }
    }
}

impl Panel for RobotPanel {
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        self.sync_editor(model);
        self.preset_chooser(model, ui);
        if !model.robot().description.is_empty() {
            ui.label(egui::RichText::new(&model.robot().description).small());
        }
        let header = egui::CollapsingHeader::new("DH table (editable)")
            .id_salt("dh_editor")
            .default_open(false)
            .show(ui, |ui| dh_table(&mut self.editor, model, ui, points));
        points.insert("dh-header", header.header_response.rect.center());
        self.file_buttons(model, ui);
        self.receive_files(model, ui);
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
    let mut changed = convention_row(&mut edited, model.robot().convention, ui);
    let unit = model.robot().length_unit.symbol();
    ui.label(
        egui::RichText::new(format!(
            "Lengths in {unit}; revolute limits in degrees, prismatic in {unit}."
        ))
        .small(),
    );
    let mut remove = None;
    egui::Grid::new("dh_grid")
        .striped(true)
        .spacing([4.0, 2.0])
        .show(ui, |ui| {
            ui.label("#");
            ui.label("type");
            for c in COLUMNS {
                ui.label(c);
            }
            ui.label("");
            ui.end_row();
            for (i, row) in edited.rows.iter_mut().enumerate() {
                let row_edit = dh_row(ui, i, row, editor.error.as_ref(), points);
                changed |= row_edit.changed;
                if row_edit.remove {
                    remove = Some(i);
                }
            }
        });
    if let Some(i) = remove {
        edited.rows.remove(i);
        changed = true;
    }
    if ui.button("+ Add joint").clicked() {
        edited.rows.push(RowText {
            kind: JointKind::Revolute,
            cells: ["0", "0", "0", "0", "-180", "180"].map(String::from),
        });
        changed = true;
    }
    if changed {
        apply_edit(editor, edited, model);
    }
    if editor.rows.is_empty() {
        ui.colored_label(
            style::ERROR,
            "The robot has no joints: a chain needs at least one.",
        );
    }
}

/// The convention's radio buttons; returns whether it changed.
fn convention_row(editor: &mut DhEditor, robot_convention: Convention, ui: &mut egui::Ui) -> bool {
    let mut changed = false;
    ui.horizontal_wrapped(|ui| {
        ui.label("Convention:");
        let mut conv = editor.convention.unwrap_or(robot_convention);
        changed |= ui
            .radio_value(&mut conv, Convention::Standard, "standard (Spong)")
            .changed();
        changed |= ui
            .radio_value(&mut conv, Convention::Modified, "modified (Craig)")
            .changed();
        editor.convention = Some(conv);
    });
    changed
}

/// What the user did in one row of the table.
struct RowEdit {
    changed: bool,
    remove: bool,
}

/// One joint's row: number, type, six cells, remove button, and its error beneath.
fn dh_row(
    ui: &mut egui::Ui,
    i: usize,
    row: &mut RowText,
    error: Option<&(usize, usize, String)>,
    points: &mut ScreenPoints,
) -> RowEdit {
    let number = ui.label(format!("{}", i + 1));
    let mut changed = kind_menu(ui, i, row, number.id);
    for (c, cell) in row.cells.iter_mut().enumerate() {
        let bad = matches!(error, Some((r, col, _)) if *r == i && *col == c);
        // As wide as its value (the column scrolls; its width is bounded by the layout).
        let font = egui::TextStyle::Body.resolve(ui.style());
        let text_width = ui
            .painter()
            .layout_no_wrap(cell.clone(), font, egui::Color32::WHITE)
            .size()
            .x;
        let mut edit = egui::TextEdit::singleline(cell)
            .desired_width((text_width + 6.0).clamp(52.0, 400.0))
            .id_salt(("dh", i, c))
            .hint_text(COLUMNS[c]);
        if bad {
            edit = edit.text_color(style::ERROR);
        }
        let cell_response = ui.add(edit);
        changed |= cell_response.changed();
        points.insert(
            format!("dh-{}-{}", i + 1, c + 1),
            cell_response.rect.center(),
        );
    }
    let remove = ui
        .small_button("×")
        .on_hover_text("Remove this joint")
        .clicked();
    ui.end_row();
    if let Some((r, _, message)) = error
        && *r == i
    {
        ui.label("");
        ui.label("");
        ui.colored_label(style::ERROR, message);
        ui.end_row();
    }
    RowEdit { changed, remove }
}

/// The R/P menu of a row; a new type gets limits that make sense for it.
fn kind_menu(ui: &mut egui::Ui, i: usize, row: &mut RowText, label: egui::Id) -> bool {
    let before = row.kind;
    egui::ComboBox::from_id_salt(("kind", i))
        .selected_text(if row.kind == JointKind::Revolute {
            "R"
        } else {
            "P"
        })
        .width(36.0)
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut row.kind, JointKind::Revolute, "R  revolute");
            ui.selectable_value(&mut row.kind, JointKind::Prismatic, "P  prismatic");
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
            *editor = edited;
            if &robot != model.robot() {
                model.edit_robot(robot, RobotSource::Custom);
            }
        }
        Err(err) => {
            edited.error = Some(err);
            *editor = edited;
        }
    }
}

/// The file name a robot is saved under: its name in lower case, spaces as dashes.
pub fn robot_file_name(robot: &Robot) -> String {
    format!("{}.json", robot.name.to_lowercase().replace(' ', "-"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reversed_or_nan_limits_give_the_cores_sentence_not_a_panic() {
        let robot = preset("rrr").expect("a preset");
        let mut editor = DhEditor::from_robot(&robot);
        editor.rows[0].cells[4] = "90".into();
        editor.rows[0].cells[5] = "-90".into();
        let (row, column, _) = editor.to_robot(&robot).expect_err("reversed limits");
        assert_eq!((row, column), (0, 4));
        editor.rows[0].cells[4] = "NaN".into();
        let (row, column, message) = editor.to_robot(&robot).expect_err("not finite");
        assert_eq!((row, column), (0, 4));
        assert_eq!(
            message,
            "In joint 1, the field \"min\" is not a finite number (NaN)."
        );
    }
}
