//! Join codes and tokens: their shape, typed codes normalised, tokens compared.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use armlab_room::{CODE_ALPHABET, is_code, is_token, normalize_code, tokens_equal};

#[test]
fn codes_have_eight_unambiguous_characters() {
    assert!(is_code("ABCD2345"));
    assert!(!is_code("ABCD234"), "seven characters");
    assert!(!is_code("ABCD23450"), "nine characters");
    for ambiguous in [
        "ABCD234O", "ABCD2341", "ABCD234I", "ABCD234L", "ABCD234U", "ABCD2340",
    ] {
        assert!(!is_code(ambiguous), "{ambiguous}");
    }
    assert!(
        !is_code("abcd2345"),
        "lowercase is normalised first, not a code as it is"
    );
    assert_eq!(CODE_ALPHABET.len(), 30);
}

#[test]
fn typed_codes_ignore_case_spaces_and_dashes() {
    assert_eq!(normalize_code("abcd-2345").as_deref(), Some("ABCD2345"));
    assert_eq!(normalize_code(" ab cd 23 45 ").as_deref(), Some("ABCD2345"));
    assert_eq!(normalize_code("abcd-234"), None);
    assert_eq!(normalize_code("ÄBCD2345"), None);
    assert_eq!(normalize_code(&"-".repeat(10_000)), None);
}

#[test]
fn tokens_are_32_lowercase_hex_digits_compared_whole() {
    let token = "0123456789abcdef0123456789abcdef";
    assert!(is_token(token));
    assert!(!is_token(&token.to_uppercase()));
    assert!(!is_token(&token[1..]));
    assert!(tokens_equal(token, token));
    assert!(!tokens_equal(token, "0123456789abcdef0123456789abcdee"));
    assert!(!tokens_equal(token, "1123456789abcdef0123456789abcdef"));
    assert!(!tokens_equal(token, &token[..31]));
    assert!(!tokens_equal("", token));
}
