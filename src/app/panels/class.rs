//! The lecture room's bar (under the top bar, on a page from a classroom server) and its
//! windows: the join link and code for the projector, and the question to the room with
//! its answers. The room's state is [`Classroom`]; this draws it and turns clicks into
//! its calls.

use armlab_room::Question;
use armlab_text::Key;

use crate::app::panels::joints;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::classroom::{Classroom, Role, shown_code};
use crate::app::state::model::Model;
use crate::app::state::{tr, trf};
use crate::app::widgets::style;

/// A question the lecturer can ask: what its truth is read from when revealed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Asked {
    /// Where the tool is (a point).
    Tool,
    /// One coordinate of the tool's position (0 = x).
    ToolAxis(usize),
    /// One joint's value (from 0).
    Joint(usize),
    /// det J (six joints).
    Det,
    /// Whether the target is reached.
    Reachable,
    /// Which joint is at a limit (0 = none).
    AtLimit,
}

/// The room's bar and windows, with what they remember between frames.
#[derive(Debug, Default)]
pub struct ClassPanel {
    /// The code typed to join.
    code: String,
    /// The join window is open (the lecturer's).
    join_open: bool,
    /// The number typed as an answer.
    number: String,
    /// What the open question asked (the lecturer's).
    asked: Option<Asked>,
    /// The question whose window was closed.
    closed: Option<u32>,
    /// The device is a touch screen: a student joining follows the camera.
    touch: bool,
}

impl ClassPanel {
    /// Notes whether the device is a touch screen (a phone or tablet follows the
    /// lecturer's camera by default).
    pub fn set_touch(&mut self, touch: bool) {
        self.touch = touch;
    }

    /// Opens or closes the join window.
    pub fn show_join(&mut self, open: bool) {
        self.join_open = open;
    }

    /// The bar: start or join a class, or the class this page is in.
    pub fn bar(
        &mut self,
        room: &mut Classroom,
        model: &mut Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
    ) {
        if !room.available() {
            return;
        }
        style::wrapped(ui, |ui| match room.role().clone() {
            Role::None => self.outside(room, model, ui, points),
            Role::Lecturer { code, .. } => self.lecturer_bar(room, model, ui, &code, points),
            Role::Student { code } => student_bar(room, model, ui, &code, points),
        });
    }

    /// Not in a class: start one, or type a code and join.
    fn outside(
        &mut self,
        room: &mut Classroom,
        model: &mut Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
    ) {
        let start = ui
            .button(tr(model, Key::StartClass))
            .on_hover_text(tr(model, Key::StartClassHint));
        points.insert("class-start", start.rect.center());
        if start.clicked() {
            room.start();
        }
        ui.separator();
        ui.label(tr(model, Key::JoinClass));
        let field = ui.add(
            egui::TextEdit::singleline(&mut self.code)
                .hint_text(tr(model, Key::JoinCode))
                .desired_width(110.0),
        );
        points.insert("class-code", field.rect.center());
        let typed = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        let join = ui.button(tr(model, Key::Join));
        points.insert("class-join", join.rect.center());
        if typed || join.clicked() {
            match armlab_room::normalize_code(&self.code) {
                Some(code) => room.join(code, self.touch),
                None => model.set_message(crate::app::state::model::Message::warning(tr(
                    model,
                    Key::RefusedBadCode,
                ))),
            }
        }
    }

    /// The lecturer's bar: the code, the students, the join link, a question, the end.
    fn lecturer_bar(
        &mut self,
        room: &mut Classroom,
        model: &mut Model,
        ui: &mut egui::Ui,
        code: &str,
        points: &mut ScreenPoints,
    ) {
        title(room, model, ui, code);
        ui.label(trf(model, Key::ClassStudents, &[&room.students()]));
        let join = crate::app::widgets::style::switch(
            ui,
            &mut self.join_open,
            tr(model, Key::ClassJoinDetails),
        );
        points.insert("class-join-link", join.rect.center());
        let ask = ui.menu_button(tr(model, Key::AskRoom), |ui| {
            if let Some((asked, question)) = ask_menu(model, ui, points) {
                self.asked = Some(asked);
                self.closed = None;
                room.ask(question);
                ui.close();
            }
        });
        points.insert("class-ask", ask.response.rect.center());
        let end = ui.button(tr(model, Key::ClassEnd));
        points.insert("class-end", end.rect.center());
        if end.clicked() {
            room.end();
        }
    }

    /// The windows: the join link (the lecturer's) and the open question.
    pub fn windows(
        &mut self,
        room: &mut Classroom,
        model: &mut Model,
        ctx: &egui::Context,
        points: &mut ScreenPoints,
    ) {
        if let Role::Lecturer { code, .. } = room.role().clone()
            && self.join_open
        {
            self.join_window(model, ctx, &code);
        }
        let Some(question) = room.question().cloned() else {
            return;
        };
        if self.closed == Some(question.id()) {
            return;
        }
        let mut open = true;
        // Above the narrow layout's tab bar on a phone.
        let lift = if ctx.content_rect().width() < 600.0 {
            64.0
        } else {
            12.0
        };
        let anchor = (egui::Align2::CENTER_BOTTOM, egui::vec2(0.0, -lift));
        let title = [tr(model, Key::AskRoom), tr(model, Key::RoomClose)];
        card(ctx, "class-question", anchor, title, &mut open, |ui| {
            ui.label(egui::RichText::new(prompt(&question)).strong());
            match room.role() {
                Role::Lecturer { .. } => self.results(room, model, ui, &question, points),
                _ => self.answering(room, model, ui, &question, points),
            }
        });
        if !open {
            self.closed = Some(question.id());
        }
    }

    /// The join window: the code in large letters, the link and its QR code.
    fn join_window(&mut self, model: &Model, ctx: &egui::Context, code: &str) {
        let link = crate::app::platform::share_link(&format!("class={code}"));
        let mut open = self.join_open;
        let anchor = (egui::Align2::CENTER_CENTER, egui::Vec2::ZERO);
        let title = [tr(model, Key::ClassJoinDetails), tr(model, Key::RoomClose)];
        card(ctx, "class-join", anchor, title, &mut open, |ui| {
            let page = link.split('#').next().unwrap_or_default();
            ui.label(trf(model, Key::ClassJoinAt, &[&page]));
            ui.label(egui::RichText::new(shown_code(code)).size(56.0).strong());
            ui.label(egui::RichText::new(&link).monospace());
            crate::app::widgets::qr::show(ui, &link);
        });
        self.join_open = open;
    }
}

/// A card over the view at `anchor` (an alignment and offset), with its title and a close
/// button (`close` its word) that clears `open`: a window without egui's window machinery (moving,
/// resizing, collapsing), which the page would otherwise carry for these two alone.
fn card(
    ctx: &egui::Context,
    id: &str,
    anchor: (egui::Align2, egui::Vec2),
    [title, close]: [&str; 2],
    open: &mut bool,
    add: impl FnOnce(&mut egui::Ui),
) {
    egui::Area::new(egui::Id::unique(id))
        .anchor(anchor.0, anchor.1)
        .order(egui::Order::Foreground)
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.horizontal(|ui| {
                    ui.strong(title);
                    if ui.small_button(close).clicked() {
                        *open = false;
                    }
                });
                add(ui);
            });
        });
}

/// The class's code, and "Connecting…" while the connection is down.
fn title(room: &Classroom, model: &Model, ui: &mut egui::Ui, code: &str) {
    ui.label(egui::RichText::new(trf(model, Key::ClassTitle, &[&shown_code(code)])).strong());
    if !room.connected() {
        ui.colored_label(style::WARNING, tr(model, Key::ClassConnecting));
    }
}

/// A student's bar: the class, following or not, the camera, leaving.
fn student_bar(
    room: &mut Classroom,
    model: &mut Model,
    ui: &mut egui::Ui,
    code: &str,
    points: &mut ScreenPoints,
) {
    title(room, model, ui, code);
    if room.following() {
        ui.label(tr(model, Key::ClassFollowing));
        let explore = ui.button(tr(model, Key::ClassExplore));
        points.insert("class-explore", explore.rect.center());
        if explore.clicked() {
            room.explore();
        }
    } else {
        ui.label(tr(model, Key::ClassOwn));
        let again = ui.button(tr(model, Key::ClassFollowAgain));
        points.insert("class-follow", again.rect.center());
        if again.clicked()
            && let Some(state) = room.follow_again()
        {
            crate::app::room::follow_state(room, model, &state);
        }
    }
    let mut camera = room.follows_camera();
    if ui
        .checkbox(&mut camera, tr(model, Key::ClassFollowCamera))
        .changed()
    {
        room.set_follow_camera(camera);
    }
    if ui.button(tr(model, Key::ClassLeave)).clicked() {
        room.leave();
    }
}

/// The menu of questions; the one chosen, with what its truth is read from.
fn ask_menu(
    model: &Model,
    ui: &mut egui::Ui,
    points: &mut ScreenPoints,
) -> Option<(Asked, Question)> {
    let unit = model.robot().length_unit.symbol().to_string();
    let mut asks: Vec<(Asked, Question)> = vec![(
        Asked::Tool,
        Question::Point {
            id: 0,
            prompt: tr(model, Key::AskPoint).into(),
        },
    )];
    for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
        let prompt = trf(model, Key::AskToolCoordinate, &[&name]);
        asks.push((Asked::ToolAxis(axis), number(prompt, &unit)));
    }
    for (i, joint) in model.robot().joints.iter().enumerate() {
        let (_, suffix, _) = joints::shown(model, joint);
        let symbol = crate::app::widgets::math::joint_symbol(i, joint.kind);
        let prompt = trf(model, Key::AskJoint, &[&symbol]);
        asks.push((Asked::Joint(i), number(prompt, suffix.trim())));
    }
    if model.robot().dof() == 6 {
        asks.push((Asked::Det, number(tr(model, Key::AskDet).into(), "")));
    }
    let yes_no = vec![tr(model, Key::Yes).into(), tr(model, Key::No).into()];
    asks.push((
        Asked::Reachable,
        choice(tr(model, Key::AskReachable), yes_no),
    ));
    let limits = std::iter::once(tr(model, Key::NoJoint).to_string())
        .chain((1..=model.robot().dof()).map(|i| i.to_string()))
        .collect();
    asks.push((Asked::AtLimit, choice(tr(model, Key::AskAtLimit), limits)));
    let mut chosen = None;
    for (index, (asked, question)) in asks.into_iter().enumerate() {
        let item = ui.button(prompt(&question));
        points.insert(format!("class-ask-{index}"), item.rect.center());
        if item.clicked() {
            chosen = Some((asked, question));
        }
    }
    chosen
}

/// A number question.
fn number(prompt: String, unit: &str) -> Question {
    Question::Number {
        id: 0,
        prompt,
        unit: (!unit.is_empty()).then(|| unit.to_string()),
    }
}

/// A choice question (at most [`armlab_room::MAX_OPTIONS`] options: a longer arm's
/// later joints are left out).
fn choice(prompt: &str, mut options: Vec<String>) -> Question {
    options.truncate(armlab_room::MAX_OPTIONS);
    Question::Choice {
        id: 0,
        prompt: prompt.into(),
        options,
    }
}

/// A question's prompt.
fn prompt(question: &Question) -> &str {
    match question {
        Question::Point { prompt, .. }
        | Question::Number { prompt, .. }
        | Question::Choice { prompt, .. } => prompt,
    }
}

#[path = "class_answers.rs"]
mod answers;
