//! What can be wrong with an IK request, as data, and the check of a target pose that
//! every entry point runs. Apart so that the methods and the solver's interface all
//! depend on it and it on none of them.

use nalgebra::{IsometryMatrix3, Matrix3};

use crate::error::RobotError;

/// What can be wrong with an IK request, as data; `armlab_text` words it for a person.
#[derive(Debug, Clone, PartialEq)]
pub enum IkError {
    /// The seed does not fit the robot.
    Robot(RobotError),
    /// The target pose holds NaN or infinity, or its rotation is not a rotation.
    Target(BadTarget),
    /// A setting is out of range: it must be a positive number.
    Settings {
        /// The setting's name (`position_tolerance`, …).
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The closed form was asked for an arm that has none here.
    NoClosedForm(String),
    /// A setting that takes one of a few values got another (`objective`, `wrap`).
    SettingChoice {
        /// The setting's name.
        name: &'static str,
        /// The value given, as written (JSON text: `"cubed"`, `2`).
        value: String,
        /// The values it takes, comma-separated (`half-squared, squared`).
        allowed: String,
    },
    /// The target lies farther from the base frame's origin than
    /// [`MAX_TARGET_DISTANCE`]: no arm reaches it, and its error would overflow.
    TargetTooFar {
        /// The target's distance from the base frame's origin (robot units).
        distance: f64,
        /// [`MAX_TARGET_DISTANCE`].
        limit: f64,
    },
}

/// The farthest a target may lie from the base frame's origin, in the robot's length unit:
/// a thousand times the longest length a robot file may hold
/// ([`crate::robot::MAX_LENGTH`]), so every arm's reach is far inside it and
/// the squared error of a target at this distance stays finite.
pub const MAX_TARGET_DISTANCE: f64 = 1e9;

/// What is wrong with a target pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BadTarget {
    /// A value is NaN or infinite.
    NotFinite,
    /// The 3×3 part is not orthonormal with determinant +1.
    NotRotation,
}

impl std::fmt::Display for IkError {
    /// What kind of error this is, for logs; `{:?}` shows its data, and a person reads the
    /// sentence the text catalogue makes of it (`armlab_text::Sentence`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("an IK request that cannot run as given")
    }
}

impl std::error::Error for IkError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            IkError::Robot(e) => Some(e),
            _ => None,
        }
    }
}

impl From<RobotError> for IkError {
    fn from(e: RobotError) -> Self {
        IkError::Robot(e)
    }
}

pub(crate) fn check_target(target: &IsometryMatrix3<f64>) -> Result<(), IkError> {
    let t = target.translation.vector;
    let r = target.rotation.matrix();
    if !t.iter().chain(r.iter()).all(|v| v.is_finite()) {
        return Err(IkError::Target(BadTarget::NotFinite));
    }
    let err = (r.transpose() * r - Matrix3::identity()).abs().max();
    if err > 1e-6 || r.determinant() < 0.0 {
        return Err(IkError::Target(BadTarget::NotRotation));
    }
    // Scaled by the largest coordinate: the plain norm of (1e308, 0, 0) overflows.
    let largest = t.abs().max();
    let distance = if largest > 0.0 {
        largest * (t / largest).norm()
    } else {
        0.0
    };
    if distance > MAX_TARGET_DISTANCE {
        return Err(IkError::TargetTooFar {
            distance,
            limit: MAX_TARGET_DISTANCE,
        });
    }
    Ok(())
}
