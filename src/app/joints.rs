//! The joint panel: a slider and a number field per joint within its limits, degrees or
//! radians, prismatic joints in length units; zero and home.

use crate::kinematics::{Joint, JointKind};

use super::hook::ScreenPoints;
use super::model::Model;
use super::{Panel, tr};
use crate::i18n::Key;

/// The joint sliders. Every value is the model's q; the panel keeps only its sliders'
/// ids, so a shortcut can focus one.
#[derive(Debug, Clone, Default)]
pub struct JointsPanel {
    sliders: Vec<egui::Id>,
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
        let mut q = model.q().to_vec();
        let mut changed = false;
        self.sliders.clear();
        // The slider fills the column: the label and the value box beside it stay.
        let rail = (ui.available_width() - 110.0).clamp(60.0, 320.0);
        ui.spacing_mut().slider_width = rail;
        egui::Grid::new("joint_sliders")
            .num_columns(2)
            .striped(true)
            .show(ui, |ui| {
                for (i, joint) in model.robot().joints.iter().enumerate() {
                    let response = joint_slider(ui, model, i, joint, &mut q[i]);
                    self.sliders.push(response.id);
                    // Where the slider's minimum and maximum values sit, for the browser
                    // tests: egui insets the rail's ends by the handle's radius, a 2.5th
                    // of the slider's height.
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
                    ui.end_row();
                }
            });
        if changed {
            model.set_q_exact(q);
        }
    }
}

/// One joint's label and slider (degrees or radians, or the length unit).
fn joint_slider(
    ui: &mut egui::Ui,
    model: &Model,
    i: usize,
    joint: &Joint,
    value: &mut f64,
) -> egui::Response {
    let symbol = match joint.kind {
        JointKind::Revolute => format!("θ{}", i + 1),
        JointKind::Prismatic => format!("d{}", i + 1),
    };
    let label = ui.label(symbol).on_hover_text(&joint.name);
    let (lo, hi) = (joint.limits.min, joint.limits.max);
    let response = match joint.kind {
        JointKind::Revolute if model.settings().degrees => {
            let mut v = value.to_degrees();
            let r = ui.add(
                egui::Slider::new(&mut v, lo.to_degrees()..=hi.to_degrees())
                    .suffix("°")
                    .fixed_decimals(1)
                    .clamping(egui::SliderClamping::Never),
            );
            if r.changed() {
                *value = v.to_radians();
            }
            r
        }
        JointKind::Revolute => ui.add(
            egui::Slider::new(value, lo..=hi)
                .suffix(" rad")
                .fixed_decimals(3)
                .clamping(egui::SliderClamping::Never),
        ),
        JointKind::Prismatic => ui.add(
            egui::Slider::new(value, lo..=hi)
                .suffix(format!(" {}", model.robot().length_unit.symbol()))
                .clamping(egui::SliderClamping::Never),
        ),
    };
    response.labelled_by(label.id)
}
