//! The 3D view's overlays and the IK panel's folds: self-motion, Jacobian columns, ghosts and branches, symbolic matrices, the notebook, the workspace, both conventions and tool directions.

use super::*;

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
fn the_planar_2r_names_the_direction_it_loses_within_its_plane() {
    // A straight elbow: the tool cannot move along the arm, (cos 0.3, sin 0.3, 0). The z
    // axis was never the planar arm's to move along, so it is never named; bent, the arm
    // loses nothing.
    let lost_sentence = |hash: &str| {
        // Wide and tall enough that the Jacobian's fold shows whole, its sentence included.
        let mut h = harness_at(hash, [2560.0, 1600.0]);
        h.run_steps(2);
        h.query_all(egui_kittest::kittest::by().include_labels())
            .map(|n| {
                let ak = n.accesskit_node();
                ak.label().or(ak.value()).unwrap_or_default()
            })
            .find(|text| text.contains("The tool cannot move along"))
    };
    let sentence = lost_sentence("#robot=planar-2r&q=0.3,0&panels=matrices&show=vel")
        .expect("the lost direction is named at the straight elbow");
    assert!(
        sentence.contains("(0.96, 0.30, 0.00)") || sentence.contains("(-0.96, -0.30, 0.00)"),
        "{sentence}"
    );
    assert_eq!(
        lost_sentence("#robot=planar-2r&q=0.3,1&panels=matrices&show=vel"),
        None
    );
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
    click_at(&mut h, at);
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
    let panel = show_symbolic(&mut h);
    // T_03 is below the fold, where blocks are not laid out: the panel is scrolled to it,
    // as a person would, and back to the top.
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
            .model()
            .replay()
            .expect("the demo ran")
            .run
            .clone();
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
fn the_jacobian_shows_in_the_tool_frame_and_symbolically() {
    let mut h = harness_at("#robot=ur10&panels=matrices", [1366.0, 768.0]);
    // The symbolic J, in the base frame again; the numeric one, scrolled out of sight, is
    // not laid out.
    assert_eq!(h.query_all_by_label("J  (6×n, base frame)").count(), 1);
    h.get_by_label("tool").click();
    h.run_steps(2);
    assert!(h.query_by_label("J  (6×n, tool frame)").is_some());
    h.get_by_label("Tool orientation").click();
    h.run_steps(2);
    h.get_by_label("symbolic").click();
    h.run_steps(2);
    let panel = h.get_by_label("symbolic").rect().center();
    app_harness::wheel(&mut h, panel, -6000.0);
    // The UR10's fifth column in the tool frame, as a textbook derives it: the last
    // wrist offset (92.2 mm) turned by θ6.
    for entry in ["92.2 c6", "-92.2 s6"] {
        assert!(h.query_by_label(entry).is_some(), "the entry {entry}");
    }
    app_harness::wheel(&mut h, panel, 6000.0);
    h.get_by_label("base").click();
    h.run_steps(2);
    app_harness::wheel(&mut h, panel, -6000.0);
    // The symbolic J, in the base frame again; the numeric one, scrolled out of sight, is
    // not laid out.
    assert_eq!(h.query_all_by_label("J  (6×n, base frame)").count(), 1);
    assert!(
        h.query_by_label("92.2 c6").is_none(),
        "the base frame's J differs"
    );
}

#[test]
fn the_planar_2rs_target_arrows_stay_clear_of_the_hint_at_1366x768() {
    let h = harness_at("#robot=planar-2r&q=0.3,0", [1366.0, 768.0]);
    let view = h.state().viewport().rect().expect("a view");
    let [x, y] = h
        .state()
        .points()
        .get("target")
        .expect("the target is drawn");
    // An arrow is 80 points long whichever way it points; the hint takes two lines (about
    // 40 points) at the foot of the view.
    let arrow = armlab::app::view3d::marker::handle_px::ARROW as f32;
    let clear = view.shrink(arrow);
    assert!(
        clear.contains(egui::pos2(x, y)) && y + arrow < view.bottom() - 40.0,
        "the target at ({x:.0}, {y:.0}) in the view {view:?}"
    );
}

#[test]
fn the_workspace_cloud_has_a_colour_legend_and_lies_in_the_view_at_1366x768() {
    use armlab::app::view3d::workspace::{SAMPLES, measure, ramp};
    let mut h = harness_at("#robot=ur10&show=cloud&panels=ik", [1366.0, 768.0]);
    h.get_by_label("Reachable workspace").click();
    h.run_steps(1);
    let m = measure(h.state().model());
    let now = armlab::app::platform::clock::now_ms;
    h.state_mut()
        .model_mut()
        .fill_workspace(m, SAMPLES, f64::INFINITY, now);
    h.run_steps(3);
    let cloud = h.state().model().workspace().expect("a cloud").clone();
    // The panel names the measure and its range.
    let largest = armlab_session::format::number(cloud.largest_value(), 3);
    let said = format!("colour: manipulability w (unit-free): blue 0 to yellow {largest}");
    assert!(h.query_by_label(&said).is_some(), "{said}");
    // The legend's bar in the view: blue at 0, yellow at the largest, as the cloud.
    let image = h.render().expect("a frame");
    let ppp = h.ctx.pixels_per_point();
    for (end, t) in [("cloud-legend-low", 0.0), ("cloud-legend-high", 1.0)] {
        let [x, y] = h.state().points().get(end).expect("the legend is drawn");
        let got = image.get_pixel((x * ppp) as u32, (y * ppp) as u32).0;
        let want = ramp(t);
        let off = (0..3).map(|i| got[i].abs_diff(want[i])).max().unwrap_or(0);
        assert!(off <= 24, "{end}: {got:?}, the cloud's colour {want:?}");
    }
    // Every sample lies in the view, above the hint lines at its foot.
    let view = h.state().viewport().rect().expect("a view");
    let size = [f64::from(view.width()), f64::from(view.height())];
    let camera = h.state().viewport().camera();
    let outside = cloud
        .positions
        .iter()
        .filter(|p| {
            camera
                .project(&nalgebra::Point3::from(**p), size)
                .is_none_or(|[x, y]| x < 0.0 || x > size[0] || y < 0.0 || y > size[1] - 40.0)
        })
        .count();
    assert_eq!(outside, 0, "samples outside the view, of {}", cloud.len());
}
