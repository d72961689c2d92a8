//! The fuzzing corpus and a few thousand seeded cases: every saved
//! input (`tests/fuzz_corpus.json`, written by the `fuzz` binary: the shortest input of
//! each kind of outcome it met) goes to its parser again, natively and as wasm; none may
//! panic, and every error sentence must stay readable. The seeded cases keep IK iteration
//! counts small (the corpus and the `fuzz` binary carry the large ones).

// On wasm32 the tests are `wasm_bindgen_test`s, which clippy does not see as tests, so
// clippy.toml's allow-unwrap-in-tests does not reach them.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use std::collections::BTreeMap;

use armlab_bench::fuzz::{Case, Generator, Target, unreadable};
use serde_json::Value;

const CORPUS: &str = include_str!("fuzz_corpus.json");

/// Seeded cases the test command runs (the `fuzz` binary runs millions).
const SEEDED_CASES: usize = 2000;

fn corpus() -> Vec<Case> {
    let list: Vec<Value> = serde_json::from_str(CORPUS).expect("the corpus is JSON");
    list.iter()
        .map(|entry| Case {
            target: entry["target"]
                .as_str()
                .and_then(Target::from_name)
                .expect("a known target"),
            input: entry["input"].as_str().expect("an input").to_string(),
        })
        .collect()
}

#[test]
fn the_saved_corpus_replays_without_a_panic_and_with_readable_sentences() {
    let cases = corpus();
    assert!(cases.len() >= 90, "{} entries", cases.len());
    let mut per_target: BTreeMap<&str, (usize, usize)> = BTreeMap::new();
    for case in &cases {
        let outcome = case.run();
        let counts = per_target.entry(case.target.name()).or_default();
        match outcome {
            Ok(_) => counts.0 += 1,
            Err(message) => {
                counts.1 += 1;
                assert_eq!(unreadable(&message), None, "{message} ← {:?}", case.input);
            }
        }
    }
    // Every parser is in the corpus, and each with errors (the corpus keeps one input
    // per kind of sentence).
    for target in Target::ALL {
        let (_, errors) = per_target.get(target.name()).copied().unwrap_or_default();
        assert!(errors >= 3, "{}: {per_target:?}", target.name());
    }
}

#[test]
fn seeded_cases_neither_panic_nor_echo_unreadable_text() {
    let mut generator = Generator::with_small_counts(20_261_123);
    let mut errors = 0;
    for _ in 0..SEEDED_CASES {
        let case = generator.case();
        if let Err(message) = case.run() {
            errors += 1;
            assert_eq!(unreadable(&message), None, "{message} ← {:?}", case.input);
        }
    }
    // Most hostile inputs are refused with a sentence; some valid ones get through.
    assert!(errors > SEEDED_CASES / 2, "{errors}");
    assert!(errors < SEEDED_CASES, "{errors}");
}
