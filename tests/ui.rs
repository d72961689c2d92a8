//! UI tests of the app through egui_kittest (native only, `app` feature): what a person
//! sees and does. The harness renders with wgpu on the machine's Vulkan adapter (lavapipe
//! here), so the 3D viewport runs its real pipeline.
#![cfg(not(target_arch = "wasm32"))]

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use armlab::app::ArmLabApp;

const SIZE: [f32; 2] = [1400.0, 860.0];

fn harness(hash: &str) -> Harness<'static, ArmLabApp> {
    let hash = hash.to_string();
    let mut h = Harness::builder()
        .with_size(SIZE)
        .wgpu()
        .build_eframe(move |cc| ArmLabApp::new(cc, &hash));
    h.run_steps(3);
    h
}

fn tool_x(h: &Harness<'_, ArmLabApp>) -> f64 {
    h.state().fk.tool_position().x
}

#[test]
fn moving_a_slider_changes_q_and_the_tool_pose_numbers() {
    let mut h = harness("#robot=ur10&q=0,-1,1,-0.5,0.8,0.3");
    let before_q = h.state().session.q.clone();
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
    let after_q = h.state().session.q.clone();
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
    assert_eq!(h.state().session.robot.name, "UR10");
    h.get_by_label("Robot").click();
    h.run_steps(2);
    h.get_by_label("Puma 560").click();
    h.run_steps(2);
    let app = h.state();
    assert_eq!(app.session.robot.name, "Puma 560");
    assert_eq!(app.session.q.len(), 6);
    // The target moved onto the new gripper and the matrices are the Puma's.
    assert!(app.ik.reached);
    assert!(h.query_by_label_contains("A_6").is_some());
}

#[test]
fn a_bad_dh_cell_shows_the_message_and_keeps_the_robot() {
    let mut h = harness("#robot=rrr");
    h.get_by_label("DH table (editable)").click();
    h.run_steps(2);
    let robot_before = h.state().session.robot.clone();
    let q_before = h.state().session.q.clone();
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
        h.state().session.robot,
        robot_before,
        "the last valid robot stays"
    );
    assert_eq!(h.state().session.q, q_before);

    // A number the core rejects (reversed limits) gives the core's sentence.
    let cells: Vec<_> = h.query_all_by_role(Role::TextInput).collect();
    cells[6 + 2].focus();
    drop(cells);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("300".into()));
    h.run_steps(3);
    assert_eq!(
        h.state().editor.first_error(),
        None,
        "a valid cell applies live"
    );
    assert!((h.state().session.robot.joints[1].dh.a - 300.0).abs() < 1e-12);
}

#[test]
fn dragging_the_target_moves_the_arm_toward_it() {
    let mut h = harness("#robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=position");
    let start = h
        .state()
        .viewport
        .point("target")
        .expect("target on screen");
    let tool_before = h.state().fk.tool_position();
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
    let base = h.state().viewport.point("base").expect("base on screen");
    let step = (egui::pos2(base[0], base[1]) - from) / 80.0;
    let mut pos = from;
    for _ in 0..20 {
        pos += step;
        h.event(egui::Event::PointerMoved(pos));
        h.run_steps(1);
    }
    assert!(h.state().viewport.dragging(), "the ball was grabbed");
    // Hold still: the IK keeps converging while the button is down.
    h.run_steps(30);
    h.event(egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(2);
    let app = h.state();
    let target = app.target.translation.vector;
    let tool = app.fk.tool_position();
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
    assert!(app.ik.reached);
    assert!(!app.viewport.dragging());
}

#[test]
fn a_garbage_link_gives_a_message_and_the_default_robot() {
    let h = harness("#robot=ur10&q=1,2,banana");
    assert_eq!(h.state().session.robot.name, "UR10");
    let message = h.state().message.clone().expect("a message");
    assert!(
        message.contains("\"banana\", which is not a number"),
        "{message}"
    );
    assert!(
        h.query_by_label_contains("This link could not be opened")
            .is_some()
    );
}

#[test]
fn ur10_snapshot_on_the_software_vulkan_adapter() {
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2");
    h.run_steps(2);
    assert!(
        h.state().viewport.rendered,
        "the wgpu scene renderer drew the viewport"
    );
    h.snapshot("ur10");
}

#[test]
fn metrover_snapshot_with_its_part_sizes() {
    let mut h = harness("#robot=metrover&q=0.5,0.9,0.6,0.3,0.2&task=position");
    h.run_steps(2);
    assert_eq!(
        h.state().session.robot.parts.base,
        Some([600.0, 300.0, 340.0])
    );
    assert!(h.state().viewport.rendered);
    h.snapshot("metrover");
}

#[test]
fn the_native_file_dialog_saves_and_opens_a_robot_file() {
    use armlab::app::files::{FileDialog, Mode};
    let dir = std::env::temp_dir().join(format!("armlab-ui-files-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let mut h = harness("#robot=scara");
    h.state_mut().file_dialog = Some(FileDialog::new(Mode::Save, "my scara", dir.clone()));
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(2);
    let saved = dir.join("my scara.json");
    let text = std::fs::read_to_string(&saved).expect("the dialog wrote the file");
    let robot = armlab::kinematics::robot_from_json(&text).expect("a valid robot file");
    assert_eq!(robot.name, h.state().session.robot.name);
    assert!(h.state().file_dialog.is_none(), "the dialog closed");

    // Open it again from another robot: pick the file in the listing, then Open.
    let mut h = harness("#robot=ur10");
    h.state_mut().file_dialog = Some(FileDialog::new(Mode::Open, "", dir.clone()));
    h.run_steps(2);
    h.get_by_label("my scara.json").click();
    h.run_steps(2);
    h.get_by_label("Open").click();
    h.run_steps(2);
    assert_eq!(h.state().session.robot.name, robot.name);
    assert_eq!(h.state().session.robot.dof(), robot.dof());
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn the_native_app_keeps_its_session_when_it_closes() {
    let file =
        std::env::temp_dir().join(format!("armlab-ui-session-{}/session", std::process::id()));
    let mut h = harness("#robot=puma560&q=0.1,0.2,0.3,0.4,0.5,0.6");
    h.state_mut().session_file = Some(file.clone());
    eframe::App::on_exit(h.state_mut());
    let hash = std::fs::read_to_string(&file).expect("the session was written");
    let reopened = armlab::app::session::Session::from_hash(&hash)
        .expect("a valid hash")
        .expect("a non-empty hash");
    assert_eq!(reopened.robot.name, "Puma 560");
    assert_eq!(reopened.q, h.state().session.q);
    if let Some(dir) = file.parent() {
        std::fs::remove_dir_all(dir).expect("clean up");
    }
}
