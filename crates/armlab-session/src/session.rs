//! What a link carries: the robot (a preset id or a whole edited table), the joint vector,
//! the target pose and the IK mode. Written as a URL hash and stored as the last session.
//!
//! Format (documented in docs/link-format.md): `#robot=ur10&q=0,-1.2,...&target=x,y,z,rx,ry,rz&task=full&method=dls`
//! - `robot`: a preset id, or `custom` with `dh=` the robot file's JSON, percent-encoded;
//! - `q`: joint values in the core's units (radians, the robot's length unit);
//! - `target`: position in the robot's length unit and Z-Y-X Euler angles α, β, γ in
//!   radians (`R = Rz(α)·Ry(β)·Rx(γ)`);
//! - `task`: `position`, `axis-x`, `axis-y`, `axis-z` or `full` (without it, the robot's
//!   default: position only below six joints, the full pose from six);
//! - `method`: `dls`, `pinv`, `gradient` or `closed`;
//! - display: `units=deg|rad`, `frames=on|off`, `decimals=0..8`, `present=on|off`,
//!   `lang=en|fi`, `panels=` and `ppanels=` (the open panels of the normal and the
//!   presentation layout: `joints,ik,matrices,robot` or `none`); each is optional, and a
//!   field a link lacks keeps the viewer's own setting (the language: the browser's);
//! - `camera=yaw,pitch,distance,x,y,z`: the 3D view's direction (radians), distance and
//!   focus (robot units); without it the view frames the arm.
//!
//! The same session as JSON, for storage: [`Session::to_json`] and [`Session::from_json`]
//! ([`crate::stored`]).

use nalgebra::IsometryMatrix3;

use armlab_core::{IkMethod, Robot, RobotError, Task, preset, robot_from_json, robot_to_json};

pub use super::error::LinkError;
use super::exercise::ExerciseId;
use super::format::{LINK_DECIMALS, number_list};
pub use super::format::{target_from_array, target_to_array};
use super::motion::MotionPatch;
use super::settings::{CameraPose, DisplayPatch, HiddenSet};

/// Where the robot came from.
#[derive(Debug, Clone, PartialEq)]
pub enum RobotSource {
    /// A preset, by id.
    Preset(String),
    /// A table the user edited or loaded.
    Custom,
}

/// Everything a link restores.
#[derive(Debug, Clone, PartialEq)]
pub struct Session {
    /// The robot.
    pub robot: Robot,
    /// Preset or custom.
    pub source: RobotSource,
    /// Joint values.
    pub q: Vec<f64>,
    /// The target pose in the base frame; `None` = at the tool.
    pub target: Option<IsometryMatrix3<f64>>,
    /// IK task.
    pub task: Task,
    /// IK method.
    pub method: IkMethod,
    /// The display settings the link names (the rest keep the viewer's own).
    pub display: DisplayPatch,
    /// The camera, if the link names one.
    pub camera: Option<CameraPose>,
    /// The motion lab's fields the link names.
    pub motion: MotionPatch,
    /// The DH-table exercise this robot is (`exercise=`): the link then names no table.
    pub exercise: Option<ExerciseId>,
    /// The parts of the link that were left out (a bad q, target, task, …), each with
    /// what was wrong: the rest of the link applies.
    pub dropped: Vec<LinkError>,
}

/// The preset the app opens with, and falls back to when a link is broken.
pub const DEFAULT_PRESET: &str = "ur10";

impl Session {
    /// A preset at its home pose, target at the tool.
    pub fn for_preset(id: &str) -> Result<Session, RobotError> {
        let robot = preset(id)?;
        let robot_dof = robot.dof();
        Ok(Session {
            q: robot.home(),
            robot,
            source: RobotSource::Preset(id.to_string()),
            target: None,
            task: Task::default_for(robot_dof),
            method: IkMethod::DampedLeastSquares,
            display: DisplayPatch::default(),
            camera: None,
            motion: MotionPatch::default(),
            exercise: None,
            dropped: Vec::new(),
        })
    }

    /// The default session (the UR10 at home).
    pub fn default_session() -> Session {
        match Session::for_preset(DEFAULT_PRESET) {
            Ok(s) => s,
            // The presets are compiled in and tested; this cannot happen in a release.
            Err(e) => panic!("the default preset does not load: {e}"),
        }
    }

    /// The URL hash (without `#`).
    // Never inlined: the page calls it from several places, and one copy is smaller.
    #[inline(never)]
    pub fn to_hash(&self) -> String {
        let mut parts = Vec::new();
        match &self.source {
            // An exercise's link names its robot, never its table.
            _ if self.exercise.is_some() => {
                let id = self
                    .exercise
                    .as_ref()
                    .map(ExerciseId::id)
                    .unwrap_or_default();
                parts.push(format!("exercise={id}"));
            }
            RobotSource::Preset(id) => parts.push(format!("robot={id}")),
            RobotSource::Custom => {
                parts.push("robot=custom".to_string());
                let compact: String = robot_to_json(&self.robot)
                    .lines()
                    .map(str::trim)
                    .collect::<Vec<_>>()
                    .join("");
                parts.push(format!("dh={}", percent_encode(&compact)));
            }
        }
        parts.push(format!("q={}", number_list(&self.q, LINK_DECIMALS)));
        if let Some(t) = &self.target {
            parts.push(format!(
                "target={}",
                number_list(&target_to_array(t), LINK_DECIMALS)
            ));
        }
        parts.push(format!("task={}", self.task.id()));
        parts.push(format!("method={}", self.method.id()));
        parts.extend(self.display.to_parts());
        if let Some(c) = &self.camera {
            parts.push(format!(
                "camera={}",
                number_list(&c.to_array(), LINK_DECIMALS)
            ));
        }
        parts.extend(self.motion.to_parts());
        parts.join("&")
    }

    /// Reads a URL hash (with or without `#`). An empty hash gives `Ok(None)`.
    // Never inlined: the page calls it from several places, and one copy is smaller.
    #[inline(never)]
    pub fn from_hash(hash: &str) -> Result<Option<Session>, LinkError> {
        let hash = hash.trim().trim_start_matches('#');
        if hash.is_empty() {
            return Ok(None);
        }
        let mut parts = LinkParts::parse(hash)?;
        let mut session = match parts.robot.as_deref() {
            _ if parts.exercise.is_some() => {
                if parts.robot.is_some() || parts.dh.is_some() {
                    return Err(LinkError::ExerciseWithRobot);
                }
                let id = parts.exercise.clone().ok_or(LinkError::NoRobot)?;
                let robot = id.robot()?;
                Session {
                    q: robot.home(),
                    task: Task::default_for(robot.dof()),
                    robot,
                    source: RobotSource::Custom,
                    target: None,
                    method: parts.method,
                    display: DisplayPatch::default(),
                    camera: None,
                    motion: MotionPatch::default(),
                    exercise: Some(id),
                    dropped: Vec::new(),
                }
            }
            Some("custom") => {
                let text = parts.dh.ok_or(LinkError::CustomWithoutTable)?;
                let robot = robot_from_json(&text)?;
                Session {
                    q: robot.home(),
                    task: Task::default_for(robot.dof()),
                    robot,
                    source: RobotSource::Custom,
                    target: None,
                    method: parts.method,
                    display: DisplayPatch::default(),
                    camera: None,
                    motion: MotionPatch::default(),
                    exercise: None,
                    dropped: Vec::new(),
                }
            }
            Some(id) => Session::for_preset(id)?,
            None => return Err(LinkError::NoRobot),
        };
        if let Some(q) = parts.q {
            match session.robot.check_q(&q) {
                Ok(()) => session.q = q,
                Err(e) => parts.dropped.push(LinkError::Robot(e)),
            }
        }
        session.target = parts.target.as_ref().map(target_from_array);
        // A link that names no task opens the robot's own default task.
        session.task = parts.task.unwrap_or(session.task);
        session.method = parts.method;
        session.display = parts.display;
        session.camera = parts.camera;
        session.motion = parts.motion;
        session.dropped = parts.dropped;
        Ok(Some(session))
    }
}

/// The parts of a link, read but not yet checked against the robot.
struct LinkParts {
    robot: Option<String>,
    dh: Option<String>,
    q: Option<Vec<f64>>,
    target: Option<[f64; 6]>,
    task: Option<Task>,
    method: IkMethod,
    display: DisplayPatch,
    camera: Option<CameraPose>,
    motion: MotionPatch,
    exercise: Option<ExerciseId>,
    dropped: Vec<LinkError>,
}

impl LinkParts {
    fn parse(hash: &str) -> Result<LinkParts, LinkError> {
        let mut parts = LinkParts {
            robot: None,
            dh: None,
            q: None,
            target: None,
            task: None,
            method: IkMethod::DampedLeastSquares,
            display: DisplayPatch::default(),
            camera: None,
            motion: MotionPatch::default(),
            exercise: None,
            dropped: Vec::new(),
        };
        for part in hash.split('&').filter(|p| !p.is_empty()) {
            let Some((key, value)) = part.split_once('=') else {
                parts.dropped.push(LinkError::NoEquals(part.to_string()));
                continue;
            };
            match key {
                "robot" => parts.robot = Some(value.to_string()),
                "dh" => parts.dh = Some(percent_decode(value)?),
                "exercise" => parts.exercise = Some(ExerciseId::parse(value)?),
                other if parts.motion.read(other, value).map_err(LinkError::Motion)? => {}
                other => {
                    if let Err(e) = parts.read_part(other, value) {
                        parts.dropped.push(e);
                    }
                }
            }
        }
        parts.motion.finish().map_err(LinkError::Motion)?;
        Ok(parts)
    }

    /// Reads a part that the robot does not depend on: a bad one is left out, and the
    /// rest of the link still applies.
    fn read_part(&mut self, key: &str, value: &str) -> Result<(), LinkError> {
        match key {
            "q" => self.q = Some(parse_numbers(value, "q")?),
            "target" => {
                let t = parse_numbers(value, "target")?;
                self.target = Some(t.try_into().map_err(|_| LinkError::TargetLength)?);
            }
            "task" => {
                self.task = Some(
                    Task::from_id(value)
                        .ok_or_else(|| LinkError::UnknownTask(value.to_string()))?,
                );
            }
            "method" => {
                self.method = IkMethod::from_id(value)
                    .ok_or_else(|| LinkError::UnknownMethod(value.to_string()))?;
            }
            "camera" => {
                let c: [f64; 6] = parse_numbers(value, "camera")?
                    .try_into()
                    .map_err(|_| LinkError::BadCamera)?;
                self.camera = Some(CameraPose::from_array(c).ok_or(LinkError::BadCamera)?);
            }
            "hide" => {
                let hidden = HiddenSet::from_link(value).map_err(LinkError::BadHidden)?;
                self.display.hidden = Some(hidden);
            }
            other => {
                let read =
                    self.display
                        .read(other, value)
                        .map_err(|allowed| LinkError::BadValue {
                            field: other.to_string(),
                            text: value.to_string(),
                            allowed,
                        })?;
                if !read {
                    return Err(LinkError::UnknownPart(other.to_string()));
                }
            }
        }
        Ok(())
    }
}

fn parse_numbers(text: &str, field: &'static str) -> Result<Vec<f64>, LinkError> {
    text.split(',')
        .map(|s| match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(LinkError::NotANumber {
                field,
                text: s.to_string(),
            }),
        })
        .collect()
}

/// Percent-encodes everything but unreserved characters (RFC 3986).
pub fn percent_encode(text: &str) -> String {
    let mut out = String::with_capacity(text.len() * 3);
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-_.~".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// Decodes `%XX` escapes (and `+` as space); fails on broken escapes or invalid UTF-8.
pub fn percent_decode(text: &str) -> Result<String, LinkError> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'%' => {
                let hex = text
                    .get(i + 1..i + 3)
                    .and_then(|h| u8::from_str_radix(h, 16).ok())
                    .ok_or(LinkError::BrokenEscape)?;
                out.push(hex);
                i += 3;
            }
            b'+' => {
                out.push(b' ');
                i += 1;
            }
            b => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8(out).map_err(|_| LinkError::NotUtf8)
}

/// Where the native app keeps the last session (its JSON):
/// `$XDG_CONFIG_HOME/armlab/session` (or `~/.config/armlab/session`; `%APPDATA%` on Windows).
#[cfg(not(target_arch = "wasm32"))]
pub fn native_session_file() -> Option<std::path::PathBuf> {
    let env = |key: &str| std::env::var_os(key).filter(|v| !v.is_empty());
    let config = env("XDG_CONFIG_HOME")
        .map(std::path::PathBuf::from)
        .or_else(|| env("APPDATA").map(std::path::PathBuf::from))
        .or_else(|| env("HOME").map(|home| std::path::PathBuf::from(home).join(".config")))?;
    Some(config.join("armlab").join("session"))
}

#[cfg(test)]
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests).
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    use armlab_text::{Lang, text};
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

    /// The one part of `hash` left out; the robot and the rest of the link apply.
    fn left_out(hash: &str) -> LinkError {
        let session = Session::from_hash(hash)
            .expect("the robot opens")
            .expect("not empty");
        assert_eq!(session.dropped.len(), 1, "{:?}", session.dropped);
        assert_eq!(session.q.len(), session.robot.dof());
        session.dropped[0].clone()
    }

    #[test]
    fn a_bad_joint_vector_is_left_out_and_the_robot_opens_at_home() {
        let session = Session::from_hash("#robot=planar-2r&q=abc,1&task=full&target=1,2")
            .expect("the robot opens")
            .expect("not empty");
        assert_eq!(
            session.robot.name,
            preset("planar-2r").expect("a preset").name
        );
        assert_eq!(session.q, session.robot.home());
        assert_eq!(session.task, Task::FullPose);
        assert_eq!(session.target, None);
        let said: Vec<String> = session.dropped.iter().map(|e| e.to_string()).collect();
        assert_eq!(
            said,
            [
                "the link's q has \"abc\", which is not a number",
                "the link's target needs six numbers (x, y, z, α, β, γ)"
            ]
        );
        // A robot that does not load still fails the whole link.
        assert!(Session::from_hash("#robot=banana&q=1").is_err());
    }

    #[test]
    fn every_allowed_value_list_of_the_display_fields_is_in_the_catalogue() {
        for key in [
            "units", "frames", "present", "decimals", "lang", "panels", "ppanels",
        ] {
            let allowed = DisplayPatch::default()
                .read(key, "bogus")
                .expect_err("a bad value");
            assert!(!text(Lang::En, allowed).is_empty(), "{key}: {allowed:?}");
        }
    }

    #[test]
    fn a_link_error_reads_in_english_and_in_finnish() {
        let e = left_out("#robot=ur10&q=1,2,banana");
        assert_eq!(
            e.to_string(),
            "the link's q has \"banana\", which is not a number"
        );
        assert_eq!(
            e.sentence(Lang::Fi),
            "linkin kentässä q on \"banana\", joka ei ole luku"
        );
        let e = left_out("#robot=ur10&units=grad");
        assert_eq!(
            e.to_string(),
            "the link's units is \"grad\"; it can be deg or rad"
        );
        assert!(e.sentence(Lang::Fi).ends_with("deg tai rad"));
        let e = left_out("#robot=ur10&q=1,2");
        assert_eq!(
            e.to_string(),
            "The robot has 6 joints but 2 joint values were given."
        );
        assert!(e.sentence(Lang::Fi).starts_with("Robotilla on 6 niveltä"));
    }

    #[test]
    fn a_link_error_repeats_at_most_forty_characters_and_no_control_character() {
        let long = "z".repeat(1000);
        let e = left_out(&format!("#robot=ur10&{long}=1"));
        assert_eq!(
            e.to_string(),
            format!("the link has an unknown part \"{}…\"", "z".repeat(39))
        );
        let e = left_out("#robot=ur10&task=a%0Ab%1B");
        assert_eq!(e.to_string(), "the link's task \"a%0Ab%1B\" is not known");
        let e = left_out("#robot=ur10&method=\u{7}x\ry");
        assert_eq!(
            e.to_string(),
            "the link's method \"\u{25A1}x\u{25A1}y\" is not known"
        );
        let e = left_out(&format!("#robot=ur10&q=1,{long}"));
        assert_eq!(
            e.sentence(Lang::Fi),
            format!(
                "linkin kentässä q on \"{}…\", joka ei ole luku",
                "z".repeat(39)
            )
        );
        // A custom robot's prismatic joint outside its stroke gets the core's sentence.
        let e = left_out("#robot=scara&q=0,0,5,0");
        assert_eq!(
            e.to_string(),
            "The value 5 of joint 3 lies outside its stroke 0 … 0.21."
        );
    }
}
