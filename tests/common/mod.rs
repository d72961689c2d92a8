//! Helpers shared by the core's test files (native and wasm).
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
#![allow(dead_code)]

use armlab::kinematics::{Robot, SplitMix64, preset, preset_ids};
use nalgebra::{Matrix3, Vector3};

/// Every preset, loaded.
pub fn all_presets() -> Vec<(String, Robot)> {
    preset_ids()
        .map(|id| (id.to_string(), preset(id).expect("preset loads")))
        .collect()
}

/// The largest absolute entry difference of two 3×3 matrices.
pub fn max_diff3(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).abs().max()
}

/// Asserts two vectors agree within `tol` per component, with a message.
pub fn assert_vec_near(what: &str, got: &Vector3<f64>, want: [f64; 3], tol: f64) {
    let want = Vector3::from(want);
    assert!(
        (got - want).abs().max() <= tol,
        "{what}: got {got:?}, want {want:?} (tolerance {tol})"
    );
}

/// Asserts a rotation matrix equals the rows given, within `tol`.
pub fn assert_rot_near(what: &str, got: &Matrix3<f64>, rows: [[f64; 3]; 3], tol: f64) {
    let want = Matrix3::from_fn(|r, c| rows[r][c]);
    assert!(
        max_diff3(got, &want) <= tol,
        "{what}: got {got}, want {want} (tolerance {tol})"
    );
}

/// A seeded generator, the same on every target.
pub fn rng(seed: u64) -> SplitMix64 {
    SplitMix64::new(seed)
}
