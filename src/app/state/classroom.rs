//! The lecture room as this page takes part in it: its role (none, the lecturer, a
//! student), what the server said last (the students connected, the lecturer's latest
//! state, the open question and its answers) and what the page has to send. No socket and
//! no clock here: the page's platform code carries the messages and passes the time in, so
//! the room's logic is tested natively without a server.
//!
//! The lecturer's page sends what it shows as a [`State`] at most every
//! [`SEND_INTERVAL_MS`], and only when it changed: during a drag the students get the
//! latest state about twenty times a second, and a state that a later one replaced before
//! its turn is never sent. A student's page follows the states it receives until the
//! student chooses to explore; "Follow again" applies the latest one.

use armlab_room::{Answer, ClientMessage, Question, Refusal, ServerMessage, State};
use armlab_room::{is_token, normalize_code};

/// The shortest time between two states the lecturer's page sends (about 20 a second).
pub const SEND_INTERVAL_MS: f64 = 50.0;
/// How long a student who was in the class waits before asking to join again when the
/// server does not know it (restarted, and the lecturer's page has not re-created it yet).
pub const REJOIN_MS: f64 = 1500.0;

/// What this page is in the room.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Role {
    /// Not in a class.
    #[default]
    None,
    /// The lecturer's page: it drives. `token` is the control the server gave.
    Lecturer {
        /// The class's join code.
        code: String,
        /// The control token (kept in the browser's storage).
        token: String,
    },
    /// A student's page.
    Student {
        /// The class's join code.
        code: String,
    },
}

/// What a message from the server asks of the app.
#[derive(Clone, Debug, PartialEq)]
pub enum Effect {
    /// Show the lecturer's state (a following student's page).
    Follow(State),
    /// The class exists: keep `token` for `code` (the lecturer's page).
    Keep {
        /// The join code.
        code: String,
        /// The control token.
        token: String,
        /// A class just started (not one resumed after a reload or a reconnection).
        new: bool,
    },
    /// The server refused to create, resume or join (the page says why).
    Refused(Refusal),
    /// The lecturer ended the class.
    Ended,
}

/// The room's state on this page.
#[derive(Debug, Default)]
pub struct Classroom {
    /// The page came from a classroom server (it answered its greeting).
    available: bool,
    role: Role,
    /// Counts the classes this page started, resumed, joined or left: a new one needs a
    /// new connection (the server knows a connection as one role in one class).
    generation: u32,
    /// The lecturer asked for a new class and waits for its code.
    creating: bool,
    connected: bool,
    students: u32,
    /// A student's page shows the lecturer's state.
    following: bool,
    /// A following student's page takes the lecturer's camera too.
    follow_camera: bool,
    /// The lecturer's latest state, as a student received it.
    latest: Option<State>,
    question: Option<Question>,
    /// The answers so far (the lecturer's page), or all of them once revealed.
    answers: Vec<Answer>,
    truth: Option<Answer>,
    /// This student's answer to the open question.
    mine: Option<Answer>,
    /// A point question took this student off the lecturer's state to drag the target:
    /// the reveal (or the next question) brings them back.
    predicting: bool,
    /// This student's page was in the class on this connection or an earlier one.
    joined: bool,
    /// A join was refused for a class this student was in: when to ask again (ms; `None`
    /// until the next tick sets it).
    rejoin: Option<Option<f64>>,
    /// The last state sent and when (ms).
    sent: Option<(State, f64)>,
    outbox: Vec<ClientMessage>,
    next_question: u32,
}

impl Classroom {
    /// Notes that the page came from a classroom server (or not).
    pub fn set_available(&mut self, available: bool) {
        self.available = available;
    }

    /// Whether the page came from a classroom server: only then can it start or join a
    /// class.
    pub fn available(&self) -> bool {
        self.available
    }

    /// The page's role.
    pub fn role(&self) -> &Role {
        &self.role
    }

    /// Changes with every class this page starts, resumes, joins or leaves: the platform
    /// opens a new connection for each.
    pub fn generation(&self) -> u32 {
        self.generation
    }

    /// The join code of the class this page is in (or creates).
    pub fn code(&self) -> Option<&str> {
        match self.role() {
            Role::None => None,
            Role::Lecturer { code, .. } | Role::Student { code } => Some(code),
        }
    }

    /// Whether the page wants its connection to the server: in a class, or creating one.
    pub fn wants_connection(&self) -> bool {
        self.creating || *self.role() != Role::None
    }

    /// Whether the connection is open.
    pub fn connected(&self) -> bool {
        self.connected
    }

    /// The students connected, as the server last counted them (the lecturer's page).
    pub fn students(&self) -> u32 {
        self.students
    }

    /// Whether this student's page follows the lecturer.
    pub fn following(&self) -> bool {
        self.following
    }

    /// Whether a following student's page takes the lecturer's camera too.
    pub fn follows_camera(&self) -> bool {
        self.follow_camera
    }

    /// Takes the lecturer's camera when following (or keeps the student's own).
    pub fn set_follow_camera(&mut self, on: bool) {
        self.follow_camera = on;
    }

    /// The open question, if any.
    pub fn question(&self) -> Option<&Question> {
        self.question.as_ref()
    }

    /// The answers the page knows of the open question.
    pub fn answers(&self) -> &[Answer] {
        &self.answers
    }

    /// The truth, once revealed.
    pub fn truth(&self) -> Option<Answer> {
        self.truth
    }

    /// This student's answer to the open question.
    pub fn my_answer(&self) -> Option<Answer> {
        self.mine
    }

    /// The messages to send, oldest first (the platform sends them while connected).
    pub fn take_outbox(&mut self) -> Vec<ClientMessage> {
        if self.connected {
            std::mem::take(&mut self.outbox)
        } else {
            Vec::new()
        }
    }

    /// Starts a new class: the page becomes its lecturer once the server answers.
    pub fn start(&mut self) {
        self.leave();
        self.creating = true;
        self.outbox.push(ClientMessage::Create {});
    }

    /// Takes control of class `code` with `token` (a reload or the lecturer's second
    /// device: the token came from the browser's storage or a remote link).
    pub fn resume(&mut self, code: String, token: String) {
        self.leave();
        self.role = Role::Lecturer { code, token };
    }

    /// Joins class `code` as a student, following the lecturer.
    pub fn join(&mut self, code: String, follow_camera: bool) {
        self.leave();
        self.role = Role::Student { code };
        self.following = true;
        self.follow_camera = follow_camera;
    }

    /// Leaves the class (a student) or forgets it (nothing is sent: the connection
    /// closes).
    pub fn leave(&mut self) {
        *self = Classroom {
            available: self.available,
            next_question: self.next_question,
            generation: self.generation.wrapping_add(1),
            ..Classroom::default()
        };
    }

    /// Ends the class for everyone (the lecturer).
    pub fn end(&mut self) {
        if matches!(self.role(), Role::Lecturer { .. }) {
            self.outbox.push(ClientMessage::End {});
        }
    }

    /// The connection opened (again): says who this page is; a lecturer's page re-creates
    /// its class with what it shows now (`state`), so a restarted server has it again.
    pub fn on_open(&mut self, state: State) {
        self.connected = true;
        let hello = match self.role().clone() {
            Role::Lecturer { code, token } => ClientMessage::Resume { code, token, state },
            Role::Student { code } => ClientMessage::Join {
                code,
                nickname: None,
            },
            Role::None if self.creating => ClientMessage::Create {},
            Role::None => return,
        };
        self.sent = None;
        self.outbox.retain(|m| !is_hello(m));
        self.outbox.insert(0, hello);
    }

    /// The connection closed (the platform reconnects while the page wants it).
    pub fn on_close(&mut self) {
        self.connected = false;
    }

    /// Explores on the student's own: the lecturer's states are kept but not shown.
    pub fn explore(&mut self) {
        self.following = false;
        self.predicting = false;
    }

    /// Follows the lecturer again: the latest state to show, if one came.
    pub fn follow_again(&mut self) -> Option<State> {
        self.following = true;
        self.predicting = false;
        self.latest.clone()
    }

    /// The lecturer's page, each frame: sends `state()` when it changed and the last send
    /// is at least [`SEND_INTERVAL_MS`] old at `now_ms`. Returns how long to wait before a
    /// changed state may go (the page asks for a frame then), if one waits.
    pub fn tick(&mut self, now_ms: f64, state: impl FnOnce() -> State) -> Option<f64> {
        if !self.connected {
            return None;
        }
        if let Some(at) = self.rejoin {
            return self.rejoin_at(now_ms, at);
        }
        if !matches!(self.role(), Role::Lecturer { .. }) {
            return None;
        }
        if let Some((_, at)) = &self.sent {
            let wait = SEND_INTERVAL_MS - (now_ms - at);
            if wait > 0.0 {
                return Some(wait);
            }
        }
        let state = state();
        if self.sent.as_ref().is_some_and(|(last, _)| *last == state) {
            return None;
        }
        self.outbox.push(ClientMessage::State {
            state: state.clone(),
        });
        self.sent = Some((state, now_ms));
        None
    }

    /// A student's page waiting to join again: asks at `at` (set [`REJOIN_MS`] after the
    /// refusal's first tick); how long until then.
    fn rejoin_at(&mut self, now_ms: f64, at: Option<f64>) -> Option<f64> {
        let at = at.unwrap_or(now_ms + REJOIN_MS);
        if now_ms < at {
            self.rejoin = Some(Some(at));
            return Some(at - now_ms);
        }
        self.rejoin = None;
        if let Role::Student { code } = self.role() {
            let code = code.clone();
            self.outbox.push(ClientMessage::Join {
                code,
                nickname: None,
            });
        }
        None
    }

    /// Asks the room `question` (the lecturer); its id is set here.
    pub fn ask(&mut self, mut question: Question) {
        self.next_question += 1;
        let id = self.next_question;
        match &mut question {
            Question::Point { id: q, .. }
            | Question::Number { id: q, .. }
            | Question::Choice { id: q, .. } => *q = id,
        }
        self.answers.clear();
        self.truth = None;
        self.question = Some(question.clone());
        self.outbox.push(ClientMessage::Ask { question });
    }

    /// Shows the truth beside the answers (the lecturer).
    pub fn reveal(&mut self, truth: Answer) {
        if let Some(question) = &self.question {
            self.outbox.push(ClientMessage::Reveal {
                question: question.id(),
                truth,
            });
        }
    }

    /// Answers the open question (a student; the last answer counts).
    pub fn answer(&mut self, value: Answer) {
        let Some(question) = &self.question else {
            return;
        };
        if self.truth.is_none() && question.fits(&value) {
            self.mine = Some(value);
            self.outbox.push(ClientMessage::Answer {
                question: question.id(),
                value,
            });
        }
    }

    /// Takes a message from the server; returns what it asks of the app.
    pub fn receive(&mut self, message: ServerMessage) -> Option<Effect> {
        match message {
            ServerMessage::Created { code, token } => {
                let new = std::mem::take(&mut self.creating);
                self.role = Role::Lecturer {
                    code: code.clone(),
                    token: token.clone(),
                };
                return Some(Effect::Keep { code, token, new });
            }
            ServerMessage::Joined { state, question } => {
                self.joined = true;
                self.rejoin = None;
                if let Some(state) = state {
                    self.latest = Some(state);
                }
                return match question {
                    Some(question) => self.open_question(question),
                    None => self.latest.clone().and_then(|s| self.lecturer_state(s)),
                };
            }
            ServerMessage::State { state } => return self.lecturer_state(state),
            // A restarted server knows the class again once the lecturer's page is back.
            ServerMessage::Refused {
                reason: Refusal::UnknownCode,
            } if self.joined => self.rejoin = Some(None),
            ServerMessage::Refused { reason } => {
                self.leave();
                return Some(Effect::Refused(reason));
            }
            ServerMessage::Count { students } => self.students = students,
            ServerMessage::Question { question } => return self.open_question(question),
            ServerMessage::Answers {
                question, values, ..
            } => {
                if self.question.as_ref().is_some_and(|q| q.id() == question) {
                    self.answers = values;
                }
            }
            ServerMessage::Revealed {
                question,
                truth,
                values,
            } => {
                if self.question.as_ref().is_some_and(|q| q.id() == question) {
                    self.truth = Some(truth);
                    self.answers = values;
                    return self.end_prediction();
                }
            }
            ServerMessage::Ended {} => {
                self.leave();
                return Some(Effect::Ended);
            }
            ServerMessage::Dropped { .. } => {}
        }
        None
    }

    /// A new question: the previous one's answers go. A point question takes a
    /// following student off the lecturer's state (they drag the target to their
    /// prediction); another question brings a predicting student back.
    fn open_question(&mut self, question: Question) -> Option<Effect> {
        if self.question.as_ref() == Some(&question) {
            return None;
        }
        let point = matches!(question, Question::Point { .. });
        self.question = Some(question);
        self.answers.clear();
        self.truth = None;
        self.mine = None;
        if point && self.following && matches!(self.role, Role::Student { .. }) {
            self.following = false;
            self.predicting = true;
            return None;
        }
        self.end_prediction()
    }

    /// Follows the lecturer again after a prediction: the latest state to show.
    fn end_prediction(&mut self) -> Option<Effect> {
        if !std::mem::take(&mut self.predicting) {
            return None;
        }
        self.following = true;
        self.latest.clone().map(Effect::Follow)
    }

    /// Whether a point question took this student off the lecturer's state.
    pub fn predicting(&self) -> bool {
        self.predicting
    }

    /// The lecturer's state arrived: kept, and shown when following.
    fn lecturer_state(&mut self, state: State) -> Option<Effect> {
        self.latest = Some(state.clone());
        self.following.then_some(Effect::Follow(state))
    }
}

/// What a link asks of the room: `class=new` (start a class), `class=CODE` (join it, or
/// take control when this browser keeps the class's token), `class=CODE&key=TOKEN` (the
/// lecturer's remote link: take control).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ClassLink {
    /// Start a new class.
    New,
    /// Join (or, with a kept token, control) the class with this code.
    Join(String),
    /// Control the class with this code and token.
    Control {
        /// The join code.
        code: String,
        /// The control token.
        token: String,
    },
    /// A `class=` part that is no join code.
    Bad,
}

/// Splits a link's `class=` and `key=` parts from the rest (the session's own link).
pub fn split_class_link(hash: &str) -> (Option<ClassLink>, String) {
    let hash = hash.trim().trim_start_matches('#');
    let (mut class, mut key, mut rest) = (None, None, Vec::new());
    for part in hash.split('&') {
        if let Some(value) = part.strip_prefix("class=") {
            class = Some(value);
        } else if let Some(value) = part.strip_prefix("key=") {
            key = Some(value);
        } else if !part.is_empty() {
            rest.push(part);
        }
    }
    let link = class.map(|value| {
        if value.eq_ignore_ascii_case("new") {
            return ClassLink::New;
        }
        match (normalize_code(value), key.filter(|k| is_token(k))) {
            (Some(code), Some(token)) => ClassLink::Control {
                code,
                token: token.to_string(),
            },
            (Some(code), None) => ClassLink::Join(code),
            (None, _) => ClassLink::Bad,
        }
    });
    (link, rest.join("&"))
}

/// A join code as people read it: two groups of four (`K7QH-3MXP`).
pub fn shown_code(code: &str) -> String {
    match code.char_indices().nth(4) {
        Some((at, _)) => format!("{}-{}", &code[..at], &code[at..]),
        None => code.to_string(),
    }
}

/// The mean of points and their spread: the root-mean-square distance from the mean.
pub fn mean_and_spread(points: &[[f64; 3]]) -> Option<([f64; 3], f64)> {
    if points.is_empty() {
        return None;
    }
    let n = points.len() as f64;
    let mut mean = [0.0; 3];
    for p in points {
        for k in 0..3 {
            mean[k] += p[k] / n;
        }
    }
    let squares: f64 = points
        .iter()
        .map(|p| (0..3).map(|k| (p[k] - mean[k]).powi(2)).sum::<f64>())
        .sum();
    Some((mean, (squares / n).sqrt()))
}

/// Whether `message` says who a page is (sent once per connection).
fn is_hello(message: &ClientMessage) -> bool {
    matches!(
        message,
        ClientMessage::Create {} | ClientMessage::Resume { .. } | ClientMessage::Join { .. }
    )
}

#[cfg(test)]
#[path = "classroom_tests.rs"]
mod tests;
