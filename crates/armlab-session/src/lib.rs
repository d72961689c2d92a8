//! The link format and what it carries, without any GUI: the session (robot, pose,
//! target, IK mode; [`session`]), the display settings and camera a link may name
//! ([`settings`]) and the one number formatter links and the app write numbers with
//! ([`format`](mod@format)). The app (feature `app`) re-exports these modules as `app::session`,
//! `app::settings` and `app::format`; here they build with the core alone, so the link
//! parser is tested and fuzzed natively and as wasm without eframe.

pub mod error;
pub mod exercise;
pub mod format;
pub mod motion;
pub mod session;
pub mod settings;
pub mod stored;
