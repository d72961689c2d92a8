//! Rate limits: a token bucket per connection, and one per client address for failed
//! joins.

use std::collections::HashMap;
use std::net::IpAddr;
use std::sync::Mutex;
use std::time::Instant;

/// A token bucket: `burst` tokens at most, `rate` more a second; each message takes one.
#[derive(Clone, Debug)]
pub struct Bucket {
    tokens: f64,
    burst: f64,
    rate: f64,
    last: Instant,
}

impl Bucket {
    /// A full bucket of `rate` a second with a burst of `burst`.
    pub fn new(rate: f64, burst: f64) -> Self {
        Self {
            tokens: burst,
            burst,
            rate,
            last: Instant::now(),
        }
    }

    fn refill(&mut self) {
        let now = Instant::now();
        let earned = now.duration_since(self.last).as_secs_f64() * self.rate;
        self.tokens = (self.tokens + earned).min(self.burst);
        self.last = now;
    }

    /// Takes a token; false (and takes none) when the bucket is empty.
    pub fn take(&mut self) -> bool {
        self.refill();
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            true
        } else {
            false
        }
    }

    /// Whether a token is there, without taking it.
    pub fn has(&mut self) -> bool {
        self.refill();
        self.tokens >= 1.0
    }
}

/// Failed joins per client address: guessing codes costs a token per miss.
#[derive(Debug)]
pub struct JoinLimiter {
    buckets: Mutex<HashMap<IpAddr, Bucket>>,
    burst: f64,
    rate: f64,
}

/// The addresses kept before the full buckets are forgotten.
const MAX_ADDRESSES: usize = 100_000;

impl JoinLimiter {
    /// A limiter allowing `burst` failures, then `rate` a second, per address.
    pub fn new(burst: f64, rate: f64) -> Self {
        Self {
            buckets: Mutex::new(HashMap::new()),
            burst,
            rate,
        }
    }

    /// Whether `ip` may try a join now.
    pub fn allowed(&self, ip: IpAddr) -> bool {
        let mut buckets = self.buckets.lock().unwrap_or_else(|e| e.into_inner());
        buckets.get_mut(&ip).is_none_or(Bucket::has)
    }

    /// Counts a failed join from `ip`.
    pub fn failed(&self, ip: IpAddr) {
        let mut buckets = self.buckets.lock().unwrap_or_else(|e| e.into_inner());
        if buckets.len() >= MAX_ADDRESSES {
            buckets.retain(|_, b| !b.has() || b.tokens < b.burst);
        }
        let (burst, rate) = (self.burst, self.rate);
        buckets
            .entry(ip)
            .or_insert_with(|| Bucket::new(rate, burst))
            .take();
    }
}
