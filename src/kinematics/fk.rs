//! Forward kinematics: every link transform A_i, every running product T_0i, the tool
//! pose, and each joint's axis and origin in the base frame (for the Jacobian).

use nalgebra::{IsometryMatrix3, Matrix3, Matrix4, Rotation3, Translation3, Vector3};

use super::error::RobotError;
use super::robot::{Convention, DhRow, JointKind, Robot};

/// Standard (Spong) DH link transform
/// `A_i = Rot_z(θ)·Trans_z(d)·Trans_x(a)·Rot_x(α)`:
///
/// ```text
/// [ cθ  −sθ·cα   sθ·sα   a·cθ ]
/// [ sθ   cθ·cα  −cθ·sα   a·sθ ]
/// [ 0    sα      cα      d    ]
/// [ 0    0       0       1    ]
/// ```
#[inline]
pub fn standard_dh_transform(theta: f64, d: f64, a: f64, alpha: f64) -> IsometryMatrix3<f64> {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    standard_from_sincos(st, ct, sa, ca, d, a)
}

/// Modified (Craig) DH link transform
/// `^{i−1}T_i = Rot_x(α_{i−1})·Trans_x(a_{i−1})·Rot_z(θ_i)·Trans_z(d_i)`:
///
/// ```text
/// [ cθ      −sθ      0     a      ]
/// [ sθ·cα    cθ·cα  −sα   −sα·d   ]
/// [ sθ·sα    cθ·sα   cα    cα·d   ]
/// [ 0        0       0     1      ]
/// ```
#[inline]
pub fn modified_dh_transform(alpha: f64, a: f64, theta: f64, d: f64) -> IsometryMatrix3<f64> {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    modified_from_sincos(st, ct, sa, ca, d, a)
}

#[inline]
fn standard_from_sincos(
    st: f64,
    ct: f64,
    sa: f64,
    ca: f64,
    d: f64,
    a: f64,
) -> IsometryMatrix3<f64> {
    #[rustfmt::skip]
    let r = Matrix3::new(
        ct, -st * ca, st * sa,
        st, ct * ca, -ct * sa,
        0.0, sa, ca,
    );
    IsometryMatrix3::from_parts(
        Translation3::new(a * ct, a * st, d),
        Rotation3::from_matrix_unchecked(r),
    )
}

#[inline]
fn modified_from_sincos(
    st: f64,
    ct: f64,
    sa: f64,
    ca: f64,
    d: f64,
    a: f64,
) -> IsometryMatrix3<f64> {
    #[rustfmt::skip]
    let r = Matrix3::new(
        ct, -st, 0.0,
        st * ca, ct * ca, -sa,
        st * sa, ct * sa, ca,
    );
    IsometryMatrix3::from_parts(
        Translation3::new(a, -sa * d, ca * d),
        Rotation3::from_matrix_unchecked(r),
    )
}

/// The DH link transform of one row with joint value `q` added to θ or d.
#[inline]
pub fn link_transform(
    convention: Convention,
    kind: JointKind,
    row: &DhRow,
    q: f64,
) -> IsometryMatrix3<f64> {
    let (theta, d) = match kind {
        JointKind::Revolute => (row.theta + q, row.d),
        JointKind::Prismatic => (row.theta, row.d + q),
    };
    match convention {
        Convention::Standard => standard_dh_transform(theta, d, row.a, row.alpha),
        Convention::Modified => modified_dh_transform(row.alpha, row.a, theta, d),
    }
}

/// The result of forward kinematics at one joint vector. Reused between frames:
/// [`ForwardKinematics::update`] overwrites it without allocating once sized.
#[derive(Debug, Clone, Default)]
pub struct ForwardKinematics {
    /// `A_i` for i = 1..n: DH frame i in DH frame i−1 (`prev_from_frame`).
    pub link_transforms: Vec<IsometryMatrix3<f64>>,
    /// `T_0i` for i = 1..n: DH frame i in the base (world) frame (`base_from_frame`),
    /// including the robot's base transform.
    pub base_from_frames: Vec<IsometryMatrix3<f64>>,
    /// The tool pose `T_0n · flange_from_tool` in the base frame.
    pub base_from_tool: IsometryMatrix3<f64>,
    /// Unit axis of joint i in the base frame: z_{i−1} (standard DH) or z_i (modified).
    pub joint_axes: Vec<Vector3<f64>>,
    /// A point on joint i's axis in the base frame: o_{i−1} (standard) or o_i (modified).
    pub joint_origins: Vec<Vector3<f64>>,
    /// Each joint's kind, copied so the Jacobian needs no robot.
    pub joint_kinds: Vec<JointKind>,
}

impl ForwardKinematics {
    /// Forward kinematics of `robot` at `q`, allocating a new result. Checks `q`.
    pub fn new(robot: &Robot, q: &[f64]) -> Result<Self, RobotError> {
        robot.check_q(q)?;
        let mut fk = ForwardKinematics::default();
        fk.update(robot, q);
        Ok(fk)
    }

    /// Recomputes everything for `robot` at `q` in place (no allocation after the first
    /// call for a given joint count). `q` must have `robot.dof()` entries; extra entries
    /// are ignored and missing ones count as zero.
    pub fn update(&mut self, robot: &Robot, q: &[f64]) {
        let n = robot.dof();
        self.link_transforms.clear();
        self.base_from_frames.clear();
        self.joint_axes.clear();
        self.joint_origins.clear();
        self.joint_kinds.clear();
        let mut base_from_prev = robot.world_from_base;
        for (i, joint) in robot.joints.iter().enumerate() {
            let qi = q.get(i).copied().unwrap_or(0.0);
            let prev_from_frame = link_transform(robot.convention, joint.kind, &joint.dh, qi);
            let base_from_frame = base_from_prev * prev_from_frame;
            let axis_frame = match robot.convention {
                Convention::Standard => &base_from_prev,
                Convention::Modified => &base_from_frame,
            };
            self.joint_axes
                .push(axis_frame.rotation.matrix().column(2).into_owned());
            self.joint_origins.push(axis_frame.translation.vector);
            self.joint_kinds.push(joint.kind);
            self.link_transforms.push(prev_from_frame);
            self.base_from_frames.push(base_from_frame);
            base_from_prev = base_from_frame;
        }
        debug_assert_eq!(self.base_from_frames.len(), n);
        self.base_from_tool = base_from_prev * robot.flange_from_tool;
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.link_transforms.len()
    }

    /// The tool position in the base frame.
    pub fn tool_position(&self) -> Vector3<f64> {
        self.base_from_tool.translation.vector
    }

    /// The tool orientation in the base frame.
    pub fn tool_rotation(&self) -> &Matrix3<f64> {
        self.base_from_tool.rotation.matrix()
    }
}

/// The tool pose alone (`T_0n · flange_from_tool`), without keeping the frames. Used by
/// the numerical Jacobian and the IK error checks.
pub fn tool_pose(robot: &Robot, q: &[f64]) -> IsometryMatrix3<f64> {
    let mut pose = robot.world_from_base;
    for (i, joint) in robot.joints.iter().enumerate() {
        let qi = q.get(i).copied().unwrap_or(0.0);
        pose *= link_transform(robot.convention, joint.kind, &joint.dh, qi);
    }
    pose * robot.flange_from_tool
}

/// A pose as the 4×4 homogeneous matrix shown to people.
pub fn homogeneous(pose: &IsometryMatrix3<f64>) -> Matrix4<f64> {
    pose.to_homogeneous()
}
