//! The IK solutions of the target as the model keeps them: the closed form's branches
//! named in words (every frame while the ghosts are drawn: microseconds), or the distinct
//! solutions of seeded restarts (on demand).

use armlab_core::{
    Branch, Elbow, IkSettings, Shoulder, Wrist, closed_form_solutions, distinct_solutions,
};
use armlab_text::Key;

use crate::app::state::model::{BranchRow, Model};
use crate::app::state::tr;
use crate::app::state::trf;
use armlab_session::settings::Overlay;

/// Restarts for the distinct solutions of an arm without a closed form.
const ATTEMPTS: usize = 48;

/// A branch in words: "shoulder right, elbow up, wrist not flipped".
pub fn branch_words(model: &Model, branch: &Branch) -> String {
    let shoulder = branch.shoulder.map(|s| match s {
        Shoulder::Right => Key::ShoulderRight,
        Shoulder::Left => Key::ShoulderLeft,
    });
    let elbow = branch.elbow.map(|e| match e {
        Elbow::Up => Key::ElbowUp,
        Elbow::Down => Key::ElbowDown,
    });
    let wrist = branch.wrist.map(|w| match w {
        Wrist::NotFlipped => Key::WristNotFlipped,
        Wrist::Flipped => Key::WristFlipped,
    });
    [shoulder, elbow, wrist]
        .into_iter()
        .flatten()
        .map(|k| tr(model, k))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The closed form's rows for the 3D view's ghosts when they are on and no rows are kept
/// for this target and robot: whether or not the IK panel, where the list is, is shown
/// (a phone's link with `show=ghosts` draws them with no sheet open).
pub fn ghost_rows(model: &mut Model) {
    if model.settings().overlays.contains(Overlay::Ghosts)
        && model.has_closed_form()
        && model.branches().is_none()
    {
        closed_form_rows(model);
    }
}

/// The closed form's solutions for the target (every frame: microseconds); true when
/// none is exact.
pub fn closed_form_rows(model: &mut Model) -> bool {
    let Ok(set) = closed_form_solutions(model.robot(), model.target(), model.q()) else {
        model.set_branches(Vec::new(), false);
        return false;
    };
    let rows = set
        .solutions
        .iter()
        .map(|s| BranchRow {
            q: s.q.clone(),
            label: branch_words(model, &s.branch),
            within_limits: s.within_limits,
        })
        .collect();
    model.set_branches(rows, false);
    set.unreachable
}

/// The distinct solutions of seeded restarts (on demand: tens of milliseconds).
pub fn found_rows(model: &mut Model) {
    let settings = IkSettings::default();
    let found = distinct_solutions(
        model.robot(),
        model.target(),
        model.task(),
        &settings,
        ATTEMPTS,
    );
    let Ok(found) = found else {
        model.set_branches(Vec::new(), false);
        return;
    };
    let rows = found
        .solutions
        .iter()
        .map(|s| {
            let signs: String = s
                .signs
                .iter()
                .map(|v| if *v > 0 { '+' } else { '−' })
                .collect();
            BranchRow {
                q: s.q.clone(),
                label: trf(model, Key::ConfigurationSigns, &[&signs]),
                within_limits: s.within_limits,
            }
        })
        .collect();
    model.set_branches(rows, found.continuum);
}
