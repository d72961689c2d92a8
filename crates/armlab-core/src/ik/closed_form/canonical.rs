//! The chain every closed form reads: the robot's DH table written as standard-DH rows
//! `T = pre·A_1⋯A_n·post` (either convention), and the tests on a row's twist that
//! recognise a family. Apart from the solvers so that each family's solver and the
//! family detection share one reading of the table.

use crate::angles::{sin_cos, wrap_to_pi};
use nalgebra::{IsometryMatrix3, Rotation3, Translation3};

use crate::robot::{Convention, JointKind, Robot};

/// A standard-DH row: the constant parts; the joint variable is θ (revolute, the
/// offset `theta0` included in it) or d (prismatic, the offset `d` included in it).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Row {
    pub(super) d: f64,
    pub(super) a: f64,
    pub(super) alpha: f64,
    /// The fixed θ of a prismatic row.
    pub(super) theta0: f64,
    pub(super) prismatic: bool,
}

impl Row {
    /// `sin α`, `cos α` once, for [`Row::transform_with`].
    pub(super) fn alpha_sin_cos(&self) -> (f64, f64) {
        sin_cos(self.alpha)
    }

    /// The standard DH transform `Rot_z(θ)·Trans_z(d)·Trans_x(a)·Rot_x(α)` of this row
    /// for the joint variable `var` (θ, or d for a prismatic row), with `sin α`, `cos α`
    /// given.
    pub(super) fn transform_with(&self, var: f64, (sa, ca): (f64, f64)) -> IsometryMatrix3<f64> {
        let (theta, d) = if self.prismatic {
            (self.theta0, var)
        } else {
            (var, self.d)
        };
        let (st, ct) = sin_cos(theta);
        IsometryMatrix3::from_parts(
            Translation3::new(self.a * ct, self.a * st, d),
            Rotation3::from_matrix_unchecked(nalgebra::Matrix3::new(
                ct,
                -st * ca,
                st * sa,
                st,
                ct * ca,
                -ct * sa,
                0.0,
                sa,
                ca,
            )),
        )
    }

    /// [`Row::transform_with`] computing `sin α`, `cos α`.
    pub(super) fn transform(&self, var: f64) -> IsometryMatrix3<f64> {
        self.transform_with(var, self.alpha_sin_cos())
    }

    /// σ = the sign of sin α (for quarter-turn rows).
    pub(super) fn sigma(&self) -> f64 {
        sin_cos(self.alpha).0.signum()
    }
}

/// `T = pre·A_1⋯A_n·post` in standard DH (see the module doc).
#[derive(Debug, Clone)]
pub(super) struct Canonical {
    pub(super) pre: IsometryMatrix3<f64>,
    pub(super) post: IsometryMatrix3<f64>,
    pub(super) rows: [Row; 6],
    pub(super) n: usize,
}

impl Canonical {
    /// The pose `pre⁻¹·target·post'⁻¹` with the last row's `a` and `α` moved into `post'`,
    /// so that the last link is `Rot_z(θ_n)·Trans_z(d_n)` (or `Trans_z(d_n)` prismatic).
    pub(super) fn without_last_link(
        &self,
        target: &IsometryMatrix3<f64>,
    ) -> (IsometryMatrix3<f64>, Row) {
        let last = self.rows[self.n - 1];
        let post = rot_x_trans_x(last.alpha, last.a) * self.post;
        let row = Row {
            a: 0.0,
            alpha: 0.0,
            ..last
        };
        (self.pre.inverse() * target * post.inverse(), row)
    }
}

fn rot_x_trans_x(alpha: f64, a: f64) -> IsometryMatrix3<f64> {
    let (s, c) = sin_cos(alpha);
    IsometryMatrix3::from_parts(
        Translation3::new(a, 0.0, 0.0),
        Rotation3::from_matrix_unchecked(nalgebra::Matrix3::new(
            1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c,
        )),
    )
}

pub(super) fn canonical(robot: &Robot) -> Option<Canonical> {
    let n = robot.dof();
    if !(2..=6).contains(&n) {
        return None;
    }
    let mut rows = [Row::default(); 6];
    let pre;
    match robot.convention {
        Convention::Standard => {
            pre = robot.world_from_base;
            for (row, j) in rows.iter_mut().zip(&robot.joints) {
                *row = Row {
                    d: j.dh.d,
                    a: j.dh.a,
                    alpha: j.dh.alpha,
                    theta0: j.dh.theta,
                    prismatic: j.kind == JointKind::Prismatic,
                };
            }
        }
        Convention::Modified => {
            let first = robot.joints.first()?.dh;
            pre = robot.world_from_base * rot_x_trans_x(first.alpha, first.a);
            for (i, (row, joint)) in rows.iter_mut().zip(&robot.joints).enumerate() {
                let (a, alpha) = match robot.joints.get(i + 1) {
                    Some(next) => (next.dh.a, next.dh.alpha),
                    None => (0.0, 0.0),
                };
                *row = Row {
                    d: joint.dh.d,
                    a,
                    alpha,
                    theta0: joint.dh.theta,
                    prismatic: joint.kind == JointKind::Prismatic,
                };
            }
        }
    }
    Some(Canonical {
        pre,
        post: robot.flange_from_tool,
        rows,
        n,
    })
}

pub(super) fn angle_is(x: f64, y: f64) -> bool {
    wrap_to_pi(x - y).abs() < 1e-9
}

pub(super) fn quarter_turn(alpha: f64) -> bool {
    sin_cos(alpha).1.abs() < 1e-9
}

/// α = 0 or π: the next axis is parallel to this one.
pub(super) fn parallel(alpha: f64) -> bool {
    sin_cos(alpha).0.abs() < 1e-9
}
