//! The app in Finnish (`lang=fi` in the link), through egui_kittest (native only, `app`
//! feature): with every panel open, no visible text is an English catalogue text; the
//! core's errors read in Finnish where the app shows them; the JSON API keeps to English.
#![cfg(not(target_arch = "wasm32"))]

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{By, NodeT, Queryable};

use armlab::app::ArmLabApp;
use armlab::app::panels::file_dialog::{FileDialog, Mode};
use armlab::app::state::model::MessageKind;
use armlab_core::ik::Reach;
use armlab_text::{Key, Lang, places, text};

const SIZE: [f32; 2] = [1400.0, 860.0];

mod app_harness;

fn harness(hash: &str) -> Harness<'static, ArmLabApp> {
    app_harness::open_app(hash, SIZE)
}

/// Every text the accessibility tree holds: each node's label and value.
fn visible_texts(h: &Harness<'_, ArmLabApp>) -> Vec<String> {
    let mut texts: Vec<String> = h
        .query_all(By::new())
        .flat_map(|node| {
            let node = node.accesskit_node();
            [node.label(), node.value()]
        })
        .flatten()
        .map(|t| t.trim().to_string())
        .filter(|t| !t.is_empty())
        .collect();
    texts.sort();
    texts.dedup();
    texts
}

/// [`visible_texts`] gathered while the panel holding the `label` is scrolled down in
/// steps of 300 points to its end, and the panel scrolled back to the top.
fn scrolled_texts(h: &mut Harness<'_, ArmLabApp>, label: &str) -> Vec<String> {
    let over = h.get_by_label(label).rect().center();
    let mut texts = visible_texts(h);
    let mut steps = 0;
    loop {
        let before = texts.len();
        app_harness::wheel(h, over, -300.0);
        texts.extend(visible_texts(h));
        texts.sort();
        texts.dedup();
        steps += 1;
        // The end: a step that shows nothing new (after the first few).
        if (texts.len() == before && steps > 3) || steps == 40 {
            break;
        }
    }
    app_harness::wheel(h, over, 1e5);
    texts
}

/// The fixed parts of a text with places: `"a {0} b {1}"` → `["a ", " b ", ""]`. Braces
/// that are not places (`α_{i−1}`) belong to the fixed parts.
fn fixed_parts(text: &str) -> Vec<String> {
    let mut parts = Vec::new();
    let mut part = String::new();
    let mut rest = text;
    while let Some(open) = rest.find('{') {
        part.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        match after.split_once('}') {
            Some((n, tail)) if n.parse::<usize>().is_ok() => {
                parts.push(std::mem::take(&mut part));
                rest = tail;
            }
            _ => {
                part.push('{');
                rest = after;
            }
        }
    }
    part.push_str(rest);
    parts.push(part);
    parts
}

/// Whether `label` is `parts` with something non-empty in every place between them.
fn fits(label: &str, parts: &[String]) -> bool {
    match parts {
        [] => label.is_empty(),
        [only] => label == only,
        [first, rest @ ..] => {
            let Some(tail) = label.strip_prefix(first.as_str()) else {
                return false;
            };
            // Try every split of the place's value (a value can hold the next part).
            (1..=tail.len())
                .filter(|n| tail.is_char_boundary(*n))
                .any(|n| {
                    let (value, after) = tail.split_at(n);
                    !value.is_empty() && fits(after, rest)
                })
        }
    }
}

/// The English texts a Finnish screen must not show: every key whose texts differ.
fn english_only() -> Vec<(Key, &'static str)> {
    Key::ALL
        .iter()
        .map(|key| (*key, text(Lang::En, *key)))
        .filter(|(key, en)| *en != text(Lang::Fi, *key))
        .collect()
}

/// The labels that read as an English catalogue text (a text with places: its fixed
/// parts around any values), with the key each one is.
fn english_labels(texts: &[String]) -> Vec<(String, Key)> {
    let english = english_only();
    let mut found = Vec::new();
    for label in texts {
        for (key, en) in &english {
            let hit = if places(en).is_empty() {
                label == en
            } else {
                fits(label, &fixed_parts(en))
            };
            if hit {
                found.push((label.clone(), *key));
            }
        }
    }
    found
}

#[test]
fn the_matcher_reads_places() {
    assert_eq!(fixed_parts("a {0} b {1}"), ["a ", " b ", ""]);
    assert_eq!(fixed_parts("α_{i−1} {0}"), ["α_{i−1} ", ""]);
    let parts = fixed_parts(text(Lang::En, Key::LastSolve));
    assert!(fits("Last solve: 12 iterations, converged", &parts));
    assert!(!fits(
        "Viimeisin ratkaisu: iteraatioita 12, suppeni",
        &parts
    ));
    let parts = fixed_parts(text(Lang::En, Key::Edited));
    assert!(fits("UR10 (edited) (edited)", &parts));
    assert!(!fits(" (edited)", &parts), "a place holds something");
}

#[test]
fn with_every_panel_open_no_text_is_english() {
    let mut h = harness("#robot=ur10&lang=fi&q=0.4,-1.1,1.3,-1.6,-1.4,0.2");
    assert_eq!(h.state().model().settings().lang, Lang::Fi);
    // A target away from the tool, solved, so the IK panel shows its status and replay.
    let mut target = *h.state().model().target();
    target.translation.vector += nalgebra::Vector3::new(-120.0, 80.0, 60.0);
    h.state_mut().model_mut().set_target(target);
    h.run_steps(1);
    h.get_by_label(text(Lang::Fi, Key::Solve)).click();
    h.run_steps(2);
    assert_eq!(h.state().model().ik().reach, Reach::Reached);
    assert!(h.state().model().replay().is_some(), "a replay");
    // The DH table, and the file dialog over everything. The IK menus' long Finnish names
    // take two lines each, and the replay's rows push the table's fold below the left
    // column's edge: a person scrolls down to it first.
    let solve = h.get_by_label(text(Lang::Fi, Key::Solve)).rect().center();
    app_harness::wheel(&mut h, solve, -300.0);
    h.get_by_label(text(Lang::Fi, Key::DhTable)).click();
    h.run_steps(2);
    // Blocks below the fold are not laid out: the matrices panel is read while it is
    // scrolled through to its end, as a person would, then back at the top.
    let mut texts = scrolled_texts(&mut h, text(Lang::Fi, Key::ToolOrientation));
    // The left column too, to the DH table's last row.
    texts.extend(scrolled_texts(&mut h, text(Lang::Fi, Key::DhTable)));
    let here = std::env::temp_dir();
    h.state_mut()
        .robot_panel_mut()
        .open_file_dialog(FileDialog::new(Mode::Save, "ur10", here));
    h.run_steps(3);

    texts.extend(visible_texts(&h));
    texts.sort();
    texts.dedup();
    for finnish in [
        Key::PanelJoints,
        Key::PanelIk,
        Key::PanelMatrices,
        Key::PanelRobot,
        Key::Solve,
        Key::TargetReached,
        Key::Jacobian,
        Key::ConditionNumber,
        Key::ToolOrientation,
        Key::DhTable,
        Key::AddJoint,
        Key::SaveDialogTitle,
        Key::FileName,
        Key::DescUr10,
    ] {
        let fi = text(Lang::Fi, finnish);
        assert!(
            texts.iter().any(|t| t == fi),
            "{finnish:?} shows in Finnish ({fi:?}); the texts: {texts:#?}"
        );
    }
    for key in [Key::LastSolve, Key::IkErrors, Key::LinkTitle, Key::RawQ] {
        let parts = fixed_parts(text(Lang::Fi, key));
        assert!(
            texts.iter().any(|t| fits(t, &parts)),
            "{key:?} shows with its values in Finnish"
        );
    }
    assert!(texts.len() > 80, "{} texts seen", texts.len());

    let english = english_labels(&texts);
    assert!(
        english.is_empty(),
        "English on a Finnish screen: {english:#?}"
    );

    // The fifth panel, the motion lab (closed unless a link opens it), with its paths
    // folded out and the arm driving with checks on.
    let mut h = harness("#robot=ur10&lang=fi&panels=motion&move=on&collide=on");
    h.get_by_label(text(Lang::Fi, Key::PathTitle)).click();
    h.run_steps(2);
    let texts = scrolled_texts(&mut h, text(Lang::Fi, Key::MotionMove));
    for finnish in [Key::PanelMotion, Key::MotionMove, Key::PathTitle] {
        let fi = text(Lang::Fi, finnish);
        assert!(
            texts.iter().any(|t| t == fi),
            "{finnish:?} shows in Finnish ({fi:?}); the texts: {texts:#?}"
        );
    }
    let english = english_labels(&texts);
    assert!(
        english.is_empty(),
        "English in the Finnish motion panel: {english:#?}"
    );
}

#[test]
fn the_language_switch_turns_the_app_finnish_and_back() {
    let mut h = harness("#robot=ur10&panels=joints,ik");
    assert_eq!(h.state().model().settings().lang, Lang::En);
    let shown = |h: &Harness<'_, ArmLabApp>, lang: Lang, key: Key| {
        h.query_all_by_label(text(lang, key)).next().is_some()
    };
    for key in [Key::PanelJoints, Key::Solve] {
        assert!(shown(&h, Lang::En, key), "{key:?} shows in English first");
    }
    // The top bar's menu shows the language in force; its list offers the other.
    let choose = |h: &mut Harness<'_, ArmLabApp>, from: &str, to: &str| {
        h.query_all_by_role(Role::ComboBox)
            .find(|n| n.accesskit_node().value().as_deref() == Some(from))
            .unwrap_or_else(|| panic!("the language menu shows {from}"))
            .click();
        h.run_steps(2);
        h.get_by_label(to).click();
        h.run_steps(3);
    };
    choose(&mut h, "English", "Suomi");
    assert_eq!(h.state().model().settings().lang, Lang::Fi);
    for key in [Key::PanelJoints, Key::Solve] {
        assert!(shown(&h, Lang::Fi, key), "{key:?} shows in Finnish");
        assert!(
            !shown(&h, Lang::En, key),
            "{key:?} no longer shows in English"
        );
    }
    assert!(h.state().hash().contains("lang=fi"), "{}", h.state().hash());
    choose(&mut h, "Suomi", "English");
    assert_eq!(h.state().model().settings().lang, Lang::En);
    for key in [Key::PanelJoints, Key::Solve] {
        assert!(shown(&h, Lang::En, key), "{key:?} shows in English again");
        assert!(
            !shown(&h, Lang::Fi, key),
            "{key:?} no longer shows in Finnish"
        );
    }
}

/// Types `text` into the `index`-th text input.
fn type_into_cell(h: &mut Harness<'_, ArmLabApp>, index: usize, text: &str) {
    let cells: Vec<_> = h.query_all_by_role(Role::TextInput).collect();
    assert!(cells.len() > index, "{} cells", cells.len());
    cells[index].focus();
    drop(cells);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text(text.into()));
    h.run_steps(3);
}

#[test]
fn a_bad_dh_cell_and_the_cores_sentence_read_in_finnish() {
    let mut h = harness("#robot=rrr&lang=fi");
    h.get_by_label(text(Lang::Fi, Key::DhTable)).click();
    h.run_steps(2);
    let robot_before = h.state().model().robot().clone();
    // Joint 2's "a" cell: not a number.
    type_into_cell(&mut h, 6 + 2, "12x");
    assert!(
        h.query_by_label("Nivel 2, a: \"12x\" ei ole luku.")
            .is_some(),
        "the app's own sentence, in Finnish"
    );
    assert_eq!(h.state().model().robot(), &robot_before);
    // Back to a number, then joint 2's lower limit above its upper: the core's sentence.
    type_into_cell(&mut h, 6 + 2, "222.1");
    assert_eq!(h.state().robot_panel().editor().first_error(), None);
    type_into_cell(&mut h, 6 + 4, "400");
    let error = h
        .state()
        .robot_panel()
        .editor()
        .error
        .clone()
        .expect("the core rejects the table");
    let finnish = error.sentence(Lang::Fi);
    assert!(
        finnish.starts_with("Nivel 2: alaraja 400 on ylärajaa"),
        "{finnish}"
    );
    assert!(
        h.query_by_label(&finnish).is_some(),
        "the core's sentence beside the cell, in Finnish: {finnish}"
    );
    assert!(
        h.query_by_label(&error.sentence(Lang::En)).is_none(),
        "not in English"
    );
    // The hook for the browser tests keeps to English.
    assert_eq!(
        h.state().robot_panel().editor().first_error().as_deref(),
        Some(error.sentence(Lang::En).as_str())
    );
    assert_eq!(h.state().model().robot(), &robot_before, "the robot stays");
}

#[test]
fn a_broken_link_and_a_failed_solve_say_so_in_finnish() {
    let mut h = harness("#robot=ur10&lang=fi&q=1,2,banana");
    assert_eq!(h.state().model().robot().name, "UR10");
    let message = h.state().model().message().expect("a message").clone();
    assert_eq!(message.kind, MessageKind::Warning);
    // The bad q is left out; the robot and the language apply.
    assert_eq!(
        message.text,
        "Osa linkistä jätettiin pois (linkin kentässä q on \"banana\", joka ei ole luku); \
         muu osa on käytössä."
    );
    assert!(
        h.query_by_label_contains("Osa linkistä jätettiin pois")
            .is_some(),
        "shown"
    );

    // A target that is not a pose: the core's IK error, in Finnish.
    let mut target = *h.state().model().target();
    target.translation.vector.x = f64::NAN;
    h.state_mut().model_mut().set_target(target);
    h.state_mut().model_mut().solve_with_trace();
    // The view draws a valid target again; the message stays.
    h.state_mut().model_mut().snap_target();
    h.run_steps(2);
    let message = h.state().model().message().expect("a message").clone();
    assert_eq!(message.kind, MessageKind::Error);
    assert_eq!(
        message.text,
        "Kohteen paikka ja asento eivät kelpaa: jokin arvo ei ole äärellinen."
    );
    assert!(h.query_by_label_contains(&message.text).is_some(), "shown");
}

#[test]
fn the_json_api_answers_in_english_whatever_the_app_shows() {
    let _finnish_app = harness("#robot=ur10&lang=fi");
    let err = armlab_api::fk(r#"{"robot": "ur10", "q": [1, 2]}"#).expect_err("two values");
    assert_eq!(
        err.to_string(),
        "The robot has 6 joints but 2 joint values were given."
    );
    let err = armlab_api::ik(
        r#"{"robot": "panda", "target": {"position": [1, 2, 3]}, "method": "closed"}"#,
    )
    .expect_err("no closed form");
    assert!(
        err.to_string()
            .starts_with("\"Franka Panda\" has no closed-form IK in ArmLab"),
        "{err}"
    );
    let err = armlab_api::robot(r#"{"robot": {"name": "x"}}"#).expect_err("no convention");
    assert_eq!(
        err.to_string(),
        "In the robot, the field \"convention\" is missing."
    );
}
