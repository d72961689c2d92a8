//! Redis: several instances share a class. The registry is a key per class (`code` →
//! the token's SHA-256, with the expiry as TTL, renewed while the lecturer is connected);
//! the latest state and open question are keys too (for a late student on another
//! instance); everything else crosses on one channel per class, `armlab:room:CODE`, which
//! every instance hears through one pattern subscription.

use crate::class::Stamped;
use crate::server::Server;
use armlab_room::{Answer, Question, State};
use futures_util::StreamExt;
use redis::aio::MultiplexedConnection;
use serde::{Deserialize, Serialize};
use std::sync::Weak;
use std::time::Duration;

/// What one instance tells the others about a class.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(tag = "t", deny_unknown_fields)]
pub enum BusEvent {
    /// The lecturer's state.
    State {
        /// The state.
        state: State,
    },
    /// A question asked.
    Question {
        /// The question.
        question: Question,
    },
    /// A student's answer (the key is the instance's and connection's numbers).
    Answer {
        /// The student's key.
        student: String,
        /// The question's id.
        question: u32,
        /// The answer.
        value: Answer,
    },
    /// The truth revealed.
    Revealed {
        /// The question's id.
        question: u32,
        /// The truth.
        truth: Answer,
    },
    /// The students on the sending instance.
    Count {
        /// How many.
        students: u32,
    },
    /// An instance began to hold the class: the others say their counts.
    Hello {},
    /// The class ended.
    Ended {},
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Envelope {
    from: u64,
    code: String,
    event: BusEvent,
}

/// The largest message read from Redis.
const MAX_BUS_BYTES: usize = 256 * 1024;

fn parse<T: serde::de::DeserializeOwned>(json: Option<String>) -> Option<T> {
    json.filter(|s| s.len() <= MAX_BUS_BYTES)
        .and_then(|s| serde_json::from_str(&s).ok())
}

/// A connection to Redis.
#[derive(Clone)]
pub struct Bus {
    client: redis::Client,
    conn: MultiplexedConnection,
    instance: u64,
}

impl std::fmt::Debug for Bus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Bus(instance {})", self.instance)
    }
}

fn class_key(code: &str) -> String {
    format!("armlab:class:{code}")
}
fn state_key(code: &str) -> String {
    format!("armlab:state:{code}")
}
fn question_key(code: &str) -> String {
    format!("armlab:question:{code}")
}
fn channel(code: &str) -> String {
    format!("armlab:room:{code}")
}

impl Bus {
    /// Connects to Redis at `url` as instance `instance`.
    pub async fn connect(url: &str, instance: u64) -> redis::RedisResult<Self> {
        let client = redis::Client::open(url)?;
        let conn = client.get_multiplexed_async_connection().await?;
        Ok(Self {
            client,
            conn,
            instance,
        })
    }

    /// Registers `code` with its token's hash unless the code is taken; whether it was free.
    pub async fn register(&self, code: &str, hash: &str, ttl: Duration) -> bool {
        let mut conn = self.conn.clone();
        let set: redis::RedisResult<Option<String>> = redis::cmd("SET")
            .arg(class_key(code))
            .arg(hash)
            .arg("NX")
            .arg("EX")
            .arg(ttl.as_secs().max(1))
            .query_async(&mut conn)
            .await;
        matches!(set, Ok(Some(_)))
    }

    /// The token hash of class `code`, when it is registered.
    pub async fn lookup(&self, code: &str) -> Option<String> {
        let mut conn = self.conn.clone();
        redis::cmd("GET")
            .arg(class_key(code))
            .query_async(&mut conn)
            .await
            .ok()
            .flatten()
    }

    /// Renews class `code`'s keys for `ttl`.
    pub async fn renew(&self, code: &str, ttl: Duration) {
        let mut conn = self.conn.clone();
        let secs = ttl.as_secs().max(1);
        let mut pipe = redis::pipe();
        for key in [class_key(code), state_key(code), question_key(code)] {
            pipe.cmd("EXPIRE").arg(key).arg(secs).ignore();
        }
        let _: redis::RedisResult<()> = pipe.query_async(&mut conn).await;
    }

    /// Removes class `code`'s keys.
    pub async fn forget(&self, code: &str) {
        let mut conn = self.conn.clone();
        let _: redis::RedisResult<()> = redis::cmd("DEL")
            .arg(class_key(code))
            .arg(state_key(code))
            .arg(question_key(code))
            .query_async(&mut conn)
            .await;
    }

    /// The latest state and open question of class `code` as stored.
    pub async fn load(&self, code: &str) -> (Option<State>, Option<Question>) {
        let mut conn = self.conn.clone();
        let got: redis::RedisResult<(Option<String>, Option<String>)> = redis::cmd("MGET")
            .arg(state_key(code))
            .arg(question_key(code))
            .query_async(&mut conn)
            .await;
        let (state, question) = got.unwrap_or_default();
        (parse(state), parse(question))
    }

    /// Tells the other instances `event` about class `code`; stores the state and the
    /// question (with the expiry as TTL) for students joining later elsewhere.
    pub async fn publish_stored(&self, code: &str, event: &BusEvent, ttl: Duration) {
        let stored = match event {
            BusEvent::State { state } => Some((state_key(code), serde_json::to_string(state))),
            BusEvent::Question { question } => {
                Some((question_key(code), serde_json::to_string(question)))
            }
            _ => None,
        };
        if let Some((key, Ok(json))) = stored {
            let mut conn = self.conn.clone();
            let _: redis::RedisResult<()> = redis::cmd("SET")
                .arg(key)
                .arg(json)
                .arg("EX")
                .arg(ttl.as_secs().max(1))
                .query_async(&mut conn)
                .await;
        }
        self.publish(code, event).await;
    }

    /// Tells the other instances `event` about class `code`.
    pub async fn publish(&self, code: &str, event: &BusEvent) {
        let envelope = Envelope {
            from: self.instance,
            code: code.to_owned(),
            event: event.clone(),
        };
        let Ok(json) = serde_json::to_string(&envelope) else {
            return;
        };
        let mut conn = self.conn.clone();
        let _: redis::RedisResult<()> = redis::cmd("PUBLISH")
            .arg(channel(code))
            .arg(json)
            .query_async(&mut conn)
            .await;
    }

    /// Hears the other instances until the server is gone, reconnecting with backoff.
    pub async fn listen(self, server: Weak<Server>) {
        let mut backoff = Duration::from_millis(100);
        while server.strong_count() > 0 {
            if let Ok(mut pubsub) = self.client.get_async_pubsub().await
                && pubsub.psubscribe("armlab:room:*").await.is_ok()
            {
                backoff = Duration::from_millis(100);
                let mut messages = pubsub.on_message();
                while let Some(message) = messages.next().await {
                    let Some(server) = server.upgrade() else {
                        return;
                    };
                    let payload = message.get_payload_bytes();
                    if payload.len() > MAX_BUS_BYTES {
                        continue;
                    }
                    if let Ok(envelope) = serde_json::from_slice::<Envelope>(payload) {
                        self.apply(&server, envelope).await;
                    }
                }
            }
            tokio::time::sleep(backoff).await;
            backoff = (backoff * 2).min(Duration::from_secs(5));
        }
    }

    async fn apply(&self, server: &Server, envelope: Envelope) {
        if envelope.from == self.instance {
            return;
        }
        let Some(class) = server.class(&envelope.code) else {
            return;
        };
        match envelope.event {
            BusEvent::State { state } => {
                class.state.send_replace(Some(Stamped::new(0, state)));
            }
            BusEvent::Question { question } => class.ask(question),
            BusEvent::Answer {
                student,
                question,
                value,
            } => {
                class.answer(&student, question, value);
            }
            BusEvent::Revealed { question, truth } => {
                class.reveal(question, truth);
            }
            BusEvent::Count { students } => class.remote_students(envelope.from, students),
            BusEvent::Hello {} => {
                let students = class.local_students();
                self.publish(&class.code, &BusEvent::Count { students })
                    .await;
            }
            BusEvent::Ended {} => server.end(&class, false).await,
        }
    }
}
