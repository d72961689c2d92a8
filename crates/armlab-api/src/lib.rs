//! The JSON API over the core: JSON text in, JSON text out. The `js` feature exposes
//! these functions to JavaScript through wasm-bindgen (see `js.rs` and docs/js-api.md); they
//! are plain Rust here so that native tests cover them too.
//!
//! Every request names a robot — a preset id (`"ur10"`) or a whole robot file object —
//! and a joint vector `q` in the core's units (radians, the robot's length unit).//!
//! The code is split by role: reading requests (`request`, and an `ik` request's own
//! fields in `ik_request`), writing answers (`answer`), and one module per group of
//! verbs (`robots`, `forward`, `jacobians`, `inverse`); this file holds the error and
//! re-exports the verbs.

mod answer;
mod forward;
mod ik_request;
mod inverse;
mod jacobians;
mod request;
mod robots;

use thiserror::Error;

use armlab_core::{IkError, RobotError};
use armlab_text::{Lang, Sentence};

pub use answer::{orientation_json, pose_rows};
pub use forward::fk;
pub use ik_request::{
    MAX_ITERATIONS, MAX_JOINT_TRANSFORMS, MAX_RESTARTS, MAX_TRACE_NUMBERS, iteration_cap,
};
pub use inverse::ik;
pub use jacobians::jacobian;
pub use robots::{presets, robot};

/// What can go wrong with an API request. `Display` is the English sentence the caller
/// reads (the JSON API keeps to English).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ApiError {
    /// The request is not JSON or lacks a field.
    #[error("Bad request: {0}")]
    Request(String),
    /// The robot or the joint vector is invalid.
    #[error("{}", .0.sentence(Lang::En))]
    Robot(#[from] RobotError),
    /// The IK could not run (no closed form for this robot, a target that is not finite,
    /// …); the core's own error, variant and all.
    #[error("{}", .0.sentence(Lang::En))]
    Ik(IkError),
}

impl From<IkError> for ApiError {
    /// A robot error inside an IK error is the robot's; the rest stay IK errors.
    fn from(e: IkError) -> Self {
        match e {
            IkError::Robot(r) => ApiError::Robot(r),
            other => ApiError::Ik(other),
        }
    }
}
