//! Robots: the preset chooser, a DH table editor that applies live (an invalid cell shows
//! the core's sentence beside it and the last valid robot stays drawn), and saving and
//! loading robot files. Every way of loading a robot goes through
//! [`RobotPanel::load_robot`].

use armlab_core::edit::{insert_joint, remove_joint, switch_convention};
use armlab_core::{
    DhRow, Joint, JointKind, JointLimits, Robot, preset, preset_names, robot_from_json,
    robot_to_json,
};
use armlab_text::Sentence;

use armlab_text::Key;

use crate::app::panels::Panel;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::{Message, Model};
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::dh_table::{
    DhEditor, RowText, TableEdit, apply_edit, convention_row, dh_rows,
};
use crate::app::widgets::style;
use armlab_session::session::RobotSource;

/// The robot panel: the preset chooser, the DH editor's texts and, natively, the file
/// dialog while it is open.
pub struct RobotPanel {
    editor: DhEditor,
    /// The robot before the focused cell's typing.
    baseline: crate::app::widgets::draft::Baseline,
    /// The DH-table exercise's answer table (while an exercise is open).
    exercise: crate::app::panels::exercise::ExercisePanel,
    /// The model's robot-load count the editor's texts were taken at.
    editor_loads: u64,
    /// The native file dialog, while it is open.
    #[cfg(not(target_arch = "wasm32"))]
    file_dialog: Option<crate::app::panels::file_dialog::FileDialog>,
}

impl RobotPanel {
    /// The panel for a robot: the editor holds its table.
    pub fn new(robot: &Robot) -> Self {
        RobotPanel {
            editor: DhEditor::from_robot(robot),
            baseline: Default::default(),
            exercise: crate::app::panels::exercise::ExercisePanel::default(),
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
    pub fn exercise(&self) -> &crate::app::panels::exercise::ExercisePanel {
        &self.exercise
    }

    /// The native file dialog, while it is open.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn file_dialog(&self) -> Option<&crate::app::panels::file_dialog::FileDialog> {
        self.file_dialog.as_ref()
    }

    /// Opens the native file dialog (the buttons do; tests too).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn open_file_dialog(&mut self, dialog: crate::app::panels::file_dialog::FileDialog) {
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
    fn file_event(
        &mut self,
        model: &mut Model,
        event: crate::app::platform::web::files::FileEvent,
    ) {
        use crate::app::platform::web::files::FileEvent;
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
        crate::app::widgets::style::wrapped(ui, |ui| {
            #[cfg(target_arch = "wasm32")]
            {
                let save = ui.button(tr(model, Key::SaveRobotDownload));
                points.insert("robot-save", save.rect.center());
                if save.clicked() {
                    let text = robot_to_json(model.robot());
                    let name = robot_file_name(model.robot());
                    let message = match crate::app::platform::web::files::download(&name, &text) {
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
                    crate::app::platform::web::files::download_urdf(
                        name,
                        robot_to_json(model.robot()),
                    );
                }
                let load = ui.button(tr(model, Key::LoadRobotFile));
                points.insert("robot-load", load.rect.center());
                if load.clicked() {
                    crate::app::platform::web::files::open_file_chooser();
                }
            }
            #[cfg(not(target_arch = "wasm32"))]
            {
                use crate::app::panels::file_dialog::{FileDialog, Mode};
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
            crate::app::platform::web::files::read_dropped_file(file);
        }
        #[cfg(target_arch = "wasm32")]
        for event in crate::app::platform::web::files::take_file_events() {
            self.file_event(model, event);
        }
    }

    /// Shows the native file dialog while it is open, and loads or saves what it chose.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn show_file_dialog(&mut self, model: &mut Model, ctx: &egui::Context) {
        use crate::app::panels::file_dialog::Choice;
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
        let header = egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::DhTable),
        ))
        .id_salt("dh_editor")
        .default_open(false)
        // Unindented: a projector's column has room for the table's blocks only
        // with the indent's 18 points.
        .show_unindented(ui, |ui| {
            dh_table((&mut self.editor, &mut self.baseline), model, ui, points)
        });
        points.insert("dh-header", header.header_response.rect.center());
        crate::app::panels::convention::both_conventions_ui(model, ui);
        self.file_buttons(model, ui, points);
        self.receive_files(model, ui);
        crate::app::panels::exercise::start_ui(model, ui, points);
    }
}

/// The editor: convention, the table, add a joint; applies a valid table live.
fn dh_table(
    (editor, baseline): (&mut DhEditor, &mut crate::app::widgets::draft::Baseline),
    model: &mut Model,
    ui: &mut egui::Ui,
    points: &mut ScreenPoints,
) {
    baseline.track(ui, model);
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
        (
            "dh_grid",
            edited.convention.unwrap_or(model.robot().convention),
        ),
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
        if editor.error.is_some() {
            baseline.restore(model, editor.rows.len());
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use armlab_core::preset_ids;
    use armlab_text::Lang;

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
