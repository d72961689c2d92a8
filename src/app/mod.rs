//! The eframe/egui application.
//!
//! - [`model::Model`] holds the session (robot, q, target, task, method), the display
//!   settings and what is derived from them; its methods are the only writers.
//! - Each panel is a type that owns its own state and has one `ui` method that reads the
//!   model and calls its methods: [`top_bar`], [`joints::JointsPanel`],
//!   [`ik_panel::IkPanel`], [`robot_panel::RobotPanel`], [`matrices::MatricesPanel`] and
//!   the 3D [`viewport::Viewport`]. Panels never write each other's state; the
//!   highlighted link is a value in the model.
//! - Screen points for the test hook go to one registry, [`hook::ScreenPoints`].
//!
//! Data flow per frame: panels ask the model for changes → the model recomputes FK, the
//! Jacobian and the IK status → the viewport builds a [`crate::render::Scene`] from the
//! model's frames and the renderer draws it.
#![deny(clippy::too_many_lines)]

#[cfg(not(target_arch = "wasm32"))]
pub mod files;
pub mod format;
pub mod hook;
pub mod ik_panel;
pub mod joints;
pub mod matrices;
pub mod model;
pub mod robot_panel;
pub mod scene;
pub mod session;
pub mod style;
pub mod top_bar;
pub mod viewport;
#[cfg(target_arch = "wasm32")]
pub mod web;

use hook::ScreenPoints;
use model::{Message, Model};
use session::Session;

/// Main-thread milliseconds of one frame of the app, in parts.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrameTime {
    /// The app's own work: egui layout of every panel, scene preparation and IK; all of
    /// the frame except `render_ms`.
    pub app_ms: f64,
    /// Of `app_ms`: the IK step of a drag.
    pub ik_ms: f64,
    /// Of `app_ms`: building the scene (instances, lines, camera).
    pub scene_ms: f64,
    /// Encoding and submitting the 3D view's draw calls to wgpu (GPU work issued from the
    /// main thread: on WebGL2 these are the GL calls).
    pub render_ms: f64,
}

/// How many recent frames' times are kept.
const RECENT_FRAMES: usize = 600;

/// The whole app: the model, the panels, and the frame's bookkeeping.
pub struct ArmLabApp {
    model: Model,
    joints: joints::JointsPanel,
    ik_panel: ik_panel::IkPanel,
    robot_panel: robot_panel::RobotPanel,
    matrices: matrices::MatricesPanel,
    viewport: viewport::Viewport,
    points: ScreenPoints,
    /// The parts of the frame being drawn, filled in as they run.
    timing: FrameTime,
    frame_ms: std::collections::VecDeque<FrameTime>,
    frame: u64,
    /// Where the native app keeps the last session (set by `main`; none in tests).
    #[cfg(not(target_arch = "wasm32"))]
    session_file: Option<std::path::PathBuf>,
}

impl ArmLabApp {
    /// Creates the app, opening the state of `hash` (a URL hash) when it is valid.
    pub fn new(cc: &eframe::CreationContext<'_>, hash: &str) -> Self {
        style::install_fonts(&cc.egui_ctx);
        style::install(&cc.egui_ctx, false);
        let mut app = ArmLabApp::with_session(Session::default_session());
        app.viewport = viewport::Viewport::new(cc.wgpu_render_state.as_ref());
        app.open_hash(hash);
        app
    }

    /// An app without a renderer (for headless tests of the logic).
    pub fn with_session(session: Session) -> Self {
        let model = Model::new(session);
        ArmLabApp {
            robot_panel: robot_panel::RobotPanel::new(model.robot()),
            model,
            joints: joints::JointsPanel,
            ik_panel: ik_panel::IkPanel::default(),
            matrices: matrices::MatricesPanel::default(),
            viewport: viewport::Viewport::new(None),
            points: ScreenPoints::default(),
            timing: FrameTime::default(),
            frame_ms: std::collections::VecDeque::new(),
            frame: 0,
            #[cfg(not(target_arch = "wasm32"))]
            session_file: None,
        }
    }

    /// Opens a URL hash; on garbage, shows the reason and falls back to the default
    /// robot. An empty hash changes nothing.
    pub fn open_hash(&mut self, hash: &str) {
        match Session::from_hash(hash) {
            Ok(Some(session)) => self.model.open(session),
            Ok(None) => {}
            Err(reason) => {
                self.model.open(Session::default_session());
                self.model.set_message(Message::warning(format!(
                    "This link could not be opened ({reason}); showing the default robot instead."
                )));
            }
        }
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
    pub fn viewport(&self) -> &viewport::Viewport {
        &self.viewport
    }

    /// The robot panel (its DH editor and file dialog).
    pub fn robot_panel(&self) -> &robot_panel::RobotPanel {
        &self.robot_panel
    }

    /// The robot panel, to open its file dialog (tests).
    pub fn robot_panel_mut(&mut self) -> &mut robot_panel::RobotPanel {
        &mut self.robot_panel
    }

    /// The IK panel (its replay).
    pub fn ik_panel(&self) -> &ik_panel::IkPanel {
        &self.ik_panel
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

    /// Draws the whole UI: top bar, joint, IK and robot panel, matrices, viewport.
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        render_state: Option<&eframe::egui_wgpu::RenderState>,
    ) {
        let start = hook::now_ms();
        self.frame += 1;
        self.points.clear();
        style::install(ui.ctx(), self.model.settings().presentation);
        egui::Panel::top("armlab_top").show(ui, |ui| {
            if let Some(action) = top_bar::ui(&mut self.model, ui) {
                self.viewport.apply(action, ui.ctx());
            }
        });
        egui::Panel::left("armlab_left")
            .default_size(330.0)
            .resizable(true)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    self.joints.ui(&mut self.model, ui, &mut self.points);
                    ui.separator();
                    self.ik_panel.ui(&mut self.model, ui, &mut self.points);
                    ui.separator();
                    self.robot_panel.ui(&mut self.model, ui, &mut self.points);
                });
            });
        egui::Panel::right("armlab_right")
            .default_size(460.0)
            .resizable(true)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    self.matrices.ui(&mut self.model, ui, &mut self.points);
                });
            });
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE.fill(style::background(self.model.settings().presentation)))
            .show(ui, |ui| {
                self.viewport.ui(
                    &mut self.model,
                    ui,
                    &mut self.points,
                    render_state,
                    &mut self.timing,
                );
            });
        #[cfg(not(target_arch = "wasm32"))]
        self.robot_panel.show_file_dialog(&mut self.model, ui.ctx());
        // Last, once every text of the frame has its glyphs in the font atlas.
        matrices::finish_numbers(ui.ctx());
        #[cfg(target_arch = "wasm32")]
        {
            web::store_hash(self, ui.ctx());
            web::publish(self, ui.ctx());
        }
        self.record_frame_time(hook::now_ms() - start);
    }
}

/// A side panel: a type that owns its own state and draws itself from the model, asking
/// the model's methods for every change.
pub trait Panel {
    /// Draws the panel; named points go to `points` for the test hook.
    fn ui(&mut self, model: &mut Model, ui: &mut egui::Ui, points: &mut ScreenPoints);
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
            let written = path
                .parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .and_then(|()| std::fs::write(path, self.model.hash()));
            if let Err(e) = written {
                log::warn!("could not keep the session in {}: {e}", path.display());
            }
        }
    }

    fn clear_color(&self, _visuals: &egui::Visuals) -> [f32; 4] {
        // Opaque: eframe's default is translucent, which lets the page show through.
        style::background(self.model.settings().presentation).to_normalized_gamma_f32()
    }

    #[cfg(target_arch = "wasm32")]
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(&mut *self)
    }
}
