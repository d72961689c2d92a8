//! The lab from the keyboard: the target moved by the arrow keys and Page Up / Page Down
//! in the view's axes (Shift fine), the camera by Alt and the same keys; a control with the
//! keyboard keeps its own arrows.

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
