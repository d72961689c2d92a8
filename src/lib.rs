//! ArmLab's app: the eframe/egui application ([`app`]) and its wgpu renderer
//! ([`render`]), natively and in the browser.
//!
//! The libraries it builds on are crates of their own (docs/ARCHITECTURE.md):
//! `armlab_core` (the kinematics), `armlab_text` (English and Finnish sentences),
//! `armlab_session` (the session and its link format).

pub mod app;
pub mod render;
