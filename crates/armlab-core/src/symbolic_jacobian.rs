//! The geometric Jacobian symbolically (docs/kinematics.md §13.4): built from the
//! symbolic T_0i as the numeric one is from the numeric T_0i, in the base frame and in
//! the tool frame.

use nalgebra::Matrix6xX;

use super::robot::{Convention, JointKind, Robot};
use super::symbolic::{Expr, SymbolicChain, SymbolicMatrix};

/// A symbolic 6 × n Jacobian: `columns[i]` is joint i's column, the linear rows (0–2)
/// then the angular rows (3–5).
#[derive(Debug, Clone, PartialEq)]
pub struct SymbolicJacobian {
    /// One column per joint.
    pub columns: Vec<[Expr; 6]>,
}

impl SymbolicJacobian {
    /// The numeric Jacobian at `q`.
    pub fn eval(&self, q: &[f64]) -> Matrix6xX<f64> {
        Matrix6xX::from_fn(self.columns.len(), |r, c| self.columns[c][r].eval(q))
    }

    /// The entry in row `r`, column `c`.
    pub fn entry(&self, r: usize, c: usize) -> &Expr {
        &self.columns[c][r]
    }

    /// The matrix as LaTeX (`\begin{bmatrix} … \end{bmatrix}`), every entry in full.
    pub fn latex(&self) -> String {
        let rows: Vec<String> = (0..6)
            .map(|r| {
                let row: Vec<String> = self.columns.iter().map(|c| c[r].latex()).collect();
                row.join(" & ")
            })
            .collect();
        format!(
            "\\begin{{bmatrix}} {} \\end{{bmatrix}}",
            rows.join(" \\\\ ")
        )
    }
}

/// The coefficients below which a term is rounding residue, as [`symbolic_chain`](super::symbolic::symbolic_chain) drops them.
fn zero(robot: &Robot) -> f64 {
    1e-12 * robot.reach().max(1.0)
}

/// Column `c` (0–2: x, y, z; 3: the origin) of a transform's top three rows.
fn column(m: &SymbolicMatrix, c: usize) -> [Expr; 3] {
    std::array::from_fn(|r| m.entries[r][c].clone())
}

/// `a × b`, each entry simplified.
fn cross(a: &[Expr; 3], b: &[Expr; 3], zero: f64) -> [Expr; 3] {
    std::array::from_fn(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let mut e = a[i].times(&b[j]).plus(&a[j].times(&b[i]).scaled(-1.0));
        e.simplify(zero);
        e
    })
}

/// The base-frame geometric Jacobian of `robot` from its symbolic `chain`: joint i's
/// column from its axis z and a point o on it (frame i−1 in standard DH, frame i in
/// modified DH) and the tool point p, revolute `(z × (p − o), z)`, prismatic `(z, 0)`.
pub fn symbolic_jacobian(robot: &Robot, chain: &SymbolicChain) -> SymbolicJacobian {
    let zero = zero(robot);
    let base = SymbolicMatrix::constant(&robot.world_from_base);
    let p = column(&chain.base_from_tool, 3);
    let columns = robot
        .joints
        .iter()
        .enumerate()
        .filter_map(|(i, joint)| {
            let frame = match (robot.convention, i) {
                (Convention::Standard, 0) => &base,
                (Convention::Standard, _) => chain.base_from_frames.get(i - 1)?,
                (Convention::Modified, _) => chain.base_from_frames.get(i)?,
            };
            let z = column(frame, 2);
            let (v, w) = match joint.kind {
                JointKind::Revolute => {
                    let o = column(frame, 3);
                    let arm: [Expr; 3] = std::array::from_fn(|k| p[k].plus(&o[k].scaled(-1.0)));
                    (cross(&z, &arm, zero), z)
                }
                JointKind::Prismatic => (z, std::array::from_fn(|_| Expr::default())),
            };
            Some(stacked(v, w))
        })
        .collect();
    SymbolicJacobian { columns }
}

/// A column of J: its linear part `v` above its angular part `w`.
fn stacked(v: [Expr; 3], w: [Expr; 3]) -> [Expr; 6] {
    let [v0, v1, v2] = v;
    let [w0, w1, w2] = w;
    [v0, v1, v2, w0, w1, w2]
}

/// The Jacobian `j` (base frame) in the tool frame: `blockdiag(Rᵀ, Rᵀ) · J` with R the
/// rotation of the tool pose in `chain`, each entry simplified.
pub fn in_tool_frame(
    robot: &Robot,
    chain: &SymbolicChain,
    j: &SymbolicJacobian,
) -> SymbolicJacobian {
    let zero = zero(robot);
    let r = &chain.base_from_tool.entries;
    let turn = |v: &[Expr]| -> [Expr; 3] {
        std::array::from_fn(|k| {
            let mut e = (0..3).fold(Expr::default(), |sum, m| sum.plus(&r[m][k].times(&v[m])));
            e.simplify(zero);
            e
        })
    };
    let columns = j
        .columns
        .iter()
        .map(|c| stacked(turn(&c[..3]), turn(&c[3..])))
        .collect();
    SymbolicJacobian { columns }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests), which
// clippy does not treat as tests.
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    use crate::fk::ForwardKinematics;
    use crate::jacobian::geometric_jacobian;
    use crate::presets::preset;
    use crate::rng::SplitMix64;
    use crate::symbolic::symbolic_chain;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    /// Joint values spread over each joint's limits.
    fn some_q(robot: &Robot, rng: &mut SplitMix64) -> Vec<f64> {
        robot
            .joints
            .iter()
            .map(|j| j.limits.min + (j.limits.max - j.limits.min) * rng.next_f64())
            .collect()
    }

    #[test]
    fn the_symbolic_jacobian_at_a_q_is_the_numeric_one_in_the_base_and_the_tool_frame() {
        let mut rng = SplitMix64::new(7);
        for id in crate::presets::preset_ids() {
            let robot = preset(id).expect("a preset");
            let chain = symbolic_chain(&robot);
            let base = symbolic_jacobian(&robot, &chain);
            let tool = in_tool_frame(&robot, &chain, &base);
            assert_eq!(base.columns.len(), robot.dof(), "{id}");
            for _ in 0..3 {
                let q = some_q(&robot, &mut rng);
                let fk = ForwardKinematics::new(&robot, &q).expect("fk");
                let numeric = geometric_jacobian(&fk);
                let scale = robot.reach().max(1.0);
                let err = (base.eval(&q) - &numeric).abs().max();
                assert!(err <= 1e-12 * scale, "{id}: base frame off by {err:e}");
                let rt = fk.base_from_tool.rotation.matrix().transpose();
                let mut want = numeric.clone();
                for c in 0..robot.dof() {
                    let v = rt * numeric.fixed_view::<3, 1>(0, c);
                    let w = rt * numeric.fixed_view::<3, 1>(3, c);
                    want.fixed_view_mut::<3, 1>(0, c).copy_from(&v);
                    want.fixed_view_mut::<3, 1>(3, c).copy_from(&w);
                }
                let err = (tool.eval(&q) - &want).abs().max();
                assert!(err <= 1e-12 * scale, "{id}: tool frame off by {err:e}");
            }
        }
    }

    #[test]
    fn the_planar_2r_jacobian_reads_as_the_textbook_one() {
        let robot = preset("planar-2r").expect("the planar 2R");
        let chain = symbolic_chain(&robot);
        let j = symbolic_jacobian(&robot, &chain);
        // J = [−a1 s1 − a2 s12, −a2 s12; a1 c1 + a2 c12, a2 c12; 0 0; 0 0; 0 0; 1 1].
        for (r, c, joints) in [(0, 0, vec![0, 1]), (0, 1, vec![0, 1]), (1, 1, vec![0, 1])] {
            assert_eq!(j.entry(r, c).joints(), joints, "J[{r}][{c}]");
        }
        assert_eq!(j.entry(0, 1).term_count(), 1, "{}", j.entry(0, 1).plain());
        assert_eq!(j.entry(0, 0).term_count(), 2, "{}", j.entry(0, 0).plain());
        for c in 0..2 {
            assert!(j.entry(2, c).is_zero());
            assert_eq!(j.entry(5, c).plain(), "1");
        }
    }
}
