//! The robots ArmLab ships with, each a human-editable file in
//! `assets/robots/`, compiled in.

use super::error::RobotError;
use super::file::robot_from_json;
use super::robot::Robot;

/// Every preset: its id (used in URLs and the JS API) and its robot file.
pub const PRESETS: &[(&str, &str)] = &[
    ("ur10", include_str!("../../../assets/robots/ur10.json")),
    (
        "ur10-standard",
        include_str!("../../../assets/robots/ur10-standard.json"),
    ),
    (
        "metrover",
        include_str!("../../../assets/robots/metrover.json"),
    ),
    (
        "planar-2r",
        include_str!("../../../assets/robots/planar-2r.json"),
    ),
    ("rrr", include_str!("../../../assets/robots/rrr.json")),
    (
        "puma560",
        include_str!("../../../assets/robots/puma560.json"),
    ),
    ("panda", include_str!("../../../assets/robots/panda.json")),
    (
        "stanford",
        include_str!("../../../assets/robots/stanford.json"),
    ),
    ("scara", include_str!("../../../assets/robots/scara.json")),
];

/// The ids of every preset, in the order of [`PRESETS`].
pub fn preset_ids() -> impl Iterator<Item = &'static str> {
    PRESETS.iter().map(|(id, _)| *id)
}

/// Loads the preset with this id.
pub fn preset(id: &str) -> Result<Robot, RobotError> {
    match PRESETS.iter().find(|(name, _)| *name == id) {
        Some((_, text)) => robot_from_json(text),
        None => Err(RobotError::UnknownPreset(
            id.to_string(),
            preset_ids().collect::<Vec<_>>().join(", "),
        )),
    }
}

/// Every preset's id and robot name, in the order of [`PRESETS`], read from the files
/// once (the first call) and kept: a menu can list them every frame without parsing
/// JSON. A preset whose file does not load is listed by its id (the tests load every
/// preset, so this does not happen in a release).
pub fn preset_names() -> &'static [(&'static str, String)] {
    static NAMES: std::sync::OnceLock<Vec<(&'static str, String)>> = std::sync::OnceLock::new();
    NAMES.get_or_init(|| {
        preset_ids()
            .map(|id| (id, preset(id).map_or_else(|_| id.to_string(), |r| r.name)))
            .collect()
    })
}
