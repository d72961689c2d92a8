//! The `jacobian` verb: the Jacobians and their measures, and its answer.

use serde::Serialize;

use crate::ApiError;
use crate::answer::{Rows, answer, matrix_rows};
use crate::request::{parse_request, task_of};
use armlab_core::{ForwardKinematics, JacobianAnalysis, task_jacobian};

/// The answer of [`jacobian`].
#[derive(Serialize)]
struct JacobianResponse<'a> {
    robot: &'a str,
    geometric: Rows,
    numerical: Rows,
    task_rows: Rows,
    singular_values: &'a [f64],
    manipulability: f64,
    determinant: Option<f64>,
    condition_number: Option<f64>,
    near_singular: bool,
    length_scale: f64,
    displayed: DisplayedResponse,
}

/// The measures of the unscaled task rows, in the robot's units.
#[derive(Serialize)]
struct DisplayedResponse {
    manipulability: f64,
    determinant: Option<f64>,
    condition_number: Option<f64>,
}

/// Jacobians and measures. Request `{"robot", "q", "task"}` (task defaults to `"full"`).
/// Response: `geometric` and `numerical` (6×n rows; linear rows first), `task_rows`
/// (the unscaled task Jacobian) and the scaled measures: `singular_values`,
/// `manipulability`, `determinant` (null unless square), `condition_number` (null when
/// exactly singular), `near_singular`, `length_scale`; and `displayed`: the
/// manipulability, determinant and condition number of the unscaled task rows, in the
/// robot's units.
pub fn jacobian(request: &str) -> Result<String, ApiError> {
    let mut req = parse_request(request)?;
    let task = task_of(&mut req.fields)?;
    let fk = ForwardKinematics::new(&req.robot, &req.q)?;
    let analysis = JacobianAnalysis::new(&req.robot, &fk, &req.q, task);
    let rows = task_jacobian(&analysis.geometric, task, fk.tool_rotation(), 1.0);
    let m = &analysis.measures;
    answer(&JacobianResponse {
        robot: &req.robot.name,
        geometric: matrix_rows(&analysis.geometric),
        numerical: matrix_rows(&analysis.numerical),
        task_rows: matrix_rows(&rows),
        singular_values: &m.singular_values,
        manipulability: m.manipulability,
        determinant: m.determinant,
        condition_number: m.condition_number,
        near_singular: m.near_singular,
        length_scale: m.length_scale,
        displayed: DisplayedResponse {
            manipulability: m.displayed.manipulability,
            determinant: m.displayed.determinant,
            condition_number: m.displayed.condition_number,
        },
    })
}
