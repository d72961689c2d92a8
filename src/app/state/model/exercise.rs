//! The model's edits that keep the arm, and the DH-table exercise
//! (docs/kinematics.md §14.3, §15): starting it, checking a table, ending it.

use armlab_core::Robot;

use armlab_core::exercise::Verdict;
use armlab_session::exercise::ExerciseId;
use armlab_session::session::RobotSource;

use super::Model;
use crate::app::platform;
use crate::app::platform::exercise::Checked;

/// An open DH-table exercise (docs/kinematics.md §15): the model's robot is its reference,
/// whose table stays hidden until a checked table is right.
#[derive(Debug, Clone, PartialEq)]
pub struct ExerciseState {
    /// The exercise's robot, as the link names it.
    pub id: ExerciseId,
    /// The answer of the last check, if any.
    pub verdict: Option<Verdict>,
    /// A check said "correct": the robot's table shows everywhere again.
    pub solved: bool,
    /// The table being checked: in the page the check runs in the lazily loaded module,
    /// and its verdict comes a few frames later ([`Model::poll_exercise_check`]).
    pub checking: Option<Robot>,
    /// The last check could not run (the module did not load): the browser's words.
    pub check_failed: Option<String>,
}

impl ExerciseState {
    /// The exercise `id` as it opens: nothing checked yet.
    pub fn open(id: ExerciseId) -> Self {
        ExerciseState {
            id,
            verdict: None,
            solved: false,
            checking: None,
            check_failed: None,
        }
    }
}

impl Model {
    /// Swaps in a robot whose joint count the DH editor changed (a joint added or
    /// removed), at the joint vector the edit kept (`kinematics::edit::insert_joint`,
    /// `remove_joint`: every other joint keeps its value), each value clamped to its
    /// joint's limits. The view frames the arm anew and the target moves onto the tool,
    /// as for any change of the joint count.
    pub fn edit_robot_with_q(&mut self, robot: Robot, source: RobotSource, q: Vec<f64>) {
        self.edit_robot(robot, source);
        self.set_q_exact(q);
        self.snap_target();
    }

    /// The open DH-table exercise, if any.
    pub fn exercise(&self) -> Option<&ExerciseState> {
        self.exercise.as_ref()
    }

    /// Whether the robot's DH table must not show (an exercise is open and not yet
    /// solved): the matrices, the frames and both-conventions views stay hidden.
    pub fn table_hidden(&self) -> bool {
        self.exercise.as_ref().is_some_and(|e| !e.solved)
    }

    /// Starts an exercise: its robot becomes the model's robot (at its home pose, its
    /// table hidden).
    pub fn start_exercise(&mut self, id: ExerciseId) -> Result<(), armlab_core::RobotError> {
        let robot = id.robot()?;
        self.load_robot(robot, RobotSource::Custom);
        self.exercise = Some(ExerciseState::open(id));
        Ok(())
    }

    /// Grades a student's table against the exercise's robot (`check_table`); a correct
    /// one solves the exercise. The verdict, or `None` when no exercise is open or, in the
    /// page, until the lazily loaded module has answered ([`Model::poll_exercise_check`]).
    pub fn check_exercise(&mut self, student: &Robot) -> Option<Verdict> {
        let exercise = self.exercise.as_mut()?;
        if exercise.check_failed.take().is_some() {
            platform::exercise::retry_check();
        }
        exercise.verdict = None;
        exercise.checking = Some(student.clone());
        self.poll_exercise_check()
    }

    /// Takes the verdict of the table being checked once it is there (called every frame
    /// the exercise is shown; nothing to do while no check is under way).
    pub fn poll_exercise_check(&mut self) -> Option<Verdict> {
        let exercise = self.exercise.as_mut()?;
        let student = exercise.checking.as_ref()?;
        match platform::exercise::check_table(&self.robot, student) {
            Checked::Ready(verdict) => {
                exercise.checking = None;
                exercise.verdict = Some(verdict);
                exercise.solved |= verdict == Verdict::Correct;
                Some(verdict)
            }
            Checked::Loading => None,
            Checked::Failed(why) => {
                exercise.checking = None;
                exercise.check_failed = Some(why);
                None
            }
        }
    }

    /// Ends the exercise: the robot stays, with its own names again, and its table shows
    /// everywhere (the DH editor takes it).
    pub fn end_exercise(&mut self) {
        let Some(exercise) = self.exercise.take() else {
            return;
        };
        if let Ok(original) = exercise.id.original_robot() {
            self.robot.name = original.name;
            self.robot.description = original.description;
            for (joint, named) in self.robot.joints.iter_mut().zip(original.joints) {
                joint.name = named.name;
            }
        }
        if let ExerciseId::Preset(id) = exercise.id {
            self.source = RobotSource::Preset(id);
        }
        self.loads += 1;
        self.robot_changes += 1;
    }
}
