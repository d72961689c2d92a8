//! The one number formatter of the app: links, DH cells, labels and measures all write
//! numbers through [`number`], so a value reads the same everywhere and no text grows to
//! dozens of digits.

use armlab_core::ZyxEuler;
use nalgebra::IsometryMatrix3;

/// Magnitudes at or above this are written in scientific form (`3.2e8`).
const LARGE: f64 = 1e6;
/// Non-zero magnitudes below this are written in scientific form (`2.5e-7`).
const SMALL: f64 = 1e-4;
/// The accuracy of the app's computations: a few thousand times f64's ε (2.2e-16), what a
/// chain of a few dozen products and sums on values near 1 keeps. A computed magnitude
/// below it is round-off (a velocity's 2.6e-14 mm/s, a singular σ of 4e-17), and one
/// above its reciprocal is the reciprocal of round-off (a condition number of 5e16).
pub const ROUND_OFF: f64 = 1e-12;

/// `v` with at most `decimals` decimals and no trailing zeros (`1.5`, `100.9`, `-180`);
/// very large and very small magnitudes in scientific form with at most `decimals`
/// digits after the mantissa's point (`3.2e8`, `1e-9`), `NaN` for NaN. Magnitudes below
/// [`ROUND_OFF`] are `0`, and those above its reciprocal (and the infinite) `∞`/`-∞`:
/// digits there are the computation's noise. `-0` is written `0`. Other text parses back
/// with `str::parse::<f64>` to `v` rounded to what is shown.
pub fn number(v: f64, decimals: usize) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    let magnitude = v.abs();
    if magnitude > 1.0 / ROUND_OFF {
        return if v > 0.0 { "∞".into() } else { "-∞".into() };
    }
    if magnitude < ROUND_OFF {
        return "0".into();
    }
    if magnitude >= LARGE || (magnitude > 0.0 && magnitude < SMALL) {
        return scientific(v, decimals);
    }
    let text = format!("{v:.decimals$}");
    let trimmed = trim_zeros(&text);
    if trimmed == "-0" {
        "0".into()
    } else {
        trimmed.into()
    }
}

/// Decimals of the numbers a link writes (1e-6 rad, 1e-6 of a length unit).
pub const LINK_DECIMALS: usize = 6;

/// A pose's six numbers `[x, y, z, α, β, γ]` as a link writes them: each rounded to the
/// link's decimals (and read back as the link's text reads). A pose made of such numbers
/// gives them back exactly, so the stored session keeps poses as links do.
pub fn pose_as_linked(pose: &IsometryMatrix3<f64>) -> [f64; 6] {
    target_to_array(pose).map(|v| number(v, LINK_DECIMALS).parse().unwrap_or(v))
}

/// An error or a residual, which spans many orders of magnitude: from 0.01 up as
/// [`number`] with 3 decimals (`450.123`, `0.012`), below that in scientific form with
/// at most `decimals` decimals in the mantissa (`4.5e-3`, `1.976e-8`), where 3 decimals
/// would show 0; zero and round-off (below [`ROUND_OFF`]) are `0` (not `0.000e0`).
pub fn error_value(v: f64, decimals: usize) -> String {
    if v.abs() >= ROUND_OFF && v.abs() < 0.01 {
        scientific(v, decimals)
    } else {
        number(v, 3)
    }
}

/// `v` in scientific form with at most `decimals` decimals in the mantissa and no trailing
/// zeros (`1.976e-8`, `4e-4`, `2.5e3`); zero is `0` (not `0.000e0`), and the non-finite as
/// Rust writes them.
fn scientific(v: f64, decimals: usize) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let text = format!("{v:.decimals$e}");
    match text.split_once('e') {
        Some((mantissa, exponent)) => format!("{}e{exponent}", trim_zeros(mantissa)),
        None => text,
    }
}

/// `v` with exactly `decimals` decimals, for columns of numbers that line up (matrices,
/// angles): `0.500`, `-1.000`. A value that rounds to zero is written without its sign
/// (`0.000`, not `-0.000`: a rotation's entries and Euler angles are often −10⁻¹⁷).
pub fn fixed(v: f64, decimals: usize) -> String {
    let text = format!("{v:.decimals$}");
    match text.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_owned(),
        _ => text,
    }
}

/// Removes trailing zeros after a decimal point, and the point if nothing follows it.
fn trim_zeros(text: &str) -> &str {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        text
    }
}

/// Numbers joined with commas (a link's `q=` or `target=`).
pub fn number_list(values: &[f64], decimals: usize) -> String {
    values
        .iter()
        .map(|v| number(*v, decimals))
        .collect::<Vec<_>>()
        .join(",")
}

/// A target pose from `[x, y, z, α, β, γ]` (Z-Y-X Euler angles, radians).
pub fn target_from_array(t: &[f64; 6]) -> IsometryMatrix3<f64> {
    let r = ZyxEuler {
        alpha: t[3],
        beta: t[4],
        gamma: t[5],
        degenerate: false,
    }
    .to_rotation();
    IsometryMatrix3::from_parts(
        nalgebra::Translation3::new(t[0], t[1], t[2]),
        nalgebra::Rotation3::from_matrix_unchecked(r),
    )
}

/// `[x, y, z, α, β, γ]` of a pose.
pub fn target_to_array(pose: &IsometryMatrix3<f64>) -> [f64; 6] {
    let e = ZyxEuler::from_rotation(pose.rotation.matrix());
    let p = pose.translation.vector;
    [p.x, p.y, p.z, e.alpha, e.beta, e.gamma]
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::{error_value, fixed, number, scientific};
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn plain_numbers_lose_trailing_zeros_only() {
        assert_eq!(number(100.9, 6), "100.9");
        assert_eq!(number(-180.0, 6), "-180");
        assert_eq!(number(1184.5, 4), "1184.5");
        assert_eq!(number(0.0, 3), "0");
        assert_eq!(number(-0.0000001, 3), "-1e-7");
        assert_eq!(number(-0.0004, 3), "0");
        assert_eq!(number(250.0, 0), "250");
    }

    #[test]
    fn errors_are_scientific_and_zero_is_zero() {
        assert_eq!(scientific(0.0, 3), "0");
        assert_eq!(scientific(-0.0, 3), "0");
        assert_eq!(scientific(1.9764e-8, 3), "1.976e-8");
        assert_eq!(scientific(0.0004, 3), "4e-4");
        assert_eq!(scientific(-2500.0, 1), "-2.5e3");
        assert_eq!(scientific(1.0, 3), "1e0");
        // Errors: tiny ones scientific, the rest plain (a 450 mm error read "4.5e2 mm").
        assert_eq!(error_value(0.0, 3), "0");
        assert_eq!(error_value(1.9764e-8, 3), "1.976e-8");
        assert_eq!(error_value(0.0045, 1), "4.5e-3");
        assert_eq!(error_value(0.0123, 3), "0.012");
        assert_eq!(error_value(450.1234, 3), "450.123");
        assert_eq!(error_value(2.5e7, 3), "2.5e7");
    }

    #[test]
    fn fixed_decimals_never_show_a_negative_zero() {
        assert_eq!(fixed(-1e-17, 3), "0.000");
        assert_eq!(fixed(-0.0, 3), "0.000");
        assert_eq!(fixed(-0.0004, 3), "0.000");
        assert_eq!(fixed(-0.0005001, 3), "-0.001");
        assert_eq!(fixed(-1.0, 3), "-1.000");
        assert_eq!(fixed(std::f64::consts::FRAC_1_SQRT_2, 5), "0.70711");
        assert_eq!(fixed(-1e-9, 0), "0");
        assert_eq!(fixed(-2.0, 0), "-2");
        assert_eq!(fixed(f64::NEG_INFINITY, 2), "-inf");
    }

    #[test]
    fn very_large_and_small_numbers_are_scientific() {
        assert_eq!(number(3.2e8, 3), "3.2e8");
        assert_eq!(number(4.98e11, 2), "4.98e11", "a condition number");
        assert_eq!(number(2.5e-7, 6), "2.5e-7");
        assert_eq!(number(1.5e-12, 6), "1.5e-12");
        assert_eq!(number(f64::INFINITY, 2), "∞");
        assert_eq!(number(f64::NAN, 2), "NaN");
    }

    #[test]
    fn round_off_reads_as_zero_and_its_reciprocal_as_infinity() {
        // A UR10 tool velocity, and the measures at its wrist singularity.
        let v = [-209.06, 2.6e-14, 425.18].map(|v| number(v, 2));
        assert_eq!(v, ["-209.06", "0", "425.18"]);
        let w = [0.0, -0.62, 3.796e-17].map(|v| number(v, 3));
        assert_eq!(w, ["0", "-0.62", "0"]);
        assert_eq!(number(4.0565e-17, 4), "0", "σ_min");
        assert_eq!(number(-4.0565e-17, 4), "0");
        assert_eq!(number(4.98e16, 2), "∞", "its condition number");
        assert_eq!(number(-4.98e16, 2), "-∞");
        assert_eq!(number(1.234_567_890_123_456_7e33, 2), "∞");
        assert_eq!(number(1e300, 6), "∞");
        assert_eq!(number(0.9e-12, 6), "0");
        assert_eq!(number(1.1e12, 6), "∞");
        assert_eq!(number(0.9e12, 6), "9e11");
        // An orientation error at a reached target.
        assert_eq!(error_value(7.48e-15, 3), "0");
        assert_eq!(error_value(2e-11, 3), "2e-11");
    }

    #[test]
    fn written_numbers_parse_back() {
        for v in [0.1, -2.5e-9, 123_456_789.0, 1e-11, -0.75, 1e6, 999_999.5] {
            let text = number(v, 12);
            let back: f64 = text.parse().expect("parses");
            assert!(
                (back - v).abs() <= 1e-9 * v.abs().max(1e-300),
                "{v} → {text}"
            );
        }
    }
}
