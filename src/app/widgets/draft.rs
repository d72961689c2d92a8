//! A number field's draft: the text while it is typed, kept apart from the value it sets.

/// A field's text while it is typed, and its sentence when the text is refused.
#[derive(Debug, Clone, Default)]
pub(crate) struct Draft {
    pub(crate) text: String,
    pub(crate) error: Option<String>,
}
