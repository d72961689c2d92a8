//! The panels: one type per panel with one `ui` method that reads the model and asks it
//! for changes, the folds each panel holds, and the layout that places the panels for the
//! screen.

pub mod class;
pub mod convention;
pub mod exercise;
#[cfg(not(target_arch = "wasm32"))]
pub mod file_dialog;
pub mod ik;
pub mod joints;
pub mod layout;
pub mod matrices;
pub mod motion;
pub mod paths;
pub mod robot;
pub mod shell;
pub mod solutions;
pub mod top_bar;
pub mod workspace;

use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;

/// A side panel: a type that owns its own state and draws itself from the model, asking
/// the model's methods for every change.
pub trait Panel {
    /// Draws the panel; named points go to `points` for the test hook.
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints);
}
