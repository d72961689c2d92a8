//! Closed-form branch counts per robot over random reachable targets, as JSON
//! (docs/kinematics.md §12).
//!
//! `cargo run --release -p armlab-bench --bin branchcount [targets]`

use armlab_bench::workspace::branch_counts;

fn main() {
    let targets = std::env::args()
        .nth(1)
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(10_000)
        .clamp(1, 1_000_000);
    match serde_json::to_string_pretty(&branch_counts(targets)) {
        Ok(text) => println!("{text}"),
        Err(e) => eprintln!("cannot print the report: {e}"),
    }
}
