//! The model's paths and waypoints (docs/kinematics.md §19): the path kind, the
//! waypoint list, the planned paths and a visit of the waypoints.

use nalgebra::IsometryMatrix3;

use crate::app::state::path_lab::PathLab;

use super::{Message, Model};

impl Model {
    /// The path kind, the waypoints, the planned paths and the visit.
    pub fn paths(&self) -> &PathLab {
        &self.paths
    }

    /// Chooses how the arm goes from one pose to the next.
    pub fn set_path_kind(&mut self, kind: armlab_core::path::PathKind) {
        self.paths.set_kind(kind);
    }

    /// Draws both planned paths in 3D, or stops.
    pub fn set_paths_shown(&mut self, shown: bool) {
        self.paths.set_shown(shown);
    }

    /// Stores the target's pose as the last waypoint.
    pub fn add_waypoint(&mut self) -> Result<(), armlab_core::motion::MotionError> {
        self.paths.waypoints_mut().push(self.target)
    }

    /// Replaces waypoint `index` (0-based); on an error the old pose stays.
    pub fn set_waypoint(
        &mut self,
        index: usize,
        pose: IsometryMatrix3<f64>,
    ) -> Result<(), armlab_core::motion::MotionError> {
        self.paths.waypoints_mut().set(index, pose).map(|_| ())
    }

    /// Removes waypoint `index` (0-based); a visit under way ends.
    pub fn remove_waypoint(&mut self, index: usize) {
        self.paths.stop_visit();
        self.paths.waypoints_mut().remove(index);
    }

    /// Plans the drawn paths anew when the arm, the target or the waypoints changed.
    pub fn update_path_plan(&mut self) {
        self.paths.update_plan(
            &self.robot,
            &self.q,
            &self.target,
            self.robot_changes,
            &mut self.solver,
        );
    }

    /// Turns "move" on and drives the arm through every waypoint in order along the
    /// chosen path kind.
    pub fn visit_waypoints(&mut self) -> Result<(), armlab_core::motion::MotionError> {
        self.set_motion_on(true);
        self.motion.sync(&self.robot, &self.q, self.robot_changes);
        let goal =
            self.paths
                .start_visit(&self.robot, &self.q, self.robot_changes, &mut self.solver)?;
        if let Some(goal) = goal {
            self.motion.clear_trail();
            self.motion.set_goal(&goal, None)?;
        }
        Ok(())
    }

    /// Takes the link's path kind and waypoints (a link without them has none, and goes
    /// in joint space).
    pub(super) fn open_paths(&mut self, patch: &armlab_session::motion::MotionPatch) {
        self.paths.stop_visit();
        self.paths.set_kind(patch.path_kind.unwrap_or_default());
        let poses = patch.waypoints.clone().unwrap_or_default();
        *self.paths.waypoints_mut() = armlab_core::path::Waypoints::new(poses).unwrap_or_default();
    }

    /// Says which parts of a link were left out (at most three reasons, then how many
    /// more), or nothing when none was.
    pub(super) fn say_left_out(&mut self, mut reasons: Vec<String>) {
        if reasons.is_empty() {
            return;
        }
        let lang = self.settings.lang;
        if reasons.len() > 3 {
            let more = reasons.len() - 3;
            reasons.truncate(3);
            reasons.push(armlab_text::fill(
                lang,
                armlab_text::Key::PathMoreIssues,
                &[&more],
            ));
        }
        self.message = Some(Message::warning(armlab_text::fill(
            lang,
            armlab_text::Key::LinkPartDropped,
            &[&reasons.join("; ")],
        )));
    }

    /// A frame of a visit: the simulation runs in slices of 5 ms of real time, and after
    /// each the goal moves on along the visit's path; the arm takes the frame's end.
    pub(super) fn advance_visit(&mut self, real_dt: f64) -> usize {
        let mut steps = 0;
        let mut left = real_dt;
        let mut moved = None;
        while left > 1e-9 {
            let dt = left.min(0.005);
            left -= dt;
            if let Some(q) = self.motion.advance(dt) {
                steps += self.motion.steps_last_frame();
                self.follow_visit(&q);
                moved = Some(q);
            }
        }
        if let Some(q) = moved {
            self.take_motion_q(q);
        }
        steps
    }

    /// Moves the visit's goal on once the arm is at `q`.
    pub(super) fn follow_visit(&mut self, q: &[f64]) {
        let Some(sim) = self.motion.sim() else {
            return;
        };
        let band = match sim.settings().controller {
            armlab_core::motion::Controller::OnOff { dead_band } => dead_band,
            _ => 0.0,
        }
        .max(crate::app::state::path_lab::STOP_ERROR);
        let arrived = sim.error().iter().all(|e| e.abs() <= band);
        if let Some(goal) = self.paths.follow(&self.robot, q, arrived) {
            let _ = self.motion.set_goal(&goal, None);
        }
    }
}
