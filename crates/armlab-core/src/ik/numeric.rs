//! The iterative methods: damped least squares (Levenberg–Marquardt), Newton with the
//! pseudo-inverse and gradient descent, sharing one workspace and one error function.

use nalgebra::{IsometryMatrix3, Matrix3, Matrix6, Matrix6xX, Vector3, Vector6};

use super::chain::{Chain, solve_spd6};
use super::{IkMethod, IkResult, IkSettings, IkStep, JacobianSource, within_limits};
use crate::angles::{self, constant_table};
use crate::fk::tool_pose;
use crate::jacobian::{NUMERIC_EPSILON, Task};
use crate::orientation::rotation_log;
use crate::rng::SplitMix64;
use crate::robot::{Joint, JointKind, Robot};
use std::f64::consts::PI;

/// The target in the form the error function needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TaskTarget {
    pub task: Task,
    pub position: Vector3<f64>,
    pub rotation: Matrix3<f64>,
}

impl TaskTarget {
    pub fn new(target: &IsometryMatrix3<f64>, task: Task) -> Self {
        TaskTarget {
            task,
            position: target.translation.vector,
            rotation: *target.rotation.matrix(),
        }
    }
}

/// The task error at one pose.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    /// The error vector: linear rows scaled, then the task's angular rows (unused rows 0).
    pub e: Vector6<f64>,
    /// ½‖e‖².
    pub cost: f64,
    /// ‖p_target − p‖ (robot units).
    pub position_error: f64,
    /// The task's orientation error (radians).
    pub orientation_error: f64,
}

/// `vee(log R)`, fast for rotations below ~170° and through [`rotation_log`] beyond.
// Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
#[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
pub(crate) fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    let v = 0.5
        * Vector3::new(
            r[(2, 1)] - r[(1, 2)],
            r[(0, 2)] - r[(2, 0)],
            r[(1, 0)] - r[(0, 1)],
        );
    let c = 0.5 * (r.trace() - 1.0);
    let s2 = v.norm_squared();
    if c > 0.0 && s2 < SMALL_SIN2 {
        // The late iterations: θ/sin θ from sin² θ alone, no square root or division.
        return v * asin_over_sin(s2);
    }
    if c > -0.98 {
        let s = s2.sqrt();
        if s < 1e-300 {
            return Vector3::zeros();
        }
        v * angle_over_sin(s, c)
    } else {
        rotation_log(r)
    }
}

/// Below this sin² θ (θ < 0.05 rad, θ < π/2) [`rotation_vector`] uses [`asin_over_sin`].
const SMALL_SIN2: f64 = 0.0025;

/// `asin(s) / s` from `s2 = s²` for `s² <` [`SMALL_SIN2`] (θ/sin θ for θ < π/2):
/// `1 + s²/6 + 3s⁴/40 + 5s⁶/112 + 35s⁸/1152 + 63s¹⁰/2816 + …`; the first omitted term,
/// `231s¹²/13312`, is below 5·10⁻¹⁸ there.
#[inline]
fn asin_over_sin(s2: f64) -> f64 {
    let k = constant_table!(
        5,
        [
            1.0 / 6.0,
            3.0 / 40.0,
            5.0 / 112.0,
            35.0 / 1152.0,
            63.0 / 2816.0
        ]
    );
    1.0 + s2 * (k(0) + s2 * (k(1) + s2 * (k(2) + s2 * (k(3) + s2 * k(4)))))
}

/// `atan2(s, c) / s` for `s > 0`: below 0.05 rad a polynomial (the late iterations of a
/// solve, where the library's atan2 would take a tenth of the time), [`angles::atan2`] above
/// (the library's natively; in the core's wasm the polynomial one, within 2 ulp, as the
/// library's is software there).
///
/// With `t = s/c`, `atan(t)/s = (1/c)·(1 − t²/3 + t⁴/5 − t⁶/7 + t⁸/9 − …)`; for t < 0.05
/// the first omitted term is below 10⁻¹⁴ of the sum.
#[inline]
fn angle_over_sin(s: f64, c: f64) -> f64 {
    if c > 0.0 && s < 0.05 * c {
        let k = constant_table!(4, [-1.0 / 3.0, 1.0 / 5.0, -1.0 / 7.0, 1.0 / 9.0]);
        let t = s / c;
        let t2 = t * t;
        (1.0 + t2 * (k(0) + t2 * (k(1) + t2 * (k(2) + t2 * k(3))))) / c
    } else {
        angles::atan2(s, c) / s
    }
}

/// The rotation vector turning unit axis `a` onto unit axis `b` (perpendicular to `a`,
/// of length the angle), and the angle; `fallback` is a unit vector perpendicular to `a`
/// used when they are opposite. The angle's atan2 is [`angles::atan2`], as in
/// [`angle_over_sin`].
fn axis_rotation(
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    fallback: &Vector3<f64>,
) -> (Vector3<f64>, f64) {
    let c = a.cross(b);
    let s = c.norm();
    let angle = angles::atan2(s, a.dot(b));
    if s > 1e-300 {
        (c * (angle / s), angle)
    } else if angle > 1.0 {
        (fallback * angle, angle)
    } else {
        (Vector3::zeros(), 0.0)
    }
}

/// The task error of `pose` against `tt`, linear rows multiplied by `inv_len`.
// Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
#[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
pub(crate) fn evaluate(tt: &TaskTarget, pose: &IsometryMatrix3<f64>, inv_len: f64) -> Eval {
    let dp = tt.position - pose.translation.vector;
    let r = pose.rotation.matrix();
    let mut e = Vector6::zeros();
    e.fixed_rows_mut::<3>(0).copy_from(&(dp * inv_len));
    let orientation_error = match tt.task {
        Task::Position => 0.0,
        Task::FullPose => {
            let w = rotation_vector(&(tt.rotation * r.transpose()));
            e.fixed_rows_mut::<3>(3).copy_from(&w);
            w.norm()
        }
        Task::PositionAndAxis(axis) => {
            let k = axis.index();
            let a = r.column(k).into_owned();
            let u = r.column((k + 1) % 3).into_owned();
            let w = r.column((k + 2) % 3).into_owned();
            let (rv, angle) = axis_rotation(&a, &tt.rotation.column(k).into_owned(), &u);
            e[3] = u.dot(&rv);
            e[4] = w.dot(&rv);
            angle
        }
    };
    let position_error = dp.norm();
    let cost = 0.5 * e.norm_squared();
    Eval {
        e,
        cost: if cost.is_finite() {
            cost
        } else {
            f64::INFINITY
        },
        position_error,
        orientation_error,
    }
}

/// How an attempt ended.
#[derive(Debug, Clone, Copy, Default)]
struct Outcome {
    iterations: usize,
    converged: bool,
    /// Stopped at a minimum of the error (no step lowers it): the closest pose nearby.
    stationary: bool,
}

impl Outcome {
    /// Marks how the attempt ended.
    #[inline]
    fn end(&mut self, end: End) {
        match end {
            End::Converged => self.converged = true,
            End::Stationary => self.stationary = true,
        }
    }
}

/// Why an attempt ended before its cap, when a step ends it.
#[derive(Debug, Clone, Copy)]
enum End {
    Converged,
    /// At a minimum of the error ([`Outcome::stationary`]).
    Stationary,
}

/// The step of one iteration ([`Workspace::step`]).
#[derive(Debug, Clone, Copy)]
enum Step {
    /// The step is in `dq`: its norm and the damping λ (0 for the undamped methods).
    Taken { norm: f64, damping: f64 },
    /// The damped system was not positive definite: more damping, at the next iteration.
    Refused,
    /// No finite step, or the damping ran out: a minimum of the error.
    Stuck,
}

/// An attempt's damping and the costs it compares with to tell slow progress or a stall.
#[derive(Debug, Clone, Copy)]
struct Progress {
    /// μ in λ² = μ·(‖e‖ + [`DLS_FLOOR`]).
    mu: f64,
    /// The cost at the start of the current [`SLOW_WINDOW`].
    checkpoint: f64,
    /// The cost after each of the last STALL_ITERATIONS iterations, by iteration mod 2.
    recent: [f64; STALL_ITERATIONS],
}

impl Progress {
    fn new(cost: f64) -> Self {
        Progress {
            mu: DLS_MU_START,
            checkpoint: cost,
            recent: [cost; STALL_ITERATIONS],
        }
    }

    /// More damping after a refused step; `true` when it passes [`DLS_MU_MAX`] (a minimum).
    #[inline]
    fn damp_more(&mut self) -> bool {
        self.mu *= DLS_MU_UP;
        self.mu > DLS_MU_MAX
    }

    /// Less damping after an accepted step.
    #[inline]
    fn damp_less(&mut self) {
        self.mu = (self.mu * DLS_MU_DOWN).max(DLS_MU_MIN);
    }

    /// Whether a damped attempt ends after `iterations` at `cost`: `Some(stationary)` when
    /// it stalled ([`STALL_ITERATIONS`], only if `may_restart`) or did not halve its cost
    /// over the [`SLOW_WINDOW`].
    // Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn stalled(&mut self, iterations: usize, cost: f64, may_restart: bool) -> Option<bool> {
        if may_restart {
            let slot = iterations % STALL_ITERATIONS;
            let before = self.recent[slot];
            if iterations >= STALL_ITERATIONS && cost > STALL_FACTOR * before {
                return Some(cost > AT_A_MINIMUM * before);
            }
            self.recent[slot] = cost;
        }
        if iterations.is_multiple_of(SLOW_WINDOW) {
            if cost > 0.5 * self.checkpoint {
                return Some(cost > AT_A_MINIMUM * self.checkpoint);
            }
            self.checkpoint = cost;
        }
        None
    }
}

/// What the solve reports of its best attempt (the attempt's joint values are in
/// `Workspace::best`).
#[derive(Debug, Clone, Copy)]
struct Best {
    converged: bool,
    cost: f64,
    stationary: bool,
    position_error: f64,
    orientation_error: f64,
}

// Damped least squares: λ² = μ·(‖e‖ + DLS_FLOOR), μ adapted in [DLS_MU_MIN, DLS_MU_MAX]
// (docs/kinematics.md §8.3: with the damping in proportion to ‖e‖, not to ½‖e‖², the
// UR10's median is 8 iterations, not 9; docs/benchmarks.md).
const DLS_FLOOR: f64 = 1e-6;
const DLS_MU_START: f64 = 0.15;
const DLS_MU_MIN: f64 = 1e-3;
const DLS_MU_MAX: f64 = 1e8;
const DLS_MU_DOWN: f64 = 0.7;
const DLS_MU_UP: f64 = 10.0;
/// An accepted step lowering the cost by less than this fraction means a minimum.
const DLS_STATIONARY: f64 = 1e-9;
/// The linear rows of the error and the Jacobian are divided by reach / LINEAR_WEIGHT:
/// a position error of a quarter of the reach weighs as one radian. With the whole reach
/// (weight 1) the orientation dominates the first steps and attempts stall more often
/// with the orientation met and the position not (docs/kinematics.md §8).
const LINEAR_WEIGHT: f64 = 4.0;
/// An attempt that does not halve its cost every this many iterations is restarted. With
/// the joint locking of §8.9, 6 gives the UR10 and the Panda a p99 about a tenth lower
/// than 8, with the same success (docs/benchmarks.md).
const SLOW_WINDOW: usize = 6;
/// While restarts remain (the first half of them), an attempt whose cost fell by less
/// than a tenth over its last two iterations (a stall: steps refused, or too small to
/// matter) is ended at once rather than at the end of its window: a fresh start is the
/// better bet (docs/kinematics.md §8.5: over 100 000 targets the p99 of iterations per
/// solve is 46 for the UR10 and 62 for the Panda with it, 61 and 76 without).
const STALL_ITERATIONS: usize = 2;
/// The fraction of its cost that an attempt must lose over [`STALL_ITERATIONS`].
const STALL_FACTOR: f64 = 0.9;
/// An attempt ended by [`SLOW_WINDOW`] or [`STALL_ITERATIONS`] whose cost is still above
/// this fraction of the cost it is compared with (less than 1 % lower) stopped at a
/// minimum, not just slowly ("stationary").
const AT_A_MINIMUM: f64 = 0.99;

/// The workspace of the numeric methods, sized to the robot on first use.
#[derive(Debug, Clone)]
pub(crate) struct Workspace {
    /// The solver's forward kinematics (axes, points on them, tool pose).
    chain: Chain,
    /// The 6×n geometric (or numerical) Jacobian.
    j: Matrix6xX<f64>,
    /// The task rows (linear rows scaled, unused rows zero).
    jt: Matrix6xX<f64>,
    /// J·Jᵀ of the task rows.
    m: Matrix6<f64>,
    q: Vec<f64>,
    q_try: Vec<f64>,
    raw: Vec<f64>,
    dq: Vec<f64>,
    best: Vec<f64>,
    scratch: Vec<f64>,
    /// Joints held at a limit in the current step ([`Workspace::damped_step`]).
    locked: Vec<bool>,
    /// Joint units per step unit: L/4 for a prismatic joint, whose value the solver
    /// measures in the length of the linear rows (docs/kinematics.md §8), 1 for a revolute.
    unit: Vec<f64>,
}

impl Default for Workspace {
    fn default() -> Self {
        Workspace {
            chain: Chain::default(),
            j: Matrix6xX::zeros(0),
            jt: Matrix6xX::zeros(0),
            m: Matrix6::zeros(),
            q: Vec::new(),
            q_try: Vec::new(),
            raw: Vec::new(),
            dq: Vec::new(),
            best: Vec::new(),
            scratch: Vec::new(),
            locked: Vec::new(),
            unit: Vec::new(),
        }
    }
}

/// Shared, per-call parameters of the attempts.
struct Ctx<'a> {
    robot: &'a Robot,
    tt: TaskTarget,
    method: IkMethod,
    /// Damped least squares (also the numeric part of the closed form): a step must lower
    /// the cost to be taken, and slow or stalled attempts end early.
    damped: bool,
    jacobian: JacobianSource,
    inv_len: f64,
    tol_p: f64,
    tol_o: f64,
    /// Keep joint values (docs/kinematics.md §3) after each step, or leave them raw.
    wrap: bool,
    /// The fixed-step gradient's factor (1 for ½‖e‖², 2 for ‖e‖²).
    gradient_factor: f64,
}

impl<'a> Ctx<'a> {
    // Inlined into the solve except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn new(
        robot: &'a Robot,
        tt: TaskTarget,
        method: IkMethod,
        settings: &IkSettings,
        inv_len: f64,
    ) -> Self {
        Ctx {
            robot,
            tt,
            method,
            damped: matches!(method, IkMethod::DampedLeastSquares | IkMethod::ClosedForm),
            jacobian: settings.jacobian,
            inv_len,
            tol_p: settings.position_tolerance / robot.length_unit.in_metres(),
            tol_o: settings.orientation_tolerance,
            wrap: settings.wrap,
            gradient_factor: settings.objective.gradient_factor(),
        }
    }

    fn converged(&self, ev: &Eval) -> bool {
        ev.position_error <= self.tol_p && ev.orientation_error <= self.tol_o
    }
}

impl Workspace {
    fn resize(&mut self, n: usize) {
        for v in [
            &mut self.q,
            &mut self.q_try,
            &mut self.raw,
            &mut self.dq,
            &mut self.best,
            &mut self.scratch,
        ] {
            v.resize(n, 0.0);
        }
        self.locked.resize(n, false);
        self.unit.resize(n, 1.0);
        if self.jt.ncols() != n {
            self.jt = Matrix6xX::zeros(n);
        }
    }

    /// The whole numeric solve: attempts from the seed, then from random restarts.
    pub(crate) fn run(
        &mut self,
        robot: &Robot,
        target: &IsometryMatrix3<f64>,
        task: Task,
        seed: &[f64],
        method: IkMethod,
        settings: &IkSettings,
    ) -> IkResult {
        let inv_len = self.prepare(robot, method);
        let ctx = Ctx::new(
            robot,
            TaskTarget::new(target, task),
            method,
            settings,
            inv_len,
        );
        let mut trace = Vec::new();
        let mut rng = SplitMix64::new(settings.seed);
        self.start_at_seed(&ctx, seed, settings.record_trace.then_some(&mut trace));
        let mut record = settings.record_trace.then_some(&mut trace);
        let mut total = 0usize;
        let mut restarts = 0usize;
        let mut best = None;
        loop {
            let cap = settings
                .max_iterations
                .min(settings.budget.saturating_sub(total));
            // Stalled attempts end early while half the restarts remain: the rest run
            // their whole window, so that the cap on restarts does not run out on short
            // attempts with iterations left in the budget.
            let may_restart = restarts < settings.restarts / 2;
            let (out, ev) = self.attempt(&ctx, cap, may_restart, record.as_deref_mut());
            total += out.iterations;
            self.keep_if_better(&mut best, &out, &ev);
            if out.converged
                || total >= settings.budget
                || restarts >= settings.restarts
                || cap == 0
            {
                break;
            }
            restarts += 1;
            self.restart_at_random(&ctx, &mut rng, record.as_deref_mut());
        }
        self.result(robot, best, total, restarts, trace)
    }

    /// Sizes the workspace and the chain to `robot`, and sets each joint's step unit;
    /// returns the factor of the linear rows (1 / length).
    // Inlined into the solve except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn prepare(&mut self, robot: &Robot, method: IkMethod) -> f64 {
        self.resize(robot.dof());
        self.chain.set(robot);
        let inv_len = match method {
            IkMethod::JacobianTranspose { alpha: Some(_) } => 1.0,
            _ => LINEAR_WEIGHT / self.chain.reach(),
        };
        for (unit, joint) in self.unit.iter_mut().zip(&robot.joints) {
            *unit = if joint.kind == JointKind::Prismatic {
                1.0 / inv_len
            } else {
                1.0
            };
        }
        inv_len
    }

    /// The first attempt's start: `q` = the seed, kept (and its step in `trace`).
    // Inlined into the solve except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn start_at_seed(&mut self, ctx: &Ctx, seed: &[f64], trace: Option<&mut Vec<IkStep>>) {
        for ((v, s), joint) in self.q.iter_mut().zip(seed).zip(&ctx.robot.joints) {
            *v = keep_or_raw(ctx.wrap, joint, *s, *s);
        }
        if let Some(t) = trace {
            self.chain.update(&self.q);
            let ev = evaluate(&ctx.tt, &self.chain.pose, ctx.inv_len);
            t.push(start_step(&self.q, seed, &ev, false));
        }
    }

    /// A restart's start: `q` drawn uniformly within the limits (and its step in `trace`).
    // Inlined into the solve except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn restart_at_random(
        &mut self,
        ctx: &Ctx,
        rng: &mut SplitMix64,
        trace: Option<&mut Vec<IkStep>>,
    ) {
        for (v, joint) in self.q.iter_mut().zip(&ctx.robot.joints) {
            *v = rng.uniform(joint.limits.min, joint.limits.max);
        }
        if let Some(t) = trace {
            self.chain.update(&self.q);
            let ev = evaluate(&ctx.tt, &self.chain.pose, ctx.inv_len);
            t.push(start_step(&self.q, &self.q, &ev, true));
        }
    }

    /// Keeps the attempt just ended (its answer in `q`) as the best when it is the first,
    /// or converged where the best did not, or as converged with a lower cost.
    // Inlined into the solve except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn keep_if_better(&mut self, best: &mut Option<Best>, out: &Outcome, ev: &Eval) {
        let better = match best {
            None => true,
            Some(b) => {
                (out.converged && !b.converged)
                    || (out.converged == b.converged && ev.cost < b.cost)
            }
        };
        if better {
            self.best.copy_from_slice(&self.q);
            *best = Some(Best {
                converged: out.converged,
                cost: ev.cost,
                stationary: out.stationary,
                position_error: ev.position_error,
                orientation_error: ev.orientation_error,
            });
        }
    }

    /// The solve's answer: the best attempt, and the iterations and restarts it took.
    // Inlined into the solve except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn result(
        &self,
        robot: &Robot,
        best: Option<Best>,
        iterations: usize,
        restarts: usize,
        trace: Vec<IkStep>,
    ) -> IkResult {
        let best = best.unwrap_or(Best {
            converged: false,
            cost: f64::INFINITY,
            stationary: false,
            position_error: f64::INFINITY,
            orientation_error: f64::INFINITY,
        });
        IkResult {
            q: self.best.clone(),
            success: best.converged,
            // Every attempt failed: at a minimum of the error, or restarts used up.
            unreachable: !best.converged && (best.stationary || restarts > 0),
            singular: false,
            clipped: false,
            within_limits: within_limits(robot, &self.best),
            position_error: best.position_error,
            orientation_error: best.orientation_error,
            iterations,
            restarts,
            trace,
        }
    }

    /// Fills `jt` (and `m` = jt·jtᵀ) at the current `q`; `chain` must hold `q`.
    fn task_jacobian(&mut self, ctx: &Ctx) {
        let n = ctx.robot.dof();
        if self.jt.ncols() != n {
            self.jt = Matrix6xX::zeros(n);
        }
        match ctx.jacobian {
            JacobianSource::Geometric => {
                self.chain
                    .task_jacobian(ctx.tt.task, ctx.inv_len, &mut self.jt, &mut self.m);
            }
            JacobianSource::CentralDifference => {
                self.central_difference(ctx.robot);
                let r = *self.chain.pose.rotation.matrix();
                let mut m = Matrix6::zeros();
                for i in 0..n {
                    let col = self.j.column(i);
                    // A prismatic column in step units (§8): inv_len · (L/4) = 1.
                    let v = col.fixed_rows::<3>(0) * (ctx.inv_len * self.unit[i]);
                    let w = col.fixed_rows::<3>(3).into_owned();
                    let c = match ctx.tt.task {
                        Task::Position => Vector6::new(v.x, v.y, v.z, 0.0, 0.0, 0.0),
                        Task::FullPose => Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z),
                        Task::PositionAndAxis(axis) => {
                            let k = axis.index();
                            let u1 = r.column((k + 1) % 3).dot(&w);
                            let u2 = r.column((k + 2) % 3).dot(&w);
                            Vector6::new(v.x, v.y, v.z, u1, u2, 0.0)
                        }
                    };
                    m += c * c.transpose();
                    self.jt.column_mut(i).copy_from(&c);
                }
                self.m = m;
            }
        }
    }

    /// The central-difference Jacobian (docs/kinematics.md §4.2) into `j`, without allocating.
    fn central_difference(&mut self, robot: &Robot) {
        let n = robot.dof();
        if self.j.ncols() != n {
            self.j = Matrix6xX::zeros(n);
        }
        self.scratch.copy_from_slice(&self.q);
        let eps = NUMERIC_EPSILON;
        for i in 0..n {
            let q0 = self.scratch[i];
            self.scratch[i] = q0 + eps;
            let plus = tool_pose(robot, &self.scratch);
            self.scratch[i] = q0 - eps;
            let minus = tool_pose(robot, &self.scratch);
            self.scratch[i] = q0;
            let v = (plus.translation.vector - minus.translation.vector) / (2.0 * eps);
            let w =
                rotation_vector(&(plus.rotation.matrix() * minus.rotation.matrix().transpose()))
                    / (2.0 * eps);
            let mut col = self.j.column_mut(i);
            col.fixed_rows_mut::<3>(0).copy_from(&v);
            col.fixed_rows_mut::<3>(3).copy_from(&w);
        }
    }

    /// The damped step `dq = Jᵀ(J·Jᵀ + λ²I)⁻¹·e` into `dq`; returns ‖dq‖, or `None`
    /// when the system is not positive definite. A joint that cannot move is locked
    /// (docs/kinematics.md §8.9): on a limit it cannot wrap past, with the gradient
    /// `J_iᵀ·e` pointing outward. Its column leaves `J·Jᵀ` (a rank-one downdate) and its
    /// step is zero, so the other joints do not count on a motion it never makes.
    fn damped_step(&mut self, ctx: &Ctx, lambda2: f64, e: &Vector6<f64>) -> Option<f64> {
        let mut reduced: Option<Matrix6<f64>> = None;
        for (((lock, joint), &q), c) in self
            .locked
            .iter_mut()
            .zip(&ctx.robot.joints)
            .zip(&self.q)
            .zip(self.jt.column_iter())
        {
            // Most joints are off their limits: the gradient only for those on one.
            *lock = (q <= joint.limits.min || q >= joint.limits.max)
                && locks(joint, ctx.wrap, q, c.dot(e));
            if *lock {
                *reduced.get_or_insert(self.m) -= c * c.transpose();
            }
        }
        let y = Vector6::from(solve_spd6(reduced.as_ref().unwrap_or(&self.m), lambda2, e)?);
        let mut norm2 = 0.0;
        for (((d, c), &lock), unit) in self
            .dq
            .iter_mut()
            .zip(self.jt.column_iter())
            .zip(&self.locked)
            .zip(&self.unit)
        {
            *d = if lock { 0.0 } else { c.dot(&y) * unit };
            norm2 += *d * *d;
        }
        Some(norm2.sqrt())
    }

    /// `dq = jtᵀ·y` in joint units; returns ‖dq‖.
    fn back_substitute(&mut self, y: &Vector6<f64>) -> f64 {
        let mut norm2 = 0.0;
        for ((d, c), unit) in self
            .dq
            .iter_mut()
            .zip(self.jt.column_iter())
            .zip(&self.unit)
        {
            *d = c.dot(y) * unit;
            norm2 += *d * *d;
        }
        norm2.sqrt()
    }

    /// `q_try = keep(q + dq)` (and the raw sum in `raw`).
    fn take_step(&mut self, robot: &Robot, wrap: bool) {
        for (i, joint) in robot.joints.iter().enumerate() {
            let (current, raw) = (self.q[i], self.q[i] + self.dq[i]);
            self.raw[i] = raw;
            self.q_try[i] = keep_or_raw(wrap, joint, raw, current);
        }
    }

    /// One attempt from the current `q` with at most `cap` iterations; `may_restart`: a
    /// stalled attempt may end early for a restart ([`STALL_ITERATIONS`]). Leaves the
    /// attempt's answer in `q` and returns its outcome and error.
    fn attempt(
        &mut self,
        ctx: &Ctx,
        cap: usize,
        may_restart: bool,
        mut trace: Option<&mut Vec<IkStep>>,
    ) -> (Outcome, Eval) {
        self.chain.update(&self.q);
        let mut ev = evaluate(&ctx.tt, &self.chain.pose, ctx.inv_len);
        let mut out = Outcome::default();
        if ctx.converged(&ev) {
            out.converged = true;
            return (out, ev);
        }
        if !ev.cost.is_finite() {
            out.stationary = true;
            return (out, ev);
        }
        self.task_jacobian(ctx);
        let mut progress = Progress::new(ev.cost);
        while out.iterations < cap {
            out.iterations += 1;
            let (step, damping) = match self.step(ctx, &ev, &mut progress) {
                Step::Taken { norm, damping } => (norm, damping),
                Step::Refused => continue,
                Step::Stuck => {
                    out.stationary = true;
                    break;
                }
            };
            if let Some(end) = self.try_step(ctx, &mut ev, &mut progress, &mut trace, step, damping)
            {
                out.end(end);
                break;
            }
            if ctx.damped
                && let Some(stationary) = progress.stalled(out.iterations, ev.cost, may_restart)
            {
                out.stationary = stationary;
                break;
            }
        }
        (out, ev)
    }

    /// This iteration's step into `dq`, by the method of `ctx`, from the error `ev`.
    // Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn step(&mut self, ctx: &Ctx, ev: &Eval, progress: &mut Progress) -> Step {
        let (norm, damping) = match ctx.method {
            IkMethod::PseudoInverse => {
                let y = pinv_times(&self.m, &ev.e);
                (self.back_substitute(&y), 0.0)
            }
            IkMethod::JacobianTranspose { alpha } => {
                let alpha = match alpha {
                    Some(a) => a * ctx.gradient_factor,
                    None => {
                        let me = self.m * ev.e;
                        let den = me.norm_squared();
                        if den > 0.0 { ev.e.dot(&me) / den } else { 0.0 }
                    }
                };
                (self.back_substitute(&(ev.e * alpha)), 0.0)
            }
            _ => {
                let lambda2 = progress.mu * ((2.0 * ev.cost).sqrt() + DLS_FLOOR);
                match self.damped_step(ctx, lambda2, &ev.e) {
                    Some(norm) => (norm, lambda2.sqrt()),
                    None if progress.damp_more() => return Step::Stuck,
                    None => return Step::Refused,
                }
            }
        };
        if norm.is_finite() {
            Step::Taken { norm, damping }
        } else {
            Step::Stuck
        }
    }

    /// Moves to `q + dq` (kept) unless a `damped` method finds its cost no lower, then
    /// adapts the damping, records the step and updates `ev` and the Jacobian; returns
    /// how the attempt ends, if this step ends it.
    // Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    fn try_step(
        &mut self,
        ctx: &Ctx,
        ev: &mut Eval,
        progress: &mut Progress,
        trace: &mut Option<&mut Vec<IkStep>>,
        step: f64,
        damping: f64,
    ) -> Option<End> {
        self.take_step(ctx.robot, ctx.wrap);
        self.chain.update(&self.q_try);
        let ev_try = evaluate(&ctx.tt, &self.chain.pose, ctx.inv_len);
        let damped = ctx.damped;
        let accepted = !damped || ev_try.cost < ev.cost;
        if !accepted {
            self.record(trace, ev, step, damping, false);
            return progress.damp_more().then_some(End::Stationary);
        }
        if !ev_try.cost.is_finite() {
            return Some(End::Stationary);
        }
        let gain = (ev.cost - ev_try.cost) / ev.cost;
        std::mem::swap(&mut self.q, &mut self.q_try);
        *ev = ev_try;
        progress.damp_less();
        self.record(trace, ev, step, damping, true);
        if ctx.converged(ev) {
            return Some(End::Converged);
        }
        if damped && gain < DLS_STATIONARY {
            return Some(End::Stationary);
        }
        self.task_jacobian(ctx);
        None
    }

    fn record(
        &self,
        trace: &mut Option<&mut Vec<IkStep>>,
        ev: &Eval,
        step: f64,
        damping: f64,
        accepted: bool,
    ) {
        if let Some(t) = trace.as_deref_mut() {
            t.push(IkStep {
                q: self.q.clone(),
                raw_q: self.raw.clone(),
                error: ev.e.norm(),
                position_error: ev.position_error,
                orientation_error: ev.orientation_error,
                step,
                damping,
                accepted,
                restart: false,
            });
        }
    }
}

/// [`Joint::keep`] with a fast path giving the same answer: a revolute joint that does not
/// wrap, moving by less than half a turn to a value inside its limits, keeps that value
/// (it is the 2π-equivalent nearest the current one).
#[inline]
fn keep(joint: &Joint, raw: f64, current: f64) -> f64 {
    if joint.kind == JointKind::Revolute
        && !joint.wraps()
        && (raw - current).abs() < PI
        && joint.limits.contains(raw, 0.0)
    {
        raw
    } else {
        joint.keep(raw, current)
    }
}

/// Whether joint `joint` at `q` cannot move in direction `dq`: it sits on a limit that
/// keeping clamps to (a prismatic joint, or a revolute one whose range is under a turn
/// while values are kept) and `dq` points outward.
#[inline]
fn locks(joint: &Joint, wrap: bool, q: f64, dq: f64) -> bool {
    let clamps = match joint.kind {
        JointKind::Prismatic => true,
        JointKind::Revolute => wrap && joint.limits.max - joint.limits.min < std::f64::consts::TAU,
    };
    clamps && ((q <= joint.limits.min && dq < 0.0) || (q >= joint.limits.max && dq > 0.0))
}

/// [`keep`] when `wrap` is on; else the raw value (a prismatic joint still clamps).
#[inline]
fn keep_or_raw(wrap: bool, joint: &Joint, raw: f64, current: f64) -> f64 {
    if wrap || joint.kind == JointKind::Prismatic {
        keep(joint, raw, current)
    } else {
        raw
    }
}

/// `y = (J·Jᵀ)⁺·e` from the symmetric eigen-decomposition `J·Jᵀ = U·Σ²·Uᵀ` (the left
/// singular vectors and squared singular values of J), so that `Jᵀ·y = J⁺·e`. Singular
/// values below 10⁻⁶·σ_max count as zero. A matrix that is not finite never reaches the
/// decomposition, which has an iteration cap: both give `y = 0` (no step, so the attempt
/// ends at a minimum).
fn pinv_times(m: &Matrix6<f64>, e: &Vector6<f64>) -> Vector6<f64> {
    /// The most sweeps of the eigen-decomposition (a 6×6 matrix takes a few).
    const MAX_EIGEN_ITERATIONS: usize = 1000;
    if !m.iter().all(|v| v.is_finite()) {
        return Vector6::zeros();
    }
    let Some(eig) = m.try_symmetric_eigen(f64::EPSILON, MAX_EIGEN_ITERATIONS) else {
        return Vector6::zeros();
    };
    let largest = eig.eigenvalues.iter().fold(0.0_f64, |a, &b| a.max(b));
    let cut = largest * 1e-12;
    let mut y = Vector6::zeros();
    for k in 0..6 {
        let s2 = eig.eigenvalues[k];
        if s2 > cut && s2 > 0.0 {
            let u = eig.eigenvectors.column(k);
            y += u * (u.dot(e) / s2);
        }
    }
    y
}

/// The trace entry of an attempt's start point (from the seed, or a restart).
fn start_step(q: &[f64], raw_q: &[f64], ev: &Eval, restart: bool) -> IkStep {
    IkStep {
        q: q.to_vec(),
        raw_q: raw_q.to_vec(),
        error: ev.e.norm(),
        position_error: ev.position_error,
        orientation_error: ev.orientation_error,
        step: 0.0,
        damping: 0.0,
        accepted: true,
        restart,
    }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
mod tests {
    use super::{SMALL_SIN2, angle_over_sin, asin_over_sin, rotation_vector};
    use crate::orientation::rotation_log;
    use nalgebra::{Rotation3, Vector3};
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn angle_over_sin_is_atan2_over_sin() {
        for k in 1..2000 {
            let theta = std::f64::consts::PI * k as f64 / 2000.0;
            let (s, c) = theta.sin_cos();
            let want = s.atan2(c) / s;
            let got = angle_over_sin(s, c);
            assert!(
                (got - want).abs() <= 1e-14 * want,
                "θ = {theta}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn asin_over_sin_is_the_angle_over_its_sine_below_the_switch() {
        // θ from 10⁻⁸ up to the switch (sin θ = 0.05): within 2 ulp of θ / sin θ.
        let top = SMALL_SIN2.sqrt().asin();
        for k in 0..=2000 {
            let theta = 1e-8 + (top - 1e-8) * k as f64 / 2000.0;
            let s = theta.sin();
            if s * s >= SMALL_SIN2 {
                continue;
            }
            let want = theta / s;
            let got = asin_over_sin(s * s);
            assert!(
                (got - want).abs() <= 4.5e-16 * want,
                "θ = {theta}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn rotation_vector_matches_the_rotation_log_on_both_sides_of_the_switch() {
        let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
        for theta in [1e-9, 1e-5, 0.01, 0.049, 0.0501, 0.051, 0.3, 1.5, 2.9, 3.1] {
            let r = *Rotation3::from_scaled_axis(axis * theta).matrix();
            let got = rotation_vector(&r);
            let want = rotation_log(&r);
            assert!(
                (got - want).norm() <= 1e-15 * theta.max(1.0),
                "θ = {theta}: {got} vs {want}"
            );
            assert!(
                (got.norm() - theta).abs() <= 1e-15 * theta.max(1.0),
                "θ = {theta}"
            );
        }
    }
}
