//! Writing an answer: matrices as rows, the four orientation forms, and a response struct
//! as JSON text. Apart from the verbs, which share these forms.

use nalgebra::{IsometryMatrix3, Matrix3};
use serde::Serialize;
use serde_json::{Value, json};

use crate::ApiError;
use armlab_core::Orientation;
use armlab_core::fk::homogeneous;

/// Rows of a matrix.
pub(crate) type Rows = Vec<Vec<f64>>;

/// Rows of a pose's 4×4 homogeneous matrix.
pub fn pose_rows(pose: &IsometryMatrix3<f64>) -> Value {
    json!(homogeneous_rows(pose))
}

pub(crate) fn homogeneous_rows(pose: &IsometryMatrix3<f64>) -> Rows {
    matrix_rows(&homogeneous(pose))
}

pub(crate) fn matrix_rows<
    R: nalgebra::Dim,
    C: nalgebra::Dim,
    S: nalgebra::RawStorage<f64, R, C>,
>(
    m: &nalgebra::Matrix<f64, R, C, S>,
) -> Rows {
    (0..m.nrows())
        .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect())
        .collect()
}

/// The four orientation forms (angles in radians).
#[derive(Serialize)]
pub(crate) struct OrientationForms {
    zyx_euler: EulerAngles,
    xyz_fixed: EulerAngles,
    angle_axis: AngleAxis,
    /// e1, e2, e3, e4 (the scalar last).
    euler_parameters: [f64; 4],
}

/// Three angles about three axes; `degenerate` at a gimbal lock.
#[derive(Serialize)]
struct EulerAngles {
    alpha: f64,
    beta: f64,
    gamma: f64,
    degenerate: bool,
}

/// A rotation angle about a unit axis; `degenerate` when the angle is 0 or π.
#[derive(Serialize)]
struct AngleAxis {
    angle: f64,
    axis: [f64; 3],
    degenerate: bool,
}

impl OrientationForms {
    pub(crate) fn new(r: &Matrix3<f64>) -> Self {
        let o = Orientation::from_rotation(r);
        OrientationForms {
            zyx_euler: EulerAngles {
                alpha: o.zyx_euler.alpha,
                beta: o.zyx_euler.beta,
                gamma: o.zyx_euler.gamma,
                degenerate: o.zyx_euler.degenerate,
            },
            xyz_fixed: EulerAngles {
                alpha: o.xyz_fixed.alpha,
                beta: o.xyz_fixed.beta,
                gamma: o.xyz_fixed.gamma,
                degenerate: o.xyz_fixed.degenerate,
            },
            angle_axis: AngleAxis {
                angle: o.angle_axis.angle,
                axis: [
                    o.angle_axis.axis.x,
                    o.angle_axis.axis.y,
                    o.angle_axis.axis.z,
                ],
                degenerate: o.angle_axis.degenerate,
            },
            euler_parameters: [
                o.euler_parameters.e1,
                o.euler_parameters.e2,
                o.euler_parameters.e3,
                o.euler_parameters.e4,
            ],
        }
    }
}

/// The four orientation forms as JSON (angles in radians).
pub fn orientation_json(r: &Matrix3<f64>) -> Value {
    serde_json::to_value(OrientationForms::new(r)).unwrap_or(Value::Null)
}

/// A response as JSON text. Writing these structs cannot fail (their maps have text keys);
/// were it to, the caller gets a sentence, not a panic.
pub(crate) fn answer(response: &impl Serialize) -> Result<String, ApiError> {
    serde_json::to_string(response).map_err(|e| ApiError::Request(e.to_string()))
}
