//! Paths and waypoints: both paths drawn, where the line fails, a visit, and the fold at every size.

use super::*;

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
