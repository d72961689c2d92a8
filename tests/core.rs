//! The core's tests as one test binary (one link natively, one wasm-bindgen-test run in
//! Node: with a binary per file, the wasm runner's start-up per binary would take about a
//! minute of the test command). Each file is a module named after
//! itself, so a test is named `file::test`. Cargo.toml sets `autotests = false` and lists
//! this binary, `ui`, `ui_finnish` and `urdf`; tools/test.sh fails when a file in tests/
//! is in none of them, so a new test file cannot be left out silently.

mod common;

mod angles;
mod bench;
mod closed_form_branches;
mod closed_form_singular;
mod collision;
mod convention;
mod dh_equivalence;
mod distinct;
mod exercise;
mod fuzz;
mod home_poses;
mod ik;
mod ik_api;
mod jacobian;
mod motion;
mod notebook;
mod orientation;
mod path;
mod redundancy;
mod reference_values;
mod robot_files;
mod robustness;
mod seed_table;
mod symbolic;
mod workspace;
