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

/// The window as the layout needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Screen {
    /// Its width in CSS pixels.
    pub css_width: f32,
}

impl Screen {
    /// The screen of a context: its width in points times the zoom (a point is a CSS
    /// pixel at zoom 1).
    pub fn of(ctx: &egui::Context) -> Screen {
        Screen {
            css_width: ctx.content_rect().width() * ctx.zoom_factor(),
        }
    }
}

/// The zoom of presentation mode for a screen `css_width` CSS pixels wide: large text,
/// but the 3D view and a panel must still fit a 1024-pixel projector.
pub fn presentation_zoom(css_width: f32) -> f32 {
    (css_width / 820.0).clamp(1.25, 1.5)
}

/// The height of every clickable thing on a touch screen (points; one point is one CSS
/// pixel at zoom 1): a thumb needs about 40.
pub const TOUCH_TARGET: f32 = 40.0;

/// Applies the dark theme, larger and higher-contrast in presentation mode, with
/// thumb-sized controls on a touch screen. Cheap to call every frame: it only writes when
/// the mode, the touch sizing or the screen's zoom step changed.
///
/// `screen` is the window's width in CSS pixels.
pub fn install(ctx: &egui::Context, presentation: bool, touch: bool, screen: Screen) {
    let zoom = if presentation {
        presentation_zoom(screen.css_width)
    } else {
        1.0
    };
    let id = egui::Id::unique("armlab_style_mode");
    let wanted = (presentation, touch, (zoom * 100.0).round() as i32);
    let current: Option<(bool, bool, i32)> = ctx.data(|d| d.get_temp(id));
    if current == Some(wanted) {
        return;
    }
    ctx.data_mut(|d| d.insert_temp(id, wanted));
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
    ctx.all_styles_mut(|style| {
        let normal = egui::style::Spacing::default();
        let spacing = &mut style.spacing;
        if touch {
            spacing.interact_size.y = TOUCH_TARGET;
            spacing.button_padding = egui::vec2(10.0, 10.0);
            spacing.scroll.bar_width = 14.0;
        } else {
            spacing.interact_size = normal.interact_size;
            spacing.button_padding = normal.button_padding;
            spacing.scroll = normal.scroll;
        }
    });
    ctx.set_zoom_factor(zoom);
}
