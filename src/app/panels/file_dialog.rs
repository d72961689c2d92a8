//! The native file dialog for robot files: a window that browses folders, lists the
//! `.json` files, and opens one or saves under a typed name. (The browser uses its own
//! download and upload instead; see the platform's `web` module.) Drawn with egui, so it looks and behaves
//! the same on every desktop and needs no system dialog service.

use std::path::{Path, PathBuf};

use armlab_text::{Key, Lang, fill, text};

/// Open a robot file, or save the current robot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Pick an existing file to load.
    Open,
    /// Choose a folder and a name to write.
    Save,
}

/// One row of the listing.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Entry {
    name: String,
    folder: bool,
}

/// What the user chose in the dialog this frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Choice {
    /// Load this file.
    Open(PathBuf),
    /// Write the robot here.
    Save(PathBuf),
}

/// The dialog's state while it is open.
#[derive(Debug, Clone)]
pub struct FileDialog {
    mode: Mode,
    folder: PathBuf,
    /// The file name field (Save) or the selected file (Open).
    name: String,
    entries: Vec<Entry>,
    /// Why the folder could not be listed: the system's words.
    error: Option<String>,
}

impl FileDialog {
    /// A dialog on `folder`; `name` is the suggested file name when saving.
    pub fn new(mode: Mode, name: &str, folder: PathBuf) -> Self {
        let mut dialog = FileDialog {
            mode,
            folder,
            name: name.to_string(),
            entries: Vec::new(),
            error: None,
        };
        dialog.list();
        dialog
    }

    /// Lists the current folder: sub-folders first, then `.json` files, each by name.
    fn list(&mut self) {
        self.entries.clear();
        self.error = None;
        match std::fs::read_dir(&self.folder) {
            Ok(read) => {
                for item in read.flatten() {
                    let name = item.file_name().to_string_lossy().into_owned();
                    let folder = item.file_type().is_ok_and(|t| t.is_dir());
                    let hidden = name.starts_with('.');
                    if !hidden && (folder || is_robot_file(&name)) {
                        self.entries.push(Entry { name, folder });
                    }
                }
                self.entries.sort_by(|a, b| {
                    b.folder
                        .cmp(&a.folder)
                        .then_with(|| a.name.to_lowercase().cmp(&b.name.to_lowercase()))
                });
            }
            Err(e) => {
                self.error = Some(e.to_string());
            }
        }
    }

    fn enter(&mut self, folder: PathBuf) {
        self.folder = folder;
        if self.mode == Mode::Open {
            self.name.clear();
        }
        self.list();
    }

    /// The file the dialog would open or write now, if the name field is usable.
    fn chosen_path(&self) -> Option<PathBuf> {
        let name = self.name.trim();
        if name.is_empty() || name.contains(['/', '\\']) {
            return None;
        }
        let name = if self.mode == Mode::Save && !is_robot_file(name) {
            format!("{name}.json")
        } else {
            name.to_string()
        };
        Some(self.folder.join(name))
    }

    /// Why the folder could not be listed, as a sentence in `lang`.
    fn error_sentence(&self, lang: Lang) -> Option<String> {
        let folder = self.folder.display();
        self.error
            .as_ref()
            .map(|e| fill(lang, Key::FolderUnreadable, &[&folder, e]))
    }

    /// Shows the dialog in `lang`; returns the choice once the user makes it, and sets
    /// `open` to false when the dialog should close.
    pub fn show(&mut self, ctx: &egui::Context, lang: Lang, open: &mut bool) -> Option<Choice> {
        let mut choice = None;
        let title = match self.mode {
            Mode::Open => Key::OpenDialogTitle,
            Mode::Save => Key::SaveDialogTitle,
        };
        let mut still_open = *open;
        egui::Window::new(text(lang, title))
            .id(egui::Id::unique("armlab_file_dialog"))
            .collapsible(false)
            .resizable(true)
            .default_size([460.0, 380.0])
            .open(&mut still_open)
            .show(ctx, |ui| choice = self.contents(ui, lang));
        *open = still_open && choice.is_none() && !self.cancelled(ctx);
        choice
    }

    fn cancelled(&self, ctx: &egui::Context) -> bool {
        ctx.input(|i| i.key_pressed(egui::Key::Escape))
    }

    fn contents(&mut self, ui: &mut egui::Ui, lang: Lang) -> Option<Choice> {
        let mut go_to = self.folder_bar(ui, lang);
        ui.separator();
        let (entered, pick) = self.listing(ui, lang);
        go_to = go_to.or(entered);
        if let Some(folder) = go_to {
            self.enter(folder);
        }
        ui.separator();
        self.confirm_row(ui, lang, pick)
    }

    /// The folder's path with an "Up" button; returns the folder to go to.
    fn folder_bar(&self, ui: &mut egui::Ui, lang: Lang) -> Option<PathBuf> {
        let mut go_to = None;
        ui.horizontal(|ui| {
            let up = egui::Button::new(text(lang, Key::Up));
            if ui
                .add_enabled(self.folder.parent().is_some(), up)
                .on_hover_text(text(lang, Key::UpHint))
                .clicked()
            {
                go_to = self.folder.parent().map(Path::to_path_buf);
            }
            ui.label(egui::RichText::new(self.folder.display().to_string()).monospace());
        });
        go_to
    }

    /// Folders and .json files: a click on a folder enters it, on a file takes its name,
    /// a double click on a file picks it. Returns (folder to enter, file picked).
    fn listing(&mut self, ui: &mut egui::Ui, lang: Lang) -> (Option<PathBuf>, Option<String>) {
        let (mut go_to, mut pick) = (None, None);
        egui::ScrollArea::vertical()
            .max_height(240.0)
            .auto_shrink([false, true])
            .show(ui, |ui| {
                if let Some(error) = self.error_sentence(lang) {
                    ui.colored_label(crate::app::widgets::style::ERROR, error);
                }
                if self.entries.is_empty() && self.error.is_none() {
                    ui.label(text(lang, Key::NoFiles));
                }
                for entry in &self.entries {
                    let label = if entry.folder {
                        format!("{}/", entry.name)
                    } else {
                        entry.name.clone()
                    };
                    let selected = !entry.folder && entry.name == self.name;
                    let response = ui.selectable_label(selected, label);
                    if response.clicked() {
                        if entry.folder {
                            go_to = Some(self.folder.join(&entry.name));
                        } else {
                            self.name = entry.name.clone();
                        }
                    }
                    if response.double_clicked() && !entry.folder {
                        pick = Some(entry.name.clone());
                    }
                }
            });
        (go_to, pick)
    }

    /// The name field, the overwrite warning and the Open/Save button; returns the
    /// choice once confirmed.
    fn confirm_row(
        &mut self,
        ui: &mut egui::Ui,
        lang: Lang,
        pick: Option<String>,
    ) -> Option<Choice> {
        let mut confirm = pick.is_some();
        ui.horizontal(|ui| {
            let label = ui.label(text(lang, Key::FileName));
            let field = ui
                .text_edit_singleline(&mut self.name)
                .labelled_by(label.id);
            confirm |= field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        });
        let path = pick
            .map(|name| self.folder.join(name))
            .or_else(|| self.chosen_path());
        let exists = path.as_ref().is_some_and(|p| p.is_file());
        if self.mode == Mode::Save && exists {
            ui.colored_label(
                crate::app::widgets::style::PENDING,
                text(lang, Key::OverwriteWarning),
            );
        }
        let ready = match self.mode {
            Mode::Open => exists,
            Mode::Save => path.is_some(),
        };
        ui.horizontal(|ui| {
            let verb = match self.mode {
                Mode::Open => Key::Open,
                Mode::Save => Key::Save,
            };
            let button = egui::Button::new(text(lang, verb));
            confirm |= ui.add_enabled(ready, button).clicked();
        });
        match (confirm && ready, path) {
            (true, Some(path)) => Some(match self.mode {
                Mode::Open => Choice::Open(path),
                Mode::Save => Choice::Save(path),
            }),
            _ => None,
        }
    }
}

fn is_robot_file(name: &str) -> bool {
    Path::new(name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_folders_first_then_json_files_and_builds_the_save_path() {
        let dir = std::env::temp_dir().join(format!("armlab-files-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("robots")).expect("temp folder");
        std::fs::write(dir.join("b.json"), "{}").expect("write");
        std::fs::write(dir.join("A.JSON"), "{}").expect("write");
        std::fs::write(dir.join("notes.txt"), "").expect("write");
        let mut d = FileDialog::new(Mode::Save, "my arm", dir.clone());
        let names: Vec<_> = d.entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["robots", "A.JSON", "b.json"]);
        assert_eq!(d.chosen_path(), Some(dir.join("my arm.json")));
        d.name = "../escape".into();
        assert_eq!(d.chosen_path(), None);
        d.enter(dir.join("missing"));
        assert!(
            d.error_sentence(Lang::En)
                .is_some_and(|e| e.contains("cannot be read"))
        );
        assert!(
            d.error_sentence(Lang::Fi)
                .is_some_and(|e| e.contains("ei voi lukea"))
        );
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
