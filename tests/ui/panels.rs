//! Each panel alone: it changes only what it asks the model for.

use super::*;

#[test]
fn the_joints_panel_alone_changes_only_the_models_q() {
    let mut h = alone("rrr", JointsPanel::default());
    let before = h.state().model.q().to_vec();
    let tool_before = h.state().model.fk().tool_position();
    h.get_by_role_and_label(Role::Slider, "θ2").focus();
    h.run_steps(1);
    for _ in 0..4 {
        h.key_press(egui::Key::ArrowRight);
        h.run_steps(1);
    }
    let model = &h.state().model;
    assert!(model.q()[1] > before[1] + 1e-3, "θ2 grew");
    assert_eq!(model.q()[0], before[0]);
    assert_eq!(model.q()[2], before[2]);
    let fresh = armlab_core::tool_pose(model.robot(), model.q());
    assert_eq!(
        model.fk().base_from_tool,
        fresh,
        "the model recomputed FK at the new q"
    );
    assert!((model.fk().tool_position() - tool_before).norm() > 1e-3);
    assert!(
        h.state().points.get("slider-2-min").is_some(),
        "the rail's ends are in the registry"
    );
    h.get_by_label("Home").click();
    h.run_steps(2);
    assert_eq!(
        h.state().model.q(),
        h.state().model.robot().home().as_slice()
    );
}

#[test]
fn the_ik_panel_alone_solves_and_replays_its_run() {
    let mut h = alone("ur10", IkPanel::default());
    let start = h.state().model.q().to_vec();
    let mut target = *h.state().model.target();
    target.translation.vector += nalgebra::Vector3::new(-120.0, 80.0, 60.0);
    h.state_mut().model.set_target(target);
    h.run_steps(1);
    assert_eq!(h.state().model.ik().reach, Reach::Pending);
    h.get_by_label("Solve").click();
    h.run_steps(2);
    let model = &h.state().model;
    assert_eq!(model.ik().reach, Reach::Reached);
    let tool = armlab_core::tool_pose(model.robot(), model.q());
    assert!((tool.translation.vector - target.translation.vector).norm() < 1e-3);
    let run = h
        .state()
        .model
        .replay()
        .expect("the run is kept for replay")
        .run
        .clone();
    assert!(
        run.trace.len() > 2,
        "{} iterations recorded",
        run.trace.len()
    );
    // A screen reader reads the error plot as its data: every iteration's error.
    let words = h
        .get_by_role(Role::Image)
        .accesskit_node()
        .label()
        .unwrap_or_default();
    let last = run.trace.len() - 1;
    let errors: Vec<String> = run
        .trace
        .iter()
        .map(|s| format!("{:.1e}", s.error))
        .collect();
    assert!(
        words.contains(&format!(
            "‖e‖ at iterations 0 to {last}: {}",
            errors.join(", ")
        )),
        "{words}"
    );
    // Back to the first iteration: the arm shows the q of that step.
    h.get_by_role_and_label(Role::Slider, "iteration").focus();
    h.run_steps(1);
    for _ in 0..run.trace.len() {
        h.key_press(egui::Key::ArrowLeft);
        h.run_steps(1);
    }
    h.run_steps(1);
    let q = h.state().model.q().to_vec();
    assert_eq!(h.state().model.replay().map(|r| r.step), Some(0));
    let first: Vec<f64> = run.trace[0].q.clone();
    for (a, b) in q.iter().zip(&first) {
        assert!((a - b).abs() < 1e-12, "{q:?} vs {first:?}");
    }
    let last = run.trace.last().expect("a trace").q.clone();
    assert_ne!(q, last, "the replay moved the arm away from the answer");
    assert_eq!(start.len(), q.len());
}

#[test]
fn a_link_naming_only_the_robot_opens_its_default_task() {
    let h = harness("#robot=metrover");
    let model = h.state().model();
    assert_eq!(
        model.task(),
        armlab_core::Task::Position,
        "five joints: position only"
    );
    assert_eq!(model.q(), model.robot().home().as_slice());
    let h = harness("#robot=panda");
    assert_eq!(h.state().model().task(), armlab_core::Task::FullPose);
    let h = harness("#robot=planar-2r&task=full");
    assert_eq!(
        h.state().model().task(),
        armlab_core::Task::FullPose,
        "a task the link names wins"
    );
}

/// Typing "1e999" into a DH cell key by key: the arm never takes a value met on the way
/// (the "1"), and while the cell shows its error the arm is the one from before the typing.
#[test]
fn a_dh_cell_applies_no_value_met_while_typing() {
    let mut h = harness_at("#robot=ur10&panels=robot", [1366.0, 768.0]);
    h.get_by_label("DH table (editable)").click();
    h.run_steps(3);
    let a_before = h.state().model().robot().joints[1].dh.a;
    let [x, y] = h.state().points().get("dh-2-3").expect("the cell is drawn");
    let at = egui::pos2(x, y);
    h.event(egui::Event::PointerMoved(at));
    click_at(&mut h, at);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.run_steps(1);
    let mut seen = Vec::new();
    for key in ["1", "e", "9", "9", "9"] {
        h.event(egui::Event::Text(key.into()));
        h.run_steps(1);
        seen.push(h.state().model().robot().joints[1].dh.a);
    }
    assert!(
        h.state().robot_panel().editor().error.is_some(),
        "the cell shows its error"
    );
    assert_eq!(
        h.state().model().robot().joints[1].dh.a,
        a_before,
        "a as before the typing; on the way {seen:?}"
    );
    // Enter on a good value applies it.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("-600".into()));
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
    assert_eq!(h.state().model().robot().joints[1].dh.a, -600.0);
}

/// A joint slider's rail stands 3:1 apart from its panel (WCAG's non-text contrast), in the
/// normal theme and in presentation mode, as drawn: egui's own rail had about 1.3:1.
#[test]
fn a_sliders_rail_has_3_to_1_on_its_panel() {
    use armlab::app::widgets::contrast::ratio;
    let pose = "#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3";
    for hash in [
        pose.to_string(),
        format!("{pose}&present=on&ppanels=joints"),
    ] {
        let mut h = harness_at(&hash, [1366.0, 768.0]);
        let rail = h.get_by_role_and_label(Role::Slider, "θ2").rect();
        let image = h.render().expect("a frame");
        let ppp = h.ctx.pixels_per_point();
        let px = |p: egui::Pos2| {
            let [r, g, b, _] = image.get_pixel((p.x * ppp) as u32, (p.y * ppp) as u32).0;
            egui::Color32::from_rgb(r, g, b)
        };
        // Above the rail, inside the slider's row: the panel.
        let panel = px(rail.left_top() + egui::vec2(1.0, 1.0));
        // Both ends (θ2 is far from either limit, so the handle covers neither).
        for end in [
            rail.left_center() + egui::vec2(2.0, 0.0),
            rail.right_center() - egui::vec2(2.0, 0.0),
        ] {
            let contrast = ratio(px(end), panel);
            assert!(
                contrast >= 3.0,
                "{hash}: the rail {:?} on the panel {panel:?}: {contrast:.2}:1",
                px(end)
            );
        }
    }
}

/// A wide layout's two columns each have an edge (egui's resize handle), named for screen
/// readers by the column it widens, in the interface's language: egui would call both
/// "Resize panel", in English on the Finnish page too.
#[test]
fn each_columns_edge_is_named_in_the_interfaces_language() {
    for (hash, left, right) in [
        (
            "#robot=ur10",
            "Width of the left column",
            "Width of the right column",
        ),
        (
            "#robot=ur10&lang=fi",
            "Vasemman sarakkeen leveys",
            "Oikean sarakkeen leveys",
        ),
    ] {
        let h = harness(hash);
        let names: Vec<String> = h
            .query_all_by_role(Role::Splitter)
            .map(|n| n.accesskit_node().label().unwrap_or_default())
            .collect();
        assert_eq!(names, [left, right], "{hash}");
    }
}
