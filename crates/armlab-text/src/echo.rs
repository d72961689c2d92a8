//! Echoing what a person wrote inside a sentence, kept readable: every message that
//! repeats user text (a field name, a preset id, a link part) or a number (a joint value,
//! a length) goes through [`text`] or [`number`] (or their `Display` wrappers [`Text`]
//! and [`Number`], for [`fill`](super::fill)).
//!
//! - Text: at most [`MAX_ECHO_CHARS`] characters, cut with `…`; control characters (and
//!   the invisible bidirectional overrides that could reorder the sentence) become `□` (a glyph the app's font has).
//! - Numbers: at most 12 significant digits, plain between 10⁻⁴ and 10¹⁵ (`-1.5`,
//!   `2500000000`), scientific beyond (`1e300`, `1.7e308`, `2.5e-7`), `inf`, `-inf`,
//!   `NaN`. Never the 301 digits of `format!("{}", 1e300)`.

/// The most characters of a person's text a message repeats.
pub const MAX_ECHO_CHARS: usize = 40;

/// Significant digits of an echoed number.
const SIGNIFICANT_DIGITS: usize = 12;

/// Decimal exponents (of the rounded value) written in plain form: 10⁻⁴ ≤ |v| < 10¹⁵.
const SMALLEST_PLAIN_EXPONENT: i32 = -4;
/// The first decimal exponent written in scientific form.
const LARGEST_PLAIN_EXPONENT: i32 = 15;

/// Whether `c` would not show as itself in a sentence: a control character, or a
/// bidirectional formatting character (U+200E/F, U+202A–U+202E, U+2066–U+2069) that
/// reorders the text around it.
fn is_hidden(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200E}' | '\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
}

/// `s` as a sentence may repeat it: control and bidirectional formatting characters
/// replaced by `□`, and cut to [`MAX_ECHO_CHARS`] characters (the last one `…`) when
/// longer.
///
/// ```
/// use armlab_text::echo;
/// assert_eq!(echo::text("ur10"), "ur10");
/// assert_eq!(echo::text("a\nb"), "a□b");
/// assert_eq!(echo::text(&"x".repeat(1000)).chars().count(), 40);
/// ```
pub fn text(s: &str) -> String {
    text_within(s, MAX_ECHO_CHARS)
}

/// [`text`] with another length limit (at least 2 characters).
pub fn text_within(s: &str, max_chars: usize) -> String {
    let max_chars = max_chars.max(2);
    let mut out = String::with_capacity(s.len().min(4 * max_chars));
    for (i, c) in s.chars().enumerate() {
        if i + 1 == max_chars && s.chars().nth(max_chars).is_some() {
            out.push('…');
            break;
        }
        out.push(if is_hidden(c) { '\u{25A1}' } else { c });
    }
    out
}

/// `v` written short: 12 significant digits at most, trailing zeros dropped, plain for
/// magnitudes from 10⁻⁴ to below 10¹⁵, scientific (`1e300`) beyond; `-0` as `0`.
///
/// ```
/// use armlab_text::echo;
/// assert_eq!(echo::number(1e300), "1e300");
/// assert_eq!(echo::number(-1.5), "-1.5");
/// assert_eq!(echo::number(2.5e9), "2500000000");
/// assert_eq!(echo::number(10.000000000000002), "10");
/// ```
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    if v == 0.0 {
        return "0".into();
    }
    // Round to the significant digits first: the rounded value's exponent decides the form.
    let scientific = format!("{v:.prec$e}", prec = SIGNIFICANT_DIGITS - 1);
    let (mantissa, exponent) = scientific
        .split_once('e')
        .unwrap_or((scientific.as_str(), "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    if (SMALLEST_PLAIN_EXPONENT..LARGEST_PLAIN_EXPONENT).contains(&exponent) {
        let decimals = (SIGNIFICANT_DIGITS as i32 - 1 - exponent).max(0) as usize;
        let plain = format!("{v:.decimals$}");
        return trim_zeros(&plain).into();
    }
    format!("{}e{exponent}", trim_zeros(mantissa))
}

/// Removes trailing zeros after a decimal point, and the point if nothing follows it.
fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// A person's text for [`fill`](super::fill), written as [`text`] writes it.
#[derive(Debug, Clone, Copy)]
pub struct Text<'a>(pub &'a str);

impl std::fmt::Display for Text<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&text(self.0))
    }
}

/// A number for [`fill`](super::fill), written as [`number`] writes it.
#[derive(Debug, Clone, Copy)]
pub struct Number(pub f64);

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&number(self.0))
    }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn long_text_is_cut_to_forty_characters_with_an_ellipsis() {
        let long = "é".repeat(1000);
        let out = text(&long);
        assert_eq!(out.chars().count(), MAX_ECHO_CHARS);
        assert!(out.ends_with('…'));
        assert_eq!(out.chars().filter(|c| *c == 'é').count(), 39);
        // Exactly forty characters are kept whole.
        let forty = "y".repeat(40);
        assert_eq!(text(&forty), forty);
        let forty_one = "y".repeat(41);
        assert_eq!(text(&forty_one), format!("{}…", "y".repeat(39)));
    }

    #[test]
    fn control_and_bidi_characters_do_not_reach_the_sentence() {
        assert_eq!(text("a\u{0}b\tc\u{1b}[31m"), "a□b□c□[31m");
        assert_eq!(text("x\u{202E}gnp.exe"), "x□gnp.exe");
        assert_eq!(text("\r\n"), "□□");
    }

    #[test]
    fn numbers_are_short() {
        let cases = [
            (1e300, "1e300"),
            (1.7e308, "1.7e308"),
            (-1.7e308, "-1.7e308"),
            (f64::MAX, "1.79769313486e308"),
            (5e-324, "4.94065645841e-324"),
            (2.5e-7, "2.5e-7"),
            (0.0001, "0.0001"),
            (1e15, "1e15"),
            (999_999_999_999_999.0, "1e15"),
            (123_456_789_012.0, "123456789012"),
            (0.1 + 0.2, "0.3"),
            (-1.5, "-1.5"),
            (-0.0, "0"),
            (0.0, "0"),
            (2.5e9, "2500000000"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
            (f64::NAN, "NaN"),
            (3600.0, "3600"),
            (57.29577951308232, "57.2957795131"),
        ];
        for (v, want) in cases {
            assert_eq!(number(v), want, "{v:e}");
            assert!(number(v).len() <= 20, "{v:e}");
        }
    }
}
