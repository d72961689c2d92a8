//! Which robot a DH-table exercise draws (docs/kinematics.md §15), as a link names it:
//! `exercise=rrr` (a preset) or `exercise=mystery-17` (the seeded arm
//! [`mystery_arm`]). The link carries only this id, never the table, so the address bar
//! and the stored session show nothing of the answer.

use armlab_core::exercise::mystery_arm;
use armlab_core::{Robot, RobotError, preset, preset_ids};

use super::error::LinkError;

/// The prefix of a mystery arm's id.
const MYSTERY: &str = "mystery-";

/// The robot of an exercise.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ExerciseId {
    /// A preset, by id.
    Preset(String),
    /// The seeded mystery arm (2–6 joints).
    Mystery(u64),
}

impl ExerciseId {
    /// The id a link writes: the preset's id, or `mystery-SEED`.
    pub fn id(&self) -> String {
        match self {
            ExerciseId::Preset(id) => id.clone(),
            ExerciseId::Mystery(seed) => format!("{MYSTERY}{seed}"),
        }
    }

    /// Reads a link's `exercise=` value: a preset id or `mystery-` and a whole number.
    pub fn parse(text: &str) -> Result<ExerciseId, LinkError> {
        if let Some(seed) = text.strip_prefix(MYSTERY) {
            return seed
                .parse::<u64>()
                .map(ExerciseId::Mystery)
                .map_err(|_| LinkError::UnknownExercise(text.to_string()));
        }
        preset_ids()
            .find(|id| *id == text)
            .map(|id| ExerciseId::Preset(id.to_string()))
            .ok_or_else(|| LinkError::UnknownExercise(text.to_string()))
    }

    /// The robot as it is named and described (a preset's own names).
    pub fn original_robot(&self) -> Result<Robot, RobotError> {
        match self {
            ExerciseId::Preset(id) => preset(id),
            ExerciseId::Mystery(seed) => Ok(mystery_arm(*seed)),
        }
    }

    /// The robot the exercise draws: the original without its name, description and
    /// joint names (a preset's name would let a student look its table up).
    pub fn robot(&self) -> Result<Robot, RobotError> {
        let mut robot = self.original_robot()?;
        robot.name = String::new();
        robot.description = String::new();
        for (i, joint) in robot.joints.iter_mut().enumerate() {
            joint.name = format!("{}", i + 1);
        }
        Ok(robot)
    }
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    use armlab_text::Lang;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    #[test]
    fn exercise_ids_round_trip_and_bad_ones_are_named() {
        for text in ["rrr", "ur10", "mystery-0", "mystery-18446744073709551615"] {
            let id = ExerciseId::parse(text).expect("a valid id");
            assert_eq!(id.id(), text);
        }
        assert_eq!(ExerciseId::parse("mystery-7"), Ok(ExerciseId::Mystery(7)));
        for bad in ["mystery-", "mystery--1", "mystery-1.5", "ur11", ""] {
            let e = ExerciseId::parse(bad).expect_err("not an exercise");
            assert_eq!(e, LinkError::UnknownExercise(bad.to_string()));
        }
        assert_eq!(
            ExerciseId::parse("ur11")
                .expect_err("bad")
                .sentence(Lang::En),
            "the link's exercise \"ur11\" is neither a preset id nor mystery- and a whole number"
        );
    }

    #[test]
    fn the_drawn_robot_has_no_name_but_the_same_kinematics() {
        let id = ExerciseId::Preset("ur10".into());
        let (drawn, original) = (
            id.robot().expect("loads"),
            id.original_robot().expect("loads"),
        );
        assert_eq!(original.name, "UR10");
        assert_eq!(drawn.name, "");
        assert_eq!(drawn.joints[1].name, "2");
        assert_eq!(drawn.joints.len(), original.joints.len());
        for (a, b) in drawn.joints.iter().zip(&original.joints) {
            assert_eq!(a.dh, b.dh);
        }
    }
}
