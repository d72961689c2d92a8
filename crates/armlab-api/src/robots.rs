//! The verbs that answer with robots: the list of presets and a robot's file. Apart
//! from the kinematics verbs, which answer with numbers.

use serde::Serialize;

use crate::ApiError;
use crate::answer::answer;
use crate::request::parse_request;
use armlab_core::{Robot, preset, preset_names, robot_to_json};

/// One preset in the list of [`presets`].
#[derive(Serialize)]
struct PresetSummary<'a> {
    id: &'a str,
    name: &'a str,
    dof: usize,
    convention: &'static str,
    length_unit: &'static str,
}

/// The presets: `[{"id", "name", "dof", "convention", "length_unit"}]`.
pub fn presets() -> String {
    let robots: Vec<(&str, Robot)> = preset_names()
        .iter()
        .filter_map(|(id, _)| preset(id).ok().map(|r| (*id, r)))
        .collect();
    let list: Vec<PresetSummary> = robots
        .iter()
        .map(|(id, r)| PresetSummary {
            id,
            name: &r.name,
            dof: r.dof(),
            convention: r.convention.as_str(),
            length_unit: r.length_unit.symbol(),
        })
        .collect();
    answer(&list).unwrap_or_else(|_| "[]".into())
}

/// The robot file of a preset (or the normalised file of a robot object), as JSON text.
pub fn robot(request: &str) -> Result<String, ApiError> {
    let req = parse_request(request)?;
    Ok(robot_to_json(&req.robot))
}
