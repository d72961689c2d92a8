//! The iterative methods: damped least squares (Levenberg–Marquardt), Newton with the
//! pseudo-inverse and gradient descent, sharing one workspace and one error function.//!
//! The attempts' loop is in [`attempt`], the linear algebra of one step in [`linear`], and
//! the error function in [`super::task_error`]; this module holds the workspace and the
//! solve over attempts and restarts.

mod attempt;
mod linear;

use nalgebra::{IsometryMatrix3, Matrix6, Matrix6xX};

use super::chain::Chain;
use super::task_error::{Eval, TaskTarget, evaluate};
use super::{IkMethod, IkResult, IkSettings, IkStep, JacobianSource, within_limits};
use crate::jacobian::Task;
use crate::rng::SplitMix64;
use crate::robot::{JointKind, Robot};
use attempt::Outcome;
use linear::keep_or_raw;

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

/// The linear rows of the error and the Jacobian are divided by reach / LINEAR_WEIGHT:
/// a position error of a quarter of the reach weighs as one radian. With the whole reach
/// (weight 1) the orientation dominates the first steps and attempts stall more often
/// with the orientation met and the position not (docs/kinematics.md §8).
const LINEAR_WEIGHT: f64 = 4.0;

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
