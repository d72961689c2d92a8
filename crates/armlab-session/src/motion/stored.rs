//! The motion lab's fields in a stored session (JSON): the values a link carries, at full
//! precision, with the link's ids (`"pid"`, `"line"`) and its checks.

use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use armlab_core::collision::{KeepOut, MAX_KEEP_OUTS};
use armlab_core::motion::{MotionError, Setting, check_time_scale};
use armlab_core::path::{MAX_WAYPOINTS, PathKind};

use super::{MotionLinkError, MotionPatch, controller_link, plant_link};
use crate::format::{pose_as_linked, target_from_array};

/// A [`MotionPatch`] as stored: each field the patch has. The errors of the values a link
/// dropped are not stored (they were reported when the link was read).
#[derive(Serialize, Deserialize, Default)]
#[serde(default)]
pub(crate) struct StoredMotion {
    #[serde(skip_serializing_if = "Option::is_none")]
    move_on: Option<bool>,
    /// The controller's link id (`ctrl=`).
    #[serde(skip_serializing_if = "Option::is_none")]
    controller: Option<String>,
    /// The controller's gains (`gains=`).
    #[serde(skip_serializing_if = "Option::is_none")]
    gains: Option<Vec<f64>>,
    /// τ, I, b, L (`plant=`).
    #[serde(skip_serializing_if = "Option::is_none")]
    plant: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    time_scale: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    collisions: Option<bool>,
    /// Each box as centre and size, `[x, y, z, sx, sy, sz]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    keep_outs: Option<Vec<[f64; 6]>>,
    /// `joint` or `line`.
    #[serde(skip_serializing_if = "Option::is_none")]
    path_kind: Option<String>,
    /// Each pose as the link's `[x, y, z, α, β, γ]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    waypoints: Option<Vec<[f64; 6]>>,
}

impl StoredMotion {
    /// The stored form of `patch`.
    pub(crate) fn of(patch: &MotionPatch) -> StoredMotion {
        let (controller, gains) = match &patch.settings {
            Some(s) => {
                let (id, gains) = controller_link(&s.controller);
                (Some(id.to_string()), Some(gains))
            }
            None => (None, None),
        };
        StoredMotion {
            move_on: patch.move_on,
            controller,
            gains,
            plant: patch.settings.as_ref().map(|s| plant_link(&s.plant)),
            time_scale: patch.time_scale,
            collisions: patch.collisions,
            keep_outs: patch.keep_outs.as_ref().map(|boxes| {
                boxes
                    .iter()
                    .map(|b| {
                        let (c, s) = (b.centre, b.size);
                        [c.x, c.y, c.z, s.x, s.y, s.z]
                    })
                    .collect()
            }),
            path_kind: patch.path_kind.map(|k| k.id().to_string()),
            waypoints: patch
                .waypoints
                .as_ref()
                .map(|poses| poses.iter().map(pose_as_linked).collect()),
        }
    }

    /// The patch, through the link's own checks: the settings as `ctrl=`, `gains=` and
    /// `plant=` are, the time scale, the boxes, the path kind and the waypoints.
    pub(crate) fn into_patch(self) -> Result<MotionPatch, MotionLinkError> {
        let mut patch = MotionPatch {
            move_on: self.move_on,
            time_scale: self
                .time_scale
                .map(check_time_scale)
                .transpose()
                .map_err(MotionLinkError::Value)?,
            collisions: self.collisions,
            keep_outs: self.keep_outs.map(keep_outs).transpose()?,
            path_kind: self
                .path_kind
                .map(|id| PathKind::from_id(&id).ok_or(MotionLinkError::UnknownPathKind(id)))
                .transpose()?,
            waypoints: self.waypoints.map(waypoints).transpose()?,
            ctrl: self.controller,
            gains: self.gains,
            plant: self.plant,
            ..MotionPatch::default()
        };
        patch.finish()?;
        Ok(patch)
    }
}

/// The keep-out boxes, each checked by the core.
fn keep_outs(boxes: Vec<[f64; 6]>) -> Result<Vec<KeepOut>, MotionLinkError> {
    if boxes.len() > MAX_KEEP_OUTS {
        return Err(MotionLinkError::WrongCount {
            field: "keepout",
            expected: MAX_KEEP_OUTS,
            found: boxes.len(),
        });
    }
    boxes
        .iter()
        .enumerate()
        .map(|(i, [x, y, z, sx, sy, sz])| {
            KeepOut::new(i + 1, Point3::new(*x, *y, *z), Vector3::new(*sx, *sy, *sz))
                .map_err(MotionLinkError::Value)
        })
        .collect()
}

/// The waypoints, at most [`MAX_WAYPOINTS`].
fn waypoints(poses: Vec<[f64; 6]>) -> Result<Vec<nalgebra::IsometryMatrix3<f64>>, MotionLinkError> {
    if poses.len() > MAX_WAYPOINTS {
        let n = MAX_WAYPOINTS + 1;
        return Err(MotionLinkError::Waypoint(
            n,
            Box::new(MotionLinkError::Value(MotionError::TooLarge {
                setting: Setting::Waypoint(n),
                value: n as f64,
                max: MAX_WAYPOINTS as f64,
            })),
        ));
    }
    Ok(poses.iter().map(target_from_array).collect())
}

impl Serialize for MotionPatch {
    /// The stored form (a session's `motion`).
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        StoredMotion::of(self).serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for MotionPatch {
    /// Reads the stored form, checked as a link's fields are.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        StoredMotion::deserialize(deserializer)?
            .into_patch()
            .map_err(|e| serde::de::Error::custom(e.sentence(armlab_text::Lang::En)))
    }
}
