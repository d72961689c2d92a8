//! The native side's storage: the last session kept in a file
//! (`armlab_session::session::native_session_file`, `~/.config/armlab/session`), as the page
//! keeps it in localStorage, both as the session's JSON.

use std::path::Path;

/// The session kept in `path`, if the file is there and readable.
pub fn stored_session(path: &Path) -> Option<String> {
    std::fs::read_to_string(path).ok()
}

/// Keeps `json` (the session's JSON) in `path`, making its folder first; a failure is
/// logged (the app closes either way).
pub fn keep_session(path: &Path, json: &str) {
    let written = path
        .parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .and_then(|()| std::fs::write(path, json));
    if let Err(e) = written {
        log::warn!("could not keep the session in {}: {e}", path.display());
    }
}
