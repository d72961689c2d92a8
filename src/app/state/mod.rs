//! The app's state: the model (the session and what is derived from it) and one
//! sub-model per lab. The model's methods are its only writers. No egui here: the state
//! is tested without a window.

pub mod branches;
pub mod classroom;
pub mod model;
pub mod motion_lab;
pub mod notebook;
pub mod path_lab;
pub mod view_words;

use armlab_text::Key;
use model::Model;

/// The text of `key` in the model's language.
pub fn tr(model: &Model, key: Key) -> &'static str {
    armlab_text::text(model.settings().lang, key)
}

/// The text of `key` in the model's language, its places filled by `args`.
pub fn trf(model: &Model, key: Key, args: &[&dyn std::fmt::Display]) -> String {
    armlab_text::fill(model.settings().lang, key, args)
}
