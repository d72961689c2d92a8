//! The Jacobian's measures (singular values, manipulability, det J, the condition
//! number), as displayed beside unit-free. Apart from the Jacobian's fold: a table of its
//! own, read from the core's measures.

use armlab_core::JacobianMeasures;
use armlab_text::Key;

use crate::app::state::model::Model;
use crate::app::state::tr;
use crate::app::state::trf;
use crate::app::widgets::style;
use crate::app::widgets::style::NameRow;
use armlab_session::format::number;

/// The measures of the task rows: as displayed (in the robot's units, what a student
/// computes from the matrix above) beside the unit-free versions (linear rows ÷ L).
pub(super) fn measures_grid(model: &Model, m: &JacobianMeasures, ui: &mut egui::Ui) {
    let sv: Vec<String> = m.singular_values.iter().map(|s| number(*s, 4)).collect();
    let unit = model.robot().length_unit.symbol();
    let scale = number(m.length_scale, 1);
    // det J and √det(J·Jᵀ) carry a length cubed (three linear rows); √det(Jᵀ·J) of an arm
    // with fewer joints than task rows mixes lengths and angles.
    let cubed = format!(" {unit}³");
    let rows = model.task().rows();
    let w_unit = if rows <= model.robot().dof() {
        cubed.as_str()
    } else {
        ""
    };
    let infinite = |c: Option<f64>, d| c.map_or("∞".to_string(), |c| number(c, d));
    ui.label(format!("{}  {rows}", tr(model, Key::TaskRows)))
        .on_hover_text(tr(model, Key::TaskRowsHint));
    let headers = [
        (
            tr(model, Key::MeasuresDisplayed).to_owned(),
            trf(model, Key::MeasuresDisplayedHint, &[&unit]),
        ),
        (
            tr(model, Key::MeasuresUnitFree).to_owned(),
            trf(model, Key::MeasuresUnitFreeHint, &[&scale, &unit]),
        ),
    ];
    let row = |name: &str, hint: Option<String>, values: [String; 2]| NameRow {
        name: name.to_owned(),
        hint,
        values: values.to_vec(),
    };
    let mut table = vec![
        row(
            tr(model, Key::SingularValues),
            Some(trf(model, Key::SingularValuesHint, &[&scale, &unit])),
            [String::new(), sv.join("  ")],
        ),
        row(
            tr(model, Key::Manipulability),
            Some(tr(model, Key::ManipulabilityHint).to_owned()),
            [
                format!("{}{w_unit}", number(m.displayed.manipulability, 5)),
                number(m.manipulability, 5),
            ],
        ),
    ];
    if let (Some(shown), Some(det)) = (m.displayed.determinant, m.determinant) {
        table.push(row(
            "det J",
            None,
            [format!("{}{cubed}", number(shown, 5)), number(det, 5)],
        ));
    }
    table.push(row(
        tr(model, Key::ConditionNumber),
        None,
        [
            infinite(m.displayed.condition_number, 2),
            infinite(m.condition_number, 2),
        ],
    ));
    style::fold_rows(ui, "measures", &headers, &table);
    if m.near_singular {
        ui.colored_label(style::UNREACHABLE, tr(model, Key::NearSingular));
    }
}
