//! ArmLab's entry point: a native window (`cargo run`) or the web page (trunk).
fn main() {}
