//! What the browser tests (and the UI tests) read: the state as JSON and the screen
//! positions of the target marker's handles and of the tool point.

use armlab_text::Sentence;
use serde_json::json;

use armlab_core::ik::Reach;

use crate::app::ArmLabApp;
use armlab_session::session::RobotSource;

/// `window.armlab.state()`: robot, q, target pose, reach, task, method, settings, the
/// message and the DH editor's error, the link hash, and the viewport's frame facts.
pub fn state_json(app: &ArmLabApp) -> String {
    let model = app.model();
    let t = model.target();
    let p = t.translation.vector;
    let e = armlab_core::EulerParameters::from_rotation(t.rotation.matrix());
    let tool = model.fk().tool_position();
    let r = t.rotation.matrix();
    let robot = model.robot();
    let ik = model.ik();
    json!({
        "robot": robot.name,
        "preset": match model.source() { RobotSource::Preset(id) => Some(id.clone()), RobotSource::Custom => None },
        // The exercise, never its table: its id, whether solved, the last verdict (English),
        // a check under way or one that could not run.
        "exercise": model.exercise().map(|e| json!({
            "id": e.id.id(),
            "solved": e.solved,
            "verdict": e.verdict.map(|v| v.sentence(armlab_text::Lang::En)),
            "check": match (&e.checking, &e.check_failed) {
                (Some(_), _) => Some("checking".to_string()),
                (None, Some(why)) => Some(format!("failed: {why}")),
                (None, None) => None,
            },
        })),
        "dof": robot.dof(),
        "reduced_motion": model.reduced_motion(),
        "length_unit": robot.length_unit.symbol(),
        "q": model.q(),
        "tool": [tool.x, tool.y, tool.z],
        "target": {
            "position": [p.x, p.y, p.z],
            "quaternion": [e.e1, e.e2, e.e3, e.e4],
            "rotation": (0..3).map(|i| (0..3).map(|j| r[(i, j)]).collect::<Vec<_>>()).collect::<Vec<_>>(),
        },
        "reach": ik.reach.id(),
        "reached": ik.reach == Reach::Reached,
        "unreachable": model.shown_reach() == Reach::OutOfReach,
        "held_at_limit": model.rescue().map(|r| serde_json::json!({
            "joint": r.held.map(|(j, _)| j + 1),
            "at_max": r.held.map(|(_, at_max)| at_max),
            "reached_from_another_start": r.reach.is_some(),
            "tried": r.tried,
        })),
        "branch": model.kept_branch().map(|b| b.id()),
        "branch_switched": model.branch_switch().map(|(from, to)| [from.id(), to.id()]),
        "position_error": ik.position_error,
        "orientation_error": ik.orientation_error,
        "task": model.task().id(),
        "method": model.method().id(),
        "degrees": model.settings().degrees,
        "presentation": model.settings().presentation,
        "lang": model.settings().lang.id(),
        "open_panels": model.settings().open_panels().to_link(),
        "sheet": app.sheet().map(|k| k.id()),
        "touch": app.touch(),
        "hovered_link": model.hovered_link(),
        "message": model.message().map(|m| m.text.clone()),
        "editor_error": app.robot_panel().editor().first_error(),
        "hash": model.hash(),
        "dragging": app.viewport().dragging(),
        "frame": app.frame(),
        "rendered": app.viewport().rendered(),
        "moving_picture": app.viewport().moving_picture(),
        "solutions": model.branches().map(|b| b.rows.iter().map(|r| r.q.clone()).collect::<Vec<_>>()),
        "workspace_samples": model.workspace().map(|c| c.len()),
        "directions_reachable": model.directions().map(|d| d.near.iter().filter(|n| **n).count()),
        "motion": motion_json(model),
        "symbolic": crate::app::platform::symbolic::symbolic_state_json(),
        "paths": paths_json(model),
    })
    .to_string()
}

/// The motion lab's part of the state: on, the controller's id, simulated time, whether
/// the arm is still moving, every joint's error and goal, collisions and the contact.
fn motion_json(model: &crate::app::state::model::Model) -> serde_json::Value {
    use crate::app::state::motion_lab::{REST_ERROR, REST_SPEED};
    let m = model.motion();
    let sim = m.sim();
    json!({
        "on": m.on(),
        "controller": crate::app::panels::motion::Choice::of(&m.settings().controller).id(),
        "time_scale": m.time_scale(),
        "time": sim.map(|s| s.time()),
        "moving": m.moving(),
        "at_rest": sim.map(|s| s.at_rest(REST_ERROR, REST_SPEED)) == Some(true)
            || (sim.is_some() && !m.moving() && m.time_scale() > 0.0),
        "error": sim.map(|s| s.error().to_vec()),
        "goal": sim.map(|s| s.goal().to_vec()),
        "collisions": m.collisions_on(),
        "contact": m.contact(),
        "checker": match crate::app::state::motion_lab::checker_state() {
            crate::app::state::motion_lab::CheckerState::Ready => "ready",
            crate::app::state::motion_lab::CheckerState::Loading => "loading",
            crate::app::state::motion_lab::CheckerState::Failed(_) => "failed",
        },
        "colliding_parts": m.colliding().iter().filter(|c| **c).count(),
        "keep_outs": m.keep_outs().len(),
        "trail": m.trail().len(),
    })
}

/// The paths' part of the state: the path kind, the waypoints' positions (robot units),
/// the problems of the path followed (the visit's, else the drawn straight line's), and
/// whether a visit is under way or done (every waypoint visited and the arm at rest).
fn paths_json(model: &crate::app::state::model::Model) -> serde_json::Value {
    let p = model.paths();
    let path = p
        .visit()
        .map(|v| &v.path)
        .or(p.plan().map(|plan| &plan.line));
    json!({
        "kind": p.kind().id(),
        "waypoints": p.waypoints().poses().iter().map(|w| {
            let t = w.translation.vector;
            [t.x, t.y, t.z]
        }).collect::<Vec<_>>(),
        "issues": path.map(|path| path.problems.iter().map(|i| (i.issue.id(), i.s)).collect::<Vec<_>>()),
        "visiting": p.visit().is_some(),
        "visit_done": p.finished() && !model.motion().moving(),
    })
}
