//! Symbolic DH matrices (docs/kinematics.md §13): every A_i and T_0i of a robot as exact
//! expressions in its joint variables, simplified the way a textbook writes them
//! (`c1(222.1 c2 + 136.2 c23)`), with plain-text and LaTeX renderings and the joints each
//! entry depends on.
//!
//! An expression is a sum of terms; a term is a coefficient (`f64`) times a product of
//! factors: `cos` or `sin` of an integer combination of joint variables (`c23` is
//! cos(q2 + q3)), or a prismatic joint's variable (`d3`). The robot's constants are
//! substituted: lengths and the sines and cosines of twists and offsets become
//! coefficients, exactly 0 and ±1 at multiples of 90°. Nothing is approximated: a term is
//! only rewritten by an identity (angle sums, like terms added), so evaluating an entry at
//! any q gives the numeric matrix to rounding.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use nalgebra::{IsometryMatrix3, Matrix4};

use super::robot::{Convention, JointKind, Robot};

/// An entry with more terms than this is shown as "too long (N terms)"
/// ([`EntryText::TooLong`]); its expression is still kept and evaluates exactly.
pub const MAX_SHOWN_TERMS: usize = 16;

/// Two coefficients closer than this (relative) are taken as equal when an angle-sum
/// identity pairs two terms; rounding in the products of the robot's constants stays far
/// below it.
const PAIR_TOLERANCE: f64 = 1e-12;

/// An integer combination of joint variables, Σ k_j q_j, kept with its first coefficient
/// positive (cos(−x) = cos x, sin(−x) = −sin x move the sign into the term).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct AngleSum {
    /// (joint index from 0, coefficient ≠ 0), sorted by joint.
    parts: Vec<(usize, i32)>,
}

impl AngleSum {
    /// The variable of joint `j` (counted from 0).
    pub fn joint(j: usize) -> Self {
        AngleSum {
            parts: vec![(j, 1)],
        }
    }

    /// (joint index from 0, integer coefficient) of every joint in the sum.
    pub fn parts(&self) -> &[(usize, i32)] {
        &self.parts
    }

    /// `self + sign · other`.
    fn combined(&self, other: &AngleSum, sign: i32) -> AngleSum {
        let mut map: BTreeMap<usize, i32> = self.parts.iter().copied().collect();
        for &(j, k) in &other.parts {
            *map.entry(j).or_insert(0) += sign * k;
        }
        AngleSum {
            parts: map.into_iter().filter(|&(_, k)| k != 0).collect(),
        }
    }

    /// The sign of the first coefficient (+1 for the empty sum).
    fn leading_sign(&self) -> i32 {
        self.parts.first().map_or(1, |&(_, k)| k.signum())
    }

    fn negated(&self) -> AngleSum {
        AngleSum {
            parts: self.parts.iter().map(|&(j, k)| (j, -k)).collect(),
        }
    }

    /// The value of the sum at `q` (missing entries count as 0).
    pub fn eval(&self, q: &[f64]) -> f64 {
        self.parts
            .iter()
            .map(|&(j, k)| f64::from(k) * q.get(j).copied().unwrap_or(0.0))
            .sum()
    }

    /// The subscript: `23` for q2 + q3 (all coefficients 1, joints below 10), otherwise
    /// the signed list `1-2`, `10+11`, `2·1+3`.
    fn subscript(&self) -> String {
        let simple = self.parts.iter().all(|&(j, k)| k == 1 && j + 1 < 10);
        let mut out = String::new();
        for (n, &(j, k)) in self.parts.iter().enumerate() {
            if simple {
                let _ = write!(out, "{}", j + 1);
                continue;
            }
            if k < 0 {
                out.push('-');
            } else if n > 0 {
                out.push('+');
            }
            if k.abs() != 1 {
                let _ = write!(out, "{}·", k.abs());
            }
            let _ = write!(out, "{}", j + 1);
        }
        out
    }

    /// Whether the subscript needs parentheses in plain text (`c(1-2)`).
    fn needs_parentheses(&self) -> bool {
        !self.parts.iter().all(|&(j, k)| k == 1 && j + 1 < 10)
    }
}

/// One factor of a term.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Factor {
    /// cos of a sum of joint angles: `c23`.
    Cos(AngleSum),
    /// sin of a sum of joint angles: `s23`.
    Sin(AngleSum),
    /// The variable q_j of prismatic joint j (from 0), printed `d{j+1}`; the row's
    /// offset d⁰ appears as its own constant term.
    Var(usize),
}

impl Factor {
    /// The factor's value at `q`.
    pub fn eval(&self, q: &[f64]) -> f64 {
        match self {
            Factor::Cos(a) => a.eval(q).cos(),
            Factor::Sin(a) => a.eval(q).sin(),
            Factor::Var(j) => q.get(*j).copied().unwrap_or(0.0),
        }
    }

    /// The joints (from 0) the factor depends on, as a bit set (joint j is bit j).
    fn joint_bits(&self) -> u64 {
        match self {
            Factor::Cos(a) | Factor::Sin(a) => {
                a.parts.iter().fold(0, |bits, &(j, _)| bits | bit(j))
            }
            Factor::Var(j) => bit(*j),
        }
    }

    /// A key for display order: by first joint, then cos, sin, variable.
    fn display_key(&self) -> (Vec<(usize, i32)>, u8) {
        match self {
            Factor::Cos(a) => (a.parts.clone(), 0),
            Factor::Sin(a) => (a.parts.clone(), 1),
            Factor::Var(j) => (vec![(*j, 1)], 2),
        }
    }

    fn plain(&self) -> String {
        match self {
            Factor::Cos(a) | Factor::Sin(a) => {
                let letter = if matches!(self, Factor::Cos(_)) {
                    'c'
                } else {
                    's'
                };
                if a.needs_parentheses() {
                    format!("{letter}({})", a.subscript())
                } else {
                    format!("{letter}{}", a.subscript())
                }
            }
            Factor::Var(j) => format!("d{}", j + 1),
        }
    }

    fn latex(&self) -> String {
        match self {
            Factor::Cos(a) => format!("c_{{{}}}", a.subscript().replace('·', " ")),
            Factor::Sin(a) => format!("s_{{{}}}", a.subscript().replace('·', " ")),
            Factor::Var(j) => format!("d_{{{}}}", j + 1),
        }
    }
}

fn bit(j: usize) -> u64 {
    if j < 64 { 1 << j } else { 0 }
}

/// cos or sin of a sum, in canonical form: `(sign, factor)`, where the factor is `None`
/// for cos 0 = 1, and the sign 0 for sin 0 = 0.
fn trig(cosine: bool, angle: AngleSum) -> (f64, Option<Factor>) {
    if angle.parts.is_empty() {
        return if cosine { (1.0, None) } else { (0.0, None) };
    }
    let (sign, angle) = if angle.leading_sign() < 0 {
        (if cosine { 1.0 } else { -1.0 }, angle.negated())
    } else {
        (1.0, angle)
    };
    let factor = if cosine {
        Factor::Cos(angle)
    } else {
        Factor::Sin(angle)
    };
    (sign, Some(factor))
}

/// A product of factors, sorted (the key of a term).
type Monomial = Vec<Factor>;

/// An exact expression: a sum of coefficient × product-of-factors terms, like terms
/// added, and (after [`Expr::simplify`]) the angle-sum identities applied.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Expr {
    terms: BTreeMap<Monomial, f64>,
}

impl Expr {
    /// The constant `c`.
    pub fn constant(c: f64) -> Expr {
        let mut e = Expr::default();
        if c != 0.0 {
            e.terms.insert(Vec::new(), c);
        }
        e
    }

    /// A single factor with coefficient 1.
    pub fn factor(f: Factor) -> Expr {
        let mut e = Expr::default();
        e.terms.insert(vec![f], 1.0);
        e
    }

    /// cos(q_j).
    pub fn cos_joint(j: usize) -> Expr {
        Expr::factor(Factor::Cos(AngleSum::joint(j)))
    }

    /// sin(q_j).
    pub fn sin_joint(j: usize) -> Expr {
        Expr::factor(Factor::Sin(AngleSum::joint(j)))
    }

    /// Whether the expression is 0.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The number of terms (after simplification).
    pub fn term_count(&self) -> usize {
        self.terms.len()
    }

    /// The terms: each product of factors with its coefficient.
    pub fn terms(&self) -> impl Iterator<Item = (&[Factor], f64)> {
        self.terms.iter().map(|(m, c)| (m.as_slice(), *c))
    }

    fn add_term(&mut self, monomial: Monomial, c: f64) {
        if c == 0.0 {
            return;
        }
        let entry = self.terms.entry(monomial).or_insert(0.0);
        *entry += c;
    }

    /// `self + other`.
    pub fn plus(&self, other: &Expr) -> Expr {
        let mut out = self.clone();
        for (m, c) in &other.terms {
            out.add_term(m.clone(), *c);
        }
        out.drop_zeros(0.0);
        out
    }

    /// `k · self`.
    pub fn scaled(&self, k: f64) -> Expr {
        if k == 0.0 {
            return Expr::default();
        }
        Expr {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), c * k)).collect(),
        }
    }

    /// `self · other`, distributed term by term.
    pub fn times(&self, other: &Expr) -> Expr {
        let mut out = Expr::default();
        for (ma, ca) in &self.terms {
            for (mb, cb) in &other.terms {
                let mut m: Monomial = ma.iter().chain(mb).cloned().collect();
                m.sort();
                out.add_term(m, ca * cb);
            }
        }
        out.drop_zeros(0.0);
        out
    }

    /// Removes the terms whose coefficient is at most `tol` in size.
    fn drop_zeros(&mut self, tol: f64) {
        self.terms.retain(|_, c| c.abs() > tol);
    }

    /// The value at `q` (joint variables; missing entries count as 0).
    pub fn eval(&self, q: &[f64]) -> f64 {
        self.terms
            .iter()
            .map(|(m, c)| c * m.iter().map(|f| f.eval(q)).product::<f64>())
            .sum()
    }

    /// The joints (from 0) the expression depends on, as a bit set: bit j is joint j
    /// (joints from 64 on are not represented).
    pub fn joint_bits(&self) -> u64 {
        self.terms
            .keys()
            .flatten()
            .fold(0, |bits, f| bits | f.joint_bits())
    }

    /// Whether the expression depends on joint `j` (counted from 0, as q's index).
    pub fn depends_on(&self, j: usize) -> bool {
        self.joint_bits() & bit(j) != 0
    }

    /// The joints (from 0) the expression depends on, in order.
    pub fn joints(&self) -> Vec<usize> {
        let bits = self.joint_bits();
        (0..64).filter(|&j| bits & bit(j) != 0).collect()
    }

    /// Applies the simplification rules of docs/kinematics.md §13.2 until none applies:
    /// coefficients of at most `zero` in size are dropped, and two terms `k·M·f·g` and
    /// `±k·M·f'·g'` that an angle-sum identity joins become one:
    ///
    /// ```text
    /// c_a c_b − s_a s_b = c_(a+b)     c_a c_b + s_a s_b = c_(a−b)
    /// s_a c_b + c_a s_b = s_(a+b)     s_a c_b − c_a s_b = s_(a−b)
    /// ```
    pub fn simplify(&mut self, zero: f64) {
        self.drop_zeros(zero);
        while let Some((first, second, monomial, c)) = self.find_pair() {
            self.terms.remove(&first);
            self.terms.remove(&second);
            self.add_term(monomial, c);
            self.drop_zeros(zero);
        }
    }

    /// The first pair of terms an angle-sum identity joins: the two monomials to remove,
    /// and the monomial and coefficient to add.
    fn find_pair(&self) -> Option<(Monomial, Monomial, Monomial, f64)> {
        for (m, &k) in &self.terms {
            for i in 0..m.len() {
                for j in 0..m.len() {
                    if i == j {
                        continue;
                    }
                    let found = match (&m[i], &m[j]) {
                        // cos a · cos b with sin a · sin b (each pair once: i < j).
                        (Factor::Cos(a), Factor::Cos(b)) if i < j => {
                            let partner =
                                replaced(m, i, j, Factor::Sin(a.clone()), Factor::Sin(b.clone()));
                            self.terms.get(&partner).and_then(|&k2| {
                                // k c_a c_b + k2 s_a s_b: k2 = −k gives c(a+b), k2 = k c(a−b).
                                let sign = pair_sign(k, k2)?;
                                Some((partner, trig(true, a.combined(b, -sign))))
                            })
                        }
                        // sin a · cos b with cos a · sin b.
                        (Factor::Sin(a), Factor::Cos(b)) => {
                            let partner =
                                replaced(m, i, j, Factor::Cos(a.clone()), Factor::Sin(b.clone()));
                            self.terms.get(&partner).and_then(|&k2| {
                                // k s_a c_b + k2 c_a s_b: k2 = k gives s(a+b), k2 = −k s(a−b).
                                let sign = pair_sign(k, k2)?;
                                Some((partner, trig(false, a.combined(b, sign))))
                            })
                        }
                        _ => None,
                    };
                    if let Some((partner, (sign, factor))) = found {
                        if &partner == m {
                            // s_a c_a is its own partner: one term, not a pair.
                            continue;
                        }
                        let mut rest: Monomial = m
                            .iter()
                            .enumerate()
                            .filter(|&(n, _)| n != i && n != j)
                            .map(|(_, f)| f.clone())
                            .collect();
                        rest.extend(factor);
                        rest.sort();
                        return Some((m.clone(), partner, rest, k * sign));
                    }
                }
            }
        }
        None
    }

    /// The expression as plain text (`c1(222.1 c2 + 136.2 c23)`), whatever its length.
    pub fn plain(&self) -> String {
        self.render(Style::Plain)
    }

    /// The expression as LaTeX (`c_{1}\left(222.1 s_{2} + …\right)`), whatever its length.
    pub fn latex(&self) -> String {
        self.render(Style::Latex)
    }

    /// Plain text and LaTeX, or [`EntryText::TooLong`] above [`MAX_SHOWN_TERMS`] terms.
    pub fn text(&self) -> EntryText {
        if self.term_count() > MAX_SHOWN_TERMS {
            EntryText::TooLong {
                terms: self.term_count(),
            }
        } else {
            EntryText::Shown {
                plain: self.plain(),
                latex: self.latex(),
            }
        }
    }

    fn render(&self, style: Style) -> String {
        if self.terms.is_empty() {
            return "0".to_string();
        }
        // The factors every term shares (with multiplicity) are written once in front.
        let mut common: Monomial = self.terms.keys().next().cloned().unwrap_or_default();
        for m in self.terms.keys().skip(1) {
            common = intersect(&common, m);
        }
        if self.terms.len() < 2 {
            common.clear();
        }
        let mut inner: Vec<(Monomial, f64)> = self
            .terms
            .iter()
            .map(|(m, c)| (remove_factors(m, &common), *c))
            .collect();
        inner.sort_by_key(|a| display_order(&a.0));
        if common.is_empty() {
            return sum_text(&inner, style);
        }
        let negative = inner.iter().all(|(_, c)| *c < 0.0);
        if negative {
            for (_, c) in inner.iter_mut() {
                *c = -*c;
            }
        }
        let mut out = String::new();
        if negative {
            out.push('-');
        }
        out.push_str(&product_text(&common, style));
        match style {
            Style::Plain => {
                let _ = write!(out, "({})", sum_text(&inner, style));
            }
            Style::Latex => {
                let _ = write!(out, "\\left({}\\right)", sum_text(&inner, style));
            }
        }
        out
    }
}

/// How [`Expr::simplify`] pairs two coefficients: +1 when equal, −1 when opposite.
fn pair_sign(k: f64, k2: f64) -> Option<i32> {
    let tol = PAIR_TOLERANCE * k.abs().max(k2.abs());
    if (k - k2).abs() <= tol {
        Some(1)
    } else if (k + k2).abs() <= tol {
        Some(-1)
    } else {
        None
    }
}

/// `m` with factors i and j replaced, sorted.
fn replaced(m: &Monomial, i: usize, j: usize, fi: Factor, fj: Factor) -> Monomial {
    let mut out = m.clone();
    out[i] = fi;
    out[j] = fj;
    out.sort();
    out
}

/// The common factors of two sorted monomials, with multiplicity.
fn intersect(a: &Monomial, b: &Monomial) -> Monomial {
    let mut rest = b.clone();
    let mut out = Vec::new();
    for f in a {
        if let Some(pos) = rest.iter().position(|g| g == f) {
            rest.remove(pos);
            out.push(f.clone());
        }
    }
    out
}

/// `m` without one copy of each factor in `common`.
fn remove_factors(m: &Monomial, common: &Monomial) -> Monomial {
    let mut out = m.clone();
    for f in common {
        if let Some(pos) = out.iter().position(|g| g == f) {
            out.remove(pos);
        }
    }
    out
}

/// Factors in display order (by first joint, then cos, sin, variable).
fn display_sorted(m: &[Factor]) -> Vec<&Factor> {
    let mut v: Vec<&Factor> = m.iter().collect();
    v.sort_by_key(|f| f.display_key());
    v
}

/// A term's place in a sum: constants first, then by the factors' joints.
fn display_order(m: &[Factor]) -> Vec<(Vec<(usize, i32)>, u8)> {
    display_sorted(m)
        .into_iter()
        .map(|f| f.display_key())
        .collect()
}

#[derive(Debug, Clone, Copy)]
enum Style {
    Plain,
    Latex,
}

fn product_text(m: &[Factor], style: Style) -> String {
    display_sorted(m)
        .into_iter()
        .map(|f| match style {
            Style::Plain => f.plain(),
            Style::Latex => f.latex(),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A sum of terms: `222.1 c2 + 136.2 c23`, `-s1`, `100.9 + 222.1 s2`.
fn sum_text(terms: &[(Monomial, f64)], style: Style) -> String {
    let mut out = String::new();
    for (n, (m, c)) in terms.iter().enumerate() {
        let sign = if *c < 0.0 { "-" } else { "+" };
        if n == 0 {
            if *c < 0.0 {
                out.push('-');
            }
        } else {
            let _ = write!(out, " {sign} ");
        }
        let magnitude = c.abs();
        let factors = product_text(m, style);
        if m.is_empty() {
            out.push_str(&number(magnitude));
        } else if is_one(magnitude) {
            out.push_str(&factors);
        } else {
            let _ = write!(out, "{} {}", number(magnitude), factors);
        }
    }
    out
}

fn is_one(x: f64) -> bool {
    (x - 1.0).abs() <= 1e-12
}

/// A coefficient as people write it: integers without a point, others with at most six
/// decimals and no trailing zeros (`222.1`, `0.15005`, `128`).
pub fn number(x: f64) -> String {
    let rounded = x.round();
    if (x - rounded).abs() <= 1e-9 * x.abs().max(1.0) {
        return format!("{}", rounded as i64);
    }
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0');
    s.trim_end_matches('.').to_string()
}

/// How one entry is shown: its text in both forms, or only its size when it is longer
/// than [`MAX_SHOWN_TERMS`] terms.
#[derive(Debug, Clone, PartialEq)]
pub enum EntryText {
    /// The entry as plain text and as LaTeX.
    Shown {
        /// Plain text: `c1(222.1 c2 + 136.2 c23)`.
        plain: String,
        /// LaTeX: `c_{1}\left(222.1 c_{2} + 136.2 c_{23}\right)`.
        latex: String,
    },
    /// Too long to show: the number of terms (the UI says "too long (N terms)").
    TooLong {
        /// The number of terms after simplification.
        terms: usize,
    },
}

/// A symbolic homogeneous transform: 4×4 entries (the last row is always 0 0 0 1).
#[derive(Debug, Clone, PartialEq)]
pub struct SymbolicMatrix {
    /// The entries, `entries[row][column]`.
    pub entries: [[Expr; 4]; 4],
}

impl SymbolicMatrix {
    /// The identity.
    pub fn identity() -> Self {
        SymbolicMatrix {
            entries: std::array::from_fn(|r| {
                std::array::from_fn(|c| Expr::constant(if r == c { 1.0 } else { 0.0 }))
            }),
        }
    }

    /// A constant transform (a robot's base or tool transform), its ±1 and 0 entries
    /// snapped within 1e−12.
    pub fn constant(pose: &IsometryMatrix3<f64>) -> Self {
        let h = pose.to_homogeneous();
        SymbolicMatrix {
            entries: std::array::from_fn(|r| {
                std::array::from_fn(|c| Expr::constant(snap(h[(r, c)])))
            }),
        }
    }

    /// `self · other`, every entry simplified with `zero` (docs/kinematics.md §13.2).
    pub fn times(&self, other: &SymbolicMatrix, zero: f64) -> SymbolicMatrix {
        SymbolicMatrix {
            entries: std::array::from_fn(|r| {
                std::array::from_fn(|c| {
                    let mut sum = Expr::default();
                    for k in 0..4 {
                        sum = sum.plus(&self.entries[r][k].times(&other.entries[k][c]));
                    }
                    sum.simplify(zero);
                    sum
                })
            }),
        }
    }

    /// The numeric matrix at `q`.
    pub fn eval(&self, q: &[f64]) -> Matrix4<f64> {
        Matrix4::from_fn(|r, c| self.entries[r][c].eval(q))
    }

    /// The joints (from 0) any entry depends on, as a bit set.
    pub fn joint_bits(&self) -> u64 {
        self.entries
            .iter()
            .flatten()
            .fold(0, |bits, e| bits | e.joint_bits())
    }

    /// The largest term count of any entry.
    pub fn max_terms(&self) -> usize {
        self.entries
            .iter()
            .flatten()
            .map(Expr::term_count)
            .max()
            .unwrap_or(0)
    }

    /// The matrix as LaTeX (`\begin{bmatrix} … \end{bmatrix}`); an entry longer than
    /// [`MAX_SHOWN_TERMS`] is written in full all the same.
    pub fn latex(&self) -> String {
        let rows: Vec<String> = self
            .entries
            .iter()
            .map(|row| row.iter().map(Expr::latex).collect::<Vec<_>>().join(" & "))
            .collect();
        format!(
            "\\begin{{bmatrix}} {} \\end{{bmatrix}}",
            rows.join(" \\\\ ")
        )
    }
}

/// 0 and ±1 within 1e−12 made exact (a constant's rounding residue, as cos 90°).
fn snap(x: f64) -> f64 {
    for exact in [0.0, 1.0, -1.0] {
        if (x - exact).abs() <= 1e-12 {
            return exact;
        }
    }
    x
}

/// sin and cos of a constant angle, exact at multiples of 90° (within 1e−9 rad).
pub fn exact_sin_cos(x: f64) -> (f64, f64) {
    let quarter = (x / std::f64::consts::FRAC_PI_2).round();
    if (x - quarter * std::f64::consts::FRAC_PI_2).abs() <= 1e-9 {
        match (quarter as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        x.sin_cos()
    }
}

/// Every symbolic matrix of a robot (docs/kinematics.md §13).
#[derive(Debug, Clone, PartialEq)]
pub struct SymbolicChain {
    /// A_i for i = 1..n in the robot's convention, constants and offsets substituted.
    pub link_transforms: Vec<SymbolicMatrix>,
    /// T_0i for i = 1..n, the robot's base transform included (as
    /// [`ForwardKinematics::base_from_frames`](super::fk::ForwardKinematics)).
    pub base_from_frames: Vec<SymbolicMatrix>,
    /// The tool pose T_0n · flange_from_tool.
    pub base_from_tool: SymbolicMatrix,
}

/// The symbolic A_i of joint `j` (from 0) of `robot`: the row's constants substituted,
/// its offset folded into the coefficients (θ = θ⁰ + q: cos θ = cos θ⁰ c − sin θ⁰ s), a
/// prismatic joint's d = d⁰ + d_j.
pub fn symbolic_link_transform(robot: &Robot, j: usize) -> Option<SymbolicMatrix> {
    let joint = robot.joints.get(j)?;
    let row = &joint.dh;
    let (cos_t, sin_t, d) = match joint.kind {
        JointKind::Revolute => {
            let (s0, c0) = exact_sin_cos(row.theta);
            let (c, s) = (Expr::cos_joint(j), Expr::sin_joint(j));
            (
                c.scaled(c0).plus(&s.scaled(-s0)),
                c.scaled(s0).plus(&s.scaled(c0)),
                Expr::constant(row.d),
            )
        }
        JointKind::Prismatic => {
            let (s0, c0) = exact_sin_cos(row.theta);
            (
                Expr::constant(c0),
                Expr::constant(s0),
                Expr::constant(row.d).plus(&Expr::factor(Factor::Var(j))),
            )
        }
    };
    let (sa, ca) = exact_sin_cos(row.alpha);
    let k = Expr::constant;
    let zero = Expr::default;
    let one = || Expr::constant(1.0);
    let entries = match robot.convention {
        Convention::Standard => [
            [
                cos_t.clone(),
                sin_t.scaled(-ca),
                sin_t.scaled(sa),
                cos_t.scaled(row.a),
            ],
            [
                sin_t.clone(),
                cos_t.scaled(ca),
                cos_t.scaled(-sa),
                sin_t.scaled(row.a),
            ],
            [zero(), k(sa), k(ca), d],
            [zero(), zero(), zero(), one()],
        ],
        Convention::Modified => [
            [cos_t.clone(), sin_t.scaled(-1.0), zero(), k(row.a)],
            [sin_t.scaled(ca), cos_t.scaled(ca), k(-sa), d.scaled(-sa)],
            [sin_t.scaled(sa), cos_t.scaled(sa), k(ca), d.scaled(ca)],
            [zero(), zero(), zero(), one()],
        ],
    };
    Some(SymbolicMatrix { entries })
}

/// Every A_i, T_0i and the tool pose of `robot`, symbolic and simplified
/// (docs/kinematics.md §13).
pub fn symbolic_chain(robot: &Robot) -> SymbolicChain {
    // Coefficients below this are rounding residue of cancelled terms.
    let zero = 1e-12 * robot.reach().max(1.0);
    let links: Vec<SymbolicMatrix> = (0..robot.dof())
        .filter_map(|j| symbolic_link_transform(robot, j))
        .collect();
    let mut running = SymbolicMatrix::constant(&robot.world_from_base);
    let mut frames = Vec::with_capacity(links.len());
    for a in &links {
        running = running.times(a, zero);
        frames.push(running.clone());
    }
    let tool = running.times(&SymbolicMatrix::constant(&robot.flange_from_tool), zero);
    SymbolicChain {
        link_transforms: links,
        base_from_frames: frames,
        base_from_tool: tool,
    }
}
