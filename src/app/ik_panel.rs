//! The IK controls: task (position / 5D with a tool axis / full pose), method, "snap
//! target to gripper", a full solve whose iterations can be replayed step by step with
//! the error per iteration, and the drag step the viewport calls every frame.

use crate::kinematics::ik::{IkMethod, IkResult, IkSettings, closed_form_family, pose_error};
use crate::kinematics::{Robot, Task, ToolAxis};

use super::session::Method;
use super::{ArmLabApp, style};

/// Orientation error (radians) below which the target counts as reached in the UI.
pub const ORIENTATION_TOLERANCE: f64 = 1e-4;
/// Position error (metres) below which the target counts as reached in the UI.
pub const POSITION_TOLERANCE_M: f64 = 1e-5;

/// The UI's "reached" position tolerance in the robot's unit.
pub fn position_tolerance(robot: &Robot) -> f64 {
    POSITION_TOLERANCE_M / robot.length_unit.in_metres()
}

/// Position and task-orientation errors of a tool pose against the target.
pub fn task_errors(
    robot: &Robot,
    q: &[f64],
    target: &nalgebra::IsometryMatrix3<f64>,
    task: Task,
) -> (f64, f64) {
    pose_error(robot, q, target, task)
}

/// The core's method for the UI's choice.
pub fn core_method(method: Method) -> IkMethod {
    match method {
        Method::DampedLeastSquares => IkMethod::DampedLeastSquares,
        Method::PseudoInverse => IkMethod::PseudoInverse,
        Method::Gradient => IkMethod::JacobianTranspose { alpha: None },
        Method::ClosedForm => IkMethod::ClosedForm,
    }
}

/// The replay of the last full solve.
#[derive(Debug, Clone, Default)]
pub struct Replay {
    /// The run, with its trace.
    pub run: Option<IkResult>,
    /// The iteration shown.
    pub step: usize,
    /// The q before the run (to go back).
    pub start_q: Vec<f64>,
}

fn apply(app: &mut ArmLabApp, result: &IkResult) {
    app.set_q(result.q.clone());
    app.ik.iterations = result.iterations;
    app.ik.unreachable = result.unreachable;
    app.update_reached();
}

/// One drag frame: IK warm-started at the current q, each joint moving at most the
/// per-call limit. Errors (which only a broken target could cause) go to the message bar.
pub fn drag_solve(app: &mut ArmLabApp) {
    let method = core_method(app.session.method);
    let settings = IkSettings::drag();
    let result = app.solver.drag_step(
        &app.session.robot,
        &app.session.q,
        &app.target,
        app.session.task,
        method,
        &settings,
    );
    match result {
        Ok(result) => apply(app, &result),
        Err(e) => app.message = Some(e.to_string()),
    }
}

/// Shows the IK controls.
pub fn show(app: &mut ArmLabApp, ui: &mut egui::Ui) {
    ui.strong("Inverse kinematics");
    let has_closed_form = closed_form_family(&app.session.robot).is_some();
    if app.session.method == Method::ClosedForm && !has_closed_form {
        app.session.method = Method::DampedLeastSquares;
    }
    egui::Grid::new("ik_controls").num_columns(2).show(ui, |ui| {
        let task_label_id = ui.label("Task").id;
        let before = app.session.task;
        egui::ComboBox::from_id_salt("ik_task")
            .selected_text(task_label(app.session.task))
            .width(200.0)
            .show_ui(ui, |ui| {
                for task in [
                    Task::Position,
                    Task::PositionAndAxis(ToolAxis::Z),
                    Task::PositionAndAxis(ToolAxis::X),
                    Task::PositionAndAxis(ToolAxis::Y),
                    Task::FullPose,
                ] {
                    ui.selectable_value(&mut app.session.task, task, task_label(task));
                }
            })
            .response
            .labelled_by(task_label_id);
        if app.session.task != before {
            app.update_reached();
        }
        ui.end_row();
        let method_label_id = ui.label("Method").id;
        egui::ComboBox::from_id_salt("ik_method")
            .selected_text(app.session.method.label())
            .width(200.0)
            .show_ui(ui, |ui| {
                for m in Method::ALL {
                    let enabled = m != Method::ClosedForm || has_closed_form;
                    ui.add_enabled_ui(enabled, |ui| {
                        ui.selectable_value(&mut app.session.method, m, m.label())
                            .on_disabled_hover_text("This robot has no closed-form IK here (the planar 2R, the RRR and the UR10 do).");
                    });
                }
            })
            .response
            .labelled_by(method_label_id);
        ui.end_row();
    });
    ui.horizontal(|ui| {
        if ui.button("Snap target to gripper").clicked() {
            app.snap_target();
        }
        if ui
            .button("Solve")
            .on_hover_text(
                "Run the method to convergence from the current pose and record every iteration",
            )
            .clicked()
        {
            full_solve(app);
        }
    });
    let unit = app.session.robot.length_unit.symbol();
    let (text, color) = if app.ik.reached {
        ("reached".to_string(), style::REACHED)
    } else if app.ik.unreachable {
        (
            "out of reach (closest pose shown)".to_string(),
            style::UNREACHABLE,
        )
    } else {
        ("not at the target".to_string(), style::PENDING)
    };
    ui.colored_label(color, format!("Target {text}"));
    ui.label(format!(
        "error: {:.3e} {unit}, {:.3e} rad  ·  {} iterations",
        app.ik.position_error, app.ik.orientation_error, app.ik.iterations
    ));
    replay_ui(app, ui);
}

fn task_label(task: Task) -> &'static str {
    match task {
        Task::Position => "Position only (3 rows)",
        Task::PositionAndAxis(ToolAxis::X) => "Position + tool x axis (5D)",
        Task::PositionAndAxis(ToolAxis::Y) => "Position + tool y axis (5D)",
        Task::PositionAndAxis(ToolAxis::Z) => "Position + tool z axis (5D)",
        Task::FullPose => "Full pose (6 rows)",
    }
}

/// Runs the chosen method to convergence with a trace, for replay.
pub fn full_solve(app: &mut ArmLabApp) {
    let settings = IkSettings {
        record_trace: true,
        restarts: 0,
        max_iterations: 2000,
        budget: 2000,
        ..IkSettings::default()
    };
    let start_q = app.session.q.clone();
    match app.solver.solve(
        &app.session.robot,
        &app.target,
        app.session.task,
        &start_q,
        core_method(app.session.method),
        &settings,
    ) {
        Ok(result) => {
            apply(app, &result);
            app.replay = Replay {
                step: result.trace.len().saturating_sub(1),
                run: Some(result),
                start_q,
            };
        }
        Err(e) => app.message = Some(e.to_string()),
    }
}

fn replay_ui(app: &mut ArmLabApp, ui: &mut egui::Ui) {
    let Some(run) = app.replay.run.clone() else {
        return;
    };
    if run.trace.is_empty() {
        return;
    }
    ui.separator();
    ui.label(format!(
        "Last solve: {} iterations, {}",
        run.iterations,
        if run.success {
            "converged"
        } else if run.unreachable {
            "target out of reach"
        } else {
            "stopped"
        }
    ));
    let last = run.trace.len() - 1;
    let mut step = app.replay.step.min(last);
    let changed = ui
        .add(egui::Slider::new(&mut step, 0..=last).text("iteration"))
        .on_hover_text("Replay the run: the arm shows q after this iteration")
        .changed();
    let s = &run.trace[step];
    ui.monospace(format!(
        "‖e‖ = {:.3e}   step = {:.3e}   λ = {:.2e}",
        s.error, s.step, s.damping
    ));
    let raw: Vec<String> = s.raw_q.iter().map(|v| format!("{v:.3}")).collect();
    let kept: Vec<String> = s.q.iter().map(|v| format!("{v:.3}")).collect();
    ui.label(format!("raw q: {}", raw.join(", ")));
    ui.label(format!("kept q: {}", kept.join(", ")));
    error_plot(ui, &run, step);
    if changed {
        app.replay.step = step;
        let q = run.trace[step].q.clone();
        app.set_q(q);
    }
}

/// The error per iteration on a log scale.
fn error_plot(ui: &mut egui::Ui, run: &IkResult, current: usize) {
    let (rect, _) = ui.allocate_exact_size(
        egui::vec2(ui.available_width().min(300.0), 90.0),
        egui::Sense::hover(),
    );
    let painter = ui.painter_at(rect);
    painter.rect_stroke(
        rect,
        2.0,
        ui.visuals().widgets.noninteractive.bg_stroke,
        egui::StrokeKind::Inside,
    );
    let errs: Vec<f64> = run
        .trace
        .iter()
        .map(|s| s.error.max(1e-16).log10())
        .collect();
    let (lo, hi) = errs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    let span = (hi - lo).max(1e-9);
    let n = errs.len().max(2) - 1;
    let to_screen = |i: usize, v: f64| {
        egui::pos2(
            rect.left() + rect.width() * i as f32 / n as f32,
            rect.bottom() - rect.height() * ((v - lo) / span) as f32,
        )
    };
    let points: Vec<egui::Pos2> = errs
        .iter()
        .enumerate()
        .map(|(i, v)| to_screen(i, *v))
        .collect();
    painter.add(egui::Shape::line(
        points,
        egui::Stroke::new(1.5, style::PENDING),
    ));
    if let Some(v) = errs.get(current) {
        painter.circle_filled(to_screen(current, *v), 3.5, style::HIGHLIGHT);
    }
    painter.text(
        rect.left_top() + egui::vec2(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        format!("log10 ‖e‖: {hi:.1} … {lo:.1}"),
        egui::FontId::proportional(11.0),
        ui.visuals().text_color(),
    );
}
