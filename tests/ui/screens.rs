//! Every screen size: the view keeps its share, projectors, phones, touch and the layout's tabs and sheets.

use super::*;

#[test]
fn at_every_screen_size_the_view_keeps_its_share_and_shows_the_arm() {
    for (size, min_share) in SCREENS {
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

/// The presentation column's width in CSS pixels: from the view's right edge to the edge
/// tabs.
fn presentation_column(h: &Harness<'_, ArmLabApp>) -> f32 {
    let view = h.state().viewport().rect().expect("the view was laid out");
    let tabs = h.ctx.content_rect().right() - armlab::app::panels::layout::EDGE_TAB_WIDTH;
    (tabs - view.right()) * h.ctx.zoom_factor()
}

#[test]
fn presentation_turned_off_and_on_keeps_its_column_and_fine_rails() {
    let mut h = harness_at("#robot=ur10&present=on", [1024.0, 768.0]);
    h.run_steps(2);
    let first = presentation_column(&h);
    for _ in 0..2 {
        h.key_press(egui::Key::P);
        h.run_steps(3);
    }
    assert!(h.state().model().settings().presentation);
    let again = presentation_column(&h);
    assert!(first > 350.0, "the column is {first} pixels wide");
    assert!(
        (again - first).abs() < 1.0,
        "turned off and on, the column is {again} pixels wide, first {first}"
    );
    // Each of the UR10's ±360° joints: no more than 3° a pixel of its rail.
    let zoom = h.ctx.zoom_factor();
    for i in 1..=6 {
        let at = |end: &str| h.state().points().get(&format!("slider-{i}-{end}"));
        let [x0, _] = at("min").expect("the rail's start");
        let [x1, _] = at("max").expect("the rail's end");
        let degrees_per_pixel = 720.0 / ((x1 - x0) * zoom);
        assert!(
            degrees_per_pixel <= 3.0,
            "θ{i}: {degrees_per_pixel:.1}° a pixel on a rail of {:.0} pixels",
            (x1 - x0) * zoom
        );
    }
}
