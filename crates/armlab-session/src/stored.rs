//! The session as JSON, for storage (localStorage in the page, the session file natively)
//! and any program that keeps sessions: [`Session::to_json`] and [`Session::from_json`],
//! and serde's `Serialize` and `Deserialize` for the session and each part it holds.
//!
//! It carries what a link carries, in the link's vocabulary: the robot as its robot file
//! (`armlab_core::robot_to_value`; none for an exercise, whose table the stored session
//! must not show), the target and the waypoints as the link's six numbers
//! `[x, y, z, α, β, γ]` with the link's six decimals (a pose turned into angles and back
//! moves by a last bit, so only numbers the link would write give the same pose again), the camera as `[yaw, pitch, distance, x, y, z]`, and
//! the task, method, language, panels, overlays and hidden items by their link ids.
//!
//! ```json
//! { "robot": { "name": "UR10", … }, "source": "ur10", "q": [0, -1.57, …],
//!   "target": [1000, -256.1, 400, 0, 0, 1.57], "task": "full", "method": "dls",
//!   "display": { "degrees": true, "panels": ["joints", "ik"] },
//!   "camera": [0.6, 0.4, 3000, 0, 0, 500], "motion": { "controller": "pid", … } }
//! ```
//!
//! Reading checks every value as a link's is checked and answers with the same typed
//! [`LinkError`]; JSON that is not a session's is [`LinkError::UnreadableSession`], and
//! serde's own message never reaches a person.

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::Value;

use armlab_core::{IkMethod, Task, preset, preset_ids, robot_from_value, robot_to_value};
use armlab_text::{Key, Lang};

use super::error::LinkError;
use super::exercise::ExerciseId;
use super::format::{pose_as_linked, target_from_array};
use super::motion::stored::StoredMotion;
use super::session::{RobotSource, Session};
use super::settings::{CameraPose, DisplayPatch, Flag, FlagSet, Hidden, HiddenSet, MAX_DECIMALS};

/// The `source` of a custom robot (the link's `robot=custom`); any other is a preset id.
const CUSTOM: &str = "custom";

/// A [`Session`] as stored.
#[derive(Serialize, Deserialize)]
struct StoredSession {
    /// The robot file; absent for an exercise (the robot comes from its id).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    robot: Option<Value>,
    /// A preset id or `custom`.
    source: String,
    q: Vec<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    target: Option<[f64; 6]>,
    task: String,
    method: String,
    #[serde(default)]
    display: StoredDisplay,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    camera: Option<[f64; 6]>,
    #[serde(default)]
    motion: StoredMotion,
    /// The exercise's link id (`rrr`, `mystery-17`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    exercise: Option<String>,
}

impl StoredSession {
    fn of(session: &Session) -> StoredSession {
        StoredSession {
            robot: session
                .exercise
                .is_none()
                .then(|| robot_to_value(&session.robot)),
            source: source_id(&session.source).to_string(),
            q: session.q.clone(),
            target: session.target.as_ref().map(pose_as_linked),
            task: session.task.id().to_string(),
            method: session.method.id().to_string(),
            display: StoredDisplay::of(&session.display),
            camera: session.camera.map(CameraPose::to_array),
            motion: StoredMotion::of(&session.motion),
            exercise: session.exercise.as_ref().map(ExerciseId::id),
        }
    }

    /// The session, each value checked as a link's is.
    fn into_session(self) -> Result<Session, LinkError> {
        let exercise = self
            .exercise
            .as_deref()
            .map(ExerciseId::parse)
            .transpose()?;
        let robot = match (&exercise, &self.robot) {
            (Some(_), Some(_)) => return Err(LinkError::ExerciseWithRobot),
            (Some(id), None) => id.robot()?,
            (None, Some(file)) => robot_from_value(file)?,
            (None, None) => return Err(LinkError::UnreadableSession),
        };
        robot.check_q(&self.q)?;
        Ok(Session {
            robot,
            source: source_from_id(&self.source)?,
            q: self.q,
            target: self.target.as_ref().map(target_from_array),
            task: Task::from_id(&self.task).ok_or(LinkError::UnknownTask(self.task))?,
            method: IkMethod::from_id(&self.method).ok_or(LinkError::UnknownMethod(self.method))?,
            display: self.display.into_patch()?,
            camera: self.camera.map(camera_from_array).transpose()?,
            motion: self.motion.into_patch().map_err(LinkError::Motion)?,
            exercise,
            dropped: Vec::new(),
        })
    }
}

/// The id of a robot's source: a preset's id, or `custom`.
fn source_id(source: &RobotSource) -> &str {
    match source {
        RobotSource::Preset(id) => id,
        RobotSource::Custom => CUSTOM,
    }
}

/// The source of an id: `custom`, or a preset's id (an unknown one is the core's error).
fn source_from_id(id: &str) -> Result<RobotSource, LinkError> {
    if id == CUSTOM {
        return Ok(RobotSource::Custom);
    }
    match preset_ids().find(|known| *known == id) {
        Some(known) => Ok(RobotSource::Preset(known.to_string())),
        // The core's own error, naming the presets.
        None => Err(preset(id)
            .err()
            .map_or(LinkError::UnreadableSession, LinkError::Robot)),
    }
}

/// The camera of the link's six numbers.
fn camera_from_array(a: [f64; 6]) -> Result<CameraPose, LinkError> {
    CameraPose::from_array(a).ok_or(LinkError::BadCamera)
}

/// A [`DisplayPatch`] as stored: each field the patch has; the panels, overlays and
/// hidden items as lists of link ids.
#[derive(Serialize, Deserialize, Default)]
#[serde(default)]
struct StoredDisplay {
    #[serde(skip_serializing_if = "Option::is_none")]
    degrees: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    show_frames: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    precision: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    presentation: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    lang: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    panels: Option<Vec<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    presentation_panels: Option<Vec<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    overlays: Option<Vec<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    hidden: Option<Vec<String>>,
}

impl StoredDisplay {
    fn of(patch: &DisplayPatch) -> StoredDisplay {
        StoredDisplay {
            degrees: patch.degrees,
            show_frames: patch.show_frames,
            precision: patch.precision,
            presentation: patch.presentation,
            lang: patch.lang.map(|l| l.id().to_string()),
            panels: patch.panels.map(flag_ids),
            presentation_panels: patch.presentation_panels.map(flag_ids),
            overlays: patch.overlays.map(flag_ids),
            hidden: patch
                .hidden
                .as_ref()
                .map(|h| h.items().iter().map(|item| item.to_link()).collect()),
        }
    }

    /// The patch; a bad value is named with its link key (`decimals`, `lang`, …).
    fn into_patch(self) -> Result<DisplayPatch, LinkError> {
        let bad = |field: &str, text: String, allowed| LinkError::BadValue {
            field: field.to_string(),
            text,
            allowed,
        };
        let precision = match self.precision {
            Some(p) if p > MAX_DECIMALS => {
                return Err(bad("decimals", p.to_string(), Key::AllowedDecimals));
            }
            other => other,
        };
        let lang = self
            .lang
            .map(|id| Lang::from_id(&id).ok_or_else(|| bad("lang", id, Key::AllowedLang)))
            .transpose()?;
        Ok(DisplayPatch {
            degrees: self.degrees,
            show_frames: self.show_frames,
            precision,
            presentation: self.presentation,
            lang,
            panels: flags(self.panels, "panels", Key::AllowedPanels)?,
            presentation_panels: flags(self.presentation_panels, "ppanels", Key::AllowedPanels)?,
            overlays: flags(self.overlays, "show", Key::AllowedShow)?,
            hidden: self.hidden.map(|items| hidden_set(&items)).transpose()?,
        })
    }
}

/// The set of a stored list of link ids; an unknown id is named with the link key `field`.
fn flags<K: Flag>(
    ids: Option<Vec<String>>,
    field: &str,
    allowed: Key,
) -> Result<Option<FlagSet<K>>, LinkError> {
    ids.map(|ids| {
        flags_from_ids(&ids).map_err(|text| LinkError::BadValue {
            field: field.to_string(),
            text,
            allowed,
        })
    })
    .transpose()
}

/// The link ids of a set's flags, in display order.
fn flag_ids<K: Flag>(set: FlagSet<K>) -> Vec<String> {
    set.iter().map(|k| k.link_id().to_string()).collect()
}

/// The set of these link ids; the first unknown id is the error.
fn flags_from_ids<K: Flag>(ids: &[String]) -> Result<FlagSet<K>, String> {
    let mut set = FlagSet::NONE;
    for id in ids {
        let kind = K::VALUES
            .iter()
            .find(|k| k.link_id() == id)
            .ok_or_else(|| id.clone())?;
        set.set(*kind, true);
    }
    Ok(set)
}

/// The hidden items of their link forms (`A2`, `T3.14`); the first bad one is the error.
fn hidden_set(items: &[String]) -> Result<HiddenSet, LinkError> {
    let mut set = HiddenSet::default();
    for text in items {
        let item = Hidden::from_link(text).ok_or_else(|| LinkError::BadHidden(text.clone()))?;
        if !set.contains(item) {
            set.toggle(item);
        }
    }
    Ok(set)
}

impl Session {
    /// The session as compact JSON, for storage ([`Session::from_json`] reads it back to
    /// an equal session).
    pub fn to_json(&self) -> String {
        // Through a JSON value, as robot files are read and written: the page's wasm then
        // holds one writer and one reader of each stored form, not one per JSON text and
        // one per value. The stored form holds only text, finite numbers and lists:
        // writing cannot fail.
        serde_json::to_value(StoredSession::of(self))
            .map_or_else(|_| String::new(), |v| v.to_string())
    }

    /// Reads a session that [`Session::to_json`] wrote, checking every value as a link's
    /// is checked; JSON that is not a session's is [`LinkError::UnreadableSession`].
    pub fn from_json(text: &str) -> Result<Session, LinkError> {
        let value: Value = serde_json::from_str(text).map_err(|_| LinkError::UnreadableSession)?;
        StoredSession::deserialize(&value)
            .map_err(|_| LinkError::UnreadableSession)?
            .into_session()
    }
}

/// `Serialize` and `Deserialize` through a stored form, whose check's typed error becomes
/// the deserializer's error (with its English sentence).
macro_rules! serde_through {
    ($type:ty, $stored:ty, $of:expr, $into:expr) => {
        impl Serialize for $type {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                $of(self).serialize(serializer)
            }
        }

        impl<'de> Deserialize<'de> for $type {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                $into(<$stored>::deserialize(deserializer)?)
                    .map_err(|e: LinkError| serde::de::Error::custom(e.sentence(Lang::En)))
            }
        }
    };
}

serde_through!(
    Session,
    StoredSession,
    StoredSession::of,
    StoredSession::into_session
);
serde_through!(
    DisplayPatch,
    StoredDisplay,
    StoredDisplay::of,
    StoredDisplay::into_patch
);
serde_through!(
    CameraPose,
    [f64; 6],
    |c: &CameraPose| c.to_array(),
    camera_from_array
);
serde_through!(ExerciseId, String, ExerciseId::id, |id: String| {
    ExerciseId::parse(&id)
});
serde_through!(
    RobotSource,
    String,
    |s: &RobotSource| source_id(s).to_string(),
    |id: String| source_from_id(&id)
);
