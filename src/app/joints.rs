//! The joint panel: a slider and a number field per joint within its limits, degrees or
//! radians, prismatic joints in length units; zero and home.

use crate::kinematics::JointKind;

use super::ArmLabApp;

/// Shows the joint sliders. Changing one moves the arm at once.
pub fn show(app: &mut ArmLabApp, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        ui.strong("Joints");
        if ui
            .button("Zero")
            .on_hover_text("All joints to 0 (or the nearest limit)")
            .clicked()
        {
            let zero = vec![0.0; app.session.robot.dof()];
            app.set_q_exact(zero);
        }
        if ui
            .button("Home")
            .on_hover_text("The robot's home pose")
            .clicked()
        {
            let home = app.session.robot.home();
            app.set_q_exact(home);
        }
    });
    let degrees = app.settings.degrees;
    let unit = app.session.robot.length_unit.symbol();
    let mut q = app.session.q.clone();
    let mut changed = false;
    egui::Grid::new("joint_sliders")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            for (i, joint) in app.session.robot.joints.iter().enumerate() {
                let symbol = match joint.kind {
                    JointKind::Revolute => format!("θ{}", i + 1),
                    JointKind::Prismatic => format!("d{}", i + 1),
                };
                let label = ui.label(symbol).on_hover_text(&joint.name);
                let (lo, hi) = (joint.limits.min, joint.limits.max);
                let response = match joint.kind {
                    JointKind::Revolute if degrees => {
                        let mut v = q[i].to_degrees();
                        let r = ui.add(
                            egui::Slider::new(&mut v, lo.to_degrees()..=hi.to_degrees())
                                .suffix("°")
                                .fixed_decimals(1)
                                .clamping(egui::SliderClamping::Never),
                        );
                        if r.changed() {
                            q[i] = v.to_radians();
                        }
                        r
                    }
                    JointKind::Revolute => ui.add(
                        egui::Slider::new(&mut q[i], lo..=hi)
                            .suffix(" rad")
                            .fixed_decimals(3)
                            .clamping(egui::SliderClamping::Never),
                    ),
                    JointKind::Prismatic => ui.add(
                        egui::Slider::new(&mut q[i], lo..=hi)
                            .suffix(format!(" {unit}"))
                            .clamping(egui::SliderClamping::Never),
                    ),
                };
                let response = response.labelled_by(label.id);
                // The rail's ends, for the browser tests.
                let r = response.rect;
                let rail = ui.spacing().slider_width;
                app.viewport
                    .points
                    .push((format!("slider-{}-min", i + 1), [r.left(), r.center().y]));
                app.viewport.points.push((
                    format!("slider-{}-max", i + 1),
                    [r.left() + rail, r.center().y],
                ));
                changed |= response.changed();
                ui.end_row();
            }
        });
    if changed {
        app.set_q_exact(q);
    }
}
