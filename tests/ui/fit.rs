//! Everything fits where it is drawn: the DH table, the menus, the motion panel, the left column, the Jacobian's blocks and the replay.

use super::*;

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
        // Row 2's a_{i−1}, the first of the modified table's columns.
        type_into_cell(&mut h, 6, "abc");
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
        type_into_cell(&mut h, 6, "-612.5");
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

#[test]
fn at_1366x768_the_symbolic_t04_to_t06_show_whole_in_their_column() {
    let mut h = harness_at("#robot=ur10", [1366.0, 768.0]);
    let panel = show_symbolic(&mut h);
    let view = h.state().viewport().rect().expect("a view");
    let right = 1366.0 - armlab::app::panels::layout::EDGE_TAB_WIDTH;
    for title in ["T_04", "T_05", "T_06"] {
        // Scrolled until the matrix's title is in sight, as a person would.
        for _ in 0..40 {
            let top = h.query_by_label(title).map(|n| n.rect().top());
            if top.is_some_and(|y| y > view.top() && y < 300.0) {
                break;
            }
            app_harness::wheel(&mut h, panel, -150.0);
        }
        let top = h.get_by_label(title).rect().top();
        // Every entry of the matrix (its labels in the next 200 points) ends in the column.
        let cut: Vec<String> = h
            .query_all_by_role(Role::Label)
            .filter(|n| n.rect().left() > view.right() && n.rect().left() < right)
            .filter(|n| n.rect().top() > top && n.rect().top() < top + 200.0)
            .filter(|n| n.rect().right() > right + 0.5)
            .map(|n| {
                format!(
                    "{:?} ends at {:.0}",
                    n.accesskit_node().label(),
                    n.rect().right()
                )
            })
            .collect();
        assert!(
            cut.is_empty(),
            "{title}, past the column's edge {right}: {cut:#?}"
        );
    }
}
