//! End-effector orientation in the four forms of docs/kinematics.md §7 (Craig's names), both ways, with
//! the degenerate cases handled without dividing by zero: R → angles → R returns R.

use nalgebra::{Matrix3, Vector3};

/// Below this `cos β` the Z-Y-X Euler angles are taken as degenerate (β = ±90°).
const GIMBAL_EPS: f64 = 1e-14;

/// Z-Y-X Euler angles: `R = Rz(α)·Ry(β)·Rx(γ)` (rotate about the moving Z, then Y, then X).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZyxEuler {
    /// α, about Z (radians).
    pub alpha: f64,
    /// β, about the new Y (radians), in [−π/2, π/2].
    pub beta: f64,
    /// γ, about the new X (radians).
    pub gamma: f64,
    /// True at β = ±90° (gimbal lock), where only α ± γ is defined; α is then set to 0.
    pub degenerate: bool,
}

impl ZyxEuler {
    /// Angles of a rotation matrix (Craig eq. 2.66). α comes from the first column; β
    /// and γ then come from `Rz(α)ᵀ·R = Ry(β)·Rx(γ)`, which uses the whole matrix, so the
    /// result is exact even near β = ±90°. At β = ±90° (first column (0, 0, ∓1)) α is
    /// undefined: it is set to 0 and γ carries the whole rotation about the common axis.
    pub fn from_rotation(r: &Matrix3<f64>) -> Self {
        let cb = r[(0, 0)].hypot(r[(1, 0)]);
        let degenerate = cb <= GIMBAL_EPS;
        let alpha = if degenerate {
            0.0
        } else {
            r[(1, 0)].atan2(r[(0, 0)])
        };
        let (sa, ca) = alpha.sin_cos();
        // Second row of Rz(α)ᵀ·R is (0, cγ, −sγ); its first column is (cβ, 0, −sβ).
        let cos_beta = if degenerate {
            cb
        } else {
            ca * r[(0, 0)] + sa * r[(1, 0)]
        };
        let beta = (-r[(2, 0)]).atan2(cos_beta);
        let gamma = (sa * r[(0, 2)] - ca * r[(1, 2)]).atan2(ca * r[(1, 1)] - sa * r[(0, 1)]);
        ZyxEuler {
            alpha,
            beta,
            gamma,
            degenerate,
        }
    }

    /// The rotation `Rz(α)·Ry(β)·Rx(γ)`.
    pub fn to_rotation(&self) -> Matrix3<f64> {
        let (sa, ca) = self.alpha.sin_cos();
        let (sb, cb) = self.beta.sin_cos();
        let (sg, cg) = self.gamma.sin_cos();
        #[rustfmt::skip]
        let r = Matrix3::new(
            ca * cb, ca * sb * sg - sa * cg, ca * sb * cg + sa * sg,
            sa * cb, sa * sb * sg + ca * cg, sa * sb * cg - ca * sg,
            -sb, cb * sg, cb * cg,
        );
        r
    }
}

/// X-Y-Z fixed angles (γ about the fixed X, then β about the fixed Y, then α about the
/// fixed Z): `R = Rz(α)·Ry(β)·Rx(γ)`, the same numbers as Z-Y-X Euler angles read the
/// other way round (Craig §2.8). Roll-pitch-yaw = (γ, β, α).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct XyzFixed {
    /// γ, about the fixed X (roll).
    pub gamma: f64,
    /// β, about the fixed Y (pitch).
    pub beta: f64,
    /// α, about the fixed Z (yaw).
    pub alpha: f64,
    /// True at β = ±90°.
    pub degenerate: bool,
}

impl XyzFixed {
    /// Angles of a rotation matrix.
    pub fn from_rotation(r: &Matrix3<f64>) -> Self {
        let e = ZyxEuler::from_rotation(r);
        XyzFixed {
            gamma: e.gamma,
            beta: e.beta,
            alpha: e.alpha,
            degenerate: e.degenerate,
        }
    }

    /// The rotation `Rz(α)·Ry(β)·Rx(γ)`.
    pub fn to_rotation(&self) -> Matrix3<f64> {
        ZyxEuler {
            alpha: self.alpha,
            beta: self.beta,
            gamma: self.gamma,
            degenerate: self.degenerate,
        }
        .to_rotation()
    }
}

/// Euler parameters (a unit quaternion), Craig's ε1..ε4 with ε4 the scalar part:
/// `ε = k̂·sin(θ/2)`, `ε4 = cos(θ/2)`. Kept with ε4 ≥ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerParameters {
    /// ε1 = kx·sin(θ/2).
    pub e1: f64,
    /// ε2 = ky·sin(θ/2).
    pub e2: f64,
    /// ε3 = kz·sin(θ/2).
    pub e3: f64,
    /// ε4 = cos(θ/2) ≥ 0.
    pub e4: f64,
}

impl EulerParameters {
    /// From a rotation matrix by Shepperd's method: the largest of the four squared
    /// parameters is taken first, so no division is ever by a small number.
    pub fn from_rotation(r: &Matrix3<f64>) -> Self {
        let (r11, r22, r33) = (r[(0, 0)], r[(1, 1)], r[(2, 2)]);
        let trace = r11 + r22 + r33;
        let candidates = [trace, r11, r22, r33];
        let mut k = 0;
        for i in 1..4 {
            if candidates[i] > candidates[k] {
                k = i;
            }
        }
        let (mut e1, mut e2, mut e3, mut e4);
        match k {
            0 => {
                let s = 2.0 * (1.0 + trace).max(0.0).sqrt(); // 4 ε4
                e4 = 0.25 * s;
                e1 = (r[(2, 1)] - r[(1, 2)]) / s;
                e2 = (r[(0, 2)] - r[(2, 0)]) / s;
                e3 = (r[(1, 0)] - r[(0, 1)]) / s;
            }
            1 => {
                let s = 2.0 * (1.0 + r11 - r22 - r33).max(0.0).sqrt(); // 4 ε1
                e1 = 0.25 * s;
                e4 = (r[(2, 1)] - r[(1, 2)]) / s;
                e2 = (r[(0, 1)] + r[(1, 0)]) / s;
                e3 = (r[(0, 2)] + r[(2, 0)]) / s;
            }
            2 => {
                let s = 2.0 * (1.0 - r11 + r22 - r33).max(0.0).sqrt(); // 4 ε2
                e2 = 0.25 * s;
                e4 = (r[(0, 2)] - r[(2, 0)]) / s;
                e1 = (r[(0, 1)] + r[(1, 0)]) / s;
                e3 = (r[(1, 2)] + r[(2, 1)]) / s;
            }
            _ => {
                let s = 2.0 * (1.0 - r11 - r22 + r33).max(0.0).sqrt(); // 4 ε3
                e3 = 0.25 * s;
                e4 = (r[(1, 0)] - r[(0, 1)]) / s;
                e1 = (r[(0, 2)] + r[(2, 0)]) / s;
                e2 = (r[(1, 2)] + r[(2, 1)]) / s;
            }
        }
        if e4 < 0.0 {
            (e1, e2, e3, e4) = (-e1, -e2, -e3, -e4);
        }
        let norm = (e1 * e1 + e2 * e2 + e3 * e3 + e4 * e4).sqrt();
        EulerParameters {
            e1: e1 / norm,
            e2: e2 / norm,
            e3: e3 / norm,
            e4: e4 / norm,
        }
    }

    /// The rotation matrix (Craig eq. 2.91).
    pub fn to_rotation(&self) -> Matrix3<f64> {
        let (e1, e2, e3, e4) = (self.e1, self.e2, self.e3, self.e4);
        #[rustfmt::skip]
        let r = Matrix3::new(
            1.0 - 2.0 * (e2 * e2 + e3 * e3), 2.0 * (e1 * e2 - e3 * e4), 2.0 * (e1 * e3 + e2 * e4),
            2.0 * (e1 * e2 + e3 * e4), 1.0 - 2.0 * (e1 * e1 + e3 * e3), 2.0 * (e2 * e3 - e1 * e4),
            2.0 * (e1 * e3 - e2 * e4), 2.0 * (e2 * e3 + e1 * e4), 1.0 - 2.0 * (e1 * e1 + e2 * e2),
        );
        r
    }
}

/// The equivalent angle-axis rotation: `angle` (radians, in [0, π]) about the unit `axis`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleAxis {
    /// Rotation angle θ ∈ [0, π].
    pub angle: f64,
    /// Unit axis k̂. At θ = 0 any axis serves; (0, 0, 1) is reported and `degenerate` set.
    pub axis: Vector3<f64>,
    /// True when θ = 0 (axis undefined). At θ = π the axis is defined up to sign.
    pub degenerate: bool,
}

impl AngleAxis {
    /// From a rotation matrix, through its Euler parameters (robust at θ = 0 and θ = π).
    pub fn from_rotation(r: &Matrix3<f64>) -> Self {
        let e = EulerParameters::from_rotation(r);
        let v = Vector3::new(e.e1, e.e2, e.e3);
        let s = v.norm();
        if s < 1e-15 {
            return AngleAxis {
                angle: 0.0,
                axis: Vector3::z(),
                degenerate: true,
            };
        }
        AngleAxis {
            angle: 2.0 * s.atan2(e.e4),
            axis: v / s,
            degenerate: false,
        }
    }

    /// Rodrigues' formula `R = I + sinθ·[k]× + (1 − cosθ)·[k]×²`.
    pub fn to_rotation(&self) -> Matrix3<f64> {
        let k = self.axis.normalize();
        let kx = k.cross_matrix();
        let (s, c) = self.angle.sin_cos();
        Matrix3::identity() + kx * s + kx * kx * (1.0 - c)
    }
}

/// The rotation vector `vee(log R)` = θ·k̂ (radians), zero for the identity. Used for
/// orientation errors and the numerical Jacobian's angular rows.
pub fn rotation_log(r: &Matrix3<f64>) -> Vector3<f64> {
    let e = EulerParameters::from_rotation(r);
    let v = Vector3::new(e.e1, e.e2, e.e3);
    let s = v.norm();
    if s < 1e-300 {
        return Vector3::zeros();
    }
    // θ/sin(θ/2)·v/|v|·sin(θ/2) with θ = 2·atan2(s, ε4); for small s, θ/s → 2/ε4.
    let angle = 2.0 * s.atan2(e.e4);
    v * (angle / s)
}

/// All four forms at once, for the panels and the JS API.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orientation {
    /// Z-Y-X Euler angles.
    pub zyx_euler: ZyxEuler,
    /// X-Y-Z fixed angles.
    pub xyz_fixed: XyzFixed,
    /// Equivalent angle-axis.
    pub angle_axis: AngleAxis,
    /// Euler parameters (unit quaternion).
    pub euler_parameters: EulerParameters,
}

impl Orientation {
    /// Every form of `r`.
    pub fn from_rotation(r: &Matrix3<f64>) -> Self {
        Orientation {
            zyx_euler: ZyxEuler::from_rotation(r),
            xyz_fixed: XyzFixed::from_rotation(r),
            angle_axis: AngleAxis::from_rotation(r),
            euler_parameters: EulerParameters::from_rotation(r),
        }
    }
}
