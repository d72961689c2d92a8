//! Benchmarks, outside the clock-free core: the IK benchmark protocol and its JSON report
//! ([`ik`]), the workspace sampling and branch-count reports ([`workspace`]), the fuzzing
//! generator ([`fuzz`]), and the one statistics helper every benchmark uses ([`stats`]). The clock is
//! the caller's (`Instant` in the native binaries, `performance.now()` through the JS
//! API), passed in as `now`.
//!
//! The crate has no GUI or web dependency (but `framebench`, feature `frame`); the
//! page never calls it, so it is not in the page's wasm.

pub mod fuzz;
pub mod ik;
pub mod stats;
pub mod workspace;
