//! Join codes and lecturer tokens: their shape, and the constant-time comparison of
//! tokens. Generating them (from the operating system's random source) is the server's.

/// The characters of a join code: digits and capitals without those read alike
/// (0/O, 1/I/L) or spelled alike aloud (U/V): 30 characters.
pub const CODE_ALPHABET: &[u8; 30] = b"23456789ABCDEFGHJKMNPQRSTVWXYZ";
/// The characters in a join code: 30⁸ ≈ 6.6 × 10¹¹ codes, which join-attempt rate
/// limits keep out of reach of guessing.
pub const CODE_LEN: usize = 8;
/// The lowercase hex digits of a lecturer token (128 bits).
pub const TOKEN_LEN: usize = 32;

/// Whether `code` is a join code's shape: [`CODE_LEN`] characters of [`CODE_ALPHABET`].
pub fn is_code(code: &str) -> bool {
    code.len() == CODE_LEN && code.bytes().all(|b| CODE_ALPHABET.contains(&b))
}

/// A typed code as a join code: capitals, spaces and dashes dropped (`abcd-efgh` →
/// `ABCDEFGH`); `None` when the result is not a code's shape.
pub fn normalize_code(typed: &str) -> Option<String> {
    if typed.len() > 4 * CODE_LEN {
        return None;
    }
    let code: String = typed
        .chars()
        .filter(|c| !matches!(c, ' ' | '-'))
        .map(|c| c.to_ascii_uppercase())
        .collect();
    is_code(&code).then_some(code)
}

/// Whether `token` is a lecturer token's shape: [`TOKEN_LEN`] lowercase hex digits.
pub fn is_token(token: &str) -> bool {
    token.len() == TOKEN_LEN
        && token
            .bytes()
            .all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'))
}

/// Whether two tokens are equal, in time that depends on their lengths only (never on
/// where they first differ), so a guesser learns nothing from the answer's delay.
pub fn tokens_equal(a: &str, b: &str) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let diff = a
        .bytes()
        .zip(b.bytes())
        .fold(0u8, |acc, (x, y)| acc | (x ^ y));
    std::hint::black_box(diff) == 0
}
