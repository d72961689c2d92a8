//! Robots: the preset chooser, a DH table editor that applies live (an invalid cell shows
//! the core's sentence beside it and the last valid robot stays drawn), and saving and
//! loading robot files.

use crate::kinematics::{
    Convention, DhRow, Joint, JointKind, JointLimits, PRESETS, Robot, preset, robot_from_json,
    robot_to_json,
};

use super::session::RobotSource;
use super::{ArmLabApp, style};

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
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
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
            let home = old
                .filter(|o| o.kind == row.kind)
                .map_or(limits.clamp(0.0), |o| limits.clamp(o.home));
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
fn locate(e: &crate::kinematics::RobotError) -> (usize, usize) {
    use crate::kinematics::{Place, RobotError};
    let column = |field: &str| match field {
        "theta" => 0,
        "d" => 1,
        "a" => 2,
        "alpha" => 3,
        "min" => 4,
        _ => 5,
    };
    match e {
        RobotError::NotFinite {
            place: Place::Joint(n),
            field,
            ..
        }
        | RobotError::TooLarge {
            place: Place::Joint(n),
            field,
            ..
        } => (n - 1, column(field)),
        RobotError::LimitsReversed { joint, .. } => (joint - 1, 4),
        _ => (0, 0),
    }
}

/// Shows the robot chooser, the DH editor and file buttons.
pub fn show(app: &mut ArmLabApp, ui: &mut egui::Ui) {
    let current = match &app.session.source {
        RobotSource::Preset(id) => id.clone(),
        RobotSource::Custom => "custom".to_string(),
    };
    let mut chosen = None;
    egui::ComboBox::new("preset_chooser", "Robot")
        .selected_text(if current == "custom" {
            format!("{} (edited)", app.session.robot.name)
        } else {
            app.session.robot.name.clone()
        })
        .width(230.0)
        .show_ui(ui, |ui| {
            for (id, _) in PRESETS {
                let name = preset(id)
                    .map(|r| r.name)
                    .unwrap_or_else(|_| id.to_string());
                if ui.selectable_label(current == *id, name).clicked() {
                    chosen = Some(id.to_string());
                }
            }
        });
    if let Some(id) = chosen {
        match preset(&id) {
            Ok(robot) => {
                let home = robot.home();
                app.editor = DhEditor::from_robot(&robot);
                app.set_robot(robot, RobotSource::Preset(id));
                app.set_q(home);
                app.snap_target();
                app.fit_camera();
            }
            Err(e) => app.message = Some(e.to_string()),
        }
    }
    if !app.session.robot.description.is_empty() {
        ui.label(egui::RichText::new(&app.session.robot.description).small());
    }
    let header = egui::CollapsingHeader::new("DH table (editable)")
        .id_salt("dh_editor")
        .default_open(false)
        .show(ui, |ui| dh_table(app, ui));
    let c = header.header_response.rect.center();
    app.viewport.points.push(("dh-header".into(), [c.x, c.y]));
    ui.horizontal(|ui| {
        #[cfg(target_arch = "wasm32")]
        {
            if ui.button("Save robot file").clicked() {
                let text = robot_to_json(&app.session.robot);
                let name = robot_file_name(&app.session.robot);
                app.message = Some(match super::web::download(&name, &text) {
                    Ok(()) => format!("Saved the robot as a download ({name})."),
                    Err(e) => format!("Could not save the robot file: {e}."),
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
                let name = robot_file_name(&app.session.robot);
                app.file_dialog = Some(FileDialog::new(Mode::Save, &name, here()));
            }
            if ui.button("Open robot file…").clicked() {
                app.file_dialog = Some(FileDialog::new(Mode::Open, "", here()));
            }
        }
    });
    ui.label(egui::RichText::new("Or drop a robot file (.json) onto the window.").small());
    let dropped = ui.ctx().input(|i| i.raw.dropped_files.clone());
    for file in dropped {
        #[cfg(not(target_arch = "wasm32"))]
        match file.bytes() {
            Ok(bytes) => load_robot_text(app, &String::from_utf8_lossy(&bytes)),
            Err(e) => app.message = Some(format!("Could not read the dropped file: {e}.")),
        }
        #[cfg(target_arch = "wasm32")]
        super::web::read_dropped_file(file);
    }
    #[cfg(target_arch = "wasm32")]
    if let Some(text) = super::web::take_uploaded_file() {
        load_robot_text(app, &text);
    }
}

/// Loads a robot file's text; a bad file leaves the robot as it is and says why.
pub fn load_robot_text(app: &mut ArmLabApp, text: &str) {
    match robot_from_json(text) {
        Ok(robot) => {
            app.editor = DhEditor::from_robot(&robot);
            let home = robot.home();
            app.set_robot(robot, RobotSource::Custom);
            app.set_q(home);
            app.snap_target();
            app.fit_camera();
            app.message = None;
        }
        Err(e) => app.message = Some(format!("That robot file was not loaded: {e}")),
    }
}

fn dh_table(app: &mut ArmLabApp, ui: &mut egui::Ui) {
    let mut editor = app.editor.clone();
    let mut changed = false;
    ui.horizontal(|ui| {
        ui.label("Convention:");
        let mut conv = editor.convention.unwrap_or(app.session.robot.convention);
        changed |= ui
            .radio_value(&mut conv, Convention::Standard, "standard (Spong)")
            .changed();
        changed |= ui
            .radio_value(&mut conv, Convention::Modified, "modified (Craig)")
            .changed();
        editor.convention = Some(conv);
    });
    let unit = app.session.robot.length_unit.symbol();
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
            for (i, row) in editor.rows.iter_mut().enumerate() {
                let number = ui.label(format!("{}", i + 1));
                let kind_before = row.kind;
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
                    .labelled_by(number.id);
                if row.kind != kind_before {
                    changed = true;
                    // Limits change meaning: give the new type sensible ones.
                    let (lo, hi) = match row.kind {
                        JointKind::Revolute => ("-180", "180"),
                        JointKind::Prismatic => ("0", "100"),
                    };
                    row.cells[4] = lo.into();
                    row.cells[5] = hi.into();
                }
                for (c, cell) in row.cells.iter_mut().enumerate() {
                    let bad =
                        matches!(&app.editor.error, Some((r, col, _)) if *r == i && *col == c);
                    let mut edit = egui::TextEdit::singleline(cell)
                        .desired_width(52.0)
                        .id_salt(("dh", i, c))
                        .hint_text(COLUMNS[c]);
                    if bad {
                        edit = edit.text_color(style::ERROR);
                    }
                    let cell_response = ui.add(edit);
                    changed |= cell_response.changed();
                    let mid = cell_response.rect.center();
                    app.viewport
                        .points
                        .push((format!("dh-{}-{}", i + 1, c + 1), [mid.x, mid.y]));
                }
                if ui
                    .small_button("×")
                    .on_hover_text("Remove this joint")
                    .clicked()
                {
                    remove = Some(i);
                }
                ui.end_row();
                if let Some((r, _, message)) = &app.editor.error
                    && *r == i
                {
                    ui.label("");
                    ui.label("");
                    ui.colored_label(style::ERROR, message);
                    ui.end_row();
                }
            }
        });
    if let Some(i) = remove {
        editor.rows.remove(i);
        changed = true;
    }
    if ui.button("+ Add joint").clicked() {
        editor.rows.push(RowText {
            kind: JointKind::Revolute,
            cells: ["0", "0", "0", "0", "-180", "180"].map(String::from),
        });
        changed = true;
    }
    if changed {
        match editor.to_robot(&app.session.robot) {
            Ok(robot) => {
                editor.error = None;
                app.editor = editor;
                if robot != app.session.robot {
                    app.set_robot(robot, RobotSource::Custom);
                }
            }
            Err(err) => {
                // Keep the texts (so the user can fix them) and the last good robot.
                editor.error = Some(err);
                app.editor = editor;
            }
        }
    }
    if app.editor.rows.is_empty() {
        ui.colored_label(
            style::ERROR,
            "The robot has no joints: a chain needs at least one.",
        );
    }
}

/// The file name a robot is saved under: its name in lower case, spaces as dashes.
pub fn robot_file_name(robot: &crate::kinematics::Robot) -> String {
    format!("{}.json", robot.name.to_lowercase().replace(' ', "-"))
}

/// Shows the native file dialog while it is open, and loads or saves what it chose.
#[cfg(not(target_arch = "wasm32"))]
pub fn show_file_dialog(app: &mut ArmLabApp, ctx: &egui::Context) {
    use super::files::Choice;
    let Some(dialog) = app.file_dialog.as_mut() else {
        return;
    };
    let mut open = true;
    let choice = dialog.show(ctx, &mut open);
    if !open {
        app.file_dialog = None;
    }
    match choice {
        Some(Choice::Open(path)) => match std::fs::read_to_string(&path) {
            Ok(text) => load_robot_text(app, &text),
            Err(e) => {
                app.message = Some(format!("Could not read {}: {e}.", path.display()));
            }
        },
        Some(Choice::Save(path)) => {
            let text = robot_to_json(&app.session.robot);
            app.message = Some(match std::fs::write(&path, text) {
                Ok(()) => format!("Saved the robot as {}.", path.display()),
                Err(e) => format!("Could not save the robot file {}: {e}.", path.display()),
            });
        }
        None => {}
    }
}
