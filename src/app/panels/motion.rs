//! The Motion panel (docs/kinematics.md §17): "move" (dragging the target or
//! Solve makes the arm drive to the IK answer with a controller instead of jumping), the
//! controller and its gains, the motor model and load, the time scale, a typed goal, the
//! measured response (overshoot, settling time, steady-state error) and the plots of
//! every joint's angle, speed and error against time with the goal lines and the dead
//! band, and the tool's distance to the target.
//!
//! Numbers are typed as text: a value that is not a number, or that the core's checks
//! refuse, gets a sentence under its field and the last good value stays in force.

use crate::app::widgets::draft::Draft;
use armlab_text::Sentence;
use std::collections::HashMap;

use egui::{Color32, Stroke};

use armlab_core::JointKind;
use armlab_core::collision::KeepOut;
use armlab_core::motion::{Controller, MotionSettings, PidGains, Series};
use armlab_core::profile::ProfileShape;
use armlab_text::{Key, echo};

use crate::app::panels::Panel;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;
use crate::app::state::motion_lab::SLOW_MOTION;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::view3d::jacobian::column_color;
use crate::app::widgets::plot::{self, PlotBox};
use crate::app::widgets::style;
use armlab_session::format::error_value;

/// The controller choices of the menu.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Choice {
    /// On/off with a dead band.
    OnOff,
    /// Proportional velocity control.
    P,
    /// PD on the joint's inertia.
    Pd,
    /// PID on the joint's inertia.
    Pid,
    /// Tracking a planned profile of this shape.
    Profile(ProfileShape),
}

impl Choice {
    /// Every choice, in menu order.
    pub const ALL: [Choice; 7] = [
        Choice::OnOff,
        Choice::P,
        Choice::Pd,
        Choice::Pid,
        Choice::Profile(ProfileShape::Trapezoidal),
        Choice::Profile(ProfileShape::Cubic),
        Choice::Profile(ProfileShape::Quintic),
    ];

    /// The choice a controller is.
    pub fn of(controller: &Controller) -> Choice {
        match controller {
            Controller::OnOff { .. } => Choice::OnOff,
            Controller::Proportional { .. } => Choice::P,
            Controller::Pid(g) if g.ki == 0.0 => Choice::Pd,
            Controller::Pid(_) => Choice::Pid,
            Controller::Profile { shape, .. } => Choice::Profile(*shape),
        }
    }

    /// Its id, as links write it: `onoff`, `p`, `pd`, `pid`, `trapezoidal`, `cubic`,
    /// `quintic`.
    pub fn id(self) -> &'static str {
        match self {
            Choice::OnOff => "onoff",
            Choice::P => "p",
            Choice::Pd => "pd",
            Choice::Pid => "pid",
            Choice::Profile(shape) => shape.id(),
        }
    }

    /// The choice of an id.
    pub fn from_id(id: &str) -> Option<Choice> {
        Choice::ALL.into_iter().find(|c| c.id() == id)
    }

    /// Its name in the menu.
    pub fn key(self) -> Key {
        match self {
            Choice::OnOff => Key::MotionOnOff,
            Choice::P => Key::MotionP,
            Choice::Pd => Key::MotionPd,
            Choice::Pid => Key::MotionPid,
            Choice::Profile(ProfileShape::Trapezoidal) => Key::MotionTrapezoid,
            Choice::Profile(ProfileShape::Cubic) => Key::MotionCubic,
            Choice::Profile(ProfileShape::Quintic) => Key::MotionQuintic,
        }
    }

    /// The controller of this choice with the default gains (0.01 dead band; K = 5/s;
    /// Kp = 100, Kd = 20, and Ki = 200 for PID; unsynchronised profiles).
    pub fn controller(self) -> Controller {
        match self {
            Choice::OnOff => Controller::OnOff { dead_band: 0.01 },
            Choice::P => Controller::Proportional { gain: 5.0 },
            Choice::Pd => Controller::Pid(PidGains {
                ki: 0.0,
                ..PidGains::default()
            }),
            Choice::Pid => Controller::Pid(PidGains::default()),
            Choice::Profile(shape) => Controller::Profile {
                shape,
                synchronised: false,
            },
        }
    }
}

/// A typed number of the panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Field {
    /// The on/off dead band.
    DeadBand,
    /// K of proportional control.
    Gain,
    /// Kp.
    Kp,
    /// Ki.
    Ki,
    /// Kd.
    Kd,
    /// The velocity servo's time constant τ.
    TimeConstant,
    /// The inertia I.
    Inertia,
    /// The friction b.
    Friction,
    /// The load L.
    Load,
    /// The time scale.
    TimeScale,
}

impl Field {
    /// Its label.
    fn key(self) -> Key {
        match self {
            Field::DeadBand => Key::MotionFieldDeadBand,
            Field::Gain => Key::MotionFieldGain,
            Field::Kp => Key::MotionFieldKp,
            Field::Ki => Key::MotionFieldKi,
            Field::Kd => Key::MotionFieldKd,
            Field::TimeConstant => Key::MotionFieldTau,
            Field::Inertia => Key::MotionFieldInertia,
            Field::Friction => Key::MotionFieldFriction,
            Field::Load => Key::MotionFieldLoad,
            Field::TimeScale => Key::MotionFieldTimeScale,
        }
    }

    /// Its value in the model now.
    fn value(self, model: &Model) -> f64 {
        let s = model.motion().settings();
        let g = match s.controller {
            Controller::Pid(g) => g,
            _ => PidGains::default(),
        };
        match self {
            Field::DeadBand => match s.controller {
                Controller::OnOff { dead_band } => dead_band,
                _ => 0.01,
            },
            Field::Gain => match s.controller {
                Controller::Proportional { gain } => gain,
                _ => 5.0,
            },
            Field::Kp => g.kp,
            Field::Ki => g.ki,
            Field::Kd => g.kd,
            Field::TimeConstant => s.plant.time_constant,
            Field::Inertia => s.plant.inertia,
            Field::Friction => s.plant.friction,
            Field::Load => s.plant.load,
            Field::TimeScale => model.motion().time_scale(),
        }
    }

    /// The settings with this field at `v`.
    fn apply(self, mut s: MotionSettings, v: f64) -> MotionSettings {
        match (self, &mut s.controller) {
            (Field::DeadBand, Controller::OnOff { dead_band }) => *dead_band = v,
            (Field::Gain, Controller::Proportional { gain }) => *gain = v,
            (Field::Kp, Controller::Pid(g)) => g.kp = v,
            (Field::Ki, Controller::Pid(g)) => g.ki = v,
            (Field::Kd, Controller::Pid(g)) => g.kd = v,
            (Field::TimeConstant, _) => s.plant.time_constant = v,
            (Field::Inertia, _) => s.plant.inertia = v,
            (Field::Friction, _) => s.plant.friction = v,
            (Field::Load, _) => s.plant.load = v,
            _ => {}
        }
        s
    }
}

/// The Motion panel; it owns the typed texts and their sentences.
#[derive(Debug, Clone, Default)]
pub struct MotionPanel {
    drafts: HashMap<Field, Draft>,
    goal_text: String,
    goal_error: Option<String>,
    /// The keep-out boxes' texts (`x, y, z, sx, sy, sz`) and sentences.
    boxes: Vec<Draft>,
    /// The model's robot-load count the box texts were written for (a robot file may
    /// bring other boxes).
    boxes_for: u64,
    /// The paths and waypoints part.
    paths: crate::app::panels::paths::PathPanel,
}

impl Panel for MotionPanel {
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        let mut on = model.motion().on();
        let r = ui
            .checkbox(&mut on, tr(model, Key::MotionMove))
            .on_hover_text(tr(model, Key::MotionMoveHint));
        points.insert("motion-move", r.rect.center());
        if r.changed() {
            model.set_motion_on(on);
        }
        self.controller_ui(model, ui);
        self.time_ui(model, ui, points);
        egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::MotionMotor),
        ))
        .id_salt("motion_motor")
        .default_open(false)
        .show(ui, |ui| {
            ui.label(egui::RichText::new(tr(model, Key::MotionMotorHint)).small());
            for field in [
                Field::TimeConstant,
                Field::Inertia,
                Field::Friction,
                Field::Load,
            ] {
                self.field_ui(model, ui, field);
            }
        });
        self.goal_ui(model, ui);
        self.paths.ui(model, ui, points);
        self.collision_ui(model, ui, points);
        measures_ui(model, ui);
        plots_ui(model, ui);
    }
}

impl MotionPanel {
    /// The controller menu and the fields of its gains.
    fn controller_ui(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let settings = *model.motion().settings();
        let current = Choice::of(&settings.controller);
        let mut chosen = current;
        style::fitted_menu(
            ui,
            "motion_controller",
            tr(model, Key::MotionController),
            tr(model, current.key()),
            None,
            |ui| {
                for choice in Choice::ALL {
                    ui.selectable_value(&mut chosen, choice, tr(model, choice.key()));
                }
            },
        );
        if chosen != current {
            let next = MotionSettings {
                controller: chosen.controller(),
                ..settings
            };
            // The defaults always pass the checks, unless a plant value forbids PD/PID
            // gains: then the sentence shows under the menu's fields.
            if let Err(e) = model.set_motion_settings(next) {
                self.drafts.entry(Field::Kp).or_default().error =
                    Some(e.sentence(model.settings().lang));
            }
            self.drafts.retain(|f, _| {
                matches!(
                    f,
                    Field::TimeConstant
                        | Field::Inertia
                        | Field::Friction
                        | Field::Load
                        | Field::TimeScale
                )
            });
        }
        let fields: &[Field] = match chosen {
            Choice::OnOff => &[Field::DeadBand],
            Choice::P => &[Field::Gain],
            Choice::Pd => &[Field::Kp, Field::Kd],
            Choice::Pid => &[Field::Kp, Field::Ki, Field::Kd],
            Choice::Profile(_) => &[],
        };
        for field in fields {
            self.field_ui(model, ui, *field);
        }
        if let Controller::Profile {
            shape,
            synchronised,
        } = model.motion().settings().controller
        {
            let mut sync = synchronised;
            if ui
                .checkbox(&mut sync, tr(model, Key::MotionSynchronised))
                .changed()
            {
                let next = MotionSettings {
                    controller: Controller::Profile {
                        shape,
                        synchronised: sync,
                    },
                    ..*model.motion().settings()
                };
                let _ = model.set_motion_settings(next);
            }
        }
    }

    /// Real time, slow motion, pause, one step, and the typed scale.
    fn time_ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        let scale = model.motion().time_scale();
        crate::app::widgets::style::wrapped(ui, |ui| {
            for (value, key, name) in [
                (1.0, Key::MotionRealTime, "motion-real-time"),
                (SLOW_MOTION, Key::MotionSlow, "motion-slow"),
                (0.0, Key::MotionPause, "motion-pause"),
            ] {
                let r = ui.add(crate::app::widgets::style::choice(
                    scale == value,
                    tr(model, key),
                ));
                points.insert(name, r.rect.center());
                if r.clicked() {
                    let _ = model.set_time_scale(value);
                    self.drafts.remove(&Field::TimeScale);
                }
            }
            let r = ui
                .add_enabled(
                    model.motion().on(),
                    egui::Button::new(tr(model, Key::MotionStep)),
                )
                .on_hover_text(tr(model, Key::MotionStepHint));
            points.insert("motion-step", r.rect.center());
            if r.clicked() {
                model.step_motion();
            }
            if ui.button(tr(model, Key::MotionClearPath)).clicked() {
                model.clear_trail();
            }
        });
        self.field_ui(model, ui, Field::TimeScale);
    }

    /// One typed number: label, text field, and the sentence when refused.
    fn field_ui(&mut self, model: &mut Model, ui: &mut egui::Ui, field: Field) {
        let value = field.value(model);
        let draft = self.drafts.entry(field).or_insert_with(|| Draft {
            text: echo::number(value),
            error: None,
        });
        if draft.error.is_none() && draft.text.trim().parse::<f64>().ok() != Some(value) {
            // Changed elsewhere (a button, a link): show the value in force.
            draft.text = echo::number(value);
        }
        let changed = ui
            .horizontal(|ui| {
                let label = ui.label(tr(model, field.key()));
                ui.add(
                    egui::TextEdit::singleline(&mut draft.text)
                        .id_salt(("motion_field", field as u8))
                        .desired_width(70.0),
                )
                .labelled_by(label.id)
                .changed()
            })
            .inner;
        if changed {
            let lang = model.settings().lang;
            draft.error = match draft.text.trim().parse::<f64>() {
                Err(_) => Some(armlab_text::fill(
                    lang,
                    Key::MotionNotNumber,
                    &[&echo::text(&draft.text)],
                )),
                Ok(v) if field == Field::TimeScale => {
                    model.set_time_scale(v).err().map(|e| e.sentence(lang))
                }
                Ok(v) => {
                    let next = field.apply(*model.motion().settings(), v);
                    model
                        .set_motion_settings(next)
                        .err()
                        .map(|e| e.sentence(lang))
                }
            };
        }
        if let Some(e) = &draft.error {
            ui.colored_label(style::ERROR, e);
        }
    }

    /// A typed goal q (degrees or radians as the joints panel shows them) and "Drive".
    fn goal_ui(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let label = ui.label(tr(model, Key::MotionGoalLabel));
        let go = ui
            .horizontal(|ui| {
                // The field takes what the button leaves of the visible room (up to 140
                // points): wider, it pushed Drive out of a projector's column and widened
                // the panel, so that the texts under it wrapped past its edge.
                let drive = tr(model, Key::MotionDrive);
                let font = egui::TextStyle::Button.resolve(ui.style());
                let spacing = ui.spacing();
                let button = style::text_width(ui, drive, &font) + 2.0 * spacing.button_padding.x;
                let field = (style::room(ui) - button - spacing.item_spacing.x).clamp(60.0, 140.0);
                let r = ui
                    .add(
                        egui::TextEdit::singleline(&mut self.goal_text)
                            .id_salt("motion_goal")
                            .hint_text(tr(model, Key::MotionGoalHint))
                            .desired_width(field),
                    )
                    .labelled_by(label.id);
                let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                let clicked = ui
                    .add_enabled(model.motion().on(), egui::Button::new(drive))
                    .clicked();
                enter || clicked
            })
            .inner;
        if go {
            self.goal_error = self.drive_to_typed(model).err();
        }
        if let Some(e) = &self.goal_error {
            ui.colored_label(style::ERROR, e);
        }
    }

    /// The collision switch, the contact, and the keep-out boxes.
    fn collision_ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        let mut on = model.motion().collisions_on();
        let r = ui
            .checkbox(&mut on, tr(model, Key::MotionCollisions))
            .on_hover_text(tr(model, Key::MotionCollisionsHint));
        points.insert("motion-collisions", r.rect.center());
        if r.changed() {
            model.set_collisions_on(on);
        }
        if on {
            use crate::app::state::motion_lab::{CheckerState, checker_state};
            match (checker_state(), model.motion().contact()) {
                (CheckerState::Loading, _) => {
                    ui.label(tr(model, Key::MotionCollisionsLoading));
                }
                (CheckerState::Failed(why), _) => {
                    let lang = model.settings().lang;
                    let why = armlab_text::echo::text_within(&why, 60);
                    let sentence = armlab_text::fill(lang, Key::MotionCollisionsFailed, &[&why]);
                    ui.colored_label(style::ERROR, sentence);
                }
                (CheckerState::Ready, Some(contact)) => {
                    ui.colored_label(style::ERROR, contact);
                }
                (CheckerState::Ready, None) => {
                    ui.label(tr(model, Key::MotionNoContact));
                }
            }
        }
        self.keep_outs_ui(model, ui);
    }

    /// The keep-out boxes: add one at the target, edit or remove each.
    fn keep_outs_ui(&mut self, model: &mut Model, ui: &mut egui::Ui) {
        let boxes = model.motion().keep_outs().to_vec();
        if self.boxes.len() != boxes.len() || self.boxes_for != model.robot_loads() {
            self.boxes_for = model.robot_loads();
            self.boxes = boxes
                .iter()
                .map(|b| Draft {
                    text: box_text(b),
                    error: None,
                })
                .collect();
        }
        egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::MotionKeepOuts),
        ))
        .id_salt("motion_keep_outs")
        .default_open(!boxes.is_empty())
        .show(ui, |ui| {
            if ui.button(tr(model, Key::MotionAddKeepOut)).clicked() {
                let side = model.robot().reach() * 0.15;
                let centre = nalgebra::Point3::from(model.target().translation.vector);
                let size = nalgebra::Vector3::repeat(side);
                let mut next = boxes.clone();
                if let Ok(b) = KeepOut::new(next.len() + 1, centre, size) {
                    next.push(b);
                }
                if let Err(e) = model.set_keep_outs(next) {
                    ui.colored_label(style::ERROR, e.sentence(model.settings().lang));
                }
                return;
            }
            let mut remove = None;
            for (i, draft) in self.boxes.iter_mut().enumerate() {
                let label = ui.label(format!("{} {}", i + 1, tr(model, Key::MotionKeepOutRow)));
                let changed = ui
                    .horizontal(|ui| {
                        let c = ui
                            .add(
                                egui::TextEdit::singleline(&mut draft.text)
                                    .id_salt(("motion_box", i))
                                    .desired_width(170.0),
                            )
                            .labelled_by(label.id)
                            .changed();
                        if ui.small_button(tr(model, Key::MotionRemove)).clicked() {
                            remove = Some(i);
                        }
                        c
                    })
                    .inner;
                if changed {
                    let lang = model.settings().lang;
                    draft.error = match parse_box(i, &draft.text, lang) {
                        Ok(b) => {
                            let mut next = model.motion().keep_outs().to_vec();
                            next[i] = b;
                            model.set_keep_outs(next).err().map(|e| e.sentence(lang))
                        }
                        Err(e) => Some(e),
                    };
                }
                if let Some(e) = &draft.error {
                    ui.colored_label(style::ERROR, e);
                }
            }
            if let Some(i) = remove {
                let mut next = model.motion().keep_outs().to_vec();
                next.remove(i);
                self.boxes.remove(i);
                let _ = model.set_keep_outs(next);
            }
        });
    }

    /// Reads the typed goal and sets it; the sentence when it is refused.
    fn drive_to_typed(&self, model: &mut Model) -> Result<(), String> {
        let lang = model.settings().lang;
        if !model.motion().on() {
            model.set_motion_on(true);
        }
        let mut goal = Vec::new();
        for part in self
            .goal_text
            .split([',', ';', ' '])
            .filter(|p| !p.is_empty())
        {
            let v: f64 = part
                .trim()
                .parse()
                .map_err(|_| armlab_text::fill(lang, Key::MotionNotNumber, &[&echo::text(part)]))?;
            goal.push(v);
        }
        let degrees = model.settings().degrees;
        for (v, joint) in goal.iter_mut().zip(&model.robot().joints) {
            if degrees && joint.kind == JointKind::Revolute {
                *v = v.to_radians();
            }
        }
        model.set_motion_goal(&goal).map_err(|e| e.sentence(lang))
    }
}

/// Every joint's overshoot, settling time and error now (the steady-state error once
/// settled).
fn measures_ui(model: &Model, ui: &mut egui::Ui) {
    let Some(sim) = model.motion().sim() else {
        ui.label(egui::RichText::new(tr(model, Key::MotionOffHint)).small());
        return;
    };
    ui.label(trf(
        model,
        Key::MotionClock,
        &[
            &format!("{:.3}", sim.time()),
            &model.motion().steps_last_frame(),
        ],
    ));
    egui::Grid::new("motion_measures")
        .striped(true)
        .show(ui, |ui| {
            for key in [
                Key::MotionJoint,
                Key::MotionOvershoot,
                Key::MotionSettling,
                Key::MotionError,
            ] {
                ui.label(egui::RichText::new(tr(model, key)).small());
            }
            ui.end_row();
            for (i, m) in sim.measures().iter().enumerate() {
                let [r, g, b] = column_color(i);
                ui.colored_label(Color32::from_rgb(r, g, b), format!("{}", i + 1));
                ui.monospace(match m.overshoot_ratio {
                    Some(ratio) => format!("{:.1} %", ratio * 100.0),
                    None => "–".to_string(),
                });
                ui.monospace(match m.settling_time {
                    Some(t) => format!("{t:.2} s"),
                    None => "–".to_string(),
                });
                ui.monospace(error_value(m.error, 1));
                ui.end_row();
            }
        });
}

/// The plots: angle, speed and error of every joint against time, the tool's distance.
fn plots_ui(model: &Model, ui: &mut egui::Ui) {
    let Some(sim) = model.motion().sim() else {
        return;
    };
    let record = sim.record();
    if record.len() < 2 {
        return;
    }
    let times = plot::range_of(record.times());
    for (series, key) in [
        (Series::Position, Key::MotionPlotAngle),
        (Series::Velocity, Key::MotionPlotSpeed),
        (Series::Error, Key::MotionPlotError),
    ] {
        joint_plot(model, ui, sim, (series, key), times);
    }
    let distance: Vec<[f64; 2]> = record.tool_distance().collect();
    if distance.len() >= 2 {
        let range = plot::range_of(distance.iter().map(|[_, d]| *d));
        let plot = PlotBox::allocate(ui, 60.0, times, (0.0, range.1.max(1e-9) * 1.05));
        plot.line(
            ui,
            distance.iter().copied(),
            Stroke::new(1.5, style::HIGHLIGHT),
        );
        let caption = trf(
            model,
            Key::MotionPlotDistance,
            &[
                &format!("{:.3}", range.1),
                &model.robot().length_unit.symbol(),
            ],
        );
        plot.describe(ui, || {
            let lang = model.settings().lang;
            let words = plot::series_words(
                lang,
                tr(model, Key::PlotTool),
                distance.iter().map(|[_, d]| *d),
                |v| format!("{v:.3}"),
            );
            plot_words(model, &caption, times.1, words.into_iter())
        });
        plot.caption(ui, caption);
    }
}

/// One series of every joint against time, with its goals or dead band, its caption and
/// its data in words.
fn joint_plot(
    model: &Model,
    ui: &mut egui::Ui,
    sim: &armlab_core::motion::MotionSim,
    (series, key): (Series, Key),
    times: (f64, f64),
) {
    let record = sim.record();
    let dof = sim.q().len();
    let dead_band = match sim.settings().controller {
        Controller::OnOff { dead_band } => Some(dead_band),
        _ => None,
    };
    let mut values = (0..dof).flat_map(|j| record.joint(j, series).map(|[_, v]| v));
    let mut range = plot::range_of(&mut values);
    if series == Series::Position {
        let goals = plot::range_of(sim.goal().iter().copied());
        range = (range.0.min(goals.0), range.1.max(goals.1));
    }
    if let (Series::Error, Some(band)) = (series, dead_band) {
        range = (range.0.min(-band), range.1.max(band));
    }
    let span = (range.1 - range.0).max(1e-9) * 0.05;
    let plot = PlotBox::allocate(ui, 70.0, times, (range.0 - span, range.1 + span));
    if series == Series::Error {
        if let Some(band) = dead_band {
            plot.band(ui, -band, band, style::PENDING.gamma_multiply(0.25));
        }
        plot.goal(ui, 0.0, ui.visuals().weak_text_color());
    }
    for j in 0..dof {
        let [r, g, b] = column_color(j);
        let color = Color32::from_rgb(r, g, b);
        if series == Series::Position {
            plot.goal(ui, sim.goal()[j], color);
        }
        plot.line(ui, record.joint(j, series), Stroke::new(1.2, color));
    }
    let mut caption = trf(
        model,
        key,
        &[&format!("{:.3}", range.0), &format!("{:.3}", range.1)],
    );
    if let (Series::Error, Some(band)) = (series, dead_band) {
        caption = trf(model, Key::MotionPlotDeadBand, &[&caption, &band]);
    }
    plot.describe(ui, || {
        let lang = model.settings().lang;
        let joints = (0..dof).filter_map(|j| {
            let name = trf(model, Key::PlotJoint, &[&(j + 1)]);
            let values = record.joint(j, series).map(|[_, v]| v);
            let words = plot::series_words(lang, &name, values, |v| format!("{v:.3}"))?;
            Some(match (series, sim.goal().get(j)) {
                (Series::Position, Some(goal)) => {
                    trf(model, Key::PlotGoal, &[&words, &format!("{goal:.3}")])
                }
                _ => words,
            })
        });
        plot_words(model, &caption, times.1, joints)
    });
    plot.caption(ui, caption);
}

/// A time plot in words: its caption, its time span and each series.
fn plot_words(
    model: &Model,
    caption: &str,
    end: f64,
    series: impl Iterator<Item = String>,
) -> String {
    let series: Vec<String> = series.collect();
    trf(
        model,
        Key::PlotTime,
        &[&caption, &format!("{end:.2}"), &series.join("; ")],
    )
}

/// A keep-out box as the panel shows it: `x, y, z, sx, sy, sz` (centre and size).
fn box_text(b: &KeepOut) -> String {
    [
        b.centre.x, b.centre.y, b.centre.z, b.size.x, b.size.y, b.size.z,
    ]
    .iter()
    .map(|v| echo::number(*v))
    .collect::<Vec<_>>()
    .join(", ")
}

/// Reads a typed box (`x, y, z, sx, sy, sz`); box `index` (0-based) in the sentence.
fn parse_box(index: usize, text: &str, lang: armlab_text::Lang) -> Result<KeepOut, String> {
    let mut v = Vec::new();
    for part in text.split([',', ';', ' ']).filter(|p| !p.is_empty()) {
        v.push(
            part.parse::<f64>()
                .map_err(|_| armlab_text::fill(lang, Key::MotionNotNumber, &[&echo::text(part)]))?,
        );
    }
    if v.len() != 6 {
        return Err(armlab_text::fill(lang, Key::MotionBoxSix, &[&v.len()]));
    }
    KeepOut::new(
        index + 1,
        nalgebra::Point3::new(v[0], v[1], v[2]),
        nalgebra::Vector3::new(v[3], v[4], v[5]),
    )
    .map_err(|e| e.sentence(lang))
}
