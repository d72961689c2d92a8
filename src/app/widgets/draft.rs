//! A number field's draft: the text while it is typed, kept apart from the value it sets.

/// A field's text while it is typed, and its sentence when the text is refused.
#[derive(Debug, Clone, Default)]
pub(crate) struct Draft {
    pub(crate) text: String,
    pub(crate) error: Option<String>,
}

/// The robot as it was when the focus came to a table cell: while the cell's text is
/// refused, the arm shows this one rather than a value typed on the way ("1" of "1e999").
/// Leaving the cell (Enter, a click elsewhere) makes the robot then the new one.
#[derive(Debug, Clone, Default)]
pub(crate) struct Baseline {
    focus: Option<egui::Id>,
    robot: Option<(armlab_core::Robot, armlab_session::session::RobotSource)>,
}

impl Baseline {
    /// Takes the model's robot as the baseline when the focus moved since the last frame.
    pub(crate) fn track(&mut self, ui: &egui::Ui, model: &crate::app::state::model::Model) {
        let focus = ui.memory(|m| m.focused());
        if focus != self.focus || self.robot.is_none() {
            self.focus = focus;
            self.robot = Some((model.robot().clone(), model.source().clone()));
        }
    }

    /// Puts the baseline robot back when a refused text left another robot in place (a
    /// table of `rows` joints: one whose joint count changed since keeps its robot).
    pub(crate) fn restore(&self, model: &mut crate::app::state::model::Model, rows: usize) {
        if let Some((robot, source)) = &self.robot
            && robot != model.robot()
            && robot.dof() == rows
            && model.robot().dof() == rows
        {
            model.edit_robot(robot.clone(), source.clone());
        }
    }
}
