//! One attempt of a numeric method: its iterations, the damping it adapts, and when it
//! ends (converged, at a minimum, stalled or slow). Apart from the solve over attempts so
//! that the loop's rules and their measured constants stand together.

use super::linear::pinv_times;
use super::{Ctx, Workspace};
use crate::ik::task_error::{Eval, evaluate};
use crate::ik::{IkMethod, IkStep};

/// How an attempt ended.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Outcome {
    pub(super) iterations: usize,
    pub(super) converged: bool,
    /// Stopped at a minimum of the error (no step lowers it): the closest pose nearby.
    pub(super) stationary: bool,
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
impl Workspace {
    /// One attempt from the current `q` with at most `cap` iterations; `may_restart`: a
    /// stalled attempt may end early for a restart ([`STALL_ITERATIONS`]). Leaves the
    /// attempt's answer in `q` and returns its outcome and error.
    pub(super) fn attempt(
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
