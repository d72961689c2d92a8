//! The lab from the keyboard: the target moved by the arrow keys and Page Up / Page Down
//! in the view's axes (Shift fine), the camera by Alt and the same keys; a control with the
//! keyboard keeps its own arrows; the zoom buttons, the one-finger alternative to pinch.

use super::*;

/// The target's position.
fn target(h: &Harness<'_, ArmLabApp>) -> nalgebra::Vector3<f64> {
    h.state().model().target().translation.vector
}

/// The view's right, up and away directions, from the camera.
fn axes(h: &Harness<'_, ArmLabApp>) -> [nalgebra::Vector3<f64>; 3] {
    let c = h.state().viewport().camera();
    let away = (c.focus - c.eye()).normalize();
    let right = away.cross(&nalgebra::Vector3::z()).normalize();
    [right, right.cross(&away), away]
}

#[test]
fn arrows_and_page_keys_move_the_target_in_the_views_axes_and_the_arm_follows() {
    let mut h = harness("#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position");
    h.run_steps(2);
    let reach = h.state().model().robot().reach();
    let [right, up, away] = axes(&h);
    let start = target(&h);
    h.key_press(egui::Key::ArrowRight);
    h.run_steps(2);
    let moved = target(&h) - start;
    assert!(
        (moved - right * 0.02 * reach).norm() < 1e-9,
        "{moved:?} is a fiftieth of the reach to the right"
    );
    h.key_press_modifiers(egui::Modifiers::SHIFT, egui::Key::ArrowUp);
    h.run_steps(2);
    let moved = target(&h) - start - right * 0.02 * reach;
    assert!(
        (moved - up * 0.002 * reach).norm() < 1e-9,
        "Shift: a five-hundredth up, {moved:?}"
    );
    let before = target(&h);
    h.key_press(egui::Key::PageDown);
    h.run_steps(2);
    assert!(
        (target(&h) - before + away * 0.02 * reach).norm() < 1e-9,
        "Page Down: toward the viewer"
    );
    // The arm followed: the tool is on the target.
    let tool = h.state().model().fk().tool_position();
    assert!(
        (tool - target(&h)).norm() < 1e-3 * reach,
        "the tool follows: {tool:?} vs {:?}",
        target(&h)
    );
    assert_eq!(h.state().model().ik().reach, Reach::Reached);
}

#[test]
fn alt_and_the_arrows_orbit_the_camera_and_leave_the_target() {
    let mut h = harness("#robot=ur10&task=position");
    h.run_steps(2);
    let (yaw, distance) = (
        h.state().viewport().camera().yaw,
        h.state().viewport().camera().distance,
    );
    let start = target(&h);
    h.key_press_modifiers(egui::Modifiers::ALT, egui::Key::ArrowLeft);
    h.key_press_modifiers(egui::Modifiers::ALT, egui::Key::PageUp);
    h.run_steps(2);
    let c = h.state().viewport().camera();
    assert!(
        (c.yaw - yaw).abs() > 0.05,
        "the camera turned: {yaw} → {}",
        c.yaw
    );
    assert!(
        c.distance < distance,
        "and came closer: {distance} → {}",
        c.distance
    );
    assert_eq!(target(&h), start);
}

#[test]
fn a_focused_slider_keeps_its_arrows_from_the_target() {
    let mut h = harness("#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position");
    h.run_steps(2);
    let start = target(&h);
    h.get_by_role_and_label(Role::Slider, "θ1").focus();
    h.run_steps(1);
    h.key_press(egui::Key::ArrowRight);
    h.run_steps(2);
    assert_eq!(target(&h), start, "the target stays");
}

/// The rotation that takes `from` to `to`, in the world, as an axis and an angle.
fn turn_between(
    from: &nalgebra::Rotation3<f64>,
    to: &nalgebra::Rotation3<f64>,
) -> (nalgebra::Vector3<f64>, f64) {
    let r = to * from.inverse();
    let axis = r
        .axis()
        .map_or(nalgebra::Vector3::zeros(), |a| a.into_inner());
    (axis, r.angle())
}

/// Checks that the arm's tool (FK of q) is on the target, position and orientation.
fn assert_tool_on_target(h: &Harness<'_, ArmLabApp>) {
    let model = h.state().model();
    let tool = armlab_core::fk::tool_pose(model.robot(), model.q());
    let target = model.target();
    let gap = (tool.translation.vector - target.translation.vector).norm();
    let (_, angle) = turn_between(&tool.rotation, &target.rotation);
    assert!(
        gap < 1e-3 * model.robot().reach() && angle < 1e-3,
        "FK(q) is on the target: {gap} apart, turned {angle} rad"
    );
    assert_eq!(model.ik().reach, Reach::Reached);
}

#[test]
fn letter_keys_turn_the_target_about_the_views_axes_and_the_arm_follows() {
    let mut h = harness("#robot=ur10&q=0.3,-1.1,1.2,-1.5,-1.2,0.3&task=full");
    h.run_steps(2);
    assert_eq!(h.state().model().task(), armlab_core::Task::FullPose);
    let [right, up, away] = axes(&h);
    let position = target(&h);
    let cases = [
        (egui::Key::L, egui::Modifiers::NONE, up, 5.0),
        (egui::Key::J, egui::Modifiers::NONE, -up, 5.0),
        (egui::Key::K, egui::Modifiers::NONE, right, 5.0),
        (egui::Key::I, egui::Modifiers::SHIFT, -right, 1.0),
        (egui::Key::O, egui::Modifiers::NONE, away, 5.0),
        (egui::Key::U, egui::Modifiers::SHIFT, -away, 1.0),
    ];
    for (key, modifiers, axis, degrees) in cases {
        let before = h.state().model().target().rotation;
        h.key_press_modifiers(modifiers, key);
        h.run_steps(2);
        let after = h.state().model().target().rotation;
        let (turned_about, angle) = turn_between(&before, &after);
        assert!(
            (angle - f64::to_radians(degrees)).abs() < 1e-9,
            "{key:?}: {degrees}° a press, turned {}°",
            angle.to_degrees()
        );
        assert!(
            (turned_about - axis).norm() < 1e-9,
            "{key:?}: about {axis:?}, turned about {turned_about:?}"
        );
        assert!(
            (target(&h) - position).norm() < 1e-9,
            "{key:?}: the target turns in place"
        );
        assert_tool_on_target(&h);
    }
}

#[test]
fn letter_keys_leave_the_target_in_a_position_task() {
    let mut h = harness("#robot=ur10&q=0.3,-1.1,1.2,-1.5,-1.2,0.3&task=position");
    h.run_steps(2);
    let before = *h.state().model().target();
    h.key_press(egui::Key::L);
    h.run_steps(2);
    assert_eq!(
        *h.state().model().target(),
        before,
        "orientation does not count"
    );
}

/// The camera's distance from its focus.
fn distance(h: &Harness<'_, ArmLabApp>) -> f64 {
    h.state().viewport().camera().distance
}

#[test]
fn the_zoom_buttons_change_the_cameras_distance_by_a_step_at_every_screen_size() {
    for (size, _) in SCREENS {
        for (lang, zoom_in, zoom_out) in
            [("en", "Zoom in", "Zoom out"), ("fi", "Lähennä", "Loitonna")]
        {
            let mut h = harness_at(&format!("#robot=ur10&lang={lang}"), size);
            h.run_steps(2);
            let start = distance(&h);
            let button = h.get_by_role_and_label(Role::Button, zoom_in);
            let rect = button.rect();
            assert!(
                egui::Rect::from_min_size(egui::Pos2::ZERO, size.into()).contains_rect(rect),
                "{size:?}: the button lies in the window, {rect:?}"
            );
            button.click();
            h.run_steps(2);
            let ratio = distance(&h) / start;
            assert!(
                (ratio - 1.0 / 1.25).abs() < 1e-9,
                "{size:?} {lang}: zoom in: the distance ×0.8, ×{ratio}"
            );
            h.get_by_role_and_label(Role::Button, zoom_out).click();
            h.run_steps(2);
            h.get_by_role_and_label(Role::Button, zoom_out).click();
            h.run_steps(2);
            let ratio = distance(&h) / start;
            assert!(
                (ratio - 1.25).abs() < 1e-9,
                "{size:?} {lang}: in, then out twice: ×1.25, ×{ratio}"
            );
        }
    }
}

/// A one-pointer drag in the view from `at` by `by`, a frame per event.
fn drag_in_view(h: &mut Harness<'_, ArmLabApp>, at: egui::Pos2, by: egui::Vec2) {
    let button = |pos, pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: egui::Modifiers::NONE,
    };
    h.event(egui::Event::PointerMoved(at));
    h.run_steps(1);
    h.event(button(at, true));
    h.run_steps(1);
    for step in 1..=4 {
        h.event(egui::Event::PointerMoved(at + by * step as f32 / 4.0));
        h.run_steps(1);
    }
    h.event(button(at + by, false));
    h.run_steps(1);
}

#[test]
fn drag_pans_in_the_view_menu_makes_one_pointer_pan_at_every_screen_size() {
    for (size, _) in SCREENS {
        for (lang, menu, view, pans) in [
            ("en", "≡ Menu", "View", "Drag pans the view"),
            ("fi", "≡ Valikko", "Näkymä", "Veto siirtää näkymää"),
        ] {
            let mut h = harness_at(&format!("#robot=ur10&lang={lang}"), size);
            h.run_steps(2);
            let rect = h.state().viewport().rect().expect("the view was laid out");
            // Low in the view's left quarter: the floor, away from the target's handles.
            let at = rect.left_bottom() + egui::vec2(rect.width() * 0.2, -rect.height() * 0.2);
            let by = egui::vec2(60.0, -30.0);
            let before = h.state().viewport().camera_pose();
            drag_in_view(&mut h, at, by);
            let orbited = h.state().viewport().camera_pose();
            assert_ne!(orbited.yaw, before.yaw, "{size:?} {lang}: a drag orbits");
            assert_eq!(
                orbited.focus, before.focus,
                "{size:?} {lang}: and keeps the focus"
            );
            // The narrow layout keeps the View menu in its menu.
            if h.query_by_label(menu).is_some() {
                h.get_by_label(menu).click();
                h.run_steps(2);
            }
            h.get_by_label(view).click();
            h.run_steps(2);
            h.get_by_role_and_label(Role::CheckBox, pans).click();
            h.run_steps(2);
            h.key_press(egui::Key::Escape);
            h.run_steps(2);
            assert!(h.state().viewport().drag_pans(), "{size:?} {lang}: ticked");
            drag_in_view(&mut h, at, by);
            let panned = h.state().viewport().camera_pose();
            assert_eq!(
                (panned.yaw, panned.pitch, panned.distance),
                (orbited.yaw, orbited.pitch, orbited.distance),
                "{size:?} {lang}: a drag that pans leaves the camera's angles and distance"
            );
            assert!(
                nalgebra::Vector3::from(panned.focus)
                    .metric_distance(&nalgebra::Vector3::from(orbited.focus))
                    > 1e-3 * orbited.distance,
                "{size:?} {lang}: and moves its focus: {:?} to {:?}",
                orbited.focus,
                panned.focus
            );
        }
    }
}

/// Where the IK panel's header lies (its top) one frame after the Joints panel's "Joint
/// speeds" fold was clicked open, and once the fold has settled.
fn fold_opening(reduced_motion: bool) -> (f32, f32) {
    // Frames a sixtieth of a second apart, as a screen draws them: the harness's own
    // quarter-second steps would end any animation within one.
    let mut h = Harness::builder()
        .with_size([1366.0, 768.0])
        .with_step_dt(1.0 / 60.0)
        .wgpu()
        .build_eframe(|cc| ArmLabApp::new(cc, "#robot=ur10"));
    h.state_mut().model_mut().set_reduced_motion(reduced_motion);
    h.run_steps(3);
    let header = |h: &Harness<'_, ArmLabApp>| {
        h.get_by_label("Close the Inverse kinematics panel")
            .rect()
            .top()
    };
    let closed = header(&h);
    h.get_by_label("Joint speeds q̇").click();
    h.run_steps(1);
    let first = header(&h);
    h.run_steps(30);
    let settled = header(&h);
    assert!(
        settled > closed + 20.0,
        "the fold opened: {closed} → {settled}"
    );
    (first, settled)
}

#[test]
fn with_reduced_motion_a_fold_opens_in_one_frame() {
    let (first, settled) = fold_opening(true);
    assert!(
        (settled - first).abs() < 0.5,
        "open at once: {first} then {settled}"
    );
    let (first, settled) = fold_opening(false);
    assert!(
        settled - first > 5.0,
        "without the setting it slides open: {first} then {settled}"
    );
}

/// The left column's edge (egui's resize handle) by its name: its left and right x, and
/// whether it has the keyboard.
fn edge(h: &Harness<'_, ArmLabApp>) -> ((f64, f64), bool) {
    let node = h.get_by_role_and_label(Role::Splitter, "Width of the left column");
    let b = node
        .accesskit_node()
        .bounding_box()
        .expect("the edge is laid out");
    ((b.x0, b.x1), node.is_focused())
}

/// Tab reaches a column's edge after the column's controls and outlines it; there Right and
/// Left widen and narrow the column by egui's step, and leave the target alone.
#[test]
fn tab_reaches_a_columns_edge_and_the_arrow_keys_step_its_width() {
    let mut h = harness("#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position");
    h.run_steps(2);
    // The edge's pixels in the focus colour (a column of its rectangle, its middle third).
    let outlined = |h: &mut Harness<'_, ArmLabApp>| {
        let colour = h
            .ctx
            .global_style()
            .visuals
            .selection
            .stroke
            .color
            .to_array();
        let ((x0, _), _) = edge(h);
        let image = h.render().expect("a frame");
        let ppp = f64::from(h.ctx.pixels_per_point());
        let x = ((x0 + 0.5) * ppp) as u32;
        let (y0, y1) = (image.height() / 3, 2 * image.height() / 3);
        (y0..y1).any(|y| {
            let p = image.get_pixel(x, y).0;
            (0..3).all(|c| p[c].abs_diff(colour[c]) < 8)
        })
    };
    assert!(
        !outlined(&mut h),
        "no outline before the edge has the keyboard"
    );
    let mut tabs = 0;
    while !edge(&h).1 {
        tabs += 1;
        assert!(tabs < 150, "Tab never reached the left column's edge");
        h.key_press(egui::Key::Tab);
        h.run_steps(2);
    }
    assert!(
        outlined(&mut h),
        "the edge is outlined in the focus colour after {tabs} Tabs"
    );
    let (start, target0) = (edge(&h).0, target(&h));
    h.key_press(egui::Key::ArrowRight);
    h.run_steps(2);
    h.key_press(egui::Key::ArrowRight);
    h.run_steps(3);
    let wider = edge(&h).0;
    let step = h.ctx.global_style().spacing.interact_size.x as f64;
    assert!(
        (wider.0 - start.0 - 2.0 * step).abs() < 1.0,
        "two steps of {step} wider: {start:?} → {wider:?}"
    );
    h.key_press(egui::Key::ArrowLeft);
    h.run_steps(3);
    let (back, focused) = edge(&h);
    assert!((back.0 - wider.0 + step).abs() < 1.0, "one step back");
    assert!(focused, "the edge keeps the keyboard");
    assert_eq!(
        target(&h),
        target0,
        "the arrows moved the edge, not the target"
    );
}
