//! What the browser tests (and the UI tests) read: the state as JSON and the screen
//! positions of the target marker's handles and of the tool point.

use serde_json::json;

use super::ArmLabApp;
use super::session::{RobotSource, task_id};

/// Milliseconds from an arbitrary origin, for the app's own frame timing (the core has
/// no clock). `performance.now()` on the web, `Instant` natively.
pub fn now_ms() -> f64 {
    #[cfg(target_arch = "wasm32")]
    {
        web_sys::window()
            .and_then(|w| w.performance())
            .map_or(0.0, |p| p.now())
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        use std::sync::OnceLock;
        static START: OnceLock<std::time::Instant> = OnceLock::new();
        START
            .get_or_init(std::time::Instant::now)
            .elapsed()
            .as_secs_f64()
            * 1e3
    }
}

/// A link to this state: the page's address with the hash replaced.
pub fn share_link(hash: &str) -> String {
    #[cfg(target_arch = "wasm32")]
    {
        let base = web_sys::window()
            .and_then(|w| w.location().href().ok())
            .unwrap_or_default();
        let base = base.split('#').next().unwrap_or_default().to_string();
        format!("{base}#{hash}")
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        format!("#{hash}")
    }
}

/// `window.armlab.state()`: robot, q, target pose, reached/unreachable, task, method.
pub fn state_json(app: &ArmLabApp) -> String {
    let t = &app.target;
    let p = t.translation.vector;
    let e = crate::kinematics::EulerParameters::from_rotation(t.rotation.matrix());
    let tool = app.fk.tool_position();
    let r = t.rotation.matrix();
    json!({
        "robot": app.session.robot.name,
        "preset": match &app.session.source { RobotSource::Preset(id) => Some(id.clone()), RobotSource::Custom => None },
        "dof": app.session.robot.dof(),
        "length_unit": app.session.robot.length_unit.symbol(),
        "q": app.session.q,
        "tool": [tool.x, tool.y, tool.z],
        "target": {
            "position": [p.x, p.y, p.z],
            "quaternion": [e.e1, e.e2, e.e3, e.e4],
            "rotation": (0..3).map(|i| (0..3).map(|j| r[(i, j)]).collect::<Vec<_>>()).collect::<Vec<_>>(),
        },
        "reached": app.ik.reached,
        "unreachable": app.ik.unreachable,
        "position_error": app.ik.position_error,
        "orientation_error": app.ik.orientation_error,
        "task": task_id(app.session.task),
        "method": app.session.method.id(),
        "degrees": app.settings.degrees,
        "presentation": app.settings.presentation,
        "message": app.message,
        "editor_error": app.editor.first_error(),
        "hash": app.hash(),
        "dragging": app.viewport.dragging(),
        "frame": app.frame,
        "rendered": app.viewport.rendered,
    })
    .to_string()
}
