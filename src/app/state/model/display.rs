//! The model's writers of the display settings, one per thing a person switches: units,
//! frames, presentation, language, precision, which panels are open, the 3D view's
//! overlays and presentation's hidden entries, and the device's reduced motion.

use armlab_session::settings::{Hidden, Overlay, PanelKind};
use armlab_text::Lang;

use super::Model;

impl Model {
    /// Angles in degrees (else radians).
    pub fn set_degrees(&mut self, degrees: bool) {
        self.settings.degrees = degrees;
    }

    /// Draws the DH frames in the 3D view.
    pub fn set_show_frames(&mut self, show: bool) {
        self.settings.show_frames = show;
    }

    /// Presentation mode: projector text sizes and its own set of open panels.
    pub fn set_presentation(&mut self, on: bool) {
        self.settings.presentation = on;
    }

    /// The interface language.
    pub fn set_lang(&mut self, lang: Lang) {
        self.settings.lang = lang;
    }

    /// Decimals of the matrices' entries.
    pub fn set_precision(&mut self, decimals: usize) {
        self.settings.precision = decimals;
    }

    /// Opens or closes a side panel (in the mode's own set: presentation keeps its own).
    pub fn set_panel_open(&mut self, kind: PanelKind, open: bool) {
        self.settings.set_panel_open(kind, open);
    }

    /// Switches one of the 3D view's overlays.
    pub fn set_overlay(&mut self, overlay: Overlay, on: bool) {
        self.settings.overlays.set(overlay, on);
    }

    /// The user's system asks for reduced motion (the platform says so at start).
    pub fn set_reduced_motion(&mut self, reduced: bool) {
        self.reduced_motion = reduced;
    }

    /// Hides an entry in presentation mode, or shows it again.
    pub fn toggle_hidden(&mut self, item: Hidden) {
        self.settings.hidden.toggle(item);
    }
}
