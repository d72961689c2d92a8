//! Draws the [`layout::Plan`](crate::app::panels::layout::Plan): the wide layout's side columns with
//! their edge tabs, or the narrow layout's tab bar and bottom sheet. The panels themselves
//! draw into whatever room they get; every column and sheet scrolls both ways, so no text
//! is cut off.

use crate::app::panels::Panel;
use crate::app::panels::ik;
use crate::app::panels::joints;
use crate::app::panels::layout::{Column, EDGE_TAB_WIDTH, Plan, Side};
use crate::app::panels::matrices;
use crate::app::panels::motion;
use crate::app::panels::robot;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::Model;
use crate::app::state::tr as t;
use armlab_session::settings::PanelKind;
use armlab_text::Key;

/// The four side panels.
pub struct SidePanels {
    /// The joint sliders.
    pub joints: joints::JointsPanel,
    /// Task, method, solve and replay.
    pub ik: ik::IkPanel,
    /// Presets, the DH editor, files.
    pub robot: robot::RobotPanel,
    /// The matrices and the Jacobian.
    pub matrices: matrices::MatricesPanel,
    /// The motion lab: controllers, time scale, plots.
    pub motion: motion::MotionPanel,
    /// A panel just opened from its edge tab: its column scrolls to it once drawn (below
    /// the others, it opened out of sight).
    pub reveal: Option<PanelKind>,
    /// The panels drawn this frame, in order, each with its first widget (its title row's
    /// close button): where the page's skip links lead.
    pub anchors: Vec<(PanelKind, egui::Id)>,
}

impl SidePanels {
    /// Draws one panel.
    pub fn ui(
        &mut self,
        kind: PanelKind,
        model: &mut Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
    ) {
        match kind {
            PanelKind::Joints => self.joints.ui(model, ui, points),
            PanelKind::Ik => self.ik.ui(model, ui, points),
            PanelKind::Matrices => self.matrices.ui(model, ui, points),
            PanelKind::Robot => self.robot.ui(model, ui, points),
            PanelKind::Motion => self.motion.ui(model, ui, points),
        }
    }

    /// The wide layout's columns; returns nothing, the central view takes what is left.
    pub fn wide(
        &mut self,
        plan: &Plan,
        model: &mut Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
    ) {
        self.anchors.clear();
        let mut used = 0.0;
        for (index, column) in plan.columns.iter().enumerate() {
            if let Some(opened) = edge_tabs(column, model, ui, points) {
                self.reveal = Some(opened);
            }
            if column.open.is_empty() {
                continue;
            }
            let max = plan.max_width_after(index, used);
            let id = match column.side {
                Side::Left => "armlab_left",
                Side::Right => "armlab_right",
            };
            // A column remembers the width it was dragged to, per mode, zoom and screen
            // width (to 50 points): a width kept from another zoom or screen (presentation
            // mode, a resized window, the page's first frame before its canvas had its
            // size) would not fit this one. The mode too: in the frame that turns
            // presentation off the zoom is still presentation's, and the two-column plan
            // squeezed the one presentation column, which kept that width when turned on.
            let salt = (
                id,
                model.settings().presentation,
                (ui.ctx().zoom_factor() * 100.0).round() as i32,
                (plan.width / 50.0).round() as i32,
            );
            let (panel, width_name) = match column.side {
                Side::Left => (egui::Panel::left(salt), Key::ColumnWidthLeft),
                Side::Right => (egui::Panel::right(salt), Key::ColumnWidthRight),
            };
            let edge = edge_id(ui, salt);
            step_edge_by_keys(ui.ctx(), edge);
            let response = panel
                .frame(panel_frame(ui.style()))
                .default_size(column.default_width.min(max))
                .size_range(column.min_width.min(max)..=max)
                .resizable(true)
                .show(ui, |ui| self.column_body(column, id, model, ui, points));
            name_and_mark_edge(ui, edge, t(model, width_name));
            used += response.response.rect.width();
        }
    }

    /// A wide layout's column: its open panels one under the other, scrolling both ways;
    /// a panel just opened from its edge tab is scrolled to.
    fn column_body(
        &mut self,
        column: &Column,
        id: &str,
        model: &mut Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
    ) {
        let width = visible_width(ui);
        egui::ScrollArea::both()
            .id_salt(id)
            .auto_shrink([false, false])
            .show(ui, |ui| {
                for (i, kind) in column.open.iter().enumerate() {
                    if i > 0 {
                        ui.separator();
                    }
                    if self.reveal == Some(*kind) {
                        ui.scroll_to_cursor(Some(egui::Align::TOP));
                        self.reveal = None;
                    }
                    let (closed, first) = section_header(*kind, model, ui);
                    self.anchors.push((*kind, first));
                    if closed {
                        model.set_panel_open(*kind, false);
                    }
                    ui.scope(|ui| {
                        wrap_at(ui, width);
                        self.ui(*kind, model, ui, points);
                    });
                }
            });
    }

    /// The narrow layout: a tab bar at the bottom and, when a tab is chosen, its panel as
    /// a sheet above the bar (the 3D view keeps the rest).
    pub fn narrow(
        &mut self,
        plan: &Plan,
        sheet: &mut Option<PanelKind>,
        model: &mut Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
    ) {
        self.anchors.clear();
        egui::Panel::bottom("armlab_tabs")
            .frame(panel_frame(ui.style()))
            .resizable(false)
            .show(ui, |ui| {
                // Five tabs share a phone's 390 points: narrow gaps keep "Matrices" (and
                // the Finnish "Matriisit") on one line.
                ui.spacing_mut().item_spacing.x = 2.0;
                ui.columns(PanelKind::ALL.len(), |cols| {
                    for (col, kind) in cols.iter_mut().zip(PanelKind::ALL) {
                        let open = *sheet == Some(kind);
                        let size = egui::vec2(col.available_width(), 40.0);
                        let response = col.add_sized(
                            size,
                            crate::app::widgets::style::choice(
                                open,
                                tab_label(col, t(model, tab_title(kind))),
                            ),
                        );
                        points.insert(format!("tab-{}", kind.id()), response.rect.center());
                        if response.clicked() {
                            *sheet = if open { None } else { Some(kind) };
                        }
                    }
                });
            });
        let Some(kind) = *sheet else {
            return;
        };
        egui::Panel::bottom("armlab_sheet")
            .frame(panel_frame(ui.style()))
            .exact_size(plan.sheet_height)
            .resizable(false)
            .show(ui, |ui| {
                let (closed, first) = section_header(kind, model, ui);
                self.anchors.push((kind, first));
                if closed {
                    *sheet = None;
                }
                let width = visible_width(ui);
                egui::ScrollArea::both()
                    .id_salt("armlab_sheet_scroll")
                    .auto_shrink([false, false])
                    .show(ui, |ui| {
                        wrap_at(ui, width);
                        self.ui(kind, model, ui, points);
                    });
            });
    }
}

/// The id of a side column's edge, egui's resize handle of the panel with `salt` in `ui`.
/// egui keeps the id to itself: this makes it as egui does (were egui to make it otherwise,
/// the edge would keep egui's name and no key: the UI tests that find it by its name fail).
fn edge_id(ui: &egui::Ui, salt: impl egui::AsIdSalt) -> egui::Id {
    ui.scope_id()
        .with_salt(egui::IdSalt::new(salt))
        .with("__resize")
}

/// Tab reaches a column's edge after the column's controls (egui's handle takes the
/// focus); there the arrow keys step the column's width, as a screen reader's Increment
/// and Decrement do: Right wider, Left narrower. Called before the panel is drawn, which
/// reads the steps.
fn step_edge_by_keys(ctx: &egui::Context, edge: egui::Id) {
    use egui::accesskit::{Action, ActionRequest, TreeId};
    // Left and Right are the edge's own, as a slider's: egui would otherwise move the focus
    // to the control beside it.
    let arrows = egui::EventFilter {
        horizontal_arrows: true,
        ..Default::default()
    };
    let focused = ctx.memory_mut(|m| {
        m.set_focus_lock_filter(edge, arrows);
        m.has_focus(edge)
    });
    if !focused {
        return;
    }
    let steps = [
        (egui::Key::ArrowRight, Action::Increment),
        (egui::Key::ArrowLeft, Action::Decrement),
    ];
    ctx.input_mut(|i| {
        for (key, action) in steps {
            while i.consume_key(egui::Modifiers::NONE, key) {
                i.events
                    .push(egui::Event::AccessKitActionRequest(ActionRequest {
                        action,
                        target_tree: TreeId::ROOT,
                        target_node: edge.accesskit_id(),
                        data: None,
                    }));
            }
        }
    });
}

/// Names a column's edge for screen readers (`name`, "Width of the left column" in the
/// interface's language) in place of the English "Resize panel" egui gives every handle,
/// and outlines it in the focus colour while it has the keyboard (egui marks it only under
/// the pointer).
fn name_and_mark_edge(ui: &egui::Ui, edge: egui::Id, name: &str) {
    ui.ctx()
        .accesskit_node_builder(edge, |node| node.set_label(name));
    if let Some(handle) = ui.ctx().read_response(edge)
        && handle.has_focus()
    {
        // Three points wide: the view drawn after the column covers the half of the handle
        // beyond the column's edge, so one line of the outline shows, along that edge.
        let colour = ui.visuals().selection.stroke.color;
        ui.painter().rect_stroke(
            handle.rect,
            2.0,
            egui::Stroke::new(3.0, colour),
            egui::StrokeKind::Inside,
        );
    }
}

/// egui's frame of a side or top panel, without its fill in the page: there the canvas is
/// cleared to the panels' colour every frame ([`panel_clear_color`]), so a fill would paint
/// each of the panels' pixels a second time, and with software WebGL every pixel is the
/// CPU's work. Natively the fill stays (the UI tests' renderer clears to transparent).
pub fn panel_frame(style: &egui::Style) -> egui::Frame {
    let frame = egui::Frame::side_top_panel(style);
    if cfg!(target_arch = "wasm32") {
        frame.fill(egui::Color32::TRANSPARENT)
    } else {
        frame
    }
}

/// The colour the window is cleared to before egui paints: the panels' own (the 3D view
/// covers the rest), so that a panel whose frame leaves out its fill ([`panel_frame`]) looks
/// as with it.
pub fn panel_clear_color(visuals: &egui::Visuals) -> [f32; 4] {
    visuals.panel_fill.to_normalized_gamma_f32()
}

/// A tab's title in the narrow bar, its text made smaller (down to three quarters) when
/// it would not fit its column on one line: with five tabs on a phone, "Matrices" wrapped
/// into "Matrice / s".
fn tab_label(ui: &egui::Ui, title: &str) -> egui::RichText {
    let font = egui::TextStyle::Button.resolve(ui.style());
    let room = ui.available_width() - 2.0 * ui.spacing().button_padding.x;
    let width = crate::app::widgets::style::text_width(ui, title, &font);
    let text = egui::RichText::new(title);
    if width > room && width > 0.0 {
        text.size(font.size * (room / width).max(0.75))
    } else {
        text
    }
}

/// The width a panel's content can be seen in: its room, but no wider than its clip
/// rectangle (egui keeps a panel's content as wide as it once grew and clips it to the
/// panel's maximum, so the room alone can be wider than what shows).
fn visible_width(ui: &egui::Ui) -> f32 {
    let margin = ui.max_rect().left() - ui.clip_rect().left();
    ui.available_width()
        .min(ui.clip_rect().right() - ui.cursor().left() - margin.max(0.0))
}

/// Inside a scroll area that scrolls sideways, text would never wrap: it wraps at the
/// column's width instead, and only what cannot wrap (a matrix, the DH table) scrolls.
/// Each panel gets its own scope, since egui widens a layout to fit anything wider: one
/// panel's matrix must not widen the next panel's text.
fn wrap_at(ui: &mut egui::Ui, width: f32) {
    ui.set_max_width((width - ui.spacing().scroll.bar_width).max(120.0));
}

/// A panel's title.
pub fn title(kind: PanelKind) -> Key {
    match kind {
        PanelKind::Joints => Key::PanelJoints,
        PanelKind::Ik => Key::PanelIk,
        PanelKind::Matrices => Key::PanelMatrices,
        PanelKind::Robot => Key::PanelRobot,
        PanelKind::Motion => Key::PanelMotion,
    }
}

/// A panel's short title, for the narrow layout's tab bar.
pub fn tab_title(kind: PanelKind) -> Key {
    match kind {
        PanelKind::Ik => Key::TabIk,
        other => title(other),
    }
}

/// A panel's title row with a close button; returns whether it was closed, and the
/// button's id.
fn section_header(kind: PanelKind, model: &Model, ui: &mut egui::Ui) -> (bool, egui::Id) {
    ui.horizontal(|ui| {
        let close = ui
            .small_button("×")
            .on_hover_text(t(model, Key::ClosePanel))
            .accessible_name(armlab_text::fill(
                model.settings().lang,
                Key::ClosePanelNamed,
                &[&t(model, title(kind))],
            ));
        ui.strong(t(model, title(kind)));
        (close.clicked(), close.id)
    })
    .inner
}

/// A column's strip of edge tabs: one vertical tab per panel, lit when open; a click
/// opens or closes that panel. Returns the panel it opened.
fn edge_tabs(
    column: &Column,
    model: &mut Model,
    ui: &mut egui::Ui,
    points: &mut ScreenPoints,
) -> Option<PanelKind> {
    let mut opened = None;
    let id = match column.side {
        Side::Left => "armlab_left_tabs",
        Side::Right => "armlab_right_tabs",
    };
    let panel = match column.side {
        Side::Left => egui::Panel::left(id),
        Side::Right => egui::Panel::right(id),
    };
    panel
        .exact_size(EDGE_TAB_WIDTH)
        .resizable(false)
        .frame(panel_frame(ui.style()).inner_margin(egui::Margin::symmetric(2, 6)))
        .show(ui, |ui| {
            ui.spacing_mut().item_spacing.y = 6.0;
            for kind in &column.tabs {
                let open = column.open.contains(kind);
                let response = edge_tab(ui, t(model, title(*kind)), open);
                points.insert(format!("tab-{}", kind.id()), response.rect.center());
                if response.clicked() {
                    model.set_panel_open(*kind, !open);
                    opened = (!open).then_some(*kind);
                }
            }
        });
    opened
}

/// One vertical tab: its label turned a quarter, reading upward.
fn edge_tab(ui: &mut egui::Ui, text: &str, open: bool) -> egui::Response {
    let font = egui::TextStyle::Button.resolve(ui.style());
    let color = ui.visuals().text_color();
    let galley = ui.painter().layout_no_wrap(text.to_owned(), font, color);
    let size = egui::vec2(EDGE_TAB_WIDTH - 4.0, galley.size().x + 18.0);
    let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click());
    let visuals = ui.style().interact_selectable(&response, open);
    // Outlined as a button is: the fill alone is too near the panel's to mark the tab.
    ui.painter().rect(
        rect,
        4.0,
        if open {
            visuals.bg_fill
        } else {
            visuals.weak_bg_fill
        },
        visuals.bg_stroke,
        egui::StrokeKind::Inside,
    );
    let at = egui::pos2(rect.center().x - galley.size().y / 2.0, rect.bottom() - 9.0);
    ui.painter().add(
        egui::epaint::TextShape::new(at, galley, visuals.text_color())
            .with_angle(-std::f32::consts::FRAC_PI_2),
    );
    response.widget_info(|| egui::WidgetInfo::selected(egui::Role::Button, true, open, text));
    response
}
