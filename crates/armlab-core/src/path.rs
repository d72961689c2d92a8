//! Paths from pose A to pose B (docs/kinematics.md §19): interpolation in joint space
//! (the tool draws a curve) and a straight line in Cartesian space with the orientation
//! interpolated by quaternion slerp, solved by IK at every step, warm-started from the
//! step before. Where the line leaves the workspace, crosses a singularity or makes the
//! arm jump to another configuration, the path says so with the step and its parameter s.
//! Waypoint lists chain such paths.

use nalgebra::{IsometryMatrix3, Rotation3, Translation3, UnitQuaternion};

use super::fk::{ForwardKinematics, tool_pose};
use super::ik::{BadTarget, IkMethod, IkSettings, IkSolver};
use super::jacobian::{Task, geometric_jacobian, jacobian_measures};
use super::motion_error::{MotionError, Setting};
use super::profile::joint_distance_to;
use super::robot::{JointKind, Robot};

/// The most steps one path segment may have.
pub const MAX_PATH_STEPS: usize = 100_000;
/// The most waypoints a list may hold.
pub const MAX_WAYPOINTS: usize = 1000;
/// A step of a Cartesian path that moves some revolute joint by more than this (radians;
/// a prismatic joint: this fraction of π of its stroke) is reported as a jump.
pub const JUMP_LIMIT: f64 = 0.5;

/// How a path goes from one pose to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum PathKind {
    /// `q(s) = q_A + s·(q_B − q_A)` (wrapped for wrapping joints): every joint moves
    /// evenly; the tool draws a curve.
    #[default]
    Joint,
    /// `p(s) = p_A + s·(p_B − p_A)`, `R(s) = slerp(R_A, R_B, s)`, q(s) by IK.
    Cartesian,
}

impl PathKind {
    /// The id used in links: `joint`, `line`.
    pub fn id(self) -> &'static str {
        match self {
            PathKind::Joint => "joint",
            PathKind::Cartesian => "line",
        }
    }

    /// The kind of an id.
    pub fn from_id(id: &str) -> Option<PathKind> {
        [PathKind::Joint, PathKind::Cartesian]
            .into_iter()
            .find(|k| k.id() == id)
    }
}

/// What went wrong at a step of a Cartesian path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PathIssue {
    /// IK found no pose on the line here: the line leaves the workspace (or the joint
    /// limits keep the arm from it).
    OutOfReach,
    /// The arm is at or near a singularity here (the smallest reach-scaled singular
    /// value of the task Jacobian is below the singularity threshold).
    Singular,
    /// Some joint moved by more than [`JUMP_LIMIT`] in one step: the arm changed
    /// configuration, and the tool leaves the line between the two steps.
    Jump,
}

impl PathIssue {
    /// The id the test hook and the JSON use: `out-of-reach`, `singular`, `jump`.
    pub fn id(self) -> &'static str {
        match self {
            PathIssue::OutOfReach => "out-of-reach",
            PathIssue::Singular => "singular",
            PathIssue::Jump => "jump",
        }
    }
}

/// One reported problem: a run of consecutive steps with the same issue is reported once,
/// at its first step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathProblem {
    /// The step's index in [`Path::points`].
    pub index: usize,
    /// The path parameter there (0 at A, 1 at B; the waypoint count at the end of a list).
    pub s: f64,
    /// What happened.
    pub issue: PathIssue,
}

/// One step of a path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    /// The path parameter (0 at the start; segment k runs from k to k + 1).
    pub s: f64,
    /// The joint values.
    pub q: Vec<f64>,
    /// The tool pose reached at `q` (on a Cartesian path, off the line where IK failed).
    pub tool: IsometryMatrix3<f64>,
}

/// A path: its steps and its problems.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Path {
    /// Every step, the start included.
    pub points: Vec<PathPoint>,
    /// The problems found, in order.
    pub problems: Vec<PathProblem>,
}

impl Path {
    /// The tool positions, for drawing the path in 3D.
    pub fn tool_positions(&self) -> impl Iterator<Item = nalgebra::Point3<f64>> + '_ {
        self.points
            .iter()
            .map(|p| nalgebra::Point3::from(p.tool.translation.vector))
    }

    /// The last step's joint values.
    pub fn end_q(&self) -> Option<&[f64]> {
        self.points.last().map(|p| p.q.as_slice())
    }
}

/// A validated list of tool poses to visit in order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Waypoints {
    poses: Vec<IsometryMatrix3<f64>>,
}

impl Waypoints {
    /// Checks every pose (finite, a proper rotation) and the count
    /// (at most [`MAX_WAYPOINTS`]).
    pub fn new(poses: Vec<IsometryMatrix3<f64>>) -> Result<Waypoints, MotionError> {
        if poses.len() > MAX_WAYPOINTS {
            return Err(MotionError::TooLarge {
                setting: Setting::Waypoint(poses.len()),
                value: poses.len() as f64,
                max: MAX_WAYPOINTS as f64,
            });
        }
        for (i, pose) in poses.iter().enumerate() {
            check_pose(Setting::Waypoint(i + 1), pose)?;
        }
        Ok(Waypoints { poses })
    }

    /// Adds a pose at the end (checked; the list is unchanged on an error).
    pub fn push(&mut self, pose: IsometryMatrix3<f64>) -> Result<(), MotionError> {
        self.insert(self.poses.len(), pose)
    }

    /// Inserts a pose at `index` (clamped to the end).
    pub fn insert(&mut self, index: usize, pose: IsometryMatrix3<f64>) -> Result<(), MotionError> {
        let n = self.poses.len() + 1;
        if n > MAX_WAYPOINTS {
            return Err(MotionError::TooLarge {
                setting: Setting::Waypoint(n),
                value: n as f64,
                max: MAX_WAYPOINTS as f64,
            });
        }
        let index = index.min(self.poses.len());
        check_pose(Setting::Waypoint(index + 1), &pose)?;
        self.poses.insert(index, pose);
        Ok(())
    }

    /// Replaces waypoint `index` (0-based); `false` when there is none.
    pub fn set(&mut self, index: usize, pose: IsometryMatrix3<f64>) -> Result<bool, MotionError> {
        check_pose(Setting::Waypoint(index + 1), &pose)?;
        Ok(match self.poses.get_mut(index) {
            Some(slot) => {
                *slot = pose;
                true
            }
            None => false,
        })
    }

    /// Removes waypoint `index` (0-based), if there is one.
    pub fn remove(&mut self, index: usize) -> Option<IsometryMatrix3<f64>> {
        (index < self.poses.len()).then(|| self.poses.remove(index))
    }

    /// The poses, in order.
    pub fn poses(&self) -> &[IsometryMatrix3<f64>] {
        &self.poses
    }

    /// Number of waypoints.
    pub fn len(&self) -> usize {
        self.poses.len()
    }

    /// Whether the list is empty.
    pub fn is_empty(&self) -> bool {
        self.poses.is_empty()
    }
}

fn check_pose(setting: Setting, pose: &IsometryMatrix3<f64>) -> Result<(), MotionError> {
    let r = pose.rotation.matrix();
    let finite =
        pose.translation.vector.iter().all(|v| v.is_finite()) && r.iter().all(|v| v.is_finite());
    if !finite {
        return Err(MotionError::BadPose {
            setting,
            why: BadTarget::NotFinite,
        });
    }
    let orthonormal = (r.transpose() * r - nalgebra::Matrix3::identity())
        .abs()
        .max();
    if orthonormal > 1e-6 || r.determinant() < 0.0 {
        return Err(MotionError::BadPose {
            setting,
            why: BadTarget::NotRotation,
        });
    }
    Ok(())
}

fn check_steps(steps: usize) -> Result<(), MotionError> {
    if steps == 0 || steps > MAX_PATH_STEPS {
        return Err(MotionError::TooLarge {
            setting: Setting::PathSteps,
            value: steps as f64,
            max: MAX_PATH_STEPS as f64,
        });
    }
    Ok(())
}

/// The pose a fraction `s` along the straight line from `a` to `b`: position linearly
/// interpolated, orientation by quaternion slerp (the shortest rotation; for two
/// orientations half a turn apart, where slerp has no unique path, a fixed one of the
/// two half-turn ways).
pub fn interpolate_pose(
    a: &IsometryMatrix3<f64>,
    b: &IsometryMatrix3<f64>,
    s: f64,
) -> IsometryMatrix3<f64> {
    let p = a.translation.vector.lerp(&b.translation.vector, s);
    let qa = UnitQuaternion::from_rotation_matrix(&a.rotation);
    let qb = UnitQuaternion::from_rotation_matrix(&b.rotation);
    let q = qa.try_slerp(&qb, s, 1e-12).unwrap_or_else(|| {
        // Half a turn apart: turn about the axis of qa⁻¹·qb (any axis of that half turn).
        let rel = qa.inverse() * qb;
        let axis = rel.axis().unwrap_or(nalgebra::Vector3::x_axis());
        qa * UnitQuaternion::from_axis_angle(&axis, s * rel.angle())
    });
    IsometryMatrix3::from_parts(Translation3::from(p), Rotation3::from(q))
}

/// The joint-space path from `from` to `to` in `steps` equal steps: joint i moves by
/// [`joint_distance_to`] scaled by s.
pub fn joint_path(
    robot: &Robot,
    from: &[f64],
    to: &[f64],
    steps: usize,
) -> Result<Path, MotionError> {
    robot.check_q(from)?;
    robot.check_q(to)?;
    check_steps(steps)?;
    let mut path = Path::default();
    append_joint_segment(robot, from, to, steps, 0.0, &mut path)?;
    Ok(path)
}

fn append_joint_segment(
    robot: &Robot,
    from: &[f64],
    to: &[f64],
    steps: usize,
    s0: f64,
    path: &mut Path,
) -> Result<(), MotionError> {
    let distance: Vec<f64> = robot
        .joints
        .iter()
        .zip(from.iter().zip(to))
        .map(|(j, (a, b))| joint_distance_to(j, *a, *b))
        .collect();
    let mut fk = ForwardKinematics::new(robot, from)?;
    let first = if path.points.is_empty() { 0 } else { 1 };
    for k in first..=steps {
        let s = k as f64 / steps as f64;
        let q: Vec<f64> = if k == steps {
            // The end exactly as given (a wrapped distance added to `from` may land a
            // turn away from `to`).
            to.to_vec()
        } else {
            from.iter().zip(&distance).map(|(a, d)| a + s * d).collect()
        };
        fk.update(robot, &q);
        path.points.push(PathPoint {
            s: s0 + s,
            q,
            tool: fk.base_from_tool,
        });
    }
    Ok(())
}

/// How a Cartesian path solves IK at each step.
#[derive(Debug, Clone, PartialEq)]
pub struct CartesianSettings {
    /// The task rows IK satisfies (the full pose for arms of six or more joints).
    pub task: Task,
    /// The IK method.
    pub method: IkMethod,
    /// IK settings; restarts are turned off (a random restart would leave the line's
    /// branch).
    pub ik: IkSettings,
    /// Steps per segment.
    pub steps: usize,
}

impl CartesianSettings {
    /// The defaults for `robot`: its default task, damped least squares, 100 steps.
    pub fn for_robot(robot: &Robot) -> CartesianSettings {
        CartesianSettings {
            task: Task::default_for(robot.dof()),
            method: IkMethod::DampedLeastSquares,
            ik: IkSettings {
                restarts: 0,
                max_iterations: 100,
                budget: 100,
                ..IkSettings::default()
            },
            steps: 100,
        }
    }
}

/// The straight Cartesian path from the tool pose at `from` to `target`: at every step
/// the interpolated pose ([`interpolate_pose`]) is solved by IK warm-started from the step
/// before. Steps where IK fails, the arm is near a singularity or jumps are reported in
/// [`Path::problems`]; the path goes on from the closest pose found.
pub fn cartesian_path(
    robot: &Robot,
    from: &[f64],
    target: &IsometryMatrix3<f64>,
    settings: &CartesianSettings,
    solver: &mut IkSolver,
) -> Result<Path, MotionError> {
    robot.check_q(from)?;
    check_pose(Setting::Waypoint(1), target)?;
    check_steps(settings.steps)?;
    let mut path = Path::default();
    append_cartesian_segment(robot, from, target, settings, solver, 0.0, &mut path)?;
    Ok(path)
}

fn append_cartesian_segment(
    robot: &Robot,
    from: &[f64],
    target: &IsometryMatrix3<f64>,
    settings: &CartesianSettings,
    solver: &mut IkSolver,
    s0: f64,
    path: &mut Path,
) -> Result<(), MotionError> {
    let start = tool_pose(robot, from);
    let mut fk = ForwardKinematics::new(robot, from)?;
    let ik = IkSettings {
        restarts: 0,
        ..settings.ik.clone()
    };
    let mut q = from.to_vec();
    let mut last_issue: [bool; 3] = [false; 3];
    let first = if path.points.is_empty() { 0 } else { 1 };
    for k in first..=settings.steps {
        let s = k as f64 / settings.steps as f64;
        let pose = interpolate_pose(&start, target, s);
        let mut issues = [false; 3];
        if k > 0 {
            let result = solver
                .solve(robot, &pose, settings.task, &q, settings.method, &ik)
                .map_err(MotionError::Ik)?;
            issues[0] = !result.success;
            issues[2] = joint_gap(robot, &q, &result.q) > JUMP_LIMIT;
            q = result.q;
        }
        fk.update(robot, &q);
        let measures = jacobian_measures(
            &geometric_jacobian(&fk),
            settings.task,
            fk.tool_rotation(),
            robot.reach(),
        );
        issues[1] = measures.near_singular;
        let index = path.points.len();
        for (n, issue) in [PathIssue::OutOfReach, PathIssue::Singular, PathIssue::Jump]
            .into_iter()
            .enumerate()
        {
            if issues[n] && !last_issue[n] {
                path.problems.push(PathProblem {
                    index,
                    s: s0 + s,
                    issue,
                });
            }
        }
        last_issue = issues;
        path.points.push(PathPoint {
            s: s0 + s,
            q: q.clone(),
            tool: fk.base_from_tool,
        });
    }
    Ok(())
}

/// The path from `from` through every waypoint in order, each segment of `kind`. A
/// joint-space segment goes to the IK answer of its waypoint (solved from the previous
/// segment's end); a Cartesian one follows the line. Segment k runs from s = k to k + 1.
pub fn waypoint_path(
    robot: &Robot,
    from: &[f64],
    waypoints: &Waypoints,
    kind: PathKind,
    settings: &CartesianSettings,
    solver: &mut IkSolver,
) -> Result<Path, MotionError> {
    robot.check_q(from)?;
    check_steps(settings.steps)?;
    let mut path = Path::default();
    let mut q = from.to_vec();
    for (k, pose) in waypoints.poses().iter().enumerate() {
        let s0 = k as f64;
        match kind {
            PathKind::Joint => {
                let ik = IkSettings {
                    restarts: settings.ik.restarts.max(20),
                    budget: settings.ik.budget.max(2000),
                    ..settings.ik.clone()
                };
                let result = solver
                    .solve(robot, pose, settings.task, &q, settings.method, &ik)
                    .map_err(MotionError::Ik)?;
                append_joint_segment(robot, &q, &result.q, settings.steps, s0, &mut path)?;
                if !result.success {
                    path.problems.push(PathProblem {
                        index: path.points.len() - 1,
                        s: s0 + 1.0,
                        issue: PathIssue::OutOfReach,
                    });
                }
                q = result.q;
            }
            PathKind::Cartesian => {
                append_cartesian_segment(robot, &q, pose, settings, solver, s0, &mut path)?;
                if let Some(end) = path.end_q() {
                    q = end.to_vec();
                }
            }
        }
    }
    if path.points.is_empty() {
        let fk = ForwardKinematics::new(robot, from)?;
        path.points.push(PathPoint {
            s: 0.0,
            q: from.to_vec(),
            tool: fk.base_from_tool,
        });
    }
    Ok(path)
}

/// The largest joint distance from `a` to `b` (a prismatic joint's as a fraction of π of
/// its stroke).
pub fn joint_gap(robot: &Robot, a: &[f64], b: &[f64]) -> f64 {
    robot
        .joints
        .iter()
        .zip(a.iter().zip(b))
        .map(|(j, (x, y))| {
            let d = joint_distance_to(j, *x, *y).abs();
            match j.kind {
                JointKind::Revolute => d,
                JointKind::Prismatic => {
                    d * std::f64::consts::PI / (j.limits.max - j.limits.min).max(1e-9)
                }
            }
        })
        .fold(0.0, f64::max)
}
