//! Joint motion toward a goal, simulated in time (docs/kinematics.md §17): the Metrover
//! thesis's on/off feedback, proportional velocity control, PD/PID on a joint with inertia
//! and a constant load, and ideal tracking of a planned profile
//! ([`crate::profile`]).
//!
//! The simulation runs fixed steps of [`STEP`] seconds. [`MotionSim::advance`] takes the
//! time to simulate (the app's frame time × its time scale), runs the whole steps it
//! holds and keeps the remainder for the next call; [`MotionSim::step`] runs one step.
//! The core has no clock: time is only what the caller passes in.

use std::collections::VecDeque;

use nalgebra::Vector3;

use super::angles::wrap_to_pi;
use super::fk::ForwardKinematics;
pub use super::motion_error::{MotionError, Setting};
use super::motion_error::{check_at_most, check_finite, check_non_negative, check_positive};
use super::profile::{MotionLimits, ProfileShape, Trajectory, joint_distance_to};
use super::robot::Robot;

/// The simulation's fixed step, seconds (1 ms).
pub const STEP: f64 = 1e-3;
/// The most steps one [`MotionSim::advance`] runs (one simulated second): after a long
/// pause (a hidden tab) the rest is dropped instead of freezing the page to catch up.
pub const MAX_STEPS_PER_ADVANCE: usize = 1000;
/// The largest time scale accepted (10× real time); 0 is a pause.
pub const MAX_TIME_SCALE: f64 = 10.0;
/// The settling band: a joint has settled when its error stays within this fraction of
/// its error at the moment the goal was set.
pub const SETTLING_BAND: f64 = 0.02;
/// The largest magnitude of any gain, dead band, load or plant constant accepted.
pub const MAX_SETTING: f64 = 1e6;

/// Checks a time scale typed or picked in the app: 0 (pause) to [`MAX_TIME_SCALE`].
pub fn check_time_scale(scale: f64) -> Result<f64, MotionError> {
    check_non_negative(Setting::TimeScale, scale, MAX_TIME_SCALE)?;
    Ok(scale)
}

/// PD/PID gains: effort `u = Kp·e + Ki·∫e dt − Kd·q̇` (the derivative on the measurement,
/// which equals `Kd·ė` while the goal stands still and does not kick when it jumps).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PidGains {
    /// Proportional gain Kp (effort per rad or per unit).
    pub kp: f64,
    /// Integral gain Ki (effort per rad·s); 0 for PD.
    pub ki: f64,
    /// Derivative gain Kd (effort per rad/s).
    pub kd: f64,
}

impl Default for PidGains {
    /// Kp = 100, Kd = 20, Ki = 200: with inertia 1, ω = 10 rad/s, critically damped as
    /// a PD, and a PID well inside its stability bound Ki < Kd·Kp/I = 2000.
    fn default() -> Self {
        PidGains {
            kp: 100.0,
            ki: 200.0,
            kd: 20.0,
        }
    }
}

/// How a joint is driven toward its goal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Controller {
    /// On/off (bang-bang) velocity control, as in the Metrover thesis: full speed toward
    /// the goal until |e| < dead band, then stop. Drives the velocity servo.
    OnOff {
        /// The dead band (rad or units), ≥ 0.
        dead_band: f64,
    },
    /// Proportional velocity control `v = K·e`, clamped to the speed limit. Drives the
    /// velocity servo.
    Proportional {
        /// K (1/s), above 0 and at most 1/[`STEP`].
        gain: f64,
    },
    /// PD/PID effort on the joint's inertia (with friction and the constant load).
    Pid(PidGains),
    /// Ideal tracking of a profile planned from the pose when the goal is set.
    Profile {
        /// The profile's shape.
        shape: ProfileShape,
        /// Whether all joints arrive together.
        synchronised: bool,
    },
}

impl Controller {
    /// The id used in links: `onoff`, `p`, `pid`, `profile`.
    pub fn id(&self) -> &'static str {
        match self {
            Controller::OnOff { .. } => "onoff",
            Controller::Proportional { .. } => "p",
            Controller::Pid(_) => "pid",
            Controller::Profile { .. } => "profile",
        }
    }
}

/// The joint's physics, the same for every joint.
///
/// - The on/off and proportional controllers command a velocity; the drive reaches it
///   with a first-order lag: `τ·q̈ = v_cmd − q̇` (τ = 0: at once). Load and inertia do
///   not act on this ideal velocity servo.
/// - PD/PID command an effort on a mass: `I·q̈ = u − b·q̇ − L`, with |q̇| clamped to the
///   joint's speed limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plant {
    /// The velocity servo's time constant τ (seconds, ≥ 0, at most 10).
    pub time_constant: f64,
    /// Inertia I (effort per rad/s²), above 0.
    pub inertia: f64,
    /// Viscous friction b (effort per rad/s), ≥ 0.
    pub friction: f64,
    /// A constant load torque L (effort; positive pushes the joint toward lower values).
    pub load: f64,
}

impl Default for Plant {
    /// τ = 20 ms, I = 1, b = 0, L = 0.
    fn default() -> Self {
        Plant {
            time_constant: 0.02,
            inertia: 1.0,
            friction: 0.0,
            load: 0.0,
        }
    }
}

/// Everything a simulation is set up with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionSettings {
    /// The controller.
    pub controller: Controller,
    /// The joint's physics.
    pub plant: Plant,
    /// Samples kept in the record (the oldest are dropped), 1 to 10⁶.
    pub record_capacity: usize,
    /// One sample is recorded every this many steps, 1 to 10⁶.
    pub record_every: usize,
}

impl Default for MotionSettings {
    /// Proportional control with K = 5/s; 10 s of samples at one per 10 ms.
    fn default() -> Self {
        MotionSettings {
            controller: Controller::Proportional { gain: 5.0 },
            plant: Plant::default(),
            record_capacity: 1000,
            record_every: 10,
        }
    }
}

impl MotionSettings {
    /// Checks every number. Beyond sign and finiteness, gains that would make the 1 ms
    /// step unstable are too large: K·Δt ≤ 1, Kp·Δt²/I ≤ 1, Kd·Δt/I ≤ 1, and the PID's
    /// Routh–Hurwitz bound Ki ≤ (Kd + b)·Kp/I (of I·s³ + (Kd + b)·s² + Kp·s + Ki).
    pub fn check(&self) -> Result<(), MotionError> {
        let p = &self.plant;
        check_non_negative(Setting::TimeConstant, p.time_constant, 10.0)?;
        check_positive(Setting::Inertia, p.inertia, MAX_SETTING)?;
        check_non_negative(Setting::Friction, p.friction, MAX_SETTING)?;
        check_finite(Setting::Load, p.load)?;
        check_at_most(Setting::Load, p.load, MAX_SETTING)?;
        for n in [self.record_capacity, self.record_every] {
            if n == 0 || n > 1_000_000 {
                return Err(MotionError::TooLarge {
                    setting: Setting::RecordLength,
                    value: n as f64,
                    max: 1e6,
                });
            }
        }
        match self.controller {
            Controller::OnOff { dead_band } => {
                check_non_negative(Setting::DeadBand, dead_band, MAX_SETTING)
            }
            Controller::Proportional { gain } => {
                check_positive(Setting::Gain, gain, MAX_SETTING)?;
                check_at_most(Setting::Gain, gain, 1.0 / STEP)
            }
            Controller::Pid(g) => {
                check_non_negative(Setting::Kp, g.kp, MAX_SETTING)?;
                check_non_negative(Setting::Ki, g.ki, MAX_SETTING)?;
                check_non_negative(Setting::Kd, g.kd, MAX_SETTING)?;
                check_at_most(Setting::Kp, g.kp, p.inertia / (STEP * STEP))?;
                check_at_most(Setting::Kd, g.kd, p.inertia / STEP)?;
                check_at_most(Setting::Ki, g.ki, (g.kd + p.friction) * g.kp / p.inertia)
            }
            Controller::Profile { .. } => Ok(()),
        }
    }
}

/// One joint's measured response since its goal was last set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointMeasures {
    /// The error e = goal − q when the goal was set.
    pub start_error: f64,
    /// How far the joint has gone past the goal (≥ 0, rad or units).
    pub overshoot: f64,
    /// `overshoot / |start_error|`, when the start error was not zero.
    pub overshoot_ratio: Option<f64>,
    /// The time from setting the goal until the error last left the settling band
    /// (`SETTLING_BAND·|start_error|`), when it is inside the band now; `None` while
    /// outside. It can still grow if the joint leaves the band again.
    pub settling_time: Option<f64>,
    /// The error now (signed): the steady-state error once the joint has settled.
    pub error: f64,
}

/// Which series of the record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Series {
    /// q.
    Position,
    /// q̇.
    Velocity,
    /// e = goal − q (wrapped for wrapping joints).
    Error,
}

/// The bounded time series for the plots: every `every`-th step, at most `capacity`
/// samples (the oldest dropped). Values are stored flat, `dof` per sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    dof: usize,
    capacity: usize,
    every: usize,
    t: VecDeque<f64>,
    q: VecDeque<f64>,
    qd: VecDeque<f64>,
    e: VecDeque<f64>,
    tool: VecDeque<f64>,
}

impl Record {
    fn new(dof: usize, capacity: usize, every: usize) -> Record {
        Record {
            dof,
            capacity,
            every,
            t: VecDeque::with_capacity(capacity),
            q: VecDeque::with_capacity(capacity * dof),
            qd: VecDeque::with_capacity(capacity * dof),
            e: VecDeque::with_capacity(capacity * dof),
            tool: VecDeque::with_capacity(capacity),
        }
    }

    fn push(&mut self, t: f64, q: &[f64], qd: &[f64], e: &[f64], tool: Option<f64>) {
        if self.t.len() == self.capacity {
            self.t.pop_front();
            self.tool.pop_front();
            for _ in 0..self.dof {
                self.q.pop_front();
                self.qd.pop_front();
                self.e.pop_front();
            }
        }
        self.t.push_back(t);
        self.tool.push_back(tool.unwrap_or(f64::NAN));
        self.q.extend(q.iter().copied());
        self.qd.extend(qd.iter().copied());
        self.e.extend(e.iter().copied());
    }

    /// Forgets every sample.
    pub fn clear(&mut self) {
        self.t.clear();
        self.q.clear();
        self.qd.clear();
        self.e.clear();
        self.tool.clear();
    }

    /// Number of samples held.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether no sample is held.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The most samples held.
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// The sample times (seconds of simulated time).
    pub fn times(&self) -> impl Iterator<Item = f64> + '_ {
        self.t.iter().copied()
    }

    /// `[t, value]` of joint `joint` (0-based) for a series: the points of a plot line.
    pub fn joint(&self, joint: usize, series: Series) -> impl Iterator<Item = [f64; 2]> + '_ {
        let values = match series {
            Series::Position => &self.q,
            Series::Velocity => &self.qd,
            Series::Error => &self.e,
        };
        let dof = self.dof;
        self.t
            .iter()
            .enumerate()
            .filter(move |_| joint < dof)
            .map(move |(k, t)| [*t, values[k * dof + joint]])
    }

    /// `[t, distance]` from the tool to the target, for the samples taken while a target
    /// was set ([`MotionSim::set_tool_target`]).
    pub fn tool_distance(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        self.t
            .iter()
            .zip(&self.tool)
            .filter(|(_, d)| d.is_finite())
            .map(|(t, d)| [*t, *d])
    }
}

/// The fixed-step simulation of every joint of one robot moving toward a goal.
#[derive(Debug, Clone)]
pub struct MotionSim {
    robot: Robot,
    limits: Vec<MotionLimits>,
    settings: MotionSettings,
    q: Vec<f64>,
    qd: Vec<f64>,
    goal: Vec<f64>,
    error: Vec<f64>,
    integral: Vec<f64>,
    trajectory: Option<Trajectory>,
    t: f64,
    goal_time: f64,
    remainder: f64,
    steps: u64,
    start_error: Vec<f64>,
    overshoot: Vec<f64>,
    last_outside: Vec<f64>,
    tool_target: Option<Vector3<f64>>,
    fk: ForwardKinematics,
    record: Record,
}

impl MotionSim {
    /// A simulation of `robot` at rest at `q`, with the goal `q` (nothing moves until
    /// [`MotionSim::set_goal`]).
    pub fn new(robot: &Robot, q: &[f64], settings: MotionSettings) -> Result<Self, MotionError> {
        robot.check_q(q)?;
        settings.check()?;
        let limits = MotionLimits::of_robot(robot);
        for l in &limits {
            l.check()?;
        }
        let n = robot.dof();
        let fk = ForwardKinematics::new(robot, q)?;
        let mut sim = MotionSim {
            robot: robot.clone(),
            limits,
            settings,
            q: q.to_vec(),
            qd: vec![0.0; n],
            goal: q.to_vec(),
            error: vec![0.0; n],
            integral: vec![0.0; n],
            trajectory: None,
            t: 0.0,
            goal_time: 0.0,
            remainder: 0.0,
            steps: 0,
            start_error: vec![0.0; n],
            overshoot: vec![0.0; n],
            last_outside: vec![0.0; n],
            tool_target: None,
            fk,
            record: Record::new(n, settings.record_capacity, settings.record_every),
        };
        sim.update_error();
        sim.record_sample();
        Ok(sim)
    }

    /// Sets a new goal (the IK answer or a typed q) and starts measuring the response
    /// anew. A joint's goal outside its limits is clamped to them; a wrapping joint's is
    /// wrapped to (−π, π]. The profile controller plans its move from the pose now.
    pub fn set_goal(&mut self, goal: &[f64]) -> Result<(), MotionError> {
        self.robot.check_q(goal)?;
        for ((g, new), joint) in self.goal.iter_mut().zip(goal).zip(&self.robot.joints) {
            *g = if joint.wraps() {
                wrap_to_pi(*new)
            } else {
                joint.limits.clamp(*new)
            };
        }
        self.integral.fill(0.0);
        self.goal_time = self.t;
        self.update_error();
        self.start_error.copy_from_slice(&self.error);
        self.overshoot.fill(0.0);
        self.last_outside.fill(self.t);
        self.trajectory = match self.settings.controller {
            Controller::Profile {
                shape,
                synchronised,
            } => {
                let distances = self.error.clone();
                Some(Trajectory::with_limits(
                    &self.q,
                    &distances,
                    &self.limits,
                    shape,
                    synchronised,
                )?)
            }
            _ => None,
        };
        Ok(())
    }

    /// Changes the controller, plant or record settings (checked first; on an error the
    /// old settings stay). A new record length clears the record. The current goal is
    /// kept; a profile controller plans anew from the pose now.
    pub fn set_settings(&mut self, settings: MotionSettings) -> Result<(), MotionError> {
        settings.check()?;
        let record_changed = settings.record_capacity != self.settings.record_capacity
            || settings.record_every != self.settings.record_every;
        self.settings = settings;
        if record_changed {
            self.record = Record::new(
                self.robot.dof(),
                settings.record_capacity,
                settings.record_every,
            );
        }
        let goal = self.goal.clone();
        self.set_goal(&goal)
    }

    /// Puts the arm at rest at `q` (a jump: dragging a slider, loading a link), with the
    /// goal `q`, and clears the record.
    pub fn reset(&mut self, q: &[f64]) -> Result<(), MotionError> {
        self.robot.check_q(q)?;
        self.q.copy_from_slice(q);
        self.qd.fill(0.0);
        self.record.clear();
        self.set_goal(q)?;
        self.record_sample();
        Ok(())
    }

    /// Sets (or clears) the target point whose distance from the tool the record keeps.
    pub fn set_tool_target(&mut self, target: Option<Vector3<f64>>) {
        self.tool_target = target.filter(|p| p.iter().all(|v| v.is_finite()));
    }

    /// Simulates `dt` seconds (frame time × time scale): runs every whole [`STEP`] in
    /// `dt` plus the remainder kept from earlier calls, at most
    /// [`MAX_STEPS_PER_ADVANCE`] (the time beyond that is dropped), and keeps what is
    /// left below one step. Returns the number of steps run. `dt` = 0 is a pause.
    pub fn advance(&mut self, dt: f64) -> Result<usize, MotionError> {
        check_non_negative(Setting::FrameTime, dt, 3600.0)?;
        let total = self.remainder + dt;
        // The 1e-9 guards against 0.999999… steps from adding frame times.
        let whole = ((total / STEP) + 1e-9).floor();
        let steps = (whole as usize).min(MAX_STEPS_PER_ADVANCE);
        self.remainder = if (whole as usize) > MAX_STEPS_PER_ADVANCE {
            0.0
        } else {
            (total - whole * STEP).max(0.0)
        };
        for _ in 0..steps {
            self.step();
        }
        Ok(steps)
    }

    /// One step of [`STEP`] seconds: the controller's command, the plant's response
    /// (exact first-order lag, or semi-implicit Euler on the mass), then the joint kept
    /// in its range (clamped at a limit, where its speed drops to zero) or wrapped.
    pub fn step(&mut self) {
        let dt = STEP;
        let plant = self.settings.plant;
        // Exact discretisation of τ·q̈ = v_cmd − q̇ over one step.
        let lag = if plant.time_constant > 0.0 {
            1.0 - (-dt / plant.time_constant).exp()
        } else {
            1.0
        };
        let elapsed = self.t + dt - self.goal_time;
        for j in 0..self.q.len() {
            let e = self.error[j];
            let vmax = self.limits[j].max_speed;
            let servo = |qd: f64, v_cmd: f64| qd + (v_cmd - qd) * lag;
            match self.settings.controller {
                Controller::OnOff { dead_band } => {
                    let v_cmd = if e.abs() < dead_band || e == 0.0 {
                        0.0
                    } else {
                        vmax * e.signum()
                    };
                    self.qd[j] = servo(self.qd[j], v_cmd);
                    self.q[j] += self.qd[j] * dt;
                }
                Controller::Proportional { gain } => {
                    let v_cmd = (gain * e).clamp(-vmax, vmax);
                    self.qd[j] = servo(self.qd[j], v_cmd);
                    self.q[j] += self.qd[j] * dt;
                }
                Controller::Pid(g) => {
                    let qd = self.qd[j];
                    let u = g.kp * e + g.ki * self.integral[j] - g.kd * qd;
                    let acc = (u - plant.friction * qd - plant.load) / plant.inertia;
                    let unclamped = qd + acc * dt;
                    let v = unclamped.clamp(-vmax, vmax);
                    // Anti-windup: no integration while the speed limit holds the joint
                    // back in the direction the error pushes.
                    if !(unclamped != v && e.signum() == v.signum()) {
                        self.integral[j] += e * dt;
                    }
                    self.qd[j] = v;
                    self.q[j] += v * dt;
                }
                Controller::Profile { .. } => {
                    if let Some(p) = self.trajectory.as_ref().and_then(|t| t.joints.get(j)) {
                        let s = p.sample(elapsed);
                        self.q[j] = s.q;
                        self.qd[j] = s.qd;
                    }
                }
            }
            let joint = &self.robot.joints[j];
            if joint.wraps() {
                self.q[j] = wrap_to_pi(self.q[j]);
            } else if !joint.limits.contains(self.q[j], 0.0) {
                self.q[j] = joint.limits.clamp(self.q[j]);
                self.qd[j] = 0.0;
            }
        }
        self.t += dt;
        self.steps += 1;
        self.update_error();
        self.measure();
        if self.steps.is_multiple_of(self.settings.record_every as u64) {
            self.record_sample();
        }
    }

    fn update_error(&mut self) {
        for (((e, q), g), joint) in self
            .error
            .iter_mut()
            .zip(&self.q)
            .zip(&self.goal)
            .zip(&self.robot.joints)
        {
            *e = joint_distance_to(joint, *q, *g);
        }
    }

    fn measure(&mut self) {
        for j in 0..self.q.len() {
            let (e, e0) = (self.error[j], self.start_error[j]);
            let past = if e0 == 0.0 { e.abs() } else { -e * e0.signum() };
            self.overshoot[j] = self.overshoot[j].max(past);
            if e.abs() > SETTLING_BAND * e0.abs() {
                self.last_outside[j] = self.t;
            }
        }
    }

    fn record_sample(&mut self) {
        let tool = self.tool_target.map(|target| {
            self.fk.update(&self.robot, &self.q);
            (self.fk.tool_position() - target).norm()
        });
        self.record
            .push(self.t, &self.q, &self.qd, &self.error, tool);
    }

    /// The simulated time (seconds since the simulation started).
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The steps run since the simulation started.
    pub fn steps_run(&self) -> u64 {
        self.steps
    }

    /// The joint values now.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// The joint speeds now.
    pub fn qd(&self) -> &[f64] {
        &self.qd
    }

    /// The goal.
    pub fn goal(&self) -> &[f64] {
        &self.goal
    }

    /// The errors e = goal − q now (wrapped for wrapping joints).
    pub fn error(&self) -> &[f64] {
        &self.error
    }

    /// The settings in force.
    pub fn settings(&self) -> &MotionSettings {
        &self.settings
    }

    /// Every joint's speed and acceleration limits used.
    pub fn limits(&self) -> &[MotionLimits] {
        &self.limits
    }

    /// The planned profile, with the profile controller.
    pub fn trajectory(&self) -> Option<&Trajectory> {
        self.trajectory.as_ref()
    }

    /// The record for the plots.
    pub fn record(&self) -> &Record {
        &self.record
    }

    /// Every joint's response measures since the goal was set.
    pub fn measures(&self) -> Vec<JointMeasures> {
        (0..self.q.len())
            .map(|j| {
                let e0 = self.start_error[j];
                let e = self.error[j];
                let inside = e.abs() <= SETTLING_BAND * e0.abs();
                JointMeasures {
                    start_error: e0,
                    overshoot: self.overshoot[j],
                    overshoot_ratio: (e0 != 0.0).then(|| self.overshoot[j] / e0.abs()),
                    settling_time: inside.then(|| self.last_outside[j] - self.goal_time),
                    error: e,
                }
            })
            .collect()
    }

    /// Whether every joint is at rest (|q̇| ≤ `speed_tol`) within `error_tol` of its goal.
    pub fn at_rest(&self, error_tol: f64, speed_tol: f64) -> bool {
        self.error.iter().all(|e| e.abs() <= error_tol)
            && self.qd.iter().all(|v| v.abs() <= speed_tol)
    }
}
