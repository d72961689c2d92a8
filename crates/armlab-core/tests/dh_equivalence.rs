//! docs/kinematics.md §2.4: the UR10's modified table and its standard-DH twin give the same T_06.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::{preset, tool_pose};

#[test]
fn ur10_modified_and_standard_agree_for_1000_random_q() {
    let modified = preset("ur10").unwrap();
    let standard = preset("ur10-standard").unwrap();
    let mut rng = common::rng(10);
    let mut worst: f64 = 0.0;
    for _ in 0..1000 {
        let q = rng.joint_vector(&modified);
        let a = tool_pose(&modified, &q).to_homogeneous();
        let b = tool_pose(&standard, &q).to_homogeneous();
        worst = worst.max((a - b).abs().max());
    }
    assert!(worst <= 1e-9, "largest difference {worst} mm");
}
