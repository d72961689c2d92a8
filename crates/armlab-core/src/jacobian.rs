//! The geometric Jacobian, its central-difference check, the task rows and the
//! unit-free measures (singular values, manipulability, det J, condition number).

use nalgebra::{DMatrix, DVector, Matrix3, Matrix3xX, Matrix6xX, Vector3, Vector6};

use super::fk::{ForwardKinematics, tool_pose};
use super::orientation::rotation_log;
use super::robot::{JointKind, Robot};

/// The step of the numerical Jacobian (docs/kinematics.md §4.2, as in the Metrover calculator).
pub const NUMERIC_EPSILON: f64 = 1e-6;

/// The smallest scaled singular value (linear rows divided by the reach) below which the
/// arm is flagged as at or near a singularity. 0.01 means: some task direction needs a
/// joint speed a hundred times that of the best-conditioned direction.
pub const SINGULARITY_THRESHOLD: f64 = 1e-2;

/// A tool axis, for the 5D task (position plus the direction of one tool axis).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ToolAxis {
    /// The tool frame's x axis.
    X,
    /// The tool frame's y axis.
    Y,
    /// The tool frame's z axis (the approach direction of most grippers).
    Z,
}

impl ToolAxis {
    /// Column index in a rotation matrix.
    pub fn index(self) -> usize {
        match self {
            ToolAxis::X => 0,
            ToolAxis::Y => 1,
            ToolAxis::Z => 2,
        }
    }
}

/// Which rows of the task the IK and the measures look at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Task {
    /// Tool position only: the three linear rows.
    Position,
    /// Tool position and the direction of one tool axis: five independent rows.
    PositionAndAxis(ToolAxis),
    /// Position and orientation: all six rows.
    FullPose,
}

impl Task {
    /// Every task, in menu order.
    pub const ALL: [Task; 5] = [
        Task::Position,
        Task::PositionAndAxis(ToolAxis::Z),
        Task::PositionAndAxis(ToolAxis::X),
        Task::PositionAndAxis(ToolAxis::Y),
        Task::FullPose,
    ];

    /// The id links and the JSON API use: `position`, `axis-x`, `axis-y`, `axis-z`,
    /// `full`.
    pub fn id(self) -> &'static str {
        match self {
            Task::Position => "position",
            Task::PositionAndAxis(ToolAxis::X) => "axis-x",
            Task::PositionAndAxis(ToolAxis::Y) => "axis-y",
            Task::PositionAndAxis(ToolAxis::Z) => "axis-z",
            Task::FullPose => "full",
        }
    }

    /// The task of an id, if it is one.
    pub fn from_id(id: &str) -> Option<Task> {
        Task::ALL.into_iter().find(|t| t.id() == id)
    }

    /// The task an arm opens with: the full pose with six joints or more, the position
    /// alone with fewer (five joints cannot set a whole pose, and a planar arm's
    /// textbook singularity shows in its position rows).
    pub fn default_for(dof: usize) -> Task {
        if dof >= 6 {
            Task::FullPose
        } else {
            Task::Position
        }
    }

    /// Every id, for messages: `position, axis-x, …`.
    pub fn id_list() -> String {
        Task::ALL.map(Task::id).join(", ")
    }

    /// The number of independent rows (3, 5 or 6).
    pub fn rows(self) -> usize {
        match self {
            Task::Position => 3,
            Task::PositionAndAxis(_) => 5,
            Task::FullPose => 6,
        }
    }
}

/// The geometric Jacobian (6×n, base frame): rows 0–2 the linear velocity of the tool
/// point, rows 3–5 the angular velocity. Column i, with z and o the axis and origin of
/// joint i (frame i−1 in standard DH, frame i in modified DH) and o_n the tool point:
/// revolute `J_v = z × (o_n − o)`, `J_ω = z`; prismatic `J_v = z`, `J_ω = 0`.
pub fn geometric_jacobian(fk: &ForwardKinematics) -> Matrix6xX<f64> {
    let mut j = Matrix6xX::zeros(fk.dof());
    geometric_jacobian_into(fk, &mut j);
    j
}

/// [`geometric_jacobian`] written into `j` (resized when its column count differs).
pub fn geometric_jacobian_into(fk: &ForwardKinematics, j: &mut Matrix6xX<f64>) {
    let n = fk.dof();
    if j.ncols() != n {
        *j = Matrix6xX::zeros(n);
    }
    let tool = fk.tool_position();
    for i in 0..n {
        let z = fk.joint_axes[i];
        let (v, w) = match fk.joint_kinds[i] {
            JointKind::Revolute => (z.cross(&(tool - fk.joint_origins[i])), z),
            JointKind::Prismatic => (z, Vector3::zeros()),
        };
        let mut col = j.column_mut(i);
        col.fixed_rows_mut::<3>(0).copy_from(&v);
        col.fixed_rows_mut::<3>(3).copy_from(&w);
    }
}

/// Random poses [`linear_motion_space`] samples.
const MOTION_SPACE_SAMPLES: usize = 16;

/// The directions the tool point can move in at some pose of the arm: an orthonormal basis
/// (columns) of the span of the Jacobian's linear rows over 16 seeded random joint vectors
/// within the limits (docs/kinematics.md §6.2). A planar arm's
/// is its plane (two columns): the direction out of the plane is never the arm's, so it is
/// never a direction the arm loses at a singularity. Most arms have all three.
pub fn linear_motion_space(robot: &Robot) -> Matrix3xX<f64> {
    let mut rng = super::rng::SplitMix64::new(0x5_1A6E);
    let mut gram = Matrix3::zeros();
    let mut fk = ForwardKinematics::default();
    for _ in 0..MOTION_SPACE_SAMPLES {
        fk.update(robot, &rng.joint_vector(robot));
        let j = geometric_jacobian(&fk);
        let jv = j.fixed_rows::<3>(0);
        gram += jv * jv.transpose();
    }
    let eigen = gram.symmetric_eigen();
    let largest = eigen.eigenvalues.iter().copied().fold(0.0, f64::max);
    let kept: Vec<Vector3<f64>> = (0..3)
        .filter(|&k| largest > 0.0 && eigen.eigenvalues[k] > 1e-12 * largest)
        .map(|k| eigen.eigenvectors.column(k).into_owned())
        .collect();
    Matrix3xX::from_columns(&kept)
}

/// The direction the tool point cannot move in at this pose, among the directions of
/// `space` ([`linear_motion_space`]): the weakest principal direction of the linear rows
/// of `j` within that space, when its singular value is below `ratio` times the strongest
/// (docs/kinematics.md §6.2). `None` away from a singularity.
pub fn lost_direction(
    j: &Matrix6xX<f64>,
    space: &Matrix3xX<f64>,
    ratio: f64,
) -> Option<Vector3<f64>> {
    let jv = j.fixed_rows::<3>(0);
    let gram: Matrix3<f64> = jv * jv.transpose();
    let strongest = gram.symmetric_eigenvalues().max();
    // A still arm (or a Jacobian with NaN) loses nothing it could name.
    if strongest.is_nan() || strongest <= 0.0 {
        return None;
    }
    // J_v's range lies in the space, so J_v·J_vᵀ is zero across it; weighing the directions
    // across it above the strongest makes the weakest direction the space's own.
    let across = Matrix3::identity() - space * space.transpose();
    let eigen = (gram + across * (2.0 * strongest)).symmetric_eigen();
    let (weakest, low) = eigen
        .eigenvalues
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))?;
    (low.max(0.0).sqrt() < ratio * strongest.sqrt())
        .then(|| eigen.eigenvectors.column(weakest).into_owned())
}

/// The Jacobian by central differences with step `eps` (docs/kinematics.md §4.2): linear rows
/// `(p(q+εe_i) − p(q−εe_i))/2ε`, angular rows `vee(log(R(q+εe_i)·R(q−εe_i)ᵀ))/2ε`.
pub fn numerical_jacobian(robot: &Robot, q: &[f64], eps: f64) -> Matrix6xX<f64> {
    let n = robot.dof();
    let mut j = Matrix6xX::zeros(n);
    let mut qq = q.to_vec();
    qq.resize(n, 0.0);
    for i in 0..n {
        let q0 = qq[i];
        qq[i] = q0 + eps;
        let plus = tool_pose(robot, &qq);
        qq[i] = q0 - eps;
        let minus = tool_pose(robot, &qq);
        qq[i] = q0;
        let v = (plus.translation.vector - minus.translation.vector) / (2.0 * eps);
        let r = plus.rotation.matrix() * minus.rotation.matrix().transpose();
        let w = rotation_log(&r) / (2.0 * eps);
        let mut col = j.column_mut(i);
        col.fixed_rows_mut::<3>(0).copy_from(&v);
        col.fixed_rows_mut::<3>(3).copy_from(&w);
    }
    j
}

/// The task rows of a 6×n Jacobian at the tool rotation `tool_rotation`, with the linear
/// rows multiplied by `linear_scale` (1 for the raw Jacobian, 1/reach for the measures):
/// position → rows 0–2; 5D → rows 0–2 and the angular rows projected on the two
/// directions perpendicular to the chosen tool axis (turning about the axis itself does
/// not change its direction); full pose → all six.
pub fn task_jacobian(
    j: &Matrix6xX<f64>,
    task: Task,
    tool_rotation: &nalgebra::Matrix3<f64>,
    linear_scale: f64,
) -> DMatrix<f64> {
    let n = j.ncols();
    let mut out = DMatrix::zeros(task.rows(), n);
    out.rows_mut(0, 3)
        .copy_from(&(j.fixed_rows::<3>(0) * linear_scale));
    match task {
        Task::Position => {}
        Task::FullPose => out.rows_mut(3, 3).copy_from(&j.fixed_rows::<3>(3)),
        Task::PositionAndAxis(axis) => {
            let k = axis.index();
            let u = tool_rotation.column((k + 1) % 3).into_owned();
            let w = tool_rotation.column((k + 2) % 3).into_owned();
            let angular = j.fixed_rows::<3>(3);
            out.row_mut(3).copy_from(&(u.transpose() * angular));
            out.row_mut(4).copy_from(&(w.transpose() * angular));
        }
    }
    out
}

/// The measures of the task Jacobian as the matrices panel displays it, in the robot's
/// units: a student who computes det J of the displayed rows gets [`Self::determinant`].
/// They change with the length unit (det J and the manipulability scale with L³, the
/// three linear rows each carrying one length); the unit-free versions are
/// [`JacobianMeasures`]' other fields.
#[derive(Debug, Clone, PartialEq)]
pub struct DisplayedMeasures {
    /// √det(J·Jᵀ) (or √det(Jᵀ·J) with fewer joints than task rows) of the unscaled rows.
    pub manipulability: f64,
    /// det J of the unscaled task rows, when square.
    pub determinant: Option<f64>,
    /// σ_max/σ_min of the unscaled rows; `None` when exactly singular.
    pub condition_number: Option<f64>,
}

/// The unit-free measures of a task Jacobian (docs/kinematics.md §6), and the same
/// measures of the rows as displayed.
#[derive(Debug, Clone, PartialEq)]
pub struct JacobianMeasures {
    /// The characteristic length the linear rows were divided by
    /// ([`Robot::length_scale`]: the same for every DH table of the same arm).
    pub length_scale: f64,
    /// Singular values of the scaled task Jacobian, largest first.
    pub singular_values: Vec<f64>,
    /// The product of the singular values: Yoshikawa's manipulability √det(J·Jᵀ) when
    /// the arm has at least as many joints as task rows, √det(Jᵀ·J) when it has fewer
    /// (docs/kinematics.md §6).
    pub manipulability: f64,
    /// det J of the scaled task Jacobian, when it is square.
    pub determinant: Option<f64>,
    /// σ_max/σ_min; `None` when σ_min is zero (exactly singular).
    pub condition_number: Option<f64>,
    /// The smallest of the min(rows, joints) singular values is below
    /// [`SINGULARITY_THRESHOLD`]. (An arm with fewer joints than task rows always lacks
    /// some task direction; that alone does not set the flag.)
    pub near_singular: bool,
    /// The measures of the unscaled rows, in the robot's units.
    pub displayed: DisplayedMeasures,
}

/// The most sweeps the singular-value decomposition of [`jacobian_measures`] may take (a
/// 6×64 Jacobian converges in a few dozen).
pub const MAX_SVD_ITERATIONS: usize = 1000;

impl JacobianMeasures {
    /// The measures of a Jacobian that holds a value that is not finite, or whose SVD did
    /// not converge within [`MAX_SVD_ITERATIONS`]: no singular values, manipulability 0,
    /// no determinant or condition number, flagged singular. `ForwardKinematics::new`
    /// refuses a pose that is not finite, so the JSON API never shows these.
    fn not_computed(length_scale: f64) -> Self {
        JacobianMeasures {
            length_scale,
            singular_values: Vec::new(),
            manipulability: 0.0,
            determinant: None,
            condition_number: None,
            near_singular: true,
            displayed: DisplayedMeasures {
                manipulability: 0.0,
                determinant: None,
                condition_number: None,
            },
        }
    }
}

/// The measures of one matrix: singular values (largest first), their product, det when
/// square, and σ_max/σ_min. `None` when a value is not finite (it never reaches the
/// decomposition: NaN or infinity would keep it from converging) or the SVD does not
/// converge within [`MAX_SVD_ITERATIONS`] (nalgebra's default tolerance, 5ε).
type Singular = (Vec<f64>, f64, Option<f64>, Option<f64>);

fn singular_measures(rows: &DMatrix<f64>) -> Option<Singular> {
    if !rows.iter().all(|v| v.is_finite()) {
        return None;
    }
    let (m, n) = rows.shape();
    let svd = rows
        .clone()
        .try_svd(false, false, 5.0 * f64::EPSILON, MAX_SVD_ITERATIONS)?;
    let mut singular_values: Vec<f64> = svd.singular_values.iter().copied().collect();
    singular_values.sort_by(|a, b| b.total_cmp(a));
    let product = singular_values.iter().product();
    let determinant = (m == n).then(|| rows.determinant());
    let smallest = singular_values.last().copied().unwrap_or(0.0);
    let largest = singular_values.first().copied().unwrap_or(0.0);
    let condition_number = (smallest > 0.0).then(|| largest / smallest);
    Some((singular_values, product, determinant, condition_number))
}

/// Measures of the task rows of `j` at the given tool rotation, with the linear rows
/// divided by `length_scale` so that mm and m, and every DH table of the same arm, give
/// the same numbers; and the same measures of the rows as displayed.
pub fn jacobian_measures(
    j: &Matrix6xX<f64>,
    task: Task,
    tool_rotation: &nalgebra::Matrix3<f64>,
    length_scale: f64,
) -> JacobianMeasures {
    let scaled = task_jacobian(j, task, tool_rotation, 1.0 / length_scale);
    let Some((singular_values, manipulability, determinant, condition_number)) =
        singular_measures(&scaled)
    else {
        return JacobianMeasures::not_computed(length_scale);
    };
    let smallest = singular_values.last().copied().unwrap_or(0.0);
    let raw = task_jacobian(j, task, tool_rotation, 1.0);
    let (raw_manipulability, raw_determinant, raw_condition) =
        singular_measures(&raw).map_or((0.0, None, None), |(_, w, d, c)| (w, d, c));
    JacobianMeasures {
        length_scale,
        singular_values,
        manipulability,
        determinant,
        condition_number,
        near_singular: smallest < SINGULARITY_THRESHOLD,
        displayed: DisplayedMeasures {
            manipulability: raw_manipulability,
            determinant: raw_determinant,
            condition_number: raw_condition,
        },
    }
}

/// Velocity kinematics `ẋ = J(q)·q̇`: the tool's linear velocity (rows 0–2, length units
/// per second) and angular velocity (rows 3–5, rad/s).
pub fn tool_velocity(j: &Matrix6xX<f64>, q_dot: &[f64]) -> Vector6<f64> {
    let qd = DVector::from_iterator(
        j.ncols(),
        (0..j.ncols()).map(|i| q_dot.get(i).copied().unwrap_or(0.0)),
    );
    j * qd
}

/// Relative agreement the central-difference Jacobian must reach with the geometric one:
/// every entry within `JACOBIAN_AGREEMENT · max(1, ‖J‖)`.
pub const JACOBIAN_AGREEMENT: f64 = 1e-5;

/// The Jacobian of a pose as the matrices panel and the JSON API show it: the geometric
/// Jacobian, its central-difference check (ε = [`NUMERIC_EPSILON`]) and their largest
/// difference against the tolerance `JACOBIAN_AGREEMENT · max(1, ‖J‖)`, and the
/// reach-scaled measures of the task rows ([`jacobian_measures`]).
#[derive(Debug, Clone, PartialEq)]
pub struct JacobianAnalysis {
    /// The geometric Jacobian (6 × n, base frame).
    pub geometric: Matrix6xX<f64>,
    /// The central-difference Jacobian (6 × n).
    pub numerical: Matrix6xX<f64>,
    /// The largest absolute difference of the two, entry by entry.
    pub max_difference: f64,
    /// The largest difference that counts as agreement.
    pub tolerance: f64,
    /// Whether the two agree within the tolerance.
    pub agrees: bool,
    /// Singular values, manipulability, det J, condition number, singularity flag.
    pub measures: JacobianMeasures,
}

impl JacobianAnalysis {
    /// The analysis at the pose `fk` (forward kinematics of `robot` at `q`) for `task`.
    pub fn new(robot: &Robot, fk: &ForwardKinematics, q: &[f64], task: Task) -> Self {
        let geometric = geometric_jacobian(fk);
        let numerical = numerical_jacobian(robot, q, NUMERIC_EPSILON);
        let max_difference = (&geometric - &numerical).abs().max();
        let tolerance = JACOBIAN_AGREEMENT * geometric.norm().max(1.0);
        let measures =
            jacobian_measures(&geometric, task, fk.tool_rotation(), robot.length_scale());
        JacobianAnalysis {
            agrees: max_difference <= tolerance,
            geometric,
            numerical,
            max_difference,
            tolerance,
            measures,
        }
    }
}
