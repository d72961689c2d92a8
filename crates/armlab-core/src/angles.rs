//! Joint-angle bookkeeping (docs/kinematics.md §3): wrapping to (−π, π] and keeping an angle as the
//! 2π-equivalent inside a joint's limits nearest the current value.

use std::f64::consts::{PI, TAU};
use std::sync::atomic::{AtomicU64, Ordering};

/// `x` wrapped to the half-open interval (−π, π].
///
/// ```
/// use armlab_core::angles::wrap_to_pi;
/// use std::f64::consts::PI;
/// assert_eq!(wrap_to_pi(-PI), PI);
/// assert!((wrap_to_pi(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
/// ```
pub fn wrap_to_pi(x: f64) -> f64 {
    if x > -PI && x <= PI {
        return x;
    }
    // About one turn off (a difference of two wrapped angles, as in every joint distance):
    // for π ≤ |x| ≤ 4π, x ∓ 2π is exact (Sterbenz: |x| lies within a factor of two of 2π),
    // so it is the number the remainder below gives (at x = −2π, +0 for its −0), without
    // the library's remainder loop: 3–4 % of a closed-form drag step (ikbench).
    if x.abs() <= 4.0 * PI {
        let r = if x > 0.0 { x - TAU } else { x + TAU };
        if r > -PI && r <= PI {
            return r;
        }
    }
    let r = x.rem_euclid(TAU); // [0, 2π)
    if r > PI { r - TAU } else { r }
}

/// [`sin_cos`] of two angles at once: `(sines, cosines)`. The same reduction and
/// polynomials written lane by lane without a branch (the quadrant taken from the rounded
/// value's low bits), so the compiler runs both lanes in one vector register (SSE2, wasm
/// simd128). Angles of 10⁶ or more, or NaN, go through [`sin_cos`] one by one. The same
/// lane code as [`sin_cos`], so equal to it bit for bit.
#[inline]
pub fn sin_cos_2(x: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    if !(x[0].abs() < 1e6 && x[1].abs() < 1e6) {
        let (a, b) = (sin_cos(x[0]), sin_cos(x[1]));
        return ([a.0, b.0], [a.1, b.1]);
    }
    let (a, b) = (sin_cos_lane(x[0]), sin_cos_lane(x[1]));
    ([a.0, b.0], [a.1, b.1])
}

/// [`sin_cos`] for |x| < 10⁶, without a branch: `x = k·π/2 + r`, the kernels on r, and
/// the quadrant from the rounded value's low bits (`t = x·2/π + 1.5·2⁵²` holds k there):
/// odd quadrants swap sin and cos by bit masks, sin is negated in quadrants 2 and 3, cos
/// in 1 and 2. Two calls side by side run in one vector register ([`sin_cos_2`]).
#[inline(always)]
fn sin_cos_lane(x: f64) -> (f64, f64) {
    // 2/π; 1.5·2⁵² (adding and removing it rounds to the nearest integer, no library
    // call); π/2 in three parts (its first 33 bits, the next 33, the rest).
    let c = constant_table!(
        5,
        [
            std::f64::consts::FRAC_2_PI,
            6755399441055744.0,
            1.5707963267341256,
            6.077100506303966e-11,
            2.0222662487959506e-21,
        ]
    );
    let t = x * c(0) + c(1);
    let q = t.to_bits();
    let k = t - c(1);
    let r = ((x - k * c(2)) - k * c(3)) - k * c(4);
    let (ps, pc) = kernels(r);
    let odd = (q & 1).wrapping_neg();
    let (ps, pc) = (ps.to_bits(), pc.to_bits());
    let s = (ps & !odd) | (pc & odd);
    let c = (pc & !odd) | (ps & odd);
    (
        f64::from_bits(s ^ ((q & 2) << 62)),
        f64::from_bits(c ^ ((q.wrapping_add(1) & 2) << 62)),
    )
}

/// atan2(y, x) for the closed forms' hot paths: [`atan2_poly`] in the core's wasm (the JS
/// API), where the library's atan2 is software and the closed forms would spend about a
/// tenth of their time in it; natively the library's (glibc's, with FMA, is as fast there
/// and correctly rounded), and in the page too, which is built for size (the page's
/// budget, docs/benchmarks.md "Page size"; the library's atan2 is in it anyway).
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    if OWN_INVERSE_TRIG {
        atan2_poly(y, x)
    } else {
        y.atan2(x)
    }
}

/// asin(x) for the closed forms: [`asin_poly`] in the core's wasm (the library's asin is
/// software there), the library's asin elsewhere (as for [`atan2`]).
#[inline]
pub fn asin(x: f64) -> f64 {
    if OWN_INVERSE_TRIG {
        asin_poly(x)
    } else {
        x.asin()
    }
}

/// asin(x) = `atan2_poly(x, √((1 − x)(1 + x)))` for |x| ≤ 1 (NaN outside). `1 − x` is
/// exact for |x| ≥ ½ (Sterbenz), so the root keeps its accuracy near ±1, where the
/// angle is least sensitive to it.
pub fn asin_poly(x: f64) -> f64 {
    atan2_poly(x, ((1.0 - x) * (1.0 + x)).sqrt())
}

/// Whether this build is the page's (wasm with the feature `small`, which the app turns on
/// for wasm32): it is built for size (opt-level "z" and a bound on the first load,
/// docs/benchmarks.md), so the core's hot paths keep their
/// smaller forms there ([`atan2`], the solver's sines one by one, its `L·D·Lᵀ` solve, and
/// its loop's functions out of line). Attributes cannot read a `const`: the solver's
/// `#[cfg_attr(not(all(target_arch = "wasm32", feature = "small")), inline(always))]`
/// (`ik::chain`, `ik::numeric`) repeats this condition, and must change with it.
pub(crate) const SIZE_OVER_SPEED: bool = cfg!(all(target_arch = "wasm32", feature = "small"));

/// Whether [`atan2`] and [`asin`] use this module's polynomials: in the core's wasm, where
/// the library's are software; not natively (glibc's are as fast) nor in the page.
const OWN_INVERSE_TRIG: bool = cfg!(target_arch = "wasm32") && !SIZE_OVER_SPEED;

/// Whether the polynomials here read their coefficients from memory ([`InMemory`]): in
/// the core's wasm. V8 (Node, Chrome) builds every f64 constant of wasm code in two
/// instructions (the bits into a general register, then into a vector register) and every
/// f64x2 constant of the paired sines in four, inside the loop that uses it; a load from
/// memory is one (docs/benchmarks.md). Not natively, where constants are memory
/// operands already, nor in the page (built for size).
const CONSTANTS_IN_MEMORY: bool = cfg!(target_arch = "wasm32") && !SIZE_OVER_SPEED;

/// A copy in memory of a table of f64 constants for a hot polynomial, which the compiler
/// cannot fold back into immediates (atomics have interior mutability; a relaxed load is
/// a plain load on wasm32), read where [`CONSTANTS_IN_MEMORY`]; elsewhere the table's
/// `const` itself.
pub(crate) struct InMemory<const N: usize>([AtomicU64; N]);

impl<const N: usize> InMemory<N> {
    /// The copy of `values`.
    pub(crate) const fn new(values: [f64; N]) -> Self {
        let mut memory = [const { AtomicU64::new(0) }; N];
        let mut i = 0;
        while i < N {
            memory[i] = AtomicU64::new(values[i].to_bits());
            i += 1;
        }
        InMemory(memory)
    }

    /// Entry `i` of `values`, the table this is a copy of.
    #[inline(always)]
    pub(crate) fn get(&self, values: &[f64; N], i: usize) -> f64 {
        if CONSTANTS_IN_MEMORY {
            f64::from_bits(self.0[i].load(Ordering::Relaxed))
        } else {
            values[i]
        }
    }
}

/// `constant_table!(N, [v₀, v₁, …])`: a closure `|i| vᵢ` over a table of N f64 constants
/// for a hot polynomial, which reads them from memory where [`CONSTANTS_IN_MEMORY`]
/// ([`InMemory`]) and is the constants themselves elsewhere. One table per use.
macro_rules! constant_table {
    ($n:literal, $values:expr) => {{
        const VALUES: [f64; $n] = $values;
        static MEMORY: $crate::angles::InMemory<$n> = $crate::angles::InMemory::new(VALUES);
        |i: usize| MEMORY.get(&VALUES, i)
    }};
}
pub(crate) use constant_table;

/// atan2(y, x) within 2 ulp of `f64::atan2`, without a library call (see [`atan2`]).
/// Zeros, infinities, NaN and magnitudes beyond 10^±290 go to the library.
///
/// Method (docs/kinematics.md §3): with `m` and `M` the smaller and larger of |x| and |y|,
/// atan(m/M) = atan(c) + atan(u) with c = k/8 the eighth nearest m/M (k counted by
/// comparisons, no division) and u = (m − c·M)/(M + c·m), |u| ≤ 1/16, where the Taylor
/// series to u¹⁵ (evaluated in Estrin's order) is exact to 10⁻¹⁸; then the octant (π/2 − ·, π − ·) and y's sign.
///
/// ```
/// use armlab_core::angles::atan2_poly;
/// assert!((atan2_poly(1.0, -2.0) - 1f64.atan2(-2.0)).abs() < 1e-15);
/// ```
pub fn atan2_poly(y: f64, x: f64) -> f64 {
    /// atan(k/8), k = 0..=8.
    const ATAN_EIGHTHS: [f64; 9] = [
        0.0,
        0.12435499454676144,
        0.24497866312686414,
        0.35877067027057225,
        0.4636476090008061,
        0.5585993153435624,
        0.6435011087932844,
        0.7188299996216245,
        std::f64::consts::FRAC_PI_4,
    ];
    let (ax, ay) = (x.abs(), y.abs());
    let (small, large) = if ay > ax { (ax, ay) } else { (ay, ax) };
    // Also false for NaN and when both are zero.
    if !(large > 1e-290 && large < 1e290) {
        return y.atan2(x);
    }
    // 1, 3, 5, …, 15 (the thresholds 2j − 1), then 1/3, 1/5, …, 1/15 (the series).
    let a = constant_table!(
        15,
        [
            1.0,
            3.0,
            5.0,
            7.0,
            9.0,
            11.0,
            13.0,
            15.0,
            1.0 / 3.0,
            1.0 / 5.0,
            1.0 / 7.0,
            1.0 / 9.0,
            1.0 / 11.0,
            1.0 / 13.0,
            1.0 / 15.0,
        ]
    );
    // k = round(8·small/large), counted: small/large ≥ (2j − 1)/16 for j = 1..=8.
    let s16 = 16.0 * small;
    let mut k = 0usize;
    for j in 0..8 {
        k += usize::from(s16 >= a(j) * large);
    }
    let c = k as f64 * 0.125;
    // c·large and c·small are exact (c has four bits).
    let u = (small - c * large) / (large + c * small);
    // u·(1 − u²/3 + u⁴/5 − … − u¹⁴/15) in Estrin's order: four independent pairs, then
    // two, then one (a quarter of the dependent steps of Horner's order).
    let u2 = u * u;
    let u4 = u2 * u2;
    let u8 = u4 * u4;
    let p01 = 1.0 - u2 * a(8);
    let p23 = a(9) - u2 * a(10);
    let p45 = a(11) - u2 * a(12);
    let p67 = a(13) - u2 * a(14);
    let series = u * ((p01 + u4 * p23) + u8 * (p45 + u4 * p67));
    let mut r = ATAN_EIGHTHS[k] + series;
    if ay > ax {
        r = std::f64::consts::FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = std::f64::consts::PI - r;
    }
    r.copysign(y)
}

/// sin r and cos r for |r| ≤ π/4: the coefficients of sin r (r³ to r¹³) and cos r (r⁴ to
/// r¹⁴) on [−π/4, π/4] are Sun's fdlibm kernels'.
#[inline(always)]
fn kernels(r: f64) -> (f64, f64) {
    let k = constant_table!(
        12,
        [
            -0.16666666666666632,
            0.00833333333332249,
            -0.0001984126982985795,
            2.7557313707070068e-6,
            -2.5050760253406863e-8,
            1.58969099521155e-10,
            0.0416666666666666,
            -0.001388888888887411,
            2.480158728947673e-5,
            -2.7557314351390663e-7,
            2.087572321298175e-9,
            -1.1359647557788195e-11,
        ]
    );
    let z = r * r;
    let s = r + r * z * (k(0) + z * (k(1) + z * (k(2) + z * (k(3) + z * (k(4) + z * k(5))))));
    let c = 1.0 - 0.5 * z
        + z * z * (k(6) + z * (k(7) + z * (k(8) + z * (k(9) + z * (k(10) + z * k(11))))));
    (s, c)
}

/// sin x and cos x together, for forward kinematics' hot loop: one shared argument
/// reduction and two short polynomials instead of two library calls (about twice as fast
/// natively, more on wasm where the library's sin and cos are software). Within 2 ulp of
/// `f64::sin_cos` for |x| < 10⁶; beyond that it calls the library.
///
/// Reduction: `x = k·π/2 + r`, |r| ≤ π/4, with π/2 split in three parts (33 + 33 + 53 bits)
/// so that `k·part` is exact; then the minimax polynomials of degree 13 (sin) and 14 (cos)
/// on [−π/4, π/4] (the coefficients of Sun's fdlibm kernels) and the quadrant's signs.
///
/// ```
/// use armlab_core::angles::sin_cos;
/// let (s, c) = sin_cos(1.0);
/// assert!((s - 1f64.sin()).abs() < 1e-15 && (c - 1f64.cos()).abs() < 1e-15);
/// ```
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.is_nan() || x.abs() >= 1e6 {
        return x.sin_cos(); // huge, infinite or NaN: the library handles it
    }
    sin_cos_lane(x)
}
