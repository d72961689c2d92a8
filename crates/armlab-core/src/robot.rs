//! The robot model: an ordered chain of revolute and prismatic joints described by a
//! Denavit–Hartenberg table in either convention, with limits, names, optional base and
//! tool transforms and the length unit it is written in.

use nalgebra::{IsometryMatrix3, Point3, Rotation3, Translation3, Vector3};

use super::angles;
use super::error::{Field, Place, RobotError};

/// The most joints a robot may have.
pub const MAX_JOINTS: usize = 64;
/// The largest magnitude of any length (in the robot's unit) or speed accepted.
pub const MAX_LENGTH: f64 = 1e6;
/// The largest magnitude of an angle accepted, in degrees (ten turns).
pub const MAX_ANGLE_DEG: f64 = 3600.0;
/// How far (in length units) a prismatic joint's value may lie outside its stroke and
/// still be accepted: the rounding of a link's six decimals, not a real overshoot.
pub const STROKE_SLACK: f64 = 1e-6;

/// Which Denavit–Hartenberg convention a table is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Convention {
    /// Standard (distal) DH, Spong: `A_i = Rot_z(θ_i)·Trans_z(d_i)·Trans_x(a_i)·Rot_x(α_i)`.
    /// Row `i` holds `(θ_i, d_i, a_i, α_i)`; joint `i` turns about `z_{i−1}`.
    Standard,
    /// Modified (proximal) DH, Craig: `^{i−1}T_i = Rot_x(α_{i−1})·Trans_x(a_{i−1})·Rot_z(θ_i)·Trans_z(d_i)`.
    /// Row `i` holds `(α_{i−1}, a_{i−1}, θ_i, d_i)`; joint `i` turns about `z_i`.
    Modified,
}

impl Convention {
    /// The name used in robot files.
    pub fn as_str(self) -> &'static str {
        match self {
            Convention::Standard => "standard",
            Convention::Modified => "modified",
        }
    }
}

/// Revolute (θ is the variable) or prismatic (d is the variable).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// The joint variable adds to θ (radians).
    Revolute,
    /// The joint variable adds to d (length units).
    Prismatic,
}

impl JointKind {
    /// The name used in robot files.
    pub fn as_str(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
        }
    }
}

/// The length unit a robot is written in. The core computes in that unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LengthUnit {
    /// Millimetres.
    Millimetre,
    /// Metres.
    Metre,
}

impl LengthUnit {
    /// The symbol used in robot files and in the UI.
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Millimetre => "mm",
            LengthUnit::Metre => "m",
        }
    }

    /// How many metres one unit is.
    pub fn in_metres(self) -> f64 {
        match self {
            LengthUnit::Millimetre => 1e-3,
            LengthUnit::Metre => 1.0,
        }
    }
}

/// One row of a DH table. In the modified convention `a` and `alpha` are `a_{i−1}` and
/// `α_{i−1}`; the joint variable is added to `theta` (revolute) or `d` (prismatic).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DhRow {
    /// θ offset (radians), the whole θ for a prismatic joint.
    pub theta: f64,
    /// d offset (length units), the whole d for a revolute joint.
    pub d: f64,
    /// Link length a (length units).
    pub a: f64,
    /// Link twist α (radians).
    pub alpha: f64,
}

/// A closed interval of joint values (radians or length units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointLimits {
    /// Lower bound.
    pub min: f64,
    /// Upper bound.
    pub max: f64,
}

impl JointLimits {
    /// The symmetric ±180° interval that revolute joints get when no limits are written.
    pub const FULL_TURN: JointLimits = JointLimits {
        min: -std::f64::consts::PI,
        max: std::f64::consts::PI,
    };

    /// Middle of the interval.
    pub fn mid(&self) -> f64 {
        0.5 * (self.min + self.max)
    }

    /// `value` clamped into the interval.
    pub fn clamp(&self, value: f64) -> f64 {
        value.clamp(self.min, self.max)
    }

    /// Whether `value` lies inside (with a tolerance of `tol`).
    pub fn contains(&self, value: f64, tol: f64) -> bool {
        value >= self.min - tol && value <= self.max + tol
    }
}

/// Outer sizes (length × width × height, in the robot's unit) of drawn parts, when the
/// robot file gives them (the Metrover does: `assets/robots/metrover.json`). Pure data: the core never uses
/// it; the renderer draws default proportions for what is `None`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PartSizes {
    /// The joint's housing: a cylinder of diameter max(length, width) and height `height`
    /// along the joint axis.
    pub housing: Option<[f64; 3]>,
    /// The link that this row's longer DH offset draws (a along x, or d along z): a box
    /// `length` long with a `width` × `height` cross-section, centred on that offset.
    pub link: Option<[f64; 3]>,
}

/// Outer sizes of the base block and the hand, when the robot file gives them.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RobotParts {
    /// A block under DH frame 0 with its top at z = 0.
    pub base: Option<[f64; 3]>,
    /// The gripper around the tool point (width across the fingers, height along them).
    pub hand: Option<[f64; 3]>,
}

/// One joint: its DH row in the robot's convention, its type, limits and name.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// A short human name ("shoulder").
    pub name: String,
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// The DH row (offsets; the joint variable adds to θ or d).
    pub dh: DhRow,
    /// Range of the joint variable (radians or length units).
    pub limits: JointLimits,
    /// Speed limit of the joint variable per second (rad/s or units/s), if known.
    pub max_speed: Option<f64>,
    /// Acceleration limit of the joint variable (rad/s² or units/s²), if known; the motion
    /// lab's default is in [`crate::profile::MotionLimits::of`].
    pub max_acceleration: Option<f64>,
    /// The home value of the joint variable.
    pub home: f64,
    /// Sizes of its drawn parts, if given.
    pub parts: PartSizes,
}

impl Joint {
    /// |d| of this row, for a prismatic joint at its largest extension within its limits.
    fn largest_offset(&self) -> f64 {
        match self.kind {
            JointKind::Revolute => self.dh.d.abs(),
            JointKind::Prismatic => (self.dh.d + self.limits.min)
                .abs()
                .max((self.dh.d + self.limits.max).abs()),
        }
    }

    /// Whether this revolute joint's angle wraps to (−π, π] (limits of ±180°), rather
    /// than being kept as the 2π-equivalent inside wider or narrower limits.
    pub fn wraps(&self) -> bool {
        self.kind == JointKind::Revolute
            && (self.limits.min - (-std::f64::consts::PI)).abs() < 1e-9
            && (self.limits.max - std::f64::consts::PI).abs() < 1e-9
    }

    /// The value this joint takes for a requested `value` when it is now at `current`
    /// (docs/kinematics.md §3): prismatic joints clamp to their stroke; ±180° revolute joints wrap to
    /// (−π, π]; other revolute joints take the 2π-equivalent of `value` inside the limits
    /// nearest `current`, or the nearest limit when no equivalent lies inside.
    pub fn keep(&self, value: f64, current: f64) -> f64 {
        match self.kind {
            JointKind::Prismatic => self.limits.clamp(value),
            JointKind::Revolute if self.wraps() => angles::wrap_to_pi(value),
            JointKind::Revolute => nearest_equivalent_within(value, current, &self.limits),
        }
    }

    /// The change from `from` to `to`: the wrapped angle difference for revolute joints,
    /// the plain difference for prismatic ones.
    pub fn change(&self, from: f64, to: f64) -> f64 {
        match self.kind {
            JointKind::Revolute => angles::wrap_to_pi(to - from),
            JointKind::Prismatic => to - from,
        }
    }
}

/// A robot arm: a serial chain in one DH convention.
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    /// Display name ("UR10").
    pub name: String,
    /// One or two sentences for the UI.
    pub description: String,
    /// The DH convention of every row.
    pub convention: Convention,
    /// The unit all lengths are written and computed in.
    pub length_unit: LengthUnit,
    /// The chain, from the base outwards.
    pub joints: Vec<Joint>,
    /// Where DH frame 0 sits in the world (identity for every preset).
    pub world_from_base: IsometryMatrix3<f64>,
    /// The tool frame relative to the last DH frame (identity when the tool is frame n).
    pub flange_from_tool: IsometryMatrix3<f64>,
    /// Sizes of the base block and the hand, if given.
    pub parts: RobotParts,
    /// Keep-out boxes the file brings for the motion lab's collision check, in the world
    /// frame and the file's length unit (at most [`MAX_KEEP_OUTS`]).
    pub keep_outs: Vec<KeepOut>,
}

impl Robot {
    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// The home pose (every joint's `home`).
    pub fn home(&self) -> Vec<f64> {
        self.joints.iter().map(|j| j.home).collect()
    }

    /// The midpoint of every joint's limits.
    pub fn mid_limits(&self) -> Vec<f64> {
        self.joints.iter().map(|j| j.limits.mid()).collect()
    }

    /// A characteristic length of the arm, its reach: the sum over the rows of
    /// √(a² + d²) (with a prismatic joint's largest extension), plus the tool offset.
    /// The Jacobian's linear rows are divided by it for the unit-free measures.
    pub fn reach(&self) -> f64 {
        let links: f64 = self
            .joints
            .iter()
            .map(|j| j.dh.a.hypot(j.largest_offset()))
            .sum();
        let reach = links + self.flange_from_tool.translation.vector.norm();
        if reach > 0.0 { reach } else { 1.0 }
    }

    /// The arm's characteristic length for the unit-free Jacobian measures: the sum of
    /// |a| and |d| over the rows (a prismatic joint at its largest extension) plus the
    /// tool offset. Unlike [`Robot::reach`], which pairs each row's a and d, it does not
    /// depend on the DH convention: a standard and a modified table of the same arm carry
    /// the same lengths in other rows, so they get the same scale and the same measures.
    pub fn length_scale(&self) -> f64 {
        let links: f64 = self
            .joints
            .iter()
            .map(|j| j.dh.a.abs() + j.largest_offset())
            .sum();
        let scale = links + self.flange_from_tool.translation.vector.norm();
        if scale > 0.0 && scale.is_finite() {
            scale
        } else {
            1.0
        }
    }

    /// Checks every number and structural rule; returns the robot unchanged when valid.
    pub fn validated(self) -> Result<Robot, RobotError> {
        if self.joints.is_empty() {
            return Err(RobotError::EmptyChain);
        }
        if self.joints.len() > MAX_JOINTS {
            return Err(RobotError::TooManyJoints {
                count: self.joints.len(),
                max: MAX_JOINTS,
            });
        }
        for (i, joint) in self.joints.iter().enumerate() {
            check_joint(i, joint)?;
        }
        self.check_parts_and_frames()?;
        check_keep_outs(&self.keep_outs)?;
        Ok(self)
    }

    /// Checks the base's and the hand's part sizes, and the base and tool transforms.
    fn check_parts_and_frames(&self) -> Result<(), RobotError> {
        for (field, size) in [
            (Field::BaseSize, self.parts.base),
            (Field::HandSize, self.parts.hand),
        ] {
            for v in size.iter().flatten() {
                check_size(&Place::Robot, field, *v)?;
            }
        }
        for (place, iso) in [
            (Place::Base, &self.world_from_base),
            (Place::Tool, &self.flange_from_tool),
        ] {
            for (k, v) in iso.translation.vector.iter().enumerate() {
                check_value(&place, [Field::X, Field::Y, Field::Z][k], *v, MAX_LENGTH)?;
            }
            for v in iso.rotation.matrix().iter() {
                check_value(&place, Field::Rotation, *v, 1.0 + 1e-6)?;
            }
        }
        Ok(())
    }

    /// Checks a joint vector against this robot: right length, all finite, and every
    /// prismatic joint inside its stroke (within [`STROKE_SLACK`]): a slide cannot extend
    /// beyond its travel, and a value far outside it would overflow the pose. Revolute
    /// values may lie outside their limits (forward kinematics answers for any angle; IK
    /// keeps its seed inside the limits, docs/kinematics.md §3).
    pub fn check_q(&self, q: &[f64]) -> Result<(), RobotError> {
        if q.len() != self.dof() {
            return Err(RobotError::WrongJointCount {
                expected: self.dof(),
                found: q.len(),
            });
        }
        for (i, (value, joint)) in q.iter().zip(&self.joints).enumerate() {
            if !value.is_finite() {
                return Err(RobotError::JointValueNotFinite {
                    joint: i + 1,
                    value: *value,
                });
            }
            if joint.kind == JointKind::Prismatic && !joint.limits.contains(*value, STROKE_SLACK) {
                return Err(RobotError::JointOutsideStroke {
                    joint: i + 1,
                    value: *value,
                    min: joint.limits.min,
                    max: joint.limits.max,
                });
            }
        }
        Ok(())
    }

    /// Every joint's value kept as docs/kinematics.md §3 says, relative to the current pose `current`.
    pub fn keep_q(&self, q: &mut [f64], current: &[f64]) {
        for ((v, c), joint) in q.iter_mut().zip(current).zip(&self.joints) {
            *v = joint.keep(*v, *c);
        }
    }
}

/// Fails when `value` is not finite or its size is above `limit`.
pub(crate) fn check_value(
    place: &Place,
    field: Field,
    value: f64,
    limit: f64,
) -> Result<(), RobotError> {
    if !value.is_finite() {
        return Err(RobotError::NotFinite {
            place: place.clone(),
            field,
            value,
        });
    }
    if value.abs() > limit {
        return Err(RobotError::TooLarge {
            place: place.clone(),
            field,
            value,
            limit,
        });
    }
    Ok(())
}

/// Checks joint `i` (from 0): its DH numbers, limits, home, part sizes and speeds within
/// range, a prismatic joint's home inside its stroke, and its limits in order.
fn check_joint(i: usize, joint: &Joint) -> Result<(), RobotError> {
    let place = Place::Joint(i + 1);
    let (lim_scale, lim_max) = match joint.kind {
        JointKind::Revolute => (1.0_f64.to_degrees(), MAX_ANGLE_DEG),
        JointKind::Prismatic => (1.0, MAX_LENGTH),
    };
    check_value(
        &place,
        Field::Theta,
        joint.dh.theta.to_degrees(),
        MAX_ANGLE_DEG,
    )?;
    check_value(&place, Field::D, joint.dh.d, MAX_LENGTH)?;
    check_value(&place, Field::A, joint.dh.a, MAX_LENGTH)?;
    check_value(
        &place,
        Field::Alpha,
        joint.dh.alpha.to_degrees(),
        MAX_ANGLE_DEG,
    )?;
    check_value(&place, Field::Min, joint.limits.min * lim_scale, lim_max)?;
    check_value(&place, Field::Max, joint.limits.max * lim_scale, lim_max)?;
    check_value(&place, Field::Home, joint.home * lim_scale, lim_max)?;
    for (field, size) in [
        (Field::Housing, joint.parts.housing),
        (Field::Link, joint.parts.link),
    ] {
        for v in size.iter().flatten() {
            check_size(&place, field, *v)?;
        }
    }
    if let Some(speed) = joint.max_speed {
        check_value(&place, Field::MaxSpeed, speed * lim_scale, MAX_LENGTH)?;
    }
    if let Some(acc) = joint.max_acceleration {
        check_value(&place, Field::MaxAcceleration, acc * lim_scale, 1e9)?;
        if acc <= 0.0 {
            return Err(RobotError::NotPositive {
                place,
                field: Field::MaxAcceleration,
                value: acc * lim_scale,
            });
        }
    }
    if joint.kind == JointKind::Prismatic
        && joint.limits.min <= joint.limits.max
        && !joint.limits.contains(joint.home, STROKE_SLACK)
    {
        return Err(RobotError::JointOutsideStroke {
            joint: i + 1,
            value: joint.home,
            min: joint.limits.min,
            max: joint.limits.max,
        });
    }
    if joint.limits.min > joint.limits.max {
        return Err(RobotError::LimitsReversed {
            joint: i + 1,
            min: joint.limits.min * lim_scale,
            max: joint.limits.max * lim_scale,
        });
    }
    Ok(())
}

/// Keep-out boxes: at most [`MAX_KEEP_OUTS`], every centre coordinate finite and within
/// [`MAX_LENGTH`], every size above zero and within it, every rotation a rotation.
fn check_keep_outs(boxes: &[KeepOut]) -> Result<(), RobotError> {
    if boxes.len() > MAX_KEEP_OUTS {
        return Err(RobotError::TooLarge {
            place: Place::Robot,
            field: Field::KeepOut,
            value: boxes.len() as f64,
            limit: MAX_KEEP_OUTS as f64,
        });
    }
    for (i, b) in boxes.iter().enumerate() {
        let place = Place::KeepOut(i + 1);
        for v in b.centre.iter() {
            check_value(&place, Field::Centre, *v, MAX_LENGTH)?;
        }
        for v in b.size.iter() {
            check_size(&place, Field::Size, *v)?;
            if *v == 0.0 {
                return Err(RobotError::NotPositive {
                    place,
                    field: Field::Size,
                    value: *v,
                });
            }
        }
        for v in b.rotation.matrix().iter() {
            check_value(&place, Field::Rotation, *v, 1.0 + 1e-6)?;
        }
    }
    Ok(())
}

/// A part size must be a finite, non-negative length.
fn check_size(place: &Place, field: Field, value: f64) -> Result<(), RobotError> {
    check_value(place, field, value, MAX_LENGTH)?;
    if value < 0.0 {
        return Err(RobotError::NegativeSize {
            place: place.clone(),
            field,
            value,
        });
    }
    Ok(())
}

/// A rigid transform from a translation and roll-pitch-yaw angles (radians):
/// `R = Rz(yaw)·Ry(pitch)·Rx(roll)`.
pub fn isometry_from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> IsometryMatrix3<f64> {
    IsometryMatrix3::from_parts(
        Translation3::from(Vector3::from(xyz)),
        Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

/// The 2π-equivalent of `value` (value + 2πk) that lies inside `limits` and is nearest
/// to `current`. When no equivalent lies inside (limits narrower than a turn), the
/// limit nearest to any equivalent is returned, so the result is always inside.
pub fn nearest_equivalent_within(value: f64, current: f64, limits: &JointLimits) -> f64 {
    // The equivalent nearest `current`, then its neighbours one turn either side.
    let base = current + angles::wrap_to_pi(value - current);
    let mut best: Option<(f64, f64)> = None; // (distance to current, candidate)
    let mut k_lo = ((limits.min - base) / std::f64::consts::TAU).floor() as i64;
    let mut k_hi = ((limits.max - base) / std::f64::consts::TAU).ceil() as i64;
    // Guard against absurd spans: at most a few turns matter.
    k_lo = k_lo.max(-8);
    k_hi = k_hi.min(8);
    for k in k_lo..=k_hi {
        let candidate = base + std::f64::consts::TAU * k as f64;
        if limits.contains(candidate, 1e-12) {
            let dist = (candidate - current).abs();
            if best.is_none_or(|(d, _)| dist < d) {
                best = Some((dist, limits.clamp(candidate)));
            }
        }
    }
    if let Some((_, candidate)) = best {
        return candidate;
    }
    // No equivalent inside: clamp to the limit closest to the wrapped value's circle.
    let to_min = angles::wrap_to_pi(limits.min - value).abs();
    let to_max = angles::wrap_to_pi(limits.max - value).abs();
    if to_min <= to_max {
        limits.min
    } else {
        limits.max
    }
}

/// The most keep-out boxes a scene may hold.
pub const MAX_KEEP_OUTS: usize = 64;

/// A box the arm must stay out of, in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeepOut {
    /// The box's centre.
    pub centre: Point3<f64>,
    /// Its full extents along its own x, y, z.
    pub size: Vector3<f64>,
    /// Its orientation.
    pub rotation: Rotation3<f64>,
}
