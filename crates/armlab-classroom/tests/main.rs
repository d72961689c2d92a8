//! The classroom server's tests as one test binary: each file is a module named after
//! itself. The servers run in this process on port 0; the clients are tokio-tungstenite
//! WebSockets.

mod fuzz;
mod heartbeat;
mod redis;
mod relay;
mod rules;
mod support;
