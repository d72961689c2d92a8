//! A class in this instance's memory: the lecturer's latest state (a watch: a slow
//! student skips to the newest), the questions with their answers, the students counted,
//! and the events every connection of the class hears (a broadcast).

use armlab_room::{Answer, Question, ServerMessage, State, tokens_equal};
use sha2::{Digest, Sha256};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::Instant;
use tokio::sync::{broadcast, watch};

/// The lecturer's state with the connection that sent it (0: another instance), so a
/// lecturer's second device follows the first without echoing its own; and its `State`
/// message, written once for every student.
#[derive(Clone, Debug)]
pub struct Stamped {
    /// The sending connection's id.
    pub from: u64,
    /// The state.
    pub state: State,
    /// The `State` message as JSON.
    pub json: Arc<str>,
}

impl Stamped {
    /// `state` from connection `from`.
    pub fn new(from: u64, state: State) -> Self {
        let json = ServerMessage::State {
            state: state.clone(),
        }
        .to_json()
        .into();
        Self { from, state, json }
    }
}

/// What every connection of a class hears besides the state.
#[derive(Clone, Debug)]
pub enum Event {
    /// A new question.
    Question(Question),
    /// The truth beside the answers.
    Revealed {
        /// The question's id.
        question: u32,
        /// The truth.
        truth: Answer,
        /// The answers.
        values: Vec<Answer>,
    },
    /// The class ended.
    Ended,
}

impl Event {
    /// The message the pages get.
    pub fn message(&self) -> ServerMessage {
        match self {
            Self::Question(q) => ServerMessage::Question {
                question: q.clone(),
            },
            Self::Revealed {
                question,
                truth,
                values,
            } => ServerMessage::Revealed {
                question: *question,
                truth: *truth,
                values: values.clone(),
            },
            Self::Ended => ServerMessage::Ended {},
        }
    }
}

/// A question asked, its answers (one per student key) and, once revealed, the truth.
#[derive(Clone, Debug)]
pub struct Asked {
    /// The question.
    pub question: Question,
    /// The answers by student key (never a name: the key is a connection's number).
    pub answers: HashMap<String, Answer>,
    /// The truth, once revealed (answers close then).
    pub truth: Option<Answer>,
}

#[derive(Debug)]
struct Inner {
    asked: Vec<Asked>,
    local_students: u32,
    remote_students: HashMap<u64, u32>,
    lecturers: u32,
    last_lecturer: Instant,
    ended: bool,
}

/// The most questions a class keeps (the oldest go first).
const MAX_QUESTIONS: usize = 200;

/// One class.
#[derive(Debug)]
pub struct Class {
    /// The join code.
    pub code: String,
    /// The SHA-256 of the lecturer's token, in hex: the token itself is never stored.
    pub token_hash: String,
    /// The lecturer's latest state.
    pub state: watch::Sender<Option<Stamped>>,
    /// Questions, reveals and the end.
    pub events: broadcast::Sender<Event>,
    /// Bumped on every answer (the lecturer's connection reads the latest).
    pub answers_changed: watch::Sender<u64>,
    /// Students connected, on every instance.
    pub count: watch::Sender<u32>,
    inner: Mutex<Inner>,
}

/// The hex SHA-256 of a token.
pub fn token_hash(token: &str) -> String {
    Sha256::digest(token.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// HMAC-SHA-256 (RFC 2104) of `message` under a 32-byte key.
pub fn hmac_sha256(key: &[u8; 32], message: &[u8]) -> [u8; 32] {
    let (mut inner_pad, mut outer_pad) = ([0x36u8; 64], [0x5cu8; 64]);
    for (i, k) in key.iter().enumerate() {
        inner_pad[i] ^= k;
        outer_pad[i] ^= k;
    }
    let inner = Sha256::new()
        .chain_update(inner_pad)
        .chain_update(message)
        .finalize();
    Sha256::new()
        .chain_update(outer_pad)
        .chain_update(inner)
        .finalize()
        .into()
}

/// The lecturer token of class `code` under `secret`: the HMAC's first 128 bits in hex.
pub fn derived_token(secret: &[u8; 32], code: &str) -> String {
    hmac_sha256(secret, code.as_bytes())[..16]
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

impl Class {
    /// A class with no lecturer connected yet (its expiry clock runs from now).
    pub fn new(code: String, token_hash: String) -> Self {
        Self {
            code,
            token_hash,
            state: watch::channel(None).0,
            events: broadcast::channel(64).0,
            answers_changed: watch::channel(0).0,
            count: watch::channel(0).0,
            inner: Mutex::new(Inner {
                asked: Vec::new(),
                local_students: 0,
                remote_students: HashMap::new(),
                lecturers: 0,
                last_lecturer: Instant::now(),
                ended: false,
            }),
        }
    }

    fn inner(&self) -> std::sync::MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Whether `token` is the lecturer's (compared in constant time, on the hashes).
    pub fn token_is(&self, token: &str) -> bool {
        tokens_equal(&token_hash(token), &self.token_hash)
    }

    /// A lecturer connection came (`+1`) or went (`-1`).
    pub fn lecturer(&self, came: bool) {
        let mut inner = self.inner();
        inner.lecturers = if came {
            inner.lecturers + 1
        } else {
            inner.lecturers.saturating_sub(1)
        };
        inner.last_lecturer = Instant::now();
    }

    /// Whether no lecturer has been connected here for `expiry`.
    pub fn idle_for(&self, expiry: std::time::Duration) -> bool {
        let inner = self.inner();
        inner.lecturers == 0 && inner.last_lecturer.elapsed() >= expiry
    }

    /// Whether a lecturer is connected to this instance.
    pub fn has_lecturer(&self) -> bool {
        self.inner().lecturers > 0
    }

    /// A student of this instance came or went; the students here now.
    pub fn student(&self, came: bool) -> u32 {
        let mut inner = self.inner();
        inner.local_students = if came {
            inner.local_students + 1
        } else {
            inner.local_students.saturating_sub(1)
        };
        let here = inner.local_students;
        self.publish_count(&inner);
        here
    }

    /// Students on another instance (`instance`), from Redis.
    pub fn remote_students(&self, instance: u64, students: u32) {
        let mut inner = self.inner();
        inner.remote_students.insert(instance, students);
        self.publish_count(&inner);
    }

    /// Students on this instance.
    pub fn local_students(&self) -> u32 {
        self.inner().local_students
    }

    fn publish_count(&self, inner: &Inner) {
        let total = inner.local_students + inner.remote_students.values().sum::<u32>();
        self.count.send_replace(total);
    }

    /// The open question (asked, not revealed), if any.
    pub fn open_question(&self) -> Option<Question> {
        self.inner()
            .asked
            .last()
            .filter(|a| a.truth.is_none())
            .map(|a| a.question.clone())
    }

    /// Asks `question`: answers to the previous one close. Asking the open question's id
    /// again (a lecturer's page resuming) keeps its answers.
    pub fn ask(&self, question: Question) {
        let mut inner = self.inner();
        match inner.asked.last_mut() {
            Some(last) if last.question.id() == question.id() && last.truth.is_none() => {
                last.question = question.clone();
            }
            _ => {
                if inner.asked.len() >= MAX_QUESTIONS {
                    inner.asked.remove(0);
                }
                inner.asked.push(Asked {
                    question: question.clone(),
                    answers: HashMap::new(),
                    truth: None,
                });
            }
        }
        drop(inner);
        self.answers_changed.send_modify(|n| *n += 1);
        let _ = self.events.send(Event::Question(question));
    }

    /// Records `student`'s answer to the open question `question` (the last counts);
    /// false when that question is not open or the answer does not fit it.
    pub fn answer(&self, student: &str, question: u32, value: Answer) -> bool {
        let mut inner = self.inner();
        let Some(last) = inner.asked.last_mut() else {
            return false;
        };
        if last.question.id() != question || last.truth.is_some() || !last.question.fits(&value) {
            return false;
        }
        last.answers.insert(student.to_owned(), value);
        drop(inner);
        self.answers_changed.send_modify(|n| *n += 1);
        true
    }

    /// The open (or last) question's id and answers.
    pub fn answers(&self) -> Option<(u32, Vec<Answer>)> {
        let inner = self.inner();
        inner
            .asked
            .last()
            .map(|a| (a.question.id(), a.answers.values().copied().collect()))
    }

    /// Reveals the truth of the open question `question`; false when it is not open or
    /// the truth does not fit it.
    pub fn reveal(&self, question: u32, truth: Answer) -> bool {
        let mut inner = self.inner();
        let Some(last) = inner.asked.last_mut() else {
            return false;
        };
        if last.question.id() != question || last.truth.is_some() || !last.question.fits(&truth) {
            return false;
        }
        last.truth = Some(truth);
        let values = last.answers.values().copied().collect();
        drop(inner);
        let _ = self.events.send(Event::Revealed {
            question,
            truth,
            values,
        });
        true
    }

    /// Every question asked, with its answers (for the CSV).
    pub fn asked(&self) -> Vec<Asked> {
        self.inner().asked.clone()
    }

    /// Ends the class (once): every connection hears `Ended`; false when it had ended.
    pub fn end(&self) -> bool {
        let mut inner = self.inner();
        if inner.ended {
            return false;
        }
        inner.ended = true;
        drop(inner);
        let _ = self.events.send(Event::Ended);
        true
    }

    /// Whether the class has ended.
    pub fn ended(&self) -> bool {
        self.inner().ended
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hmac_matches_rfc_4231() {
        // Test case 2: key "Jefe" (zero-padded, as HMAC pads every short key).
        let mut key = [0u8; 32];
        key[..4].copy_from_slice(b"Jefe");
        let mac = hmac_sha256(&key, b"what do ya want for nothing?");
        let hex: String = mac.iter().map(|b| format!("{b:02x}")).collect();
        assert_eq!(
            hex,
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"
        );
        let token = derived_token(&key, "ABCD2345");
        assert!(armlab_room::is_token(&token));
        assert_ne!(token, derived_token(&key, "ABCD2346"));
    }
}
