//! The motion lab's costs natively, printed as JSON: one simulation step per controller
//! and the collision check of one pose, for the UR10 and the Panda.
//!
//! `cargo run --release -p armlab-bench --bin motionbench [steps] [poses]`

use std::hint::black_box;
use std::time::Instant;

use armlab_core::collision::CollisionChecker;
use armlab_core::{
    Controller, ForwardKinematics, MotionSettings, MotionSim, PidGains, ProfileShape, Robot,
    SplitMix64, preset,
};
use serde_json::{Value, json};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let steps = args
        .first()
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(200_000)
        .clamp(1000, 10_000_000);
    let poses = args
        .get(1)
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(20_000)
        .clamp(100, 1_000_000);
    let mut robots = Vec::new();
    for id in ["ur10", "panda"] {
        match preset(id) {
            Ok(robot) => robots.push((id, robot)),
            Err(e) => eprintln!("{id}: {e}"),
        }
    }
    let controllers = [
        Controller::OnOff { dead_band: 0.01 },
        Controller::Proportional { gain: 5.0 },
        Controller::Pid(PidGains::default()),
        Controller::Profile {
            shape: ProfileShape::Trapezoidal,
            synchronised: true,
        },
    ];
    let mut step_rows = Vec::new();
    let mut collision_rows = Vec::new();
    for (id, robot) in &robots {
        let mut rng = SplitMix64::new(7);
        let goals: Vec<Vec<f64>> = (0..64).map(|_| rng.joint_vector(robot)).collect();
        for controller in controllers {
            step_rows.extend(step_row(id, robot, controller, &goals, steps));
        }
        let qs: Vec<Vec<f64>> = (0..poses).map(|_| rng.joint_vector(robot)).collect();
        collision_rows.extend(collision_row(id, robot, &qs));
    }
    let report: Value = json!({
        "runtime": format!("native {} ({}), clock std::time::Instant", std::env::consts::ARCH, std::env::consts::OS),
        "simulation_step": step_rows,
        "collision_per_pose": collision_rows,
    });
    match serde_json::to_string_pretty(&report) {
        Ok(text) => println!("{text}"),
        Err(e) => eprintln!("cannot print the report: {e}"),
    }
}

/// The time of one simulation step of `controller` over `steps` steps, a new goal of
/// `goals` every simulated second so the joints keep moving; `None` when the simulation
/// cannot start.
fn step_row(
    id: &str,
    robot: &Robot,
    controller: Controller,
    goals: &[Vec<f64>],
    steps: usize,
) -> Option<Value> {
    let settings = MotionSettings {
        controller,
        ..MotionSettings::default()
    };
    let mut sim = MotionSim::new(robot, &robot.home(), settings).ok()?;
    let start = Instant::now();
    for k in 0..steps {
        if k % 1000 == 0 {
            let _ = sim.set_goal(&goals[(k / 1000) % goals.len()]);
        }
        sim.step();
    }
    let secs = start.elapsed().as_secs_f64();
    black_box(sim.q());
    Some(json!({
        "robot": id,
        "controller": controller.id(),
        "steps": steps,
        "ns_per_step": 1e9 * secs / steps as f64,
        "record_every": settings.record_every,
    }))
}

/// The time of the collision check (with FK and parts) of each pose of `qs`, against FK
/// alone; `None` when the kinematics or the checker cannot start.
fn collision_row(id: &str, robot: &Robot, qs: &[Vec<f64>]) -> Option<Value> {
    let poses = qs.len();
    let mut fk = ForwardKinematics::new(robot, &robot.home()).ok()?;
    let mut checker = CollisionChecker::new(true, vec![]).ok()?;
    let (mut colliding, mut exact) = (0usize, 0usize);
    let start = Instant::now();
    for q in qs {
        fk.update(robot, q);
        let report = checker.check(robot, &fk);
        exact += report.exact_tests;
        colliding += usize::from(!report.is_free());
    }
    let secs = start.elapsed().as_secs_f64();
    let start = Instant::now();
    for q in qs {
        fk.update(robot, q);
        black_box(&fk);
    }
    let fk_secs = start.elapsed().as_secs_f64();
    Some(json!({
        "robot": id,
        "poses": poses,
        "parts": checker.parts().len(),
        "us_per_pose_fk_parts_and_check": 1e6 * secs / poses as f64,
        "us_per_pose_fk_only": 1e6 * fk_secs / poses as f64,
        "exact_tests_per_pose": exact as f64 / poses as f64,
        "colliding_fraction_of_random_poses": colliding as f64 / poses as f64,
    }))
}
