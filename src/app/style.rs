//! Colours and text sizes, normal and for projectors (presentation mode).

use egui::Color32;

use crate::kinematics::ik::Reach;

/// Error text.
pub const ERROR: Color32 = Color32::from_rgb(255, 130, 110);
/// Warning text (done, but not as asked).
pub const WARNING: Color32 = Color32::from_rgb(240, 190, 80);
/// Information text (done as asked).
pub const INFO: Color32 = Color32::from_rgb(140, 200, 240);
/// "Reached" green, used for the target marker and status text.
pub const REACHED: Color32 = Color32::from_rgb(60, 200, 90);
/// "Out of reach" red.
pub const UNREACHABLE: Color32 = Color32::from_rgb(230, 60, 50);
/// "Not yet there" amber (a target that has not been solved for).
pub const PENDING: Color32 = Color32::from_rgb(235, 180, 40);
/// Highlight of the hovered link and matrix.
pub const HIGHLIGHT: Color32 = Color32::from_rgb(255, 210, 60);

/// The one colour table of the IK status: the marker's ball, the viewport's status line
/// and the IK panel all draw a [`Reach`] in its colour.
pub fn reach_color(reach: Reach) -> Color32 {
    match reach {
        Reach::Reached => REACHED,
        Reach::OutOfReach => UNREACHABLE,
        Reach::Pending => PENDING,
    }
}

/// The viewport and window background (opaque).
pub fn background(presentation: bool) -> Color32 {
    if presentation {
        Color32::from_rgb(0, 0, 0)
    } else {
        Color32::from_rgb(30, 33, 38)
    }
}

/// Installs ArmLab's one font (a DejaVu Sans subset, `assets/fonts/`) for both the
/// proportional and the monospace family; egui's default fonts are not compiled in.
pub fn install_fonts(ctx: &egui::Context) {
    let mut fonts = egui::FontDefinitions::empty();
    fonts.font_data.insert(
        "armlab-sans".to_owned(),
        std::sync::Arc::new(egui::FontData::from_static(include_bytes!(
            "../../assets/fonts/ArmLabSans.ttf"
        ))),
    );
    for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
        fonts
            .families
            .entry(family)
            .or_default()
            .push("armlab-sans".to_owned());
    }
    ctx.set_fonts(fonts);
}

/// Applies the dark theme, larger and higher-contrast in presentation mode. Cheap to call
/// every frame: it only writes when the mode changed.
pub fn install(ctx: &egui::Context, presentation: bool) {
    let id = egui::Id::unique("armlab_presentation_mode");
    let current: Option<bool> = ctx.data(|d| d.get_temp(id));
    if current == Some(presentation) {
        return;
    }
    ctx.data_mut(|d| d.insert_temp(id, presentation));
    let mut visuals = egui::Visuals::dark();
    visuals.panel_fill = if presentation {
        Color32::from_rgb(8, 8, 8)
    } else {
        Color32::from_rgb(38, 41, 46)
    };
    if presentation {
        visuals.override_text_color = Some(Color32::WHITE);
        visuals.widgets.noninteractive.fg_stroke.color = Color32::WHITE;
        visuals.widgets.inactive.fg_stroke.color = Color32::WHITE;
        visuals.selection.bg_fill = Color32::from_rgb(0, 110, 220);
    }
    // One theme everywhere: the browser's light/dark preference must not change the
    // colours the lecture sees (nor the browser tests' comparison with native).
    ctx.set_theme(egui::Theme::Dark);
    ctx.set_visuals_of(egui::Theme::Dark, visuals);
    ctx.set_zoom_factor(if presentation { 1.4 } else { 1.0 });
}
