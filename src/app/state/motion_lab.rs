//! The motion lab's state in the app (docs/kinematics.md §20.2): whether "move" is on,
//! the controller and plant settings, the time scale, the core's [`MotionSim`] that drives
//! the arm, and the tool's trail for the 3D view. No egui and no clock here: the model owns one
//! [`MotionLab`] and passes it the frame's time; the Motion panel
//! draws it.

pub use crate::app::platform::checker::CheckerState;
use std::collections::VecDeque;

use nalgebra::{IsometryMatrix3, Point3};

use armlab_core::collision::{
    CollisionChecker, CollisionReport, KeepOut, Obstacle, TOUCH_TOLERANCE,
};
use armlab_core::parts::{Part, robot_parts};
use armlab_text::Lang;

use armlab_core::motion::{MotionError, MotionSettings, MotionSim, check_time_scale};
use armlab_core::{ForwardKinematics, Robot};

/// The most tool positions the trail keeps (the oldest are dropped).
pub const TRAIL_POINTS: usize = 4000;
/// A joint is at rest within this error (rad or units; well inside the "reached"
/// tolerance of the tool, so the target turns green before the page stops drawing) …
pub const REST_ERROR: f64 = 1e-7;
/// … and below this speed (rad/s or units/s).
pub const REST_SPEED: f64 = 1e-3;
/// The slow-motion time scale (one simulated second takes ten real ones).
pub const SLOW_MOTION: f64 = 0.1;

/// The motion lab's state.
#[derive(Debug, Clone)]
pub struct MotionLab {
    on: bool,
    settings: MotionSettings,
    time_scale: f64,
    sim: Option<MotionSim>,
    /// The model's robot-change count the simulation was built for.
    built_for: u64,
    /// The target the current goal was solved for (a drag solves again when it moves).
    goal_target: Option<IsometryMatrix3<f64>>,
    trail: VecDeque<Point3<f64>>,
    steps_last_frame: usize,
    collisions: Collisions,
}

/// The collision check of the page: on or off, the keep-out boxes, the checker for the
/// robot, and the last report.
#[derive(Debug, Clone, Default)]
struct Collisions {
    on: bool,
    keep_outs: Vec<KeepOut>,
    checker: Option<CollisionChecker>,
    /// The robot-change count the checker was set up for.
    built_for: u64,
    /// The joint values last checked.
    checked_q: Vec<f64>,
    report: CollisionReport,
    /// The first contact of the last report, as a sentence.
    sentence: Option<String>,
    last_free: Option<Vec<f64>>,
}

impl Default for MotionLab {
    fn default() -> Self {
        MotionLab {
            on: false,
            settings: MotionSettings::default(),
            time_scale: 1.0,
            sim: None,
            built_for: u64::MAX,
            goal_target: None,
            trail: VecDeque::new(),
            steps_last_frame: 0,
            collisions: Collisions::default(),
        }
    }
}

impl MotionLab {
    /// Whether "move" is on: the arm drives to each IK answer instead of jumping.
    pub fn on(&self) -> bool {
        self.on
    }

    /// The controller and plant settings in force (the last good ones).
    pub fn settings(&self) -> &MotionSettings {
        &self.settings
    }

    /// Simulated seconds per real second: 1 real time, [`SLOW_MOTION`], 0 paused.
    pub fn time_scale(&self) -> f64 {
        self.time_scale
    }

    /// The simulation, once "move" has run on this robot.
    pub fn sim(&self) -> Option<&MotionSim> {
        self.sim.as_ref()
    }

    /// The tool's positions as it moved, oldest first.
    pub fn trail(&self) -> &VecDeque<Point3<f64>> {
        &self.trail
    }

    /// The simulation steps run in the last frame.
    pub fn steps_last_frame(&self) -> usize {
        self.steps_last_frame
    }

    /// Whether the arm is still on its way and the time runs: a joint moves, or is
    /// farther from its goal than [`REST_ERROR`] (than the dead band, for on/off control,
    /// which stops anywhere inside it).
    pub fn moving(&self) -> bool {
        let Some(sim) = self
            .sim
            .as_ref()
            .filter(|_| self.on && self.time_scale > 0.0)
        else {
            return false;
        };
        let band = match sim.settings().controller {
            armlab_core::motion::Controller::OnOff { dead_band } => dead_band.max(REST_ERROR),
            _ => REST_ERROR,
        };
        sim.qd().iter().any(|v| v.abs() > REST_SPEED) || sim.error().iter().any(|e| e.abs() > band)
    }

    /// Turns "move" on or off (off drops the simulation; the arm stays where it is).
    pub fn set_on(&mut self, on: bool) {
        self.on = on;
        if !on {
            self.sim = None;
            self.goal_target = None;
        }
    }

    /// Takes new settings when they pass the core's checks; otherwise the old ones stay
    /// and the error says why.
    pub fn set_settings(&mut self, settings: MotionSettings) -> Result<(), MotionError> {
        settings.check()?;
        if let Some(sim) = self.sim.as_mut() {
            sim.set_settings(settings)?;
        }
        self.settings = settings;
        Ok(())
    }

    /// Takes a time scale from 0 (pause) to 10; otherwise the old one stays.
    pub fn set_time_scale(&mut self, scale: f64) -> Result<(), MotionError> {
        self.time_scale = check_time_scale(scale)?;
        Ok(())
    }

    /// The simulation for this robot at `q`: built anew for a new robot, reset when
    /// something else moved the arm (a slider, a link), kept otherwise.
    pub fn sync(&mut self, robot: &Robot, q: &[f64], robot_changes: u64) {
        let fresh = self.built_for != robot_changes || self.sim.is_none();
        if fresh {
            self.sim = MotionSim::new(robot, q, self.settings).ok();
            self.built_for = robot_changes;
            self.goal_target = None;
            self.trail.clear();
        } else if let Some(sim) = self.sim.as_mut()
            && sim.q() != q
            && sim.reset(q).is_ok()
        {
            self.goal_target = None;
            self.trail.clear();
        }
    }

    /// The target the goal was last solved for.
    pub fn goal_target(&self) -> Option<&IsometryMatrix3<f64>> {
        self.goal_target.as_ref()
    }

    /// Sets the goal (an IK answer for `target`, or a typed q with no target).
    pub fn set_goal(
        &mut self,
        goal: &[f64],
        target: Option<IsometryMatrix3<f64>>,
    ) -> Result<(), MotionError> {
        let Some(sim) = self.sim.as_mut() else {
            return Ok(());
        };
        sim.set_goal(goal)?;
        sim.set_tool_target(target.map(|t| t.translation.vector));
        self.goal_target = target;
        Ok(())
    }

    /// Simulates `real_dt` seconds of real time × the time scale; returns the joint
    /// values when any step ran.
    pub fn advance(&mut self, real_dt: f64) -> Option<Vec<f64>> {
        self.steps_last_frame = 0;
        let sim = self.sim.as_mut()?;
        let steps = sim.advance(real_dt * self.time_scale).ok()?;
        self.steps_last_frame = steps;
        (steps > 0).then(|| sim.q().to_vec())
    }

    /// One step of the record's spacing (10 ms by default) whatever the time scale: the
    /// single step of a paused simulation. Returns the joint values.
    pub fn single_step(&mut self) -> Option<Vec<f64>> {
        let every = self.settings.record_every;
        let sim = self.sim.as_mut()?;
        for _ in 0..every {
            sim.step();
        }
        self.steps_last_frame = every;
        Some(sim.q().to_vec())
    }

    /// Adds the tool's position to the trail when it moved.
    pub fn note_tool(&mut self, tool: Point3<f64>, min_move: f64) {
        if self
            .trail
            .back()
            .is_none_or(|last| (last - tool).norm() > min_move)
        {
            if self.trail.len() == TRAIL_POINTS {
                self.trail.pop_front();
            }
            self.trail.push_back(tool);
        }
    }

    /// Forgets the trail.
    pub fn clear_trail(&mut self) {
        self.trail.clear();
    }

    /// Puts the simulation back at rest at `q` (the last collision-free pose).
    pub fn stop_at(&mut self, q: &[f64]) {
        if let Some(sim) = self.sim.as_mut() {
            let _ = sim.reset(q);
        }
        self.goal_target = None;
    }

    /// Whether collisions are checked.
    pub fn collisions_on(&self) -> bool {
        self.collisions.on
    }

    /// Checks collisions (or stops checking; the red parts go). In the page the checks run
    /// in the lazily loaded module, which the first check of the visit starts loading.
    pub fn set_collisions_on(&mut self, on: bool) {
        #[cfg(target_arch = "wasm32")]
        if on && !self.collisions.on {
            // A module that failed to load is fetched again when the checks go on again.
            crate::app::platform::web::modules::retry_collision_module();
        }
        self.collisions.on = on;
        self.collisions.checked_q.clear();
        self.collisions.report = CollisionReport::default();
        self.collisions.sentence = None;
        self.collisions.last_free = None;
    }

    /// The keep-out boxes.
    pub fn keep_outs(&self) -> &[KeepOut] {
        &self.collisions.keep_outs
    }

    /// Replaces the keep-out boxes (checked by the core when built).
    pub fn set_keep_outs(&mut self, boxes: Vec<KeepOut>) -> Result<(), MotionError> {
        let floor = self.collisions.checker.as_ref().is_none_or(|c| c.floor);
        let checker = CollisionChecker::new(floor, boxes.clone())?;
        self.collisions.keep_outs = boxes;
        if self.collisions.checker.is_some() {
            self.collisions.checker = Some(checker);
        }
        self.collisions.checked_q.clear();
        Ok(())
    }

    /// One flag per part of the arm (the renderer's part order): whether it touches
    /// something in the last check.
    pub fn colliding(&self) -> &[bool] {
        &self.collisions.report.colliding
    }

    /// The last contact, as a sentence ("Contact: link 5 touches the base.").
    pub fn contact(&self) -> Option<&str> {
        self.collisions.sentence.as_deref()
    }

    /// Checks the pose `q` (its frames `fk`) when collisions are on and `q` was not the
    /// last pose checked; returns whether it is free. A free pose becomes the last
    /// collision-free pose. While the page's collision module loads (or when it could not
    /// be loaded) nothing is checked and the pose counts as free.
    pub fn check(
        &mut self,
        robot: &Robot,
        q: &[f64],
        fk: &ForwardKinematics,
        robot_changes: u64,
        lang: Lang,
    ) -> bool {
        if !self.collisions.on || !self.collisions.set_up(robot, robot_changes) {
            return true;
        }
        let c = &mut self.collisions;
        if c.checked_q == q {
            return c.report.is_free();
        }
        let Some(checker) = c.checker.as_mut() else {
            return true;
        };
        let Some(report) = checker.check_with(robot, fk, check_parts) else {
            return true;
        };
        c.report = report;
        c.sentence = armlab_text::contact_sentence(&c.report, checker.parts(), lang);
        c.checked_q = q.to_vec();
        let free = c.report.is_free();
        if free {
            c.last_free = Some(q.to_vec());
        }
        free
    }

    /// The last collision-free pose checked.
    pub fn last_free(&self) -> Option<&[f64]> {
        self.collisions.last_free.as_deref()
    }

    /// After a blocked move back to `q`: the red parts stay those of the blocked pose
    /// until the arm moves again.
    pub fn keep_report_at(&mut self, q: &[f64]) {
        self.collisions.checked_q = q.to_vec();
    }
}

impl Collisions {
    /// Sets up the checker for the robot (once per robot change): the floor is left out
    /// for an arm that lies on it at home (the planar 2R drawn in the plane z = 0).
    /// Whether the checker is ready (not while the page's module loads).
    fn set_up(&mut self, robot: &Robot, robot_changes: u64) -> bool {
        if self.checker.is_some() && self.built_for == robot_changes {
            return true;
        }
        let Ok(mut checker) = CollisionChecker::new(true, self.keep_outs.clone()) else {
            return false;
        };
        if let Ok(home) = ForwardKinematics::new(robot, &robot.home()) {
            let parts = robot_parts(robot, &home);
            let Some(report) = check_parts(&checker, &parts, TOUCH_TOLERANCE * robot.reach())
            else {
                return false;
            };
            checker.floor = !report.contacts.iter().any(|k| k.other == Obstacle::Floor);
        }
        self.checker = Some(checker);
        self.built_for = robot_changes;
        self.checked_q.clear();
        self.last_free = None;
        true
    }
}

/// Where the collision check runs: natively the core's; in the page the lazily loaded
/// module's (`None` while it loads or when it could not be loaded, see [`checker_state`]).
fn check_parts(
    checker: &CollisionChecker,
    parts: &[Part],
    tolerance: f64,
) -> Option<CollisionReport> {
    #[cfg(target_arch = "wasm32")]
    {
        crate::app::platform::web::modules::collide_parts(checker, parts, tolerance)
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        Some(checker.check_parts(parts, tolerance))
    }
}

/// The state of the code that checks collisions.
pub fn checker_state() -> CheckerState {
    #[cfg(target_arch = "wasm32")]
    {
        crate::app::platform::web::modules::collision_module_state()
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        CheckerState::Ready
    }
}
