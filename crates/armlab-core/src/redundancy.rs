//! Self-motion of a redundant arm (docs/kinematics.md §11): the joints move through the
//! null space of the task Jacobian while the tool keeps its task pose — the Panda's elbow
//! swinging with the hand held still.
//!
//! Defined where the null space is one-dimensional (one joint more than task rows: the
//! Panda on a full pose, a 6-joint arm on a 5D task, a 4-joint arm on a position task).
//! Its direction there is exact and continuous: the generalised cross product of the task
//! rows (the cofactors of the rows with each column left out), so the slider's "+" is the
//! same direction every time the same pose is opened.

use nalgebra::{DMatrix, DVector, IsometryMatrix3};

use super::error::RobotError;
use super::fk::{ForwardKinematics, tool_pose};
use super::ik::pose_error;
use super::jacobian::{Task, geometric_jacobian, task_jacobian};
use super::orientation::rotation_log;
use super::robot::Robot;

/// Arc length in joint space (rad for revolute joints) of one integration step.
const STEP: f64 = 0.01;
/// Task error (robot units and rad) each step's correction reaches.
const TOLERANCE: f64 = 1e-11;
/// Newton corrections per step at most.
const CORRECTIONS: usize = 12;
/// The largest sweep one call makes (|s| in rad of joint-space arc length).
pub const MAX_SWEEP: f64 = 10.0;

/// Why the arm cannot move in its null space here.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SelfMotionError {
    /// The null space is not one-dimensional for this task: `joints − rows` is not 1.
    #[error(
        "self-motion needs exactly one joint more than task rows ({joints} joints, {rows} task rows)"
    )]
    NotOneDimensional {
        /// The arm's joint count.
        joints: usize,
        /// The task's row count.
        rows: usize,
    },
    /// The task rows lose rank at the start or on the way (a singular pose): the null
    /// space has more than one direction there.
    #[error("the arm is at a singular pose, where the self-motion is not one curve")]
    Singular,
    /// The pose could not be computed (non-finite values).
    #[error(transparent)]
    Robot(#[from] RobotError),
}

/// Where a sweep ended.
#[derive(Debug, Clone, PartialEq)]
pub struct SelfMotion {
    /// The joint values at the end of the sweep.
    pub q: Vec<f64>,
    /// The arc length actually travelled (signed like the request): shorter than asked
    /// when a joint reached its limit.
    pub travelled: f64,
    /// The joint (0-based) whose limit stopped the sweep, if one did.
    pub stopped_by: Option<usize>,
    /// The largest position error left after any step (robot units).
    pub max_position_error: f64,
    /// The largest task orientation error left after any step (rad).
    pub max_orientation_error: f64,
}

/// The unit null-space direction of the task rows at `q` (the generalised cross product
/// of the rows), or an error when the rows have lost rank.
pub fn null_direction(
    robot: &Robot,
    q: &[f64],
    task: Task,
) -> Result<DVector<f64>, SelfMotionError> {
    let rows = rows_at(robot, q, task)?;
    cross_product(&rows)
}

fn rows_at(robot: &Robot, q: &[f64], task: Task) -> Result<DMatrix<f64>, SelfMotionError> {
    let n = robot.dof();
    let m = task.rows();
    if n != m + 1 {
        return Err(SelfMotionError::NotOneDimensional { joints: n, rows: m });
    }
    let fk = ForwardKinematics::new(robot, q)?;
    // Linear rows divided by the arm's length so that lengths and angles weigh alike.
    Ok(task_jacobian(
        &geometric_jacobian(&fk),
        task,
        fk.tool_rotation(),
        1.0 / robot.length_scale(),
    ))
}

/// n_i = (−1)^i det(rows without column i): orthogonal to every row, nonzero exactly when
/// the rows have full rank.
fn cross_product(rows: &DMatrix<f64>) -> Result<DVector<f64>, SelfMotionError> {
    let n = rows.ncols();
    let v = DVector::from_iterator(
        n,
        (0..n).map(|i| {
            let minor = rows.clone().remove_column(i);
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            sign * minor.determinant()
        }),
    );
    let norm = v.norm();
    if !norm.is_finite() || norm < 1e-9 {
        return Err(SelfMotionError::Singular);
    }
    Ok(v / norm)
}

/// The task error of `q` against the pose `goal`: position (÷ the length scale) and the
/// rotation vector, in the task's rows.
fn task_error(robot: &Robot, q: &[f64], goal: &IsometryMatrix3<f64>, task: Task) -> DVector<f64> {
    let pose = tool_pose(robot, q);
    let scale = 1.0 / robot.length_scale();
    let dp = (goal.translation.vector - pose.translation.vector) * scale;
    let w = rotation_log(&(goal.rotation * pose.rotation.inverse()).into_inner());
    let r = pose.rotation.matrix();
    let mut e = DVector::zeros(task.rows());
    e.rows_mut(0, 3).copy_from(&dp);
    match task {
        Task::Position => {}
        Task::FullPose => e.rows_mut(3, 3).copy_from(&w),
        Task::PositionAndAxis(axis) => {
            let k = axis.index();
            e[3] = r.column((k + 1) % 3).dot(&w);
            e[4] = r.column((k + 2) % 3).dot(&w);
        }
    }
    e
}

/// Moves `q0` along the self-motion by the signed joint-space arc length `s` (at most
/// [`MAX_SWEEP`]), keeping the tool's task pose: steps of 0.01 rad along the null
/// direction (midpoint rule), each followed by minimum-norm Newton corrections back onto
/// the start pose. Stops at the first joint limit on the way.
pub fn self_motion(
    robot: &Robot,
    q0: &[f64],
    task: Task,
    s: f64,
) -> Result<SelfMotion, SelfMotionError> {
    let s = if s.is_finite() {
        s.clamp(-MAX_SWEEP, MAX_SWEEP)
    } else {
        0.0
    };
    let goal = ForwardKinematics::new(robot, q0)?.base_from_tool;
    let mut q = DVector::from_column_slice(q0);
    let mut dir = null_direction(robot, q0, task)?;
    let sign = s.signum();
    let steps = (s.abs() / STEP).ceil() as usize;
    let mut travelled = 0.0;
    let (mut max_position_error, mut max_orientation_error) = (0.0f64, 0.0f64);
    for k in 0..steps {
        let h = (s.abs() - k as f64 * STEP).min(STEP) * sign;
        let mid = &q + &dir * (h / 2.0);
        let mut mid_dir = null_direction(robot, mid.as_slice(), task)?;
        if mid_dir.dot(&dir) < 0.0 {
            mid_dir = -mid_dir;
        }
        let mut next = &q + &mid_dir * h;
        for _ in 0..CORRECTIONS {
            let e = task_error(robot, next.as_slice(), &goal, task);
            if e.norm() < TOLERANCE {
                break;
            }
            let rows = rows_at(robot, next.as_slice(), task)?;
            let step = rows
                .pseudo_inverse(1e-12)
                .map_err(|_| SelfMotionError::Singular)?
                * e;
            next += step;
        }
        let (p, o) = pose_error(robot, next.as_slice(), &goal, task);
        max_position_error = max_position_error.max(p);
        max_orientation_error = max_orientation_error.max(o);
        if let Some(j) = robot
            .joints
            .iter()
            .zip(next.iter())
            .position(|(joint, v)| !joint.limits.contains(*v, 1e-9))
        {
            return Ok(SelfMotion {
                q: q.as_slice().to_vec(),
                travelled,
                stopped_by: Some(j),
                max_position_error,
                max_orientation_error,
            });
        }
        let mut next_dir = null_direction(robot, next.as_slice(), task)?;
        if next_dir.dot(&mid_dir) < 0.0 {
            next_dir = -next_dir;
        }
        q = next;
        dir = next_dir;
        travelled += h;
    }
    Ok(SelfMotion {
        q: q.as_slice().to_vec(),
        travelled,
        stopped_by: None,
        max_position_error,
        max_orientation_error,
    })
}
