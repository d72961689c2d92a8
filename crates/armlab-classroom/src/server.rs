//! The classes of this instance and how a connection gets into one: create, resume,
//! join (through Redis when the class lives on another instance), end, expire.

use crate::bus::{Bus, BusEvent};
use crate::class::{Class, Stamped, derived_token, token_hash};
use crate::config::Config;
use crate::limit::JoinLimiter;
use armlab_room::{CODE_ALPHABET, CODE_LEN, DropReason, Refusal, ServerMessage, tokens_equal};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use tokio::sync::watch;

/// Counters of what was dropped and refused (no personal data: kinds and counts only).
#[derive(Debug, Default)]
pub struct Stats {
    dropped: [AtomicU64; 6],
    refused: [AtomicU64; 7],
    /// WebSocket connections opened.
    pub connections: AtomicU64,
    /// Classes created (or re-created by a resume).
    pub created: AtomicU64,
}

const DROPS: [DropReason; 6] = [
    DropReason::TooLarge,
    DropReason::Malformed,
    DropReason::Invalid,
    DropReason::NotAllowed,
    DropReason::RateLimited,
    DropReason::NotOpen,
];

const REFUSALS: [Refusal; 7] = [
    Refusal::UnknownCode,
    Refusal::BadCode,
    Refusal::WrongToken,
    Refusal::CodeTaken,
    Refusal::TooManyAttempts,
    Refusal::Full,
    Refusal::AlreadyInClass,
];

impl Stats {
    /// Counts a dropped message.
    pub fn drop(&self, reason: DropReason) {
        self.dropped[reason as usize].fetch_add(1, Ordering::Relaxed);
    }

    /// Messages dropped for `reason` so far.
    pub fn dropped(&self, reason: DropReason) -> u64 {
        self.dropped[reason as usize].load(Ordering::Relaxed)
    }

    /// Counts a refusal.
    pub fn refuse(&self, reason: Refusal) {
        self.refused[reason as usize].fetch_add(1, Ordering::Relaxed);
    }

    /// Refusals for `reason` so far.
    pub fn refused(&self, reason: Refusal) -> u64 {
        self.refused[reason as usize].load(Ordering::Relaxed)
    }

    /// The counters as JSON (`/classroom/stats`).
    pub fn to_json(&self, classes: usize) -> String {
        let name = |d: &dyn std::fmt::Debug| format!("{d:?}");
        let dropped: serde_json::Map<_, _> = DROPS
            .iter()
            .map(|&d| (name(&d), self.dropped(d).into()))
            .collect();
        let refused: serde_json::Map<_, _> = REFUSALS
            .iter()
            .map(|&r| (name(&r), self.refused(r).into()))
            .collect();
        serde_json::json!({
            "classes": classes,
            "connections": self.connections.load(Ordering::Relaxed),
            "created": self.created.load(Ordering::Relaxed),
            "dropped": dropped,
            "refused": refused,
        })
        .to_string()
    }
}

/// One server instance.
#[derive(Debug)]
pub struct Server {
    /// Its settings.
    pub config: Config,
    classes: Mutex<HashMap<String, Arc<Class>>>,
    /// Its counters.
    pub stats: Stats,
    /// Failed joins per address.
    pub joins: JoinLimiter,
    /// Redis, when instances share classes.
    pub bus: Option<Bus>,
    /// This instance's random id (on the Redis channels).
    pub instance: u64,
    next_connection: AtomicU64,
    /// Set when the server stops: every connection closes.
    pub shutdown: watch::Sender<bool>,
}

/// `n` random bytes from the operating system.
pub fn random_bytes<const N: usize>() -> [u8; N] {
    let mut bytes = [0u8; N];
    // Without the operating system's random source no code or token may be made; the
    // server cannot run then, and says so at its first class.
    if getrandom::fill(&mut bytes).is_err() {
        panic!("the operating system's random source failed");
    }
    bytes
}

/// A new join code: each character drawn uniformly (bytes ≥ 240 redrawn, 240 = 8 × 30).
pub fn new_code() -> String {
    let mut code = String::with_capacity(CODE_LEN);
    while code.len() < CODE_LEN {
        for b in random_bytes::<16>() {
            if usize::from(b) < 240 && code.len() < CODE_LEN {
                code.push(char::from(
                    CODE_ALPHABET[usize::from(b) % CODE_ALPHABET.len()],
                ));
            }
        }
    }
    code
}

/// A new lecturer token: 128 random bits as 32 hex digits.
pub fn new_token() -> String {
    random_bytes::<16>()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

impl Server {
    /// A server with no class (and Redis, when `bus` is given).
    pub fn new(config: Config, bus: Option<Bus>, instance: u64) -> Self {
        let joins = JoinLimiter::new(config.join_failures, config.join_refill);
        Self {
            config,
            classes: Mutex::new(HashMap::new()),
            stats: Stats::default(),
            joins,
            bus,
            instance,
            next_connection: AtomicU64::new(1),
            shutdown: watch::channel(false).0,
        }
    }

    fn classes(&self) -> std::sync::MutexGuard<'_, HashMap<String, Arc<Class>>> {
        self.classes.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A new connection's id (from 1; 0 is another instance).
    pub fn connection_id(&self) -> u64 {
        self.stats.connections.fetch_add(1, Ordering::Relaxed);
        self.next_connection.fetch_add(1, Ordering::Relaxed)
    }

    /// The class `code` held here, if any.
    pub fn class(&self, code: &str) -> Option<Arc<Class>> {
        self.classes().get(code).cloned()
    }

    /// Classes held here.
    pub fn class_count(&self) -> usize {
        self.classes().len()
    }

    /// Every class held here.
    pub fn all_classes(&self) -> Vec<Arc<Class>> {
        self.classes().values().cloned().collect()
    }

    /// Holds `class` unless a class has its code (then that one); None when full.
    fn hold(&self, class: Class) -> Option<Arc<Class>> {
        let mut classes = self.classes();
        if let Some(held) = classes.get(&class.code) {
            return Some(held.clone());
        }
        if classes.len() >= self.config.max_classes {
            return None;
        }
        let class = Arc::new(class);
        classes.insert(class.code.clone(), class.clone());
        Some(class)
    }

    /// A new class and its token.
    pub async fn create(&self) -> Result<(Arc<Class>, String), Refusal> {
        if self.class_count() >= self.config.max_classes {
            return Err(Refusal::Full);
        }
        for _ in 0..16 {
            let code = new_code();
            let token = match &self.config.secret {
                Some(secret) => derived_token(secret, &code),
                None => new_token(),
            };
            let hash = token_hash(&token);
            if self.class(&code).is_some() {
                continue;
            }
            if let Some(bus) = &self.bus
                && !bus.register(&code, &hash, self.config.expiry).await
            {
                continue;
            }
            let class = self.hold(Class::new(code, hash)).ok_or(Refusal::Full)?;
            self.stats.created.fetch_add(1, Ordering::Relaxed);
            return Ok((class, token));
        }
        Err(Refusal::Full)
    }

    /// The class `code` for a student: held here, or (with Redis) mirrored from another
    /// instance with its latest state and open question.
    pub async fn join(&self, code: &str) -> Result<Arc<Class>, Refusal> {
        if let Some(class) = self.class(code) {
            return Ok(class);
        }
        let bus = self.bus.as_ref().ok_or(Refusal::UnknownCode)?;
        let hash = bus.lookup(code).await.ok_or(Refusal::UnknownCode)?;
        self.mirror(bus, code, hash).await
    }

    async fn mirror(&self, bus: &Bus, code: &str, hash: String) -> Result<Arc<Class>, Refusal> {
        let (state, question) = bus.load(code).await;
        let class = self
            .hold(Class::new(code.to_owned(), hash))
            .ok_or(Refusal::Full)?;
        if class.state.borrow().is_none()
            && let Some(state) = state
        {
            class.state.send_replace(Some(Stamped::new(0, state)));
        }
        if class.open_question().is_none()
            && let Some(question) = question
        {
            class.ask(question);
        }
        bus.publish(code, &BusEvent::Hello {}).await;
        Ok(class)
    }

    /// The class `code` for its lecturer: held here or on another instance (the token
    /// must be its), or re-created with this code and token (after a restart).
    pub async fn resume(&self, code: &str, token: &str) -> Result<Arc<Class>, Refusal> {
        let class = match self.class(code) {
            Some(class) => class,
            None => {
                let hash = token_hash(token);
                match &self.bus {
                    Some(bus) => match bus.lookup(code).await {
                        Some(held) => self.mirror(bus, code, held).await?,
                        None => {
                            self.may_recreate(code, token)?;
                            if !bus.register(code, &hash, self.config.expiry).await {
                                return Err(Refusal::CodeTaken);
                            }
                            self.recreate(code, hash)?
                        }
                    },
                    None => {
                        self.may_recreate(code, token)?;
                        self.recreate(code, hash)?
                    }
                }
            }
        };
        if !class.token_is(token) {
            return Err(Refusal::WrongToken);
        }
        Ok(class)
    }

    /// Whether class `code`, lost in a restart, may be re-created with `token`: with a
    /// secret only for the token derived from it, without one for any.
    fn may_recreate(&self, code: &str, token: &str) -> Result<(), Refusal> {
        match &self.config.secret {
            Some(secret) if !tokens_equal(token, &derived_token(secret, code)) => {
                Err(Refusal::WrongToken)
            }
            _ => Ok(()),
        }
    }

    fn recreate(&self, code: &str, hash: String) -> Result<Arc<Class>, Refusal> {
        self.stats.created.fetch_add(1, Ordering::Relaxed);
        self.hold(Class::new(code.to_owned(), hash))
            .ok_or(Refusal::Full)
    }

    /// Ends `class` here (and, with Redis, everywhere).
    pub async fn end(&self, class: &Class, everywhere: bool) {
        self.classes().remove(&class.code);
        if class.end()
            && everywhere
            && let Some(bus) = &self.bus
        {
            bus.publish(&class.code, &BusEvent::Ended {}).await;
            bus.forget(&class.code).await;
        }
    }

    /// Ends the classes without a lecturer for the expiry (with Redis: those whose key is
    /// gone, since the lecturer's instance renews it), and renews the keys of classes
    /// whose lecturer is here.
    pub async fn sweep(&self) {
        for class in self.all_classes() {
            if class.has_lecturer() {
                if let Some(bus) = &self.bus {
                    bus.renew(&class.code, self.config.expiry).await;
                }
                continue;
            }
            if !class.idle_for(self.config.expiry) {
                continue;
            }
            let alive = match &self.bus {
                Some(bus) => bus.lookup(&class.code).await.is_some(),
                None => false,
            };
            if !alive {
                self.end(&class, false).await;
            }
        }
    }

    /// The message a refusal sends, counted.
    pub fn refusal(&self, reason: Refusal) -> ServerMessage {
        self.stats.refuse(reason);
        ServerMessage::Refused { reason }
    }
}
