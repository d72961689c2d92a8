//! The IK benchmark (TRAC-IK protocol) natively: prints the report as JSON.
//!
//! `cargo run --release -p armlab-bench --bin ikbench [samples] [budget] [seed table entries]`

use std::time::Instant;

use armlab_bench::ik::{BenchConfig, MAX_BUDGET, MAX_SAMPLES, run};
use armlab_core::ik::MAX_SEED_TABLE;

fn main() {
    let mut config = BenchConfig::default();
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(samples) = args.first().and_then(|s| s.parse::<usize>().ok()) {
        config.samples = samples.clamp(1, MAX_SAMPLES);
    }
    if let Some(budget) = args.get(1).and_then(|s| s.parse::<usize>().ok()) {
        config.budget = budget.clamp(1, MAX_BUDGET);
    }
    if let Some(entries) = args.get(2).and_then(|s| s.parse::<usize>().ok()) {
        config.seed_table = entries.clamp(1, MAX_SEED_TABLE);
    }
    let start = Instant::now();
    let now = move || start.elapsed().as_secs_f64();
    let mut report = run(&config, &now);
    if let Some(obj) = report.as_object_mut() {
        obj.insert(
            "runtime".into(),
            format!(
                "native {} ({}), clock std::time::Instant",
                std::env::consts::ARCH,
                std::env::consts::OS
            )
            .into(),
        );
    }
    match serde_json::to_string_pretty(&report) {
        Ok(text) => println!("{text}"),
        Err(e) => eprintln!("cannot print the report: {e}"),
    }
}
