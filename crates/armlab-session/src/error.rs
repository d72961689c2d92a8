//! What is wrong with a link, as data and as the sentence a person reads.

use armlab_core::RobotError;
use armlab_text::echo::Text;
use armlab_text::{Key, Lang, Sentence, fill, text};

use super::motion::MotionLinkError;

/// What is wrong with a link; each reads as the middle of the sentence "This link could
/// not be opened (…)". `Display` is English; the app shows [`LinkError::sentence`]. The
/// link's own text is repeated through [`armlab_text::echo`] (40 characters at most, no
/// control characters).
#[derive(Debug, Clone, PartialEq)]
pub enum LinkError {
    /// A `key=value` part without `=`.
    NoEquals(String),
    /// A key the format does not have.
    UnknownPart(String),
    /// A broken `%XX` escape.
    BrokenEscape,
    /// Escapes that do not decode to UTF-8 text.
    NotUtf8,
    /// A list item that is not a finite number.
    NotANumber {
        /// `q`, `target` or `camera`.
        field: &'static str,
        /// The item as written.
        text: String,
    },
    /// A target that is not six numbers.
    TargetLength,
    /// A task id that is not known.
    UnknownTask(String),
    /// A display field whose value is not one of those allowed.
    BadValue {
        /// The field's key.
        field: String,
        /// The value as written.
        text: String,
        /// The catalogue's text of the values it can have.
        allowed: Key,
    },
    /// A camera that is not six numbers with a positive distance.
    BadCamera,
    /// A method id that is not known.
    UnknownMethod(String),
    /// `robot=` is missing.
    NoRobot,
    /// `robot=custom` without its table.
    CustomWithoutTable,
    /// The robot (a preset id, a table) or the joint vector is not valid.
    Robot(RobotError),
    /// A motion lab field (`move`, `ctrl`, `gains`, `plant`, `timescale`, `collide`,
    /// `keepout`) is not valid.
    Motion(MotionLinkError),
    /// `exercise=` names neither a preset nor `mystery-SEED`.
    UnknownExercise(String),
    /// `exercise=` with `robot=` or `dh=`: an exercise's link names no table.
    ExerciseWithRobot,
    /// An item of `hide=` that is not a matrix, an entry or a Jacobian column.
    BadHidden(String),
    /// Stored JSON that is not a session's (not JSON, a field missing or of another type).
    UnreadableSession,
}

impl LinkError {
    /// The reason in `lang`, as the middle of [`Key::LinkNotOpened`].
    pub fn sentence(&self, lang: Lang) -> String {
        let plain = |key| text(lang, key).to_string();
        match self {
            LinkError::NoEquals(part) => fill(lang, Key::LinkNoEquals, &[&Text(part)]),
            LinkError::UnknownPart(part) => fill(lang, Key::LinkUnknownPart, &[&Text(part)]),
            LinkError::BrokenEscape => plain(Key::LinkBrokenEscape),
            LinkError::NotUtf8 => plain(Key::LinkNotUtf8),
            LinkError::NotANumber { field, text } => {
                fill(lang, Key::LinkNotANumber, &[field, &Text(text)])
            }
            LinkError::TargetLength => plain(Key::LinkTargetLength),
            LinkError::UnknownTask(task) => fill(lang, Key::LinkUnknownTask, &[&Text(task)]),
            LinkError::BadValue {
                field,
                text,
                allowed,
            } => fill(
                lang,
                Key::LinkBadValue,
                &[
                    &Text(field),
                    &Text(text),
                    &armlab_text::text(lang, *allowed),
                ],
            ),
            LinkError::BadCamera => plain(Key::LinkBadCamera),
            LinkError::UnknownMethod(method) => {
                fill(lang, Key::LinkUnknownMethod, &[&Text(method)])
            }
            LinkError::NoRobot => plain(Key::LinkNoRobot),
            LinkError::CustomWithoutTable => plain(Key::LinkCustomWithoutTable),
            LinkError::Robot(e) => e.sentence(lang),
            LinkError::Motion(e) => e.sentence(lang),
            LinkError::UnknownExercise(id) => fill(lang, Key::LinkUnknownExercise, &[&Text(id)]),
            LinkError::ExerciseWithRobot => plain(Key::LinkExerciseWithRobot),
            LinkError::BadHidden(item) => fill(lang, Key::LinkBadHidden, &[&Text(item)]),
            LinkError::UnreadableSession => plain(Key::LinkUnreadableSession),
        }
    }
}

impl std::fmt::Display for LinkError {
    /// The English reason.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.sentence(Lang::En))
    }
}

impl std::error::Error for LinkError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            LinkError::Robot(e) => Some(e),
            _ => None,
        }
    }
}

impl From<RobotError> for LinkError {
    fn from(e: RobotError) -> Self {
        LinkError::Robot(e)
    }
}
