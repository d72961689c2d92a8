//! The core's tests as one test binary (one link natively, one wasm-bindgen-test run in
//! Node: the wasm runner's start-up per binary is seconds). Each file is a module named
//! after itself, so a test is named `file::test`. Cargo.toml sets `autotests = false` and
//! lists this binary; tools/test.sh fails when a test file is in no test binary, so a new
//! one cannot be left out silently.

mod common;

mod angles;
mod closed_form_branches;
mod closed_form_singular;
mod collision;
mod convention;
mod dh_equivalence;
mod distinct;
mod exercise;
mod home_poses;
mod ik;
mod ik_closed_form;
mod ik_drag;
mod ik_singular;
mod jacobian;
mod motion;
mod orientation;
mod path;
mod redundancy;
mod reference_values;
mod symbolic;
mod workspace;
