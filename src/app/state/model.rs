//! The app's one model: the session (robot, joint vector, target, task, method), the
//! display settings, and what is derived from them (forward kinematics, the Jacobian, the
//! IK status). Its methods are the only writers: a panel reads the model and calls a
//! method to change it; derived values are recomputed exactly when their inputs change
//! (FK and the Jacobian when q or the robot changes; the IK status when q, the robot, the
//! target or the task changes). No egui here: the model is tested without a window.

use armlab_text::Sentence;
use nalgebra::{IsometryMatrix3, Matrix6xX, Point3, Vector3};

use armlab_core::ik::{
    Branch, IkError, IkResult, IkSettings, IkSolver, REACHED_ORIENTATION_TOLERANCE,
    REACHED_POSITION_TOLERANCE_M, Reach, branch_of, closed_form_family, closed_form_solutions,
    distinct_solutions, joint_distance, pose_error,
};
use armlab_core::workspace::{
    DirectionReach, WorkspaceCloud, WorkspaceMeasure, direction_reachability,
    joints_held_at_limits, sphere_directions,
};
use armlab_core::{
    ForwardKinematics, IkMethod, Robot, SplitMix64, Task, ToolAxis, geometric_jacobian_into,
    tool_pose,
};

use crate::app::state::motion_lab::MotionLab;
use crate::app::state::path_lab::PathLab;
use armlab_core::exercise::{Verdict, check_table};
use armlab_session::exercise::ExerciseId;
use armlab_session::session::{RobotSource, Session};
pub use armlab_session::settings::Settings;
use armlab_session::settings::{CameraPose, DisplayPatch};

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

/// A drag stalled short of its target (often with a joint at its limit), and what other
/// starts make of the target.
#[derive(Debug, Clone, PartialEq)]
pub struct Rescue {
    target: IsometryMatrix3<f64>,
    robot_changes: u64,
    task: Task,
    /// The joint (from 0) that holds the arm, pulled past its limit by the error, and
    /// whether at its upper limit; `None` when the stall is not at a limit.
    pub held: Option<(usize, bool)>,
    /// A solution within the limits that reaches the target (the closed form's branches
    /// or seeded restarts), nearest the arm; `None` when none was found.
    pub reach: Option<Vec<f64>>,
    /// Starts tried: closed-form branches plus restarts.
    pub tried: usize,
}

/// Which tool directions the arm reaches at one position (docs/kinematics.md §12).
#[derive(Debug, Clone, PartialEq)]
pub struct DirectionSphere {
    robot_changes: u64,
    task: Task,
    /// The position the directions were tested at.
    pub position: Vector3<f64>,
    /// Each direction and whether the 5D task reaches it.
    pub directions: Vec<DirectionReach>,
    /// For each direction, whether the arm reaches the position with its tool axis
    /// within [`DirectionSphere::tolerance`] of it: a 5-axis arm points an axis along a
    /// curve of directions, which a finite lattice never hits exactly; the lattice points
    /// within half their spacing of it draw that curve.
    pub near: Vec<bool>,
    /// Half the lattice's spacing, √(4π/n)/2 (radians).
    pub tolerance: f64,
    /// The axis's directions in position-only solves from random starts that put the
    /// tool at the position: samples of every direction the arm can point the axis at
    /// there (a curve for a 5-axis arm).
    pub samples: Vec<Vector3<f64>>,
}

/// Directions tested on the sphere of [`Model::fill_directions`].
pub const DIRECTION_SAMPLES: usize = 64;
/// The iteration budget of each direction's 5D solve.
const DIRECTION_BUDGET: usize = 300;

/// Random restarts tried for a target held at a limit: few and short, since the search
/// runs once per target while a drag stalls (about 0.3 ms natively).
const RESCUE_RESTARTS: usize = 4;
/// The iteration budget of each of those restarts.
const RESCUE_BUDGET: usize = 200;

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
    ik: IkStatus,
    solver: IkSolver,
    hover: Option<(usize, HoverSource)>,
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
}

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
            ik: IkStatus::default(),
            solver: IkSolver::new(),
            hover: None,
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

    // --- Writing -------------------------------------------------------------------------

    /// Adds workspace samples for at most `budget_ms` (measured with `clock`, the app's
    /// milliseconds), starting a new cloud of `samples` points when the robot or the
    /// measure changed; returns the milliseconds spent.
    pub fn fill_workspace(
        &mut self,
        measure: WorkspaceMeasure,
        samples: usize,
        budget_ms: f64,
        clock: impl Fn() -> f64,
    ) -> f64 {
        let fresh = self
            .workspace
            .as_ref()
            .is_some_and(|(made_for, c)| *made_for == self.robot_changes && c.measure() == measure);
        if !fresh {
            let cloud = WorkspaceCloud::new(&self.robot, measure, samples, 0x5eed);
            self.workspace = Some((self.robot_changes, cloud));
        }
        let start = clock();
        if let Some((_, cloud)) = self.workspace.as_mut() {
            // Slices of 256 samples (about 0.1–0.3 ms each natively) until the budget.
            while !cloud.is_full() && clock() - start < budget_ms {
                cloud.fill(256);
            }
        }
        clock() - start
    }

    /// The tool directions reached at the target's position, as last filled.
    pub fn directions(&self) -> Option<&DirectionSphere> {
        self.directions.as_ref()
    }

    /// Tests [`DIRECTION_SAMPLES`] tool directions at the target's position (the task's
    /// tool axis, else the one nearest the last joint's axis) by a 5D solve each from q,
    /// and samples the axis's direction in as many position-only solves from random
    /// starts, unless the last test was for this robot and task and a position within 1 %
    /// of the reach. Returns the milliseconds spent (`clock` in ms).
    pub fn fill_directions(&mut self, clock: impl Fn() -> f64) -> f64 {
        let start = clock();
        let position = self.target.translation.vector;
        let near = 0.01 * self.robot.reach();
        let fresh = self.directions.as_ref().is_some_and(|d| {
            d.robot_changes == self.robot_changes
                && d.task == self.task
                && (d.position - position).norm() <= near
        });
        if fresh {
            return clock() - start;
        }
        let axis = match self.task {
            Task::PositionAndAxis(axis) => axis,
            _ => self.last_joint_tool_axis(),
        };
        let settings = IkSettings {
            budget: DIRECTION_BUDGET,
            max_iterations: DIRECTION_BUDGET,
            restarts: 0,
            ..IkSettings::default()
        };
        let sphere = sphere_directions(DIRECTION_SAMPLES);
        let directions =
            direction_reachability(&self.robot, &position, axis, &sphere, &self.q, &settings)
                .unwrap_or_default();
        let tolerance = 0.5 * (4.0 * std::f64::consts::PI / DIRECTION_SAMPLES as f64).sqrt();
        let pointing = |q: &[f64]| {
            tool_pose(&self.robot, q)
                .rotation
                .matrix()
                .column(axis.index())
                .into_owned()
        };
        let mut rng = SplitMix64::new(0xd1ec7);
        let mut samples = Vec::with_capacity(DIRECTION_SAMPLES);
        for _ in 0..DIRECTION_SAMPLES {
            let seed = rng.joint_vector(&self.robot);
            let solved = self.solver.solve(
                &self.robot,
                &self.target,
                Task::Position,
                &seed,
                IkMethod::DampedLeastSquares,
                &settings,
            );
            if let Ok(r) = solved
                && r.success
                && r.within_limits
            {
                samples.push(pointing(&r.q));
            }
        }
        let near = directions
            .iter()
            .map(|d| d.reachable || samples.iter().any(|s| s.angle(&d.direction) <= tolerance))
            .collect();
        self.directions = Some(DirectionSphere {
            robot_changes: self.robot_changes,
            task: self.task,
            position,
            directions,
            near,
            tolerance,
            samples,
        });
        clock() - start
    }

    /// The tool axis most nearly along the last joint's axis: the one direction the last
    /// joint cannot turn, so the one whose reachable directions show what the other joints
    /// can do (the Metrover's y). The last column of J's angular rows is that axis in the
    /// base frame (zero for a prismatic joint: then z).
    fn last_joint_tool_axis(&self) -> ToolAxis {
        let n = self.robot.dof();
        if n == 0 {
            return ToolAxis::Z;
        }
        let w = Vector3::new(
            self.jacobian[(3, n - 1)],
            self.jacobian[(4, n - 1)],
            self.jacobian[(5, n - 1)],
        );
        let in_tool = self.fk.tool_rotation().transpose() * w;
        let [x, y, z] = [in_tool.x.abs(), in_tool.y.abs(), in_tool.z.abs()];
        if x > y && x > z {
            ToolAxis::X
        } else if y > z {
            ToolAxis::Y
        } else {
            ToolAxis::Z
        }
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
    /// method; the target sits at the tool when the session names none.
    pub fn open(&mut self, session: Session) {
        session.display.apply(&mut self.settings);
        if session.camera.is_some() {
            self.camera = session.camera;
            self.camera_loads += 1;
        }
        self.exercise = session.exercise.map(|id| ExerciseState {
            id,
            verdict: None,
            solved: false,
        });
        self.robot = session.robot;
        self.source = session.source;
        self.q = session.q;
        self.q.resize(self.robot.dof(), 0.0);
        self.task = session.task;
        self.method = session.method;
        self.keep_method_available();
        self.loads += 1;
        self.robot_changes += 1;
        self.reframes += 1;
        self.hover = None;
        self.recompute_kinematics();
        self.target = session.target.unwrap_or(self.fk.base_from_tool);
        self.ik = IkStatus::default();
        self.recompute_reach();
        self.open_motion(&session.motion);
    }

    /// Loads a robot as a new start (a preset or a file): its home pose, its default task
    /// (position only below six joints) and method, the target on its tool, the view
    /// framed anew; the keep-out boxes of a file that brings some.
    pub fn load_robot(&mut self, robot: Robot, source: RobotSource) {
        if !robot.keep_outs.is_empty() {
            // A robot file's keep-out boxes (checked with the file) replace the lab's.
            let _ = self.motion.set_keep_outs(robot.keep_outs.clone());
        }
        self.q = robot.home();
        self.task = Task::default_for(robot.dof());
        self.method = IkMethod::DampedLeastSquares;
        self.robot = robot;
        self.source = source;
        self.exercise = None;
        self.keep_method_available();
        self.loads += 1;
        self.robot_changes += 1;
        self.reframes += 1;
        self.hover = None;
        self.recompute_kinematics();
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
        self.robot = robot;
        self.source = source;
        self.exercise = None;
        self.q = q;
        self.robot_changes += 1;
        self.keep_method_available();
        if self.hovered_link().is_some_and(|l| l > self.robot.dof()) {
            self.hover = None;
        }
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

    /// One drag frame: while the target is pending or out of reach, one IK step
    /// warm-started at q (each joint moves at most the per-call limit). Returns whether it
    /// ran. A failure (only a broken target could cause one) becomes the message.
    pub fn drag_step(&mut self) -> bool {
        if self.motion.on() {
            return self.motion_drag();
        }
        if self.ik.reach == Reach::Reached {
            return false;
        }
        if !(self.method == IkMethod::ClosedForm && self.drag_step_on_branch()) {
            let result = self.solver.drag_step(
                &self.robot,
                &self.q,
                &self.target,
                self.task,
                self.method,
                &IkSettings::drag(),
            );
            self.apply_result(result);
        }
        self.stop_at_collision();
        true
    }

    /// A closed-form drag frame that keeps the branch by its label
    /// ([`IkSolver::drag_step_on_branch`]); false when the arm's branch cannot be named
    /// (the plain closed-form step runs instead).
    fn drag_step_on_branch(&mut self) -> bool {
        let previous = match self.kept_branch() {
            Some(branch) => branch,
            None => {
                self.branch_switch = None;
                match branch_of(&self.robot, &self.q) {
                    Ok(Some(branch)) => branch,
                    _ => return false,
                }
            }
        };
        let result = self.solver.drag_step_on_branch(
            &self.robot,
            &self.q,
            &self.target,
            self.task,
            &previous,
            &IkSettings::drag(),
        );
        match result {
            Ok((result, step)) => {
                if step.vanished {
                    self.branch_switch = Some((previous, step.branch));
                }
                self.apply_result(Ok(result));
                self.kept_branch = Some((step.branch, self.q.clone()));
            }
            Err(e) => {
                self.apply_result(Err(e));
            }
        }
        true
    }

    /// Runs the method to convergence from q with every iteration recorded, moves the
    /// arm to its answer and returns the run (for replay).
    pub fn solve_with_trace(&mut self) -> Option<IkResult> {
        self.solve_with_settings(&IkSettings {
            record_trace: true,
            restarts: 0,
            max_iterations: 2000,
            budget: 2000,
            ..IkSettings::default()
        })
    }

    /// Runs the chosen method with these settings from the current q (the notebook's
    /// demos set their own tolerance, wrapping and objective); the arm takes the answer.
    pub fn solve_with_settings(&mut self, settings: &IkSettings) -> Option<IkResult> {
        let result = self.solver.solve(
            &self.robot,
            &self.target,
            self.task,
            &self.q,
            self.method,
            settings,
        );
        self.apply_result(result)
    }

    fn apply_result(&mut self, result: Result<IkResult, IkError>) -> Option<IkResult> {
        match result {
            Ok(result) if self.motion.on() => {
                self.drive_to(result.q.clone(), result.unreachable);
                self.ik.iterations = result.iterations;
                Some(result)
            }
            Ok(result) => {
                self.set_q(result.q.clone());
                self.ik.iterations = result.iterations;
                if self.ik.reach != Reach::Reached {
                    self.ik.reach = if result.unreachable {
                        Reach::OutOfReach
                    } else {
                        Reach::Pending
                    };
                }
                if self.ik.reach == Reach::OutOfReach && self.rescue().is_none() {
                    self.rescue = self.find_rescue();
                }
                Some(result)
            }
            Err(e) => {
                self.message = Some(Message::error(e.sentence(self.settings.lang)));
                None
            }
        }
    }

    // --- Paths and waypoints (docs/kinematics.md §19) ------------------------------------

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
    /// in joint space); the values it left out get a sentence.
    fn open_paths(&mut self, patch: &armlab_session::motion::MotionPatch) {
        self.paths.stop_visit();
        self.paths.set_kind(patch.path_kind.unwrap_or_default());
        let poses = patch.waypoints.clone().unwrap_or_default();
        *self.paths.waypoints_mut() = armlab_core::path::Waypoints::new(poses).unwrap_or_default();
        if !patch.dropped.is_empty() {
            let lang = self.settings.lang;
            let mut reasons: Vec<String> = patch
                .dropped
                .iter()
                .take(3)
                .map(|e| e.sentence(lang))
                .collect();
            if patch.dropped.len() > 3 {
                reasons.push(armlab_text::fill(
                    lang,
                    armlab_text::Key::PathMoreIssues,
                    &[&(patch.dropped.len() - 3)],
                ));
            }
            self.message = Some(Message::warning(armlab_text::fill(
                lang,
                armlab_text::Key::LinkPartDropped,
                &[&reasons.join("; ")],
            )));
        }
    }

    /// A frame of a visit: the simulation runs in slices of 5 ms of real time, and after
    /// each the goal moves on along the visit's path; the arm takes the frame's end.
    fn advance_visit(&mut self, real_dt: f64) -> usize {
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
    fn follow_visit(&mut self, q: &[f64]) {
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

    // --- The motion lab (docs/kinematics.md §17) -----------------------------------------

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
    fn open_motion(&mut self, patch: &armlab_session::motion::MotionPatch) {
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
    fn drive_to(&mut self, mut goal: Vec<f64>, unreachable: bool) {
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
    fn motion_drag(&mut self) -> bool {
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
    fn take_motion_q(&mut self, q: Vec<f64>) {
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
    fn stop_at_collision(&mut self) {
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

    // --- Editing that keeps the arm, the DH-table exercise (docs/kinematics.md §14.3, §15)

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
        self.exercise = Some(ExerciseState {
            id,
            verdict: None,
            solved: false,
        });
        Ok(())
    }

    /// Grades a student's table against the exercise's robot (`check_table`); a correct
    /// one solves the exercise. `None` when no exercise is open.
    pub fn check_exercise(&mut self, student: &Robot) -> Option<Verdict> {
        let exercise = self.exercise.as_mut()?;
        let verdict = check_table(&self.robot, student);
        exercise.verdict = Some(verdict);
        exercise.solved |= verdict == Verdict::Correct;
        Some(verdict)
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

    // --- Derived values ------------------------------------------------------------------

    /// When the drag stalls short of the target: the joint that holds it at a limit, if
    /// one does, and of every closed-form branch of the target and a few seeded restarts,
    /// the one within the limits that reaches it nearest the arm.
    fn find_rescue(&self) -> Option<Rescue> {
        let held = joints_held_at_limits(&self.robot, &self.q, &self.target, self.task, 1e-6)
            .first()
            .map(|h| (h.joint, h.at_max));
        let tolerance = REACHED_POSITION_TOLERANCE_M / self.robot.length_unit.in_metres();
        let reaches = |q: &[f64]| {
            let (p, o) = pose_error(&self.robot, q, &self.target, self.task);
            p <= tolerance && o <= REACHED_ORIENTATION_TOLERANCE
        };
        let mut candidates: Vec<Vec<f64>> = Vec::new();
        if closed_form_family(&self.robot).is_some()
            && let Ok(set) = closed_form_solutions(&self.robot, &self.target, &self.q)
        {
            candidates.extend(
                set.solutions
                    .into_iter()
                    .filter(|s| s.exact && s.within_limits)
                    .map(|s| s.q),
            );
        }
        let branches = candidates.len();
        let settings = IkSettings {
            budget: RESCUE_BUDGET,
            max_iterations: RESCUE_BUDGET,
            ..IkSettings::default()
        };
        if let Ok(found) = distinct_solutions(
            &self.robot,
            &self.target,
            self.task,
            &settings,
            RESCUE_RESTARTS,
        ) {
            candidates.extend(
                found
                    .solutions
                    .into_iter()
                    .filter(|s| s.within_limits)
                    .map(|s| s.q),
            );
        }
        let reach = candidates
            .into_iter()
            .filter(|q| reaches(q))
            .min_by(|a, b| {
                joint_distance(&self.robot, &self.q, a)
                    .partial_cmp(&joint_distance(&self.robot, &self.q, b))
                    .unwrap_or(std::cmp::Ordering::Equal)
            });
        Some(Rescue {
            target: self.target,
            robot_changes: self.robot_changes,
            task: self.task,
            held,
            reach,
            tried: branches + RESCUE_RESTARTS,
        })
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
    }

    /// The errors against the target and whether they are within the "reached"
    /// tolerances; an "out of reach" verdict stays until the target is reached or moved
    /// onto the tool.
    fn recompute_reach(&mut self) {
        let (position, orientation) = pose_error(&self.robot, &self.q, &self.target, self.task);
        self.ik.position_error = position;
        self.ik.orientation_error = orientation;
        let tolerance = REACHED_POSITION_TOLERANCE_M / self.robot.length_unit.in_metres();
        if position <= tolerance && orientation <= REACHED_ORIENTATION_TOLERANCE {
            self.ik.reach = Reach::Reached;
        } else if self.ik.reach == Reach::Reached {
            self.ik.reach = Reach::Pending;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use armlab_core::ik::{Elbow, Shoulder, Wrist};
    use armlab_core::{SplitMix64, geometric_jacobian, preset, preset_ids, tool_pose};

    /// One call of the model's writing API, drawn at random.
    fn random_call(model: &mut Model, rng: &mut SplitMix64) {
        let robot = model.robot().clone();
        match rng.next_u64() % 12 {
            0 => model.set_q(rng.joint_vector(&robot)),
            1 => {
                // Slid or typed values, some outside the limits.
                let q = rng.joint_vector(&robot).iter().map(|v| v * 1.5).collect();
                model.set_q_exact(q);
            }
            2 | 3 => {
                let mut target = *model.target();
                let reach = robot.reach();
                target.translation.vector += nalgebra::Vector3::new(
                    rng.uniform(-0.3, 0.3) * reach,
                    rng.uniform(-0.3, 0.3) * reach,
                    rng.uniform(-0.3, 0.3) * reach,
                );
                model.set_target(target);
            }
            4 => model.snap_target(),
            5 => model.set_task(Task::ALL[(rng.next_u64() % Task::ALL.len() as u64) as usize]),
            6 => model
                .set_method(IkMethod::ALL[(rng.next_u64() % IkMethod::ALL.len() as u64) as usize]),
            7 => {
                let ids: Vec<&str> = preset_ids().collect();
                let id = ids[(rng.next_u64() % ids.len() as u64) as usize];
                let robot = preset(id).expect("presets load");
                model.load_robot(robot, RobotSource::Preset(id.to_string()));
            }
            8 => {
                // An edit of one DH length, as the editor makes it.
                let mut edited = robot.clone();
                let i = (rng.next_u64() % edited.dof() as u64) as usize;
                edited.joints[i].dh.a += rng.uniform(-0.2, 0.2) * robot.reach();
                model.edit_robot(edited, RobotSource::Custom);
            }
            9 | 10 => {
                model.drag_step();
            }
            _ => {
                model.solve_with_trace();
            }
        }
    }

    /// The derived values equal a fresh recomputation from the session alone.
    fn assert_derived_values_fresh(model: &Model, context: &str) {
        let robot = model.robot();
        assert_eq!(model.q().len(), robot.dof(), "{context}");
        let fresh = ForwardKinematics::new(robot, model.q()).expect("a valid q");
        assert_eq!(model.fk().base_from_tool, fresh.base_from_tool, "{context}");
        assert_eq!(
            model.fk().base_from_frames,
            fresh.base_from_frames,
            "{context}"
        );
        assert_eq!(*model.jacobian(), geometric_jacobian(&fresh), "{context}");
        let (position, orientation) = pose_error(robot, model.q(), model.target(), model.task());
        assert_eq!(model.ik().position_error, position, "{context}");
        assert_eq!(model.ik().orientation_error, orientation, "{context}");
        let tolerance = REACHED_POSITION_TOLERANCE_M / robot.length_unit.in_metres();
        let within = position <= tolerance && orientation <= REACHED_ORIENTATION_TOLERANCE;
        assert_eq!(model.ik().reach == Reach::Reached, within, "{context}");
        for (i, (v, joint)) in model.q().iter().zip(&robot.joints).enumerate() {
            assert!(
                joint.limits.contains(*v, 1e-9),
                "{context}: joint {} at {v} outside [{}, {}]",
                i + 1,
                joint.limits.min,
                joint.limits.max
            );
        }
        if model.method() == IkMethod::ClosedForm {
            assert!(model.has_closed_form(), "{context}");
        }
        if let Some(link) = model.hovered_link() {
            assert!(link <= robot.dof(), "{context}");
        }
    }

    #[test]
    fn random_call_sequences_keep_every_derived_value_fresh() {
        let mut rng = SplitMix64::new(20_261_123);
        for sequence in 0..60 {
            let ids: Vec<&str> = preset_ids().collect();
            let id = ids[sequence % ids.len()];
            let mut model = Model::new(Session::for_preset(id).expect("presets load"));
            assert_derived_values_fresh(&model, &format!("{id}, new"));
            for call in 0..40 {
                random_call(&mut model, &mut rng);
                assert_derived_values_fresh(
                    &model,
                    &format!("{id}, sequence {sequence}, call {call}"),
                );
            }
        }
    }

    #[test]
    fn the_target_is_stored_once_and_travels_in_the_link() {
        let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
        let mut target = *model.target();
        target.translation.vector.x -= 150.0;
        model.set_target(target);
        assert_eq!(model.ik().reach, Reach::Pending);
        let reopened = Session::from_hash(&model.hash())
            .expect("a valid link")
            .expect("not empty");
        let back = reopened.target.expect("the link names the target");
        assert!((back.translation.vector - target.translation.vector).norm() < 1e-6);
        let again = Model::new(reopened);
        assert!((again.target().translation.vector - target.translation.vector).norm() < 1e-6);
    }

    #[test]
    fn the_drag_step_runs_only_while_the_target_is_not_reached() {
        let mut model = Model::new(Session::for_preset("rrr").expect("preset"));
        assert_eq!(
            model.ik().reach,
            Reach::Reached,
            "the target opens on the tool"
        );
        assert!(!model.drag_step(), "nothing to do at the target");
        // Home is the stretched arm, a singular pose whose Jacobian has no component
        // toward the base: start from a bent elbow instead.
        model.set_q(vec![0.0, 0.5, -1.0]);
        model.snap_target();
        assert!(!model.drag_step(), "nothing to do at the target");
        let mut target = *model.target();
        target.translation.vector.x -= 40.0;
        model.set_target(target);
        model.set_task(Task::Position);
        let mut steps = 0;
        while model.drag_step() {
            steps += 1;
            assert!(
                steps < 200,
                "the drag converges: {:?} at {:?}",
                model.ik(),
                model.q()
            );
        }
        assert_eq!(model.ik().reach, Reach::Reached);
        assert!(model.ik().position_error < 1e-6);
    }

    #[test]
    fn an_unreachable_target_is_out_of_reach_until_moved_back() {
        let mut model = Model::new(Session::for_preset("planar-2r").expect("preset"));
        model.set_task(Task::Position);
        let mut target = *model.target();
        target.translation.vector = nalgebra::Vector3::new(5.0, 1.0, 0.0);
        model.set_target(target);
        for _ in 0..100 {
            model.drag_step();
        }
        assert_eq!(model.ik().reach, Reach::OutOfReach);
        model.snap_target();
        assert_eq!(model.ik().reach, Reach::Reached);
    }

    #[test]
    fn the_closed_form_is_kept_only_where_the_robot_has_one() {
        let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
        model.set_method(IkMethod::ClosedForm);
        assert_eq!(model.method(), IkMethod::ClosedForm);
        model.load_robot(
            preset("panda").expect("preset"),
            RobotSource::Preset("panda".into()),
        );
        assert_eq!(model.method(), IkMethod::DampedLeastSquares);
        model.set_method(IkMethod::ClosedForm);
        assert_eq!(model.method(), IkMethod::DampedLeastSquares);
    }

    /// A random q of `robot` (within its limits) whose closed-form branch is `branch`.
    fn q_on_branch(robot: &Robot, branch: Branch, rng: &mut SplitMix64) -> Vec<f64> {
        loop {
            let q = rng.joint_vector(robot);
            if branch_of(robot, &q).ok().flatten() == Some(branch) {
                return q;
            }
        }
    }

    #[test]
    fn a_closed_form_drag_keeps_its_branch_by_label_and_says_when_it_vanishes() {
        let mut rng = SplitMix64::new(12);
        let mut model = Model::new(Session::for_preset("ur10").expect("preset"));
        model.set_method(IkMethod::ClosedForm);
        model.set_task(Task::FullPose);
        let robot = model.robot().clone();
        // Kept: targets of the arm's own branch, reached on that branch.
        for _ in 0..20 {
            let start = rng.joint_vector(&robot);
            let Some(branch) = branch_of(&robot, &start).expect("a valid q") else {
                panic!("the UR10 has a closed form");
            };
            model.set_q(start);
            let goal = q_on_branch(&robot, branch, &mut rng);
            model.set_target(tool_pose(&robot, &goal));
            for _ in 0..200 {
                if !model.drag_step() {
                    break;
                }
                assert_eq!(model.kept_branch(), Some(branch), "the label is kept");
            }
            assert_eq!(model.ik().reach, Reach::Reached);
            assert_eq!(branch_of(&robot, model.q()).ok().flatten(), Some(branch));
            assert_eq!(model.branch_switch(), None);
        }
        // Vanished: a target with only some branches, the arm on a missing one.
        let mut switched = 0;
        for _ in 0..2000 {
            let goal = rng.joint_vector(&robot);
            let target = tool_pose(&robot, &goal);
            let set = closed_form_solutions(&robot, &target, &goal).expect("a valid target");
            let present: Vec<Branch> = set
                .solutions
                .iter()
                .filter(|s| s.exact)
                .map(|s| s.branch)
                .collect();
            let Some(missing) = [false, true]
                .iter()
                .flat_map(|&left| [false, true].map(|up| (left, up)))
                .flat_map(|(left, up)| {
                    [false, true].map(|flip| Branch {
                        shoulder: Some(if left {
                            Shoulder::Left
                        } else {
                            Shoulder::Right
                        }),
                        elbow: Some(if up { Elbow::Up } else { Elbow::Down }),
                        wrist: Some(if flip {
                            Wrist::Flipped
                        } else {
                            Wrist::NotFlipped
                        }),
                    })
                })
                .find(|b| !present.contains(b))
            else {
                continue;
            };
            model.set_q(q_on_branch(&robot, missing, &mut rng));
            model.set_target(target);
            model.drag_step();
            let Some((asked, taken)) = model.branch_switch() else {
                panic!("the branch {} vanished", missing.id());
            };
            assert_eq!(asked, missing);
            assert!(present.contains(&taken), "{} is a branch here", taken.id());
            assert_eq!(model.kept_branch(), Some(taken));
            switched += 1;
            if switched == 5 {
                break;
            }
        }
        assert_eq!(
            switched, 5,
            "targets with fewer than eight branches were found"
        );
    }

    #[test]
    fn a_stalled_drag_offers_the_start_that_reaches_and_says_out_of_reach_only_when_none_does() {
        let mut rng = SplitMix64::new(5);
        let mut model = Model::new(Session::for_preset("puma560").expect("preset"));
        model.set_method(IkMethod::DampedLeastSquares);
        let robot = model.robot().clone();
        let mut rescued = 0;
        for _ in 0..400 {
            model.set_q(rng.joint_vector(&robot));
            let goal = rng.joint_vector(&robot);
            model.set_target(tool_pose(&robot, &goal));
            for _ in 0..300 {
                if !model.drag_step() || model.ik().reach == Reach::OutOfReach {
                    break;
                }
            }
            if model.ik().reach != Reach::OutOfReach {
                continue;
            }
            // Every stall gets the search: which joint holds it, and the other starts.
            let rescue = model.rescue().cloned().expect("a stall is searched");
            // The target is FK of a q within the limits: some start usually reaches it.
            let Some(q) = rescue.reach.clone() else {
                assert_eq!(model.shown_reach(), Reach::OutOfReach);
                continue;
            };
            assert_eq!(
                model.shown_reach(),
                Reach::Pending,
                "not called out of reach"
            );
            if let Some((j, at_max)) = rescue.held {
                let joint = &robot.joints[j];
                let limit = if at_max {
                    joint.limits.max
                } else {
                    joint.limits.min
                };
                assert!((model.q()[j] - limit).abs() < 1e-5, "held at the limit");
            }
            model.take_rescue();
            assert!(
                joint_distance(&robot, model.q(), &q) < 1e-12,
                "the arm took it"
            );
            assert_eq!(
                model.ik().reach,
                Reach::Reached,
                "the other start reaches it"
            );
            rescued += 1;
            if rescued == 3 {
                break;
            }
        }
        assert!(rescued >= 3, "{rescued} stalls were rescued");
        // Far away: out of reach from every start, and said so.
        let mut far = *model.target();
        far.translation.vector *= 50.0;
        model.set_target(far);
        for _ in 0..300 {
            if !model.drag_step() || model.ik().reach == Reach::OutOfReach {
                break;
            }
        }
        assert_eq!(model.shown_reach(), Reach::OutOfReach);
        if let Some(rescue) = model.rescue() {
            assert_eq!(rescue.reach, None);
        }
    }
}
