//! The motion lab's link fields (docs/link-format.md):
//!
//! - `move=on|off`: the arm drives to each IK answer with the controller;
//! - `ctrl=onoff|p|pd|pid|trapezoidal|cubic|quintic` and `gains=`: the dead band (on/off),
//!   K (p), Kp,Kd (pd), Kp,Ki,Kd (pid), or 1 for synchronised joints (profiles, optional);
//! - `plant=τ,I,b,L`: the motor's lag, the joint's inertia, friction and load;
//! - `timescale=0..10`;
//! - `collide=on|off`: the collision check;
//! - `keepout=x,y,z,sx,sy,sz;…`: keep-out boxes (centre and size in the robot's unit);
//! - `path=joint|line`: how the arm goes from one pose to the next;
//! - `wp=x,y,z,α,β,γ;…`: the waypoints (as `target=`: position in the robot's unit, Z-Y-X
//!   Euler angles in radians).
//!
//! Every field is optional; a link writes only what differs from the defaults, so a link
//! that leaves the motion lab alone carries none of these fields. Values go through the
//! core's own checks ([`MotionSettings::check`], [`KeepOut::new`]): a bad one is a typed
//! [`MotionLinkError`].
//! A bad `path=` or waypoint is left out with its error in [`MotionPatch::dropped`] and
//! the rest of the link applies.

use armlab_text::{Name, Sentence};
use nalgebra::{IsometryMatrix3, Point3, Vector3};

use armlab_core::collision::{KeepOut, MAX_KEEP_OUTS};
use armlab_core::motion::{
    Controller, MotionError, MotionSettings, PidGains, Plant, check_time_scale,
};
use armlab_core::path::{MAX_WAYPOINTS, PathKind};
use armlab_core::profile::ProfileShape;
use armlab_text::echo::Text;
use armlab_text::{Key, Lang, fill};

use super::format::number_list;
use super::format::{target_from_array, target_to_array};

pub(crate) mod stored;

/// Decimals of the numbers the motion fields write.
const DECIMALS: usize = 6;

/// What is wrong with a motion field of a link.
#[derive(Debug, Clone, PartialEq)]
pub enum MotionLinkError {
    /// `ctrl=` names no controller.
    UnknownController(String),
    /// A list item is not a finite number.
    NotANumber {
        /// The field's key.
        field: &'static str,
        /// The item as written.
        text: String,
    },
    /// A list has the wrong length.
    WrongCount {
        /// The field's key.
        field: &'static str,
        /// How many numbers it needs.
        expected: usize,
        /// How many it has.
        found: usize,
    },
    /// An on/off field is neither.
    NotOnOff {
        /// The field's key.
        field: &'static str,
        /// The value as written.
        text: String,
    },
    /// A value the core refuses (a negative gain, an unstable one, a flat box).
    Value(MotionError),
    /// `path=` names no path kind.
    UnknownPathKind(String),
    /// Waypoint N (1-based) of `wp=`: what is wrong with it.
    Waypoint(usize, Box<MotionLinkError>),
}

impl MotionLinkError {
    /// The reason in `lang`, as the middle of "This link could not be opened (…)".
    pub fn sentence(&self, lang: Lang) -> String {
        match self {
            MotionLinkError::UnknownController(c) => {
                fill(lang, Key::LinkUnknownController, &[&Text(c)])
            }
            MotionLinkError::NotANumber { field, text } => {
                fill(lang, Key::LinkNotANumber, &[field, &Text(text)])
            }
            MotionLinkError::WrongCount {
                field,
                expected,
                found,
            } => fill(lang, Key::LinkWrongCount, &[field, expected, found]),
            MotionLinkError::NotOnOff { field, text } => fill(
                lang,
                Key::LinkBadValue,
                &[
                    field,
                    &Text(text),
                    &armlab_text::text(lang, Key::AllowedOnOff),
                ],
            ),
            MotionLinkError::Value(e) => e.sentence(lang),
            MotionLinkError::UnknownPathKind(kind) => fill(
                lang,
                Key::LinkBadValue,
                &[
                    &"path",
                    &Text(kind),
                    &armlab_text::text(lang, Key::PathAllowedKinds),
                ],
            ),
            MotionLinkError::Waypoint(n, e) => format!(
                "{}: {}",
                armlab_core::motion::Setting::Waypoint(*n).name(lang),
                e.sentence(lang)
            ),
        }
    }
}

/// The motion lab as a link carries it: each field the link has.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MotionPatch {
    /// `move=`.
    pub move_on: Option<bool>,
    /// `ctrl=` with `gains=` and `plant=` (checked together).
    pub settings: Option<MotionSettings>,
    /// `timescale=`.
    pub time_scale: Option<f64>,
    /// `collide=`.
    pub collisions: Option<bool>,
    /// `keepout=`.
    pub keep_outs: Option<Vec<KeepOut>>,
    /// `path=`.
    pub path_kind: Option<PathKind>,
    /// `wp=`: the waypoints that read well.
    pub waypoints: Option<Vec<IsometryMatrix3<f64>>>,
    /// The errors of the values left out (a bad `path=`, bad waypoints).
    pub dropped: Vec<MotionLinkError>,
    ctrl: Option<String>,
    gains: Option<Vec<f64>>,
    plant: Option<Vec<f64>>,
}

impl MotionPatch {
    /// The fields of a motion lab state that differ from the defaults.
    pub fn of(
        move_on: bool,
        settings: &MotionSettings,
        time_scale: f64,
        collisions: bool,
        keep_outs: &[KeepOut],
    ) -> MotionPatch {
        MotionPatch {
            move_on: move_on.then_some(true),
            settings: (*settings != MotionSettings::default()).then_some(*settings),
            time_scale: (time_scale != 1.0).then_some(time_scale),
            collisions: collisions.then_some(true),
            keep_outs: (!keep_outs.is_empty()).then(|| keep_outs.to_vec()),
            ..MotionPatch::default()
        }
    }

    /// The link's `key=value` parts.
    pub fn to_parts(&self) -> Vec<String> {
        let on = |b: bool| if b { "on" } else { "off" };
        let mut parts = Vec::new();
        if let Some(m) = self.move_on {
            parts.push(format!("move={}", on(m)));
        }
        if let Some(s) = &self.settings {
            let (id, gains) = controller_link(&s.controller);
            parts.push(format!("ctrl={id}"));
            parts.push(format!("gains={}", number_list(&gains, DECIMALS)));
            parts.push(format!(
                "plant={}",
                number_list(&plant_link(&s.plant), DECIMALS)
            ));
        }
        if let Some(t) = self.time_scale {
            parts.push(format!("timescale={}", number_list(&[t], DECIMALS)));
        }
        if let Some(c) = self.collisions {
            parts.push(format!("collide={}", on(c)));
        }
        if let Some(boxes) = &self.keep_outs {
            let text: Vec<String> = boxes
                .iter()
                .map(|b| {
                    number_list(
                        &[
                            b.centre.x, b.centre.y, b.centre.z, b.size.x, b.size.y, b.size.z,
                        ],
                        DECIMALS,
                    )
                })
                .collect();
            parts.push(format!("keepout={}", text.join(";")));
        }
        if let Some(kind) = self.path_kind.filter(|k| *k != PathKind::Joint) {
            parts.push(format!("path={}", kind.id()));
        }
        if let Some(poses) = self.waypoints.as_ref().filter(|w| !w.is_empty()) {
            let text: Vec<String> = poses
                .iter()
                .map(|p| number_list(&target_to_array(p), DECIMALS))
                .collect();
            parts.push(format!("wp={}", text.join(";")));
        }
        parts
    }

    /// Reads one `key=value` part if it is a motion field: `Ok(true)` when read,
    /// `Ok(false)` when the key is not one of them.
    pub fn read(&mut self, key: &str, value: &str) -> Result<bool, MotionLinkError> {
        let switch = |field, v: &str| match v {
            "on" | "1" | "true" => Ok(true),
            "off" | "0" | "false" => Ok(false),
            _ => Err(MotionLinkError::NotOnOff {
                field,
                text: v.to_string(),
            }),
        };
        match key {
            "move" => self.move_on = Some(switch("move", value)?),
            "collide" => self.collisions = Some(switch("collide", value)?),
            "ctrl" => self.ctrl = Some(value.to_string()),
            "gains" => self.gains = Some(numbers("gains", value)?),
            "plant" => self.plant = Some(numbers("plant", value)?),
            "timescale" => {
                let t = numbers("timescale", value)?;
                let [t] = t[..] else {
                    return Err(MotionLinkError::WrongCount {
                        field: "timescale",
                        expected: 1,
                        found: t.len(),
                    });
                };
                self.time_scale = Some(check_time_scale(t).map_err(MotionLinkError::Value)?);
            }
            "keepout" => {
                let mut boxes = Vec::new();
                for (i, text) in value.split(';').filter(|t| !t.is_empty()).enumerate() {
                    let v = numbers("keepout", text)?;
                    let [x, y, z, sx, sy, sz] = v[..] else {
                        return Err(MotionLinkError::WrongCount {
                            field: "keepout",
                            expected: 6,
                            found: v.len(),
                        });
                    };
                    boxes.push(
                        KeepOut::new(i + 1, Point3::new(x, y, z), Vector3::new(sx, sy, sz))
                            .map_err(MotionLinkError::Value)?,
                    );
                }
                if boxes.len() > MAX_KEEP_OUTS {
                    return Err(MotionLinkError::WrongCount {
                        field: "keepout",
                        expected: MAX_KEEP_OUTS,
                        found: boxes.len(),
                    });
                }
                self.keep_outs = Some(boxes);
            }
            "path" => match PathKind::from_id(value) {
                Some(kind) => self.path_kind = Some(kind),
                None => self
                    .dropped
                    .push(MotionLinkError::UnknownPathKind(value.to_string())),
            },
            "wp" => self.read_waypoints(value),
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// Reads `wp=`: each waypoint that is six finite numbers is kept (at most
    /// [`MAX_WAYPOINTS`]); each other one is dropped with its error.
    fn read_waypoints(&mut self, value: &str) {
        let mut poses = Vec::new();
        for (i, text) in value.split(';').filter(|t| !t.is_empty()).enumerate() {
            let pose = numbers("wp", text).and_then(|v| {
                let six: [f64; 6] =
                    v.try_into()
                        .map_err(|v: Vec<f64>| MotionLinkError::WrongCount {
                            field: "wp",
                            expected: 6,
                            found: v.len(),
                        })?;
                if poses.len() == MAX_WAYPOINTS {
                    return Err(MotionLinkError::Value(MotionError::TooLarge {
                        setting: armlab_core::motion::Setting::Waypoint(i + 1),
                        value: (i + 1) as f64,
                        max: MAX_WAYPOINTS as f64,
                    }));
                }
                Ok(target_from_array(&six))
            });
            match pose {
                Ok(p) => poses.push(p),
                Err(e) => self
                    .dropped
                    .push(MotionLinkError::Waypoint(i + 1, Box::new(e))),
            }
        }
        self.waypoints = Some(poses);
    }

    /// Once every part is read: builds and checks the settings from `ctrl`, `gains` and
    /// `plant` (a field the link lacks takes its default).
    /// The fields are read once: a patch that is read equals the patch that was written.
    pub fn finish(&mut self) -> Result<(), MotionLinkError> {
        let (ctrl, gains, plant) = (self.ctrl.take(), self.gains.take(), self.plant.take());
        if ctrl.is_none() && gains.is_none() && plant.is_none() {
            return Ok(());
        }
        let defaults = MotionSettings::default();
        let id = ctrl.unwrap_or_else(|| "p".to_string());
        let want = |n: usize| -> Result<Option<Vec<f64>>, MotionLinkError> {
            match &gains {
                Some(g) if g.len() != n => Err(MotionLinkError::WrongCount {
                    field: "gains",
                    expected: n,
                    found: g.len(),
                }),
                other => Ok(other.clone()),
            }
        };
        let controller = match id.as_str() {
            "onoff" => Controller::OnOff {
                dead_band: want(1)?.map_or(0.01, |g| g[0]),
            },
            "p" => Controller::Proportional {
                gain: want(1)?.map_or(5.0, |g| g[0]),
            },
            "pd" => {
                let d = PidGains::default();
                let g = want(2)?.unwrap_or(vec![d.kp, d.kd]);
                Controller::Pid(PidGains {
                    kp: g[0],
                    ki: 0.0,
                    kd: g[1],
                })
            }
            "pid" => {
                let d = PidGains::default();
                let g = want(3)?.unwrap_or(vec![d.kp, d.ki, d.kd]);
                Controller::Pid(PidGains {
                    kp: g[0],
                    ki: g[1],
                    kd: g[2],
                })
            }
            other => {
                let shape = ProfileShape::from_id(other)
                    .ok_or_else(|| MotionLinkError::UnknownController(other.to_string()))?;
                let sync = want(1)?.is_some_and(|g| g[0] != 0.0);
                Controller::Profile {
                    shape,
                    synchronised: sync,
                }
            }
        };
        let plant = match &plant {
            None => defaults.plant,
            Some(p) => {
                let [time_constant, inertia, friction, load] = p[..] else {
                    return Err(MotionLinkError::WrongCount {
                        field: "plant",
                        expected: 4,
                        found: p.len(),
                    });
                };
                Plant {
                    time_constant,
                    inertia,
                    friction,
                    load,
                }
            }
        };
        let settings = MotionSettings {
            controller,
            plant,
            ..defaults
        };
        settings.check().map_err(MotionLinkError::Value)?;
        self.settings = Some(settings);
        Ok(())
    }
}

/// A controller as the link writes it: its id (`ctrl=`) and its gains (`gains=`).
fn controller_link(controller: &Controller) -> (&'static str, Vec<f64>) {
    match *controller {
        Controller::OnOff { dead_band } => ("onoff", vec![dead_band]),
        Controller::Proportional { gain } => ("p", vec![gain]),
        Controller::Pid(g) if g.ki == 0.0 => ("pd", vec![g.kp, g.kd]),
        Controller::Pid(g) => ("pid", vec![g.kp, g.ki, g.kd]),
        Controller::Profile {
            shape,
            synchronised,
        } => (shape.id(), vec![if synchronised { 1.0 } else { 0.0 }]),
    }
}

/// A plant as the link writes it (`plant=τ,I,b,L`).
fn plant_link(p: &Plant) -> Vec<f64> {
    vec![p.time_constant, p.inertia, p.friction, p.load]
}

/// A comma-separated list of finite numbers.
fn numbers(field: &'static str, text: &str) -> Result<Vec<f64>, MotionLinkError> {
    text.split(',')
        .map(|s| match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(MotionLinkError::NotANumber {
                field,
                text: s.to_string(),
            }),
        })
        .collect()
}

#[cfg(test)]
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    fn read_all(parts: &[String]) -> Result<MotionPatch, MotionLinkError> {
        let mut patch = MotionPatch::default();
        for part in parts {
            let (k, v) = part.split_once('=').expect("key=value");
            assert_eq!(patch.read(k, v), Ok(true), "{part}");
        }
        patch.finish()?;
        Ok(patch)
    }

    #[test]
    fn every_controller_and_the_keep_out_boxes_round_trip() {
        let boxes = vec![
            KeepOut::new(
                1,
                Point3::new(500.0, -200.0, 300.0),
                Vector3::new(100.0, 200.0, 50.0),
            )
            .expect("a box"),
        ];
        for controller in [
            Controller::OnOff { dead_band: 0.002 },
            Controller::Proportional { gain: 12.5 },
            Controller::Pid(PidGains {
                kp: 80.0,
                ki: 0.0,
                kd: 15.0,
            }),
            Controller::Pid(PidGains {
                kp: 100.0,
                ki: 150.0,
                kd: 20.0,
            }),
            Controller::Profile {
                shape: ProfileShape::Quintic,
                synchronised: true,
            },
        ] {
            let settings = MotionSettings {
                controller,
                plant: Plant {
                    time_constant: 0.05,
                    inertia: 2.0,
                    friction: 0.5,
                    load: 30.0,
                },
                ..MotionSettings::default()
            };
            let patch = MotionPatch::of(true, &settings, 0.1, true, &boxes);
            let back = read_all(&patch.to_parts()).expect("reads back");
            assert_eq!(back.settings, Some(settings));
            assert_eq!(back.move_on, Some(true));
            assert_eq!(back.time_scale, Some(0.1));
            assert_eq!(back.collisions, Some(true));
            assert_eq!(back.keep_outs, Some(boxes.clone()));
        }
        // The path kind and the waypoints.
        let pose = target_from_array(&[512.5, -120.25, 300.0, 0.3, -0.2, 1.1]);
        let patch = MotionPatch {
            path_kind: Some(PathKind::Cartesian),
            waypoints: Some(vec![pose, IsometryMatrix3::identity()]),
            ..MotionPatch::default()
        };
        let parts = patch.to_parts();
        assert_eq!(parts[0], "path=line");
        let back = read_all(&parts).expect("reads back");
        assert_eq!(back.path_kind, Some(PathKind::Cartesian));
        let poses = back.waypoints.expect("the waypoints");
        assert_eq!(poses.len(), 2);
        assert!((poses[0].translation.vector - pose.translation.vector).norm() < 1e-9);
        assert!((poses[0].rotation.inverse() * pose.rotation).angle() < 1e-6);
        assert!(back.dropped.is_empty());
        // The defaults write nothing.
        let none = MotionPatch::of(false, &MotionSettings::default(), 1.0, false, &[]);
        assert!(none.to_parts().is_empty());
    }

    #[test]
    fn bad_motion_fields_are_typed_errors() {
        let parts = |s: &[&str]| s.iter().map(|p| p.to_string()).collect::<Vec<_>>();
        assert_eq!(
            read_all(&parts(&["ctrl=bang", "gains=1"])),
            Err(MotionLinkError::UnknownController("bang".into()))
        );
        assert_eq!(
            read_all(&parts(&["ctrl=pid", "gains=1,2"])),
            Err(MotionLinkError::WrongCount {
                field: "gains",
                expected: 3,
                found: 2
            })
        );
        assert!(matches!(
            read_all(&parts(&["ctrl=p", "gains=-5"])),
            Err(MotionLinkError::Value(MotionError::NotPositive { .. }))
        ));
        // K·Δt above 1 would make the 1 ms step unstable.
        assert!(matches!(
            read_all(&parts(&["ctrl=p", "gains=5000"])),
            Err(MotionLinkError::Value(MotionError::TooLarge { .. }))
        ));
        let mut patch = MotionPatch::default();
        assert!(matches!(
            patch.read("keepout", "0,0,0,1,0,1"),
            Err(MotionLinkError::Value(MotionError::NotPositive { .. }))
        ));
        assert_eq!(
            patch.read("keepout", "0,0,0,1,1"),
            Err(MotionLinkError::WrongCount {
                field: "keepout",
                expected: 6,
                found: 5
            })
        );
        assert!(matches!(
            patch.read("gains", "1,NaN"),
            Err(MotionLinkError::NotANumber { .. })
        ));
        assert!(matches!(
            patch.read("timescale", "20"),
            Err(MotionLinkError::Value(MotionError::TooLarge { .. }))
        ));
        assert_eq!(
            patch.read("move", "maybe"),
            Err(MotionLinkError::NotOnOff {
                field: "move",
                text: "maybe".into()
            })
        );
        assert_eq!(patch.read("q", "1"), Ok(false));
    }

    #[test]
    fn bad_path_fields_are_dropped_with_their_errors() {
        // Path fields never fail the link: a bad value is dropped with its error.
        let mut patch = MotionPatch::default();
        assert_eq!(patch.read("path", "curvy"), Ok(true));
        assert_eq!(patch.read("wp", "1,2,3,0,0,0;1,2;4,5,6,0,0,NaN"), Ok(true));
        assert_eq!(patch.waypoints.as_ref().map(Vec::len), Some(1));
        assert_eq!(
            patch.dropped,
            vec![
                MotionLinkError::UnknownPathKind("curvy".into()),
                MotionLinkError::Waypoint(
                    2,
                    Box::new(MotionLinkError::WrongCount {
                        field: "wp",
                        expected: 6,
                        found: 2
                    })
                ),
                MotionLinkError::Waypoint(
                    3,
                    Box::new(MotionLinkError::NotANumber {
                        field: "wp",
                        text: "NaN".into()
                    })
                ),
            ]
        );
        let fi = patch.dropped[1].sentence(Lang::Fi);
        assert!(fi.contains("välipiste 2"), "{fi}");
        let sentence = MotionLinkError::UnknownController("bang".into()).sentence(Lang::En);
        assert!(sentence.contains("bang"), "{sentence}");
    }
}
