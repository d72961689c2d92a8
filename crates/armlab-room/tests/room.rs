//! The protocol crate's tests as one test binary (one link natively, one wasm-bindgen-test
//! run in Node). Each file is a module named after itself. Cargo.toml sets
//! `autotests = false` and lists this binary; tools/test.sh fails when a test file is in
//! no test binary.

mod decoding;
mod ids;
