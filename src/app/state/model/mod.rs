//! The app's one model: the session (robot, joint vector, target, task, method), the
//! display settings, and what is derived from them (forward kinematics, the Jacobian, the
//! IK status). Its methods are the only writers: a panel reads the model and calls a
//! method to change it; derived values are recomputed exactly when their inputs change
//! (FK and the Jacobian when q or the robot changes; the IK status when q, the robot, the
//! target or the task changes). No egui here: the model is tested without a window.

use nalgebra::{IsometryMatrix3, Matrix3xX, Matrix6xX, Vector3};

use armlab_core::ik::{
    Branch, IkSolver, REACHED_ORIENTATION_TOLERANCE, REACHED_POSITION_TOLERANCE_M, Reach,
    closed_form_family, pose_error,
};
use armlab_core::workspace::WorkspaceCloud;
use armlab_core::{
    ForwardKinematics, IkMethod, Robot, Task, geometric_jacobian_into, linear_motion_space,
    lost_direction,
};

use crate::app::state::motion_lab::MotionLab;
use crate::app::state::path_lab::PathLab;
use armlab_session::session::{RobotSource, Session};
pub use armlab_session::settings::Settings;
use armlab_session::settings::{CameraPose, DisplayPatch, Overlay};

mod display;
mod drag;
mod exercise;
mod explore;
mod follow;

pub use drag::{Replay, Rescue};
pub use exercise::ExerciseState;
pub use explore::{DIRECTION_SAMPLES, DirectionSphere};
mod motion;
mod paths;
#[cfg(test)]
mod robot_change_tests;
#[cfg(test)]
mod tests;

/// The IK state as the user sees it: the marker's colour and the IK panel's numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IkStatus {
    /// Reached, out of reach or pending.
    pub reach: Reach,
    /// Position error (robot units) of the tool against the target.
    pub position_error: f64,
    /// Orientation error (radians) for the task's rows.
    pub orientation_error: f64,
    /// Iterations of the last solve or drag step.
    pub iterations: usize,
}

impl Default for IkStatus {
    fn default() -> Self {
        IkStatus {
            reach: Reach::Pending,
            position_error: 0.0,
            orientation_error: 0.0,
            iterations: 0,
        }
    }
}

/// What a message to the user is: it decides the colour and the sign it is drawn with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MessageKind {
    /// Something done as asked ("Saved the robot …").
    Info,
    /// Something done, but not quite as asked (a broken link fell back to the default).
    Warning,
    /// Something not done (a file that does not load, a failed solve).
    Error,
}

/// A sentence for the user, shown in the top bar until dismissed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Message {
    /// How it is drawn.
    pub kind: MessageKind,
    /// The sentence.
    pub text: String,
}

impl Message {
    /// An information message.
    pub fn info(text: impl Into<String>) -> Self {
        Message {
            kind: MessageKind::Info,
            text: text.into(),
        }
    }

    /// A warning.
    pub fn warning(text: impl Into<String>) -> Self {
        Message {
            kind: MessageKind::Warning,
            text: text.into(),
        }
    }

    /// An error.
    pub fn error(text: impl Into<String>) -> Self {
        Message {
            kind: MessageKind::Error,
            text: text.into(),
        }
    }
}

/// Where the highlighted link was chosen: the matrices panel or the 3D view. Each place
/// only clears a highlight it set itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HoverSource {
    /// A matrix block under the pointer.
    Matrices,
    /// A link under the pointer in the 3D view.
    View,
    /// A joint's slider under the pointer.
    Joints,
}

/// One IK solution of the current target, as the IK panel lists it and the 3D view draws
/// it as a ghost arm.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchRow {
    /// The joint values.
    pub q: Vec<f64>,
    /// Its name (the branch in words, or the configuration signs).
    pub label: String,
    /// Every joint within its limits.
    pub within_limits: bool,
}

/// The solutions of one target, with what they were found for.
#[derive(Debug, Clone, PartialEq)]
pub struct Branches {
    target: IsometryMatrix3<f64>,
    robot_changes: u64,
    /// The solutions.
    pub rows: Vec<BranchRow>,
    /// The rows are samples of a continuum (a redundant task), not every solution.
    pub continuum: bool,
}

/// σ_min/σ_max of the linear rows, within the arm's motion space, below which a direction
/// counts as lost (docs/kinematics.md §6.1).
pub const LOST_RATIO: f64 = 0.02;

/// The session, the settings and everything derived from them.
#[derive(Debug, Clone)]
pub struct Model {
    robot: Robot,
    source: RobotSource,
    q: Vec<f64>,
    target: IsometryMatrix3<f64>,
    task: Task,
    method: IkMethod,
    settings: Settings,
    fk: ForwardKinematics,
    jacobian: Matrix6xX<f64>,
    /// The directions the tool can move in at some pose (a planar arm's plane), and the
    /// robot change it was found for.
    motion_space: (u64, Matrix3xX<f64>),
    ik: IkStatus,
    solver: IkSolver,
    hover: Option<(usize, HoverSource)>,
    /// A student's page in a lecture room hides the entries the lecturer hid, as
    /// presentation mode does (`follow.rs`).
    room_hides: bool,
    hovered_column: Option<(usize, HoverSource)>,
    joint_speeds: Vec<f64>,
    branches: Option<Branches>,
    workspace: Option<(u64, WorkspaceCloud)>,
    message: Option<Message>,
    loads: u64,
    robot_changes: u64,
    reframes: u64,
    camera: Option<CameraPose>,
    camera_loads: u64,
    /// The closed-form branch the drag keeps (by its label), with the q it was last true
    /// at: a q moved by anything else (a slider, a solve) starts from the arm's own branch.
    kept_branch: Option<(Branch, Vec<f64>)>,
    /// The branch the drag asked for when it vanished, and the one the arm took instead.
    branch_switch: Option<(Branch, Branch)>,
    /// The last stall at a joint limit and what other starts found.
    rescue: Option<Rescue>,
    /// The tool directions reached at the target's position, when asked for.
    directions: Option<DirectionSphere>,
    motion: MotionLab,
    paths: PathLab,
    exercise: Option<ExerciseState>,
    replay: Option<Replay>,
    /// The closed form's "no exact solution", and the target, task and robot it is for.
    no_exact: Option<(IsometryMatrix3<f64>, Task, u64, bool)>,
    /// The user's system asks for reduced motion (the device's setting, in no link).
    reduced_motion: bool,
}

impl Model {
    /// The model of a session (target at the tool when the session names none).
    pub fn new(session: Session) -> Self {
        let mut model = Model {
            robot: session.robot.clone(),
            source: session.source.clone(),
            q: Vec::new(),
            target: IsometryMatrix3::identity(),
            task: session.task,
            method: session.method,
            settings: Settings::default(),
            fk: ForwardKinematics::default(),
            jacobian: Matrix6xX::zeros(0),
            motion_space: (u64::MAX, Matrix3xX::zeros(0)),
            ik: IkStatus::default(),
            solver: IkSolver::new(),
            hover: None,
            room_hides: false,
            hovered_column: None,
            joint_speeds: Vec::new(),
            branches: None,
            workspace: None,
            message: None,
            loads: 0,
            robot_changes: 0,
            reframes: 0,
            camera: None,
            camera_loads: 0,
            kept_branch: None,
            branch_switch: None,
            rescue: None,
            directions: None,
            motion: MotionLab::default(),
            paths: PathLab::default(),
            exercise: None,
            replay: None,
            no_exact: None,
            reduced_motion: false,
        };
        model.open(session);
        model
    }

    // --- Reading -------------------------------------------------------------------------

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// Where the robot came from (a preset or an edited table).
    pub fn source(&self) -> &RobotSource {
        &self.source
    }

    /// The joint vector (radians, the robot's length unit).
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// Whether the user's system asks for reduced motion: nothing moves by itself.
    pub fn reduced_motion(&self) -> bool {
        self.reduced_motion
    }

    /// The IK target in the base frame.
    pub fn target(&self) -> &IsometryMatrix3<f64> {
        &self.target
    }

    /// The IK task.
    pub fn task(&self) -> Task {
        self.task
    }

    /// The IK method.
    pub fn method(&self) -> IkMethod {
        self.method
    }

    /// The display settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Forward kinematics at q.
    pub fn fk(&self) -> &ForwardKinematics {
        &self.fk
    }

    /// The geometric Jacobian at q (6 × n, base frame).
    pub fn jacobian(&self) -> &Matrix6xX<f64> {
        &self.jacobian
    }

    /// The directions the tool can move in at some pose of this robot (docs/kinematics.md
    /// §6.2): a planar arm's plane, most arms' all three.
    pub fn motion_space(&self) -> &Matrix3xX<f64> {
        &self.motion_space.1
    }

    /// The direction the tool cannot move in at this pose, within [`Model::motion_space`],
    /// when the pose is singular (σ_min/σ_max below [`LOST_RATIO`]).
    pub fn lost_direction(&self) -> Option<Vector3<f64>> {
        lost_direction(&self.jacobian, &self.motion_space.1, LOST_RATIO)
    }

    /// The IK status.
    pub fn ik(&self) -> &IkStatus {
        &self.ik
    }

    /// The highlighted link (1-based, as in the DH table), if any.
    pub fn hovered_link(&self) -> Option<usize> {
        self.hover.map(|(link, _)| link)
    }

    /// Where the highlighted link was chosen.
    pub fn hover_source(&self) -> Option<HoverSource> {
        self.hover.map(|(_, source)| source)
    }

    /// The joint speeds q̇ (rad/s or length units/s), one per joint.
    pub fn joint_speeds(&self) -> Vec<f64> {
        (0..self.robot.dof())
            .map(|i| self.joint_speeds.get(i).copied().unwrap_or(0.0))
            .collect()
    }

    /// The sampled workspace of the current robot, if one was started (it fills over
    /// frames: [`Model::fill_workspace`]).
    pub fn workspace(&self) -> Option<&WorkspaceCloud> {
        self.workspace
            .as_ref()
            .filter(|(made_for, _)| *made_for == self.robot_changes)
            .map(|(_, cloud)| cloud)
    }

    /// The workspace cloud when the view shows it (its overlay is on).
    pub fn shown_workspace(&self) -> Option<&WorkspaceCloud> {
        self.workspace()
            .filter(|_| self.settings().overlays.contains(Overlay::Workspace))
    }

    /// The IK solutions of the current target, when the IK panel found them for this
    /// target and robot.
    pub fn branches(&self) -> Option<&Branches> {
        self.branches
            .as_ref()
            .filter(|b| b.target == self.target && b.robot_changes == self.robot_changes)
    }

    /// The Jacobian column (0-based) under the pointer, in the matrices panel's legend or
    /// as an arrow in the 3D view: both highlight it.
    pub fn hovered_column(&self) -> Option<usize> {
        self.hovered_column.map(|(c, _)| c)
    }

    /// The message in the top bar, if any.
    pub fn message(&self) -> Option<&Message> {
        self.message.as_ref()
    }

    /// Counts robot loads from outside the DH editor (a preset, a file, a link): the
    /// editor takes the new table when it changes.
    pub fn robot_loads(&self) -> u64 {
        self.loads
    }

    /// Counts every change of the robot: loads and DH-table edits. The page keeps the
    /// session in localStorage at once when this changes.
    pub fn robot_changes(&self) -> u64 {
        self.robot_changes
    }

    /// Counts the times the view should frame the arm anew: every load, and edits that
    /// change the joint count or the arm's size by more than a factor of two. Other edits
    /// keep the camera where the user put it.
    pub fn reframes(&self) -> u64 {
        self.reframes
    }

    /// The branch a closed-form drag asked for when it vanished (the target crossed a
    /// singularity), and the nearest one the arm took instead; cleared when the arm is
    /// moved by anything but the drag.
    pub fn branch_switch(&self) -> Option<(Branch, Branch)> {
        self.branch_switch
    }

    /// The stall of the current target (only while it is out of reach from where the arm
    /// is): which joint holds it at a limit if one does, and a start that reaches it if any.
    pub fn rescue(&self) -> Option<&Rescue> {
        self.rescue.as_ref().filter(|r| {
            self.ik.reach == Reach::OutOfReach
                && r.target == self.target
                && r.robot_changes == self.robot_changes
                && r.task == self.task
        })
    }

    /// The verdict as a person is told it: "out of reach" only when no branch or restart
    /// reaches the target; a target held by a joint limit that another start reaches is
    /// "not yet there" ([`Model::rescue`] says how).
    pub fn shown_reach(&self) -> Reach {
        match (self.ik.reach, self.rescue()) {
            (Reach::OutOfReach, Some(r)) if r.reach.is_some() => Reach::Pending,
            (reach, _) => reach,
        }
    }

    /// Moves the arm to the start that reaches a target the drag stalled short of.
    pub fn take_rescue(&mut self) {
        if let Some(q) = self.rescue().and_then(|r| r.reach.clone()) {
            self.set_q(q);
        }
    }

    /// The branch the closed-form drag keeps, while the arm is where the drag left it.
    pub fn kept_branch(&self) -> Option<Branch> {
        self.kept_branch
            .as_ref()
            .filter(|(_, q)| *q == self.q)
            .map(|(b, _)| *b)
    }

    /// Whether the robot has a closed-form IK solver.
    pub fn has_closed_form(&self) -> bool {
        closed_form_family(&self.robot).is_some()
    }

    /// What a link carries, as a session.
    pub fn session(&self) -> Session {
        let mut motion = armlab_session::motion::MotionPatch::of(
            self.motion.on(),
            self.motion.settings(),
            self.motion.time_scale(),
            self.motion.collisions_on(),
            self.motion.keep_outs(),
        );
        motion.path_kind = Some(self.paths.kind());
        motion.waypoints = Some(self.paths.waypoints().poses().to_vec());
        Session {
            robot: self.robot.clone(),
            source: self.source.clone(),
            q: self.q.clone(),
            target: Some(self.target),
            task: self.task,
            method: self.method,
            display: DisplayPatch::of(&self.settings),
            camera: self.camera,
            motion,
            exercise: self.exercise.as_ref().map(|e| e.id.clone()),
            dropped: Vec::new(),
        }
    }

    /// The camera as the 3D view last reported it (for the link).
    pub fn camera(&self) -> Option<CameraPose> {
        self.camera
    }

    /// Counts the cameras a link asked for: the 3D view takes [`Model::camera`] when this
    /// changes.
    pub fn camera_loads(&self) -> u64 {
        self.camera_loads
    }

    /// The link hash of the session (without `#`).
    pub fn hash(&self) -> String {
        self.session().to_hash()
    }

    /// Keeps the solutions found for the current target (the IK panel's list, the view's
    /// ghosts).
    pub fn set_branches(&mut self, rows: Vec<BranchRow>, continuum: bool) {
        self.branches = Some(Branches {
            target: self.target,
            robot_changes: self.robot_changes,
            rows,
            continuum,
        });
    }

    /// Sets the joint speeds q̇ of the velocity-kinematics rows (one per joint; missing
    /// ones are 0, non-finite ones 0).
    pub fn set_joint_speeds(&mut self, speeds: &[f64]) {
        self.joint_speeds = (0..self.robot.dof())
            .map(|i| {
                speeds
                    .get(i)
                    .copied()
                    .filter(|v| v.is_finite())
                    .unwrap_or(0.0)
            })
            .collect();
    }

    /// Notes the Jacobian column under the pointer in `source`; `None` clears only a
    /// column that `source` set.
    pub fn set_hovered_column(&mut self, column: Option<usize>, source: HoverSource) {
        match column.filter(|c| *c < self.robot.dof()) {
            Some(c) => self.hovered_column = Some((c, source)),
            None if self.hovered_column.is_some_and(|(_, s)| s == source) => {
                self.hovered_column = None;
            }
            None => {}
        }
    }

    /// Replaces the whole session (a link, a stored session): robot, q, target, task and
    /// method; the target sits at the tool when the session names none. A sentence about
    /// the session before goes; the parts the link left out get one.
    pub fn open(&mut self, session: Session) {
        self.message = None;
        session.display.apply(&mut self.settings);
        if session.camera.is_some() {
            self.camera = session.camera;
            self.camera_loads += 1;
        }
        self.exercise = session.exercise.map(ExerciseState::open);
        self.robot = session.robot;
        self.source = session.source;
        self.q = session.q;
        self.q.resize(self.robot.dof(), 0.0);
        self.task = session.task;
        self.method = session.method;
        self.start_anew();
        // The link brings its own waypoints.
        self.forget_old_robot(None);
        self.target = session.target.unwrap_or(self.fk.base_from_tool);
        self.ik = IkStatus::default();
        self.recompute_reach();
        self.open_motion(&session.motion);
        let lang = self.settings.lang;
        let left_out = (session.dropped.iter().map(|e| e.sentence(lang)))
            .chain(session.motion.dropped.iter().map(|e| e.sentence(lang)))
            .collect();
        self.say_left_out(left_out);
    }

    /// Loads a robot as a new start (a preset or a file): its home pose, its default task
    /// (position only below six joints) and method, the target on its tool, the view
    /// framed anew; the keep-out boxes of a file that brings some.
    pub fn load_robot(&mut self, robot: Robot, source: RobotSource) {
        if !robot.keep_outs.is_empty() {
            // A robot file's keep-out boxes (checked with the file) replace the lab's.
            let _ = self.motion.set_keep_outs(robot.keep_outs.clone());
        }
        let unit_before = self.robot.length_unit;
        self.q = robot.home();
        self.task = Task::default_for(robot.dof());
        self.method = IkMethod::DampedLeastSquares;
        self.robot = robot;
        self.source = source;
        self.exercise = None;
        self.start_anew();
        self.forget_old_robot(Some(unit_before));
        self.snap_target();
    }

    /// Swaps in an edited robot, keeping what can be kept: q when the joint count is the
    /// same (each value kept as its joint keeps angles), else the home pose; the target
    /// stays unless the arm's size or shape changed a lot, then it moves onto the tool.
    pub fn edit_robot(&mut self, robot: Robot, source: RobotSource) {
        let same_shape = robot.dof() == self.robot.dof();
        let q = if same_shape {
            let mut q = self.q.clone();
            robot.keep_q(&mut q, &self.q);
            q
        } else {
            robot.home()
        };
        let reframe = robot.reach() / self.robot.reach();
        let unit_before = self.robot.length_unit;
        self.robot = robot;
        self.source = source;
        self.exercise = None;
        self.q = q;
        self.robot_changes += 1;
        self.keep_method_available();
        self.forget_old_robot(Some(unit_before));
        self.recompute_kinematics();
        if !same_shape || !(0.5..2.0).contains(&reframe) {
            self.reframes += 1;
            self.snap_target();
        } else {
            self.recompute_reach();
        }
    }

    /// Sets the joint vector as an IK step or a replay gives it: each revolute angle kept
    /// as the turn nearest the current value inside its limits (docs/kinematics.md §3).
    pub fn set_q(&mut self, mut q: Vec<f64>) {
        q.resize(self.robot.dof(), 0.0);
        self.robot.keep_q(&mut q, &self.q);
        self.q = q;
        self.recompute_kinematics();
        self.recompute_reach();
    }

    /// Sets the joint vector as typed or slid: each value clamped to its joint's limits,
    /// not re-mapped to another turn (a slider at 216° stays at 216°).
    pub fn set_q_exact(&mut self, mut q: Vec<f64>) {
        q.resize(self.robot.dof(), 0.0);
        for (v, joint) in q.iter_mut().zip(&self.robot.joints) {
            *v = joint.limits.clamp(*v);
        }
        self.q = q;
        self.recompute_kinematics();
        self.recompute_reach();
    }

    /// Sets the target pose (a drag or a typed value).
    pub fn set_target(&mut self, target: IsometryMatrix3<f64>) {
        if target != self.target {
            self.target = target;
            self.recompute_reach();
        }
    }

    /// Moves the target onto the tool.
    pub fn snap_target(&mut self) {
        self.target = self.fk.base_from_tool;
        self.ik = IkStatus::default();
        self.recompute_reach();
    }

    /// Sets the IK task.
    pub fn set_task(&mut self, task: Task) {
        if task != self.task {
            self.task = task;
            self.recompute_reach();
        }
    }

    /// Sets the IK method; the closed form only where the robot has one.
    pub fn set_method(&mut self, method: IkMethod) {
        self.method = method;
        self.keep_method_available();
    }

    /// Notes where the 3D view's camera is (the view calls this when it moves).
    pub fn note_camera(&mut self, camera: CameraPose) {
        self.camera = Some(camera);
    }

    /// Sets the display settings.
    pub fn set_settings(&mut self, settings: Settings) {
        self.settings = settings;
    }

    /// Highlights a link (1-based) chosen in `source`, or clears a highlight that
    /// `source` set.
    pub fn set_hovered_link(&mut self, link: Option<usize>, source: HoverSource) {
        match link {
            Some(link) => self.hover = Some((link, source)),
            None if self.hover_source() == Some(source) => self.hover = None,
            None => {}
        }
    }

    /// Shows a message in the top bar.
    pub fn set_message(&mut self, message: Message) {
        self.message = Some(message);
    }

    /// Removes the message.
    pub fn dismiss_message(&mut self) {
        self.message = None;
    }

    /// After a new robot, q, task and method are in place (a link, a preset, a file): the
    /// method kept available, the load counted (the view frames the arm anew), no highlight,
    /// and the kinematics recomputed.
    fn start_anew(&mut self) {
        self.keep_method_available();
        self.loads += 1;
        self.robot_changes += 1;
        self.reframes += 1;
        self.hover = None;
        self.recompute_kinematics();
    }

    /// After a robot change: what was found for the old robot goes (the replay, the
    /// solutions and their ghosts, the rescue, the kept branch, the direction sphere, a
    /// highlight past the last joint), and so do waypoints written in another length unit
    /// than the new robot's, with a sentence saying so, unless `unit_before` is `None` (new
    /// waypoints come with the robot).
    fn forget_old_robot(&mut self, unit_before: Option<armlab_core::LengthUnit>) {
        self.replay = None;
        self.branches = None;
        self.rescue = None;
        self.kept_branch = None;
        self.branch_switch = None;
        self.directions = None;
        let dof = self.robot.dof();
        if self.hovered_link().is_some_and(|l| l > dof) {
            self.hover = None;
        }
        if self.hovered_column().is_some_and(|c| c >= dof) {
            self.hovered_column = None;
        }
        let Some(unit_before) = unit_before else {
            return;
        };
        // Waypoints out of the new reach stay (the plan shows them unreached): a DH cell
        // typed digit by digit passes through small arms on the way.
        if self.robot.length_unit != unit_before && !self.paths.waypoints().is_empty() {
            self.paths.stop_visit();
            *self.paths.waypoints_mut() = armlab_core::path::Waypoints::default();
            self.message = Some(Message::warning(armlab_text::text(
                self.settings.lang,
                armlab_text::Key::WaypointsDropped,
            )));
        }
    }

    fn keep_method_available(&mut self) {
        if self.method == IkMethod::ClosedForm && !self.has_closed_form() {
            self.method = IkMethod::DampedLeastSquares;
        }
    }

    fn recompute_kinematics(&mut self) {
        self.fk.update(&self.robot, &self.q);
        if self.jacobian.ncols() != self.robot.dof() {
            self.jacobian = Matrix6xX::zeros(self.robot.dof());
        }
        geometric_jacobian_into(&self.fk, &mut self.jacobian);
        if self.motion_space.0 != self.robot_changes {
            self.motion_space = (self.robot_changes, linear_motion_space(&self.robot));
        }
    }

    /// The errors against the target and whether they are within the "reached"
    /// tolerances; a target the closed form has no exact solution for is out of reach
    /// whatever the iterations say; an "out of reach" verdict stays until the target is
    /// reached or moved onto the tool.
    fn recompute_reach(&mut self) {
        let (position, orientation) = pose_error(&self.robot, &self.q, &self.target, self.task);
        self.ik.position_error = position;
        self.ik.orientation_error = orientation;
        let tolerance = REACHED_POSITION_TOLERANCE_M / self.robot.length_unit.in_metres();
        if position <= tolerance && orientation <= REACHED_ORIENTATION_TOLERANCE {
            self.ik.reach = Reach::Reached;
        } else if self.no_exact_solution() {
            self.ik.reach = Reach::OutOfReach;
        } else if self.ik.reach == Reach::Reached {
            self.ik.reach = Reach::Pending;
        }
    }
}
