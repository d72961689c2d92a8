//! Whether the app can check collisions yet: natively at once; in the page once the lazily
//! loaded module that holds the collision library is there.

/// The state of the code that checks collisions: always ready natively; in the page the
/// module that holds the collision library (dist/urdf/) loads once per visit.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CheckerState {
    /// Checks run.
    Ready,
    /// The module is being fetched.
    Loading,
    /// The module could not be loaded: the browser's words.
    Failed(String),
}
