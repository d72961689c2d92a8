//! The reachable workspace, sampled (docs/kinematics.md §12): tool positions from random
//! joint vectors within the limits, each with a measure of how well the arm can move
//! there. Filled in slices ([`WorkspaceCloud::fill`]) so that a page can spread the work
//! over frames; the core has no clock, so a slice is a number of samples.

use nalgebra::{Matrix3, Vector3};

use super::angles::sin_cos;
use super::fk::ForwardKinematics;
use super::rng::SplitMix64;
use super::robot::{Convention, JointKind, Robot};

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
    chain: Chain,
    q: Vec<f64>,
    target: usize,
    /// Tool positions in the world frame (robot units), in sampling order.
    pub positions: Vec<Vector3<f64>>,
    /// The measure at each position (unit-free).
    pub values: Vec<f64>,
    /// The joint vector of each sample (for "take the arm there"), when kept
    /// ([`WorkspaceCloud::keep_joint_vectors`]).
    pub joint_vectors: Vec<Vec<f64>>,
    keep_q: bool,
    min: [f64; 3],
    max: [f64; 3],
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
            chain: Chain::new(robot),
            q: vec![0.0; robot.dof()],
            target: samples,
            positions: Vec::with_capacity(samples),
            values: Vec::with_capacity(samples),
            joint_vectors: Vec::new(),
            keep_q: false,
            min: [f64::INFINITY; 3],
            max: [f64::NEG_INFINITY; 3],
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
        let base = self.robot.world_from_base.translation.vector;
        for _ in 0..count {
            for (v, link) in self.q.iter_mut().zip(&self.chain.links) {
                *v = self.rng.uniform(link.lo, link.hi);
            }
            let tool = self.chain.sample(&self.q);
            let value = match self.measure {
                WorkspaceMeasure::Manipulability => self.chain.gram.manipulability(),
                WorkspaceMeasure::SigmaMin => self.chain.gram.sigma_min(),
            };
            for ((lo, hi), &t) in self.min.iter_mut().zip(self.max.iter_mut()).zip(&tool) {
                *lo = lo.min(t);
                *hi = hi.max(t);
            }
            self.largest_value = self.largest_value.max(value);
            let d = [tool[0] - base.x, tool[1] - base.y, tool[2] - base.z];
            self.farthest = self.farthest.max(dot(&d, &d).sqrt());
            self.positions.push(Vector3::from(tool));
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
        (!self.is_empty()).then_some((self.min.into(), self.max.into()))
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

/// One joint's constants for the sampler: the DH row with sin and cos of α computed
/// once, the kind, and the limits the joint values are drawn from.
#[derive(Debug, Clone, Copy)]
struct Link {
    revolute: bool,
    theta: f64,
    d: f64,
    a: f64,
    sa: f64,
    ca: f64,
    lo: f64,
    hi: f64,
}

/// The sampler's forward kinematics over plain arrays (docs/kinematics.md §12): the
/// recurrence of `fk::advance` (the frame's columns, no 4×4 products), one sine and
/// cosine per joint, the linear Jacobian columns from the frames already computed, and
/// nothing allocated per sample. Written without nalgebra's generic layers so that the
/// page's size-optimised build (opt-level "z") has no small functions to leave
/// un-inlined in the hot loop. Numbers as [`ForwardKinematics::update`] gives them.
#[derive(Debug, Clone)]
struct Chain {
    modified: bool,
    links: Vec<Link>,
    /// The base rotation's columns and the base origin.
    base_r: [[f64; 3]; 3],
    base_o: [f64; 3],
    /// The tool's offset in the flange frame.
    flange_t: [f64; 3],
    inv_len: f64,
    /// Per joint, overwritten by each sample: its axis and a point on it (base frame).
    axes: Vec<([f64; 3], [f64; 3])>,
    /// The last sample's Gram matrix of the linear rows.
    gram: Gram,
}

impl Chain {
    fn new(robot: &Robot) -> Self {
        let links = robot
            .joints
            .iter()
            .map(|j| {
                let (sa, ca) = sin_cos(j.dh.alpha);
                Link {
                    revolute: j.kind == JointKind::Revolute,
                    theta: j.dh.theta,
                    d: j.dh.d,
                    a: j.dh.a,
                    sa,
                    ca,
                    lo: j.limits.min,
                    hi: j.limits.max,
                }
            })
            .collect();
        let r = robot.world_from_base.rotation.matrix();
        let column = |k: usize| [r[(0, k)], r[(1, k)], r[(2, k)]];
        Chain {
            modified: robot.convention == Convention::Modified,
            links,
            base_r: [column(0), column(1), column(2)],
            base_o: robot.world_from_base.translation.vector.into(),
            flange_t: robot.flange_from_tool.translation.vector.into(),
            inv_len: 1.0 / robot.length_scale(),
            axes: vec![([0.0; 3], [0.0; 3]); robot.dof()],
            gram: Gram::default(),
        }
    }

    /// The tool position at `q` (one entry per joint); fills [`Chain::gram`].
    fn sample(&mut self, q: &[f64]) -> [f64; 3] {
        let [mut c0, mut c1, mut c2] = self.base_r;
        let mut o = self.base_o;
        for ((link, &qi), slot) in self.links.iter().zip(q).zip(&mut self.axes) {
            let (theta, d) = if link.revolute {
                (link.theta + qi, link.d)
            } else {
                (link.theta, link.d + qi)
            };
            let (st, ct) = sin_cos(theta);
            let (sa, ca, a) = (link.sa, link.ca, link.a);
            if self.modified {
                let y1 = lin(&c1, ca, &c2, sa);
                let z = lin(&c2, ca, &c1, -sa);
                let x = lin(&c0, ct, &y1, st);
                c1 = lin(&y1, ct, &c0, -st);
                o = lin(&lin(&o, 1.0, &c0, a), 1.0, &z, d);
                (c0, c2) = (x, z);
                *slot = (z, o);
            } else {
                *slot = (c2, o);
                let x = lin(&c0, ct, &c1, st);
                let y0 = lin(&c1, ct, &c0, -st);
                let z = lin(&c2, ca, &y0, -sa);
                c1 = lin(&y0, ca, &c2, sa);
                o = lin(&lin(&o, 1.0, &x, a), 1.0, &c2, d);
                (c0, c2) = (x, z);
            }
        }
        let t = self.flange_t;
        let shift = lin(&lin(&c0, t[0], &c1, t[1]), 1.0, &c2, t[2]);
        let tool = lin(&o, 1.0, &shift, 1.0);
        self.gram = Gram::default();
        for ((z, origin), link) in self.axes.iter().zip(&self.links) {
            let v = if link.revolute {
                cross(z, &lin(&tool, 1.0, origin, -1.0))
            } else {
                *z
            };
            self.gram.add(&scaled(&v, self.inv_len));
        }
        tool
    }
}

/// `a·x + b·y` per component (with x = 1 exactly `a + b·y`, as nalgebra's `a + b * y`).
#[inline(always)]
fn lin(a: &[f64; 3], x: f64, b: &[f64; 3], y: f64) -> [f64; 3] {
    [
        a[0] * x + b[0] * y,
        a[1] * x + b[1] * y,
        a[2] * x + b[2] * y,
    ]
}

#[inline(always)]
fn scaled(a: &[f64; 3], x: f64) -> [f64; 3] {
    [a[0] * x, a[1] * x, a[2] * x]
}

#[inline(always)]
fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The linear rows' Gram matrix `G = J̃v·J̃vᵀ = Σ_i v_i·v_iᵀ` (symmetric 3×3, stored as
/// its upper triangle xx, xy, xz, yy, yz, zz), with `v_i` joint i's linear column
/// divided by the reach; the first two columns are kept for the n×n `J̃vᵀ·J̃v` when n < 3.
#[derive(Debug, Clone, Copy, Default)]
struct Gram {
    m: [f64; 6],
    first: [[f64; 3]; 2],
    n: usize,
}

impl Gram {
    #[inline(always)]
    fn add(&mut self, v: &[f64; 3]) {
        if let Some(slot) = self.first.get_mut(self.n) {
            *slot = *v;
        }
        self.n += 1;
        let m = &mut self.m;
        m[0] += v[0] * v[0];
        m[1] += v[0] * v[1];
        m[2] += v[0] * v[2];
        m[3] += v[1] * v[1];
        m[4] += v[1] * v[2];
        m[5] += v[2] * v[2];
    }

    /// `√det G`, or `√det(J̃vᵀ·J̃v)` with fewer than three joints.
    fn manipulability(&self) -> f64 {
        let [a, b] = &self.first;
        let det = match self.n {
            0 => 0.0,
            1 => dot(a, a),
            2 => dot(a, a) * dot(b, b) - dot(a, b).powi(2),
            _ => symmetric_determinant(&self.m),
        };
        det.max(0.0).sqrt()
    }

    /// σ_min: the square root of the smallest eigenvalue of G (of the n×n Gram matrix
    /// with fewer than three joints).
    fn sigma_min(&self) -> f64 {
        let [a, b] = &self.first;
        let smallest = match self.n {
            0 => 0.0,
            1 => dot(a, a),
            2 => {
                let (aa, bb) = (dot(a, a), dot(b, b));
                let c = dot(a, b);
                let mean = 0.5 * (aa + bb);
                let half = (0.25 * (aa - bb) * (aa - bb) + c * c).sqrt();
                mean - half
            }
            _ => smallest_eigenvalue_upper(&self.m),
        };
        smallest.max(0.0).sqrt()
    }
}

/// The Gram matrix of the linear rows at `fk`'s pose.
fn gram_of(fk: &ForwardKinematics, inv_len: f64) -> Gram {
    let tool: [f64; 3] = fk.tool_position().into();
    let mut gram = Gram::default();
    let joints = fk
        .joint_axes
        .iter()
        .zip(&fk.joint_origins)
        .zip(&fk.joint_kinds);
    for ((z, o), kind) in joints {
        let z: [f64; 3] = (*z).into();
        let v = match kind {
            JointKind::Revolute => cross(&z, &lin(&tool, 1.0, &(*o).into(), -1.0)),
            JointKind::Prismatic => z,
        };
        gram.add(&scaled(&v, inv_len));
    }
    gram
}

/// `√det(J̃v·J̃vᵀ)`, or `√det(J̃vᵀ·J̃v)` with fewer than three joints (docs/kinematics.md
/// §12.1).
pub fn linear_manipulability(fk: &ForwardKinematics, inv_len: f64) -> f64 {
    gram_of(fk, inv_len).manipulability()
}

/// The smallest singular value of J̃v (the smallest of min(3, n)), from the eigenvalues
/// of the symmetric 3×3 (or n×n) Gram matrix in closed form (docs/kinematics.md §12.1).
pub fn linear_sigma_min(fk: &ForwardKinematics, inv_len: f64) -> f64 {
    gram_of(fk, inv_len).sigma_min()
}

/// The determinant of a symmetric 3×3 given by its upper triangle (xx, xy, xz, yy, yz,
/// zz), expanded along the first row as nalgebra's `Matrix3::determinant` does.
#[inline(always)]
fn symmetric_determinant(m: &[f64; 6]) -> f64 {
    let [m11, m12, m13, m22, m23, m33] = *m;
    let minor_m12_m23 = m22 * m33 - m23 * m23;
    let minor_m11_m23 = m12 * m33 - m13 * m23;
    let minor_m11_m22 = m12 * m23 - m13 * m22;
    m11 * minor_m12_m23 - m12 * minor_m11_m23 + m13 * minor_m11_m22
}

/// The smallest eigenvalue of a symmetric 3×3 matrix by the trigonometric solution of
/// its characteristic cubic (Smith 1961): with `q = tr/3`, `p = √(‖A − qI‖²_F / 6)` and
/// `r = det((A − qI)/p)/2`, the eigenvalues are `q + 2p·cos(φ + 2πk/3)`,
/// `φ = acos(r)/3`; the smallest is k = 1.
pub fn smallest_symmetric_eigenvalue(a: &Matrix3<f64>) -> f64 {
    smallest_eigenvalue_upper(&[
        a[(0, 0)],
        a[(0, 1)],
        a[(0, 2)],
        a[(1, 1)],
        a[(1, 2)],
        a[(2, 2)],
    ])
}

/// [`smallest_symmetric_eigenvalue`] of the matrix with upper triangle `a` (xx, xy, xz,
/// yy, yz, zz).
fn smallest_eigenvalue_upper(a: &[f64; 6]) -> f64 {
    let [a00, a01, a02, a11, a12, a22] = *a;
    let off = a01 * a01 + a02 * a02 + a12 * a12;
    let q = (a00 + a11 + a22) / 3.0;
    let d = [a00 - q, a11 - q, a22 - q];
    let p2 = (dot(&d, &d) + 2.0 * off) / 6.0;
    if p2 <= 1e-300 {
        return q;
    }
    let p = p2.sqrt();
    let b = [d[0] / p, a01 / p, a02 / p, d[1] / p, a12 / p, d[2] / p];
    let r = (0.5 * symmetric_determinant(&b)).clamp(-1.0, 1.0);
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
