//! The joint panel: a slider and a number field per joint within its limits, degrees or
//! radians, prismatic joints in length units; zero and home.

use armlab_core::redundancy::{SelfMotionError, self_motion};
use armlab_core::{Joint, JointKind, tool_velocity};
use armlab_text::Sentence;

use crate::app::panels::Panel;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::{HoverSource, Model};
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::style;
use crate::app::widgets::toggles::overlay_checkbox;
use armlab_session::format::number;
use armlab_session::settings::Overlay;
use armlab_text::Key;

/// The joint sliders, the self-motion slider of a redundant arm and the joint-speed rows.
/// Every joint value is the model's q; the panel keeps its sliders' ids (so a shortcut
/// can focus one), where the self-motion slider started, and whether q̇ plays.
#[derive(Debug, Clone, Default)]
pub struct JointsPanel {
    sliders: Vec<egui::Id>,
    self_motion: Option<SelfMotionSlider>,
    playing: bool,
}

/// The self-motion slider's state: the pose it started from (s = 0), its value, the q it
/// last set (another change of q starts it anew) and what the last sweep reported.
#[derive(Debug, Clone)]
struct SelfMotionSlider {
    anchor: Vec<f64>,
    s: f64,
    set_q: Vec<f64>,
    note: Option<String>,
}

impl JointsPanel {
    /// Gives joint `i`'s slider the keyboard (the arrow keys then move it).
    pub fn focus(&self, i: usize, ctx: &egui::Context) {
        if let Some(id) = self.sliders.get(i) {
            ctx.memory_mut(|m| m.request_focus(*id));
        }
    }
}

impl Panel for JointsPanel {
    /// Draws the sliders; a change moves the arm at once.
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        ui.horizontal(|ui| {
            if ui
                .button(tr(model, Key::Zero))
                .on_hover_text(tr(model, Key::ZeroHint))
                .clicked()
            {
                model.set_q_exact(vec![0.0; model.robot().dof()]);
            }
            if ui
                .button(tr(model, Key::Home))
                .on_hover_text(tr(model, Key::HomeHint))
                .clicked()
            {
                model.set_q_exact(model.robot().home());
            }
        });
        let (q, changed, slider_under) = self.sliders_ui(model, ui, points);
        if changed {
            model.set_q_exact(q);
        }
        // The joint under the pointer highlights its link in 3D and its matrices (and the
        // symbolic entries that depend on it).
        model.set_hovered_link(slider_under, HoverSource::Joints);
        self.self_motion_ui(model, ui);
        self.speeds_ui(model, ui);
    }
}

impl JointsPanel {
    /// The joints' sliders; returns q as they set it, whether one changed it, and the
    /// joint (from 1) whose slider is under the pointer.
    fn sliders_ui(
        &mut self,
        model: &Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
    ) -> (Vec<f64>, bool, Option<usize>) {
        let mut q = model.q().to_vec();
        let mut changed = false;
        let mut slider_under = None;
        self.sliders.clear();
        // The slider fills the column: the name and the value box beside it stay, unless
        // that leaves the rail too short to set a joint by the degree; then the name and
        // the value box share a line and the rail has the next one to itself.
        let stacked = joints_rail(ui, model) < fine_rail(ui, model);
        let mut row = |ui: &mut egui::Ui, i: usize, joint: &Joint, q: &mut f64| {
            let response = joint_slider(ui, model, (i, joint), q, stacked);
            self.sliders.push(response.id);
            // Where the slider's minimum and maximum values sit, for the browser tests:
            // egui insets the rail's ends by the handle's radius, a 2.5th of the
            // slider's height.
            let r = response.rect;
            let inset = r.height() / 2.5;
            let rail = ui.spacing().slider_width;
            let y = r.center().y;
            points.insert(
                format!("slider-{}-min", i + 1),
                egui::pos2(r.left() + inset, y),
            );
            points.insert(
                format!("slider-{}-max", i + 1),
                egui::pos2(r.left() + rail - inset, y),
            );
            changed |= response.changed();
            if response.hovered() {
                slider_under = Some(i + 1);
            }
        };
        let joints = &model.robot().joints;
        if stacked {
            ui.scope(|ui| {
                ui.spacing_mut().slider_width = style::room(ui).max(40.0);
                for (i, joint) in joints.iter().enumerate() {
                    row(ui, i, joint, &mut q[i]);
                }
            });
        } else {
            egui::Grid::new("joint_sliders")
                .num_columns(2)
                .striped(true)
                .show(ui, |ui| {
                    for (i, joint) in joints.iter().enumerate() {
                        row(ui, i, joint, &mut q[i]);
                        ui.end_row();
                    }
                });
        }
        (q, changed, slider_under)
    }
}

/// A speed slider's range: ±1 rad/s, or ±a quarter of the reach per second for a
/// prismatic joint.
fn speed_range(model: &Model, joint: &Joint) -> f64 {
    match joint.kind {
        JointKind::Revolute => 1.0,
        JointKind::Prismatic => 0.25 * model.robot().reach(),
    }
}

/// The speed sliders' rail: what the fold's visible room leaves beside the name and the
/// widest value. The joints' rail, set without the fold's indent and for other values,
/// pushed the speeds (then with their units, "0.00 rad/s") past a projector's column, and
/// the tool's v and ω under them wrapped at that width, out of sight.
fn speed_rail(ui: &mut egui::Ui, model: &Model) {
    let widest = model
        .robot()
        .joints
        .iter()
        .map(|j| format!("-{:.2}", speed_range(model, j)))
        .max_by_key(|t| t.len())
        .unwrap_or_default();
    let font = egui::TextStyle::Body.resolve(ui.style());
    let name_width = style::text_width(ui, "q̇00", &font);
    style::fit_rail(ui, name_width, &widest);
}

/// The joint sliders' rail: what the visible room leaves beside the widest name (the
/// grid's name column is at least egui's interact width) and the widest value at either
/// limit. A fixed 110 points for both would leave a prismatic joint's "-0.300 m" past a
/// phone's edge. Returns the rail's length.
fn joints_rail(ui: &mut egui::Ui, model: &Model) -> f32 {
    let robot = model.robot();
    let degrees = model.settings().degrees;
    let unit = robot.length_unit.symbol();
    let widest = robot
        .joints
        .iter()
        .flat_map(|j| [j.limits.min, j.limits.max].map(|v| (j.kind, v)))
        .map(|(kind, v)| match kind {
            JointKind::Revolute if degrees => format!("{:.1}°", v.to_degrees()),
            JointKind::Revolute => format!("{v:.3} rad"),
            JointKind::Prismatic => format!("{v:.3} {unit}"),
        })
        .max_by_key(|t| t.chars().count())
        .unwrap_or_default();
    let name = format!("θ{}", robot.dof());
    let font = egui::TextStyle::Body.resolve(ui.style());
    let name_width = style::text_width(ui, &name, &font).max(ui.spacing().interact_size.x);
    style::fit_rail(ui, name_width, &widest)
}

/// The self-motion slider (±3 rad, in steps of 0.05 rad: an arrow key moves it by one
/// step whatever the rail's width), named as [`style::named_slider`] places it.
fn self_motion_slider(ui: &mut egui::Ui, model: &Model, s: &mut f64) -> egui::Response {
    let (name, hint) = (tr(model, Key::SelfMotion), tr(model, Key::SelfMotionHint));
    style::named_slider(ui, (name, hint), "-3.00 rad", |ui| {
        style::slider(
            ui,
            egui::Slider::new(s, -3.0..=3.0)
                .suffix(" rad")
                .step_by(0.05)
                .fixed_decimals(2),
        )
    })
}

impl JointsPanel {
    /// The self-motion slider, for an arm with exactly one joint more than task rows.
    fn self_motion_ui(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        if model.robot().dof() != model.task().rows() + 1 {
            self.self_motion = None;
            return;
        }
        let q = model.q().to_vec();
        let state = match self.self_motion.take() {
            Some(state) if state.set_q == q => state,
            _ => SelfMotionSlider {
                anchor: q.clone(),
                s: 0.0,
                set_q: q,
                note: None,
            },
        };
        let mut state = state;
        ui.separator();
        let mut s = state.s;
        let response = self_motion_slider(ui, model, &mut s);
        if response.changed() {
            let unit = model.robot().length_unit.symbol();
            match self_motion(model.robot(), &state.anchor, model.task(), s) {
                Ok(m) => {
                    let mut note = trf(
                        model,
                        Key::SelfMotionDrift,
                        &[
                            &number(m.max_position_error, 1),
                            &unit,
                            &number(m.max_orientation_error, 1),
                        ],
                    );
                    if let Some(j) = m.stopped_by {
                        note =
                            format!("{} {note}", trf(model, Key::SelfMotionStopped, &[&(j + 1)]));
                    }
                    state.s = m.travelled;
                    model.set_q_exact(m.q);
                    state.set_q = model.q().to_vec();
                    state.note = Some(note);
                }
                Err(SelfMotionError::Singular) => {
                    state.note = Some(tr(model, Key::SelfMotionSingular).to_string());
                }
                Err(SelfMotionError::Robot(e)) => {
                    state.note = Some(e.sentence(model.settings().lang))
                }
                Err(e) => state.note = Some(e.to_string()),
            }
        }
        if let Some(note) = &state.note {
            ui.label(egui::RichText::new(note).small());
        }
        overlay_checkbox(
            model,
            ui,
            Overlay::NullSpace,
            Key::DrawNullSpace,
            Key::SelfMotionHint,
        );
        self.self_motion = Some(state);
    }

    /// Velocity kinematics: a q̇ slider per joint, v and ω at the tool, play.
    fn speeds_ui(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let header = egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::JointSpeeds),
        ))
        .id_salt("joint_speeds")
        .default_open(false)
        .show(ui, |ui| {
            ui.label(egui::RichText::new(tr(model, Key::JointSpeedsHint)).small());
            let speeds = speed_rows(model, ui);
            twist_line(model, ui, &speeds);
            crate::app::widgets::style::wrapped(ui, |ui| {
                let label = if self.playing { Key::Pause } else { Key::Play };
                if ui
                    .button(tr(model, label))
                    .on_hover_text(tr(model, Key::PlayHint))
                    .clicked()
                {
                    self.playing = !self.playing;
                }
                if ui.button(tr(model, Key::Stop)).clicked() {
                    model.set_joint_speeds(&[]);
                    self.playing = false;
                }
                overlay_checkbox(
                    model,
                    ui,
                    Overlay::Twist,
                    Key::DrawTwist,
                    Key::JointSpeedsHint,
                );
            });
        });
        if header.body_returned.is_none() {
            self.playing = false;
        }
        if self.playing {
            self.play_step(model, ui.ctx());
        }
    }

    /// Moves q by q̇·dt for this frame; stops (and says which joint) at a limit.
    fn play_step(&mut self, model: &mut Model, ctx: &egui::Context) {
        let dt = f64::from(ctx.input(|i| i.stable_dt)).min(0.1);
        let speeds = model.joint_speeds();
        let mut q = model.q().to_vec();
        let mut stopped = None;
        for (i, joint) in model.robot().joints.iter().enumerate() {
            let next = q[i] + speeds[i] * dt;
            if !joint.limits.contains(next, 0.0) {
                stopped = Some(i);
            }
            q[i] = next.clamp(joint.limits.min, joint.limits.max);
        }
        model.set_q_exact(q);
        if let Some(j) = stopped {
            self.playing = false;
            model.set_message(crate::app::state::model::Message::info(trf(
                model,
                Key::SelfMotionStopped,
                &[&(j + 1)],
            )));
        } else {
            ctx.request_repaint();
        }
    }
}

/// The most degrees a pixel of a joint's rail may stand for: at more, a drag of a few
/// pixels jumps past the angle wanted (a 35-pixel rail for ±360° made a 17-pixel drag
/// turn a joint by 290°).
const MAX_DEGREES_PER_PIXEL: f32 = 3.0;

/// The shortest rail (points) on which every revolute joint's range keeps to
/// [`MAX_DEGREES_PER_PIXEL`]; a point is the zoom's count of CSS pixels.
fn fine_rail(ui: &egui::Ui, model: &Model) -> f32 {
    let widest = model
        .robot()
        .joints
        .iter()
        .filter(|j| j.kind == JointKind::Revolute)
        .map(|j| (j.limits.max - j.limits.min).to_degrees() as f32)
        .fold(0.0, f32::max);
    widest / (MAX_DEGREES_PER_PIXEL * ui.ctx().zoom_factor())
}

/// A joint's value as its slider shows it: the factor from the model's unit, the suffix
/// and the decimals (none: egui's own).
pub(crate) fn shown(model: &Model, joint: &Joint) -> (f64, String, Option<usize>) {
    match joint.kind {
        JointKind::Revolute if model.settings().degrees => {
            (180.0 / std::f64::consts::PI, "°".into(), Some(1))
        }
        JointKind::Revolute => (1.0, " rad".into(), Some(3)),
        JointKind::Prismatic => (
            1.0,
            format!(" {}", model.robot().length_unit.symbol()),
            None,
        ),
    }
}

/// One joint's label and slider (degrees or radians, or the length unit). `stacked`: the
/// name and a value box on one line, the rail alone on the next.
fn joint_slider(
    ui: &mut egui::Ui,
    model: &Model,
    (i, joint): (usize, &Joint),
    value: &mut f64,
    stacked: bool,
) -> egui::Response {
    let symbol = crate::app::widgets::math::joint_symbol(i, joint.kind);
    let (scale, suffix, decimals) = shown(model, joint);
    let range = joint.limits.min * scale..=joint.limits.max * scale;
    let mut v = *value * scale;
    let mut typed = false;
    let label = if stacked {
        ui.horizontal(|ui| {
            let label = ui.label(&symbol).on_hover_text(&joint.name);
            let mut field = egui::DragValue::new(&mut v)
                .suffix(&suffix)
                .range(range.clone())
                .clamp_existing_to_range(false)
                .speed((range.end() - range.start()) / 1000.0);
            if let Some(d) = decimals {
                field = field.fixed_decimals(d);
            }
            typed = ui.add(field).labelled_by(label.id).changed();
            label
        })
        .inner
    } else {
        ui.label(&symbol).on_hover_text(&joint.name)
    };
    let mut slider = egui::Slider::new(&mut v, range)
        .suffix(suffix.clone())
        .show_value(!stacked)
        .clamping(egui::SliderClamping::Never);
    if let Some(d) = decimals {
        slider = slider.fixed_decimals(d);
    }
    let mut response = style::slider(ui, slider);
    if typed {
        response.mark_changed();
    }
    if response.changed() {
        *value = v / scale;
    }
    // A screen reader says the joint's symbol and its value as shown: "θ2, −63.0°".
    let spoken = match decimals {
        Some(d) => format!("{v:.d$}{suffix}"),
        None => format!("{v}{suffix}"),
    }
    .replace('-', "\u{2212}");
    let response = response.labelled_by(label.id);
    ui.ctx().accesskit_node_builder(response.id, |node| {
        node.set_label(symbol);
        node.set_value(spoken);
    });
    response
}

/// The q̇ sliders, their units once above them; returns the speeds as set.
fn speed_rows(model: &mut Model, ui: &mut egui::Ui) -> Vec<f64> {
    // The units once, above the sliders: beside each value they did not
    // fit a projector's column.
    let robot = model.robot();
    let units = if robot.joints.iter().any(|j| j.kind == JointKind::Prismatic) {
        let unit = robot.length_unit.symbol();
        trf(model, Key::JointSpeedsUnitsPrismatic, &[&unit])
    } else {
        tr(model, Key::JointSpeedsUnits).to_string()
    };
    ui.label(egui::RichText::new(units).small());
    let mut speeds = model.joint_speeds();
    let mut changed = false;
    speed_rail(ui, model);
    egui::Grid::new("joint_speed_rows")
        .num_columns(2)
        .min_col_width(0.0)
        .show(ui, |ui| {
            for (i, joint) in model.robot().joints.iter().enumerate() {
                let range = speed_range(model, joint);
                ui.label(format!("q̇{}", i + 1));
                changed |=
                    style::slider(ui, egui::Slider::new(&mut speeds[i], -range..=range)).changed();
                ui.end_row();
            }
        });
    if changed {
        model.set_joint_speeds(&speeds);
    }
    speeds
}

/// The tool's twist for these joint speeds: v and ω.
fn twist_line(model: &Model, ui: &mut egui::Ui, speeds: &[f64]) {
    let twist = tool_velocity(model.jacobian(), speeds);
    let v = format!(
        "{}, {}, {}",
        number(twist[0], 2),
        number(twist[1], 2),
        number(twist[2], 2)
    );
    let w = format!(
        "{}, {}, {}",
        number(twist[3], 3),
        number(twist[4], 3),
        number(twist[5], 3)
    );
    let unit = model.robot().length_unit.symbol();
    ui.monospace(trf(model, Key::ToolTwist, &[&v, &unit, &w]));
}
