//! Forward kinematics: every link transform A_i, every running product T_0i, the tool
//! pose, and each joint's axis and origin in the base frame (for the Jacobian).

use nalgebra::{IsometryMatrix3, Matrix3, Matrix4, Rotation3, Translation3, Vector3};

use super::angles::sin_cos;
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
    let (st, ct) = sin_cos(theta);
    let (sa, ca) = sin_cos(alpha);
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
    let (st, ct) = sin_cos(theta);
    let (sa, ca) = sin_cos(alpha);
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
    let (theta, d) = theta_d(kind, row, q);
    match convention {
        Convention::Standard => standard_dh_transform(theta, d, row.a, row.alpha),
        Convention::Modified => modified_dh_transform(row.alpha, row.a, theta, d),
    }
}

/// One step along the chain: the frame after joint i from the frame before it, written
/// out on the rotation's columns (≈ 30 multiplications instead of a 4×4 product).
/// Returns the new rotation and origin, and the joint's axis and a point on it.
///
/// Standard DH, `R_i = R·Rz(θ)·Rx(α)`, `o_i = o + a·x_i + d·z_{i−1}`, axis `z_{i−1}` at `o`.
/// Modified DH, `R_i = R·Rx(α)·Rz(θ)`, `o_i = o + a·x_{i−1} + d·z_i`, axis `z_i` at `o_i`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn advance(
    convention: Convention,
    r: &Matrix3<f64>,
    o: &Vector3<f64>,
    (st, ct): (f64, f64),
    (sa, ca): (f64, f64),
    a: f64,
    d: f64,
) -> (Matrix3<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let c0 = r.column(0).into_owned();
    let c1 = r.column(1).into_owned();
    let c2 = r.column(2).into_owned();
    match convention {
        Convention::Standard => {
            let x = c0 * ct + c1 * st;
            let y0 = c1 * ct - c0 * st;
            let y = y0 * ca + c2 * sa;
            let z = c2 * ca - y0 * sa;
            let o_new = o + x * a + c2 * d;
            (Matrix3::from_columns(&[x, y, z]), o_new, c2, *o)
        }
        Convention::Modified => {
            let y1 = c1 * ca + c2 * sa;
            let z = c2 * ca - c1 * sa;
            let x = c0 * ct + y1 * st;
            let y = y1 * ct - c0 * st;
            let o_new = o + c0 * a + z * d;
            (Matrix3::from_columns(&[x, y, z]), o_new, z, o_new)
        }
    }
}

/// θ and d of a row with joint value `q` added to the variable one.
#[inline(always)]
fn theta_d(kind: JointKind, row: &DhRow, q: f64) -> (f64, f64) {
    match kind {
        JointKind::Revolute => (row.theta + q, row.d),
        JointKind::Prismatic => (row.theta, row.d + q),
    }
}

fn iso(r: Matrix3<f64>, o: Vector3<f64>) -> IsometryMatrix3<f64> {
    IsometryMatrix3::from_parts(Translation3::from(o), Rotation3::from_matrix_unchecked(r))
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
    /// (sin α, cos α) per row, and the α they were computed for (a self-checking cache:
    /// α is constant while q changes every frame).
    alpha_sin_cos: Vec<(f64, f64)>,
    alpha_of_cache: Vec<u64>,
}

impl ForwardKinematics {
    /// Forward kinematics of `robot` at `q`, allocating a new result. Checks `q`, and
    /// that every frame came out finite ([`RobotError::PoseNotFinite`] otherwise: a pose
    /// that overflowed must never reach a Jacobian or its singular values).
    pub fn new(robot: &Robot, q: &[f64]) -> Result<Self, RobotError> {
        robot.check_q(q)?;
        let mut fk = ForwardKinematics::default();
        fk.update(robot, q);
        if !fk.is_finite() {
            return Err(RobotError::PoseNotFinite);
        }
        Ok(fk)
    }

    /// Whether every frame, axis and origin holds finite numbers only.
    pub fn is_finite(&self) -> bool {
        let pose_finite = |p: &IsometryMatrix3<f64>| {
            p.translation.vector.iter().all(|v| v.is_finite())
                && p.rotation.matrix().iter().all(|v| v.is_finite())
        };
        pose_finite(&self.base_from_tool)
            && self.base_from_frames.iter().all(pose_finite)
            && self.link_transforms.iter().all(pose_finite)
            && self
                .joint_axes
                .iter()
                .chain(&self.joint_origins)
                .all(|v| v.iter().all(|x| x.is_finite()))
    }

    /// Recomputes everything for `robot` at `q` in place (no allocation after the first
    /// call for a given joint count). `q` must have `robot.dof()` entries; extra entries
    /// are ignored and missing ones count as zero.
    pub fn update(&mut self, robot: &Robot, q: &[f64]) {
        let n = robot.dof();
        if self.link_transforms.len() != n {
            let id = IsometryMatrix3::identity();
            self.link_transforms.resize(n, id);
            self.base_from_frames.resize(n, id);
            self.joint_axes.resize(n, Vector3::z());
            self.joint_origins.resize(n, Vector3::zeros());
            self.joint_kinds.resize(n, JointKind::Revolute);
            self.alpha_sin_cos.resize(n, (0.0, 1.0));
            self.alpha_of_cache.resize(n, f64::NAN.to_bits());
        }
        let mut r = *robot.world_from_base.rotation.matrix();
        let mut o = robot.world_from_base.translation.vector;
        for (i, joint) in robot.joints.iter().enumerate() {
            let bits = joint.dh.alpha.to_bits();
            if self.alpha_of_cache[i] != bits {
                self.alpha_of_cache[i] = bits;
                self.alpha_sin_cos[i] = sin_cos(joint.dh.alpha);
            }
            let (sa, ca) = self.alpha_sin_cos[i];
            let (theta, d) = theta_d(joint.kind, &joint.dh, q.get(i).copied().unwrap_or(0.0));
            let (st, ct) = sin_cos(theta);
            let a = joint.dh.a;
            let (r_new, o_new, axis, origin) =
                advance(robot.convention, &r, &o, (st, ct), (sa, ca), a, d);
            self.link_transforms[i] = match robot.convention {
                Convention::Standard => standard_from_sincos(st, ct, sa, ca, d, a),
                Convention::Modified => modified_from_sincos(st, ct, sa, ca, d, a),
            };
            self.base_from_frames[i] = iso(r_new, o_new);
            self.joint_axes[i] = axis;
            self.joint_origins[i] = origin;
            self.joint_kinds[i] = joint.kind;
            r = r_new;
            o = o_new;
        }
        self.base_from_tool = iso(r, o) * robot.flange_from_tool;
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
    let mut r = *robot.world_from_base.rotation.matrix();
    let mut o = robot.world_from_base.translation.vector;
    for (i, joint) in robot.joints.iter().enumerate() {
        let (theta, d) = theta_d(joint.kind, &joint.dh, q.get(i).copied().unwrap_or(0.0));
        let (r_new, o_new, _, _) = advance(
            robot.convention,
            &r,
            &o,
            sin_cos(theta),
            sin_cos(joint.dh.alpha),
            joint.dh.a,
            d,
        );
        r = r_new;
        o = o_new;
    }
    iso(r, o) * robot.flange_from_tool
}

/// A pose as the 4×4 homogeneous matrix shown to people.
pub fn homogeneous(pose: &IsometryMatrix3<f64>) -> Matrix4<f64> {
    pose.to_homogeneous()
}
