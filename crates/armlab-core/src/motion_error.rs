//! What can be wrong with a motion, profile or path request, as data: which setting and
//! which value. The motion lab, its profiles, paths and keep-out boxes share it.

use super::error::RobotError;
use super::ik::{BadTarget, IkError};

/// A setting of the motion lab, for error sentences.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Setting {
    /// The proportional gain K of velocity control (1/s).
    Gain,
    /// Kp of PD/PID.
    Kp,
    /// Ki of PID.
    Ki,
    /// Kd of PD/PID.
    Kd,
    /// The on/off controller's dead band.
    DeadBand,
    /// The time scale (simulated seconds per real second).
    TimeScale,
    /// The time passed to [`MotionSim::advance`](crate::motion::MotionSim::advance).
    FrameTime,
    /// The velocity servo's time constant τ.
    TimeConstant,
    /// The joint's inertia I.
    Inertia,
    /// The joint's viscous friction b.
    Friction,
    /// The constant load torque L.
    Load,
    /// A joint's speed limit.
    MaxSpeed,
    /// A joint's acceleration limit.
    MaxAcceleration,
    /// The goal value of joint N (1-based).
    Goal(usize),
    /// Waypoint N (1-based) of a path.
    Waypoint(usize),
    /// The number of steps of a path.
    PathSteps,
    /// The record's length or decimation.
    RecordLength,
    /// Keep-out box N (1-based).
    KeepOut(usize),
}

/// What can be wrong with a motion, profile or path request, as data; `armlab_text` words
/// it for a person.
#[derive(Debug, Clone, PartialEq)]
pub enum MotionError {
    /// A value is NaN or infinite.
    NotFinite {
        /// Which setting.
        setting: Setting,
        /// The value.
        value: f64,
    },
    /// A value that cannot be negative is.
    Negative {
        /// Which setting.
        setting: Setting,
        /// The value.
        value: f64,
    },
    /// A value that must be above zero is not.
    NotPositive {
        /// Which setting.
        setting: Setting,
        /// The value.
        value: f64,
    },
    /// A value is absurdly large, or large enough to make the 1 ms simulation unstable.
    TooLarge {
        /// Which setting.
        setting: Setting,
        /// The value.
        value: f64,
        /// The largest value accepted.
        max: f64,
    },
    /// A joint list has the wrong length.
    WrongJointCount {
        /// The robot's joint count.
        expected: usize,
        /// The count given.
        found: usize,
    },
    /// The robot rejected a joint vector.
    Robot(RobotError),
    /// A pose (a waypoint, a path's target) is not a pose.
    BadPose {
        /// Which one.
        setting: Setting,
        /// What is wrong with it.
        why: BadTarget,
    },
    /// IK refused a path's request.
    Ik(IkError),
}

impl std::fmt::Display for MotionError {
    /// What kind of error this is, for logs; `{:?}` shows its data, and a person reads the
    /// sentence the text catalogue makes of it (`armlab_text::Sentence`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a motion, profile or path setting that is not valid")
    }
}

impl std::error::Error for MotionError {}

impl From<RobotError> for MotionError {
    fn from(e: RobotError) -> Self {
        match e {
            RobotError::WrongJointCount { expected, found } => {
                MotionError::WrongJointCount { expected, found }
            }
            other => MotionError::Robot(other),
        }
    }
}

pub(crate) fn check_finite(setting: Setting, value: f64) -> Result<(), MotionError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(MotionError::NotFinite { setting, value })
    }
}

pub(crate) fn check_at_most(setting: Setting, value: f64, max: f64) -> Result<(), MotionError> {
    if value.abs() > max {
        Err(MotionError::TooLarge {
            setting,
            value,
            max,
        })
    } else {
        Ok(())
    }
}

/// Checks that `value` is finite, ≥ 0 and ≤ `max`.
pub(crate) fn check_non_negative(
    setting: Setting,
    value: f64,
    max: f64,
) -> Result<(), MotionError> {
    check_finite(setting, value)?;
    if value < 0.0 {
        return Err(MotionError::Negative { setting, value });
    }
    check_at_most(setting, value, max)
}

/// Checks that `value` is finite, > 0 and ≤ `max`.
pub(crate) fn check_positive(setting: Setting, value: f64, max: f64) -> Result<(), MotionError> {
    check_finite(setting, value)?;
    if value <= 0.0 {
        return Err(MotionError::NotPositive { setting, value });
    }
    check_at_most(setting, value, max)
}
