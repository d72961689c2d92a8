//! The numeric solver's own forward kinematics (docs/kinematics.md §8.8): the DH rows
//! with sin α and cos α computed once per robot, one pass down the chain per iteration
//! keeping only what the solver reads (each joint's axis and a point on it, and the tool
//! pose; not the link transforms A_i or the frames the app shows), and the task Jacobian
//! built from those axes with `J·Jᵀ` summed on its upper triangle.

use nalgebra::{IsometryMatrix3, Matrix3, Matrix6, Matrix6xX, Rotation3, Translation3, Vector3};

use crate::angles::{SIZE_OVER_SPEED, sin_cos, sin_cos_2};
use crate::jacobian::Task;
use crate::robot::{Convention, JointKind, Robot};

/// A row's twist α when it is a multiple of a quarter turn (to within 10⁻¹⁵ in sin α and
/// cos α, as the presets' ±π/2 are): the pass then permutes and negates columns instead
/// of multiplying by sin α and cos α, whose rounded values (cos(π/2) ≈ 6·10⁻¹⁷) it drops.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Twist {
    /// α = 0.
    Zero,
    /// α = +π/2.
    Quarter,
    /// α = −π/2.
    MinusQuarter,
    /// α = π.
    Half,
    /// Any other α: sin α and cos α.
    General,
}

impl Twist {
    fn of(sa: f64, ca: f64) -> Twist {
        const EPS: f64 = 1e-15;
        let near = |v: f64, w: f64| (v - w).abs() <= EPS;
        if near(sa, 0.0) && near(ca, 1.0) {
            Twist::Zero
        } else if near(sa, 1.0) && near(ca, 0.0) {
            Twist::Quarter
        } else if near(sa, -1.0) && near(ca, 0.0) {
            Twist::MinusQuarter
        } else if near(sa, 0.0) && near(ca, -1.0) {
            Twist::Half
        } else {
            Twist::General
        }
    }

    /// `(b·cos α + c·sin α, c·cos α − b·sin α)`.
    #[inline(always)]
    fn turn(
        self,
        sa: f64,
        ca: f64,
        b: Vector3<f64>,
        c: Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        match self {
            Twist::Zero => (b, c),
            Twist::Quarter => (c, -b),
            Twist::MinusQuarter => (-c, b),
            Twist::Half => (-b, -c),
            Twist::General => (b * ca + c * sa, c * ca - b * sa),
        }
    }
}

/// One DH row in the form the pass needs.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Link {
    twist: Twist,
    sa: f64,
    ca: f64,
    a: f64,
    d: f64,
    theta: f64,
    prismatic: bool,
    /// The row's α and the joint's limits, to notice a changed robot.
    alpha: f64,
    limits: (f64, f64),
}

/// The chain of one robot and the result of the last [`Chain::update`].
#[derive(Debug, Clone, Default)]
pub(crate) struct Chain {
    links: Vec<Link>,
    modified: bool,
    base_r: Matrix3<f64>,
    base_o: Vector3<f64>,
    /// `flange_from_tool`, `None` when it is the identity.
    tool: Option<IsometryMatrix3<f64>>,
    /// Axis of joint i in the base frame (unit).
    axes: Vec<Vector3<f64>>,
    /// A point on joint i's axis in the base frame.
    origins: Vec<Vector3<f64>>,
    /// (sin θ_i, cos θ_i) and d_i of the last update.
    sc: Vec<(f64, f64, f64)>,
    /// The tool pose at the last update.
    pub pose: IsometryMatrix3<f64>,
    reach: f64,
}

impl Chain {
    /// Takes `robot`'s rows; nothing is recomputed when they are the ones it holds
    /// (sin α and cos α, the reach).
    pub fn set(&mut self, robot: &Robot) {
        let n = robot.dof();
        let tool = (robot.flange_from_tool != IsometryMatrix3::identity())
            .then_some(robot.flange_from_tool);
        let modified = robot.convention == Convention::Modified;
        let same = self.links.len() == n
            && self.modified == modified
            && self.tool == tool
            && self.base_r == *robot.world_from_base.rotation.matrix()
            && self.base_o == robot.world_from_base.translation.vector
            && self.links.iter().zip(&robot.joints).all(|(l, j)| {
                l.alpha.to_bits() == j.dh.alpha.to_bits()
                    && l.a.to_bits() == j.dh.a.to_bits()
                    && l.d.to_bits() == j.dh.d.to_bits()
                    && l.theta.to_bits() == j.dh.theta.to_bits()
                    && l.prismatic == (j.kind == JointKind::Prismatic)
                    && l.limits == (j.limits.min, j.limits.max)
            });
        if same {
            return;
        }
        self.links.clear();
        self.links.extend(robot.joints.iter().map(|joint| {
            let (sa, ca) = sin_cos(joint.dh.alpha);
            Link {
                twist: Twist::of(sa, ca),
                sa,
                ca,
                a: joint.dh.a,
                d: joint.dh.d,
                theta: joint.dh.theta,
                prismatic: joint.kind == JointKind::Prismatic,
                alpha: joint.dh.alpha,
                limits: (joint.limits.min, joint.limits.max),
            }
        }));
        self.axes.resize(n, Vector3::z());
        self.origins.resize(n, Vector3::zeros());
        self.sc.resize(n, (0.0, 1.0, 0.0));
        self.modified = modified;
        self.base_r = *robot.world_from_base.rotation.matrix();
        self.base_o = robot.world_from_base.translation.vector;
        self.tool = tool;
        self.reach = robot.reach();
    }

    /// The robot's reach ([`Robot::reach`]), kept with its rows.
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// Forward kinematics at `q` (one entry per joint): the tool pose, and each joint's
    /// axis and point for [`Chain::task_jacobian`].
    // Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    pub fn update(&mut self, q: &[f64]) {
        // Every joint's sine and cosine first, in a loop of independent work (the chain
        // below is one long dependency, and the sines do not wait in it), two joints at a
        // time in one vector register.
        for ((link, &qi), sc) in self.links.iter().zip(q).zip(self.sc.iter_mut()) {
            *sc = if link.prismatic {
                (link.theta, 0.0, link.d + qi)
            } else {
                (link.theta + qi, 0.0, link.d)
            };
        }
        // Two at a time, except in the page (the vector copy of the polynomials cost it
        // about 370 B): there one by one.
        let paired = if SIZE_OVER_SPEED {
            0
        } else {
            self.sc.len() / 2 * 2
        };
        let (pairs, rest) = self.sc.split_at_mut(paired);
        for pair in pairs.chunks_exact_mut(2) {
            let (s, c) = sin_cos_2([pair[0].0, pair[1].0]);
            pair[0] = (s[0], c[0], pair[0].2);
            pair[1] = (s[1], c[1], pair[1].2);
        }
        for sc in rest {
            let (st, ct) = sin_cos(sc.0);
            *sc = (st, ct, sc.2);
        }
        let mut r = self.base_r;
        let mut o = self.base_o;
        let modified = self.modified;
        for (((link, &(st, ct, d)), axis), origin) in self
            .links
            .iter()
            .zip(&self.sc)
            .zip(self.axes.iter_mut())
            .zip(self.origins.iter_mut())
        {
            let (sa, ca) = (link.sa, link.ca);
            let c0 = r.column(0).into_owned();
            let c1 = r.column(1).into_owned();
            let c2 = r.column(2).into_owned();
            if modified {
                // R_i = R·Rx(α)·Rz(θ), o_i = o + a·x_{i−1} + d·z_i; axis z_i at o_i.
                let (y1, z) = link.twist.turn(sa, ca, c1, c2);
                let x = c0 * ct + y1 * st;
                let y = y1 * ct - c0 * st;
                o += c0 * link.a + z * d;
                *axis = z;
                *origin = o;
                r = Matrix3::from_columns(&[x, y, z]);
            } else {
                // R_i = R·Rz(θ)·Rx(α), o_i = o + a·x_i + d·z_{i−1}; axis z_{i−1} at o_{i−1}.
                let x = c0 * ct + c1 * st;
                let y0 = c1 * ct - c0 * st;
                let (y, z) = link.twist.turn(sa, ca, y0, c2);
                *axis = c2;
                *origin = o;
                o += x * link.a + c2 * d;
                r = Matrix3::from_columns(&[x, y, z]);
            }
        }
        let flange =
            IsometryMatrix3::from_parts(Translation3::from(o), Rotation3::from_matrix_unchecked(r));
        self.pose = match &self.tool {
            Some(tool) => flange * tool,
            None => flange,
        };
    }

    /// The task rows of the geometric Jacobian at the last update into `jt` (linear rows
    /// times `inv_len`, a prismatic joint's column per step unit of `1/inv_len` so that
    /// it is its unit axis; unused rows zero), and `m = jt·jtᵀ`.
    // Inlined into the solver's loop except in the page (`angles::SIZE_OVER_SPEED`).
    #[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]
    pub fn task_jacobian(
        &self,
        task: Task,
        inv_len: f64,
        jt: &mut Matrix6xX<f64>,
        m: &mut Matrix6<f64>,
    ) {
        let p = self.pose.translation.vector;
        let r = self.pose.rotation.matrix();
        // 5D: the angular rows projected on the two directions perpendicular to the axis.
        let (u1, u2) = match task {
            Task::PositionAndAxis(axis) => {
                let k = axis.index();
                (
                    r.column((k + 1) % 3).into_owned(),
                    r.column((k + 2) % 3).into_owned(),
                )
            }
            _ => (Vector3::zeros(), Vector3::zeros()),
        };
        let mut upper = [0.0; 21];
        for ((link, (z, o)), mut col) in self
            .links
            .iter()
            .zip(self.axes.iter().zip(&self.origins))
            .zip(jt.column_iter_mut())
        {
            // A prismatic joint's value is in step units of 1/inv_len (docs/kinematics.md
            // §8): its column, axis · inv_len per unit of q, is the axis per step unit.
            let (v, w) = if link.prismatic {
                (*z, Vector3::zeros())
            } else {
                (z.cross(&(p - o)) * inv_len, *z)
            };
            let c: [f64; 6] = match task {
                Task::Position => [v.x, v.y, v.z, 0.0, 0.0, 0.0],
                Task::FullPose => [v.x, v.y, v.z, w.x, w.y, w.z],
                Task::PositionAndAxis(_) => [v.x, v.y, v.z, u1.dot(&w), u2.dot(&w), 0.0],
            };
            let mut k = 0;
            for a in 0..6 {
                for b in a..6 {
                    upper[k] += c[a] * c[b];
                    k += 1;
                }
            }
            col.copy_from_slice(&c);
        }
        let mut k = 0;
        for a in 0..6 {
            for b in a..6 {
                m[(a, b)] = upper[k];
                m[(b, a)] = upper[k];
                k += 1;
            }
        }
    }
}

/// Solves `(A + shift·I)·y = b` for a symmetric 6×6 `A` with `A + shift·I` positive
/// definite (docs/kinematics.md §8.8, step 4): by block elimination on the 3×3 blocks
/// ([`solve_spd6_blocks`]) when both blocks it inverts are well conditioned, else by the
/// `L·D·Lᵀ` factorisation ([`solve_spd6_ldl`]), which the page's build
/// ([`SIZE_OVER_SPEED`]) uses alone. `None` when `A + shift·I` is not positive
/// definite to working precision.
pub(crate) fn solve_spd6(
    a: &Matrix6<f64>,
    shift: f64,
    b: &nalgebra::Vector6<f64>,
) -> Option<[f64; 6]> {
    // The page (built for size) keeps the factorisation alone: one iteration a frame.
    if !SIZE_OVER_SPEED && let Some(y) = solve_spd6_blocks(a, shift, b) {
        return Some(y);
    }
    solve_spd6_ldl(a, shift, b)
}

/// `(A + shift·I)·y = b` by block elimination: with `A + shift·I = [P Q; Qᵀ R]`, `P⁻¹` from
/// its adjugate, the Schur complement `S = R − Qᵀ·P⁻¹·Q` (positive definite when the
/// whole is), then `y₂ = S⁻¹·(b₂ − Qᵀ·P⁻¹·b₁)` and `y₁ = P⁻¹·b₁ − P⁻¹·Q·y₂`. Two divisions
/// in all, where `L·D·Lᵀ` waits on six in a row. An explicit inverse is accurate only for a
/// well-conditioned block: `None` unless `P` and `S` pass [`inverse_spd3`]'s test.
fn solve_spd6_blocks(a: &Matrix6<f64>, shift: f64, b: &nalgebra::Vector6<f64>) -> Option<[f64; 6]> {
    let block = |r: usize, c: usize| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| a[(r + i, c + j)]))
    };
    let mut p = block(0, 0);
    let q = block(0, 3);
    let mut r = block(3, 3);
    for k in 0..3 {
        p[k][k] += shift;
        r[k][k] += shift;
    }
    let qt: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|k| q[k][i]));
    let p_inv = inverse_spd3(&p)?;
    // X = P⁻¹·Q and z = P⁻¹·b₁.
    let x: [[f64; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| dot3(&p_inv[i], |k| q[k][j])));
    let z: [f64; 3] = std::array::from_fn(|i| dot3(&p_inv[i], |k| b[k]));
    // S = R − Qᵀ·X (symmetric) and r₂ = b₂ − Qᵀ·z.
    let s: [[f64; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| r[i][j] - dot3(&qt[i], |k| x[k][j])));
    let r2: [f64; 3] = std::array::from_fn(|i| b[3 + i] - dot3(&qt[i], |k| z[k]));
    let s_inv = inverse_spd3(&s)?;
    let y2: [f64; 3] = std::array::from_fn(|i| dot3(&s_inv[i], |k| r2[k]));
    let y1: [f64; 3] = std::array::from_fn(|i| z[i] - dot3(&x[i], |k| y2[k]));
    Some([y1[0], y1[1], y1[2], y2[0], y2[1], y2[2]])
}

/// The least `det / (m₀₀·m₁₁·m₂₂)` of a block that [`solve_spd6_blocks`] inverts.
const WELL_CONDITIONED: f64 = 1e-4;

/// `Σₖ u[k]·v(k)` over k = 0, 1, 2.
#[inline(always)]
fn dot3(u: &[f64; 3], v: impl Fn(usize) -> f64) -> f64 {
    u[0] * v(0) + u[1] * v(1) + u[2] * v(2)
}

/// The inverse of a symmetric 3×3 matrix from its adjugate, or `None` unless it is
/// positive definite (Sylvester's criterion: `m₀₀ > 0`, `m₀₀m₁₁ − m₀₁² > 0`, det > 0) and
/// well conditioned: det ≥ [`WELL_CONDITIONED`] · m₀₀m₁₁m₂₂ (Hadamard: det ≤ m₀₀m₁₁m₂₂, with
/// equality for a diagonal matrix; a small ratio means a nearly singular one).
#[inline(always)]
fn inverse_spd3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c00 = m[1][1] * m[2][2] - m[1][2] * m[1][2];
    let c01 = m[0][2] * m[1][2] - m[0][1] * m[2][2];
    let c02 = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    let c11 = m[0][0] * m[2][2] - m[0][2] * m[0][2];
    let c12 = m[0][1] * m[0][2] - m[0][0] * m[1][2];
    let c22 = m[0][0] * m[1][1] - m[0][1] * m[0][1];
    let det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    // Written so that NaN fails too.
    if !(m[0][0] > 0.0
        && c22 > 0.0
        && det > 0.0
        && det >= WELL_CONDITIONED * (m[0][0] * m[1][1] * m[2][2]))
    {
        return None;
    }
    let inv = 1.0 / det;
    let (a, b, c, d, e, f) = (
        c00 * inv,
        c01 * inv,
        c02 * inv,
        c11 * inv,
        c12 * inv,
        c22 * inv,
    );
    Some([[a, b, c], [b, d, e], [c, e, f]])
}

/// [`solve_spd6`] by the `L·D·Lᵀ` factorisation of `A + shift·I` (L unit lower
/// triangular, D diagonal: Cholesky without square roots), then forward substitution,
/// division by D and back substitution, written out on arrays (one division per pivot; the
/// shift is added to the pivots, so `A` is not copied). `None` when a pivot is not positive
/// (not positive definite to working precision).
fn solve_spd6_ldl(a: &Matrix6<f64>, shift: f64, b: &nalgebra::Vector6<f64>) -> Option<[f64; 6]> {
    let mut f = Ldl {
        l: [[0.0; 6]; 6],
        d: [0.0; 6],
        inv_d: [0.0; 6],
    };
    // One call per column with the column's index a constant, so that every inner loop
    // has a known length and unrolls (with run-time lengths they stayed loops).
    let ok = f.column::<0>(a, shift)
        && f.column::<1>(a, shift)
        && f.column::<2>(a, shift)
        && f.column::<3>(a, shift)
        && f.column::<4>(a, shift)
        && f.column::<5>(a, shift);
    if !ok {
        return None;
    }
    let mut y = [b[0], b[1], b[2], b[3], b[4], b[5]];
    f.forward::<1>(&mut y);
    f.forward::<2>(&mut y);
    f.forward::<3>(&mut y);
    f.forward::<4>(&mut y);
    f.forward::<5>(&mut y);
    f.backward::<5>(&mut y);
    f.backward::<4>(&mut y);
    f.backward::<3>(&mut y);
    f.backward::<2>(&mut y);
    f.backward::<1>(&mut y);
    f.backward::<0>(&mut y);
    Some(y)
}

/// The `L·D·Lᵀ` factors of [`solve_spd6`].
struct Ldl {
    /// L below the diagonal (row, column).
    l: [[f64; 6]; 6],
    d: [f64; 6],
    inv_d: [f64; 6],
}

// The loops index L by row and column, as the formulas do; their lengths are constants.
#[allow(clippy::needless_range_loop)]
impl Ldl {
    /// Column `J` of L and pivot `J` of D from `A + shift·I`; false when the pivot is not
    /// positive.
    #[inline(always)]
    fn column<const J: usize>(&mut self, a: &Matrix6<f64>, shift: f64) -> bool {
        // w[k] = L[J][k]·D[k] for k < J
        let mut w = [0.0f64; 6];
        let mut d = a[(J, J)] + shift;
        for k in 0..J {
            w[k] = self.l[J][k] * self.d[k];
            d -= w[k] * self.l[J][k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let inv = 1.0 / d;
        self.d[J] = d;
        self.inv_d[J] = inv;
        for i in J + 1..6 {
            let mut s = a[(i, J)];
            for k in 0..J {
                s -= self.l[i][k] * w[k];
            }
            self.l[i][J] = s * inv;
        }
        true
    }

    /// Row `I` of the forward substitution `L·z = b` (rows before it done).
    #[inline(always)]
    fn forward<const I: usize>(&self, y: &mut [f64; 6]) {
        let mut s = y[I];
        for k in 0..I {
            s -= self.l[I][k] * y[k];
        }
        y[I] = s;
    }

    /// Row `I` of `Lᵀ·y = D⁻¹·z` (rows after it done).
    #[inline(always)]
    fn backward<const I: usize>(&self, y: &mut [f64; 6]) {
        let mut s = y[I] * self.inv_d[I];
        for k in I + 1..6 {
            s -= self.l[k][I] * y[k];
        }
        y[I] = s;
    }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
mod tests {
    use super::solve_spd6;
    use crate::rng::SplitMix64;
    use nalgebra::{Matrix6, Matrix6xX, Vector6};
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    /// A random 6×n Jacobian (n = 3..8 columns: J·Jᵀ is rank-deficient for n < 6).
    fn random_j(rng: &mut SplitMix64, n: usize) -> Matrix6xX<f64> {
        Matrix6xX::from_fn(n, |_, _| rng.uniform(-2.0, 2.0))
    }

    #[test]
    fn the_block_solve_gives_the_damped_step_of_cholesky_and_refuses_what_is_not_positive_definite()
    {
        let mut rng = SplitMix64::new(11);
        // The largest relative difference of the steps Δq = Jᵀ·y, for well-conditioned
        // systems (κ ≤ 1e6) and for all.
        let (mut well, mut all) = (0.0f64, 0.0f64);
        for k in 0..3000 {
            let n = 3 + k % 6;
            let j = random_j(&mut rng, n);
            let m: Matrix6<f64> = &j * j.transpose();
            // The solver's damping spans 1e-9 (near a solution) to about 1.
            let shift = 10f64.powf(rng.uniform(-9.0, 0.0));
            let e = Vector6::from_fn(|_, _| rng.uniform(-1.0, 1.0));
            let a = m + Matrix6::identity() * shift;
            let want = a
                .cholesky()
                .expect("J·Jᵀ + λ²I is positive definite")
                .solve(&e);
            let got = Vector6::from(solve_spd6(&m, shift, &e).expect("positive definite"));
            let eig = a.symmetric_eigenvalues();
            let cond = eig.max() / eig.min();
            let (dq_want, dq_got) = (j.transpose() * want, j.transpose() * got);
            let diff = (&dq_got - &dq_want).norm() / dq_want.norm();
            all = all.max(diff);
            if cond <= 1e6 {
                well = well.max(diff);
            }
        }
        println!("largest relative step difference: {well:e} (κ ≤ 1e6), {all:e} (all)");
        // Measured: 5.6e-9 and 9.6e-5 (Cholesky's own error is about κ·ε); the steps of
        // an iteration need far less.
        assert!(well <= 1e-7, "{well:e}");
        assert!(all <= 1e-3, "{all:e}");
        // Not positive definite: a negative shift past the smallest eigenvalue, NaN.
        let j = random_j(&mut rng, 6);
        let m: Matrix6<f64> = &j * j.transpose();
        let smallest = m.symmetric_eigenvalues().min();
        let b = Vector6::repeat(1.0);
        assert!(solve_spd6(&m, -smallest - 1e-3, &b).is_none());
        assert!(solve_spd6(&m, -1.0e3, &b).is_none());
        assert!(solve_spd6(&m, f64::NAN, &b).is_none());
        let mut bad = m;
        bad[(4, 4)] = f64::NAN;
        assert!(solve_spd6(&bad, 1.0, &b).is_none());
    }
}
