//! Loading, dragging, bad input, the native session and file dialog, and the snapshots of the whole app.

use super::*;

#[test]
fn moving_a_slider_changes_q_and_the_tool_pose_numbers() {
    let mut h = harness("#robot=ur10&q=0,-1,1,-0.5,0.8,0.3");
    let before_q = h.state().model().q().to_vec();
    let before_x = tool_x(&h);
    let shown = format!("{:.3}", before_x);
    assert!(
        h.query_all_by_label_contains(&shown).count() >= 1,
        "T_0n shows x = {shown}"
    );
    // Focus the θ1 slider and press the right arrow a few times.
    h.get_by_role_and_label(Role::Slider, "θ1").focus();
    h.run_steps(1);
    for _ in 0..5 {
        h.key_press(egui::Key::ArrowRight);
        h.run_steps(1);
    }
    let after_q = h.state().model().q().to_vec();
    assert!(
        after_q[0] > before_q[0] + 1e-3,
        "θ1 grew: {} → {}",
        before_q[0],
        after_q[0]
    );
    assert_eq!(&after_q[1..], &before_q[1..], "only θ1 moved");
    let after_x = tool_x(&h);
    assert!((after_x - before_x).abs() > 1e-3);
    let shown_after = format!("{:.3}", after_x);
    assert!(
        h.query_all_by_label_contains(&shown_after).count() >= 1,
        "T_0n now shows x = {shown_after}"
    );
}

#[test]
fn choosing_a_preset_swaps_the_robot() {
    let mut h = harness("");
    assert_eq!(h.state().model().robot().name, "UR10");
    h.get_by_label("Preset").click();
    h.run_steps(2);
    h.get_by_label("Puma 560").click();
    h.run_steps(2);
    let model = h.state().model();
    assert_eq!(model.robot().name, "Puma 560");
    // It opens at its own home pose and default task, the target on the new gripper.
    assert_eq!(model.q(), model.robot().home().as_slice());
    assert_eq!(model.task(), armlab_core::Task::FullPose);
    assert_eq!(model.ik().reach, Reach::Reached);
    // The matrices are the Puma's: at q = 0 (the Zero button) its T_06 has
    // p = (0.4521, −0.15005, 1.10363) m with R = I.
    h.get_by_label("Zero").click();
    h.run_steps(2);
    let model = h.state().model();
    assert_eq!(model.q(), &[0.0; 6]);
    let p = model.fk().tool_position();
    assert!((p - nalgebra::Vector3::new(0.4521, -0.15005, 1.10363)).norm() < 1e-5);
    let spec: [[f64; 4]; 3] = [
        [1.0, 0.0, 0.0, 0.4521],
        [0.0, 1.0, 0.0, -0.15005],
        [0.0, 0.0, 1.0, 1.10363],
    ];
    // The matrix's text: each entry right-aligned in 10 characters, 3 decimals.
    let rows = spec.map(|row| row.map(|v| format!("{v:>10.3}")).join(" "));
    assert!(
        h.query_all_by_label_contains(&rows[0]).any(|node| {
            let label = node.accesskit_node().value().unwrap_or_default();
            rows.iter().all(|row| label.contains(row))
        }),
        "T_06 shows the Puma's pose, row by row"
    );
}

#[test]
fn a_bad_dh_cell_shows_the_message_and_keeps_the_robot() {
    let mut h = harness("#robot=rrr");
    h.get_by_label("DH table (editable)").click();
    h.run_steps(2);
    let robot_before = h.state().model().robot().clone();
    let q_before = h.state().model().q().to_vec();
    // The cells are text inputs in table order: θ, d, a, α, min, max per joint.
    let cells: Vec<_> = h.query_all_by_role(Role::TextInput).collect();
    assert!(
        cells.len() >= 18,
        "three joints × six cells, found {}",
        cells.len()
    );
    // Joint 2's "a" cell (222.1).
    cells[6 + 2].focus();
    drop(cells);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("12x".into()));
    h.run_steps(3);
    assert!(
        h.query_by_label("Joint 2, a: \"12x\" is not a number.")
            .is_some(),
        "the message sits beside the cell"
    );
    assert_eq!(
        h.state().model().robot(),
        &robot_before,
        "the last valid robot stays"
    );
    assert_eq!(h.state().model().q(), q_before.as_slice());

    // A number the core rejects (reversed limits) gives the core's sentence.
    let cells: Vec<_> = h.query_all_by_role(Role::TextInput).collect();
    cells[6 + 2].focus();
    drop(cells);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("300".into()));
    h.run_steps(3);
    assert_eq!(
        h.state().robot_panel().editor().first_error(),
        None,
        "a valid cell applies live"
    );
    assert!((h.state().model().robot().joints[1].dh.a - 300.0).abs() < 1e-12);
}

#[test]
fn dragging_the_target_moves_the_arm_toward_it() {
    let mut h = harness("#robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=position");
    let start = h.state().points().get("target").expect("target on screen");
    let tool_before = h.state().model().fk().tool_position();
    let from = egui::pos2(start[0], start[1]);
    h.event(egui::Event::PointerMoved(from));
    h.run_steps(1);
    h.event(egui::Event::PointerButton {
        pos: from,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(1);
    // Toward the base by a quarter of the way: a target the arm can reach.
    let base = h.state().points().get("base").expect("base on screen");
    let step = (egui::pos2(base[0], base[1]) - from) / 80.0;
    let mut pos = from;
    for _ in 0..20 {
        pos += step;
        h.event(egui::Event::PointerMoved(pos));
        h.run_steps(1);
    }
    assert!(h.state().viewport().dragging(), "the ball was grabbed");
    // Hold still: the IK keeps converging while the button is down.
    h.run_steps(30);
    h.event(egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(2);
    let model = h.state().model();
    let target = model.target().translation.vector;
    let tool = model.fk().tool_position();
    assert!(
        (target - tool_before).norm() > 30.0,
        "the target moved ({:?})",
        target - tool_before
    );
    assert!(
        (tool - target).norm() < 1e-2,
        "the tool followed: {:?} vs {:?}",
        tool,
        target
    );
    assert_eq!(model.ik().reach, Reach::Reached);
    assert!(!h.state().viewport().dragging());
}

#[test]
fn a_garbage_link_gives_a_message_and_the_default_robot() {
    let h = harness("#robot=banana&q=1,2");
    assert_eq!(h.state().model().robot().name, "UR10");
    let message = h.state().model().message().expect("a message").clone();
    assert_eq!(message.kind, MessageKind::Warning);
    let message = message.text;
    assert!(
        message.contains("There is no robot called \"banana\""),
        "{message}"
    );
    assert!(
        h.query_by_label_contains("This link could not be opened")
            .is_some()
    );
}

#[test]
fn a_bad_q_in_a_link_keeps_the_robot_at_home_and_says_what_was_left_out() {
    let mut h = app_harness::open_app("#robot=planar-2r&q=abc,1", [1366.0, 768.0]);
    h.run_steps(2);
    let model = h.state().model();
    assert_eq!(model.robot().dof(), 2, "{}", model.robot().name);
    assert_eq!(model.q(), model.robot().home().as_slice());
    let message = model.message().expect("a message").clone();
    assert_eq!(message.kind, MessageKind::Warning);
    assert_eq!(
        message.text,
        "Part of this link was left out (the link's q has \"abc\", which is not a number); \
         the rest of it applies."
    );
    assert!(
        h.query_by_label_contains("Part of this link was left out")
            .is_some()
    );
}

#[test]
fn a_good_link_after_a_broken_one_takes_its_banner_away() {
    for (broken, banner) in [
        ("#robot=banana", "This link could not be opened"),
        ("#robot=banana&lang=fi", "Linkkiä ei voitu avata"),
    ] {
        let mut h = app_harness::open_app(broken, [1366.0, 768.0]);
        assert!(h.query_by_label_contains(banner).is_some(), "{broken}");
        h.state_mut().open_hash("#exercise=mystery-3");
        h.run_steps(3);
        assert!(h.state().model().exercise().is_some(), "{broken}");
        assert_eq!(h.state().model().message(), None, "{broken}");
        assert!(h.query_by_label_contains(banner).is_none(), "{broken}");
    }
}

#[test]
fn ur10_snapshot_on_the_software_vulkan_adapter() {
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2");
    h.run_steps(2);
    assert!(
        h.state().viewport().rendered(),
        "the wgpu scene renderer drew the viewport"
    );
    h.snapshot("ur10");
}

#[test]
fn the_view_draws_a_pass_only_when_its_scene_changes_and_never_shows_a_stale_arm() {
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2");
    h.run_steps(2);
    let first = view_pixels(&mut h);
    let passes = h.state().viewport().scene_passes();
    assert!(passes >= 1, "the scene was drawn");
    // Frames with nothing new for the view (egui repaints after every event, and a
    // pointer over a side panel's text changes only the panel) reuse the picture. Over a
    // joint's slider it would light that joint's link.
    h.event(egui::Event::PointerMoved(egui::pos2(150.0, 500.0)));
    h.run_steps(5);
    assert_eq!(
        h.state().viewport().scene_passes(),
        passes,
        "no pass for an unchanged scene"
    );
    assert!(
        view_pixels(&mut h) == first,
        "the reused picture is the same"
    );
    // A new q: the next frame draws the moved arm.
    h.state_mut()
        .model_mut()
        .set_q(vec![0.9, -1.1, 1.3, -1.6, -1.4, 0.2]);
    h.run_steps(1);
    assert_eq!(
        h.state().viewport().scene_passes(),
        passes + 1,
        "one pass for the new scene"
    );
    let moved = view_pixels(&mut h);
    let changed = first
        .chunks(4)
        .zip(moved.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        changed > 500,
        "the arm moved in the picture: {changed} pixels changed"
    );
    // Back to the first q: the picture is the first one again, pixel for pixel.
    h.state_mut()
        .model_mut()
        .set_q(vec![0.4, -1.1, 1.3, -1.6, -1.4, 0.2]);
    h.run_steps(3);
    assert_eq!(h.state().viewport().scene_passes(), passes + 2);
    assert!(view_pixels(&mut h) == first, "the first arm is drawn again");
}

#[test]
fn on_a_software_renderer_a_moving_scene_is_drawn_fast_and_the_resting_one_sharp() {
    let q = vec![0.4, -1.1, 1.3, -1.6, -1.4, 0.2];
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2");
    h.state_mut().viewport_mut().adapt_to_software();
    h.run_steps(2);
    // The first picture is the full-quality one: a page that opens shows it sharp.
    assert!(!h.state().viewport().moving_picture());
    let sharp = view_pixels(&mut h);
    // The arm moves away and back within one step (a quarter second): the scene
    // changed, so the picture is the fast one, of the same arm.
    h.state_mut()
        .model_mut()
        .set_q(vec![0.9, -1.1, 1.3, -1.6, -1.4, 0.2]);
    h.run_steps(1);
    h.state_mut().model_mut().set_q(q);
    h.run_steps(1);
    assert!(
        h.state().viewport().moving_picture(),
        "a changing scene is drawn as a moving picture"
    );
    let moving = view_pixels(&mut h);
    assert_eq!(moving.len(), sharp.len());
    let differ = sharp
        .chunks(4)
        .zip(moving.chunks(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 24))
        .count();
    let pixels = sharp.len() / 4;
    // Half the width and height, no MSAA: the edges differ, the arm and the floor do not.
    assert!(
        differ > 50,
        "the moving picture has fewer pixels: {differ} differ"
    );
    assert!(
        differ < pixels / 20,
        "the moving picture shows the same arm: {differ} of {pixels} pixels differ"
    );
    // At rest (past 0.3 s without a change) the full-quality picture returns, pixel for
    // pixel, and stays.
    h.run_steps(2);
    assert!(!h.state().viewport().moving_picture());
    assert!(
        view_pixels(&mut h) == sharp,
        "the resting picture is the sharp one"
    );
}

#[test]
fn metrover_snapshot_with_its_part_sizes() {
    let mut h = harness("#robot=metrover&q=0.5,0.9,0.6,0.3,0.2&task=position");
    h.run_steps(2);
    assert_eq!(
        h.state().model().robot().parts.base,
        Some([600.0, 300.0, 340.0])
    );
    assert!(h.state().viewport().rendered());
    h.snapshot("metrover");
}

#[test]
fn the_native_file_dialog_saves_and_opens_a_robot_file() {
    use armlab::app::panels::file_dialog::{FileDialog, Mode};
    let dir = std::env::temp_dir().join(format!("armlab-ui-files-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let mut h = harness("#robot=scara");
    h.state_mut()
        .robot_panel_mut()
        .open_file_dialog(FileDialog::new(Mode::Save, "my scara", dir.clone()));
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(2);
    let saved = dir.join("my scara.json");
    let text = std::fs::read_to_string(&saved).expect("the dialog wrote the file");
    let robot = armlab_core::robot_from_json(&text).expect("a valid robot file");
    assert_eq!(
        &robot,
        h.state().model().robot(),
        "the file holds the whole robot"
    );
    assert!(
        h.state().robot_panel().file_dialog().is_none(),
        "the dialog closed"
    );
    let saved_message = h.state().model().message().expect("a message").clone();
    assert_eq!(
        saved_message.kind,
        MessageKind::Info,
        "{}",
        saved_message.text
    );

    // Open it again from another robot: pick the file in the listing, then Open.
    let mut h = harness("#robot=ur10");
    h.state_mut()
        .robot_panel_mut()
        .open_file_dialog(FileDialog::new(Mode::Open, "", dir.clone()));
    h.run_steps(2);
    h.get_by_label("my scara.json").click();
    h.run_steps(2);
    h.get_by_label("Open").click();
    h.run_steps(2);
    assert_eq!(
        h.state().model().robot(),
        &robot,
        "the reopened robot is the saved one, whole"
    );
    assert_eq!(h.state().model().q(), robot.home().as_slice());
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn the_native_app_keeps_its_session_when_it_closes() {
    let file =
        std::env::temp_dir().join(format!("armlab-ui-session-{}/session", std::process::id()));
    let mut h = harness("#robot=puma560&q=0.1,0.2,0.3,0.4,0.5,0.6");
    h.state_mut().set_session_file(Some(file.clone()));
    eframe::App::on_exit(h.state_mut());
    let stored = std::fs::read_to_string(&file).expect("the session was written");
    let reopened = Session::from_json(&stored).expect("the stored session reads");
    assert_eq!(reopened.robot.name, "Puma 560");
    assert_eq!(reopened.q, h.state().model().q());
    // The next start opens it as it was (the target as a link keeps it: to 10⁻⁶); a stored
    // session that cannot be read says so.
    let mut app = ArmLabApp::with_session(Session::default_session());
    app.open_stored(&stored);
    assert_eq!(app.stored_session(), stored);
    let moved =
        app.model().target().translation.vector - h.state().model().target().translation.vector;
    assert!(moved.norm() < 1e-6, "the target moved by {moved:?}");
    app.open_stored("{\"robot\": 5}");
    assert_eq!(app.model().robot().name, "UR10");
    let said = &app.model().message().expect("a message").text;
    assert!(
        said.contains("last session could not be reopened"),
        "{said}"
    );
    if let Some(dir) = file.parent() {
        std::fs::remove_dir_all(dir).expect("clean up");
    }
}

#[test]
fn a_click_in_the_view_with_no_move_before_it_leaves_the_camera() {
    let mut h = app_harness::open_app("#robot=ur10", [1024.0, 768.0]);
    h.run_steps(2);
    let rect = h.state().viewport().rect().expect("the view was laid out");
    // The pointer was last over the side panel (then off to the slides); it comes back
    // with a click in the view, as a presenter's remote and synthetic input do.
    h.event(egui::Event::PointerMoved(egui::pos2(20.0, rect.center().y)));
    h.run_steps(2);
    let before = h.state().viewport().camera_pose();
    let at = rect.center() + egui::vec2(rect.width() * 0.3, -rect.height() * 0.3);
    click_at(&mut h, at);
    let after = h.state().viewport().camera_pose();
    assert_eq!((after.yaw, after.pitch), (before.yaw, before.pitch));
    // A real drag still orbits, by the pointer's own path.
    h.event(egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(1);
    h.event(egui::Event::PointerMoved(at + egui::vec2(40.0, 0.0)));
    h.run_steps(1);
    h.event(egui::Event::PointerButton {
        pos: at + egui::vec2(40.0, 0.0),
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(1);
    let dragged = h.state().viewport().camera_pose();
    assert_ne!(dragged.yaw, after.yaw, "a drag orbits");
    assert_eq!(dragged.pitch, after.pitch, "a level drag keeps the pitch");
}

/// A target inside the UR10's base cylinder (the shoulder offset keeps the wrist out of
/// it), dragged there with the pseudo-inverse: the ball, the status, Solve and the
/// Solutions fold all say "out of reach".
#[test]
fn a_target_by_the_base_axis_reads_out_of_reach_everywhere() {
    let mut h = app_harness::open_app("#robot=ur10&panels=ik&method=pinv", [1366.0, 768.0]);
    let start = *h.state().model().target();
    for i in 1..=60 {
        let mut t = start;
        let f = i as f64 / 60.0;
        t.translation.vector.x = start.translation.vector.x * (1.0 - f) - 135.0 * f;
        t.translation.vector.y = start.translation.vector.y * (1.0 - f);
        h.state_mut().model_mut().set_target(t);
        h.state_mut().model_mut().drag_step();
    }
    for _ in 0..300 {
        h.state_mut().model_mut().drag_step();
    }
    h.run_steps(2);
    assert!(
        h.query_by_label("Target out of reach (closest pose shown)")
            .is_some()
    );
    assert!(h.query_by_label("Tool not at the target").is_none());
    h.get_by_label("Solve").click();
    h.run_steps(2);
    assert!(
        h.query_by_label_contains("iterations, target out of reach")
            .is_some()
    );
    h.get_by_label("Solutions of this target").click();
    h.run_steps(3);
    assert!(h.query_by_label_contains("No exact solution").is_some());
    assert!(
        h.query_by_label("Target out of reach (closest pose shown)")
            .is_some()
    );
    assert_eq!(h.state().model().shown_reach(), Reach::OutOfReach);
}

/// The page paints its panels without their fills (each of their pixels would otherwise be
/// drawn twice, a cost with software WebGL): the window is cleared to the panels' colour,
/// in the dark theme and in presentation mode, so they look the same.
#[test]
fn the_window_is_cleared_to_the_panels_colour() {
    let mut h = harness("#robot=ur10");
    for presentation in [false, true] {
        h.state_mut().model_mut().set_presentation(presentation);
        h.run_steps(2);
        let visuals = h.ctx.global_style().visuals.clone();
        let fill = visuals.panel_fill;
        let clear = eframe::App::clear_color(h.state(), &visuals);
        let rgb = |c: [f32; 4]| c.map(|v| (v * 255.0).round() as u8);
        assert_eq!(
            rgb(clear),
            [fill.r(), fill.g(), fill.b(), 255],
            "presentation {presentation}"
        );
    }
}
