//! The 3D view in words, for the page's live region: the robot, where the tool is,
//! whether the target is reached (and, when a joint limit holds the arm back, which
//! joint), the closed-form branch the arm keeps, a singularity with the direction the
//! tool has lost, and the sampled workspace when the view shows it.

use armlab_core::ik::{Reach, branch_of};
use armlab_session::format::fixed;
use armlab_text::Key;

use super::branches::branch_words;
use super::model::Model;
use super::{tr, trf};

/// What the 3D view shows, in the interface's language, as a few short sentences.
pub fn view_words(model: &Model) -> String {
    let tool = model.fk().tool_position();
    let unit = model.robot().length_unit.symbol();
    // Millimetres whole, metres to the centimetre: a number a listener takes in at once.
    let decimals = if model.robot().reach() > 100.0 { 0 } else { 2 };
    let [x, y, z] = [tool.x, tool.y, tool.z].map(|v| fixed(v, decimals));
    let mut words = trf(
        model,
        Key::ViewWordsTool,
        &[&model.robot().name, &x, &y, &z, &unit],
    );
    for sentence in [
        reach_words(model),
        branch(model),
        singular(model),
        workspace(model),
    ] {
        if !sentence.is_empty() {
            words.push(' ');
            words.push_str(&sentence);
        }
    }
    words
}

/// Whether the target is reached, in one sentence (out of reach: with the joint at its
/// limit that holds the arm back, if one does); empty while the target is not yet settled.
/// The live region says this alone while the target is dragged.
pub fn reach_words(model: &Model) -> String {
    match model.shown_reach() {
        Reach::Reached => tr(model, Key::ViewWordsReached).to_owned(),
        Reach::OutOfReach => match model.rescue().and_then(|r| r.held) {
            Some((joint, at_max)) => {
                let side = tr(model, if at_max { Key::LimitMax } else { Key::LimitMin });
                trf(model, Key::ViewWordsHeld, &[&(joint + 1), &side])
            }
            None => tr(model, Key::ViewWordsOutOfReach).to_owned(),
        },
        _ => String::new(),
    }
}

/// The closed-form branch the arm is in (the one it keeps, else the one of its pose), in
/// words; empty for an arm without a closed form.
fn branch(model: &Model) -> String {
    model
        .kept_branch()
        .or_else(|| branch_of(model.robot(), model.q()).ok().flatten())
        .map(|b| trf(model, Key::ViewWordsBranch, &[&branch_words(model, &b)]))
        .unwrap_or_default()
}

/// The singularity and its lost direction; empty away from one.
fn singular(model: &Model) -> String {
    model
        .lost_direction()
        .map(|d| {
            let d = [d.x, d.y, d.z].map(|v| fixed(v, 2)).join(", ");
            trf(model, Key::ViewWordsSingular, &[&d])
        })
        .unwrap_or_default()
}

/// The workspace cloud once it is whole (while it fills, its count would change every
/// second): how many tool positions, how far from the base and between which heights.
fn workspace(model: &Model) -> String {
    let Some(cloud) = model.shown_workspace().filter(|c| c.is_full()) else {
        return String::new();
    };
    let Some((lo, hi)) = cloud.bounds() else {
        return String::new();
    };
    let decimals = if model.robot().reach() > 100.0 { 0 } else { 2 };
    trf(
        model,
        Key::ViewWordsWorkspace,
        &[
            &cloud.len(),
            &fixed(cloud.outer_reach(), decimals),
            &fixed(lo.z, decimals),
            &fixed(hi.z, decimals),
            &model.robot().length_unit.symbol(),
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use armlab_session::session::Session;
    use armlab_text::Lang;

    fn ur10() -> Model {
        Model::new(Session::for_preset("ur10").expect("preset"))
    }

    #[test]
    fn a_reached_target_is_said_with_the_robot_tool_and_branch() {
        let model = ur10();
        let words = view_words(&model);
        let tool = model.fk().tool_position();
        assert!(
            words.starts_with(&format!(
                "{}. Tool at x {:.0}, ",
                model.robot().name,
                tool.x
            )),
            "{words}"
        );
        assert!(words.contains("Target reached."), "{words}");
        assert!(words.contains("Branch: shoulder"), "{words}");
    }

    #[test]
    fn a_target_far_away_is_out_of_reach_in_both_languages() {
        let mut model = ur10();
        let mut target = *model.target();
        target.translation.vector *= 10.0;
        model.set_target(target);
        let words = view_words(&model);
        assert!(words.contains("Target out of reach"), "{words}");
        assert!(!words.contains("Target reached"), "{words}");
        model.set_lang(Lang::Fi);
        let words = view_words(&model);
        assert!(
            words.contains("Työkalu kohdassa") && words.contains("Kohde ulottumattomissa"),
            "{words}"
        );
    }

    #[test]
    fn the_reach_sentence_alone_is_the_full_sentences_reach_part() {
        let mut model = ur10();
        assert_eq!(reach_words(&model), "Target reached.");
        let mut target = *model.target();
        target.translation.vector *= 10.0;
        model.set_target(target);
        let reach = reach_words(&model);
        assert!(reach.starts_with("Target out of reach"), "{reach}");
        assert!(!reach.contains("Tool at"), "{reach}");
        let words = view_words(&model);
        assert!(words.contains(&format!(" {reach} ")), "{words}");
        model.set_lang(Lang::Fi);
        assert!(reach_words(&model).starts_with("Kohde ulottumattomissa"));
    }

    #[test]
    fn a_straight_elbow_says_its_lost_direction_and_a_bent_one_none() {
        let mut model = Model::new(Session::for_preset("planar-2r").expect("preset"));
        // The straight elbow: the tool cannot move along the arm, (cos 0.3, sin 0.3, 0).
        model.set_q(vec![0.3, 0.0]);
        let words = view_words(&model);
        assert!(
            words.contains("At a singularity: the tool cannot move along ("),
            "{words}"
        );
        assert!(
            words.contains("(0.96, 0.30, 0.00)") || words.contains("(-0.96, -0.30, 0.00)"),
            "{words}"
        );
        assert!(
            words.contains("Tool at x 2.87, y 0.89, z 0.00 m."),
            "{words}"
        );
        model.set_q(vec![0.3, 1.0]);
        let words = view_words(&model);
        assert!(!words.contains("singularity"), "{words}");
    }

    #[test]
    fn a_whole_workspace_cloud_is_said_with_its_size_reach_and_heights() {
        let mut model = ur10();
        model.set_overlay(armlab_session::settings::Overlay::Workspace, true);
        let measure = armlab_core::workspace::WorkspaceMeasure::Manipulability;
        model.fill_workspace(measure, 500, 0.0, || 0.0);
        assert!(
            !view_words(&model).contains("Workspace"),
            "said only when whole"
        );
        model.fill_workspace(measure, 500, f64::INFINITY, || 0.0);
        let cloud = model.shown_workspace().expect("shown");
        assert!(cloud.is_full());
        let (lo, hi) = cloud.bounds().expect("samples");
        let expected = format!(
            "Workspace: 500 sampled tool positions, up to {:.0} mm from the base, at heights {:.0} to {:.0} mm.",
            cloud.outer_reach(),
            lo.z,
            hi.z
        );
        assert!(
            view_words(&model).ends_with(&expected),
            "{}",
            view_words(&model)
        );
        model.set_overlay(armlab_session::settings::Overlay::Workspace, false);
        assert!(!view_words(&model).contains("Workspace"));
    }
}
