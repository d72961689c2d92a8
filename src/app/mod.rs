//! The eframe/egui application, grouped by role:
//!
//! - [`state`]: the model (the session and what is derived from it) and one sub-model per
//!   lab; its methods are the only writers. No egui.
//! - [`panels`]: one type per panel with one `ui` method that reads the model and asks it
//!   for changes, the folds each holds, and the layout that places them. Panels never
//!   write each other's state; the highlighted link is a value in the model.
//! - [`widgets`]: the controls and style the panels share (the DH table editor, number
//!   fields' drafts, plots, colours and text sizes).
//! - [`view3d`]: the 3D view: camera and input, the target marker, overlays, and the
//!   scene built from the model's frames.
//! - [`platform`]: the web and the native side: the clock, the address bar and storage,
//!   downloads and uploads, the lazily loaded modules. It knows no app.
//! - `page` (in the page only): the app started on the canvas, its link and session kept
//!   each frame, and its state published for `window.armlab`.
//! - [`hook`] and [`screen_points`]: what the browser and UI tests read.
//!
//! Data flow per frame: panels ask the model for changes → the model recomputes FK, the
//! Jacobian and the IK status → the 3D view builds a [`crate::render::Scene`] from the
//! model's frames and the renderer draws it.
#![deny(clippy::too_many_lines)]

pub mod hook;
#[cfg(target_arch = "wasm32")]
pub mod page;
pub mod panels;
pub mod platform;
pub mod room;
pub mod screen_points;
pub mod state;
pub mod view3d;
pub mod widgets;

use armlab_session::session::Session;
use armlab_session::settings::PanelKind;
use panels::{class, ik, joints, layout, matrices, motion, robot, shell, top_bar};
use platform::clock;
use platform::clock::FrameTime;
use screen_points::ScreenPoints;
use state::classroom::{ClassLink, Classroom, split_class_link};
use state::model::{Message, Model};
use state::trf;
use widgets::style;

use armlab_text::Key;

/// What the device says before any link is read: the browser's language, whether its
/// main pointer is a finger and whether it asks for reduced motion.
#[derive(Debug, Clone, Copy, Default)]
pub struct Preferences {
    /// The first of the browser's languages that ArmLab has (English when none).
    pub lang: armlab_text::Lang,
    /// A touch screen: thumb-sized controls.
    pub touch: bool,
    /// The system asks for reduced motion: egui's animations off.
    pub reduced_motion: bool,
}

/// Whether egui dithers its colours (eframe's `dithering`, in the page and the desktop app).
/// Off: the 3D view's picture and the theme are 8-bit colours, which dithering leaves as
/// they are; on an anti-aliased edge it moves a pixel by one level at most, while its
/// noise cost about a fifth of a frame's CPU on a software renderer. The UI tests'
/// renderer never dithers either.
pub const DITHERING: bool = false;

/// The first character of a session stored as JSON (an object), written as an escape.
const JSON_OBJECT: char = '\u{7b}';

/// How many recent frames' times are kept.
const RECENT_FRAMES: usize = 600;

/// The whole app: the model, the panels, and the frame's bookkeeping.
pub struct ArmLabApp {
    model: Model,
    panels: shell::SidePanels,
    /// The narrow layout's open sheet.
    sheet: Option<PanelKind>,
    /// Touch screen: larger hit areas (from the browser's pointer, or the first touch).
    touch: bool,
    viewport: view3d::Viewport,
    points: ScreenPoints,
    /// The parts of the frame being drawn, filled in as they run.
    timing: FrameTime,
    frame_ms: std::collections::VecDeque<FrameTime>,
    frame: u64,
    /// The lecture room as this page takes part in it.
    classroom: Classroom,
    /// The lecture room's bar and windows.
    class_panel: class::ClassPanel,
    /// A link's `class=` part waiting for the page to handle it.
    class_link: Option<ClassLink>,
    /// Where the native app keeps the last session (set by `main`; none in tests).
    #[cfg(not(target_arch = "wasm32"))]
    session_file: Option<std::path::PathBuf>,
}

impl ArmLabApp {
    /// Creates the app, opening the state of `hash` (a URL hash) when it is valid.
    pub fn new(cc: &eframe::CreationContext<'_>, hash: &str) -> Self {
        ArmLabApp::new_with(cc, hash, None, Preferences::default())
    }

    /// Creates the app with the device's preferences; a link's own settings (its
    /// language) win over them.
    pub fn new_with(
        cc: &eframe::CreationContext<'_>,
        link: &str,
        stored: Option<&str>,
        preferences: Preferences,
    ) -> Self {
        style::install_fonts(&cc.egui_ctx);
        style::install(
            &cc.egui_ctx,
            false,
            preferences.touch,
            style::Screen::of(&cc.egui_ctx),
        );
        let mut app = ArmLabApp::with_session(Session::default_session());
        app.viewport = view3d::Viewport::new(cc.wgpu_render_state.as_ref());
        app.touch = preferences.touch;
        app.model.set_lang(preferences.lang);
        app.model.set_reduced_motion(preferences.reduced_motion);
        // A link with only a class part (`#class=…`) opens the last session in the class.
        let (class, link) = split_class_link(link);
        app.class_link = class;
        if link.is_empty() {
            app.open_stored(stored.unwrap_or_default());
        } else {
            app.open_hash(&link);
        }
        app
    }

    /// An app without a renderer (for headless tests of the logic).
    pub fn with_session(session: Session) -> Self {
        let model = Model::new(session);
        ArmLabApp {
            panels: shell::SidePanels {
                robot: robot::RobotPanel::new(model.robot()),
                joints: joints::JointsPanel::default(),
                ik: ik::IkPanel::default(),
                matrices: matrices::MatricesPanel::default(),
                motion: motion::MotionPanel::default(),
                reveal: None,
                anchors: Vec::new(),
            },
            model,
            sheet: None,
            touch: false,
            viewport: view3d::Viewport::new(None),
            points: ScreenPoints::default(),
            timing: FrameTime::default(),
            frame_ms: std::collections::VecDeque::new(),
            frame: 0,
            classroom: Classroom::default(),
            class_panel: class::ClassPanel::default(),
            class_link: None,
            #[cfg(not(target_arch = "wasm32"))]
            session_file: None,
        }
    }

    /// Opens a URL hash; on garbage, shows the reason and falls back to the default
    /// robot. An empty hash changes nothing. The reason reads in the language the link
    /// names (`lang=`), when it names one the app has. A `class=` part waits for the page
    /// ([`ArmLabApp::take_class_link`]); the rest opens.
    pub fn open_hash(&mut self, hash: &str) {
        let (class, rest) = split_class_link(hash);
        if class.is_some() {
            self.class_link = class;
        }
        let hash = rest.as_str();
        match Session::from_hash(hash) {
            Ok(Some(session)) => self.model.open(session),
            Ok(None) => {}
            Err(reason) => {
                self.model.open(Session::default_session());
                let asked = hash
                    .trim()
                    .trim_start_matches('#')
                    .split('&')
                    .find_map(|part| part.strip_prefix("lang="))
                    .and_then(armlab_text::Lang::from_id);
                if let Some(lang) = asked {
                    self.model.set_lang(lang);
                }
                let reason = reason.sentence(self.model.settings().lang);
                let text = trf(&self.model, Key::LinkNotOpened, &[&reason]);
                self.model.set_message(Message::warning(text));
            }
        }
    }

    /// Opens the last session as it was stored (its JSON; a session stored as its link
    /// hash opens as that link). On garbage, says so and shows the default robot; an
    /// empty store changes nothing.
    pub fn open_stored(&mut self, text: &str) {
        let text = text.trim();
        if !text.starts_with(JSON_OBJECT) {
            return self.open_hash(text);
        }
        match Session::from_json(text) {
            Ok(session) => self.model.open(session),
            Err(reason) => {
                self.model.open(Session::default_session());
                let reason = reason.sentence(self.model.settings().lang);
                let text = trf(&self.model, Key::StoredNotOpened, &[&reason]);
                self.model.set_message(Message::warning(text));
            }
        }
    }

    /// The session as it is stored (localStorage, the native session file): JSON.
    pub fn stored_session(&self) -> String {
        self.model.session().to_json()
    }

    /// The model: the session and what is derived from it.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The model, to change it as a panel would (tests, the page's hooks).
    pub fn model_mut(&mut self) -> &mut Model {
        &mut self.model
    }

    /// The 3D view.
    pub fn viewport(&self) -> &view3d::Viewport {
        &self.viewport
    }

    /// The 3D view, to change (tests).
    pub fn viewport_mut(&mut self) -> &mut view3d::Viewport {
        &mut self.viewport
    }

    /// The robot panel (its DH editor and file dialog).
    pub fn robot_panel(&self) -> &robot::RobotPanel {
        &self.panels.robot
    }

    /// The robot panel, to open its file dialog (tests).
    pub fn robot_panel_mut(&mut self) -> &mut robot::RobotPanel {
        &mut self.panels.robot
    }

    /// The IK panel (its replay).
    pub fn ik_panel(&self) -> &ik::IkPanel {
        &self.panels.ik
    }

    /// The narrow layout's open sheet, if any.
    pub fn sheet(&self) -> Option<PanelKind> {
        self.sheet
    }

    /// Opens (or closes, with `None`) the narrow layout's sheet.
    pub fn set_sheet(&mut self, sheet: Option<PanelKind>) {
        self.sheet = sheet;
    }

    /// Whether the UI is sized for touch (hit areas at least 40 px tall).
    pub fn touch(&self) -> bool {
        self.touch
    }

    /// Sizes the UI for touch (the page sets it for a coarse pointer; the first touch
    /// sets it too).
    pub fn set_touch(&mut self, touch: bool) {
        self.touch = touch;
    }

    /// The named screen points drawn last frame.
    pub fn points(&self) -> &ScreenPoints {
        &self.points
    }

    /// Frames drawn so far.
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// Main-thread times of recent frames, oldest first.
    pub fn frame_times(&self) -> &std::collections::VecDeque<FrameTime> {
        &self.frame_ms
    }

    /// The lecture room as this page takes part in it.
    pub fn classroom(&self) -> &Classroom {
        &self.classroom
    }

    /// The lecture room, to feed it what the server said (the page, tests).
    pub fn classroom_mut(&mut self) -> &mut Classroom {
        &mut self.classroom
    }

    /// A link's `class=` part the page has not handled yet.
    pub fn take_class_link(&mut self) -> Option<ClassLink> {
        self.class_link.take()
    }

    /// Where the native app keeps the last session when it closes.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn set_session_file(&mut self, path: Option<std::path::PathBuf>) {
        self.session_file = path;
    }

    /// The state the browser tests read (`window.armlab.state()`), as JSON.
    pub fn state_json(&self) -> String {
        hook::state_json(self)
    }

    /// The current link hash (without `#`).
    pub fn hash(&self) -> String {
        self.model.hash()
    }

    /// Takes the app's own time for a frame.
    fn record_frame_time(&mut self, total_ms: f64) {
        if self.frame_ms.len() >= RECENT_FRAMES {
            self.frame_ms.pop_front();
        }
        let mut t = std::mem::take(&mut self.timing);
        t.app_ms = total_ms - t.render_ms;
        self.frame_ms.push_back(t);
    }

    /// Draws the whole UI for the screen: the top bar, the side panels as the layout
    /// plan places them (columns when wide, a bottom sheet when narrow), and the 3D view
    /// in the room left.
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        render_state: Option<&eframe::egui_wgpu::RenderState>,
    ) {
        let start = clock::now_ms();
        self.frame += 1;
        self.points.clear();
        let ctx = ui.ctx().clone();
        self.touch |= ctx.input(|i| i.any_touches());
        self.room_frame(&ctx);
        let screen = screen(&ctx);
        style::install(&ctx, self.model.settings().presentation, self.touch, screen);
        style::reduce_motion(&ctx, self.model.reduced_motion());
        let plan = layout::plan(
            ui.max_rect().size(),
            screen.css_width,
            self.model.settings(),
        );
        let narrow = plan.mode == layout::Mode::Narrow;
        if let Some(action) = self.shortcuts(&ctx, narrow) {
            self.viewport.apply(action, &ctx);
        }
        egui::Panel::top("armlab_top")
            .frame(shell::panel_frame(ui.style()))
            .show(ui, |ui| {
                let pans = self.viewport.drag_pans();
                let bar = top_bar::ui(&mut self.model, ui, narrow, pans, &mut self.points);
                if let Some(action) = bar {
                    self.viewport.apply(action, ui.ctx());
                }
                self.class_panel
                    .bar(&mut self.classroom, &mut self.model, ui, &mut self.points);
            });
        match plan.mode {
            layout::Mode::Wide => {
                self.panels
                    .wide(&plan, &mut self.model, ui, &mut self.points);
            }
            layout::Mode::Narrow => self.panels.narrow(
                &plan,
                &mut self.sheet,
                &mut self.model,
                ui,
                &mut self.points,
            ),
        }
        // No fill: the 3D view's picture covers the whole panel (and without a renderer the
        // view fills it itself). A fill under it would be a screen of pixels drawn for
        // nothing in every frame: about a fifth of the page's drawing with software WebGL.
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| {
                self.viewport.ui(
                    &mut self.model,
                    ui,
                    &mut self.points,
                    render_state,
                    &mut self.timing,
                );
            });
        self.class_panel
            .windows(&mut self.classroom, &mut self.model, &ctx, &mut self.points);
        #[cfg(not(target_arch = "wasm32"))]
        self.panels.robot.show_file_dialog(&mut self.model, &ctx);
        // Last, once every text of the frame has its glyphs in the font atlas.
        widgets::numbers::finish_numbers(&ctx);
        #[cfg(target_arch = "wasm32")]
        page::store_hash(self, &ctx);
        self.record_frame_time(clock::now_ms() - start);
        // The browser tests' hook, outside the frame's own time (`FrameTime::hook_ms`).
        #[cfg(target_arch = "wasm32")]
        page::publish(self, &ctx);
    }

    /// The keyboard shortcuts (none while a text field has the keyboard): F frames the
    /// arm, P toggles presentation mode, 1–9 focus joint N's slider (the arrow keys then
    /// move it), Escape closes the narrow layout's sheet.
    fn shortcuts(&mut self, ctx: &egui::Context, narrow: bool) -> Option<view3d::ViewAction> {
        if ctx.text_edit_focused() {
            return None;
        }
        let pressed = |key| ctx.input_mut(|i| i.consume_key(egui::Modifiers::NONE, key));
        if pressed(egui::Key::P) {
            let on = self.model.settings().presentation;
            self.model.set_presentation(!on);
        }
        if pressed(egui::Key::Escape) {
            self.sheet = None;
        }
        const DIGITS: [egui::Key; 9] = [
            egui::Key::Num1,
            egui::Key::Num2,
            egui::Key::Num3,
            egui::Key::Num4,
            egui::Key::Num5,
            egui::Key::Num6,
            egui::Key::Num7,
            egui::Key::Num8,
            egui::Key::Num9,
        ];
        for (i, key) in DIGITS.into_iter().enumerate() {
            if i < self.model.robot().dof() && pressed(key) {
                if narrow {
                    self.sheet = Some(PanelKind::Joints);
                } else {
                    self.model.set_panel_open(PanelKind::Joints, true);
                }
                self.panels.joints.focus(i, ctx);
            }
        }
        pressed(egui::Key::F).then_some(view3d::ViewAction::Fit)
    }
}

/// The window's width in CSS pixels.
fn screen(ctx: &egui::Context) -> style::Screen {
    #[cfg(target_arch = "wasm32")]
    if let Some(css_width) = platform::web::measure_canvas(ctx) {
        return style::Screen { css_width };
    }
    style::Screen::of(ctx)
}

impl eframe::App for ArmLabApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let render_state = frame.wgpu_render_state().cloned();
        self.show(ui, render_state.as_ref());
    }

    #[cfg(not(target_arch = "wasm32"))]
    fn on_exit(&mut self) {
        // The native app's session persistence (the page uses localStorage).
        if let Some(path) = &self.session_file {
            platform::native::keep_session(path, &self.stored_session());
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        // Opaque: eframe's default is translucent, which lets the page show through.
        shell::panel_clear_color(visuals)
    }

    #[cfg(target_arch = "wasm32")]
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(&mut *self)
    }
}
