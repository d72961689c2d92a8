//! The one number formatter of the app: links, DH cells, labels and measures all write
//! numbers through [`number`], so a value reads the same everywhere and no text grows to
//! dozens of digits.

/// Magnitudes at or above this are written in scientific form (`3.2e8`).
const LARGE: f64 = 1e6;
/// Non-zero magnitudes below this are written in scientific form (`2.5e-7`).
const SMALL: f64 = 1e-4;

/// `v` with at most `decimals` decimals and no trailing zeros (`1.5`, `100.9`, `-180`);
/// very large and very small magnitudes in scientific form with at most `decimals`
/// digits after the mantissa's point (`3.2e8`, `1e-9`), `∞`/`-∞` and `NaN` for the
/// non-finite. `-0` is written `0`. The text parses back with `str::parse::<f64>` to
/// `v` rounded to what is shown.
pub fn number(v: f64, decimals: usize) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "∞".into() } else { "-∞".into() };
    }
    let magnitude = v.abs();
    if magnitude >= LARGE || (magnitude > 0.0 && magnitude < SMALL) {
        let text = format!("{v:.decimals$e}");
        return match text.split_once('e') {
            Some((mantissa, exponent)) => format!("{}e{exponent}", trim_zeros(mantissa)),
            None => text,
        };
    }
    let text = format!("{v:.decimals$}");
    let trimmed = trim_zeros(&text);
    if trimmed == "-0" {
        "0".into()
    } else {
        trimmed.into()
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

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::number;
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
    fn very_large_and_small_numbers_are_scientific() {
        assert_eq!(number(3.2e8, 3), "3.2e8");
        assert_eq!(
            number(1.234_567_890_123_456_7e33, 2),
            "1.23e33",
            "a condition number"
        );
        assert_eq!(number(2.5e-7, 6), "2.5e-7");
        assert_eq!(number(1e300, 6), "1e300");
        assert_eq!(number(f64::INFINITY, 2), "∞");
        assert_eq!(number(f64::NAN, 2), "NaN");
    }

    #[test]
    fn written_numbers_parse_back() {
        for v in [0.1, -2.5e-9, 123_456_789.0, 1e-300, -0.75, 1e6, 999_999.5] {
            let text = number(v, 12);
            let back: f64 = text.parse().expect("parses");
            assert!(
                (back - v).abs() <= 1e-9 * v.abs().max(1e-300),
                "{v} → {text}"
            );
        }
    }
}
