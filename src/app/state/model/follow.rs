//! A student's page showing the lecturer's session (the lecture room).

use armlab_session::session::Session;

use super::Model;

impl Model {
    /// Whether the matrices hide the entries chosen for predicting ([`Settings::hidden`]):
    /// in presentation mode, and on a student's page in a lecture room (whose layout is
    /// the student's own).
    ///
    /// [`Settings::hidden`]: armlab_session::settings::Settings::hidden
    pub fn hides_entries(&self) -> bool {
        self.settings.presentation || self.room_hides
    }

    /// Hides the chosen entries as presentation mode does (a student's page in a class).
    pub fn set_room_hides(&mut self, on: bool) {
        self.room_hides = on;
    }

    /// Shows the lecturer's `session` as a following student's page: the robot, joints,
    /// target, task, method, display settings, overlays, presentation's hidden entries,
    /// waypoints and, when it names one, the camera. The student's own language, layout
    /// and presentation mode stay (a phone is not a projector). The same robot keeps
    /// everything else (the view is not framed anew twenty times a second during the
    /// lecturer's drag); another robot opens as a link does.
    pub fn follow(&mut self, mut session: Session) {
        session.display.lang = None;
        session.display.presentation = None;
        session.display.panels = None;
        session.display.presentation_panels = None;
        let exercise = self.exercise.as_ref().map(|e| &e.id);
        if session.robot != self.robot
            || session.source != self.source
            || session.exercise.as_ref() != exercise
        {
            return self.open(session);
        }
        session.display.apply(&mut self.settings);
        if session.camera.is_some() && session.camera != self.camera {
            self.camera = session.camera;
            self.camera_loads += 1;
        }
        self.task = session.task;
        self.method = session.method;
        self.keep_method_available();
        self.q = session.q;
        self.q.resize(self.robot.dof(), 0.0);
        self.recompute_kinematics();
        self.target = session.target.unwrap_or(self.fk.base_from_tool);
        self.recompute_reach();
        // Compared as the link writes them: a link leaves out what is at its default.
        if session.motion.to_parts() != self.session().motion.to_parts() {
            self.open_motion(&session.motion);
        }
    }
}

#[cfg(test)]
mod tests {
    use armlab_session::session::Session;
    use armlab_text::Lang;

    use super::Model;

    /// The lecturer's UR10 at `q2`, in English, in presentation mode.
    fn lecturer(q2: f64) -> Session {
        let mut lecturer = Model::new(Session::default_session());
        let mut q = lecturer.q().to_vec();
        q[1] = q2;
        lecturer.set_q_exact(q);
        lecturer.set_presentation(true);
        lecturer.set_lang(Lang::En);
        let hash = lecturer.hash();
        Session::from_hash(&hash)
            .ok()
            .flatten()
            .expect("the link reads")
    }

    #[test]
    fn a_student_follows_the_pose_without_reframing_and_keeps_their_language_and_layout() {
        let mut student = Model::new(Session::default_session());
        student.set_lang(Lang::Fi);
        let reframes = student.reframes();
        for step in 0..20 {
            let q2 = -1.2 + 0.05 * f64::from(step);
            let session = lecturer(q2);
            let target = session.target.expect("the link has a target");
            student.follow(session);
            assert!((student.q()[1] - q2).abs() < 1e-9);
            let moved = student.target().translation.vector - target.translation.vector;
            assert!(moved.norm() < 1e-9, "the target came with the state");
        }
        assert_eq!(student.reframes(), reframes, "the view was framed anew");
        assert_eq!(student.settings().lang, Lang::Fi);
        assert!(!student.settings().presentation);
    }

    #[test]
    fn another_robot_opens_as_a_link_does() {
        let mut student = Model::new(Session::default_session());
        let puma = Session::for_preset("puma560").expect("a preset");
        let reframes = student.reframes();
        student.follow(puma);
        assert_eq!(student.robot().dof(), 6);
        assert_ne!(student.reframes(), reframes);
        assert_eq!(student.hash().split('&').next(), Some("robot=puma560"));
    }
}
