//! The matrices panel: every A_i and T_0i, the tool pose, the Jacobian with its measures,
//! and the tool orientation in four forms. Values update live; precision is selectable;
//! every matrix can be copied as plain text, LaTeX or NumPy.
//!
//! This module holds the panel and its `ui`; its parts are apart by role: a matrix's
//! block (`block`), its text (`export`), how its numbers fit (`fit`), predict-and-reveal
//! (`predict`), the Jacobian's fold (`jacobian`) and measures (`measures`), the tool's
//! orientation (`orientation`) and the symbolic matrices (`symbolic`). The numbers
//! themselves are drawn by the `numbers` widget.

mod block;
mod export;
mod fit;
mod jacobian;
mod measures;
mod orientation;
mod predict;
mod symbolic;

use nalgebra::DMatrix;

use armlab_core::{Convention, JacobianAnalysis, Orientation, Robot, Task};
use armlab_text::Key;

use crate::app::panels::Panel;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::{HoverSource, Model};
use crate::app::state::tr;
use crate::app::state::trf;
use armlab_core::symbolic_tables::{SymbolicTable, SymbolicTables};
use armlab_session::settings::{Hidden, MatrixId};
use block::{Axes, matrix_block};
use jacobian::jacobian_block;
use orientation::orientation_block;
use predict::{Hiding, Target};
use symbolic::{SymbolicCache, symbolic_block};

fn homogeneous(pose: &nalgebra::IsometryMatrix3<f64>) -> DMatrix<f64> {
    let h = armlab_core::fk::homogeneous(pose);
    DMatrix::from_fn(4, 4, |r, c| h[(r, c)])
}

/// The matrices panel. It keeps the Jacobian analysis of the pose it last showed (the
/// central-difference check and an SVD, recomputed only when the robot, q or the task
/// changes); its layout caches (each block's size while scrolled out of sight, the glyph
/// quads of the numbers) live in egui's memory for the frame.
#[derive(Debug, Clone, Default)]
pub struct MatricesPanel {
    analysis: Option<AnalysisCache>,
    /// Show A_i, T_0i and J symbolically instead of as numbers.
    symbolic: bool,
    /// Show J in the tool frame instead of the base frame.
    tool_frame: bool,
    chain: SymbolicCache,
    /// Predict, then reveal: the lecturer is choosing what to hide.
    choosing: bool,
    /// What a click revealed during the lecture ("Hide again" puts it back).
    revealed: Vec<Hidden>,
}

/// A Jacobian analysis and what it was computed for.
#[derive(Debug, Clone)]
struct AnalysisCache {
    robot: Robot,
    q: Vec<f64>,
    task: Task,
    analysis: JacobianAnalysis,
}

impl MatricesPanel {
    /// The analysis of the model's pose, from the cache when nothing it depends on changed.
    fn analysis(&mut self, model: &Model) -> &JacobianAnalysis {
        let fresh = self.analysis.as_ref().is_some_and(|c| {
            c.task == model.task() && c.q.as_slice() == model.q() && &c.robot == model.robot()
        });
        if !fresh {
            self.analysis = None;
        }
        let cache = self.analysis.get_or_insert_with(|| AnalysisCache {
            robot: model.robot().clone(),
            q: model.q().to_vec(),
            task: model.task(),
            analysis: JacobianAnalysis::new(model.robot(), model.fk(), model.q(), model.task()),
        });
        &cache.analysis
    }
}

impl Panel for MatricesPanel {
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints) {
        if model.table_hidden() {
            // Every number here (A_i, T_0i, J, even T_0n at a chosen q) would give the
            // exercise's table away.
            ui.label(tr(model, Key::ExerciseHidden));
            return;
        }
        precision_row(model, ui);
        let mut hiding = self.hiding(model, ui);
        let decimals = model.settings().precision;
        let n = model.robot().dof();
        let unit = model.robot().length_unit.symbol();
        let lang = model.settings().lang;
        matrix_block(
            ui,
            lang,
            &trf(model, Key::ToolPoseTitle, &[&n, &unit]),
            tr(model, Key::ToolPoseHint),
            &homogeneous(&model.fk().base_from_tool),
            decimals,
            (false, Axes::Pose),
            (Target::Matrix(MatrixId::Tool), &mut hiding),
        );
        orientation_block(
            ui,
            lang,
            &Orientation::from_rotation(model.fk().tool_rotation()),
            model.settings().degrees,
            decimals,
        );
        egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::Jacobian),
        ))
        .id_salt("jacobian")
        .default_open(true)
        .show(ui, |ui| {
            jacobian::frame_switch(model, ui, &mut self.tool_frame);
            let tool_frame = self.tool_frame;
            let analysis = self.analysis(model);
            jacobian_block(model, analysis, ui, (decimals, tool_frame), &mut hiding)
        });
        let hovered = self.links_fold(model, ui, (decimals, points), &mut hiding);
        model.set_hovered_link(hovered, HoverSource::Matrices);
        self.finish_hiding(model, hiding, points);
    }
}

impl MatricesPanel {
    /// The fold of every A_i and T_0i (and, symbolically, J); returns the link whose
    /// matrix is under the pointer.
    fn links_fold(
        &mut self,
        model: &Model,
        ui: &mut egui::Ui,
        (decimals, points): (usize, &mut ScreenPoints),
        hiding: &mut Hiding,
    ) -> Option<usize> {
        let tool_frame = self.tool_frame;
        egui::CollapsingHeader::new(crate::app::widgets::style::fold_title(
            ui,
            tr(model, Key::LinkTransforms),
        ))
        .id_salt("link_transforms")
        .default_open(true)
        .show(ui, |ui| {
            let tick = ui
                .checkbox(&mut self.symbolic, tr(model, Key::ShowSymbolic))
                .on_hover_text(tr(model, Key::ShowSymbolicHint));
            points.insert("matrices-symbolic", tick.rect.center());
            if tick.changed() && self.symbolic {
                // Tables that failed to load are asked for again when ticked again.
                crate::app::platform::symbolic::retry_symbolic_tables();
            }
            let tables = self
                .symbolic
                .then(|| self.chain.tables(model.robot(), model.robot_changes()));
            let ready = tables.and_then(|t| ready_or_say(model, ui, t));
            let links = link_blocks(model, ui, decimals, ready.as_deref(), hiding);
            if let Some(t) = &ready {
                let j = if tool_frame {
                    &t.jacobian_tool
                } else {
                    &t.jacobian_base
                };
                symbolic_jacobian_block(model, ui, j, tool_frame);
            }
            links
        })
        .body_returned
        .flatten()
    }
}

/// Ready tables, or `None` after saying that they load or could not be loaded (the
/// numbers are shown meanwhile).
fn ready_or_say(
    model: &Model,
    ui: &mut egui::Ui,
    tables: crate::app::platform::symbolic::Tables,
) -> Option<std::rc::Rc<SymbolicTables>> {
    use crate::app::platform::symbolic::Tables;
    match tables {
        Tables::Ready(t) => return Some(t),
        Tables::Loading => {
            ui.label(tr(model, Key::SymbolicLoading));
        }
        Tables::Failed(why) => {
            let why = armlab_text::echo::text_within(&why, 60);
            let sentence = trf(model, Key::SymbolicFailed, &[&why]);
            ui.colored_label(crate::app::widgets::style::ERROR, sentence);
        }
    }
    None
}

/// A symbolic A_i or T_0i, or the "?" of a whole matrix hidden for the lecture; `hot`:
/// the joint under the pointer and whether this matrix is its. Returns whether the
/// pointer is over it.
fn symbolic_unless_hidden(
    ui: &mut egui::Ui,
    hiding: &mut Hiding,
    (id, title, lang): (MatrixId, &str, armlab_text::Lang),
    m: &SymbolicTable,
    (joint_under, highlighted): (Option<usize>, bool),
) -> bool {
    match hiding.concealed_whole(id) {
        Some(item) => hiding.concealed_block(ui, lang, title, item),
        None => symbolic_block(ui, lang, title, m, joint_under, highlighted),
    }
}

/// The symbolic J under the symbolic T_0i, in the frame the Jacobian's fold shows; the
/// entries that depend on the joint under the pointer are highlighted.
fn symbolic_jacobian_block(model: &Model, ui: &mut egui::Ui, j: &SymbolicTable, tool_frame: bool) {
    let title = tr(model, jacobian::title(tool_frame));
    let joint_under = model.hovered_link().and_then(|l| l.checked_sub(1));
    let lang = model.settings().lang;
    symbolic_block(ui, lang, title, j, joint_under, false);
}

fn precision_row(model: &mut Model, ui: &mut egui::Ui) {
    ui.horizontal(|ui| {
        let label = ui.label(tr(model, Key::Decimals));
        let mut precision = model.settings().precision;
        if ui
            .add(egui::DragValue::new(&mut precision).range(0..=8))
            .labelled_by(label.id)
            .changed()
        {
            let mut settings = model.settings().clone();
            settings.precision = precision;
            model.set_settings(settings);
        }
    });
}

/// Every A_i and T_0i; returns the link whose matrix is under the pointer.
fn link_blocks(
    model: &Model,
    ui: &mut egui::Ui,
    decimals: usize,
    symbolic: Option<&SymbolicTables>,
    hiding: &mut Hiding,
) -> Option<usize> {
    let convention = match model.robot().convention {
        Convention::Standard => Key::StandardFormula,
        Convention::Modified => Key::ModifiedFormula,
    };
    crate::app::widgets::math::label(ui, tr(model, convention));
    let lang = model.settings().lang;
    let mut hovered = None;
    // The joint under the pointer (its slider, its link in 3D, its matrices): symbolic
    // entries that depend on it are highlighted.
    let joint_under = model.hovered_link().and_then(|l| l.checked_sub(1));
    for (i, joint) in model.robot().joints.iter().enumerate() {
        let highlighted = model.hovered_link() == Some(i + 1);
        let variable = crate::app::widgets::math::joint_variable(joint.kind);
        if let Some((a, t)) =
            symbolic.and_then(|s| s.link_transforms.get(i).zip(s.base_from_frames.get(i)))
        {
            let title = trf(model, Key::LinkTitle, &[&(i + 1), &joint.name, &variable]);
            let hot = (joint_under, highlighted);
            let over_a =
                symbolic_unless_hidden(ui, hiding, (MatrixId::Link(i + 1), &title, lang), a, hot);
            let title = format!("T_0{}", i + 1);
            let over_t =
                symbolic_unless_hidden(ui, hiding, (MatrixId::Frame(i + 1), &title, lang), t, hot);
            if over_a || over_t {
                hovered = Some(i + 1);
            }
            continue;
        }
        let a = homogeneous(&model.fk().link_transforms[i]);
        let title = trf(model, Key::LinkTitle, &[&(i + 1), &joint.name, &variable]);
        if matrix_block(
            ui,
            lang,
            &title,
            tr(model, Key::FrameInPrevious),
            &a,
            decimals,
            (highlighted, Axes::Pose),
            (Target::Matrix(MatrixId::Link(i + 1)), &mut *hiding),
        ) {
            hovered = Some(i + 1);
        }
        let t = homogeneous(&model.fk().base_from_frames[i]);
        let title = format!("T_0{}", i + 1);
        let hover = tr(model, Key::FrameInBase);
        let target = (Target::Matrix(MatrixId::Frame(i + 1)), &mut *hiding);
        let shown = (highlighted, Axes::Pose);
        if matrix_block(ui, lang, &title, hover, &t, decimals, shown, target) {
            hovered = Some(i + 1);
        }
    }
    hovered
}
