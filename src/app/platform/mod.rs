//! The web and the native side of the app: its clock, whether the collision checker has
//! loaded, the symbolic matrices (made natively, by a lazily loaded module in the page),
//! the DH exercise's check and the join link's QR code (the same way), the last session's storage (`native`: a file;
//! `web`: localStorage), and in the page its
//! message box, the test hook, files and the lazily loaded modules. Nothing here imports
//! the app above it.

pub mod checker;
pub mod clock;
pub mod exercise;
#[cfg(not(target_arch = "wasm32"))]
pub mod native;
pub mod qr;
pub mod symbolic;
#[cfg(target_arch = "wasm32")]
pub mod web;

/// Where a result is that the page asks its lazily loaded module for (natively it is
/// made at once): the symbolic tables, the exercise's verdict, the join link's QR code.
#[derive(Debug, Clone, PartialEq)]
pub enum Answer<T> {
    /// Made.
    Ready(T),
    /// Being made by the module, which may itself still be loading.
    Loading,
    /// The module could not be loaded, or it threw: the words.
    Failed(String),
}

/// Whether this pass builds the accessibility tree for the page's mirror, the screen
/// readers' copy of the interface: the panels then lay out what is scrolled out of sight
/// too ([`crate::app::widgets::style::unless_out_of_sight`]). Natively never: the UI
/// tests' harness builds the tree in every frame, where laying out every block cost the
/// tests about 40 s (the desktop app keeps egui's tree of what is in sight).
pub fn mirror_pass() -> bool {
    #[cfg(target_arch = "wasm32")]
    {
        web::a11y::tree_this_pass()
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        false
    }
}

/// A link to this state: the page's address with the hash replaced.
pub fn share_link(hash: &str) -> String {
    #[cfg(target_arch = "wasm32")]
    {
        let base = web_sys::window()
            .and_then(|w| w.location().href().ok())
            .unwrap_or_default();
        let base = base.split('#').next().unwrap_or_default().to_string();
        format!("{base}#{hash}")
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        format!("#{hash}")
    }
}
