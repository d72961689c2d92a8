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

use armlab_bench::fuzz::{Case, Generator, unreadable};
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
    let mut per_target: BTreeMap<&'static str, u64> = BTreeMap::new();
    let mut panics: Vec<Value> = Vec::new();
    let (mut panic_count, mut unreadable_count) = (0u64, 0u64);
    let mut unreadable_messages: Vec<Value> = Vec::new();
    let mut kinds: BTreeMap<String, Case> = BTreeMap::new();
    let mut slowest: Option<(f64, Case)> = None;
    // The slowest cases by wall time, timed again at the end: on a loaded machine one
    // call's wall time can be mostly waiting for a core.
    let mut slowest_few: Vec<(f64, Case)> = Vec::new();
    let start = Instant::now();
    for done in 0..executions {
        if done > 0 && done % 500_000 == 0 {
            // Progress on stderr, so a long run can be read before it ends.
            eprintln!(
                "{{\"executions\": {done}, \"panics\": {}, \"unreadable\": {}, \"seconds\": {:.1}, \"slowest_ms\": {:.3}}}",
                panic_count,
                unreadable_count,
                start.elapsed().as_secs_f64(),
                slowest.as_ref().map_or(0.0, |(s, _)| s * 1e3)
            );
        }
        let case = generator.case();
        let t0 = Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| case.run()));
        let seconds = t0.elapsed().as_secs_f64();
        *per_target.entry(case.target.name()).or_default() += 1;
        if slowest.as_ref().is_none_or(|(s, _)| seconds > *s) {
            slowest = Some((seconds, case.clone()));
        }
        if slowest_few.len() < 10 || slowest_few.iter().any(|(s, _)| seconds > *s) {
            slowest_few.push((seconds, case.clone()));
            slowest_few.sort_by(|a, b| b.0.total_cmp(&a.0));
            slowest_few.truncate(10);
        }
        match outcome {
            Err(_) => {
                panic_count += 1;
                if panics.len() < 20 {
                    panics.push(json!({"target": case.target.name(), "input": case.input}));
                }
            }
            Ok(outcome) => {
                if let Err(message) = &outcome
                    && unreadable(message).is_some()
                {
                    unreadable_count += 1;
                }
                if let Err(message) = &outcome
                    && let Some(why) = unreadable(message)
                    && unreadable_messages.len() < 20
                {
                    unreadable_messages.push(json!({"target": case.target.name(), "why": why, "message": short(message), "input": short(&case.input)}));
                }
                let k = kind(case.target.name(), &outcome);
                // Keep the shortest input of each kind (small corpus entries).
                let keep = kinds
                    .get(&k)
                    .is_none_or(|c| case.input.len() < c.input.len());
                if keep {
                    kinds.insert(k, case);
                }
            }
        }
    }
    let elapsed = start.elapsed().as_secs_f64();
    // Each of the ten slowest again, five times: the least of the five is the input's time.
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
    let retimed_json: Vec<Value> = retimed
        .iter()
        .map(|(best, first, case)| {
            json!({"milliseconds": best * 1e3, "first_wall_milliseconds": first * 1e3,
                   "target": case.target.name(), "input": short(&case.input)})
        })
        .collect();
    if let Some(path) = corpus_path {
        let mut corpus: Vec<Value> = kinds
            .iter()
            .filter(|(_, c)| c.input.len() <= 20_000)
            .map(|(k, c)| json!({"target": c.target.name(), "kind": k, "input": c.input}))
            .collect();
        corpus.extend(panics.iter().cloned());
        match serde_json::to_string_pretty(&corpus) {
            Ok(text) => {
                if let Err(e) = std::fs::write(&path, text + "\n") {
                    eprintln!("cannot write {path}: {e}");
                }
            }
            Err(e) => eprintln!("cannot write the corpus: {e}"),
        }
    }
    let (slow_seconds, slow_case) = match slowest {
        Some((s, c)) => (s, Some(c)),
        None => (0.0, None),
    };
    let report = json!({
        "executions": executions,
        "seed": seed,
        "per_target": per_target,
        "panics": panic_count,
        "unreadable_count": unreadable_count,
        "panic_inputs": panics,
        "unreadable_messages": unreadable_messages,
        "outcome_kinds": kinds.len(),
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
