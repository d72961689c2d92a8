//! The IK benchmark on the TRAC-IK protocol: random joint vectors within the limits
//! (fixed seed), target = FK(q), a full-pose solve from the midpoint of the limits
//! (q = 0 for the UR10), success = position error ≤ 10⁻⁵ m and orientation error ≤ 10⁻⁵
//! rad, checked by a separate FK call on the returned q. Plus a drag scenario: the tool
//! traces a circle of 400 mm diameter (orientation held) in 1 mm steps, each solve
//! warm-started from the previous answer.
//!
//! The core has no clock: the caller passes `now` (seconds, monotonic): `Instant` in the
//! `ikbench` binary, `performance.now()` through the JS API in Node.

use nalgebra::{IsometryMatrix3, Matrix3, Vector3};
use serde_json::{Value, json};
use thiserror::Error;

use super::stats::{mean, percentile};
use armlab_core::fk::tool_pose;
use armlab_core::ik::{
    IkMethod, IkSettings, IkSolver, SeedTable, closed_form_solutions, pose_error, target_pose,
};
use armlab_core::jacobian::Task;
use armlab_core::presets::preset;
use armlab_core::rng::SplitMix64;
use armlab_core::robot::Robot;

/// The most targets a request may ask for per row (a run of this size takes about a
/// second per row natively).
pub const MAX_SAMPLES: usize = 100_000;
/// The largest iteration budget a request may give one solve.
pub const MAX_BUDGET: usize = 100_000;

/// What is wrong with a benchmark request.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum BenchError {
    /// The text is not JSON.
    #[error("Bad request: not JSON ({0})")]
    NotJson(String),
    /// A count that is not a whole number ≥ 0 (`samples`, `budget`, `seed`).
    #[error("Bad request: \"{0}\" must be a whole number")]
    NotACount(&'static str),
    /// A count outside its range.
    #[error("Bad request: \"{field}\" must be between 1 and {max}")]
    OutOfRange {
        /// The field.
        field: &'static str,
        /// Its largest value.
        max: usize,
    },
    /// A solver tolerance that is not a positive finite number.
    #[error("Bad request: \"solver_tolerance\" must be a positive number")]
    BadTolerance,
    /// A field the request does not have.
    #[error("Bad request: \"{0}\" is not known; use samples, budget, seed, solver_tolerance")]
    UnknownField(String),
    /// The report could not be written.
    #[error("The report could not be written: {0}")]
    Report(String),
}

/// The success threshold of the protocol: 10⁻⁵ m and 10⁻⁵ rad.
pub const SUCCESS_TOLERANCE: f64 = 1e-5;

/// What to run.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchConfig {
    /// Random targets per cold-solve row (10 000 in the protocol).
    pub samples: usize,
    /// Seed of the random joint vectors.
    pub seed: u64,
    /// The iteration budget of one cold solve (restarts included); about 1 ms natively.
    pub budget: usize,
    /// The solver's own tolerance (metres and radians), below the success threshold.
    pub solver_tolerance: f64,
    /// Entries of the seed table of the seed-table rows ([`SeedTable`]).
    pub seed_table: usize,
}

/// The default number of entries of the seed-table rows' tables.
pub const SEED_TABLE_SIZE: usize = 64;

/// The seed of the seed table's random joint vectors (another seed than the targets').
pub const SEED_TABLE_RNG_SEED: u64 = 0x5EED_7AB1_E000_0015;

/// The seed-table seed for `config`: [`SEED_TABLE_RNG_SEED`], or the next number when the
/// targets happen to use that one, so that the table never holds the targets' own q.
pub fn seed_table_rng_seed(config: &BenchConfig) -> u64 {
    if config.seed == SEED_TABLE_RNG_SEED {
        SEED_TABLE_RNG_SEED.wrapping_add(1)
    } else {
        SEED_TABLE_RNG_SEED
    }
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            samples: 10_000,
            seed: 20_240_601,
            budget: 1000,
            solver_tolerance: 5e-6,
            seed_table: SEED_TABLE_SIZE,
        }
    }
}

/// Timing and success statistics of one row.
#[derive(Debug, Default)]
struct Stats {
    times: Vec<f64>,
    iterations: Vec<f64>,
    successes: usize,
    extra: Vec<(&'static str, Value)>,
}

impl Stats {
    fn json(&mut self, name: &str, robot: &str, method: &str, note: &str) -> Value {
        let n = self.times.len().max(1);
        self.times.sort_by(f64::total_cmp);
        self.iterations.sort_by(f64::total_cmp);
        let pick = |v: &[f64], f: f64| percentile(v, f).unwrap_or(0.0);
        let mean = |v: &[f64]| mean(v).unwrap_or(0.0);
        let us = |s: f64| (s * 1e8).round() / 100.0;
        let mut row = json!({
            "name": name,
            "robot": robot,
            "method": method,
            "note": note,
            "samples": self.times.len(),
            "success_pct": (self.successes as f64 / n as f64 * 1e6).round() / 1e4,
            "time_us": {
                "median": us(pick(&self.times, 0.5)),
                "mean": us(mean(&self.times)),
                "p99": us(pick(&self.times, 0.99)),
                "max": us(pick(&self.times, 1.0)),
            },
            "iterations": {
                "mean": (mean(&self.iterations) * 100.0).round() / 100.0,
                "median": pick(&self.iterations, 0.5),
                "max": pick(&self.iterations, 1.0),
            },
        });
        if let Some(obj) = row.as_object_mut() {
            for (k, v) in self.extra.drain(..) {
                obj.insert(k.to_string(), v);
            }
        }
        row
    }
}

/// Whether `q` meets the protocol's success test (a separate FK call).
fn verified(robot: &Robot, q: &[f64], target: &IsometryMatrix3<f64>) -> bool {
    let (pe, oe) = pose_error(robot, q, target, Task::FullPose);
    pe * robot.length_unit.in_metres() <= SUCCESS_TOLERANCE && oe <= SUCCESS_TOLERANCE
}

fn settings(config: &BenchConfig) -> IkSettings {
    IkSettings {
        position_tolerance: config.solver_tolerance,
        orientation_tolerance: config.solver_tolerance,
        budget: config.budget,
        ..IkSettings::default()
    }
}

/// Random targets of the protocol for one robot.
fn targets(robot: &Robot, config: &BenchConfig) -> Vec<IsometryMatrix3<f64>> {
    let mut rng = SplitMix64::new(config.seed);
    (0..config.samples)
        .map(|_| tool_pose(robot, &rng.joint_vector(robot)))
        .collect()
}

/// Solves every protocol target with `method`, from the midpoint of the limits or, given a
/// table, from its entry nearest the target (the look-up timed with the solve), timing
/// each call and verifying each answer with a separate FK; also returns the restarts used.
fn solve_stats(
    robot_id: &str,
    method: IkMethod,
    table: Option<&SeedTable>,
    config: &BenchConfig,
    now: &dyn Fn() -> f64,
) -> Option<(Stats, usize)> {
    let robot = preset(robot_id).ok()?;
    let mid = robot.mid_limits();
    let settings = settings(config);
    let mut solver = IkSolver::new();
    let mut stats = Stats::default();
    let mut restarts = 0usize;
    for target in targets(&robot, config) {
        let t0 = now();
        let seed = match table {
            Some(table) => table.nearest(&target).unwrap_or(&mid),
            None => &mid,
        };
        let r = solver.solve(&robot, &target, Task::FullPose, seed, method, &settings);
        let t1 = now();
        let r = r.ok()?;
        stats.times.push(t1 - t0);
        stats.iterations.push(r.iterations as f64);
        restarts += r.restarts;
        if verified(&robot, &r.q, &target) {
            stats.successes += 1;
        }
    }
    Some((stats, restarts))
}

/// Cold numeric solves from the midpoint of the limits.
fn cold_row(robot_id: &str, config: &BenchConfig, now: &dyn Fn() -> f64) -> Option<Value> {
    let (mut stats, restarts) =
        solve_stats(robot_id, IkMethod::DampedLeastSquares, None, config, now)?;
    stats.extra.push((
        "restarts_mean",
        json!(restarts as f64 / config.samples.max(1) as f64),
    ));
    stats
        .extra
        .push(("budget_iterations", json!(config.budget)));
    Some(stats.json(
        &format!("{robot_id} cold, damped least squares alone"),
        robot_id,
        "dls",
        "seed at the midpoint of the limits, random restarts within the budget",
    ))
}

/// Cold numeric solves from the seed table's entry nearest each target (a table of
/// [`BenchConfig::seed_table`] joint vectors drawn with [`seed_table_rng_seed`], not the
/// targets' seed; built once, untimed).
fn seed_table_row(robot_id: &str, config: &BenchConfig, now: &dyn Fn() -> f64) -> Option<Value> {
    let robot = preset(robot_id).ok()?;
    let table = SeedTable::sample(&robot, config.seed_table, seed_table_rng_seed(config));
    let (mut stats, restarts) = solve_stats(
        robot_id,
        IkMethod::DampedLeastSquares,
        Some(&table),
        config,
        now,
    )?;
    stats.extra.push((
        "restarts_mean",
        json!(restarts as f64 / config.samples.max(1) as f64),
    ));
    stats
        .extra
        .push(("budget_iterations", json!(config.budget)));
    stats.extra.push(("seed_table_entries", json!(table.len())));
    stats
        .extra
        .push(("seed_table_rng_seed", json!(seed_table_rng_seed(config))));
    Some(stats.json(
        &format!("{robot_id} cold, seed table"),
        robot_id,
        "dls",
        "seed = the sampled q whose tool pose is nearest the target (look-up timed), table drawn with another seed than the targets",
    ))
}

/// All closed-form solutions of each target, every one verified.
fn closed_form_row(robot_id: &str, config: &BenchConfig, now: &dyn Fn() -> f64) -> Option<Value> {
    let robot = preset(robot_id).ok()?;
    let seed = robot.mid_limits();
    let mut stats = Stats::default();
    let mut counts = [0usize; 9];
    let mut all_valid = 0usize;
    for target in targets(&robot, config) {
        let t0 = now();
        let set = closed_form_solutions(&robot, &target, &seed);
        let t1 = now();
        let set = set.ok()?;
        stats.times.push(t1 - t0);
        stats.iterations.push(0.0);
        counts[set.solutions.len().min(8)] += 1;
        let valid = set
            .solutions
            .iter()
            .filter(|s| verified(&robot, &s.q, &target))
            .count();
        if valid > 0 {
            stats.successes += 1;
        }
        if valid == set.solutions.len() {
            all_valid += 1;
        }
    }
    stats.extra.push(("solution_counts", json!(counts)));
    stats.extra.push((
        "all_solutions_verified_pct",
        json!(all_valid as f64 / config.samples.max(1) as f64 * 100.0),
    ));
    Some(stats.json(
        &format!("{robot_id} closed form, all branches"),
        robot_id,
        "closed-form-all",
        "time to compute every solution; success = one verifies, all verified listed apart",
    ))
}

/// The hybrid: the closed-form branch nearest the seed through the solver interface.
fn hybrid_row(robot_id: &str, config: &BenchConfig, now: &dyn Fn() -> f64) -> Option<Value> {
    let (mut stats, _) = solve_stats(robot_id, IkMethod::ClosedForm, None, config, now)?;
    Some(stats.json(
        &format!("{robot_id} closed form, branch nearest the seed"),
        robot_id,
        "closed-form",
        "IkSolver::solve with IkMethod::ClosedForm (verifies the chosen branch)",
    ))
}

/// The drag scenario: a 400 mm circle in 1 mm steps, orientation held.
fn drag_row(
    robot_id: &str,
    center_mm: [f64; 3],
    rotation: Matrix3<f64>,
    method: IkMethod,
    config: &BenchConfig,
    now: &dyn Fn() -> f64,
) -> Option<Value> {
    let robot = preset(robot_id).ok()?;
    let unit = robot.length_unit.in_metres();
    let to_units = 1e-3 / unit;
    let center = Vector3::from(center_mm) * to_units;
    let radius = 200.0 * to_units;
    let steps = (std::f64::consts::TAU * 200.0).round() as usize; // 1 mm arcs
    let point = |k: usize| {
        let a = std::f64::consts::TAU * k as f64 / steps as f64;
        target_pose(
            center + Vector3::new(radius * a.cos(), radius * a.sin(), 0.0),
            rotation,
        )
    };
    let mut solver = IkSolver::new();
    // Start: a full solve at the first point from the midpoint of the limits (untimed).
    let start = solver
        .solve(
            &robot,
            &point(0),
            Task::FullPose,
            &robot.mid_limits(),
            IkMethod::DampedLeastSquares,
            &IkSettings::default(),
        )
        .ok()?;
    let mut q = start.q;
    let settings = IkSettings {
        position_tolerance: config.solver_tolerance,
        orientation_tolerance: config.solver_tolerance,
        ..IkSettings::drag()
    };
    let mut stats = Stats::default();
    let mut worst_move: f64 = 0.0;
    for k in 1..=steps {
        let target = point(k);
        let t0 = now();
        let r = solver.drag_step(&robot, &q, &target, Task::FullPose, method, &settings);
        let t1 = now();
        let r = r.ok()?;
        stats.times.push(t1 - t0);
        stats.iterations.push(r.iterations as f64);
        for ((j, a), b) in robot.joints.iter().zip(&q).zip(&r.q) {
            worst_move = worst_move.max(j.change(*a, *b).abs());
        }
        if verified(&robot, &r.q, &target) {
            stats.successes += 1;
        }
        q = r.q;
    }
    stats.extra.push(("start_solved", json!(start.success)));
    stats
        .extra
        .push(("largest_joint_change_rad", json!(worst_move)));
    Some(stats.json(
        &format!("{robot_id} drag, 400 mm circle in 1 mm steps"),
        robot_id,
        method.id(),
        "drag_step warm-started from the previous answer, orientation held",
    ))
}

/// The cost of the building blocks of one iteration, in batches (ns per call).
fn building_blocks(robot_id: &str, config: &BenchConfig, now: &dyn Fn() -> f64) -> Option<Value> {
    use armlab_core::fk::ForwardKinematics;
    use armlab_core::jacobian::geometric_jacobian_into;
    let robot = preset(robot_id).ok()?;
    let mut rng = SplitMix64::new(config.seed);
    let qs: Vec<Vec<f64>> = (0..1000).map(|_| rng.joint_vector(&robot)).collect();
    let reps = (config.samples / 1000).max(1);
    let mut fk = ForwardKinematics::new(&robot, &qs[0]).ok()?;
    let mut j = nalgebra::Matrix6xX::zeros(robot.dof());
    let mut sink = 0.0;
    let t0 = now();
    for _ in 0..reps {
        for q in &qs {
            fk.update(&robot, q);
            sink += fk.base_from_tool.translation.vector.x;
        }
    }
    let t1 = now();
    for _ in 0..reps {
        for q in &qs {
            fk.update(&robot, q);
            geometric_jacobian_into(&fk, &mut j);
            sink += j[(0, 0)];
        }
    }
    let t2 = now();
    for _ in 0..reps {
        for q in &qs {
            sink += tool_pose(&robot, q).translation.vector.x;
        }
    }
    let t3 = now();
    let per = |t: f64| (t / (reps * qs.len()) as f64 * 1e10).round() / 10.0;
    Some(json!({
        "name": format!("{robot_id} building blocks (ns per call)"),
        "fk_update_ns": per(t1 - t0),
        "fk_update_plus_jacobian_ns": per(t2 - t1),
        "tool_pose_ns": per(t3 - t2),
        "checksum": sink.is_finite(),
    }))
}

/// Targets per row of the untimed pass that [`run`] makes before the timed one.
pub const WARM_UP_SAMPLES: usize = 1000;

/// Runs every row and returns the report as JSON. An untimed pass of every row with at
/// most [`WARM_UP_SAMPLES`] targets comes first: V8 compiles wasm with its baseline
/// compiler and swaps in optimised code only once a function is hot, so without it in Node
/// the first row would be timed partly on baseline code (UR10 cold 5.2–5.6 µs beside
/// 4.6–4.9 µs for the same arm in the next row); natively it changes nothing.
pub fn run(config: &BenchConfig, now: &dyn Fn() -> f64) -> Value {
    let warm = BenchConfig {
        samples: config.samples.min(WARM_UP_SAMPLES),
        ..config.clone()
    };
    std::hint::black_box(rows(&warm, now));
    json!({
        "protocol": "TRAC-IK: random q within limits (fixed seed), target = FK(q), full pose from the midpoint of the limits; success = 1e-5 m and 1e-5 rad by a separate FK",
        "samples": config.samples,
        "warm_up_samples_per_row": warm.samples,
        "seed": config.seed,
        "budget_iterations": config.budget,
        "solver_tolerance": config.solver_tolerance,
        "rows": rows(config, now),
    })
}

/// Every row, timed with `now`.
fn rows(config: &BenchConfig, now: &dyn Fn() -> f64) -> Vec<Value> {
    let down = Matrix3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
    [
        cold_row("ur10", config, now),
        cold_row("ur10-standard", config, now),
        cold_row("panda", config, now),
        seed_table_row("ur10", config, now),
        seed_table_row("panda", config, now),
        closed_form_row("ur10", config, now),
        hybrid_row("ur10", config, now),
        drag_row(
            "ur10",
            [700.0, -200.0, 400.0],
            down,
            IkMethod::DampedLeastSquares,
            config,
            now,
        ),
        drag_row(
            "ur10",
            [700.0, -200.0, 400.0],
            down,
            IkMethod::ClosedForm,
            config,
            now,
        ),
        drag_row(
            "panda",
            [450.0, 0.0, 400.0],
            down,
            IkMethod::DampedLeastSquares,
            config,
            now,
        ),
        building_blocks("ur10", config, now),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// Parses a benchmark request `{"samples", "budget", "seed", "solver_tolerance"}` (all
/// optional; `{}` or empty text for the defaults). `samples` is at most [`MAX_SAMPLES`]
/// and `budget` at most [`MAX_BUDGET`], so no request runs unbounded.
pub fn config_from_json(request: &str) -> Result<BenchConfig, BenchError> {
    let mut config = BenchConfig::default();
    if request.trim().is_empty() {
        return Ok(config);
    }
    let value: Value =
        serde_json::from_str(request).map_err(|e| BenchError::NotJson(e.to_string()))?;
    let Some(object) = value.as_object() else {
        return Err(BenchError::NotJson("not an object { ... }".into()));
    };
    if let Some(key) = object
        .keys()
        .find(|k| !["samples", "budget", "seed", "solver_tolerance"].contains(&k.as_str()))
    {
        return Err(BenchError::UnknownField(key.chars().take(40).collect()));
    }
    let count = |key: &'static str| -> Result<Option<u64>, BenchError> {
        match value.get(key) {
            None => Ok(None),
            Some(v) => v.as_u64().map(Some).ok_or(BenchError::NotACount(key)),
        }
    };
    let bounded = |key: &'static str, max: usize| -> Result<Option<usize>, BenchError> {
        match count(key)? {
            None => Ok(None),
            Some(n) if (1..=max as u64).contains(&n) => Ok(Some(n as usize)),
            Some(_) => Err(BenchError::OutOfRange { field: key, max }),
        }
    };
    if let Some(n) = bounded("samples", MAX_SAMPLES)? {
        config.samples = n;
    }
    if let Some(n) = bounded("budget", MAX_BUDGET)? {
        config.budget = n;
    }
    if let Some(n) = count("seed")? {
        config.seed = n;
    }
    if let Some(v) = value.get("solver_tolerance") {
        config.solver_tolerance = v
            .as_f64()
            .filter(|t| t.is_finite() && *t > 0.0)
            .ok_or(BenchError::BadTolerance)?;
    }
    Ok(config)
}

/// [`run`] from a JSON request ([`config_from_json`]) to pretty JSON text.
pub fn run_json(request: &str, now: &dyn Fn() -> f64) -> Result<String, BenchError> {
    let config = config_from_json(request)?;
    serde_json::to_string_pretty(&run(&config, now)).map_err(|e| BenchError::Report(e.to_string()))
}
