//! The DH editor that keeps the arm, its cells and column heads, the A_i formula, the frames' names, the DH-table exercise (its framing, labels and checks), predict then reveal, and robot files with keep-out boxes.

use super::*;

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
    // a2 moved to row 2 but typed as 222.0: the one cell to change, and to what.
    type_into_cell(&mut h, 2, "0");
    type_into_cell(&mut h, 6 + 2, "222");
    h.get_by_label("Check").click();
    h.run_steps(2);
    let near = "Joint 3's frame is the first to disagree: change a in row 2 from 222 to 222.1.";
    assert!(
        h.query_by_label(near).is_some(),
        "the verdict names a2's value"
    );
    // Correct: the table shows everywhere again.
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
    for (size, min_share) in SCREENS {
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

/// The share of the view's width and height the exercise's labels span, after checking
/// that no label covers another or leaves the view.
fn exercise_labels_span(h: &Harness<'_, ArmLabApp>, what: &str) -> (f32, f32) {
    let view = h.state().viewport().rect().expect("the view was laid out");
    let labels = h.state().viewport().labels();
    let dof = h.state().model().robot().dof();
    assert!(labels.len() > dof, "{what}: {labels:?}");
    for (i, a) in labels.iter().enumerate() {
        assert!(view.contains_rect(a.rect), "{what}: {a:?} leaves {view:?}");
        assert!(a.rect.height() >= 15.0, "{what}: {a:?} is readable");
        // Every label names its axis or the pair of axes it measures.
        assert!(
            a.text.contains("axis") || a.text.contains("axes"),
            "{what}: {a:?}"
        );
        for b in &labels[i + 1..] {
            assert!(!a.rect.intersects(b.rect), "{what}: {a:?} covers {b:?}");
        }
    }
    let union = labels
        .iter()
        .fold(egui::Rect::NOTHING, |u, l| u.union(l.rect));
    (union.width() / view.width(), union.height() / view.height())
}

#[test]
fn the_exercise_fills_the_view_and_no_label_covers_another() {
    for (hash, size) in [
        ("#exercise=mystery-3", [1366.0, 768.0]),
        ("#exercise=mystery-3", [1024.0, 768.0]),
        ("#exercise=mystery-3", [390.0, 844.0]),
        ("#exercise=rrr", [1366.0, 768.0]),
        ("#exercise=mystery-42", [1366.0, 768.0]),
    ] {
        let mut h = harness_at(hash, size);
        h.run_steps(2);
        let what = format!("{hash} at {size:?}");
        let (w, hgt) = exercise_labels_span(&h, &what);
        // The drawing and its labels fill the view in one direction at least.
        assert!(
            w.max(hgt) >= 0.6,
            "{what}: the labels span {w} × {hgt} of the view"
        );
        if hash == "#exercise=mystery-3" && size[0] == 1366.0 {
            // Zoomed far out, F frames the arm again.
            let centre = h.state().viewport().rect().expect("a view").center();
            app_harness::wheel(&mut h, centre, -2000.0);
            let (zoomed, _) = exercise_labels_span(&h, &what);
            assert!(
                zoomed < w * 0.8,
                "{what}: the wheel zoomed out ({zoomed} of {w})"
            );
            h.key_press(egui::Key::F);
            h.run_steps(3);
            let (again, _) = exercise_labels_span(&h, &what);
            assert!(
                (again - w).abs() < 0.05,
                "{what}: F framed it ({again}, first {w})"
            );
        }
    }
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
    // In T_0n alone: T_03 below the fold (the RRR's T_03 is T_0n) is not laid out.
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

/// Every DH cell's text lies whole inside its cell and, in a tall touch cell, at its
/// middle; gives what does not.
fn dh_texts_out_of_place(h: &Harness<'_, ArmLabApp>) -> Vec<String> {
    let mut out = Vec::new();
    for cell in h.query_all_by_role(Role::TextInput) {
        let rect = cell.rect();
        let value = cell
            .accesskit_node()
            .value()
            .unwrap_or_default()
            .to_string();
        for run in cell.children() {
            let text = run.rect();
            // The text's margin on the right at least its margin on the left: a narrower
            // one means the cell's inner edge cuts the text.
            let left = text.left() - rect.left();
            if left < 2.0 || rect.right() - text.right() < left - 0.5 {
                out.push(format!("{value:?} cut: text {text:?} in cell {rect:?}"));
            } else if (text.center().y - rect.center().y).abs() > 2.0 {
                out.push(format!(
                    "{value:?} off centre: text {text:?} in cell {rect:?}"
                ));
            }
        }
    }
    out
}

#[test]
fn a_tablets_dh_cells_show_their_numbers_whole_and_centred() {
    let mut h = harness_at("#robot=ur10&panels=robot", [820.0, 1180.0]);
    h.state_mut().set_touch(true);
    h.run_steps(3);
    h.get_by_label("Robot").click();
    h.run_steps(3);
    h.get_by_label("DH table (editable)").click();
    h.run_steps(3);
    assert_eq!(h.query_all_by_role(Role::TextInput).count(), 36);
    let tall = h
        .query_all_by_role(Role::TextInput)
        .next()
        .expect("a cell")
        .rect();
    assert!(tall.height() >= 36.0, "touch cells are tall: {tall:?}");
    let runs: usize = h
        .query_all_by_role(Role::TextInput)
        .map(|c| c.children().count())
        .sum();
    assert!(runs >= 36, "each cell's text is seen: {runs}");
    let wrong = dh_texts_out_of_place(&h);
    assert!(wrong.is_empty(), "{wrong:#?}");
}

#[test]
fn modified_dh_columns_read_a_i_minus_1_alpha_i_minus_1_d_i_theta_i() {
    let mut h = harness_at("#robot=ur10&panels=robot", [1920.0, 1080.0]);
    h.get_by_label("DH table (editable)").click();
    h.run_steps(3);
    let x = |h: &Harness<'_, ArmLabApp>, label: &str| h.get_by_label(label).rect().center().x;
    let heads = ["ai−1", "αi−1 (°)", "di", "θi (°)"];
    let xs: Vec<f32> = heads.iter().map(|l| x(&h, l)).collect();
    assert!(xs.windows(2).all(|w| w[0] < w[1]), "{heads:?} at {xs:?}");
    // The cells follow their headers: row 1's a, α, d, θ (columns 3, 4, 2, 1).
    let at = |name: &str| h.state().points().get(name).expect("a cell")[0];
    let cells = [at("dh-1-3"), at("dh-1-4"), at("dh-1-2"), at("dh-1-1")];
    assert!(cells.windows(2).all(|w| w[0] < w[1]), "{cells:?}");
    for (head, cell) in xs.iter().zip(cells) {
        assert!((head - cell).abs() < 40.0, "header {head} over cell {cell}");
    }
    // The standard table keeps θ_i, d_i, a_i, α_i, and the two tables side by side have
    // headers in the body's size.
    h.get_by_label("Both conventions side by side").click();
    h.run_steps(3);
    for head in ["θi", "ai", "ai−1", "αi−1"] {
        let r = h.get_all_by_label(head).last().expect("a header").rect();
        assert!(r.height() >= 14.0, "{head}: {r:?}");
    }
}

/// The A_i formula is laid out as mathematics: subscripts, not LaTeX's marks as typed.
#[test]
fn the_a_i_formula_shows_subscripts_not_latex_marks() {
    for (preset, formula) in [
        ("ur10", "modified DH: Ai = Rx(αi−1)·Tx(ai−1)·Rz(θi)·Tz(di)"),
        ("puma560", "standard DH: Ai = Rz(θi)·Tz(di)·Tx(ai)·Rx(αi)"),
    ] {
        let mut h = harness_at(&format!("#robot={preset}&panels=matrices"), [1366.0, 768.0]);
        h.get_by_label_contains("Link transforms").click();
        h.run_steps(3);
        let label = h.get_by_label(formula);
        let r = label.rect();
        assert!(r.height() >= 14.0 && r.width() > 150.0, "{formula}: {r:?}");
        let _ = label;
        assert!(
            h.query_by_label_contains("_\u{7b}").is_none()
                && h.query_by_label_contains("A_i =").is_none(),
            "no LaTeX marks as text"
        );
    }
}

/// The heights (CSS pixels) of the text rows of the first label containing `text`.
fn row_heights(h: &Harness<'_, ArmLabApp>, text: &str) -> Vec<f32> {
    let zoom = h.ctx.zoom_factor();
    let label = h.get_by_label_contains(text);
    let rows: Vec<f32> = label.children().map(|r| r.rect().height() * zoom).collect();
    if rows.is_empty() {
        vec![label.rect().height() * zoom]
    } else {
        rows
    }
}

/// On a 1024 × 768 projector in presentation mode the robot's description and the DH
/// table's units read at 14 pixels, and the DH cells keep a fill apart from the panel.
#[test]
fn presentation_notes_are_large_and_dh_cells_keep_their_boxes() {
    let mut h = harness_at("#robot=ur10&present=on&ppanels=robot", [1024.0, 768.0]);
    h.get_by_label("DH table (editable)").click();
    h.run_steps(3);
    for text in ["Universal Robots UR10 in modified DH", "Lengths in mm"] {
        let rows = row_heights(&h, text);
        assert!(rows.iter().all(|&r| r >= 16.0), "{text}: rows {rows:?} px");
    }
    // A cell's fill against the panel's: a visible box.
    let cell = h
        .query_all_by_role(Role::TextInput)
        .next()
        .expect("a cell")
        .rect();
    let image = h.render().expect("a frame");
    let ppp = h.ctx.pixels_per_point();
    let px = |p: egui::Pos2| image.get_pixel((p.x * ppp) as u32, (p.y * ppp) as u32).0;
    let inside = px(cell.left_center() + egui::vec2(3.0, 0.0));
    let outside = px(cell.left_center() - egui::vec2(3.0, 0.0));
    let diff = (0..3)
        .map(|i| (inside[i] as i32 - outside[i] as i32).abs())
        .max();
    assert!(
        diff >= Some(20),
        "cell {inside:?} against panel {outside:?}"
    );
}

/// Each DH frame's x and z axes are named where the view has room, no name over another.
#[test]
fn the_dh_frames_axes_are_named() {
    for (hash, size, least) in [
        ("#robot=ur10", [1366.0, 768.0], 8),
        ("#robot=rrr", [1024.0, 768.0], 6),
        ("#robot=ur10", [390.0, 844.0], 4),
    ] {
        let h = harness_at(hash, size);
        let view = h.state().viewport().rect().expect("the view was laid out");
        let labels = h.state().viewport().labels();
        let names: Vec<&str> = labels.iter().map(|l| l.text.as_str()).collect();
        assert!(labels.len() >= least, "{hash} at {size:?}: {names:?}");
        assert!(names.contains(&"z1") && names.contains(&"x1"), "{names:?}");
        for (i, a) in labels.iter().enumerate() {
            assert!(view.contains_rect(a.rect), "{a:?}");
            assert!(
                a.rect.center().distance(a.anchor) < 40.0,
                "{a:?} beside its axis"
            );
            for b in &labels[i + 1..] {
                assert!(!a.rect.intersects(b.rect), "{a:?} covers {b:?}");
            }
        }
    }
}
