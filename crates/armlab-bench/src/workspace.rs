//! Two reports for the workspace and branch notes (docs/kinematics.md §12): the cost of
//! sampling the workspace (forward kinematics + the determinant manipulability, and
//! σ_min separately) and the number of closed-form branches per robot over random
//! reachable targets. The clock is the caller's (`now`, seconds).

use serde_json::{Value, json};

use armlab_core::fk::tool_pose;
use armlab_core::ik::{closed_form_family, closed_form_solutions};
use armlab_core::presets::{preset, preset_ids};
use armlab_core::rng::SplitMix64;
use armlab_core::workspace::{WorkspaceCloud, WorkspaceMeasure};

/// The seed of both reports.
pub const SEED: u64 = 0x00C0_FFEE;

/// Samples `samples` UR10 points with each measure, in one call and timed by `now`;
/// the best of `repeats` runs (and every run) in milliseconds. `cpu`, when given, is the
/// calling thread's CPU time in seconds: on a shared machine the wall clock counts the
/// time other processes hold the core, the CPU time does not (`mean_cpu_ms`, the mean
/// over the runs, so that a clock of coarse ticks still adds up).
pub fn workspace_report(
    samples: usize,
    repeats: usize,
    now: &dyn Fn() -> f64,
    cpu: Option<&dyn Fn() -> f64>,
) -> Value {
    let mut rows = Vec::new();
    let Ok(robot) = preset("ur10") else {
        return json!({ "error": "the ur10 preset does not load" });
    };
    for measure in [WorkspaceMeasure::Manipulability, WorkspaceMeasure::SigmaMin] {
        let mut runs = Vec::with_capacity(repeats);
        let mut cpu_runs = Vec::with_capacity(repeats);
        let mut checksum = 0.0;
        for _ in 0..repeats.max(1) {
            let mut cloud = WorkspaceCloud::new(&robot, measure, samples, SEED);
            let cpu_start = cpu.map(|c| c());
            let start = now();
            cloud.fill(samples);
            runs.push((now() - start) * 1e3);
            if let (Some(c), Some(c0)) = (cpu, cpu_start) {
                cpu_runs.push((c() - c0) * 1e3);
            }
            checksum = cloud.values.iter().sum::<f64>() / samples.max(1) as f64;
        }
        let best = runs.iter().copied().fold(f64::INFINITY, f64::min);
        let mean_cpu =
            (!cpu_runs.is_empty()).then(|| cpu_runs.iter().sum::<f64>() / cpu_runs.len() as f64);
        rows.push(json!({
            "measure": measure.id(),
            "samples": samples,
            "best_ms": best,
            "runs_ms": runs,
            "mean_cpu_ms": mean_cpu,
            "cpu_runs_ms": cpu_runs,
            "ns_per_sample": best * 1e6 / samples.max(1) as f64,
            "mean_value": checksum,
        }));
    }
    json!({ "robot": "ur10", "threads": 1, "seed": SEED, "rows": rows })
}

/// For every preset with a closed form: `targets` random joint vectors within the
/// limits, target = FK(q) (reachable by construction), and a histogram of how many
/// exact solutions the closed form lists and how many of them lie within the limits.
pub fn branch_counts(targets: usize) -> Value {
    let mut rows = Vec::new();
    for id in preset_ids() {
        let Ok(robot) = preset(id) else { continue };
        let Some(family) = closed_form_family(&robot) else {
            continue;
        };
        let mut rng = SplitMix64::new(SEED);
        let mut all = vec![0usize; 17];
        let mut inside = vec![0usize; 17];
        let mut singular = 0usize;
        let mut failed = 0usize;
        for _ in 0..targets {
            let q = rng.joint_vector(&robot);
            let target = tool_pose(&robot, &q);
            match closed_form_solutions(&robot, &target, &q) {
                Ok(set) if !set.unreachable => {
                    let n = set.solutions.len().min(16);
                    let k = set
                        .solutions
                        .iter()
                        .filter(|s| s.within_limits)
                        .count()
                        .min(16);
                    all[n] += 1;
                    inside[k] += 1;
                    singular += usize::from(set.singular);
                }
                _ => failed += 1,
            }
        }
        let histogram = |h: &[usize]| {
            let mut m = serde_json::Map::new();
            for (count, &times) in h.iter().enumerate() {
                if times > 0 {
                    m.insert(count.to_string(), json!(times));
                }
            }
            Value::Object(m)
        };
        let mean = |h: &[usize]| {
            let total: usize = h.iter().sum();
            h.iter().enumerate().map(|(c, t)| c * t).sum::<usize>() as f64 / total.max(1) as f64
        };
        rows.push(json!({
            "robot": id,
            "family": family.name(),
            "targets": targets,
            "solutions": histogram(&all),
            "mean_solutions": mean(&all),
            "within_limits": histogram(&inside),
            "mean_within_limits": mean(&inside),
            "singular_targets": singular,
            "unsolved": failed,
        }));
    }
    json!({ "seed": SEED, "rows": rows })
}
