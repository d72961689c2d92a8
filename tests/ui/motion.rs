//! The motion lab: driving to the answer, its plots, and stopping at a collision.

use super::*;

#[test]
fn with_move_on_the_arm_drives_to_the_answer_and_the_motion_panel_plots_it() {
    use armlab_core::motion::Controller;
    let mut h = harness("#robot=rrr&q=0,0.5,-1&panels=ik,motion");
    h.get_by_label("Move: drive to the IK answer").click();
    h.run_steps(1);
    assert!(h.state().model().motion().on());
    let start = h.state().model().q().to_vec();
    let mut target = *h.state().model().target();
    target.translation.vector += nalgebra::Vector3::new(-150.0, 120.0, 80.0);
    let distance0 = (h.state().model().fk().tool_position() - target.translation.vector).norm();
    h.state_mut().model_mut().set_target(target);
    h.get_by_label("Solve").click();
    // kittest's frames are 0.25 s, each simulated as 0.1 s (the frame time is capped).
    h.run_steps(1);
    let d1 = (h.state().model().fk().tool_position() - target.translation.vector).norm();
    assert!(
        d1 > 1.0 && d1 < distance0,
        "after one frame the arm is on its way: {d1} of {distance0}"
    );
    assert_ne!(h.state().model().q(), &start[..]);
    h.run_steps(60);
    let model = h.state().model();
    assert_eq!(model.ik().reach, Reach::Reached, "{:?}", model.ik());
    assert!(model.ik().position_error < 1e-3);
    let sim = model.motion().sim().expect("the simulation runs");
    assert!(sim.time() > 5.0, "simulated {} s", sim.time());
    for (i, m) in sim.measures().iter().enumerate() {
        // P on a first-order lag with K·τ = 0.1 < 1/4: no overshoot, settled.
        assert!(
            m.overshoot <= 1e-9,
            "joint {}: overshoot {}",
            i + 1,
            m.overshoot
        );
        assert!(m.settling_time.is_some(), "joint {} settled", i + 1);
        assert!(m.error.abs() < 1e-4, "joint {}: error {}", i + 1, m.error);
    }
    assert!(
        model.motion().trail().len() > 10,
        "the tool's path is kept: {} points",
        model.motion().trail().len()
    );
    angle_plot_reads_as_its_data(&h);
    // A negative gain gets a sentence and K stays 5.
    h.get_by_role_and_label(Role::TextInput, "K (1/s)").click();
    h.run_steps(1);
    h.key_press(egui::Key::Backspace);
    h.get_by_role_and_label(Role::TextInput, "K (1/s)")
        .type_text("-3");
    h.run_steps(2);
    assert!(
        h.query_by_label_contains("must be above zero").is_some(),
        "the sentence shows"
    );
    assert_eq!(
        h.state().model().motion().settings().controller,
        Controller::Proportional { gain: 5.0 }
    );
    // The Motion panel alone in its column: its measures and plots in sight.
    h.state_mut()
        .model_mut()
        .set_panel_open(armlab_session::settings::PanelKind::Ik, false);
    h.run_steps(2);
    h.snapshot("motion_panel_plots");
}

/// A screen reader reads each plot as its data: the angle plot says where each joint
/// began and ended and its goal.
fn angle_plot_reads_as_its_data(h: &Harness<'static, ArmLabApp>) {
    let sim = h
        .state()
        .model()
        .motion()
        .sim()
        .expect("the simulation runs");
    let (start, end, goal) = (
        sim.record()
            .joint(1, armlab_core::motion::Series::Position)
            .next(),
        sim.record()
            .joint(1, armlab_core::motion::Series::Position)
            .last(),
        sim.goal()[1],
    );
    let angles = h
        .query_all_by_role(Role::Image)
        .filter_map(|n| n.accesskit_node().label())
        .find(|l| l.starts_with("q against t"))
        .expect("the angle plot is in the accessibility tree");
    let [Some([_, a]), Some([_, b])] = [start, end] else {
        panic!("joint 2 was recorded")
    };
    assert!(
        angles.contains(&format!("joint 2: {a:.3} at the start, {b:.3} at the end"))
            && angles.contains(&format!("goal {goal:.3}")),
        "{angles}"
    );
}

#[test]
fn the_motion_panel_fits_a_projector_and_a_phone() {
    use armlab_session::settings::PanelKind;
    for (size, min_share) in [([1024.0, 768.0], 0.5), ([390.0, 844.0], 0.99)] {
        let mut h = harness_at(
            "#robot=ur10&panels=joints,motion&move=on&ctrl=pid&gains=100,200,20",
            size,
        );
        if size[0] < 900.0 {
            h.state_mut().set_sheet(Some(PanelKind::Motion));
        }
        h.run_steps(3);
        let share = view_share_and_points(&h, size[0]);
        assert!(share >= min_share, "{size:?}: the view has {share}");
        // The panel's controls lie inside the window, left of the view in the wide layout.
        let view = h.state().viewport().rect().expect("a view");
        for label in ["Move: drive to the IK answer", "Kp", "Ki", "Kd"] {
            let node = h.get_by_label(label);
            let rect = node.rect();
            assert!(
                rect.min.x >= 0.0 && rect.max.x <= size[0],
                "{size:?}: {label} at {rect:?}"
            );
            if size[0] >= 900.0 {
                assert!(
                    rect.max.x <= view.min.x,
                    "{size:?}: {label} beside the view"
                );
            } else {
                assert!(rect.min.y >= view.max.y, "{size:?}: {label} under the view");
            }
        }
    }
}

#[test]
fn a_motion_into_the_base_stops_at_the_last_free_pose_and_names_the_parts() {
    use armlab_core::ForwardKinematics;
    use armlab_core::collision::CollisionChecker;
    let mut h = harness("#robot=ur10&move=on&collide=on&ctrl=quintic&panels=motion");
    let robot = h.state().model().robot().clone();
    // The folded UR10 of tests/collision.rs: the wrist comes down onto the base.
    let mut folded = robot.home();
    folded[1] = 0.0;
    folded[2] = (-150f64).to_radians();
    h.state_mut()
        .model_mut()
        .set_motion_goal(&folded)
        .expect("a valid goal");
    let mut checker = CollisionChecker::new(true, vec![]).expect("a checker");
    let mut touches = |q: &[f64]| {
        let fk = ForwardKinematics::new(&robot, q).expect("a valid q");
        !checker.check(&robot, &fk).is_free()
    };
    // Frame by frame, keeping the simulation as each frame starts: the frame that refuses
    // its pose is replayed from there to find the pose it refused.
    let stopped = |h: &Harness<'_, ArmLabApp>| {
        h.state()
            .model()
            .message()
            .is_some_and(|m| m.text.contains("stopped at the last collision-free"))
    };
    let mut before = None;
    let mut frames = 0;
    while !stopped(&h) && frames < 60 {
        before = h.state().model().motion().sim().cloned();
        h.run_steps(1);
        frames += 1;
    }
    let model = h.state().model();
    let message = model.message().map(|m| m.text.clone()).unwrap_or_default();
    assert!(
        message.starts_with("Contact: ") && message.contains("stopped at the last collision-free"),
        "after {frames} frames: {message}"
    );
    assert!(
        model.motion().colliding().iter().any(|c| *c),
        "parts drawn red"
    );
    assert!(!model.motion().moving(), "the motion stopped");
    let q = model.q().to_vec();
    assert!(
        (q[2] - folded[2]).abs() > 0.05,
        "the arm did not reach the folded pose: {q:?}"
    );
    assert!(!touches(&q), "it rests where nothing touches: {q:?}");
    // The last free pose: the one the previous frame took (the check runs once a frame) …
    let mut refused = before.expect("the motion ran at least one frame");
    assert_eq!(
        q,
        refused.q(),
        "the arm rests at the pose of the frame before the contact"
    );
    // … and the same motion one frame on (the steps that frame ran) touches.
    let steps = model.motion().steps_last_frame();
    assert!(steps > 0, "the refused frame ran simulation steps");
    for _ in 0..steps {
        refused.step();
    }
    let next = refused.q().to_vec();
    assert!(
        next.iter().zip(&q).any(|(a, b)| (a - b).abs() > 1e-6),
        "the refused pose lies on: {next:?} vs {q:?}"
    );
    assert!(
        touches(&next),
        "the next pose of the motion touches: {next:?}"
    );
    // The picture after the same 60 frames as ever (the panel shows the simulated time).
    h.run_steps(60 - frames);
    h.snapshot("motion_collision_stop");
}

#[test]
fn the_motion_tab_brings_its_panel_into_sight_at_1366x768() {
    let mut h = harness_at("#robot=ur10", [1366.0, 768.0]);
    h.get_by_label("Motion").click();
    h.run_steps(30);
    // The panel's first control and its last fold both show: the column scrolled to it.
    let bottom = h.ctx.content_rect().bottom();
    let top = h.state().viewport().rect().expect("a view").top();
    let [_, first] = h
        .state()
        .points()
        .get("motion-move")
        .expect("the motion panel is drawn");
    let last = h.get_by_label("Keep-out boxes").rect().bottom();
    assert!(
        first > top && last < bottom,
        "the panel runs from y {first} to {last}, the column shows {top}..{bottom}"
    );
}
