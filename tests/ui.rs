//! UI tests of the app through egui_kittest (native only, `app` feature): what a person
//! sees and does. The harness renders with wgpu on the machine's Vulkan adapter (lavapipe
//! here), so the 3D viewport runs its real pipeline.
#![cfg(not(target_arch = "wasm32"))]

use armlab_text::Sentence;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

use armlab::app::ArmLabApp;
use armlab::app::panels::Panel;
use armlab::app::panels::ik::IkPanel;
use armlab::app::panels::joints::JointsPanel;
use armlab::app::screen_points::ScreenPoints;
use armlab::app::state::model::{MessageKind, Model};
use armlab_core::ik::Reach;
use armlab_session::session::Session;

const SIZE: [f32; 2] = [1400.0, 860.0];

mod app_harness;

fn harness(hash: &str) -> Harness<'static, ArmLabApp> {
    app_harness::open_app(hash, SIZE)
}

fn tool_x(h: &Harness<'_, ArmLabApp>) -> f64 {
    h.state().model().fk().tool_position().x
}

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
    let h = harness("#robot=ur10&q=1,2,banana");
    assert_eq!(h.state().model().robot().name, "UR10");
    let message = h.state().model().message().expect("a message").clone();
    assert_eq!(message.kind, MessageKind::Warning);
    let message = message.text;
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
        h.state().viewport().rendered(),
        "the wgpu scene renderer drew the viewport"
    );
    h.snapshot("ur10");
}

/// The 3D view's pixels (RGBA, row by row), as egui's painter shows them this frame.
fn view_pixels(h: &mut Harness<'_, ArmLabApp>) -> Vec<u8> {
    let rect = h.state().viewport().rect().expect("the view was laid out");
    let image = h.render().expect("a frame");
    let rect = rect * h.ctx.pixels_per_point();
    let xs = (rect.left().ceil() as u32)..(rect.right().floor() as u32).min(image.width());
    let ys = (rect.top().ceil() as u32)..(rect.bottom().floor() as u32).min(image.height());
    ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
        .flat_map(|(x, y)| image.get_pixel(x, y).0)
        .collect()
}

#[test]
fn the_view_draws_a_pass_only_when_its_scene_changes_and_never_shows_a_stale_arm() {
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2");
    h.run_steps(2);
    let first = view_pixels(&mut h);
    let passes = h.state().viewport().scene_passes();
    assert!(passes >= 1, "the scene was drawn");
    // Frames with nothing new for the view (egui repaints after every event, and a
    // pointer over a side panel changes only the panel) reuse the picture.
    h.event(egui::Event::PointerMoved(egui::pos2(150.0, 300.0)));
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
    let hash = std::fs::read_to_string(&file).expect("the session was written");
    let reopened = armlab_session::session::Session::from_hash(&hash)
        .expect("a valid hash")
        .expect("a non-empty hash");
    assert_eq!(reopened.robot.name, "Puma 560");
    assert_eq!(reopened.q, h.state().model().q());
    if let Some(dir) = file.parent() {
        std::fs::remove_dir_all(dir).expect("clean up");
    }
}

/// A panel drawn alone over a model, as egui's demo app tests each demo alone.
struct Alone<P> {
    model: Model,
    panel: P,
    points: ScreenPoints,
}

fn alone<P: Panel + 'static>(preset: &str, panel: P) -> Harness<'static, Alone<P>> {
    let model = Model::new(Session::for_preset(preset).expect("a preset"));
    let mut h = Harness::builder()
        .with_size([420.0, 520.0])
        .with_context_setup(armlab::app::widgets::style::install_fonts)
        .build_ui_state(
            |ui, s: &mut Alone<P>| {
                s.points.clear();
                s.panel.ui(&mut s.model, ui, &mut s.points);
            },
            Alone {
                model,
                panel,
                points: ScreenPoints::default(),
            },
        );
    h.run_steps(2);
    h
}

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
        .panel
        .replay()
        .run
        .clone()
        .expect("the run is kept for replay");
    assert!(
        run.trace.len() > 2,
        "{} iterations recorded",
        run.trace.len()
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
    assert_eq!(h.state().panel.replay().step, 0);
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

/// The app at a screen size, one frame more settled (the columns take their widths).
fn harness_at(hash: &str, size: [f32; 2]) -> Harness<'static, ArmLabApp> {
    let mut h = app_harness::open_app(hash, size);
    h.run_steps(1);
    h
}

/// The view's share of the window's width, and whether the named points lie in the view.
fn view_share_and_points(h: &Harness<'_, ArmLabApp>, width: f32) -> f32 {
    let app = h.state();
    let rect = app.viewport().rect().expect("the view was laid out");
    for name in ["base", "tool", "target"] {
        let [x, y] = app.points().get(name).expect("the point is drawn");
        assert!(
            rect.contains(egui::pos2(x, y)),
            "{name} ({x}, {y}) lies in the view {rect:?}"
        );
    }
    // The view's width in CSS pixels (points times the zoom) against the window's.
    rect.width() * h.ctx.zoom_factor() / width
}

#[test]
fn at_every_screen_size_the_view_keeps_its_share_and_shows_the_arm() {
    for (size, min_share) in [
        ([1024.0, 768.0], 0.5),
        ([1280.0, 720.0], 0.5),
        ([1366.0, 768.0], 0.5),
        ([1920.0, 1080.0], 0.5),
        ([820.0, 1180.0], 0.99),
        ([390.0, 844.0], 0.99),
    ] {
        let h = harness_at("#robot=ur10", size);
        let share = view_share_and_points(&h, size[0]);
        assert!(
            share >= min_share,
            "{size:?}: the view has {share} of the width"
        );
    }
    // Presentation mode on a projector: at least 60 %.
    let h = harness_at("#robot=ur10&present=on", [1024.0, 768.0]);
    let share = view_share_and_points(&h, 1024.0);
    assert!(
        share >= 0.6,
        "presentation: the view has {share} of the width"
    );
}

/// The controls of a column (buttons, menus, check boxes, fold headers) that end past its
/// visible edge: clipped, so a person reads "Solutions of th" or misses a button.
fn clipped_controls(h: &Harness<'_, ArmLabApp>, column: egui::Rect) -> Vec<String> {
    let mut clipped = Vec::new();
    for role in [
        Role::Button,
        Role::ComboBox,
        Role::CheckBox,
        Role::DisclosureTriangle,
    ] {
        for node in h.query_all_by_role(role) {
            let rect = node.rect();
            // Below the screen's foot the column scrolls: what shows there is not judged.
            let inside = rect.left() > column.left()
                && rect.left() < column.right()
                && rect.top() > column.top()
                && rect.bottom() < column.bottom();
            if inside && rect.right() > column.right() + 0.5 {
                let label = node.accesskit_node().label().unwrap_or_default();
                clipped.push(format!(
                    "{label:?} ends at {:.0} > {:.0}",
                    rect.right(),
                    column.right()
                ));
            }
        }
    }
    clipped
}

#[test]
fn on_a_projector_every_control_of_the_columns_shows_whole() {
    for size in [[1024.0, 768.0], [1280.0, 720.0], [1366.0, 768.0]] {
        let h = harness_at("#robot=ur10", size);
        let view = h.state().viewport().rect().expect("the view was laid out");
        // The left column ends where the view starts, the right one at its edge tabs.
        let column = |x0: f32, x1: f32| {
            egui::Rect::from_x_y_ranges(x0..=x1, view.top()..=h.ctx.content_rect().bottom())
        };
        let left = clipped_controls(&h, column(30.0, view.left()));
        let right = clipped_controls(&h, column(view.right(), size[0] - 30.0));
        assert!(left.is_empty(), "{size:?}, left column: {left:#?}");
        assert!(right.is_empty(), "{size:?}, right column: {right:#?}");
    }
    // Each fold of the projector's columns opened on its own: what it shows fits too.
    let mut h = harness_at("#robot=ur10", [1024.0, 768.0]);
    let view = h.state().viewport().rect().expect("the view was laid out");
    let bottom = h.ctx.content_rect().bottom();
    let columns = [
        egui::Rect::from_x_y_ranges(30.0..=view.left(), view.top()..=bottom),
        egui::Rect::from_x_y_ranges(view.right()..=994.0, view.top()..=bottom),
    ];
    let folds: Vec<String> = h
        .query_all_by_role(Role::DisclosureTriangle)
        .filter(|n| n.rect().bottom() < bottom)
        .filter_map(|n| n.accesskit_node().label())
        .collect();
    assert!(folds.len() >= 6, "the columns' folds: {folds:?}");
    for fold in folds {
        h.get_by_label(&fold).click();
        h.run_steps(3);
        for column in columns {
            let clipped = clipped_controls(&h, column);
            assert!(clipped.is_empty(), "with {fold:?} open: {clipped:#?}");
        }
        h.get_by_label(&fold).click();
        h.run_steps(3);
    }
}

#[test]
fn narrow_layout_snapshot_with_the_joints_sheet() {
    let mut h = harness_at("#robot=ur10", [390.0, 844.0]);
    h.get_by_label("Joints").click();
    h.run_steps(3);
    assert_eq!(
        h.state().sheet(),
        Some(armlab_session::settings::PanelKind::Joints)
    );
    let share = view_share_and_points(&h, 390.0);
    assert!(
        share >= 0.99,
        "the view keeps the full width above the sheet"
    );
    h.snapshot("narrow_joints_sheet");
}

#[test]
fn presentation_snapshot_at_a_projectors_size() {
    let mut h = harness_at("#robot=ur10&present=on", [1024.0, 768.0]);
    h.run_steps(2);
    h.snapshot("presentation_1024x768");
}

#[test]
fn a_closed_panel_reopens_from_its_edge_tab_and_shortcuts_skip_text_fields() {
    let mut h = harness_at("#robot=ur10&panels=joints,ik,robot", [1280.0, 800.0]);
    assert!(
        h.query_by_label("decimals:").is_none(),
        "the matrices are closed"
    );
    h.get_by_label("Matrices").click();
    h.run_steps(3);
    assert!(
        h.query_by_label("decimals:").is_some(),
        "the edge tab opened them"
    );
    // P toggles presentation mode; typed into a text field it does not.
    h.key_press(egui::Key::P);
    h.run_steps(2);
    assert!(h.state().model().settings().presentation);
    h.key_press(egui::Key::P);
    h.run_steps(2);
    assert!(!h.state().model().settings().presentation);
    // The same key with a text field focused (a DH cell) is the field's, not the
    // shortcut's.
    h.get_by_label("DH table (editable)").click();
    h.run_steps(2);
    h.query_all_by_role(Role::TextInput)
        .next()
        .expect("a DH cell")
        .focus();
    h.run_steps(1);
    assert!(h.ctx.text_edit_focused(), "the text field has the keyboard");
    h.key_press(egui::Key::P);
    h.run_steps(2);
    assert!(
        !h.state().model().settings().presentation,
        "P typed into a text field leaves presentation mode off"
    );
}

#[test]
fn on_a_touch_screen_every_control_is_at_least_40_points_tall() {
    let mut h = harness_at("#robot=ur10", [820.0, 1180.0]);
    h.state_mut().set_touch(true);
    h.run_steps(3);
    let tabs = ["Fit", "Joints", "IK", "Matrices"].map(|l| (l, h.get_by_label(l).rect()));
    h.get_by_label("Joints").click();
    h.run_steps(3);
    for (label, rect) in tabs {
        assert!(rect.height() >= 40.0, "{label} is {} tall", rect.height());
    }
    for label in ["Zero", "Home"] {
        let rect = h.get_by_label(label).rect();
        assert!(rect.height() >= 40.0, "{label} is {} tall", rect.height());
    }
    let slider = h
        .get_all_by_role(Role::Slider)
        .next()
        .expect("a joint slider");
    assert!(
        slider.rect().height() >= 40.0,
        "a slider is {} tall",
        slider.rect().height()
    );
}

/// A finger's events as the browser delivers them (eframe's touch handlers): the press or
/// move of the primary pointer, then the touch itself.
fn finger(phase: egui::TouchPhase, pos: egui::Pos2) -> Vec<egui::Event> {
    let pointer = match phase {
        egui::TouchPhase::Start => egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed: true,
            modifiers: egui::Modifiers::NONE,
        },
        egui::TouchPhase::Move => egui::Event::PointerMoved(pos),
        egui::TouchPhase::End | egui::TouchPhase::Cancel => egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed: false,
            modifiers: egui::Modifiers::NONE,
        },
    };
    let touch = egui::Event::Touch {
        device_id: egui::TouchDeviceId(1),
        id: egui::TouchId(1),
        phase,
        pos,
        force: None,
    };
    vec![pointer, touch]
}

#[test]
fn a_finger_held_on_the_target_before_moving_still_drags_it() {
    // egui turns a touch held still for longer than a click (0.8 s) into a long press and
    // drops the drag it was waiting for; students rest a finger on the ball before moving.
    let mut h = harness_at(
        "#robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=position",
        [390.0, 844.0],
    );
    h.state_mut().set_touch(true);
    h.run_steps(3);
    let start = h.state().points().get("target").expect("target on screen");
    let before = h.state().model().target().translation.vector;
    let from = egui::pos2(start[0], start[1]);
    for e in finger(egui::TouchPhase::Start, from) {
        h.event(e);
    }
    // The harness's clock advances a quarter second a frame: the finger rests 1.5 s.
    h.run_steps(6);
    let mut pos = from;
    for _ in 0..12 {
        pos += egui::vec2(-4.0, 3.0);
        for e in finger(egui::TouchPhase::Move, pos) {
            h.event(e);
        }
        h.run_steps(1);
    }
    assert!(
        h.state().viewport().dragging(),
        "the ball is held by the finger"
    );
    for e in finger(egui::TouchPhase::End, pos) {
        h.event(e);
    }
    h.run_steps(2);
    let moved = (h.state().model().target().translation.vector - before).norm();
    assert!(
        moved > 20.0,
        "the target moved {moved:.1} mm under the finger"
    );
    assert!(!h.state().viewport().dragging());
}

#[test]
fn the_panda_self_motion_slider_swings_the_elbow_and_keeps_the_hand() {
    let mut h = harness("#robot=panda&q=0.4,-0.3,-0.5,-1.9,0.3,1.9,-0.2&task=full");
    let before = h.state().model().fk().base_from_tool;
    let q0 = h.state().model().q().to_vec();
    h.get_by_role_and_label(Role::Slider, "Self-motion").focus();
    h.run_steps(1);
    // Each arrow key moves the slider by 0.05 rad. (The slider loses the keyboard after a
    // change that moves the arm, so it is focused again before each key, as a click would.)
    for _ in 0..6 {
        h.get_by_role_and_label(Role::Slider, "Self-motion").focus();
        h.run_steps(1);
        h.key_press(egui::Key::ArrowRight);
        h.run_steps(1);
    }
    let model = h.state().model();
    let moved: f64 = model
        .q()
        .iter()
        .zip(&q0)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(
        (0.25..=0.3 + 1e-9).contains(&moved),
        "the joints moved {moved} rad along the self-motion"
    );
    let after = model.fk().base_from_tool;
    let dp = (after.translation.vector - before.translation.vector).norm();
    let dr = (after.rotation.inverse() * before.rotation).angle();
    assert!(dp < 1e-6 && dr < 1e-6, "the hand moved {dp} m and {dr} rad");
    assert!(
        h.query_by_label_contains("The tool stayed within")
            .is_some()
    );
}

#[test]
fn the_jacobian_columns_and_the_velocity_ellipsoid_are_drawn_at_the_tool() {
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2&show=jcols,vel&panels=matrices");
    h.run_steps(2);
    assert!(
        h.query_by_label_contains("J columns:").is_some(),
        "the legend is shown"
    );
    assert!(
        h.state()
            .model()
            .settings()
            .overlays
            .contains(armlab_session::settings::Overlay::VelocityEllipsoid)
    );
    h.snapshot("jacobian_columns_ellipsoid");
}

#[test]
fn ghosts_from_a_link_show_without_the_ik_panel() {
    // A lecturer's link opened on a phone (no sheet open) or with the IK panel closed: the
    // ghosts must not wait for the IK panel's list, which finds the solutions only when shown.
    for (hash, size) in [
        (
            "#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2&show=ghosts&panels=joints",
            [1366.0, 768.0],
        ),
        (
            "#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2&show=ghosts",
            [390.0, 844.0],
        ),
    ] {
        let h = harness_at(hash, size);
        assert!(h.state().sheet().is_none(), "{size:?}: no sheet open");
        let rows = h
            .state()
            .model()
            .branches()
            .map(|b| b.rows.len())
            .unwrap_or_default();
        assert_eq!(rows, 8, "{size:?}: the UR10's eight branches");
        let ghosts = h
            .state()
            .points()
            .all()
            .iter()
            .filter(|(n, _)| n.starts_with("ghost-"))
            .count();
        assert_eq!(
            ghosts, 7,
            "{size:?}: every branch but the arm's own is drawn"
        );
    }
}

#[test]
fn every_ur10_branch_is_listed_and_a_click_on_its_ghost_moves_the_arm_there() {
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2&show=ghosts&panels=ik");
    h.get_by_label("Solutions of this target").click();
    h.run_steps(2);
    let rows = h
        .state()
        .model()
        .branches()
        .expect("the IK panel listed the solutions")
        .rows
        .clone();
    assert_eq!(rows.len(), 8, "the UR10 has eight branches here");
    // Wrist flipped and not: two rows each.
    assert_eq!(
        h.query_all_by_label_contains("shoulder right, elbow up")
            .count(),
        2
    );
    let q0 = h.state().model().q().to_vec();
    let (name, pos) = h
        .state()
        .points()
        .all()
        .iter()
        .find(|(n, _)| n.starts_with("ghost-"))
        .cloned()
        .expect("a ghost on screen");
    let index: usize = name["ghost-".len()..].parse().unwrap();
    let at = egui::pos2(pos[0], pos[1]);
    h.event(egui::Event::PointerMoved(at));
    h.run_steps(1);
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
        h.run_steps(1);
    }
    let q = h.state().model().q().to_vec();
    assert_ne!(q, q0, "the arm moved");
    let want = &rows[index - 1].q;
    for (a, b) in q.iter().zip(want) {
        assert!((a - b).abs() < 1e-9, "{q:?} is solution {index} {want:?}");
    }
    h.snapshot("ghosts");
}

#[test]
fn the_rrr_symbolic_t03_reads_like_the_lecture_and_highlights_the_hovered_joint() {
    let mut h = harness("#robot=rrr&panels=joints,matrices");
    // The orientation and the Jacobian folded: the symbolic matrices come into sight.
    for fold in ["Tool orientation", "Jacobian"] {
        h.get_by_label(fold).click();
        h.run_steps(2);
    }
    h.get_by_label("symbolic").click();
    h.run_steps(2);
    // T_03 is below the fold, where blocks are not laid out: the panel is scrolled to it,
    // as a person would, and back to the top.
    let panel = h.get_by_label("symbolic").rect().center();
    assert!(
        h.query_by_label("c1(222.1 c2 + 136.2 c23)").is_none(),
        "T_03 out of sight is not laid out"
    );
    app_harness::wheel(&mut h, panel, -2000.0);
    // SPEC §1.4: x = c1(222.1 c2 + 136.2 c23).
    assert!(
        h.query_by_label("c1(222.1 c2 + 136.2 c23)").is_some(),
        "T_03's x entry"
    );
    app_harness::wheel(&mut h, panel, 4000.0);
    // The pointer over θ2's slider: its link (2) is the one under the pointer.
    let slider = h.get_by_role_and_label(Role::Slider, "θ2").rect().center();
    h.event(egui::Event::PointerMoved(slider));
    h.run_steps(2);
    assert_eq!(h.state().model().hovered_link(), Some(2));
    h.snapshot("symbolic_rrr");
}

#[test]
fn the_notebook_demos_print_the_notebooks_numbers_and_plot_the_error() {
    let mut h = harness("#robot=ur10&panels=ik");
    h.get_by_label("The lecture notebook's runs").click();
    h.run_steps(2);
    for (button, printed, decimals) in [
        ("Newton–Raphson", [-5.9844821, 20.54568008], [7, 8]),
        ("Gradient descent", [0.46058393, 2.0236129], [8, 7]),
    ] {
        h.get_by_label(button).click();
        h.run_steps(3);
        let run = h
            .state()
            .ik_panel()
            .replay()
            .run
            .clone()
            .expect("the demo ran");
        for ((got, want), d) in run.q.iter().zip(printed).zip(decimals) {
            let half = 0.5 * 10f64.powi(-d);
            assert!(
                (got - want).abs() <= half,
                "{button}: {got} prints as {want}"
            );
        }
        assert_eq!(h.state().model().robot().name, "Planar 2R");
        assert!(h.query_by_label_contains("never wrapped").is_some());
        assert!(h.query_by_label_contains("wrapped into").is_some());
    }
    h.snapshot("notebook_gradient");
}

#[test]
fn the_workspace_cloud_fills_over_frames_and_says_where_the_target_lies() {
    use armlab::app::view3d::workspace::{SAMPLES, measure};
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2&show=cloud&panels=ik");
    h.get_by_label("Reachable workspace").click();
    h.run_steps(1);
    assert!(h.state().model().workspace().is_some_and(|c| !c.is_empty()));
    // A time budget a frame: slices of 256 samples until it is spent. With a clock that
    // advances 1 ms per reading and a 4 ms budget, each frame adds exactly 3 slices, so
    // the cloud grows over frames and is not full at once (the sampler is fast enough to
    // fill all 20 000 samples within one real frame's budget on some machines).
    // The other measure starts a new cloud.
    use armlab_core::WorkspaceMeasure;
    let m = measure(h.state().model());
    let other = match m {
        WorkspaceMeasure::Manipulability => WorkspaceMeasure::SigmaMin,
        WorkspaceMeasure::SigmaMin => WorkspaceMeasure::Manipulability,
    };
    let ticks = std::cell::Cell::new(0.0);
    let clock = || {
        ticks.set(ticks.get() + 1.0);
        ticks.get()
    };
    let mut counts = Vec::new();
    for _ in 0..3 {
        h.state_mut()
            .model_mut()
            .fill_workspace(other, SAMPLES, 4.0, clock);
        counts.push(h.state().model().workspace().map_or(0, |c| c.len()));
    }
    assert_eq!(counts, [768, 1536, 2304], "three slices of 256 a frame");
    // The rest at once, then the panel reads it.
    h.state_mut().model_mut().fill_workspace(
        m,
        SAMPLES,
        f64::INFINITY,
        armlab::app::platform::clock::now_ms,
    );
    h.run_steps(2);
    let cloud = h.state().model().workspace().expect("a cloud");
    assert!(cloud.is_full() && cloud.len() == SAMPLES, "{}", cloud.len());
    // The target sits on the tool: inside the sampled workspace.
    assert!(
        h.query_by_label_contains("The target is inside the sampled workspace")
            .is_some()
    );
    h.snapshot("workspace_cloud");
}

#[test]
fn both_conventions_are_shown_side_by_side_and_agree() {
    let mut h = harness("#robot=ur10&q=0.4,-1.1,1.3,-1.6,-1.4,0.2&show=both&panels=robot");
    h.get_by_label("Both conventions side by side").click();
    h.run_steps(2);
    assert!(h.query_by_label("standard (Spong)").is_some());
    assert!(h.query_by_label("modified (Craig)").is_some());
    let agree = h
        .query_by_label_contains("tables' T_0n agree to")
        .expect("the agreement is shown");
    let text = agree
        .accesskit_node()
        .value()
        .unwrap_or_default()
        .to_string();
    let number: f64 = text
        .split_whitespace()
        .find_map(|w| w.parse().ok())
        .expect("a number");
    assert!(number < 1e-9, "{text}");
    h.snapshot("both_conventions");
}

#[test]
fn the_metrover_reaches_only_some_tool_directions_at_its_target_and_the_ur10_all() {
    let reached = |hash: &str| {
        let mut h = harness(hash);
        h.get_by_label("Reachable workspace").click();
        h.run_steps(3);
        let model = h.state().model();
        let sphere = model.directions().expect("the sphere was filled");
        let n = sphere.near.iter().filter(|n| **n).count();
        assert!(
            h.query_by_label(&format!(
                "{n} of 64 tool directions reachable here (to 13°)"
            ))
            .is_some(),
            "{hash}: the panel says {n} of 64"
        );
        (n, sphere.directions.len())
    };
    // Five joints: the tool's y axis (joint 5's) points along a curve of directions.
    let (metrover, total) = reached("#robot=metrover&show=dirs&panels=ik");
    assert_eq!(total, 64);
    assert!(
        metrover > 0 && metrover < total / 2,
        "the Metrover reaches {metrover} of {total}"
    );
    // Six joints reach them all.
    let (ur10, total) = reached("#robot=ur10&show=dirs&panels=ik&task=position");
    assert!(ur10 >= total * 9 / 10, "the UR10 reaches {ur10} of {total}");
}

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

// --- The editor keeps q, the DH-table exercise, predict then reveal ----------------------

/// Types `text` over the `index`-th text input (the DH cells come first in table order).
fn type_into_cell(h: &mut Harness<'_, ArmLabApp>, index: usize, text: &str) {
    let cells: Vec<_> = h.query_all_by_role(Role::TextInput).collect();
    cells[index].focus();
    drop(cells);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text(text.into()));
    h.run_steps(2);
}

#[test]
fn adding_or_removing_a_joint_in_the_dh_editor_keeps_the_other_joints_values() {
    let mut h = harness("#robot=rrr&q=0.3,-0.4,0.5&panels=robot");
    h.get_by_label("DH table (editable)").click();
    h.run_steps(2);
    h.get_by_label("+ Add joint").click();
    h.run_steps(3);
    let model = h.state().model();
    assert_eq!(model.robot().dof(), 4);
    assert_eq!(model.q(), &[0.3, -0.4, 0.5, 0.0], "the new joint at 0");
    // The tool follows the kept pose: the RRR's first three joints where they were.
    let rrr = armlab_core::preset("rrr").expect("a preset");
    let before = armlab_core::ForwardKinematics::new(&rrr, &[0.3, -0.4, 0.5])
        .expect("a pose")
        .tool_position();
    assert!((model.fk().tool_position() - before).norm() < 1e-9);
    // Remove joint 2 (the × on its row): joints 1, 3 and 4 keep their values.
    h.get_by_label("Remove joint 2").click_accesskit();
    h.run_steps(3);
    let model = h.state().model();
    assert_eq!(model.robot().dof(), 3);
    assert_eq!(model.q(), &[0.3, 0.5, 0.0]);
    assert!(
        (model.robot().joints[1].dh.a - 136.2).abs() < 1e-12,
        "row 3 moved up"
    );
}

#[test]
fn the_dh_exercise_hides_the_table_and_names_the_joint_of_a_wrong_answer() {
    let mut h = harness("#exercise=rrr&panels=robot,matrices&q=0.4,0.5,-0.9");
    let hash = h.state().hash();
    assert!(hash.starts_with("exercise=rrr&"), "{hash}");
    assert!(!hash.contains("dh=") && !hash.contains("robot="), "{hash}");
    assert!(h.state().model().table_hidden());
    let hidden = "Hidden during the DH-table exercise";
    assert!(
        h.query_by_label_contains(hidden).is_some(),
        "the matrices say why they are empty"
    );
    assert!(
        h.query_by_label_contains("T_03").is_none(),
        "no A_i or T_0i anywhere"
    );
    assert!(
        h.query_by_label("RRR").is_none(),
        "the preset's name does not show"
    );
    // The answer starts blank: 3 rows of zeros (+ its limits) in standard DH.
    let answer = h.state().robot_panel().exercise().answer().clone();
    assert_eq!(answer.rows.len(), 3);
    // A wrong table: a2 = 222.1 written in row 1.
    for (cell, text) in [(1, "100.9"), (3, "90"), (2, "222.1"), (12 + 2, "136.2")] {
        type_into_cell(&mut h, cell, text);
    }
    h.get_by_label("Check").click();
    h.run_steps(2);
    let wrong = "Joint 2's frame is the first to disagree: the length a in row 1 belongs in column a of row 2.";
    assert!(
        h.query_by_label(wrong).is_some(),
        "the verdict names joint 2"
    );
    assert!(h.state().model().table_hidden(), "still hidden");
    h.snapshot("exercise_rrr_wrong");
    // Move a2 to row 2: correct, and the table shows everywhere again.
    type_into_cell(&mut h, 2, "0");
    type_into_cell(&mut h, 6 + 2, "222.1");
    h.get_by_label("Check").click();
    h.run_steps(2);
    assert!(
        h.query_by_label_contains("Correct: your table gives the robot's tool pose")
            .is_some()
    );
    assert!(!h.state().model().table_hidden());
    assert!(h.query_by_label_contains(hidden).is_none());
    assert!(
        h.query_all_by_label_contains("T_03").count() > 0,
        "the matrices are back"
    );
    assert!(
        h.query_by_label("The robot's own table (standard (Spong)):")
            .is_some()
    );
}

#[test]
fn a_mystery_exercise_draws_its_axes_and_fits_every_screen() {
    for (size, min_share) in [
        ([1024.0, 768.0], 0.5),
        ([1280.0, 720.0], 0.5),
        ([1366.0, 768.0], 0.5),
        ([1920.0, 1080.0], 0.5),
        ([820.0, 1180.0], 0.99),
        ([390.0, 844.0], 0.99),
    ] {
        let h = harness_at("#exercise=mystery-42", size);
        let share = view_share_and_points(&h, size[0]);
        assert!(
            share >= min_share,
            "{size:?}: the view has {share} of the width"
        );
        assert!(h.state().model().table_hidden());
    }
    let mut h = harness_at("#exercise=mystery-42&panels=robot", [1366.0, 768.0]);
    h.run_steps(2);
    let model = h.state().model();
    assert!((2..=6).contains(&model.robot().dof()));
    assert!(model.hash().starts_with("exercise=mystery-42&"));
    // What the view labels: every joint's axis and at least one length per joint.
    let dims = armlab::app::view3d::exercise::dimensions(model.robot(), model.fk());
    let lengths = dims.iter().filter(|d| d.length > 1e-6).count();
    assert!(lengths >= model.robot().dof(), "{dims:?}");
    h.snapshot("exercise_mystery_42");
}

#[test]
fn predict_then_reveal_hides_entries_until_a_click_and_the_link_keeps_them() {
    let mut h = harness_at(
        "#robot=rrr&q=0.4,0.5,-0.9&present=on&ppanels=matrices&decimals=2&hide=Tn.34,J2",
        [1024.0, 768.0],
    );
    h.run_steps(2);
    let tool = h.state().model().fk().tool_position();
    let z = format!("{:.2}", tool.z);
    // T_0n's z and J's column 2 (six entries) are "?".
    assert_eq!(h.query_all_by_label("?").count(), 7);
    assert_eq!(h.query_all_by_label(&z).count(), 0, "z = {z} is hidden");
    h.snapshot("predict_reveal_1024x768");
    // A click reveals z (drawn first); "Hide again" puts it back.
    h.get_all_by_label("?").next().expect("z's ?").click();
    h.run_steps(2);
    assert_eq!(h.query_all_by_label(&z).count(), 1, "z = {z} revealed");
    assert_eq!(
        h.query_all_by_label("?").count(),
        6,
        "the column stays hidden"
    );
    h.get_by_label("Hide again").click();
    h.run_steps(2);
    assert_eq!(h.query_all_by_label("?").count(), 7);
    // Choosing: every number shows; a click on T_0n's y hides it too, and the link
    // carries it.
    h.get_by_label("Choose what to hide").click();
    h.run_steps(2);
    assert_eq!(
        h.query_all_by_label(&z).count(),
        1,
        "z shows while choosing"
    );
    assert!(
        h.state().points().get("hide-Tn").is_some(),
        "T_0n's whole-matrix ?"
    );
    let y = format!("{:.2}", tool.y);
    h.get_all_by_label(&y).next().expect("T_0n's y").click();
    h.run_steps(2);
    let hash = h.state().hash();
    assert!(hash.contains("hide=Tn.24,Tn.34,J2"), "{hash}");
    assert!(h.state().points().get("cell-Tn-2-4").is_some());
    h.get_by_label("Choose what to hide").click();
    h.run_steps(2);
    assert_eq!(h.query_all_by_label("?").count(), 8);
}

/// A robot file with keep-out boxes sets the motion lab's boxes; a file with a bad box
/// gets the file's sentence naming the box, and the last good robot and boxes stay.
#[test]
fn a_robot_file_brings_its_keep_out_boxes_and_a_bad_box_leaves_the_last_good_robot() {
    use armlab::app::panels::robot::RobotPanel;
    let mut model = Model::new(Session::for_preset("ur10").expect("a preset"));
    let mut panel = RobotPanel::new(model.robot());
    let ur10 = armlab_core::preset("ur10").expect("the UR10");
    let mut file: serde_json::Value =
        serde_json::from_str(&armlab_core::robot_to_json(&ur10)).expect("JSON");
    file["name"] = "UR10 in a cell".into();
    file["keep_out"] = serde_json::json!([{ "centre": [900, 0, 400], "size": [200, 400, 800] }]);
    assert!(panel.load_robot_text(&mut model, &file.to_string()));
    assert_eq!(model.robot().name, "UR10 in a cell");
    let boxes = model.motion().keep_outs().to_vec();
    assert_eq!(boxes.len(), 1);
    assert_eq!(boxes[0].size, nalgebra::Vector3::new(200.0, 400.0, 800.0));
    model.set_collisions_on(true);
    assert_eq!(
        model.motion().contact(),
        Some("Contact: link 4 touches keep-out box 1."),
        "the file's box is checked: the UR10's arm at home reaches into it"
    );

    file["name"] = "bad".into();
    file["keep_out"][0]["size"] = serde_json::json!([200, -5, 800]);
    assert!(!panel.load_robot_text(&mut model, &file.to_string()));
    let message = model.message().expect("a message");
    assert_eq!(message.kind, MessageKind::Error);
    assert!(
        message.text.ends_with(
            "In keep-out box 1, the field \"size\" holds -5: a size cannot be negative."
        ),
        "{}",
        message.text
    );
    assert_eq!(model.robot().name, "UR10 in a cell");
    assert_eq!(model.motion().keep_outs(), &boxes[..]);
}

/// Bad text in waypoint 1's x gets a sentence and the last good x stays; a good value is
/// taken.
fn edit_waypoint_1_x(h: &mut Harness<'_, ArmLabApp>) {
    // Bad text in waypoint 1's x: a sentence, and the last good x stays.
    let x0 = h.state().model().paths().waypoints().poses()[0]
        .translation
        .x;
    let inputs: Vec<_> = h
        .query_all_by_role(Role::TextInput)
        .filter(|n| n.accesskit_node().label().as_deref() == Some("Waypoint 1: x, y, z (mm)"))
        .collect();
    assert_eq!(inputs.len(), 3, "x, y and z of waypoint 1");
    inputs[0].focus();
    drop(inputs);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("12,5x".into()));
    h.run_steps(2);
    assert!(
        h.query_by_label("\"12,5x\" is not a number.").is_some(),
        "the sentence shows"
    );
    assert_eq!(
        h.state().model().paths().waypoints().poses()[0]
            .translation
            .x,
        x0
    );
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text(format!("{}", (x0 + 10.0).round())));
    h.run_steps(2);
    let x1 = h.state().model().paths().waypoints().poses()[0]
        .translation
        .x;
    assert_eq!(x1, (x0 + 10.0).round(), "a good value is taken");
}

/// Visits the two waypoints in joint space: Move turns on, the arm sets off toward
/// waypoint 1, goes on to waypoint 2 and rests there.
fn visit_the_waypoints_in_joint_space(h: &mut Harness<'_, ArmLabApp>) {
    // Visit in joint space: move turns on and the arm sets off toward waypoint 1, then
    // goes on to waypoint 2 and rests there.
    h.get_by_label("Joint space").click();
    h.get_by_label("Visit").click();
    h.run_steps(4);
    let model = h.state().model();
    assert!(model.motion().on(), "Visit turns Move on");
    assert!(model.paths().visit().is_some(), "the visit is under way");
    assert!(h.query_by_label("Visiting: waypoint 1 of 2.").is_some());
    assert!(model.motion().trail().len() >= 2, "the trail draws");
    let mut on_to_the_second = false;
    let mut frames = 4;
    while frames < 600 {
        let model = h.state().model();
        if model.paths().finished() && !model.motion().moving() {
            break;
        }
        on_to_the_second |= h.query_by_label("Visiting: waypoint 2 of 2.").is_some();
        h.run_steps(1);
        frames += 1;
    }
    let model = h.state().model();
    assert!(
        model.paths().finished() && !model.motion().moving(),
        "the visit ends within {frames} frames"
    );
    assert!(on_to_the_second, "waypoint 1 was reached, the arm went on");
    let last = model.paths().waypoints().poses()[1].translation.vector;
    let off = (model.fk().tool_position() - last).norm();
    assert!(off < 0.01, "the tool rests {off} mm from waypoint 2");
}

#[test]
fn both_paths_are_drawn_side_by_side_the_line_says_where_it_fails_and_waypoints_are_visited() {
    use armlab_core::path::PathKind;
    use armlab_core::tool_pose;
    let mut h = harness("#robot=ur10&q=0.3,-1.2,1.4,-1.8,-1.5,0&panels=motion");
    h.get_by_label("Paths and waypoints").click();
    h.run_steps(2);
    // Two waypoints on either side of the base: the straight line between them passes by
    // the base's axis, where the shoulder is singular or the line out of reach.
    for q in [
        [0.3, -1.2, 1.4, -1.8, -1.5, 0.0],
        [0.3 + std::f64::consts::PI, -1.2, 1.4, -1.8, -1.5, 0.0],
    ] {
        let pose = tool_pose(h.state().model().robot(), &q);
        h.state_mut().model_mut().set_target(pose);
        h.get_by_label("Add waypoint").click();
        h.run_steps(1);
    }
    assert_eq!(h.state().model().paths().waypoints().len(), 2);
    h.get_by_label("Straight line").click();
    h.get_by_label("Draw both paths").click();
    h.run_steps(3);
    let model = h.state().model();
    assert_eq!(model.paths().kind(), PathKind::Cartesian);
    let plan = model.paths().plan().expect("both paths are planned");
    assert_eq!(plan.joint.points.len(), 201);
    assert_eq!(plan.line.points.len(), 201);
    let first = plan.line.problems.first().expect("the line has a problem");
    let sentence = first.sentence(armlab_text::Lang::En);
    assert!(
        h.query_by_label(&sentence).is_some(),
        "the panel says: {sentence}"
    );
    edit_waypoint_1_x(&mut h);
    // The panel with both paths drawn, the legend and the line's problem marked.
    h.state_mut()
        .model_mut()
        .set_panel_open(armlab_session::settings::PanelKind::Motion, true);
    h.run_steps(2);
    h.snapshot("motion_paths");
    visit_the_waypoints_in_joint_space(&mut h);
}

#[test]
fn the_paths_part_with_waypoints_fits_a_projector_and_a_phone() {
    use armlab_session::settings::PanelKind;
    let hash = "#robot=ur10&panels=motion&path=line&wp=900,100,300,0,0,0;700,-200,500,0,1,0";
    for size in [
        [1024.0, 768.0],
        [1280.0, 720.0],
        [1366.0, 768.0],
        [390.0, 844.0],
    ] {
        let mut h = harness_at(hash, size);
        if size[0] < 900.0 {
            h.state_mut().set_sheet(Some(PanelKind::Motion));
            h.run_steps(2);
        }
        h.get_by_label("Paths and waypoints").click();
        h.run_steps(2);
        h.get_by_label("Draw both paths").click();
        h.run_steps(3);
        assert!(
            h.state().model().paths().plan().is_some(),
            "{size:?}: planned"
        );
        let view = h.state().viewport().rect().expect("the view was laid out");
        let bottom = h.ctx.content_rect().bottom();
        let column = if size[0] < 900.0 {
            egui::Rect::from_x_y_ranges(0.0..=size[0], view.bottom()..=bottom)
        } else {
            egui::Rect::from_x_y_ranges(30.0..=view.left(), view.top()..=bottom)
        };
        let clipped = clipped_controls(&h, column);
        assert!(clipped.is_empty(), "{size:?}: {clipped:#?}");
        for label in ["Add waypoint", "Visit", "Straight line", "Joint space"] {
            let rect = h.get_by_label(label).rect();
            assert!(
                rect.min.x >= 0.0 && rect.max.x <= size[0],
                "{size:?}: {label} at {rect:?}"
            );
        }
    }
}

/// The DH table's cells that a person cannot read whole at this screen: past the visible
/// edge of `column` (sideways), or narrower than their text.
fn hidden_dh_cells(h: &Harness<'_, ArmLabApp>, column: egui::Rect) -> Vec<String> {
    let font = egui::TextStyle::Body.resolve(&h.ctx.global_style());
    let mut hidden = Vec::new();
    for node in h.query_all_by_role(Role::TextInput) {
        let rect = node.rect();
        let text = node.accesskit_node().value().unwrap_or_default();
        let width = h
            .ctx
            .fonts_mut(|f| f.layout_no_wrap(text.to_string(), font.clone(), egui::Color32::WHITE))
            .size()
            .x;
        if rect.left() < column.left() - 0.5 || rect.right() > column.right() + 0.5 {
            hidden.push(format!(
                "{text:?} at x {:.0}..{:.0}",
                rect.left(),
                rect.right()
            ));
        } else if rect.width() < width + 12.0 {
            hidden.push(format!(
                "{text:?} cut: {:.0} wide for {width:.0}",
                rect.width()
            ));
        }
    }
    hidden
}

#[test]
fn the_dh_table_shows_every_cell_whole_at_every_screen_size() {
    for size in [
        [1024.0, 768.0],
        [1280.0, 720.0],
        [1366.0, 768.0],
        [1920.0, 1080.0],
        [820.0, 1180.0],
        [390.0, 844.0],
    ] {
        let mut h = harness_at("#robot=ur10&panels=robot,matrices", size);
        let wide = h.state().sheet().is_none() && size[0] > size[1];
        if !wide {
            h.get_by_label("Robot").click();
            h.run_steps(3);
        }
        h.get_by_label("DH table (editable)").click();
        h.run_steps(3);
        let view = h.state().viewport().rect().expect("the view was laid out");
        let column = if wide {
            egui::Rect::from_x_y_ranges(30.0..=view.left(), view.top()..=view.bottom())
        } else {
            egui::Rect::from_x_y_ranges(0.0..=size[0], view.bottom()..=size[1])
        };
        if std::env::var_os("DUMP_DH").is_some() {
            let image = h.render().expect("a frame");
            image
                .save(format!("/tmp/dh-{}x{}.png", size[0], size[1]))
                .expect("saved");
        }
        let cells = h.query_all_by_role(Role::TextInput).count();
        assert_eq!(cells, 36, "{size:?}: six joints × six cells");
        let hidden = hidden_dh_cells(&h, column);
        assert!(hidden.is_empty(), "{size:?}: {hidden:#?}");
        // A wrong cell's sentence goes under the table: it widens no column.
        type_into_cell(&mut h, 8, "abc");
        h.run_steps(2);
        assert!(
            h.query_by_label_contains("\"abc\" is not a number")
                .is_some(),
            "{size:?}: the sentence shows"
        );
        let hidden = hidden_dh_cells(&h, column);
        assert!(
            hidden.is_empty(),
            "{size:?}, with a wrong cell: {hidden:#?}"
        );
        // A valid edit: the menu says "UR10 (edited)", cut to the column if need be, and
        // its label stays on one line.
        type_into_cell(&mut h, 8, "-612.5");
        h.run_steps(2);
        assert_eq!(h.state().model().robot().joints[1].dh.a, -612.5);
        let preset = h.get_by_label("Preset").rect();
        assert!(
            preset.height() < 30.0 && preset.right() <= column.right() + 0.5,
            "{size:?}: the preset menu and its label take one line in the column: {preset:?}"
        );
    }
}

#[test]
fn the_preset_menu_names_the_robot_whole_at_every_screen_size() {
    for size in [
        [1024.0, 768.0],
        [1280.0, 720.0],
        [1366.0, 768.0],
        [820.0, 1180.0],
        [390.0, 844.0],
    ] {
        let mut h = harness_at("#robot=panda", size);
        if h.state().sheet().is_some() || size[0] < size[1] {
            h.get_by_label("Robot").click();
            h.run_steps(3);
        }
        let menus: Vec<(String, egui::Rect)> = h
            .query_all_by_role(Role::ComboBox)
            .map(|n| {
                let value = n.accesskit_node().value().unwrap_or_default().to_string();
                (value, n.rect())
            })
            .collect();
        // In a projector's side column the menu's label goes above and the name wraps if it
        // must, inside the screen, rather than being cut ("Franka Pa…").
        let preset = menus
            .iter()
            .find(|(value, _)| value.starts_with("Franka"))
            .unwrap_or_else(|| panic!("{size:?}: the preset menu among {menus:?}"));
        assert_eq!(preset.0, "Franka Panda", "{size:?}");
        let view = h.state().viewport().rect().expect("the view was laid out");
        let right = if view.left() > 100.0 {
            view.left()
        } else {
            size[0]
        };
        assert!(
            preset.1.left() >= 0.0 && preset.1.right() <= right + 0.5,
            "{size:?}: the menu at {:?} ends past {right}",
            preset.1
        );
        let label = h.get_by_role_and_label(Role::Label, "Preset").rect();
        assert!(
            label.right() <= right + 0.5 && label.height() < 30.0,
            "{size:?}: the label at {label:?}"
        );
    }
}

#[test]
fn the_ik_menus_sit_alike_beside_or_under_their_labels() {
    // At 1280×720 "Full pose (6 rows)" sat beside "Task" and "Damped least squares" under
    // "Method": one group, two arrangements.
    let mut seen = Vec::new();
    for size in [
        [1024.0, 768.0],
        [1280.0, 720.0],
        [1366.0, 768.0],
        [1920.0, 1080.0],
    ] {
        let h = harness_at("#robot=ur10", size);
        let beside = |label: &str, value: &str| {
            let label = h.get_by_role_and_label(Role::Label, label).rect();
            let menu = h
                .query_all_by_role(Role::ComboBox)
                .find(|n| n.accesskit_node().value().as_deref() == Some(value))
                .unwrap_or_else(|| panic!("{size:?}: the {value:?} menu"))
                .rect();
            assert!(menu.right() <= h.state().viewport().rect().expect("a view").left());
            menu.left() > label.right() && (menu.center().y - label.center().y).abs() < 4.0
        };
        let task = beside("Task", "Full pose (6 rows)");
        let method = beside("Method", "Damped least squares");
        assert_eq!(
            task, method,
            "{size:?}: task beside {task}, method beside {method}"
        );
        seen.push(task);
    }
    // Under at a projector's 1024, beside at full HD.
    assert_eq!(seen.first(), Some(&false));
    assert_eq!(seen.last(), Some(&true));
}

#[test]
fn on_a_projector_the_motion_panel_keeps_to_its_column() {
    let size = [1024.0, 768.0];
    let h = harness_at("#robot=ur10&panels=motion,matrices", size);
    let view = h.state().viewport().rect().expect("the view was laid out");
    let bottom = h.ctx.content_rect().bottom();
    let column = egui::Rect::from_x_y_ranges(30.0..=view.left(), view.top()..=bottom);
    let clipped = clipped_controls(&h, column);
    assert!(clipped.is_empty(), "{clipped:#?}");
    // The controller menu's label stays on one line beside it (it wrapped a letter per
    // line), and the typed goal's Drive button shows whole.
    let menu = h.get_by_label("Controller").rect();
    assert!(menu.height() < 30.0, "the menu and its label: {menu:?}");
    let drive = h.get_by_label("Drive").rect();
    assert!(
        drive.right() <= view.left() && drive.width() > 30.0,
        "Drive at {drive:?}"
    );
}

/// What of the left column runs into the view (its unclipped rectangle crosses the view's
/// left edge: cut where a person sees it) or stands a letter per line, with the fold
/// `fold` open.
fn left_column_overflow(h: &Harness<'_, ArmLabApp>, fold: &str) -> Vec<String> {
    let view = h.state().viewport().rect().expect("the view was laid out");
    let mut found = Vec::new();
    for node in h.query_all(egui_kittest::kittest::by().include_labels()) {
        let Some(b) = node.accesskit_node().bounding_box() else {
            continue;
        };
        let r = egui::Rect::from_min_max(
            egui::pos2(b.x0 as f32, b.y0 as f32),
            egui::pos2(b.x1 as f32, b.y1 as f32),
        );
        let ak = node.accesskit_node();
        let text = ak.label().or(ak.value()).unwrap_or_default();
        // The top bar and the column's resize handle are not the column's content.
        if r.top() < view.top() || text == "Resize panel" || r.top() > view.bottom() {
            continue;
        }
        if r.left() < view.left() - 1.0 && r.right() > view.left() + 1.0 {
            found.push(format!("{fold}: {text:?} runs to x {:.0}", r.right()));
        }
        if text.chars().count() >= 3 && r.width() < 20.0 && r.height() > 40.0 {
            found.push(format!("{fold}: {text:?} a letter per line"));
        }
    }
    found
}

#[test]
fn on_a_projector_nothing_in_the_left_column_runs_into_the_view() {
    for hash in [
        "#robot=ur10&panels=joints,ik,robot,matrices",
        "#robot=ur10&panels=motion,matrices",
        "#robot=scara&panels=joints,robot,matrices",
    ] {
        let mut h = harness_at(hash, [1024.0, 768.0]);
        let view = h.state().viewport().rect().expect("the view was laid out");
        let folds: Vec<String> = h
            .query_all_by_role(Role::DisclosureTriangle)
            .filter(|n| n.rect().right() < view.left())
            .filter_map(|n| n.accesskit_node().label())
            .collect();
        let mut found = left_column_overflow(&h, "none");
        for fold in folds {
            h.get_by_label(&fold).click();
            h.run_steps(3);
            found.extend(left_column_overflow(&h, &fold));
            h.get_by_label(&fold).click();
            h.run_steps(3);
        }
        assert!(found.is_empty(), "{hash}: {found:#?}");
    }
}

/// A projector's and a laptop's right column print the 6×6 Jacobian in blocks of columns,
/// every block inside the column, rather than a table that scrolls sideways with half its
/// columns out of sight.
#[test]
fn at_lecture_sizes_the_jacobian_shows_every_column_in_blocks() {
    for size in [[1024.0, 768.0], [1280.0, 720.0], [1366.0, 768.0]] {
        let h = harness_at("#robot=ur10&panels=joints,ik,robot,matrices", size);
        let view = h.state().viewport().rect().expect("the view was laid out");
        let jacobian = h.state().model().jacobian().clone();
        let first = format!("{:.3}", jacobian[(0, 0)]);
        let captions: Vec<egui::Rect> = ["columns 1–3", "columns 4–6"]
            .iter()
            .map(|c| {
                let caption = h.query_by_label(c);
                caption.unwrap_or_else(|| panic!("{size:?}: {c}")).rect()
            })
            .collect();
        assert!(
            captions[0].bottom() < captions[1].top(),
            "{size:?}: one under the other"
        );
        // The first block carries the whole matrix's text, for screen readers.
        let text = |n: &egui_kittest::Node<'_>| {
            let ak = n.accesskit_node();
            ak.label().or(ak.value()).unwrap_or_default()
        };
        let table = h
            .query_all(egui_kittest::kittest::by().include_labels())
            .find(|n| {
                let t = text(n);
                t.lines().count() == 6 && t.trim_start().starts_with(&first)
            })
            .unwrap_or_else(|| panic!("{size:?}: the Jacobian's table"));
        let r = table.rect();
        assert!(r.left() > view.right(), "{size:?}: in the right column");
        assert!(
            r.top() > captions[0].top() && r.bottom() < captions[1].top(),
            "{size:?}: under its caption"
        );
        assert!(
            r.right() <= size[0] - 30.0,
            "{size:?}: the block ends at {} (the tab strip at {})",
            r.right(),
            size[0] - 30.0
        );
    }
}

/// On a full-HD screen (a laptop, a modern lecture hall's projector) the DH table is the
/// textbook's table, one line per joint; on a 1366-wide laptop, a block per joint.
#[test]
fn on_a_full_hd_screen_the_dh_table_has_one_line_per_joint() {
    for (size, one_line) in [([1920.0, 1080.0], true), ([1366.0, 768.0], false)] {
        let mut h = harness_at("#robot=ur10&panels=joints,ik,robot,matrices", size);
        h.get_by_label("DH table (editable)").click();
        h.run_steps(3);
        let at = |name: &str| {
            let [x, y] = h.state().points().get(name).expect("the cell is drawn");
            egui::pos2(x, y)
        };
        let (theta, max, next) = (at("dh-1-1"), at("dh-1-6"), at("dh-2-1"));
        assert_eq!(
            (theta.y - max.y).abs() < 1.0,
            one_line,
            "{size:?}: θ1 at {theta:?}, max1 at {max:?}"
        );
        assert!(
            next.y > theta.y.max(max.y),
            "{size:?}: joint 2 under joint 1"
        );
        assert!(
            (theta.x - next.x).abs() < 1.0,
            "{size:?}: θ cells in one column"
        );
    }
}

#[test]
fn on_a_projector_the_replay_of_a_solve_fits_its_column() {
    // The replay's slider (its name, rail and value) and the error plot stay inside the
    // left column: nothing runs past its edge, and the column needs no sideways scrolling.
    for size in [[1024.0, 768.0], [1280.0, 720.0], [1366.0, 768.0]] {
        let mut h = harness_at(
            "#robot=ur10&q=0,-1,1.2,-1.5,-1.2,0.3&task=full&method=dls&panels=ik,matrices",
            size,
        );
        let mut target = *h.state().model().target();
        target.translation.vector += nalgebra::Vector3::new(-120.0, 80.0, 60.0);
        h.state_mut().model_mut().set_target(target);
        h.run_steps(1);
        h.get_by_label("Solve").click();
        h.run_steps(3);
        assert!(
            h.query_by_role_and_label(Role::Slider, "iteration")
                .is_some(),
            "{size:?}: the replay is shown"
        );
        let view = h.state().viewport().rect().expect("the view was laid out");
        let edge = view.left() - 3.0;
        let mut outside = Vec::new();
        for node in h.query_all(egui_kittest::kittest::by()) {
            let ak = node.accesskit_node();
            if ak.bounding_box().is_none() || ak.role() == Role::Splitter {
                continue;
            }
            let r = node.rect();
            if r.top() < view.top() || r.left() < 30.0 || r.left() >= edge {
                continue;
            }
            let sideways_bar = ak.role() == Role::ScrollBar && r.width() > r.height();
            if r.right() > edge + 0.5 || sideways_bar {
                outside.push(format!("{:?} {:?} {r:?}", ak.role(), ak.label()));
            }
        }
        assert!(outside.is_empty(), "{size:?}, edge {edge}: {outside:#?}");
    }
}
