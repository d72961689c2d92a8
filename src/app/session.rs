//! What a link carries: the robot (a preset id or a whole edited table), the joint vector,
//! the target pose and the IK mode. Written as a URL hash and stored as the last session.
//!
//! Format (documented in the README): `#robot=ur10&q=0,-1.2,...&target=x,y,z,rx,ry,rz&task=full&method=dls`
//! - `robot`: a preset id, or `custom` with `dh=` the robot file's JSON, percent-encoded;
//! - `q`: joint values in the core's units (radians, the robot's length unit);
//! - `target`: position in the robot's length unit and Z-Y-X Euler angles α, β, γ in
//!   radians (`R = Rz(α)·Ry(β)·Rx(γ)`);
//! - `task`: `position`, `axis-x`, `axis-y`, `axis-z` or `full`;
//! - `method`: `dls`, `pinv`, `gradient` or `closed`.

use crate::api::parse_task;
use crate::kinematics::{
    Robot, RobotError, Task, ToolAxis, preset, robot_from_json, robot_to_json,
};

/// Which IK method the drag uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// Damped least squares (Levenberg–Marquardt): the default.
    DampedLeastSquares,
    /// Newton with the Moore–Penrose pseudo-inverse.
    PseudoInverse,
    /// Jacobian transpose / gradient descent.
    Gradient,
    /// The robot's closed-form solver, where it has one.
    ClosedForm,
}

impl Method {
    /// Every method, in menu order.
    pub const ALL: [Method; 4] = [
        Method::DampedLeastSquares,
        Method::PseudoInverse,
        Method::Gradient,
        Method::ClosedForm,
    ];

    /// The short name used in links.
    pub fn id(self) -> &'static str {
        match self {
            Method::DampedLeastSquares => "dls",
            Method::PseudoInverse => "pinv",
            Method::Gradient => "gradient",
            Method::ClosedForm => "closed",
        }
    }

    /// The name shown in the UI.
    pub fn label(self) -> &'static str {
        match self {
            Method::DampedLeastSquares => "Damped least squares",
            Method::PseudoInverse => "Pseudo-inverse (Newton)",
            Method::Gradient => "Jacobian transpose (gradient)",
            Method::ClosedForm => "Closed form",
        }
    }

    fn from_id(id: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.id() == id)
    }
}

/// The short name of a task used in links.
pub fn task_id(task: Task) -> &'static str {
    match task {
        Task::Position => "position",
        Task::PositionAndAxis(ToolAxis::X) => "axis-x",
        Task::PositionAndAxis(ToolAxis::Y) => "axis-y",
        Task::PositionAndAxis(ToolAxis::Z) => "axis-z",
        Task::FullPose => "full",
    }
}

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
    /// Target position (robot units) and Z-Y-X Euler angles (radians); `None` = at the tool.
    pub target: Option<[f64; 6]>,
    /// IK task.
    pub task: Task,
    /// IK method.
    pub method: Method,
}

/// The preset the app opens with, and falls back to when a link is broken.
pub const DEFAULT_PRESET: &str = "ur10";

impl Session {
    /// A preset at its home pose, target at the tool.
    pub fn for_preset(id: &str) -> Result<Session, RobotError> {
        let robot = preset(id)?;
        Ok(Session {
            q: robot.home(),
            robot,
            source: RobotSource::Preset(id.to_string()),
            target: None,
            task: Task::FullPose,
            method: Method::DampedLeastSquares,
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
    pub fn to_hash(&self) -> String {
        let mut parts = Vec::new();
        match &self.source {
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
        parts.push(format!("q={}", join_numbers(&self.q)));
        if let Some(t) = &self.target {
            parts.push(format!("target={}", join_numbers(t)));
        }
        parts.push(format!("task={}", task_id(self.task)));
        parts.push(format!("method={}", self.method.id()));
        parts.join("&")
    }

    /// Reads a URL hash (with or without `#`). An empty hash gives `Ok(None)`.
    pub fn from_hash(hash: &str) -> Result<Option<Session>, String> {
        let hash = hash.trim().trim_start_matches('#');
        if hash.is_empty() {
            return Ok(None);
        }
        let mut robot_id = None;
        let mut dh = None;
        let mut q = None;
        let mut target = None;
        let mut task = Task::FullPose;
        let mut method = Method::DampedLeastSquares;
        for part in hash.split('&').filter(|p| !p.is_empty()) {
            let (key, value) = part
                .split_once('=')
                .ok_or_else(|| format!("the link part \"{part}\" has no '='"))?;
            match key {
                "robot" => robot_id = Some(value.to_string()),
                "dh" => dh = Some(percent_decode(value)?),
                "q" => q = Some(parse_numbers(value, "q")?),
                "target" => {
                    let t = parse_numbers(value, "target")?;
                    let arr: [f64; 6] = t.try_into().map_err(|_| {
                        "the link's target needs six numbers (x, y, z, α, β, γ)".to_string()
                    })?;
                    target = Some(arr);
                }
                "task" => {
                    task = parse_task(value)
                        .ok_or_else(|| format!("the link's task \"{value}\" is not known"))?;
                }
                "method" => {
                    method = Method::from_id(value)
                        .ok_or_else(|| format!("the link's method \"{value}\" is not known"))?;
                }
                other => return Err(format!("the link has an unknown part \"{other}\"")),
            }
        }
        let mut session = match robot_id.as_deref() {
            Some("custom") => {
                let text = dh.ok_or("the link says robot=custom but carries no dh= table")?;
                let robot = robot_from_json(&text).map_err(|e| e.to_string())?;
                Session {
                    q: robot.home(),
                    robot,
                    source: RobotSource::Custom,
                    target: None,
                    task,
                    method,
                }
            }
            Some(id) => Session::for_preset(id).map_err(|e| e.to_string())?,
            None => return Err("the link names no robot (robot=...)".into()),
        };
        if let Some(q) = q {
            session.robot.check_q(&q).map_err(|e| e.to_string())?;
            session.q = q;
        }
        session.target = target;
        session.task = task;
        session.method = method;
        Ok(Some(session))
    }
}

fn join_numbers(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| {
            let s = format!("{v:.6}");
            let s = s.trim_end_matches('0').trim_end_matches('.');
            if s == "-0" {
                "0".to_string()
            } else {
                s.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(",")
}

fn parse_numbers(text: &str, what: &str) -> Result<Vec<f64>, String> {
    text.split(',')
        .map(|s| match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(format!(
                "the link's {what} has \"{s}\", which is not a number"
            )),
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
pub fn percent_decode(text: &str) -> Result<String, String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'%' => {
                let hex = text
                    .get(i + 1..i + 3)
                    .and_then(|h| u8::from_str_radix(h, 16).ok())
                    .ok_or("the link has a broken %-escape")?;
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
    String::from_utf8(out).map_err(|_| "the link's text is not valid UTF-8".to_string())
}

/// Where the native app keeps the last session's link hash:
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
