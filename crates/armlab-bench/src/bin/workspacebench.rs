//! The workspace benchmark natively: prints JSON (docs/kinematics.md §12). UR10,
//! forward kinematics + manipulability by the determinant, one thread; σ_min apart.
//!
//! `cargo run --release -p armlab-bench --bin workspacebench [samples] [repeats]`

use std::time::Instant;

use armlab_bench::workspace::workspace_report;

/// The process's CPU time (user + system) in seconds from Linux's `/proc/self/stat`
/// (fields 14 and 15, in ticks of 1/100 s); NaN elsewhere. The process has one thread
/// while it samples.
fn thread_cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|t| {
            let rest = t.rsplit_once(')')?.1;
            let fields: Vec<&str> = rest.split_whitespace().collect();
            let utime = fields.get(11)?.parse::<f64>().ok()?;
            let stime = fields.get(12)?.parse::<f64>().ok()?;
            Some((utime + stime) / 100.0)
        })
        .unwrap_or(f64::NAN)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let samples = args
        .first()
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(100_000)
        .clamp(1, 10_000_000);
    let repeats = args
        .get(1)
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(5)
        .clamp(1, 100);
    let start = Instant::now();
    let now = move || start.elapsed().as_secs_f64();
    let cpu = thread_cpu_seconds;
    let has_cpu = thread_cpu_seconds().is_finite();
    let mut report = workspace_report(
        samples,
        repeats,
        &now,
        has_cpu.then_some(&cpu as &dyn Fn() -> f64),
    );
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
