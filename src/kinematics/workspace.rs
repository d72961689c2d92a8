//! The reachable workspace, sampled (docs/kinematics.md §12): tool positions from random
//! joint vectors within the limits, each with a measure of how well the arm can move
//! there. Filled in slices ([`WorkspaceCloud::fill`]) so that a page can spread the work
//! over frames; the core has no clock, so a slice is a number of samples.

use nalgebra::{Matrix3, Vector3};

use super::fk::ForwardKinematics;
use super::rng::SplitMix64;
use super::robot::{JointKind, Robot};

/// The measure each sample carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum WorkspaceMeasure {
    /// Yoshikawa's manipulability of the linear rows, `√det(J̃v·J̃vᵀ)` from the 3×3
    /// determinant (no SVD), with J̃v = Jv / L (L = [`Robot::length_scale`], as the
    /// measures of docs/kinematics.md §6): 0 at a singularity. With
    /// fewer than three joints, `√det(J̃vᵀ·J̃v)`.
    #[default]
    Manipulability,
    /// The distance to a singularity: the smallest singular value σ_min of J̃v, the square
    /// root of the smallest eigenvalue of J̃v·J̃vᵀ (closed form for a symmetric 3×3).
    SigmaMin,
}

impl WorkspaceMeasure {
    /// The id for links and the JSON API: `manipulability`, `sigma-min`.
    pub fn id(self) -> &'static str {
        match self {
            WorkspaceMeasure::Manipulability => "manipulability",
            WorkspaceMeasure::SigmaMin => "sigma-min",
        }
    }
}

/// The sampled point nearest a query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearestSample {
    /// Index into [`WorkspaceCloud::positions`].
    pub index: usize,
    /// Its distance from the query, in the robot's length unit.
    pub distance: f64,
}

/// A point cloud of tool positions, filled incrementally.
#[derive(Debug, Clone)]
pub struct WorkspaceCloud {
    robot: Robot,
    measure: WorkspaceMeasure,
    rng: SplitMix64,
    fk: ForwardKinematics,
    q: Vec<f64>,
    inv_len: f64,
    target: usize,
    /// Tool positions in the world frame (robot units), in sampling order.
    pub positions: Vec<Vector3<f64>>,
    /// The measure at each position (unit-free).
    pub values: Vec<f64>,
    /// The joint vector of each sample (for "take the arm there"), when kept
    /// ([`WorkspaceCloud::keep_joint_vectors`]).
    pub joint_vectors: Vec<Vec<f64>>,
    keep_q: bool,
    min: Vector3<f64>,
    max: Vector3<f64>,
    largest_value: f64,
    farthest: f64,
}

impl WorkspaceCloud {
    /// An empty cloud that will hold `samples` points of `robot` (cloned), drawn with
    /// [`SplitMix64`] from `seed`, each carrying `measure`.
    pub fn new(robot: &Robot, measure: WorkspaceMeasure, samples: usize, seed: u64) -> Self {
        WorkspaceCloud {
            robot: robot.clone(),
            measure,
            rng: SplitMix64::new(seed),
            fk: ForwardKinematics::default(),
            q: vec![0.0; robot.dof()],
            inv_len: 1.0 / robot.length_scale(),
            target: samples,
            positions: Vec::with_capacity(samples),
            values: Vec::with_capacity(samples),
            joint_vectors: Vec::new(),
            keep_q: false,
            min: Vector3::repeat(f64::INFINITY),
            max: Vector3::repeat(f64::NEG_INFINITY),
            largest_value: 0.0,
            farthest: 0.0,
        }
    }

    /// Keeps every sample's joint vector in [`WorkspaceCloud::joint_vectors`] (off by
    /// default: n numbers more per point).
    pub fn keep_joint_vectors(mut self) -> Self {
        self.joint_vectors = Vec::with_capacity(self.target);
        self.keep_q = true;
        self
    }

    /// The measure the samples carry.
    pub fn measure(&self) -> WorkspaceMeasure {
        self.measure
    }

    /// Adds up to `max_samples` more points (never beyond the size given to
    /// [`WorkspaceCloud::new`]); returns how many were added. A page calls it once per
    /// frame with a slice sized to its time budget.
    pub fn fill(&mut self, max_samples: usize) -> usize {
        let count = max_samples.min(self.target - self.positions.len());
        for _ in 0..count {
            for (v, joint) in self.q.iter_mut().zip(&self.robot.joints) {
                *v = self.rng.uniform(joint.limits.min, joint.limits.max);
            }
            self.fk.update(&self.robot, &self.q);
            let p = self.fk.base_from_tool.translation.vector;
            let value = match self.measure {
                WorkspaceMeasure::Manipulability => linear_manipulability(&self.fk, self.inv_len),
                WorkspaceMeasure::SigmaMin => linear_sigma_min(&self.fk, self.inv_len),
            };
            self.min = self.min.inf(&p);
            self.max = self.max.sup(&p);
            self.largest_value = self.largest_value.max(value);
            let base = self.robot.world_from_base.translation.vector;
            self.farthest = self.farthest.max((p - base).norm());
            self.positions.push(p);
            self.values.push(value);
            if self.keep_q {
                self.joint_vectors.push(self.q.clone());
            }
        }
        count
    }

    /// Points sampled so far.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// No point sampled yet.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Every point asked for is sampled.
    pub fn is_full(&self) -> bool {
        self.positions.len() >= self.target
    }

    /// The share sampled, 0 to 1.
    pub fn progress(&self) -> f64 {
        if self.target == 0 {
            1.0
        } else {
            self.positions.len() as f64 / self.target as f64
        }
    }

    /// The largest measure so far (for a colour scale), 0 when empty.
    pub fn largest_value(&self) -> f64 {
        self.largest_value
    }

    /// The farthest sampled point from the base origin: the outer reach found so far.
    pub fn outer_reach(&self) -> f64 {
        self.farthest
    }

    /// The corners of the box around the samples, `None` when empty.
    pub fn bounds(&self) -> Option<(Vector3<f64>, Vector3<f64>)> {
        (!self.is_empty()).then_some((self.min, self.max))
    }

    /// A typical distance between neighbouring samples: the edge of the cube holding one
    /// sample of the box's volume, `(V / N)^(1/3)` (flat boxes, as a planar arm's, use
    /// the area or length of their non-flat sides). 0 when empty.
    pub fn spacing(&self) -> f64 {
        let Some((lo, hi)) = self.bounds() else {
            return 0.0;
        };
        let extent = hi - lo;
        let big = extent.max() * 1e-9;
        let sides: Vec<f64> = extent.iter().copied().filter(|s| *s > big).collect();
        if sides.is_empty() {
            return 0.0;
        }
        let measure: f64 = sides.iter().product();
        (measure / self.len() as f64).powf(1.0 / sides.len() as f64)
    }

    /// The sampled point nearest `p` (a linear scan: 100 000 points in well under a
    /// millisecond), `None` when empty.
    pub fn nearest(&self, p: &Vector3<f64>) -> Option<NearestSample> {
        let mut best: Option<(usize, f64)> = None;
        for (i, x) in self.positions.iter().enumerate() {
            let d2 = (x - p).norm_squared();
            if best.is_none_or(|(_, b)| d2 < b) {
                best = Some((i, d2));
            }
        }
        best.map(|(index, d2)| NearestSample {
            index,
            distance: d2.sqrt(),
        })
    }

    /// Whether `p` lies inside the sampled workspace: a sampled point within
    /// `2 ·` [`WorkspaceCloud::spacing`] of it.
    pub fn contains(&self, p: &Vector3<f64>) -> bool {
        let spacing = self.spacing();
        self.nearest(p).is_some_and(|n| n.distance <= 2.0 * spacing)
    }
}

/// The linear rows' Gram matrix `J̃v·J̃vᵀ = Σ_i v_i·v_iᵀ` (3×3) with `v_i` joint i's
/// linear column divided by the reach, and the columns for the n×n `J̃vᵀ·J̃v` when n < 3.
fn linear_columns(fk: &ForwardKinematics, inv_len: f64) -> (Matrix3<f64>, [Vector3<f64>; 2]) {
    let tool = fk.tool_position();
    let mut m = Matrix3::zeros();
    let mut first = [Vector3::zeros(); 2];
    let joints = fk
        .joint_axes
        .iter()
        .zip(&fk.joint_origins)
        .zip(&fk.joint_kinds);
    for (i, ((z, o), kind)) in joints.enumerate() {
        let v = match kind {
            JointKind::Revolute => z.cross(&(tool - o)),
            JointKind::Prismatic => *z,
        } * inv_len;
        if let Some(slot) = first.get_mut(i) {
            *slot = v;
        }
        m += v * v.transpose();
    }
    (m, first)
}

/// `√det(J̃v·J̃vᵀ)`, or `√det(J̃vᵀ·J̃v)` with fewer than three joints (docs/kinematics.md
/// §12.1).
pub fn linear_manipulability(fk: &ForwardKinematics, inv_len: f64) -> f64 {
    let (m, cols) = linear_columns(fk, inv_len);
    let det = match fk.dof() {
        0 => 0.0,
        1 => cols[0].norm_squared(),
        2 => {
            let (a, b) = (cols[0], cols[1]);
            a.norm_squared() * b.norm_squared() - a.dot(&b).powi(2)
        }
        _ => m.determinant(),
    };
    det.max(0.0).sqrt()
}

/// The smallest singular value of J̃v (the smallest of min(3, n)), from the eigenvalues
/// of the symmetric 3×3 (or n×n) Gram matrix in closed form (docs/kinematics.md §12.1).
pub fn linear_sigma_min(fk: &ForwardKinematics, inv_len: f64) -> f64 {
    let (m, cols) = linear_columns(fk, inv_len);
    let smallest = match fk.dof() {
        0 => 0.0,
        1 => cols[0].norm_squared(),
        2 => {
            let (a, b) = (cols[0].norm_squared(), cols[1].norm_squared());
            let c = cols[0].dot(&cols[1]);
            let mean = 0.5 * (a + b);
            let half = (0.25 * (a - b) * (a - b) + c * c).sqrt();
            mean - half
        }
        _ => smallest_symmetric_eigenvalue(&m),
    };
    smallest.max(0.0).sqrt()
}

/// The smallest eigenvalue of a symmetric 3×3 matrix by the trigonometric solution of
/// its characteristic cubic (Smith 1961): with `q = tr/3`, `p = √(‖A − qI‖²_F / 6)` and
/// `r = det((A − qI)/p)/2`, the eigenvalues are `q + 2p·cos(φ + 2πk/3)`,
/// `φ = acos(r)/3`; the smallest is k = 1.
pub fn smallest_symmetric_eigenvalue(a: &Matrix3<f64>) -> f64 {
    let off = a[(0, 1)].powi(2) + a[(0, 2)].powi(2) + a[(1, 2)].powi(2);
    let q = a.trace() / 3.0;
    let d = Vector3::new(a[(0, 0)] - q, a[(1, 1)] - q, a[(2, 2)] - q);
    let p2 = (d.norm_squared() + 2.0 * off) / 6.0;
    if p2 <= 1e-300 {
        return q;
    }
    let p = p2.sqrt();
    let b = (a - Matrix3::identity() * q) / p;
    let r = (0.5 * b.determinant()).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos()
}

/// Where a stalled IK is held by a joint limit (docs/kinematics.md §12.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeldAtLimit {
    /// The joint's index (from 0).
    pub joint: usize,
    /// It sits at its upper limit (else its lower).
    pub at_max: bool,
    /// The joint's component of the descent direction `Jᵀe` (robot units): how hard the
    /// error pulls it past the limit.
    pub pull: f64,
}

/// The joints that hold the tool away from `target` at `q`: each joint within `slack`
/// of a limit whose component of the descent direction `Jᵀ·e` of ½‖e‖² (e the task
/// error, linear rows divided by the reach) points out of its range — the error would
/// fall if that joint could move on. Strongest pull first. Empty when nothing is at a
/// limit or the error does not push any joint outward.
pub fn joints_held_at_limits(
    robot: &Robot,
    q: &[f64],
    target: &nalgebra::IsometryMatrix3<f64>,
    task: super::jacobian::Task,
    slack: f64,
) -> Vec<HeldAtLimit> {
    use super::jacobian::{geometric_jacobian, task_jacobian};
    if q.len() != robot.dof() {
        return Vec::new();
    }
    let mut fk = ForwardKinematics::default();
    fk.update(robot, q);
    let inv_len = 1.0 / robot.reach();
    let j = task_jacobian(&geometric_jacobian(&fk), task, fk.tool_rotation(), inv_len);
    let e = super::ik::task_error_vector(target, &fk.base_from_tool, task, inv_len);
    let g = j.transpose() * e;
    let mut held: Vec<HeldAtLimit> = robot
        .joints
        .iter()
        .enumerate()
        .filter_map(|(i, joint)| {
            let pull = g[i];
            let at_max = q[i] >= joint.limits.max - slack && pull > 0.0;
            let at_min = q[i] <= joint.limits.min + slack && pull < 0.0;
            (at_max || at_min).then_some(HeldAtLimit {
                joint: i,
                at_max,
                pull: pull.abs(),
            })
        })
        .collect();
    held.sort_by(|a, b| {
        b.pull
            .partial_cmp(&a.pull)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    held
}

/// `n` unit directions spread evenly over the sphere (the Fibonacci lattice: heights
/// `z_k = 1 − (2k + 1)/n`, turned by the golden angle π(3 − √5) each).
pub fn sphere_directions(n: usize) -> Vec<Vector3<f64>> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|k| {
            let z = 1.0 - (2.0 * k as f64 + 1.0) / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let (s, c) = (golden * k as f64).sin_cos();
            Vector3::new(r * c, r * s, z)
        })
        .collect()
}

/// Whether the tool can point its `axis` along one direction at a position.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectionReach {
    /// The unit direction asked for.
    pub direction: Vector3<f64>,
    /// The 5D task (position + that axis) was solved within the settings' tolerances.
    pub reachable: bool,
    /// The joint vector found (the closest one when not reachable).
    pub q: Vec<f64>,
}

/// For each direction, whether the tool reaches `position` with its `axis` along it:
/// the 5D task of docs/kinematics.md §5 solved by damped least squares from `seed` (and
/// the settings' random restarts). For a 5-axis arm (the Metrover) this draws why five
/// joints cannot set a full pose: at one position only some directions are reachable.
/// Directions that are not unit vectors are normalised; a zero one is not reachable.
pub fn direction_reachability(
    robot: &Robot,
    position: &Vector3<f64>,
    axis: super::jacobian::ToolAxis,
    directions: &[Vector3<f64>],
    seed: &[f64],
    settings: &super::ik::IkSettings,
) -> Result<Vec<DirectionReach>, super::ik::IkError> {
    use super::ik::{IkMethod, IkSolver};
    use super::jacobian::Task;
    let mut solver = IkSolver::new();
    let k = axis.index();
    let mut out = Vec::with_capacity(directions.len());
    for d in directions {
        let Some(dir) = d.try_normalize(1e-12) else {
            out.push(DirectionReach {
                direction: *d,
                reachable: false,
                q: seed.to_vec(),
            });
            continue;
        };
        // A rotation whose column k is `dir`: u ⟂ dir, then dir × u (right-handed).
        let helper = if dir.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let u = helper.cross(&dir).normalize();
        let w = dir.cross(&u);
        let mut cols = [Vector3::zeros(); 3];
        cols[k] = dir;
        cols[(k + 1) % 3] = u;
        cols[(k + 2) % 3] = w;
        let target = super::ik::target_pose(*position, Matrix3::from_columns(&cols));
        let r = solver.solve(
            robot,
            &target,
            Task::PositionAndAxis(axis),
            seed,
            IkMethod::DampedLeastSquares,
            settings,
        )?;
        out.push(DirectionReach {
            direction: dir,
            reachable: r.success,
            q: r.q,
        });
    }
    Ok(out)
}
