//! The `fk` verb: forward kinematics and its answer.

use serde::Serialize;

use crate::ApiError;
use crate::answer::{OrientationForms, Rows, answer, homogeneous_rows};
use crate::request::parse_request;
use armlab_core::ForwardKinematics;

/// The answer of [`fk`].
#[derive(Serialize)]
struct FkResponse<'a> {
    robot: &'a str,
    length_unit: &'static str,
    q: &'a [f64],
    /// T_0n (tool included) as 4 rows.
    tool: Rows,
    position: [f64; 3],
    orientation: OrientationForms,
    /// Every A_i.
    links: Vec<Rows>,
    /// Every T_0i.
    frames: Vec<Rows>,
}

/// Forward kinematics. Request `{"robot", "q"}` (q defaults to the robot's home).
/// Response: `tool` (4×4 rows of T_0n), `position`, `orientation` (the four forms),
/// `links` (every A_i) and `frames` (every T_0i), plus the robot's name and length unit.
pub fn fk(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    let fk = ForwardKinematics::new(&req.robot, &req.q)?;
    let p = fk.tool_position();
    answer(&FkResponse {
        robot: &req.robot.name,
        length_unit: req.robot.length_unit.symbol(),
        q: &req.q,
        tool: homogeneous_rows(&fk.base_from_tool),
        position: [p.x, p.y, p.z],
        orientation: OrientationForms::new(fk.tool_rotation()),
        links: fk.link_transforms.iter().map(homogeneous_rows).collect(),
        frames: fk.base_from_frames.iter().map(homogeneous_rows).collect(),
    })
}
