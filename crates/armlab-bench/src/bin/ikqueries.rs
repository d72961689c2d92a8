//! A million IK queries: random and degenerate queries over every
//! preset and a set of degenerate arms (zero-length links, coincident axes, one joint,
//! 64 joints, prismatic joints only, huge lengths), every method and every task. Each
//! call runs under `catch_unwind`; the report counts panics, NaN or infinity in any
//! returned q or in FK(q), errors by sentence, success on the reachable queries
//! (target = FK(q), checked by a separate FK call) per robot, method and task, and the
//! slowest query. Prints one JSON report.
//!
//! `cargo run --release -p armlab-bench --bin ikqueries [queries] [seed]`

use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use armlab_core::ik::{pose_error, target_pose};
use armlab_core::{
    IkError, IkMethod, IkResult, IkSettings, IkSolver, Robot, SplitMix64, Task, closed_form_family,
    preset, preset_ids, robot_from_value, tool_pose,
};
use nalgebra::{IsometryMatrix3, Matrix3, Vector3};
use serde_json::{Value, json};

/// Success: within 10⁻⁵ m and 10⁻⁵ rad of the target (the ikbench protocol's threshold).
const SUCCESS_M: f64 = 1e-5;
const SUCCESS_RAD: f64 = 1e-5;

/// The kinds of query.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    /// target = FK(q) for a random q within the limits.
    Random,
    /// target = FK(q) with some joints at 0 or ±π (stretched, folded, wrist aligned).
    Singular,
    /// The target at the base frame's origin.
    Base,
    /// The target ten reaches away.
    Unreachable,
    /// The target 10⁸ units away (inside the accepted distance, far beyond any arm).
    Huge,
}

impl Kind {
    const ALL: [Kind; 5] = [
        Kind::Random,
        Kind::Singular,
        Kind::Base,
        Kind::Unreachable,
        Kind::Huge,
    ];

    fn name(self) -> &'static str {
        match self {
            Kind::Random => "random",
            Kind::Singular => "singular",
            Kind::Base => "base",
            Kind::Unreachable => "unreachable",
            Kind::Huge => "huge",
        }
    }

    fn reachable(self) -> bool {
        matches!(self, Kind::Random | Kind::Singular)
    }
}

fn joint(kind: &str, d: f64, a: f64, alpha_deg: f64) -> Value {
    if kind == "prismatic" {
        json!({"type": kind, "theta_deg": 0, "d": d, "a": a, "alpha_deg": alpha_deg, "min": 0, "max": 500})
    } else {
        json!({"type": kind, "theta_deg": 0, "d": d, "a": a, "alpha_deg": alpha_deg})
    }
}

/// The degenerate arms, as robot files (validated like any file).
fn degenerate_robots() -> Vec<(String, Robot)> {
    let file = |name: &str, joints: Vec<Value>| json!({"name": name, "convention": "standard", "length_unit": "mm", "joints": joints});
    let alternating = |n: usize, a: f64| {
        (0..n)
            .map(|i| joint("revolute", 0.0, a, if i % 2 == 0 { 90.0 } else { -90.0 }))
            .collect::<Vec<_>>()
    };
    let files = [
        ("zero-length-links", file("zero", alternating(6, 0.0))),
        (
            "coincident-axes",
            file(
                "coincident",
                vec![
                    joint("revolute", 0.0, 0.0, 0.0),
                    joint("revolute", 0.0, 0.0, 0.0),
                    joint("revolute", 0.0, 300.0, 0.0),
                    joint("revolute", 0.0, 200.0, 90.0),
                ],
            ),
        ),
        (
            "one-joint",
            file("one", vec![joint("revolute", 50.0, 300.0, 0.0)]),
        ),
        ("64-joints", file("snake", alternating(64, 20.0))),
        (
            "prismatic-only",
            file(
                "gantry",
                vec![
                    joint("prismatic", 0.0, 0.0, -90.0),
                    joint("prismatic", 0.0, 0.0, -90.0),
                    joint("prismatic", 0.0, 0.0, 0.0),
                ],
            ),
        ),
        (
            "huge-lengths",
            file(
                "huge",
                vec![
                    joint("revolute", 1e6, 0.0, 90.0),
                    joint("revolute", 0.0, 1e6, 0.0),
                    joint("revolute", 0.0, 1e6, 0.0),
                    joint("revolute", 1e6, 0.0, 90.0),
                    joint("revolute", 1e6, 0.0, -90.0),
                    joint("revolute", 1e6, 0.0, 0.0),
                ],
            ),
        ),
    ];
    files
        .into_iter()
        .filter_map(|(id, f)| match robot_from_value(&f) {
            Ok(r) => Some((id.to_string(), r)),
            Err(e) => {
                eprintln!("{id}: {e}");
                None
            }
        })
        .collect()
}

fn finite_pose(p: &IsometryMatrix3<f64>) -> bool {
    p.translation.vector.iter().all(|v| v.is_finite())
        && p.rotation.matrix().iter().all(|v| v.is_finite())
}

#[derive(Default)]
struct Cell {
    reachable: u64,
    success: u64,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let queries: u64 = args
        .first()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let seed: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(15);
    std::panic::set_hook(Box::new(|_| {}));
    let mut robots: Vec<(String, Robot)> = preset_ids()
        .filter_map(|id| preset(id).ok().map(|r| (id.to_string(), r)))
        .collect();
    robots.extend(degenerate_robots());
    let mut rng = SplitMix64::new(seed);
    let settings = IkSettings {
        budget: 1000,
        ..IkSettings::default()
    };
    let mut solver = IkSolver::new();
    let mut tally = Tally::default();
    let start = Instant::now();
    for done in 0..queries {
        if done > 0 && done % 50_000 == 0 {
            // Progress on stderr, so a long run can be read before it ends.
            eprintln!(
                "{{\"queries\": {done}, \"panics\": {}, \"non_finite\": {}, \"seconds\": {:.1}, \"slowest_ms\": {:.3}}}",
                tally.panics,
                tally.non_finite,
                start.elapsed().as_secs_f64(),
                tally.slowest.0 * 1e3
            );
        }
        let query = Query::draw(&mut rng, &robots);
        let robot = &robots[query.robot].1;
        let t0 = Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            query.solve(&mut solver, robot, &settings)
        }));
        tally.add(&query, &robots, t0.elapsed().as_secs_f64(), outcome);
    }
    let elapsed = start.elapsed().as_secs_f64();
    let (by_robot_method, by_task) = success_tables(&tally.cells);
    let report = json!({
        "queries": queries,
        "seed": seed,
        "robots": robots.len(),
        "panics": tally.panics,
        "non_finite_results": tally.non_finite,
        "examples": tally.examples,
        "per_kind": tally.per_kind,
        "errors": tally.errors,
        "success_reachable_by_robot_and_method": by_robot_method,
        "success_reachable_by_robot_method_task": by_task,
        "slowest": {"milliseconds": tally.slowest.0 * 1e3, "query": tally.slowest.1},
        "seconds": elapsed,
        "queries_per_second": queries as f64 / elapsed.max(1e-9),
        "settings": {"budget": settings.budget, "max_iterations": settings.max_iterations, "restarts": settings.restarts, "drag_share": 0.1},
        "success_threshold": "1e-5 m and 1e-5 rad on the task's rows, by a separate FK of the returned q",
        "runtime": format!("native {} ({}), release, one thread", std::env::consts::ARCH, std::env::consts::OS),
    });
    match serde_json::to_string_pretty(&report) {
        Ok(text) => println!("{text}"),
        Err(e) => eprintln!("cannot print the report: {e}"),
    }
}

/// One query: a robot (its index), method, task and kind, the target and the seed, and
/// whether it is a drag step.
struct Query {
    robot: usize,
    method: IkMethod,
    task: Task,
    kind: Kind,
    target: IsometryMatrix3<f64>,
    seed: Vec<f64>,
    drag: bool,
}

impl Query {
    /// The next query from `rng` (its draws in a fixed order, so a seed gives one run).
    fn draw(rng: &mut SplitMix64, robots: &[(String, Robot)]) -> Query {
        let index = (rng.next_u64() % robots.len() as u64) as usize;
        let robot = &robots[index].1;
        let method = IkMethod::ALL[(rng.next_u64() % 4) as usize];
        let task = Task::ALL[(rng.next_u64() % 5) as usize];
        let kind = Kind::ALL[(rng.next_u64() % 5) as usize];
        let mut q = rng.joint_vector(robot);
        if kind == Kind::Singular {
            for (v, j) in q.iter_mut().zip(&robot.joints) {
                if rng.next_f64() < 0.4 {
                    let special = [0.0, std::f64::consts::PI, -std::f64::consts::PI]
                        [(rng.next_u64() % 3) as usize];
                    *v = j.limits.clamp(special);
                }
            }
        }
        let reach = robot.reach();
        let target = match kind {
            Kind::Random | Kind::Singular => tool_pose(robot, &q),
            Kind::Base => target_pose(Vector3::zeros(), Matrix3::identity()),
            Kind::Unreachable => {
                let dir =
                    Vector3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.5).normalize();
                target_pose(dir * 10.0 * reach, Matrix3::identity())
            }
            Kind::Huge => target_pose(Vector3::new(1e8, -1e8, 1e8), Matrix3::identity()),
        };
        let seed = rng.joint_vector(robot);
        let drag = rng.next_f64() < 0.1;
        Query {
            robot: index,
            method,
            task,
            kind,
            target,
            seed,
            drag,
        }
    }

    /// Solves the query: a drag step with the drag settings, or a solve with `settings`.
    fn solve(
        &self,
        solver: &mut IkSolver,
        robot: &Robot,
        settings: &IkSettings,
    ) -> Result<IkResult, IkError> {
        if self.drag {
            solver.drag_step(
                robot,
                &self.seed,
                &self.target,
                self.task,
                self.method,
                &IkSettings::drag(),
            )
        } else {
            solver.solve(
                robot,
                &self.target,
                self.task,
                &self.seed,
                self.method,
                settings,
            )
        }
    }

    /// The query as JSON, for the report's examples and its slowest query.
    fn describe(&self, robots: &[(String, Robot)]) -> Value {
        json!({"robot": robots[self.robot].0, "method": self.method.id(), "task": self.task.id(), "kind": self.kind.name(), "drag": self.drag,
               "seed": self.seed, "target": tool_pose_rows(&self.target)})
    }
}

/// What the run has counted so far.
#[derive(Default)]
struct Tally {
    /// Success on reachable queries by robot, method and task.
    cells: BTreeMap<(String, &'static str, &'static str), Cell>,
    per_kind: BTreeMap<&'static str, u64>,
    /// Errors by their sentence without numbers and quoted names.
    errors: BTreeMap<String, u64>,
    panics: u64,
    non_finite: u64,
    /// The first ten panics or non-finite results.
    examples: Vec<Value>,
    /// The slowest query's seconds and description.
    slowest: (f64, Value),
}

impl Tally {
    /// Counts one query's outcome, which took `seconds`.
    fn add(
        &mut self,
        query: &Query,
        robots: &[(String, Robot)],
        seconds: f64,
        outcome: std::thread::Result<Result<IkResult, IkError>>,
    ) {
        *self.per_kind.entry(query.kind.name()).or_default() += 1;
        if seconds > self.slowest.0 {
            self.slowest = (seconds, query.describe(robots));
        }
        let result = match outcome {
            Err(_) => {
                self.panics += 1;
                if self.examples.len() < 10 {
                    self.examples.push(json!({"panic": query.describe(robots)}));
                }
                return;
            }
            Ok(Err(e)) => {
                *self.errors.entry(error_key(&e)).or_default() += 1;
                return;
            }
            Ok(Ok(r)) => r,
        };
        let (id, robot) = &robots[query.robot];
        let finite = result.q.iter().all(|v| v.is_finite())
            && finite_pose(&tool_pose(robot, &result.q))
            && result.position_error.is_finite()
            && result.orientation_error.is_finite();
        if !finite {
            self.non_finite += 1;
            if self.examples.len() < 10 {
                self.examples.push(
                    json!({"non_finite": query.describe(robots), "q": format!("{:?}", result.q)}),
                );
            }
            return;
        }
        if query.kind.reachable() && !query.drag {
            let method = query.method;
            let applicable = method != IkMethod::ClosedForm || closed_form_family(robot).is_some();
            if applicable {
                let (p, o) = pose_error(robot, &result.q, &query.target, query.task);
                let tol = SUCCESS_M / robot.length_unit.in_metres();
                let cell = self
                    .cells
                    .entry((id.clone(), method.id(), query.task.id()))
                    .or_default();
                cell.reachable += 1;
                if p <= tol && o <= SUCCESS_RAD {
                    cell.success += 1;
                }
            }
        }
    }
}

/// The error's sentence without its numbers and quoted names: one key per kind.
fn error_key(e: &IkError) -> String {
    let mut quoted = false;
    e.to_string()
        .chars()
        .filter(|c| {
            if *c == '"' {
                quoted = !quoted;
                return false;
            }
            !quoted && !c.is_ascii_digit()
        })
        .take(70)
        .collect()
}

/// Success per robot and method (all tasks), and per robot, method and task.
fn success_tables(
    cells: &BTreeMap<(String, &'static str, &'static str), Cell>,
) -> (
    BTreeMap<String, BTreeMap<String, Value>>,
    BTreeMap<String, Value>,
) {
    let mut by_robot_method: BTreeMap<String, BTreeMap<String, Value>> = BTreeMap::new();
    let mut by_task: BTreeMap<String, Value> = BTreeMap::new();
    let mut totals: BTreeMap<(String, &'static str), (u64, u64)> = BTreeMap::new();
    for ((robot, method, task), cell) in cells {
        let t = totals.entry((robot.clone(), method)).or_default();
        t.0 += cell.reachable;
        t.1 += cell.success;
        by_task.insert(
            format!("{robot}/{method}/{task}"),
            json!(format!(
                "{}/{} ({:.2} %)",
                cell.success,
                cell.reachable,
                100.0 * cell.success as f64 / cell.reachable.max(1) as f64
            )),
        );
    }
    for ((robot, method), (reachable, success)) in totals {
        by_robot_method.entry(robot).or_default().insert(
            method.to_string(),
            json!(format!(
                "{success}/{reachable} ({:.2} %)",
                100.0 * success as f64 / reachable.max(1) as f64
            )),
        );
    }
    (by_robot_method, by_task)
}

fn tool_pose_rows(pose: &IsometryMatrix3<f64>) -> Value {
    armlab_api::pose_rows(pose)
}
