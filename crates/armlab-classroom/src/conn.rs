//! One WebSocket connection: a visitor until `Create`, `Resume` or `Join`, then the
//! class's lecturer or a student. Every frame is rate-limited, decoded and checked
//! against the role; what fails is dropped, counted and answered with `Dropped`.

use crate::bus::BusEvent;
use crate::class::{Class, Event, Stamped};
use crate::limit::Bucket;
use crate::server::Server;
use armlab_room::{
    ClientMessage, DecodeError, DropReason, Refusal, ServerMessage, State, decode_client,
};
use axum::extract::ws::{Message, Utf8Bytes, WebSocket};
use futures_util::{SinkExt, StreamExt};
use std::net::IpAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::{broadcast, watch};

pub(crate) enum Role {
    Visitor,
    Lecturer(Arc<Class>),
    Student(Arc<Class>),
}

#[derive(Default)]
pub(crate) struct Subs {
    state: Option<watch::Receiver<Option<Stamped>>>,
    events: Option<broadcast::Receiver<Event>>,
    count: Option<watch::Receiver<u32>>,
    answers: Option<watch::Receiver<u64>>,
}

enum Wake {
    Frame(Option<Message>),
    State(Option<Option<Stamped>>),
    Event(Result<Event, broadcast::error::RecvError>),
    Count(Option<u32>),
    Answers(Option<u64>),
    AnswersDue,
    Heartbeat,
    Shutdown,
}

/// What goes out: a message, or a state already written as JSON.
pub(crate) enum Out {
    Message(ServerMessage),
    Json(Arc<str>),
}

async fn changed<T: Clone>(rx: &mut Option<watch::Receiver<T>>) -> Option<T> {
    match rx {
        Some(rx) => match rx.changed().await {
            Ok(()) => Some(rx.borrow_and_update().clone()),
            Err(_) => None,
        },
        None => std::future::pending().await,
    }
}

/// Sends `message`; false when the socket failed or took longer than `wait` to take it (a
/// peer that vanished fills the socket's buffer and would hold the connection forever).
async fn send(
    tx: &mut futures_util::stream::SplitSink<WebSocket, Message>,
    message: Message,
    wait: Duration,
) -> bool {
    matches!(
        tokio::time::timeout(wait, tx.send(message)).await,
        Ok(Ok(()))
    )
}

async fn until(at: Option<tokio::time::Instant>) {
    match at {
        Some(at) => tokio::time::sleep_until(at).await,
        None => std::future::pending().await,
    }
}

/// The least time between two `Answers` to the lecturer: 300 students answering within a
/// second make ten updates of the projector's chart, not 300 (each with every answer).
const ANSWERS_INTERVAL: Duration = Duration::from_millis(100);

async fn event(
    rx: &mut Option<broadcast::Receiver<Event>>,
) -> Result<Event, broadcast::error::RecvError> {
    match rx {
        Some(rx) => rx.recv().await,
        None => std::future::pending().await,
    }
}

/// A connection's state.
pub struct Connection {
    server: Arc<Server>,
    ip: IpAddr,
    id: u64,
    bucket: Bucket,
    role: Role,
    subs: Subs,
    rate_replied: Option<Instant>,
    answers_sent: Option<tokio::time::Instant>,
    answers_due: Option<tokio::time::Instant>,
}

impl Connection {
    /// A new connection from `ip`.
    pub fn new(server: Arc<Server>, ip: IpAddr) -> Self {
        let id = server.connection_id();
        let rate = server.config.student_rate;
        Self {
            server,
            ip,
            id,
            bucket: Bucket::new(rate, rate),
            role: Role::Visitor,
            subs: Subs::default(),
            rate_replied: None,
            answers_sent: None,
            answers_due: None,
        }
    }

    /// Serves the socket until it closes or the server stops.
    pub async fn run(mut self, socket: WebSocket) {
        let (mut tx, mut rx) = socket.split();
        let mut shutdown = self.server.shutdown.subscribe();
        let beat = self.server.config.heartbeat;
        let mut heard = tokio::time::Instant::now();
        let mut next_ping = heard + beat;
        loop {
            let wake = tokio::select! {
                frame = rx.next() => Wake::Frame(frame.and_then(Result::ok)),
                () = tokio::time::sleep_until(next_ping) => Wake::Heartbeat,
                state = changed(&mut self.subs.state) => Wake::State(state),
                event = event(&mut self.subs.events) => Wake::Event(event),
                count = changed(&mut self.subs.count) => Wake::Count(count),
                answers = changed(&mut self.subs.answers) => Wake::Answers(answers),
                () = until(self.answers_due) => Wake::AnswersDue,
                _ = shutdown.changed() => Wake::Shutdown,
            };
            if matches!(wake, Wake::Frame(Some(_))) {
                heard = tokio::time::Instant::now();
            }
            let out = match wake {
                Wake::Frame(None) | Wake::Shutdown => break,
                // A browser answers a ping by itself; nothing for two beats is a page gone
                // without closing its socket.
                Wake::Heartbeat if heard.elapsed() >= 2 * beat => break,
                Wake::Heartbeat => {
                    next_ping = tokio::time::Instant::now() + beat;
                    if !send(&mut tx, Message::Ping(Default::default()), beat).await {
                        break;
                    }
                    Vec::new()
                }
                Wake::Frame(Some(Message::Text(text))) => self.on_frame(text.as_bytes()).await,
                Wake::Frame(Some(Message::Binary(bytes))) => self.on_frame(&bytes).await,
                Wake::Frame(Some(_)) => Vec::new(),
                Wake::State(state) => self.on_state(state),
                Wake::Event(event) => self.on_event(event),
                Wake::Count(count) => self.on_count(count),
                Wake::Answers(answers) => self.on_answers(answers),
                Wake::AnswersDue => {
                    self.answers_due = None;
                    self.answers_now()
                }
            };
            for out in out {
                let text = match out {
                    Out::Message(m) => Utf8Bytes::from(m.to_json()),
                    Out::Json(json) => Utf8Bytes::from(&*json),
                };
                if !send(&mut tx, Message::Text(text), beat).await {
                    self.leave();
                    return;
                }
            }
        }
        self.leave();
    }

    fn leave(&mut self) {
        match std::mem::replace(&mut self.role, Role::Visitor) {
            Role::Lecturer(class) => class.lecturer(false),
            Role::Student(class) => {
                let here = class.student(false);
                self.publish_count(&class, here);
            }
            Role::Visitor => {}
        }
        self.subs = Subs::default();
    }

    fn publish_count(&self, class: &Arc<Class>, students: u32) {
        if let Some(bus) = self.server.bus.clone() {
            let code = class.code.clone();
            tokio::spawn(async move { bus.publish(&code, &BusEvent::Count { students }).await });
        }
    }

    fn dropped(&mut self, reason: DropReason) -> Vec<Out> {
        self.server.stats.drop(reason);
        if reason == DropReason::RateLimited {
            // One reply a second at most: a flood must not become a flood of replies.
            if self
                .rate_replied
                .is_some_and(|t| t.elapsed() < Duration::from_secs(1))
            {
                return Vec::new();
            }
            self.rate_replied = Some(Instant::now());
        }
        vec![Out::Message(ServerMessage::Dropped { reason })]
    }

    async fn on_frame(&mut self, bytes: &[u8]) -> Vec<Out> {
        if !self.bucket.take() {
            return self.dropped(DropReason::RateLimited);
        }
        let message = match decode_client(bytes) {
            Ok(message) => message,
            Err(DecodeError::TooLarge { .. }) => return self.dropped(DropReason::TooLarge),
            Err(DecodeError::Malformed { .. }) => return self.dropped(DropReason::Malformed),
            Err(DecodeError::Invalid(_)) => return self.dropped(DropReason::Invalid),
        };
        match (&self.role, message) {
            (Role::Visitor, ClientMessage::Create {}) => self.create().await,
            (Role::Visitor, ClientMessage::Resume { code, token, state }) => {
                self.resume(&code, &token, state).await
            }
            (Role::Visitor, ClientMessage::Join { code, .. }) => self.join(&code).await,
            (
                _,
                ClientMessage::Create {}
                | ClientMessage::Resume { .. }
                | ClientMessage::Join { .. },
            ) => {
                vec![Out::Message(self.server.refusal(Refusal::AlreadyInClass))]
            }
            (Role::Lecturer(class), message) => {
                let class = class.clone();
                self.drive(&class, message).await
            }
            (Role::Student(class), ClientMessage::Answer { question, value }) => {
                let class = class.clone();
                let student = format!("{}-{}", self.server.instance, self.id);
                if !class.answer(&student, question, value) {
                    return self.dropped(DropReason::NotOpen);
                }
                if let Some(bus) = &self.server.bus {
                    bus.publish(
                        &class.code,
                        &BusEvent::Answer {
                            student,
                            question,
                            value,
                        },
                    )
                    .await;
                }
                Vec::new()
            }
            _ => self.dropped(DropReason::NotAllowed),
        }
    }
}

impl Connection {
    fn become_lecturer(&mut self, class: &Arc<Class>) {
        class.lecturer(true);
        let rate = self.server.config.lecturer_rate;
        self.bucket = Bucket::new(rate, rate);
        let mut count = class.count.subscribe();
        count.mark_changed();
        let mut answers = class.answers_changed.subscribe();
        if class.open_question().is_some() {
            answers.mark_changed();
        }
        self.subs = Subs {
            state: Some(class.state.subscribe()),
            events: Some(class.events.subscribe()),
            count: Some(count),
            answers: Some(answers),
        };
        self.role = Role::Lecturer(class.clone());
    }

    async fn create(&mut self) -> Vec<Out> {
        match self.server.create().await {
            Ok((class, token)) => {
                self.become_lecturer(&class);
                vec![Out::Message(ServerMessage::Created {
                    code: class.code.clone(),
                    token,
                })]
            }
            Err(reason) => vec![Out::Message(self.server.refusal(reason))],
        }
    }

    async fn resume(&mut self, code: &str, token: &str, state: State) -> Vec<Out> {
        if !self.server.joins.allowed(self.ip) {
            return vec![Out::Message(self.server.refusal(Refusal::TooManyAttempts))];
        }
        match self.server.resume(code, token).await {
            Ok(class) => {
                self.become_lecturer(&class);
                let mut out = vec![Out::Message(ServerMessage::Created {
                    code: class.code.clone(),
                    token: token.to_owned(),
                })];
                out.extend(self.drive(&class, ClientMessage::State { state }).await);
                out
            }
            Err(reason) => {
                self.server.joins.failed(self.ip);
                vec![Out::Message(self.server.refusal(reason))]
            }
        }
    }

    async fn join(&mut self, code: &str) -> Vec<Out> {
        if !self.server.joins.allowed(self.ip) {
            return vec![Out::Message(self.server.refusal(Refusal::TooManyAttempts))];
        }
        let class = match self.server.join(code).await {
            Ok(class) => class,
            Err(reason) => {
                self.server.joins.failed(self.ip);
                return vec![Out::Message(self.server.refusal(reason))];
            }
        };
        // Subscribed before reading, so nothing between the read and the first wake is lost.
        let mut state = class.state.subscribe();
        let events = class.events.subscribe();
        let latest = state.borrow_and_update().as_ref().map(|s| s.state.clone());
        let question = class.open_question();
        self.subs = Subs {
            state: Some(state),
            events: Some(events),
            count: None,
            answers: None,
        };
        let here = class.student(true);
        self.publish_count(&class, here);
        self.role = Role::Student(class);
        vec![Out::Message(ServerMessage::Joined {
            state: latest,
            question,
        })]
    }

    /// The lecturer's commands.
    async fn drive(&mut self, class: &Arc<Class>, message: ClientMessage) -> Vec<Out> {
        let (ttl, bus) = (self.server.config.expiry, self.server.bus.clone());
        match message {
            ClientMessage::State { state } => {
                class
                    .state
                    .send_replace(Some(Stamped::new(self.id, state.clone())));
                if let Some(bus) = bus {
                    bus.publish_stored(&class.code, &BusEvent::State { state }, ttl)
                        .await;
                }
            }
            ClientMessage::Ask { question } => {
                class.ask(question.clone());
                if let Some(bus) = bus {
                    bus.publish_stored(&class.code, &BusEvent::Question { question }, ttl)
                        .await;
                }
            }
            ClientMessage::Reveal { question, truth } => {
                if !class.reveal(question, truth) {
                    return self.dropped(DropReason::NotOpen);
                }
                if let Some(bus) = bus {
                    bus.publish(&class.code, &BusEvent::Revealed { question, truth })
                        .await;
                }
            }
            ClientMessage::End {} => self.server.end(class, true).await,
            ClientMessage::Answer { .. } => return self.dropped(DropReason::NotAllowed),
            ClientMessage::Create {}
            | ClientMessage::Resume { .. }
            | ClientMessage::Join { .. } => {}
        }
        Vec::new()
    }

    fn on_state(&mut self, state: Option<Option<Stamped>>) -> Vec<Out> {
        match state {
            Some(Some(stamped)) if stamped.from != self.id => vec![Out::Json(stamped.json)],
            Some(_) => Vec::new(),
            None => {
                self.subs.state = None;
                Vec::new()
            }
        }
    }

    fn on_event(&mut self, event: Result<Event, broadcast::error::RecvError>) -> Vec<Out> {
        match event {
            Ok(Event::Ended) => {
                self.leave();
                vec![Out::Message(ServerMessage::Ended {})]
            }
            Ok(event) => vec![Out::Message(event.message())],
            // Lagged: the missed questions are older than the open one, which the
            // page gets again when asked; nothing to resend.
            Err(broadcast::error::RecvError::Lagged(_)) => Vec::new(),
            Err(broadcast::error::RecvError::Closed) => {
                self.subs.events = None;
                Vec::new()
            }
        }
    }

    fn on_count(&mut self, count: Option<u32>) -> Vec<Out> {
        match count {
            Some(students) => vec![Out::Message(ServerMessage::Count { students })],
            None => {
                self.subs.count = None;
                Vec::new()
            }
        }
    }

    fn on_answers(&mut self, answers: Option<u64>) -> Vec<Out> {
        if answers.is_none() {
            self.subs.answers = None;
            return Vec::new();
        }
        let now = tokio::time::Instant::now();
        match self.answers_sent {
            Some(sent) if now < sent + ANSWERS_INTERVAL => {
                self.answers_due.get_or_insert(sent + ANSWERS_INTERVAL);
                Vec::new()
            }
            _ => self.answers_now(),
        }
    }

    /// The answers so far, to the lecturer.
    fn answers_now(&mut self) -> Vec<Out> {
        let Role::Lecturer(class) = &self.role else {
            return Vec::new();
        };
        self.answers_sent = Some(tokio::time::Instant::now());
        match class.answers() {
            Some((question, values)) => {
                let count = u32::try_from(values.len()).unwrap_or(u32::MAX);
                vec![Out::Message(ServerMessage::Answers {
                    question,
                    values,
                    count,
                })]
            }
            None => Vec::new(),
        }
    }
}
