//! Contrast ratios as WCAG 2.1 defines them (relative luminance of sRGB colours), for the
//! test that holds the theme's text to 4.5:1, its controls' outlines and its marks in the
//! 3D view to 3:1.

use egui::Color32;

/// The relative luminance of an opaque colour (0 black … 1 white).
pub fn luminance(c: Color32) -> f64 {
    let linear = |v: u8| {
        let s = f64::from(v) / 255.0;
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * linear(c.r()) + 0.7152 * linear(c.g()) + 0.0722 * linear(c.b())
}

/// The contrast ratio of two opaque colours, 1 (none) to 21 (black on white).
pub fn ratio(a: Color32, b: Color32) -> f64 {
    let (la, lb) = (luminance(a), luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::view3d::scene::AXIS;
    use crate::app::widgets::style;

    /// The theme's visuals as the app installs them, normal or for presentation.
    fn visuals(presentation: bool) -> egui::Visuals {
        let ctx = egui::Context::default();
        style::install(
            &ctx,
            presentation,
            false,
            style::Screen { css_width: 1366.0 },
        );
        ctx.style_of(egui::Theme::Dark).visuals.clone()
    }

    /// Each (what, colour, background) below `least`, with its ratio.
    fn failing(pairs: &[(&str, Color32, Color32)], least: f64) -> Vec<String> {
        pairs
            .iter()
            .map(|(what, fg, bg)| (what, ratio(*fg, *bg)))
            .inspect(|(what, r)| println!("{what}: {r:.2}:1"))
            .filter(|(_, r)| *r < least)
            .map(|(what, r)| format!("{what}: {r:.2}:1"))
            .collect()
    }

    #[test]
    fn the_ratio_of_black_and_white_is_21_and_of_a_colour_with_itself_1() {
        assert!((ratio(Color32::BLACK, Color32::WHITE) - 21.0).abs() < 1e-9);
        assert!(
            (ratio(Color32::from_rgb(30, 33, 38), Color32::from_rgb(30, 33, 38)) - 1.0).abs()
                < 1e-12
        );
        // WCAG's own example: #767676 on white is 4.54:1.
        assert!((ratio(Color32::from_gray(0x76), Color32::WHITE) - 4.54).abs() < 0.01);
    }

    #[test]
    fn text_has_at_least_4_5_to_1_on_the_panels_and_the_view() {
        for presentation in [false, true] {
            let v = visuals(presentation);
            let (panel, view) = (v.panel_fill, style::background(presentation));
            let button = v.widgets.inactive;
            let mut pairs = vec![
                ("text on a panel", v.text_color(), panel),
                ("text on the view", v.text_color(), view),
                (
                    "a button's text",
                    button.fg_stroke.color,
                    button.weak_bg_fill,
                ),
                ("a field's text", v.text_color(), v.extreme_bg_color),
            ];
            for (what, c) in [
                ("error text", style::ERROR),
                ("warning text", style::WARNING),
                ("information text", style::INFO),
                ("reached text", style::REACHED),
                ("out-of-reach text", style::UNREACHABLE),
                ("pending text", style::PENDING),
            ] {
                pairs.push((what, c, panel));
                pairs.push((what, c, view));
            }
            let failing = failing(&pairs, 4.5);
            assert!(
                failing.is_empty(),
                "presentation {presentation}: {failing:?}"
            );
        }
    }

    #[test]
    fn control_outlines_have_at_least_3_to_1_on_the_panels_and_windows() {
        for presentation in [false, true] {
            let v = visuals(presentation);
            let (idle, hovered) = (v.widgets.inactive.bg_stroke, v.widgets.hovered.bg_stroke);
            assert!(
                idle.width >= 1.0 && hovered.width >= 1.0,
                "presentation {presentation}: controls are outlined, {idle:?} {hovered:?}"
            );
            let pairs = [
                ("an idle control on a panel", idle.color, v.panel_fill),
                ("an idle control in a window", idle.color, v.window_fill),
                ("a hovered control on a panel", hovered.color, v.panel_fill),
                (
                    "a hovered control in a window",
                    hovered.color,
                    v.window_fill,
                ),
            ];
            let failing = failing(&pairs, 3.0);
            assert!(
                failing.is_empty(),
                "presentation {presentation}: {failing:?}"
            );
        }
    }

    #[test]
    fn the_views_marks_have_at_least_3_to_1_on_its_background() {
        for presentation in [false, true] {
            let view = style::background(presentation);
            let axis = |c: [u8; 4]| Color32::from_rgb(c[0], c[1], c[2]);
            let pairs = [
                ("the reached target", style::REACHED, view),
                ("the out-of-reach target", style::UNREACHABLE, view),
                ("the pending target", style::PENDING, view),
                ("the highlight", style::HIGHLIGHT, view),
                ("the x axis", axis(AXIS[0]), view),
                ("the y axis", axis(AXIS[1]), view),
                ("the z axis", axis(AXIS[2]), view),
            ];
            let failing = failing(&pairs, 3.0);
            assert!(
                failing.is_empty(),
                "presentation {presentation}: {failing:?}"
            );
        }
    }
}
