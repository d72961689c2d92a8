//! Trajectory profiles in joint space (docs/kinematics.md §18): the trapezoidal velocity
//! profile (LSPB, linear segments with parabolic blends), the cubic and the quintic
//! polynomial, each timed so that no joint exceeds its speed and acceleration limits,
//! optionally synchronised so that every joint arrives at the same time.
//!
//! A joint's move is `q(t) = q_start + D·s(t)` with `s` going from 0 to 1 (trapezoid: the
//! distance covered, written in the same form). The distance `D` is
//! [`joint_distance_to`]: the wrapped difference for joints that wrap to (−π, π], the
//! plain difference for every other joint (so a limited joint never leaves its range).

use super::angles::wrap_to_pi;
use super::motion_error::{MotionError, Setting};
use super::robot::{Joint, JointKind, Robot};

/// A revolute joint's speed limit when its robot file gives none: 90°/s (radians/s here).
pub const DEFAULT_MAX_SPEED_REVOLUTE: f64 = std::f64::consts::FRAC_PI_2;
/// A prismatic joint's speed limit when its robot file gives none, as a fraction of its
/// stroke per second (half the stroke per second).
pub const DEFAULT_PRISMATIC_STROKE_PER_S: f64 = 0.5;
/// A joint's acceleration limit when its robot file gives none is its speed limit divided
/// by this time (seconds): full speed is reached in a quarter of a second.
pub const DEFAULT_ACCELERATION_TIME: f64 = 0.25;

/// A joint's speed and acceleration limits (rad/s and rad/s², or units/s and units/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionLimits {
    /// The largest |q̇|.
    pub max_speed: f64,
    /// The largest |q̈|.
    pub max_acceleration: f64,
}

impl MotionLimits {
    /// The joint's limits from its robot file, with the documented defaults
    /// ([`DEFAULT_MAX_SPEED_REVOLUTE`], [`DEFAULT_PRISMATIC_STROKE_PER_S`],
    /// [`DEFAULT_ACCELERATION_TIME`]) for what the file does not give. A speed that is not
    /// a positive finite number is treated as absent.
    pub fn of(joint: &Joint) -> MotionLimits {
        let usable = |v: Option<f64>| v.filter(|v| v.is_finite() && *v > 0.0);
        let max_speed = usable(joint.max_speed).unwrap_or_else(|| match joint.kind {
            JointKind::Revolute => DEFAULT_MAX_SPEED_REVOLUTE,
            JointKind::Prismatic => {
                let stroke = joint.limits.max - joint.limits.min;
                if stroke.is_finite() && stroke > 0.0 {
                    stroke * DEFAULT_PRISMATIC_STROKE_PER_S
                } else {
                    1.0
                }
            }
        });
        let max_acceleration =
            usable(joint.max_acceleration).unwrap_or(max_speed / DEFAULT_ACCELERATION_TIME);
        MotionLimits {
            max_speed,
            max_acceleration,
        }
    }

    /// Every joint's limits, in chain order.
    pub fn of_robot(robot: &Robot) -> Vec<MotionLimits> {
        robot.joints.iter().map(MotionLimits::of).collect()
    }

    /// Checks both limits: positive, finite, at most `1e6`.
    pub fn check(&self) -> Result<(), MotionError> {
        super::motion_error::check_positive(Setting::MaxSpeed, self.max_speed, 1e6)?;
        super::motion_error::check_positive(Setting::MaxAcceleration, self.max_acceleration, 1e9)
    }
}

/// The signed distance a joint travels from `from` to `to`: `wrap_to_pi(to − from)` for a
/// revolute joint limited to ±180° (it wraps, so the short way round is free), `to − from`
/// for every other joint (the straight way stays inside its limits).
pub fn joint_distance_to(joint: &Joint, from: f64, to: f64) -> f64 {
    if joint.wraps() {
        wrap_to_pi(to - from)
    } else {
        to - from
    }
}

/// The shape of a profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum ProfileShape {
    /// Linear segment with parabolic blends: accelerate at the limit, cruise, decelerate
    /// (a triangle when the distance is too short to reach the cruise speed).
    #[default]
    Trapezoidal,
    /// `s(τ) = 3τ² − 2τ³`, τ = t/T: zero speed at both ends, acceleration jumps.
    Cubic,
    /// `s(τ) = 10τ³ − 15τ⁴ + 6τ⁵`: zero speed and acceleration at both ends.
    Quintic,
}

impl ProfileShape {
    /// Every shape, in menu order.
    pub const ALL: [ProfileShape; 3] = [
        ProfileShape::Trapezoidal,
        ProfileShape::Cubic,
        ProfileShape::Quintic,
    ];

    /// The id used in links: `trapezoidal`, `cubic`, `quintic`.
    pub fn id(self) -> &'static str {
        match self {
            ProfileShape::Trapezoidal => "trapezoidal",
            ProfileShape::Cubic => "cubic",
            ProfileShape::Quintic => "quintic",
        }
    }

    /// The shape of an id.
    pub fn from_id(id: &str) -> Option<ProfileShape> {
        ProfileShape::ALL.into_iter().find(|s| s.id() == id)
    }

    /// The polynomials' peak of |ṡ|·T / D: 3/2 for the cubic, 15/8 for the quintic (the
    /// trapezoid is timed by its own formula in [`JointProfile::min_duration`]).
    fn speed_factor(self) -> f64 {
        match self {
            ProfileShape::Trapezoidal => 1.0,
            ProfileShape::Cubic => 1.5,
            ProfileShape::Quintic => 15.0 / 8.0,
        }
    }

    /// The polynomials' peak of |s̈|·T² / D: 6 for the cubic (at both ends), 10/√3 for the
    /// quintic (at τ = ½ ± √3/6); 4 is the trapezoid's triangle, for completeness.
    fn acceleration_factor(self) -> f64 {
        match self {
            ProfileShape::Trapezoidal => 4.0,
            ProfileShape::Cubic => 6.0,
            ProfileShape::Quintic => 10.0 / 3f64.sqrt(),
        }
    }
}

/// Position, speed and acceleration of one joint at one time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ProfileSample {
    /// q(t).
    pub q: f64,
    /// q̇(t).
    pub qd: f64,
    /// q̈(t).
    pub qdd: f64,
}

/// One joint's timed move from `start` by `distance` in `duration` seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointProfile {
    /// The shape.
    pub shape: ProfileShape,
    /// q at t = 0.
    pub start: f64,
    /// The signed distance travelled.
    pub distance: f64,
    /// The time of the move T (seconds); after it the joint stays at `start + distance`.
    pub duration: f64,
    /// Trapezoid only: the cruise speed |q̇| (0 for the polynomials).
    pub cruise_speed: f64,
    /// Trapezoid only: the acceleration used in the blends (0 for the polynomials).
    pub blend_acceleration: f64,
}

impl JointProfile {
    /// The shortest time for `|distance|` within `limits`:
    /// trapezoid `D/v + v/a` when `D ≥ v²/a`, else the triangle `2√(D/a)`;
    /// cubic `max(3D/2v, √(6D/a))`; quintic `max(15D/8v, √(10D/(√3·a)))`.
    pub fn min_duration(shape: ProfileShape, distance: f64, limits: &MotionLimits) -> f64 {
        let d = distance.abs();
        let (v, a) = (limits.max_speed, limits.max_acceleration);
        if d == 0.0 {
            return 0.0;
        }
        match shape {
            ProfileShape::Trapezoidal => {
                if d >= v * v / a {
                    d / v + v / a
                } else {
                    2.0 * (d / a).sqrt()
                }
            }
            _ => (shape.speed_factor() * d / v).max((shape.acceleration_factor() * d / a).sqrt()),
        }
    }

    /// The move of `distance` from `start` taking `duration` seconds, at least
    /// [`JointProfile::min_duration`] (a shorter duration is raised to it). A trapezoid
    /// stretched to `T` keeps the acceleration limit `a` in its blends and cruises at
    /// `v = (aT − √(a²T² − 4aD))/2`, the root of `D = v·(T − v/a)`.
    pub fn new(
        shape: ProfileShape,
        start: f64,
        distance: f64,
        limits: &MotionLimits,
        duration: f64,
    ) -> JointProfile {
        let t = duration.max(JointProfile::min_duration(shape, distance, limits));
        let d = distance.abs();
        let (cruise_speed, blend_acceleration) = match shape {
            ProfileShape::Trapezoidal if d > 0.0 => {
                let a = limits.max_acceleration;
                let disc = (a * a * t * t - 4.0 * a * d).max(0.0);
                let v = ((a * t - disc.sqrt()) * 0.5).min(limits.max_speed);
                (v, a)
            }
            _ => (0.0, 0.0),
        };
        JointProfile {
            shape,
            start,
            distance,
            duration: t,
            cruise_speed,
            blend_acceleration,
        }
    }

    /// q, q̇ and q̈ at time `t` (clamped to [0, T]).
    pub fn sample(&self, t: f64) -> ProfileSample {
        let d = self.distance;
        let total = self.duration;
        if d == 0.0 || total <= 0.0 || t >= total {
            return ProfileSample {
                q: self.start + d,
                qd: 0.0,
                qdd: 0.0,
            };
        }
        let t = t.max(0.0);
        let sign = d.signum();
        let (s, sd, sdd) = match self.shape {
            ProfileShape::Trapezoidal => {
                let (v, a) = (self.cruise_speed, self.blend_acceleration);
                let blend = if a > 0.0 { v / a } else { 0.0 };
                if t < blend {
                    (0.5 * a * t * t, a * t, a)
                } else if t <= total - blend {
                    (0.5 * a * blend * blend + v * (t - blend), v, 0.0)
                } else {
                    let r = total - t;
                    (d.abs() - 0.5 * a * r * r, a * r, -a)
                }
            }
            ProfileShape::Cubic => {
                let u = t / total;
                let m = d.abs();
                (
                    m * (3.0 * u * u - 2.0 * u * u * u),
                    m * (6.0 * u - 6.0 * u * u) / total,
                    m * (6.0 - 12.0 * u) / (total * total),
                )
            }
            ProfileShape::Quintic => {
                let u = t / total;
                let (u2, u3) = (u * u, u * u * u);
                let m = d.abs();
                (
                    m * (10.0 * u3 - 15.0 * u3 * u + 6.0 * u3 * u2),
                    m * (30.0 * u2 - 60.0 * u3 + 30.0 * u2 * u2) / total,
                    m * (60.0 * u - 180.0 * u2 + 120.0 * u3) / (total * total),
                )
            }
        };
        ProfileSample {
            q: self.start + sign * s,
            qd: sign * sd,
            qdd: sign * sdd,
        }
    }
}

/// Every joint's move, planned together.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// One profile per joint.
    pub joints: Vec<JointProfile>,
    /// The longest joint's duration: the time the whole move takes.
    pub duration: f64,
}

impl Trajectory {
    /// Plans the move of `robot` from `from` to `to` with `shape`, each joint within its
    /// [`MotionLimits::of`]. With `synchronised` every joint takes the slowest joint's
    /// time (all arrive together); otherwise each joint takes its own shortest time.
    /// `to` is the goal as given: a joint that wraps goes the short way round.
    pub fn plan(
        robot: &Robot,
        from: &[f64],
        to: &[f64],
        shape: ProfileShape,
        synchronised: bool,
    ) -> Result<Trajectory, MotionError> {
        robot.check_q(from)?;
        robot.check_q(to)?;
        let limits = MotionLimits::of_robot(robot);
        let distances: Vec<f64> = robot
            .joints
            .iter()
            .zip(from.iter().zip(to))
            .map(|(j, (a, b))| joint_distance_to(j, *a, *b))
            .collect();
        Trajectory::with_limits(from, &distances, &limits, shape, synchronised)
    }

    /// Plans the moves of `distances` from `start` within `limits` (one of each per joint).
    pub fn with_limits(
        start: &[f64],
        distances: &[f64],
        limits: &[MotionLimits],
        shape: ProfileShape,
        synchronised: bool,
    ) -> Result<Trajectory, MotionError> {
        if start.len() != distances.len() || limits.len() != distances.len() {
            return Err(MotionError::WrongJointCount {
                expected: limits.len(),
                found: distances.len().min(start.len()),
            });
        }
        for (i, (s, d)) in start.iter().zip(distances).enumerate() {
            if !s.is_finite() || !d.is_finite() {
                return Err(MotionError::NotFinite {
                    setting: Setting::Goal(i + 1),
                    value: if s.is_finite() { *d } else { *s },
                });
            }
        }
        for l in limits {
            l.check()?;
        }
        let common = if synchronised {
            distances
                .iter()
                .zip(limits)
                .map(|(d, l)| JointProfile::min_duration(shape, *d, l))
                .fold(0.0, f64::max)
        } else {
            0.0
        };
        let joints: Vec<JointProfile> = start
            .iter()
            .zip(distances)
            .zip(limits)
            .map(|((s, d), l)| JointProfile::new(shape, *s, *d, l, common))
            .collect();
        let duration = joints.iter().map(|j| j.duration).fold(0.0, f64::max);
        Ok(Trajectory { joints, duration })
    }

    /// Writes q(t) and q̇(t) of every joint into `q` and `qd` (as many joints as both hold).
    pub fn sample_into(&self, t: f64, q: &mut [f64], qd: &mut [f64]) {
        for ((p, qv), qdv) in self.joints.iter().zip(q.iter_mut()).zip(qd.iter_mut()) {
            let s = p.sample(t);
            *qv = s.q;
            *qdv = s.qd;
        }
    }

    /// Every joint's sample at time `t`.
    pub fn sample(&self, t: f64) -> Vec<ProfileSample> {
        self.joints.iter().map(|p| p.sample(t)).collect()
    }
}
