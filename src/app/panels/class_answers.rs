//! The question's window: the lecturer's live answers (a histogram of numbers, bars of
//! choices, the predicted points' mean and spread) with Reveal, and a student's answer.

use armlab_core::Reach;
use armlab_room::{Answer, Question};
use armlab_text::Key;

use super::{Asked, ClassPanel};
use crate::app::screen_points::ScreenPoints;
use crate::app::state::classroom::{Classroom, Role, mean_and_spread};
use crate::app::state::model::Model;
use crate::app::state::{tr, trf};
use crate::app::widgets::style;

/// The bins of a number question's histogram.
const BINS: usize = 8;
/// How near a joint's limit counts as at it (radians or length units).
const AT_LIMIT: f64 = 1e-6;

impl ClassPanel {
    /// The lecturer's side: the count, the answers so far, Reveal, the CSV.
    pub(super) fn results(
        &mut self,
        room: &mut Classroom,
        model: &Model,
        ui: &mut egui::Ui,
        question: &Question,
        points: &mut ScreenPoints,
    ) {
        let answers = room.answers().to_vec();
        let count = ui.label(trf(model, Key::RoomAnswers, &[&answers.len()]));
        points.insert("class-answers", count.rect.center());
        chart(model, ui, question, &answers, room.truth());
        match (room.truth(), self.asked) {
            (Some(truth), _) => {
                ui.label(trf(
                    model,
                    Key::RoomTruth,
                    &[&shown(model, question, truth)],
                ));
            }
            (None, Some(asked)) => {
                let reveal = ui.button(tr(model, Key::RoomReveal));
                points.insert("class-reveal", reveal.rect.center());
                if reveal.clicked() {
                    room.reveal(truth(asked, model));
                }
            }
            (None, None) => {}
        }
        if let Role::Lecturer { code, token } = room.role() {
            let csv = format!("classroom/{code}/answers.csv?token={token}");
            ui.hyperlink_to(tr(model, Key::RoomCsv), csv);
        }
    }

    /// A student's side: the answer controls until the truth is revealed, then the truth
    /// beside the room's answers.
    pub(super) fn answering(
        &mut self,
        room: &mut Classroom,
        model: &Model,
        ui: &mut egui::Ui,
        question: &Question,
        points: &mut ScreenPoints,
    ) {
        if let Some(truth) = room.truth() {
            ui.label(trf(
                model,
                Key::RoomTruth,
                &[&shown(model, question, truth)],
            ));
            chart(model, ui, question, room.answers(), Some(truth));
        } else {
            let answer = match question {
                Question::Point { .. } => {
                    let send = ui.button(tr(model, Key::RoomSendTarget));
                    points.insert("class-send-target", send.rect.center());
                    send.clicked().then(|| tool_point(model, model.target()))
                }
                Question::Number { unit, .. } => self.number_field(model, ui, unit, points),
                Question::Choice { options, .. } => choice_buttons(room, ui, options, points),
            };
            if let Some(answer) = answer {
                room.answer(answer);
            }
        }
        if let Some(mine) = room.my_answer() {
            ui.label(trf(model, Key::RoomYours, &[&shown(model, question, mine)]));
        }
    }

    /// A number's field and its Answer button; the number once sent.
    fn number_field(
        &mut self,
        model: &Model,
        ui: &mut egui::Ui,
        unit: &Option<String>,
        points: &mut ScreenPoints,
    ) -> Option<Answer> {
        ui.horizontal(|ui| {
            let field = ui.add(egui::TextEdit::singleline(&mut self.number).desired_width(100.0));
            points.insert("class-number", field.rect.center());
            if let Some(unit) = unit {
                ui.label(unit);
            }
            let typed = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            let send = ui.button(tr(model, Key::RoomSend));
            points.insert("class-send", send.rect.center());
            let value = self.number.trim().replace(',', ".").replace('−', "-");
            let value = value.parse::<f64>().ok().filter(|v| v.is_finite());
            value
                .filter(|_| typed || send.clicked())
                .map(|value| Answer::Number { value })
        })
        .inner
    }
}

/// One button per option; the option clicked.
fn choice_buttons(
    room: &Classroom,
    ui: &mut egui::Ui,
    options: &[String],
    points: &mut ScreenPoints,
) -> Option<Answer> {
    let mut chosen = None;
    ui.horizontal_wrapped(|ui| {
        for (index, option) in (0u32..).zip(options) {
            let mine = room.my_answer() == Some(Answer::Choice { index });
            let button = ui.add(crate::app::widgets::style::choice(mine, option));
            points.insert(format!("class-option-{index}"), button.rect.center());
            if button.clicked() {
                chosen = Some(Answer::Choice { index });
            }
        }
    });
    chosen
}

/// The answers drawn by the question's kind, the truth marked once revealed.
fn chart(
    model: &Model,
    ui: &mut egui::Ui,
    question: &Question,
    answers: &[Answer],
    truth: Option<Answer>,
) {
    match question {
        Question::Number { .. } => {
            let values: Vec<f64> = answers.iter().filter_map(number_of).collect();
            histogram(model, ui, &values, truth.as_ref().and_then(number_of));
        }
        Question::Choice { options, .. } => {
            let mut counts = vec![0usize; options.len()];
            for answer in answers {
                if let Answer::Choice { index } = answer
                    && let Some(c) = counts.get_mut(*index as usize)
                {
                    *c += 1;
                }
            }
            let right = match truth {
                Some(Answer::Choice { index }) => Some(index as usize),
                _ => None,
            };
            bars(ui, options, &counts, right);
        }
        Question::Point { .. } => {
            let at: Vec<[f64; 3]> = answers
                .iter()
                .filter_map(|a| match a {
                    Answer::Point { at } => Some(*at),
                    _ => None,
                })
                .collect();
            if let Some((mean, spread)) = mean_and_spread(&at) {
                let mean = point_text(mean);
                let spread = format!("{} m", armlab_session::format::number(spread, 3));
                ui.label(trf(model, Key::RoomSpread, &[&mean, &spread]));
            }
        }
    }
}

/// A number answer's value.
fn number_of(answer: &Answer) -> Option<f64> {
    match answer {
        Answer::Number { value } => Some(*value),
        _ => None,
    }
}

/// A histogram of `values` in [`BINS`] bins between the smallest and largest (the truth
/// included), the truth a line, the ends written under it.
fn histogram(model: &Model, ui: &mut egui::Ui, values: &[f64], truth: Option<f64>) {
    let all = values.iter().chain(&truth);
    let lo = all.clone().copied().fold(f64::INFINITY, f64::min);
    let hi = all.copied().fold(f64::NEG_INFINITY, f64::max);
    if !lo.is_finite() {
        return;
    }
    let (lo, hi) = if hi - lo > 1e-12 {
        (lo, hi)
    } else {
        (lo - 1.0, hi + 1.0)
    };
    let counts = bin_counts(values, lo, hi);
    let most = counts.iter().copied().max().unwrap_or(1).max(1) as f32;
    let (rect, _) = ui.allocate_exact_size(egui::vec2(280.0, 90.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let width = rect.width() / BINS as f32;
    for (i, &count) in counts.iter().enumerate() {
        let height = rect.height() * count as f32 / most;
        let left = rect.left() + i as f32 * width;
        let bar = egui::Rect::from_min_max(
            egui::pos2(left + 1.0, rect.bottom() - height),
            egui::pos2(left + width - 1.0, rect.bottom()),
        );
        painter.rect_filled(bar, 2.0, style::INFO);
    }
    if let Some(truth) = truth {
        let x = rect.left() + rect.width() * ((truth - lo) / (hi - lo)) as f32;
        painter.vline(x, rect.y_range(), egui::Stroke::new(3.0, style::REACHED));
    }
    let decimals = model.settings().precision;
    ui.horizontal(|ui| {
        ui.label(armlab_session::format::number(lo, decimals));
        ui.add_space(160.0);
        ui.label(armlab_session::format::number(hi, decimals));
    });
}

/// How many of `values` fall in each of [`BINS`] equal bins from `lo` to `hi` (the last
/// bin holds `hi`).
pub fn bin_counts(values: &[f64], lo: f64, hi: f64) -> [usize; BINS] {
    let mut counts = [0; BINS];
    for v in values {
        let at = ((v - lo) / (hi - lo) * BINS as f64).floor();
        if at.is_finite() && at >= 0.0 {
            counts[(at as usize).min(BINS - 1)] += 1;
        }
    }
    counts
}

/// One bar per option, its count beside it; the right option's bar in the reached colour
/// and its name marked ✓.
fn bars(ui: &mut egui::Ui, options: &[String], counts: &[usize], right: Option<usize>) {
    let most = counts.iter().copied().max().unwrap_or(1).max(1) as f32;
    egui::Grid::new("class-bars").show(ui, |ui| {
        for (i, (option, &count)) in options.iter().zip(counts).enumerate() {
            let is_right = right == Some(i);
            ui.label(if is_right {
                format!("✓ {option}")
            } else {
                option.clone()
            });
            let (rect, _) = ui.allocate_exact_size(egui::vec2(180.0, 16.0), egui::Sense::hover());
            let bar = egui::Rect::from_min_size(
                rect.min,
                egui::vec2(rect.width() * count as f32 / most, rect.height()),
            );
            let colour = if is_right {
                style::REACHED
            } else {
                style::INFO
            };
            ui.painter().rect_filled(bar, 2.0, colour);
            ui.label(count.to_string());
            ui.end_row();
        }
    });
}

/// A point in metres as text.
fn point_text(at: [f64; 3]) -> String {
    let [x, y, z] = at.map(|v| armlab_session::format::number(v, 3));
    format!("({x}, {y}, {z}) m")
}

/// An answer as the question shows it: a point in metres, a number with the question's
/// unit, a choice's option.
fn shown(model: &Model, question: &Question, answer: Answer) -> String {
    match (question, answer) {
        (_, Answer::Point { at }) => point_text(at),
        (Question::Number { unit, .. }, Answer::Number { value }) => {
            let number = armlab_session::format::number(value, model.settings().precision);
            format!("{number} {}", unit.as_deref().unwrap_or_default())
                .trim_end()
                .to_string()
        }
        (Question::Choice { options, .. }, Answer::Choice { index }) => {
            options.get(index as usize).cloned().unwrap_or_default()
        }
        (_, Answer::Number { value }) => value.to_string(),
        (_, Answer::Choice { index }) => index.to_string(),
    }
}

/// A pose's position in metres, as a point answer.
fn tool_point(model: &Model, pose: &nalgebra::IsometryMatrix3<f64>) -> Answer {
    let metres = model.robot().length_unit.in_metres();
    let p = pose.translation.vector * metres;
    Answer::Point {
        at: [p.x, p.y, p.z],
    }
}

/// The truth of what was asked, read from the lecturer's page as it is now.
pub fn truth(asked: Asked, model: &Model) -> Answer {
    let tool = &model.fk().base_from_tool;
    match asked {
        Asked::Tool => tool_point(model, tool),
        Asked::ToolAxis(axis) => Answer::Number {
            value: tool.translation.vector[axis.min(2)],
        },
        Asked::Joint(i) => {
            let value = match model.robot().joints.get(i) {
                Some(joint) => model.q()[i] * super::joints::shown(model, joint).0,
                None => 0.0,
            };
            Answer::Number { value }
        }
        Asked::Det => {
            let j = model.jacobian();
            let square = nalgebra::Matrix6::from_iterator(j.iter().copied());
            Answer::Number {
                value: square.determinant(),
            }
        }
        Asked::Reachable => Answer::Choice {
            index: u32::from(model.shown_reach() != Reach::Reached),
        },
        Asked::AtLimit => {
            let at_limit = (model.robot().joints.iter().zip(model.q()))
                .position(|(joint, &q)| {
                    q - joint.limits.min < AT_LIMIT || joint.limits.max - q < AT_LIMIT
                })
                .map_or(0, |i| (i + 1).min(armlab_room::MAX_OPTIONS - 1));
            Answer::Choice {
                index: at_limit as u32,
            }
        }
    }
}
