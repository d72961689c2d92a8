//! The linear algebra of one step: the task Jacobian (geometric or by central
//! differences), the damped, pseudo-inverse and transpose solves, the joints locked at a
//! limit, and the joint values a step gives. Apart from the attempts' loop, which decides
//! which step to take and whether to keep it.

use nalgebra::{Matrix6, Matrix6xX, Vector6};
use std::f64::consts::PI;

use super::{Ctx, JacobianSource, Workspace};
use crate::fk::tool_pose;
use crate::ik::chain::solve_spd6;
use crate::ik::task_error::rotation_vector;
use crate::jacobian::{NUMERIC_EPSILON, Task};
use crate::robot::{Joint, JointKind, Robot};

impl Workspace {
    /// Fills `jt` (and `m` = jt·jtᵀ) at the current `q`; `chain` must hold `q`.
    pub(super) fn task_jacobian(&mut self, ctx: &Ctx) {
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
    pub(super) fn damped_step(&mut self, ctx: &Ctx, lambda2: f64, e: &Vector6<f64>) -> Option<f64> {
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
    pub(super) fn back_substitute(&mut self, y: &Vector6<f64>) -> f64 {
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
    pub(super) fn take_step(&mut self, robot: &Robot, wrap: bool) {
        for (i, joint) in robot.joints.iter().enumerate() {
            let (current, raw) = (self.q[i], self.q[i] + self.dq[i]);
            self.raw[i] = raw;
            self.q_try[i] = keep_or_raw(wrap, joint, raw, current);
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
pub(super) fn keep_or_raw(wrap: bool, joint: &Joint, raw: f64, current: f64) -> f64 {
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
pub(super) fn pinv_times(m: &Matrix6<f64>, e: &Vector6<f64>) -> Vector6<f64> {
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
