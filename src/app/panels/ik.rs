//! The IK controls: task (position / 5D with a tool axis / full pose), method, "snap
//! target to gripper", and a full solve whose iterations can be replayed step by step with
//! the error per iteration. The drag step itself is the model's ([`Model::drag_step`]).

use armlab_core::ik::{IkResult, Reach};
use armlab_core::{IkMethod, Task, wrapped_equivalent};
use armlab_text::Labelled;

use armlab_text::Key;

use crate::app::panels::Panel;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;
use crate::app::state::notebook::NotebookDemo;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::plot;
use crate::app::widgets::style;
use armlab_session::format::{error_value, fixed};

/// The IK panel; the replay of the last full solve is the model's ([`Model::replay`]).
#[derive(Debug, Clone, Default)]
pub struct IkPanel {
    /// The Task and Method menus' widths ([`MenuWidths`]), measured once per language,
    /// text size and choice rather than in every frame of a drag.
    menu_widths: Option<MenuWidths>,
}

/// The widths the IK panel's two menus share: their labels' (the wider), the menus' (the
/// widest choice of either), and what the two chosen names need beside their labels (the
/// more of the two: both menus go beside or both under), for one language, text size,
/// pixel density and pair of choices.
#[derive(Debug, Clone, Copy, PartialEq)]
struct MenuWidths {
    /// What they were measured for: the language, the button font's size and the points
    /// per pixel as bits, and the chosen task and method.
    key: (armlab_text::Lang, u32, u32, Task, IkMethod),
    label: f32,
    menu: f32,
    need: f32,
}

impl MenuWidths {
    /// The widths for `ui`'s style in the model's language, measured again only when the
    /// kept ones were measured for another language, text size, pixel density or choice.
    fn of(kept: &mut Option<MenuWidths>, model: &Model, ui: &egui::Ui) -> MenuWidths {
        let font = egui::TextStyle::Button.resolve(ui.style());
        let key = (
            model.settings().lang,
            font.size.to_bits(),
            ui.ctx().pixels_per_point().to_bits(),
            model.task(),
            model.method(),
        );
        if let Some(widths) = kept.filter(|w| w.key == key) {
            return widths;
        }
        let label = [Key::Task, Key::Method]
            .map(|k| style::text_width(ui, tr(model, k), &font))
            .into_iter()
            .fold(0.0, f32::max);
        let choices: Vec<&str> = Task::ALL
            .iter()
            .map(|t| t.label_key())
            .chain(IkMethod::ALL.iter().map(|m| m.label_key()))
            .map(|k| tr(model, k))
            .collect();
        let widths = MenuWidths {
            key,
            label,
            menu: style::menu_width(ui, &choices),
            need: [model.task().label_key(), model.method().label_key()]
                .map(|k| style::menu_need(ui, tr(model, k)))
                .into_iter()
                .fold(0.0, f32::max),
        };
        *kept = Some(widths);
        widths
    }
}

impl IkPanel {
    /// Runs the chosen method to convergence with a trace and keeps it for replay.
    pub fn solve(&mut self, model: &mut Model) {
        if let Some(run) = model.solve_with_trace() {
            model.keep_replay(run, None);
        }
    }
}

impl IkPanel {
    /// The notebook's two runs, one click each; after a run, its answer as the notebook
    /// printed it (never wrapped) beside the wrapped equivalent.
    fn notebook_ui(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::NotebookRuns),
        ))
        .id_salt("notebook_runs")
        .default_open(false)
        .show(ui, |ui| {
            ui.label(egui::RichText::new(tr(model, Key::NotebookHint)).small());
            crate::app::widgets::style::wrapped(ui, |ui| {
                for (demo, key) in [
                    (NotebookDemo::Newton, Key::NotebookNewton),
                    (NotebookDemo::Gradient, Key::NotebookGradient),
                ] {
                    if ui.button(tr(model, key)).clicked()
                        && let Some(run) = demo.run(model)
                    {
                        model.keep_replay(run, Some(demo));
                    }
                }
            });
            let Some((demo, run)) = model.replay().and_then(|r| Some((r.demo?, &r.run))) else {
                return;
            };
            let list = |q: &[f64]| {
                let v: Vec<String> = q.iter().map(|v| format!("{v:.8}")).collect();
                format!("[{}]", v.join(", "))
            };
            let wrapped = wrapped_equivalent(model.robot(), &run.q);
            ui.monospace(trf(
                model,
                Key::NotebookRaw,
                &[&list(&run.q), &demo.printed()],
            ));
            ui.monospace(trf(model, Key::NotebookWrapped, &[&list(&wrapped)]));
        });
    }
}

impl Panel for IkPanel {
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        // One width for both menus and their labels, so that they line up and keep their
        // size whichever is chosen; both beside their labels or both under them.
        let widths = MenuWidths::of(&mut self.menu_widths, model, ui);
        task_menu(model, ui, widths.label, (widths.need, widths.menu));
        method_menu(model, ui, widths.label, (widths.need, widths.menu));
        crate::app::widgets::style::wrapped(ui, |ui| {
            if ui.button(tr(model, Key::SnapTarget)).clicked() {
                model.snap_target();
            }
            let solve = ui
                .button(tr(model, Key::Solve))
                .on_hover_text(tr(model, Key::SolveHint));
            points.insert("ik-solve", solve.rect.center());
            if solve.clicked() {
                self.solve(model);
            }
        });
        status(model, ui);
        replay_ui(model, ui);
        self.notebook_ui(model, ui);
        crate::app::panels::solutions::solutions_ui(model, ui);
        crate::app::panels::workspace::workspace_ui(model, ui);
    }
}

fn task_menu(model: &mut Model, ui: &mut egui::Ui, label_width: f32, size: (f32, f32)) {
    let mut task = model.task();
    crate::app::widgets::style::menu_row(
        ui,
        "ik_task",
        (tr(model, Key::Task), label_width),
        tr(model, task.label_key()),
        size,
        |ui| {
            for t in Task::ALL {
                ui.selectable_value(&mut task, t, tr(model, t.label_key()));
            }
        },
    );
    model.set_task(task);
}

fn method_menu(model: &mut Model, ui: &mut egui::Ui, label_width: f32, size: (f32, f32)) {
    let has_closed_form = model.has_closed_form();
    let mut method = model.method();
    crate::app::widgets::style::menu_row(
        ui,
        "ik_method",
        (tr(model, Key::Method), label_width),
        tr(model, method.label_key()),
        size,
        |ui| {
            for m in IkMethod::ALL {
                let enabled = m != IkMethod::ClosedForm || has_closed_form;
                ui.add_enabled_ui(enabled, |ui| {
                    ui.selectable_value(&mut method, m, tr(model, m.label_key()))
                        .on_disabled_hover_text(tr(model, Key::NoClosedFormHint));
                });
            }
        },
    );
    if method != model.method() {
        model.set_method(method);
    }
}

/// The target's status in its colour, and the errors.
fn status(model: &Model, ui: &mut egui::Ui) {
    let ik = model.ik();
    let reach = model.shown_reach();
    let text = match reach {
        Reach::Reached => Key::TargetReached,
        Reach::OutOfReach => Key::TargetOutOfReach,
        Reach::Pending => Key::TargetPending,
    };
    ui.colored_label(style::reach_color(reach), tr(model, text));
    if let Some((asked, taken)) = model.branch_switch() {
        let words = |b| crate::app::state::branches::branch_words(model, &b);
        ui.colored_label(
            style::WARNING,
            trf(model, Key::BranchVanished, &[&words(asked), &words(taken)]),
        );
    }
    ui.label(trf(
        model,
        Key::IkErrors,
        &[
            &error_value(ik.position_error, 3),
            &model.robot().length_unit.symbol(),
            &error_value(ik.orientation_error, 3),
            &ik.iterations,
        ],
    ));
}

fn replay_ui(model: &mut Model, ui: &mut egui::Ui) {
    let Some(replay) = model.replay() else {
        return;
    };
    let run = &replay.run;
    if run.trace.is_empty() {
        return;
    }
    ui.separator();
    let outcome = if run.success {
        Key::SolveConverged
    } else if run.unreachable {
        Key::SolveOutOfReach
    } else {
        Key::SolveStopped
    };
    ui.label(trf(
        model,
        Key::LastSolve,
        &[&run.iterations, &tr(model, outcome)],
    ));
    let last = run.trace.len() - 1;
    let mut step = replay.step.min(last);
    let name = (tr(model, Key::Iteration), tr(model, Key::ReplayHint));
    let changed = style::named_slider(ui, name, &last.to_string(), |ui| {
        style::slider(ui, egui::Slider::new(&mut step, 0..=last))
    })
    .changed();
    let s = &run.trace[step];
    ui.monospace(trf(
        model,
        Key::StepLine,
        &[
            &error_value(s.error, 3),
            &error_value(s.step, 3),
            &error_value(s.damping, 3),
        ],
    ));
    let raw: Vec<String> = s.raw_q.iter().map(|v| fixed(*v, 3)).collect();
    let kept: Vec<String> = s.q.iter().map(|v| fixed(*v, 3)).collect();
    ui.label(trf(model, Key::RawQ, &[&raw.join(", ")]));
    ui.label(trf(model, Key::KeptQ, &[&kept.join(", ")]));
    error_plot(model, ui, run, step);
    if changed {
        model.replay_step(step);
    }
}

/// The error per iteration on a log scale (log10 ‖e‖ from the top to the bottom of the
/// box), the replayed iteration marked.
fn error_plot(model: &Model, ui: &mut egui::Ui, run: &IkResult, current: usize) {
    let errs: Vec<f64> = run
        .trace
        .iter()
        .map(|s| s.error.max(1e-16).log10())
        .collect();
    let (lo, hi) = plot::range_of(errs.iter().copied());
    let n = errs.len().max(2) - 1;
    let plot = plot::PlotBox::allocate(ui, 90.0, (0.0, n as f64), (lo, hi));
    plot.line(
        ui,
        errs.iter().enumerate().map(|(i, v)| [i as f64, *v]),
        egui::Stroke::new(1.5, style::PENDING),
    );
    if let Some(v) = errs.get(current) {
        plot.dot(ui, current as f64, *v, style::HIGHLIGHT);
    }
    let caption = trf(
        model,
        Key::ErrorPlotRange,
        &[&format!("{hi:.1}"), &format!("{lo:.1}")],
    );
    plot.describe(ui, || {
        let errors: Vec<String> = run
            .trace
            .iter()
            .map(|s| format!("{:.1e}", s.error))
            .collect();
        trf(
            model,
            Key::PlotIterations,
            &[
                &caption,
                &run.trace.len().saturating_sub(1),
                &errors.join(", "),
            ],
        )
    });
    plot.caption(ui, caption);
}
