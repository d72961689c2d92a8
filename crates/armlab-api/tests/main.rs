//! The JSON API's tests as one test binary (natively and as wasm in Node). Each file is a
//! module named after itself.

#[path = "../../armlab-core/tests/common/mod.rs"]
mod common;

mod ik_api;
mod notebook;
mod robot_files;
mod robustness;
