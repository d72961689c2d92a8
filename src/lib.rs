//! ArmLab: a robot-arm kinematics lab that runs in a browser tab.
//!
//! - [`kinematics`] is the core: robots as DH tables, forward kinematics, Jacobians,
//!   orientation forms. It has no GUI dependency and runs natively and as wasm.
//! - `app` (feature `app`) is the eframe/egui application.
//! - [`api`] is the JSON API over the core (JSON text in and out).
//! - [`link`] is the link format (session, display settings), without the GUI.
//! - [`i18n`] is the one catalogue of user-facing text (English, Finnish).
//! - [`bench`](mod@bench) is the IK benchmark protocol and its statistics, outside the core.
//! - `js` (feature `js`) is the JavaScript API over the core, through wasm-bindgen.

pub mod api;
pub mod bench;
pub mod i18n;
pub mod kinematics;
pub mod link;

#[cfg(feature = "app")]
pub mod app;

#[cfg(feature = "app")]
pub mod render;

#[cfg(feature = "js")]
pub mod js;
