//! Fuzzing on stable Rust: the seeded, structure-aware generator of `bench::fuzz` fed to
//! the robot-file parser, the link-hash parser and the JSON API, each call under
//! `catch_unwind` and timed. Prints one JSON report: executions per target, panics (with
//! their inputs), messages that break the readability rules, throughput and the slowest
//! input (the ten slowest by wall time are timed again five times at the end, the least
//! time reported, since a loaded machine's wall time is mostly waiting). With a corpus path, writes the inputs that gave a new kind of outcome (the
//! first words of an error sentence, or success) and every panicking input as JSON.
//!
//! `cargo run --release -p armlab-bench --bin fuzz [executions] [seed] [corpus.json]`

use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use armlab_bench::fuzz::{Case, Generator, Outcome, unreadable};
use serde_json::{Value, json};

/// The kind of an outcome: "ok", or the error sentence up to its first quote or digit.
fn kind(target: &str, outcome: &Result<usize, String>) -> String {
    match outcome {
        Ok(_) => format!("{target}: ok"),
        Err(message) => {
            let head: String = message
                .chars()
                .take_while(|c| !(c.is_ascii_digit() || *c == '"' || *c == '('))
                .take(60)
                .collect();
            format!("{target}: {head}")
        }
    }
}

fn short(input: &str) -> String {
    if input.chars().count() > 400 {
        format!(
            "{}… ({} bytes)",
            input.chars().take(400).collect::<String>(),
            input.len()
        )
    } else {
        input.to_string()
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let executions: u64 = args.first().and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let seed: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(15);
    let corpus_path = args.get(2).cloned();
    // Panics are counted and reported, not printed one by one.
    std::panic::set_hook(Box::new(|_| {}));
    let mut generator = Generator::new(seed);
    let mut tally = Tally::default();
    let start = Instant::now();
    for done in 0..executions {
        if done > 0 && done % 500_000 == 0 {
            // Progress on stderr, so a long run can be read before it ends.
            eprintln!(
                "{{\"executions\": {done}, \"panics\": {}, \"unreadable\": {}, \"seconds\": {:.1}, \"slowest_ms\": {:.3}}}",
                tally.panic_count,
                tally.unreadable_count,
                start.elapsed().as_secs_f64(),
                tally.slowest.as_ref().map_or(0.0, |(s, _)| s * 1e3)
            );
        }
        let case = generator.case();
        let t0 = Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| case.run()));
        let seconds = t0.elapsed().as_secs_f64();
        tally.add(case, seconds, outcome);
    }
    let elapsed = start.elapsed().as_secs_f64();
    let retimed_json = retime(&tally.slowest_few);
    if let Some(path) = corpus_path {
        write_corpus(&path, &tally.kinds, &tally.panics);
    }
    let (slow_seconds, slow_case) = match tally.slowest {
        Some((s, c)) => (s, Some(c)),
        None => (0.0, None),
    };
    let report = json!({
        "executions": executions,
        "seed": seed,
        "per_target": tally.per_target,
        "panics": tally.panic_count,
        "unreadable_count": tally.unreadable_count,
        "panic_inputs": tally.panics,
        "unreadable_messages": tally.unreadable_messages,
        "outcome_kinds": tally.kinds.len(),
        "seconds": elapsed,
        "executions_per_second": executions as f64 / elapsed.max(1e-9),
        "slowest_retimed": retimed_json.first(),
        "ten_slowest_retimed": retimed_json,
        "slowest_first_wall_time": {
            "milliseconds": slow_seconds * 1e3,
            "target": slow_case.as_ref().map(|c| c.target.name()),
            "input": slow_case.as_ref().map(|c| short(&c.input)),
        },
        "runtime": format!("native {} ({}), release, one thread", std::env::consts::ARCH, std::env::consts::OS),
    });
    match serde_json::to_string_pretty(&report) {
        Ok(text) => println!("{text}"),
        Err(e) => eprintln!("cannot print the report: {e}"),
    }
}

/// What the run has counted so far.
#[derive(Default)]
struct Tally {
    per_target: BTreeMap<&'static str, u64>,
    /// The first twenty panicking inputs.
    panics: Vec<Value>,
    panic_count: u64,
    unreadable_count: u64,
    /// The first twenty messages that break the readability rules.
    unreadable_messages: Vec<Value>,
    /// The shortest input of each kind of outcome.
    kinds: BTreeMap<String, Case>,
    slowest: Option<(f64, Case)>,
    /// The slowest cases by wall time, timed again at the end: on a loaded machine one
    /// call's wall time can be mostly waiting for a core.
    slowest_few: Vec<(f64, Case)>,
}

impl Tally {
    /// Counts one case's outcome, which took `seconds`.
    fn add(&mut self, case: Case, seconds: f64, outcome: std::thread::Result<Outcome>) {
        *self.per_target.entry(case.target.name()).or_default() += 1;
        if self.slowest.as_ref().is_none_or(|(s, _)| seconds > *s) {
            self.slowest = Some((seconds, case.clone()));
        }
        if self.slowest_few.len() < 10 || self.slowest_few.iter().any(|(s, _)| seconds > *s) {
            self.slowest_few.push((seconds, case.clone()));
            self.slowest_few.sort_by(|a, b| b.0.total_cmp(&a.0));
            self.slowest_few.truncate(10);
        }
        match outcome {
            Err(_) => {
                self.panic_count += 1;
                if self.panics.len() < 20 {
                    self.panics
                        .push(json!({"target": case.target.name(), "input": case.input}));
                }
            }
            Ok(outcome) => self.add_returned(case, &outcome),
        }
    }

    /// Counts a case that returned: its message's readability and its kind of outcome.
    fn add_returned(&mut self, case: Case, outcome: &Outcome) {
        if let Err(message) = outcome
            && unreadable(message).is_some()
        {
            self.unreadable_count += 1;
        }
        if let Err(message) = outcome
            && let Some(why) = unreadable(message)
            && self.unreadable_messages.len() < 20
        {
            self.unreadable_messages.push(json!({"target": case.target.name(), "why": why, "message": short(message), "input": short(&case.input)}));
        }
        let k = kind(case.target.name(), outcome);
        // Keep the shortest input of each kind (small corpus entries).
        let keep = self
            .kinds
            .get(&k)
            .is_none_or(|c| case.input.len() < c.input.len());
        if keep {
            self.kinds.insert(k, case);
        }
    }
}

/// Each of the slowest cases again, five times: the least of the five is the input's
/// time. The slowest first, as JSON.
fn retime(slowest_few: &[(f64, Case)]) -> Vec<Value> {
    let mut retimed: Vec<(f64, f64, &Case)> = slowest_few
        .iter()
        .map(|(first, case)| {
            let best = (0..5)
                .map(|_| {
                    let t0 = Instant::now();
                    let _ = catch_unwind(AssertUnwindSafe(|| case.run()));
                    t0.elapsed().as_secs_f64()
                })
                .fold(f64::INFINITY, f64::min);
            (best, *first, case)
        })
        .collect();
    retimed.sort_by(|a, b| b.0.total_cmp(&a.0));
    retimed
        .iter()
        .map(|(best, first, case)| {
            json!({"milliseconds": best * 1e3, "first_wall_milliseconds": first * 1e3,
                   "target": case.target.name(), "input": short(&case.input)})
        })
        .collect()
}

/// Writes the corpus to `path`: one input of each kind of outcome (up to 20 000 bytes)
/// and the panicking inputs.
fn write_corpus(path: &str, kinds: &BTreeMap<String, Case>, panics: &[Value]) {
    let mut corpus: Vec<Value> = kinds
        .iter()
        .filter(|(_, c)| c.input.len() <= 20_000)
        .map(|(k, c)| json!({"target": c.target.name(), "kind": k, "input": c.input}))
        .collect();
    corpus.extend(panics.iter().cloned());
    match serde_json::to_string_pretty(&corpus) {
        Ok(text) => {
            if let Err(e) = std::fs::write(path, text + "\n") {
                eprintln!("cannot write {path}: {e}");
            }
        }
        Err(e) => eprintln!("cannot write the corpus: {e}"),
    }
}
