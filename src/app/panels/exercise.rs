//! The DH-table exercise (docs/kinematics.md §15) in the app: starting one (a mystery arm
//! or a preset), the student's answer table and its Check, and the joint axes with their
//! distances and angles drawn over the 3D view.
//!
//! While an exercise is open and not solved, [`Model::table_hidden`] keeps the robot's
//! table out of sight: the robot panel shows only the exercise, the matrices panel a
//! sentence instead of its numbers, the 3D view no DH frames and no other-convention
//! frames, and the link names only the exercise (`exercise=`), never the table.

use armlab_text::Sentence;

use armlab_core::exercise::Verdict;
use armlab_core::{Convention, Robot, preset_names};
use armlab_session::exercise::ExerciseId;
use armlab_text::Key;

use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::{Message, Model};
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::dh_table::{
    DhEditor, RowText, column_order, convention_row, dh_rows, header,
};
use crate::app::widgets::math;
use crate::app::widgets::style;
use armlab_session::format::number;

/// The student's answer table, kept while the exercise is open.
#[derive(Debug, Clone, Default)]
pub struct ExercisePanel {
    answer: DhEditor,
    /// The model's robot-load count the answer was started at.
    loads: Option<u64>,
}

/// A blank answer for `robot`: its joint count and kinds (both show in the view and the
/// sliders), zeros for θ, d, a and α, its limits, standard DH.
pub fn blank_answer(robot: &Robot) -> DhEditor {
    let mut answer = DhEditor::from_robot(robot);
    for row in &mut answer.rows {
        for cell in &mut row.cells[..4] {
            *cell = "0".to_string();
        }
    }
    answer.convention = Some(Convention::Standard);
    answer
}

impl ExercisePanel {
    /// The answer table as typed.
    pub fn answer(&self) -> &DhEditor {
        &self.answer
    }

    /// The exercise: what to do, the answer table, Check and its verdict, and once
    /// solved the robot's own table.
    pub fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        if self.loads != Some(model.robot_loads()) {
            self.answer = blank_answer(model.robot());
            self.loads = Some(model.robot_loads());
        }
        model.poll_exercise_check();
        ui.strong(tr(model, Key::ExerciseTitle));
        ui.label(egui::RichText::new(tr(model, Key::ExerciseIntro)).small());
        self.answer_table(model, ui, points);
        crate::app::widgets::style::wrapped(ui, |ui| {
            let check = ui
                .button(tr(model, Key::ExerciseCheck))
                .on_hover_text(tr(model, Key::ExerciseCheckHint));
            points.insert("exercise-check", check.rect.center());
            if check.clicked() {
                self.check(model);
            }
            if ui.button(tr(model, Key::ExerciseEnd)).clicked() {
                model.end_exercise();
            }
        });
        let Some(exercise) = model.exercise() else {
            return;
        };
        // Sentences wrap at the column's visible edge (the table may be wider and scroll).
        if exercise.checking.is_some() {
            style::sentence(ui, egui::RichText::new(tr(model, Key::ExerciseChecking)));
        }
        if let Some(why) = &exercise.check_failed {
            let why = armlab_text::echo::text_within(why, 60);
            let sentence = trf(model, Key::ExerciseCheckFailed, &[&why]);
            style::sentence(ui, egui::RichText::new(sentence).color(style::ERROR));
        }
        if let Some(verdict) = exercise.verdict {
            let color = match verdict {
                Verdict::Correct => style::REACHED,
                Verdict::Wrong(_) => style::ERROR,
            };
            let sentence = egui::RichText::new(verdict.sentence(model.settings().lang));
            style::sentence(ui, sentence.color(color));
        }
        if exercise.solved {
            own_table(model, ui);
        }
        style::sentence(
            ui,
            egui::RichText::new(tr(model, Key::ExerciseShareHint)).small(),
        );
    }

    /// Grades the answer; a cell that is not a number is named beside it instead.
    fn check(&mut self, model: &mut Model) {
        match self.answer.to_robot(model.robot()) {
            Ok(student) => {
                self.answer.error = None;
                model.check_exercise(&student);
            }
            Err(e) => self.answer.error = Some(e),
        }
    }

    /// The answer's convention and rows (the DH editor's cells, the same screen points),
    /// with + and × for joints.
    fn answer_table(&mut self, model: &Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        let answer = &mut self.answer;
        convention_row(answer, model, ui);
        let error = answer.error.clone();
        let convention = answer.convention.unwrap_or(Convention::Standard);
        let edit = dh_rows(
            ui,
            model,
            ("exercise_grid", convention),
            &mut answer.rows,
            error.as_ref(),
            points,
        );
        if edit.changed {
            answer.error = None;
        }
        if let Some(i) = edit.remove {
            answer.rows.remove(i);
            answer.error = None;
        }
        if ui.button(tr(model, Key::AddJoint)).clicked() {
            answer.rows.push(RowText::blank());
        }
    }
}

/// The robot's own table (θ, d, a, α), shown once the exercise is solved.
fn own_table(model: &Model, ui: &mut egui::Ui) {
    let robot = model.robot();
    let convention = match robot.convention {
        Convention::Standard => tr(model, Key::ConventionStandard),
        Convention::Modified => tr(model, Key::ConventionModified),
    };
    ui.label(trf(model, Key::ExerciseOwnTable, &[&convention]));
    // Columns as wide as their numbers (egui's default minimum is 40 points each), as in
    // the two conventions' tables: the five fit a projector's side column.
    egui::Grid::new("exercise_own_table")
        .striped(true)
        .min_col_width(0.0)
        .spacing([8.0, 2.0])
        .show(ui, |ui| {
            ui.label("#");
            let order = column_order(robot.convention);
            for &c in order.iter().take(4) {
                math::label(ui, header(robot.convention, c, true));
            }
            ui.end_row();
            for (i, joint) in robot.joints.iter().enumerate() {
                ui.label(format!("{}", i + 1));
                let dh = joint.dh;
                let values = [dh.theta.to_degrees(), dh.d, dh.a, dh.alpha.to_degrees()];
                for &c in order.iter().take(4) {
                    ui.monospace(number(values[c], 3));
                }
                ui.end_row();
            }
        });
}

/// Starting an exercise (folded, under the robot panel): a new mystery arm or a preset.
pub fn start_ui(model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
    let header = egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
        ui,
        tr(model, Key::ExerciseStart),
    ))
    .id_salt("exercise_start")
    .default_open(false)
    .show(ui, |ui| {
        ui.label(egui::RichText::new(tr(model, Key::ExerciseStartHint)).small());
        let mut chosen = None;
        crate::app::widgets::style::wrapped(ui, |ui| {
            let new = ui.button(tr(model, Key::ExerciseNewMystery));
            points.insert("exercise-new", new.rect.center());
            if new.clicked() {
                // A seed from the clock: each press a different arm (the core has no
                // clock; the app does).
                let seed = (crate::app::platform::clock::now_ms() * 1e3) as u64 % 1_000_000;
                chosen = Some(ExerciseId::Mystery(seed));
            }
            egui::ComboBox::from_id_salt("exercise_preset")
                .selected_text(tr(model, Key::ExercisePreset))
                .show_ui(ui, |ui| {
                    for (id, name) in preset_names() {
                        if ui.selectable_label(false, name.as_str()).clicked() {
                            chosen = Some(ExerciseId::Preset(id.to_string()));
                        }
                    }
                });
        });
        chosen
    });
    points.insert("exercise-header", header.header_response.rect.center());
    if let Some(id) = header.body_returned.flatten()
        && let Err(e) = model.start_exercise(id)
    {
        model.set_message(Message::error(e.sentence(model.settings().lang)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use armlab_core::{JointKind, preset};

    #[test]
    fn a_blank_answer_keeps_the_count_and_kinds_and_hides_every_length() {
        let scara = preset("scara").expect("a preset");
        let answer = blank_answer(&scara);
        assert_eq!(answer.rows.len(), 4);
        assert_eq!(answer.rows[2].kind, JointKind::Prismatic);
        assert!(
            answer
                .rows
                .iter()
                .all(|r| r.cells[..4].iter().all(|c| c == "0"))
        );
    }
}
