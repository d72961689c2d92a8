//! Colours and text sizes, normal and for projectors (presentation mode).

use egui::Color32;

use armlab_core::ik::Reach;

/// Error text.
pub const ERROR: Color32 = Color32::from_rgb(255, 130, 110);
/// Warning text (done, but not as asked).
pub const WARNING: Color32 = Color32::from_rgb(240, 190, 80);
/// Information text (done as asked).
pub const INFO: Color32 = Color32::from_rgb(140, 200, 240);
/// "Reached" green, used for the target marker and status text.
pub const REACHED: Color32 = Color32::from_rgb(60, 200, 90);
/// "Out of reach" red; light enough to be read as text on the panels (4.5:1).
pub const UNREACHABLE: Color32 = Color32::from_rgb(250, 100, 90);
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

/// An idle control's outline: 3.3:1 on the panel, 4.5:1 on presentation mode's.
pub const CONTROL_OUTLINE: Color32 = Color32::from_gray(120);

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
            "../../../assets/fonts/ArmLabSans.ttf"
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

/// The small text's size (points): egui's, and presentation mode's (14 CSS pixels at the
/// smallest presentation zoom).
const NORMAL_SMALL: f32 = 9.0;
const PRESENT_SMALL: f32 = 11.2;
/// A text field's fill in presentation mode, against its black panels.
const PRESENT_FIELD: Color32 = Color32::from_gray(36);

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
    // egui marks an idle button or field by a fill only slightly lighter than the panel
    // (about 1.2:1); a thin outline gives its boundary 3:1 (WCAG's non-text contrast),
    // grey so the panels stay calm.
    visuals.widgets.inactive.bg_stroke = egui::Stroke::new(1.0, CONTROL_OUTLINE);
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
        // A text field's fill apart from the black panel: the DH cells keep their boxes.
        visuals.extreme_bg_color = PRESENT_FIELD;
    } else {
        // egui's grey text (140) has 4.3:1 on the panel, under the 4.5:1 text needs.
        visuals.widgets.noninteractive.fg_stroke.color = Color32::from_gray(150);
    }
    // One theme everywhere: the browser's light/dark preference must not change the
    // colours the lecture sees (nor the browser tests' comparison with native).
    ctx.set_theme(egui::Theme::Dark);
    ctx.set_visuals_of(egui::Theme::Dark, visuals);
    ctx.all_styles_mut(|style| {
        let normal = egui::style::Spacing::default();
        // Notes under a heading (a robot's description, the units of a table) read from
        // the back of the room too: small text is nearly body-sized in presentation.
        let small = if presentation {
            PRESENT_SMALL
        } else {
            NORMAL_SMALL
        };
        if let Some(font) = style.text_styles.get_mut(&egui::TextStyle::Small) {
            font.size = small;
        }
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

/// Stops egui's own motion when the system asks for reduced motion: folds open and
/// scroll areas jump to a control at once instead of sliding. Cheap to call every frame:
/// it only writes when the setting changed.
pub fn reduce_motion(ctx: &egui::Context, reduced: bool) {
    let id = egui::Id::unique("armlab_reduced_motion");
    if ctx.data(|d| d.get_temp::<bool>(id)) == Some(reduced) {
        return;
    }
    ctx.data_mut(|d| d.insert_temp(id, reduced));
    let normal = egui::Style::default();
    ctx.all_styles_mut(|style| {
        if reduced {
            style.animation_time = 0.0;
            style.scroll_animation = egui::style::ScrollAnimation::none();
        } else {
            style.animation_time = normal.animation_time;
            style.scroll_animation = normal.scroll_animation;
        }
    });
}

/// A fold header's title, wrapped to the room the header has: egui lays a
/// [`egui::CollapsingHeader`]'s title out on one line however long it is, which widens
/// the whole column past the screen on a projector ("Both conventions side by…" cut off).
/// The galley keeps the placeholder colour, so the header still paints it in its own
/// (hovered, open) text colour.
pub fn fold_title(ui: &egui::Ui, text: impl ToString) -> egui::WidgetText {
    let font = egui::TextStyle::Button.resolve(ui.style());
    let padding = ui.spacing().indent + 2.0 * ui.spacing().button_padding.x;
    let width = (room(ui) - padding).max(60.0);
    ui.painter()
        .layout(text.to_string(), font, Color32::PLACEHOLDER, width)
        .into()
}

/// The width left on this row that a person can see: the room to the layout's right edge,
/// but no further than the visible (clipped) part of a column that scrolls sideways. A
/// matrix wider than its column widens the column's layout for everything after it, so
/// `available_width` alone would let text and buttons run out of sight.
pub fn room(ui: &egui::Ui) -> f32 {
    let visible = ui.clip_rect().right() - ui.cursor().left() - ui.spacing().scroll.bar_width;
    ui.available_width().min(visible).max(0.0)
}

/// Sets the slider rail to what the visible room leaves on a row beside a name
/// `name_width` wide and a value as wide as `value` (with the value box's padding and the
/// gaps between), at least 40 points; returns what the room left.
pub fn fit_rail(ui: &mut egui::Ui, name_width: f32, value: &str) -> f32 {
    let font = egui::TextStyle::Body.resolve(ui.style());
    let spacing = ui.spacing();
    let taken = name_width
        + text_width(ui, value, &font)
        + 2.0 * spacing.button_padding.x
        + 3.0 * spacing.item_spacing.x;
    let left = room(ui) - taken;
    ui.spacing_mut().slider_width = left.clamp(40.0, 320.0);
    left
}

/// Adds `slider` with its rail in the idle controls' outline grey ([`CONTROL_OUTLINE`]):
/// egui fills a rail with an idle control's fill, about 1.3:1 on the panel, under the 3:1
/// a control needs to be seen. Only the slider's: check boxes and radio buttons keep that
/// fill inside their outline. The idle handle takes the same grey; its light rim and its
/// size, above and below the rail, set it apart.
pub fn slider(ui: &mut egui::Ui, slider: egui::Slider<'_>) -> egui::Response {
    let idle = std::mem::replace(
        &mut ui.visuals_mut().widgets.inactive.bg_fill,
        CONTROL_OUTLINE,
    );
    let response = ui.add(slider);
    ui.visuals_mut().widgets.inactive.bg_fill = idle;
    response
}

/// A slider (`add` draws it) after its name (with its hover `hint`), the rail fitted to
/// the visible room ([`fit_rail`]; values up to `widest` wide): beside the name where the
/// row leaves the rail 60 points, else under it (a projector's column). The slider is
/// labelled by the name for screen readers and the tests, and shows the hint too.
pub fn named_slider(
    ui: &mut egui::Ui,
    (name, hint): (&str, &str),
    widest: &str,
    add: impl FnOnce(&mut egui::Ui) -> egui::Response,
) -> egui::Response {
    ui.scope(|ui| {
        let font = egui::TextStyle::Body.resolve(ui.style());
        if fit_rail(ui, text_width(ui, name, &font), widest) >= 60.0 {
            ui.horizontal(|ui| {
                let label = ui.label(name).on_hover_text(hint);
                add(ui).labelled_by(label.id).on_hover_text(hint)
            })
            .inner
        } else {
            let label = ui.label(name).on_hover_text(hint);
            fit_rail(ui, 0.0, widest);
            add(ui).labelled_by(label.id).on_hover_text(hint)
        }
    })
    .inner
}

/// Lays out `add` unless it would be out of sight: a side panel scrolls, and its blocks
/// below the fold (the A_i and T_0i of a six-joint arm, about twelve framed matrices) cost
/// egui's layout and text shaping in every frame while the arm moves, unseen. The size
/// the content took the last time it was laid out at this width is kept under `id`; when
/// that rect at the cursor is wholly outside the visible (clipped) area, the space is
/// allocated empty and `add` is not called (`None`). Scrolled or resized into sight, it is
/// laid out again in the same frame, so nothing on screen is ever missing. A pass that
/// builds the page's tree for screen readers lays it out wherever it is: a screen reader
/// reads the whole panel, not only what is scrolled into view (the page builds that tree
/// at most twice a second, on a key, or when a script asks, and not during a pointer
/// drag; [`crate::app::platform::mirror_pass`]).
pub fn unless_out_of_sight<R>(
    ui: &mut egui::Ui,
    id: egui::Id,
    add: impl FnOnce(&mut egui::Ui) -> R,
) -> Option<R> {
    let width = ui.available_width();
    let known: Option<(f32, egui::Vec2)> = ui.data(|d| d.get_temp(id));
    let mirror = crate::app::platform::mirror_pass();
    if let Some((_, size)) = known.filter(|(w, _)| *w == width && !mirror) {
        let rect = egui::Rect::from_min_size(ui.cursor().min, size);
        if !ui.is_rect_visible(rect) {
            ui.allocate_exact_size(size, egui::Sense::hover());
            return None;
        }
    }
    let shown = ui.scope(add);
    let size = shown.response.rect.size();
    ui.data_mut(|d| d.insert_temp(id, (width, size)));
    Some(shown.inner)
}

/// One of a row of choices, or a switch, drawn as a button whose outline shows also while
/// it is not chosen: egui's selectable buttons show only their text until hovered or
/// chosen, and a control needs a boundary of 3:1 against the panel (WCAG 1.4.11; the
/// idle outline's ratio is in [`crate::app::widgets::contrast`]). Chosen, it takes the
/// selection's colours. Choices in a menu's list stay plain: the menu frames them.
pub fn choice<'a>(selected: bool, text: impl egui::IntoAtoms<'a>) -> egui::Button<'a> {
    egui::Button::selectable(selected, text).frame_when_inactive(true)
}

/// A [`choice`] that switches `on` when clicked (`changed()` then holds), as
/// [`egui::Ui::toggle_value`] does.
pub fn switch<'a>(
    ui: &mut egui::Ui,
    on: &mut bool,
    text: impl egui::IntoAtoms<'a>,
) -> egui::Response {
    let mut response = ui.add(choice(*on, text));
    if response.clicked() {
        *on = !*on;
        response.mark_changed();
    }
    response
}

/// [`egui::Ui::horizontal_wrapped`] that wraps at the visible [`room`] instead of the
/// layout's (possibly widened) right edge.
pub fn wrapped<R>(
    ui: &mut egui::Ui,
    add: impl FnOnce(&mut egui::Ui) -> R,
) -> egui::InnerResponse<R> {
    let size = egui::vec2(room(ui).max(60.0), ui.spacing().interact_size.y);
    let layout = egui::Layout::left_to_right(egui::Align::Center).with_main_wrap(true);
    ui.allocate_ui_with_layout(size, layout, add)
}

/// One row of [`fold_rows`]: a name (with an optional hover text) and its values.
#[derive(Debug, Clone, Default)]
pub struct NameRow {
    /// The quantity's name.
    pub name: String,
    /// Shown when the name is hovered.
    pub hint: Option<String>,
    /// One value per value column (an empty string leaves its cell empty).
    pub values: Vec<String>,
}

/// A sentence wrapped at the visible edge of its panel ([`room`]), however wide a table
/// above it (one that scrolls sideways) has made the layout.
pub fn sentence(ui: &mut egui::Ui, text: egui::RichText) -> egui::Response {
    let width = room(ui).max(120.0);
    ui.scope(|ui| {
        ui.set_max_width(width);
        ui.add(egui::Label::new(text).wrap())
    })
    .inner
}

/// The width of `text` on one line in `font` (points).
pub fn text_width(ui: &egui::Ui, text: &str, font: &egui::FontId) -> f32 {
    ui.painter()
        .layout_no_wrap(text.to_owned(), font.clone(), Color32::PLACEHOLDER)
        .size()
        .x
}

/// A menu with its label on its left ([`menu_row`]), `wish` points wide (`None`: as wide
/// as its selected text, at least egui's combo width) and never narrower than its
/// selected text where the room allows. A long selected text in a narrow column (a
/// projector's side column: "Franka Panda" beside "Preset" at 1024×768) puts the
/// label above and wraps the text rather than cutting it to "Franka Pa…".
pub fn fitted_menu<R>(
    ui: &mut egui::Ui,
    id_salt: &str,
    label: &str,
    selected: &str,
    wish: Option<f32>,
    add_contents: impl FnOnce(&mut egui::Ui) -> R,
) -> egui::InnerResponse<Option<R>> {
    let font = egui::TextStyle::Button.resolve(ui.style());
    let label_width = text_width(ui, label, &font);
    let need = menu_need(ui, selected);
    let wish = wish.unwrap_or(ui.spacing().combo_width).max(need);
    menu_row(
        ui,
        id_salt,
        (label, label_width),
        selected,
        (need, wish),
        add_contents,
    )
}

/// A menu button's width beyond its selected text: the padding, the arrow and the gap
/// before it.
pub fn menu_frame(ui: &egui::Ui) -> f32 {
    let spacing = ui.spacing();
    spacing.icon_width + 2.0 * spacing.button_padding.x + 4.0
}

/// The width a menu needs to show the longest of `choices` whole ([`menu_frame`] added),
/// so that it keeps one width whichever is chosen.
pub fn menu_width(ui: &egui::Ui, choices: &[&str]) -> f32 {
    choices.iter().map(|c| menu_need(ui, c)).fold(0.0, f32::max)
}

/// The width a menu needs to show `selected` whole on one line.
pub fn menu_need(ui: &egui::Ui, selected: &str) -> f32 {
    text_width(ui, selected, &egui::TextStyle::Button.resolve(ui.style())) + menu_frame(ui)
}

/// A menu with its label on its left, the label `label_width` wide (the widest of its
/// group's labels, so that the group's menus line up) and the menu `wish` wide or what
/// the row has left. Where that leaves less than `need` ([`menu_need`] of the selected
/// text, or the most of a group's, so that the group's menus are placed alike: a
/// projector's side column has no room for "Damped least squares" beside "Method" at
/// 1024×768; a long Finnish name), the label goes above and the menu takes the whole
/// row, its text wrapped onto a second line rather than cut.
pub fn menu_row<R>(
    ui: &mut egui::Ui,
    id_salt: &str,
    (label, label_width): (&str, f32),
    selected: &str,
    (need, wish): (f32, f32),
    add_contents: impl FnOnce(&mut egui::Ui) -> R,
) -> egui::InnerResponse<Option<R>> {
    let room = room(ui);
    let beside = room - label_width - ui.spacing().item_spacing.x;
    let menu = |ui: &mut egui::Ui, label: egui::Id, width: f32| {
        ui.scope(|ui| {
            ui.set_max_width(width);
            let inner = egui::ComboBox::from_id_salt(id_salt)
                .selected_text(selected)
                .width(width)
                .wrap()
                .show_ui(ui, add_contents);
            egui::InnerResponse::new(inner.inner, inner.response.labelled_by(label))
        })
        .inner
    };
    if need <= beside {
        ui.horizontal(|ui| {
            let size = egui::vec2(label_width, ui.spacing().interact_size.y);
            let layout = egui::Layout::left_to_right(egui::Align::Center);
            let label = ui
                .allocate_ui_with_layout(size, layout, |ui| {
                    ui.set_min_width(label_width);
                    ui.label(label).id
                })
                .inner;
            menu(ui, label, wish.min(beside))
        })
        .inner
    } else {
        let label = ui.label(label).id;
        menu(ui, label, wish.min(room))
    }
}

/// Names and their values as a grid (a header row over the value columns when `headers`
/// is not empty) where the grid fits the visible [`room`]; on a narrow column (a projector's
/// side column, a phone) each name stands over its values instead, indented and labelled
/// with their column's header, so no number runs out of sight. Scrolled out of sight, the
/// rows keep their space without being laid out ([`unless_out_of_sight`]).
pub fn fold_rows(ui: &mut egui::Ui, id: &str, headers: &[(String, String)], rows: &[NameRow]) {
    let key = ui.make_persistent_id(("fold rows", id));
    unless_out_of_sight(ui, key, |ui| lay_out_rows(ui, id, headers, rows));
}

/// [`fold_rows`]' layout: measures every text, then the grid or the folded rows.
fn lay_out_rows(ui: &mut egui::Ui, id: &str, headers: &[(String, String)], rows: &[NameRow]) {
    let body = egui::TextStyle::Body.resolve(ui.style());
    let mono = egui::TextStyle::Monospace.resolve(ui.style());
    let width = |text: &str, font: &egui::FontId| text_width(ui, text, font);
    let columns = rows.iter().map(|r| r.values.len()).max().unwrap_or(0);
    let mut widths = vec![0.0_f32; columns + 1];
    for row in rows {
        widths[0] = widths[0].max(width(&row.name, &body));
        for (c, value) in row.values.iter().enumerate() {
            widths[c + 1] = widths[c + 1].max(width(value, &mono));
        }
    }
    for (c, (header, _)) in headers.iter().enumerate().take(columns) {
        widths[c + 1] = widths[c + 1].max(width(header, &body));
    }
    let spacing = ui.spacing().item_spacing.x;
    let needed: f32 = widths.iter().sum::<f32>() + spacing * columns as f32;
    if needed <= room(ui) {
        egui::Grid::new(id).num_columns(columns + 1).show(ui, |ui| {
            if !headers.is_empty() {
                ui.label("");
                for (header, hint) in headers {
                    ui.label(header).on_hover_text(hint);
                }
                ui.end_row();
            }
            for row in rows {
                let name = ui.label(&row.name);
                if let Some(hint) = &row.hint {
                    name.on_hover_text(hint);
                }
                for value in &row.values {
                    ui.monospace(value);
                }
                ui.end_row();
            }
        });
        return;
    }
    for row in rows {
        let name = ui.label(&row.name);
        if let Some(hint) = &row.hint {
            name.on_hover_text(hint);
        }
        ui.indent((id, &row.name), |ui| {
            let filled = row.values.iter().filter(|v| !v.is_empty()).count();
            for (c, value) in row.values.iter().enumerate() {
                if value.is_empty() {
                    continue;
                }
                let text = match headers.get(c) {
                    Some((header, _)) if filled > 1 || headers.len() > 1 => {
                        format!("{value}  ({header})")
                    }
                    _ => value.clone(),
                };
                ui.add(egui::Label::new(egui::RichText::new(text).monospace()).wrap());
            }
        });
    }
}
