//! The benchmark protocols' tests as one test binary (natively and as wasm in Node). Each
//! file is a module named after itself.

mod bench;
mod fuzz;
mod seed_table;
