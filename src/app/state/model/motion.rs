//! The model's motion lab (docs/kinematics.md §17): "move", the controller, the
//! simulation's steps, the trail, keep-out boxes and the stop at a collision.

use armlab_text::Sentence;
use nalgebra::Point3;

use armlab_core::ik::{IkSettings, Reach};

use crate::app::state::motion_lab::MotionLab;

use super::{Message, Model};

impl Model {
    /// The motion lab: "move", its controller, the simulation and the tool's trail.
    pub fn motion(&self) -> &MotionLab {
        &self.motion
    }

    /// Turns "move" on (the arm drives to each IK answer with the controller) or off (it
    /// jumps to each answer).
    pub fn set_motion_on(&mut self, on: bool) {
        self.motion.set_on(on);
        if on {
            self.motion.sync(&self.robot, &self.q, self.robot_changes);
        }
    }

    /// Takes the motion settings when they pass the core's checks; otherwise the last
    /// good ones stay and the error says why.
    pub fn set_motion_settings(
        &mut self,
        settings: armlab_core::motion::MotionSettings,
    ) -> Result<(), armlab_core::motion::MotionError> {
        self.motion.set_settings(settings)
    }

    /// Takes a time scale (0 pauses, 1 is real time, at most 10).
    pub fn set_time_scale(&mut self, scale: f64) -> Result<(), armlab_core::motion::MotionError> {
        self.motion.set_time_scale(scale)
    }

    /// Drives the arm to a typed joint vector (with "move" on).
    pub fn set_motion_goal(
        &mut self,
        goal: &[f64],
    ) -> Result<(), armlab_core::motion::MotionError> {
        self.paths.stop_visit();
        self.motion.sync(&self.robot, &self.q, self.robot_changes);
        self.motion.set_goal(goal, None)
    }

    /// Takes the motion lab's fields a link names (already checked by the link parser).
    pub(super) fn open_motion(&mut self, patch: &armlab_session::motion::MotionPatch) {
        if let Some(settings) = patch.settings {
            let _ = self.motion.set_settings(settings);
        }
        if let Some(scale) = patch.time_scale {
            let _ = self.motion.set_time_scale(scale);
        }
        if let Some(boxes) = &patch.keep_outs {
            let _ = self.motion.set_keep_outs(boxes.clone());
        }
        if let Some(on) = patch.collisions {
            self.motion.set_collisions_on(on);
        }
        if let Some(on) = patch.move_on {
            self.set_motion_on(on);
        }
        self.open_paths(patch);
    }

    /// Sets the simulation's goal to an IK answer of the target.
    pub(super) fn drive_to(&mut self, mut goal: Vec<f64>, unreachable: bool) {
        self.paths.stop_visit();
        self.motion.sync(&self.robot, &self.q, self.robot_changes);
        goal.resize(self.robot.dof(), 0.0);
        self.robot.keep_q(&mut goal, &self.q);
        if let Err(e) = self.motion.set_goal(&goal, Some(self.target)) {
            self.message = Some(Message::error(e.sentence(self.settings.lang)));
        }
        if unreachable && self.ik.reach != Reach::Reached {
            self.ik.reach = Reach::OutOfReach;
        }
    }

    /// A drag frame with "move" on: when the target moved since the goal was solved, a
    /// full solve warm-started at the current goal gives the new goal.
    pub(super) fn motion_drag(&mut self) -> bool {
        self.motion.sync(&self.robot, &self.q, self.robot_changes);
        if self.motion.goal_target() == Some(&self.target) {
            return false;
        }
        let start = self
            .motion
            .sim()
            .map_or_else(|| self.q.clone(), |s| s.goal().to_vec());
        let settings = IkSettings {
            restarts: 0,
            max_iterations: 300,
            budget: 300,
            ..IkSettings::default()
        };
        let result = self.solver.solve(
            &self.robot,
            &self.target,
            self.task,
            &start,
            self.method,
            &settings,
        );
        match result {
            Ok(result) => {
                self.ik.iterations = result.iterations;
                self.drive_to(result.q, result.unreachable);
            }
            Err(e) => self.message = Some(Message::error(e.sentence(self.settings.lang))),
        }
        true
    }

    /// Runs the simulation for `real_dt` seconds of real time (× the time scale) and
    /// moves the arm where it got to; returns the steps run.
    pub fn advance_motion(&mut self, real_dt: f64) -> usize {
        if !self.motion.on() {
            return 0;
        }
        if !self.paths.visiting_at(&self.q, self.robot_changes) {
            self.paths.stop_visit();
        }
        self.motion.sync(&self.robot, &self.q, self.robot_changes);
        if self.paths.visit().is_some() {
            return self.advance_visit(real_dt);
        }
        if let Some(q) = self.motion.advance(real_dt) {
            self.take_motion_q(q);
        }
        self.motion.steps_last_frame()
    }

    /// One step of the record's spacing (10 ms), for a paused simulation.
    pub fn step_motion(&mut self) {
        if !self.motion.on() {
            return;
        }
        self.motion.sync(&self.robot, &self.q, self.robot_changes);
        if let Some(q) = self.motion.single_step() {
            self.follow_visit(&q);
            self.take_motion_q(q);
        }
    }

    /// Forgets the tool's trail.
    pub fn clear_trail(&mut self) {
        self.motion.clear_trail();
    }

    /// Moves the arm to where the simulation got, as it is (no turn re-mapping: the
    /// simulation keeps its joints in range).
    pub(super) fn take_motion_q(&mut self, q: Vec<f64>) {
        self.q = q;
        self.recompute_kinematics();
        self.recompute_reach();
        self.stop_at_collision();
        let tool = Point3::from(self.fk.tool_position());
        self.motion.note_tool(tool, self.robot.reach() * 1e-4);
    }

    /// Turns the collision check on or off.
    pub fn set_collisions_on(&mut self, on: bool) {
        self.motion.set_collisions_on(on);
        self.update_collisions();
    }

    /// Replaces the keep-out boxes; on an error the old ones stay.
    pub fn set_keep_outs(
        &mut self,
        boxes: Vec<armlab_core::collision::KeepOut>,
    ) -> Result<(), armlab_core::motion::MotionError> {
        self.motion.set_keep_outs(boxes)?;
        self.update_collisions();
        Ok(())
    }

    /// Checks the pose now (when collisions are on and the arm moved since the last
    /// check), so touching parts show red whatever moved the arm.
    pub fn update_collisions(&mut self) {
        self.motion.check(
            &self.robot,
            &self.q,
            &self.fk,
            self.robot_changes,
            self.settings.lang,
        );
    }

    /// Checks the pose now; when it collides and a collision-free pose is known, moves
    /// the arm back there, stops the motion and says which parts touch (the drag IK and
    /// the motion stop at the last collision-free pose).
    pub(super) fn stop_at_collision(&mut self) {
        let lang = self.settings.lang;
        if self
            .motion
            .check(&self.robot, &self.q, &self.fk, self.robot_changes, lang)
        {
            return;
        }
        let Some(back) = self.motion.last_free().map(<[f64]>::to_vec) else {
            return;
        };
        if back == self.q {
            return;
        }
        let contact = self.motion.contact().unwrap_or_default().to_string();
        self.q = back;
        self.recompute_kinematics();
        self.recompute_reach();
        self.motion.stop_at(&self.q);
        self.motion.keep_report_at(&self.q);
        self.message = Some(Message::warning(armlab_text::fill(
            lang,
            armlab_text::Key::CollisionStopped,
            &[&contact],
        )));
    }
}
