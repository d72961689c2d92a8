//! The app in the lecture room: what the lecturer's page sends (the state it shows), what
//! a student's page does with the server's messages (follow the lecturer, say why a join
//! was refused), and a link's `class=` part. The socket is the page's
//! (`crate::app::page`); the room's logic is [`crate::app::state::classroom`].

use armlab_room::{Answer, Question, Refusal, State};
use armlab_session::session::Session;
use armlab_session::settings::CameraPose;
use armlab_text::Key;

use crate::app::ArmLabApp;
use crate::app::state::classroom::{ClassLink, Classroom, Effect, Role};
use crate::app::state::model::{Message, Model};
use crate::app::state::tr;
use crate::app::view3d::predictions::Predictions;

/// The digits a camera keeps in the room's states (as a link writes it).
const CAMERA_DECIMALS: usize = 4;

impl ArmLabApp {
    /// The room's part of a frame, before the panels: the page's messages (in the page),
    /// the entries a student's page hides, the predictions the view draws.
    pub(crate) fn room_frame(&mut self, ctx: &egui::Context) {
        #[cfg(target_arch = "wasm32")]
        crate::app::page::pump_room(self, ctx);
        #[cfg(not(target_arch = "wasm32"))]
        let _ = ctx;
        self.class_panel.set_touch(self.touch);
        let student = matches!(self.classroom.role(), Role::Student { .. });
        self.model.set_room_hides(student);
        let predictions = self.room_predictions();
        self.viewport.set_predictions(predictions);
    }

    /// What the lecturer's page shows, as the students' pages follow it.
    pub fn room_state(&self) -> State {
        room_state(&self.model)
    }

    /// The lecturer's page, each frame: sends what it shows when it changed, at the
    /// room's pace ([`crate::app::state::classroom::SEND_INTERVAL_MS`]); how long until a
    /// waiting change may go (ms), if one waits.
    pub fn tick_room(&mut self, now_ms: f64) -> Option<f64> {
        let model = &self.model;
        self.classroom.tick(now_ms, || room_state(model))
    }

    /// Does what a server message asks of the app; `keep_token` keeps a lecturer's
    /// control token in the browser.
    pub fn apply_room_effect(&mut self, effect: Effect, keep_token: impl FnOnce(&str, &str)) {
        match effect {
            Effect::Follow(state) => follow_state(&self.classroom, &mut self.model, &state),
            Effect::Keep { code, token, new } => {
                keep_token(&code, &token);
                // A resumed class keeps the projector as it was.
                if new {
                    self.class_panel.show_join(true);
                }
            }
            Effect::Refused(reason) => {
                let text = tr(&self.model, refusal_key(reason));
                self.model.set_message(Message::warning(text));
            }
            Effect::Ended => {
                let text = tr(&self.model, Key::ClassEnded);
                self.model.set_message(Message::info(text));
            }
        }
    }

    /// Starts, joins or takes control of the class a link names (`class=`): the lecturer's
    /// token for `code`, if this browser keeps one, comes from `token`. Says so when the
    /// page did not come from a classroom server, or the code is not one.
    pub fn open_class_link(&mut self, link: ClassLink, token: impl FnOnce(&str) -> Option<String>) {
        if !self.classroom.available() {
            let text = tr(&self.model, Key::ClassNoServer);
            return self.model.set_message(Message::warning(text));
        }
        match link {
            ClassLink::New => self.classroom.start(),
            ClassLink::Join(code) => match token(&code) {
                Some(token) => self.classroom.resume(code, token),
                None => self.classroom.join(code, self.touch),
            },
            ClassLink::Control { code, token } => self.classroom.resume(code, token),
            ClassLink::Bad => {
                let text = tr(&self.model, Key::RefusedBadCode);
                self.model.set_message(Message::warning(text));
            }
        }
    }

    /// `window.armlab.classroom()`'s JSON: the role (`lecturer`, `student`, `none`), the
    /// code, the students connected, whether a student follows, whether the connection is
    /// open, and the open question's id, answers and whether its truth is out.
    pub fn classroom_json(&self) -> String {
        let room = &self.classroom;
        let role = match room.role() {
            Role::None => "none",
            Role::Lecturer { .. } => "lecturer",
            Role::Student { .. } => "student",
        };
        serde_json::json!({
            "role": role,
            "code": room.code(),
            "students": room.students(),
            "following": room.following(),
            "connected": room.connected(),
            "available": room.available(),
            "question": room.question().map(|q| q.id()),
            "answers": room.answers().len(),
            "revealed": room.truth().is_some(),
        })
        .to_string()
    }

    /// The room's predicted tool points in the robot's units, with the truth once
    /// revealed: empty unless the open question is a point question.
    pub fn room_predictions(&self) -> Predictions {
        let room = &self.classroom;
        if !matches!(room.question(), Some(Question::Point { .. })) {
            return Predictions::default();
        }
        let metres = self.model.robot().length_unit.in_metres();
        let point = |answer: &Answer| match answer {
            Answer::Point { at } => Some(at.map(|v| v / metres)),
            _ => None,
        };
        Predictions {
            points: room.answers().iter().filter_map(point).collect(),
            truth: room.truth().as_ref().and_then(point),
        }
    }

    /// The link as the address bar shows it: in a class, its code first, so that a reload
    /// comes back into the class.
    pub fn link_in_room(&self) -> String {
        match self.classroom.code() {
            Some(code) => format!("class={code}&{}", self.hash()),
            None => self.hash(),
        }
    }
}

/// What a lecturer's `model` shows, as the students' pages follow it: its link without
/// the camera, and the camera apart (a student may keep their own view).
fn room_state(model: &Model) -> State {
    let mut session = model.session();
    let camera = (session.camera.take())
        .map(|c| armlab_session::format::number_list(&c.to_array(), CAMERA_DECIMALS));
    State {
        link: session.to_hash(),
        camera,
    }
}

/// Shows the lecturer's state on a student's page, with the lecturer's camera when the
/// student follows it. A state that does not read is skipped: the next one replaces it.
pub(crate) fn follow_state(room: &Classroom, model: &mut Model, state: &State) {
    let Ok(Some(mut session)) = Session::from_hash(&state.link) else {
        return;
    };
    session.camera = None;
    if room.follows_camera() {
        session.camera = state.camera.as_deref().and_then(camera_from_text);
    }
    model.follow(session);
}

/// A camera as a room state carries it: yaw, pitch, distance and focus, comma-separated.
fn camera_from_text(text: &str) -> Option<CameraPose> {
    let numbers: Vec<f64> = text
        .split(',')
        .map(|n| n.parse().ok())
        .collect::<Option<_>>()?;
    CameraPose::from_array(numbers.try_into().ok()?)
}

/// The sentence of a refusal.
fn refusal_key(reason: Refusal) -> Key {
    match reason {
        Refusal::UnknownCode => Key::RefusedUnknownCode,
        Refusal::BadCode => Key::RefusedBadCode,
        Refusal::WrongToken => Key::RefusedWrongToken,
        Refusal::CodeTaken => Key::RefusedCodeTaken,
        Refusal::TooManyAttempts => Key::RefusedTooManyAttempts,
        Refusal::Full => Key::RefusedFull,
        Refusal::AlreadyInClass => Key::RefusedAlreadyInClass,
    }
}
