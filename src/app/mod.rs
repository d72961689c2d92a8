//! The eframe/egui application. One panel per file; the state lives in [`ArmLabApp`] and
//! every number comes from the core ([`crate::kinematics`]). Data flow per frame: panels
//! change `q`, the robot or the target → the core recomputes FK, the Jacobian and IK → the
//! viewport builds a [`crate::render::Scene`] and the panels show the matrices.

#[cfg(not(target_arch = "wasm32"))]
pub mod files;
pub mod hook;
pub mod ik_panel;
pub mod joints;
pub mod matrices;
pub mod robot_panel;
pub mod scene;
pub mod session;
pub mod style;
pub mod viewport;
#[cfg(target_arch = "wasm32")]
pub mod web;

use nalgebra::{IsometryMatrix3, Matrix6xX};

use crate::kinematics::{ForwardKinematics, Robot, ZyxEuler, geometric_jacobian_into};
use crate::render::SceneRenderer;
use crate::render::camera::OrbitCamera;
use session::{RobotSource, Session};

/// Display preferences.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Angles in degrees (true) or radians.
    pub degrees: bool,
    /// Draw the DH frames (x red, y green, z blue).
    pub show_frames: bool,
    /// Decimals in the matrices.
    pub precision: usize,
    /// Large fonts and high contrast for projectors.
    pub presentation: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            degrees: true,
            show_frames: true,
            precision: 3,
            presentation: false,
        }
    }
}

/// The state of the IK as the user last saw it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IkStatus {
    /// The tool is at the target (within tolerance).
    pub reached: bool,
    /// The last solve found the target out of reach.
    pub unreachable: bool,
    /// Position error (robot units).
    pub position_error: f64,
    /// Orientation error (radians) for the task's rows.
    pub orientation_error: f64,
    /// Iterations of the last solve.
    pub iterations: usize,
}

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

/// The whole app.
pub struct ArmLabApp {
    /// Robot, joints, target and IK mode: what a link carries.
    pub session: Session,
    /// Forward kinematics at `session.q`.
    pub fk: ForwardKinematics,
    /// Geometric Jacobian at `session.q`.
    pub jacobian: Matrix6xX<f64>,
    /// The IK target in the base frame.
    pub target: IsometryMatrix3<f64>,
    /// IK state shown by the marker colour and the IK panel.
    pub ik: IkStatus,
    /// The 3D camera.
    pub camera: OrbitCamera,
    /// Display preferences.
    pub settings: Settings,
    /// A sentence for the user (bad link, bad file), shown in the top bar until dismissed.
    pub message: Option<String>,
    /// The DH editor's cell texts and errors.
    pub editor: robot_panel::DhEditor,
    /// The joint (1-based link) whose frame and matrix are highlighted.
    pub hovered_link: Option<usize>,
    /// The viewport's interaction state.
    pub viewport: viewport::ViewportState,
    /// Main-thread time of recent frames, split into its parts.
    pub frame_ms: std::collections::VecDeque<FrameTime>,
    /// The parts of the frame being drawn, filled in as they run.
    pub timing: FrameTime,
    /// Frames drawn so far.
    pub frame: u64,
    /// The IK solver with its reusable workspaces.
    pub solver: crate::kinematics::ik::IkSolver,
    /// The last full solve, for replay.
    pub replay: ik_panel::Replay,
    /// The native file dialog, while it is open.
    #[cfg(not(target_arch = "wasm32"))]
    pub file_dialog: Option<files::FileDialog>,
    /// Where the native app keeps the last session (set by `main`; none in tests).
    #[cfg(not(target_arch = "wasm32"))]
    pub session_file: Option<std::path::PathBuf>,
    renderer: Option<SceneRenderer>,
}

impl ArmLabApp {
    /// Creates the app, opening the state of `hash` (a URL hash) when it is valid.
    pub fn new(cc: &eframe::CreationContext<'_>, hash: &str) -> Self {
        style::install_fonts(&cc.egui_ctx);
        style::install(&cc.egui_ctx, false);
        let renderer = cc.wgpu_render_state.as_ref().map(SceneRenderer::new);
        let mut app = ArmLabApp::with_session(Session::default_session());
        app.renderer = renderer;
        app.open_hash(hash);
        app
    }

    /// An app without a renderer (for headless tests of the logic).
    pub fn with_session(session: Session) -> Self {
        let mut app = ArmLabApp {
            fk: ForwardKinematics::default(),
            jacobian: Matrix6xX::zeros(session.robot.dof()),
            target: IsometryMatrix3::identity(),
            ik: IkStatus::default(),
            camera: OrbitCamera::default(),
            settings: Settings::default(),
            message: None,
            editor: robot_panel::DhEditor::default(),
            hovered_link: None,
            viewport: viewport::ViewportState::default(),
            frame_ms: std::collections::VecDeque::new(),
            timing: FrameTime::default(),
            frame: 0,
            solver: crate::kinematics::ik::IkSolver::new(),
            replay: ik_panel::Replay::default(),
            #[cfg(not(target_arch = "wasm32"))]
            file_dialog: None,
            #[cfg(not(target_arch = "wasm32"))]
            session_file: None,
            renderer: None,
            session,
        };
        app.load_session(app.session.clone());
        app
    }

    /// Opens a URL hash; on garbage, shows the reason and keeps (or falls back to) the
    /// default robot. An empty hash changes nothing.
    pub fn open_hash(&mut self, hash: &str) {
        match Session::from_hash(hash) {
            Ok(Some(session)) => self.load_session(session),
            Ok(None) => {}
            Err(reason) => {
                self.load_session(Session::default_session());
                self.message = Some(format!(
                    "This link could not be opened ({reason}); showing the default robot instead."
                ));
            }
        }
    }

    /// Replaces the whole state.
    pub fn load_session(&mut self, session: Session) {
        self.session = session;
        self.editor = robot_panel::DhEditor::from_robot(&self.session.robot);
        self.refresh();
        self.target = match self.session.target {
            Some(t) => target_from_array(&t),
            None => self.fk.base_from_tool,
        };
        self.ik = IkStatus::default();
        self.update_reached();
        self.fit_camera();
    }

    /// Swaps in a new robot (a preset or an edited table), keeping what can be kept.
    pub fn set_robot(&mut self, robot: Robot, source: RobotSource) {
        let same_shape = robot.dof() == self.session.robot.dof();
        let q = if same_shape {
            let mut q = self.session.q.clone();
            let current = q.clone();
            robot.keep_q(&mut q, &current);
            q
        } else {
            robot.home()
        };
        let reframe = robot.reach() / self.session.robot.reach();
        self.session.robot = robot;
        self.session.source = source;
        self.session.q = q;
        self.refresh();
        if !same_shape || !(0.5..2.0).contains(&reframe) {
            self.snap_target();
            self.fit_camera();
        }
        self.update_reached();
    }

    /// Sets the joint vector (kept as SPEC §2 says) and recomputes FK and the Jacobian.
    pub fn set_q(&mut self, mut q: Vec<f64>) {
        q.resize(self.session.robot.dof(), 0.0);
        let current = self.session.q.clone();
        self.session.robot.keep_q(&mut q, &current);
        self.session.q = q;
        self.refresh();
        self.update_reached();
    }

    /// Sets the joint vector as typed or slid: each value clamped to its joint's limits,
    /// not re-mapped to another turn (a slider at 216° stays at 216°).
    pub fn set_q_exact(&mut self, mut q: Vec<f64>) {
        q.resize(self.session.robot.dof(), 0.0);
        for (v, joint) in q.iter_mut().zip(&self.session.robot.joints) {
            *v = joint.limits.clamp(*v);
        }
        self.session.q = q;
        self.refresh();
        self.update_reached();
    }

    /// Recomputes forward kinematics and the Jacobian at the current q.
    pub fn refresh(&mut self) {
        self.fk.update(&self.session.robot, &self.session.q);
        geometric_jacobian_into(&self.fk, &mut self.jacobian);
    }

    /// Moves the target onto the gripper.
    pub fn snap_target(&mut self) {
        self.target = self.fk.base_from_tool;
        self.session.target = Some(target_to_array(&self.target));
        self.ik = IkStatus::default();
        self.update_reached();
    }

    /// Sets the target pose (from a drag or a typed value).
    pub fn set_target(&mut self, target: IsometryMatrix3<f64>) {
        self.target = target;
        self.session.target = Some(target_to_array(&target));
    }

    /// Recomputes whether the tool is at the target for the current task.
    pub fn update_reached(&mut self) {
        let (pos, rot) = ik_panel::task_errors(
            &self.session.robot,
            &self.session.q,
            &self.target,
            self.session.task,
        );
        self.ik.position_error = pos;
        self.ik.orientation_error = rot;
        let tol = ik_panel::position_tolerance(&self.session.robot);
        self.ik.reached = pos <= tol && rot <= ik_panel::ORIENTATION_TOLERANCE;
        if self.ik.reached {
            self.ik.unreachable = false;
        }
    }

    /// Frames the robot in the viewport.
    pub fn fit_camera(&mut self) {
        let reach = self.session.robot.reach();
        let base = self.session.robot.world_from_base.translation.vector;
        let centre = nalgebra::Point3::from(base + nalgebra::Vector3::new(0.0, 0.0, reach * 0.35));
        self.camera.fit(centre, reach * 0.85);
    }

    /// The state the browser tests read (`window.armlab.state()`), as JSON.
    pub fn state_json(&self) -> String {
        hook::state_json(self)
    }

    /// The current link hash (without `#`).
    pub fn hash(&self) -> String {
        let mut s = self.session.clone();
        s.target = Some(target_to_array(&self.target));
        s.to_hash()
    }

    /// Takes the app's own time for a frame.
    fn record_frame_time(&mut self, total_ms: f64) {
        if self.frame_ms.len() >= 600 {
            self.frame_ms.pop_front();
        }
        let mut t = std::mem::take(&mut self.timing);
        t.app_ms = total_ms - t.render_ms;
        self.frame_ms.push_back(t);
    }

    /// Draws the whole UI: top bar, joint and IK panel, matrices, viewport.
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        render_state: Option<&eframe::egui_wgpu::RenderState>,
    ) {
        let start = hook::now_ms();
        self.frame += 1;
        self.viewport.points.clear();
        style::install(ui.ctx(), self.settings.presentation);
        egui::Panel::top("armlab_top").show(ui, |ui| self.top_bar(ui));
        egui::Panel::left("armlab_left")
            .default_size(330.0)
            .resizable(true)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    joints::show(self, ui);
                    ui.separator();
                    ik_panel::show(self, ui);
                    ui.separator();
                    robot_panel::show(self, ui);
                });
            });
        egui::Panel::right("armlab_right")
            .default_size(460.0)
            .resizable(true)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| matrices::show(self, ui));
            });
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE.fill(style::background(self.settings.presentation)))
            .show(ui, |ui| {
                // Lent to the viewport for the frame (it also borrows the app).
                let mut renderer = self.renderer.take();
                viewport::show(self, ui, render_state, renderer.as_mut());
                self.renderer = renderer;
            });
        #[cfg(not(target_arch = "wasm32"))]
        robot_panel::show_file_dialog(self, ui.ctx());
        // Last, once every text of the frame has its glyphs in the font atlas.
        matrices::finish_numbers(ui.ctx());
        #[cfg(target_arch = "wasm32")]
        {
            web::store_hash(self, ui.ctx());
            web::publish(self, ui.ctx());
        }
        self.record_frame_time(hook::now_ms() - start);
    }

    fn top_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            ui.heading("ArmLab");
            ui.label(egui::RichText::new(&self.session.robot.name).strong());
            ui.separator();
            ui.toggle_value(&mut self.settings.degrees, "Degrees")
                .on_hover_text("Show angles in degrees (off: radians)");
            ui.toggle_value(&mut self.settings.show_frames, "DH frames")
                .on_hover_text("Draw every DH frame: x red, y green, z blue");
            ui.toggle_value(&mut self.settings.presentation, "Presentation")
                .on_hover_text("Large fonts and high contrast for a projector");
            ui.separator();
            if ui.button("Fit").on_hover_text("Frame the robot").clicked() {
                self.fit_camera();
            }
            use crate::render::camera::StandardView;
            for (label, view) in [
                ("Top", StandardView::Top),
                ("Front", StandardView::Front),
                ("Side", StandardView::Side),
                ("3D", StandardView::Iso),
            ] {
                if ui.button(label).clicked() {
                    self.camera.set_view(view);
                }
            }
            ui.separator();
            if ui
                .button("Copy link")
                .on_hover_text("A link that opens this robot, pose and target")
                .clicked()
            {
                let link = hook::share_link(&self.hash());
                ui.ctx().copy_text(link);
            }
        });
        if let Some(message) = self.message.clone() {
            ui.horizontal(|ui| {
                ui.colored_label(style::ERROR, format!("⚠ {message}"));
                if ui.small_button("Dismiss").clicked() {
                    self.message = None;
                }
            });
        }
    }
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
                .and_then(|()| std::fs::write(path, self.hash()));
            if let Err(e) = written {
                log::warn!("could not keep the session in {}: {e}", path.display());
            }
        }
    }

    fn clear_color(&self, _visuals: &egui::Visuals) -> [f32; 4] {
        // Opaque: eframe's default is translucent, which lets the page show through.
        style::background(self.settings.presentation).to_normalized_gamma_f32()
    }

    #[cfg(target_arch = "wasm32")]
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(&mut *self)
    }
}

/// A target pose from `[x, y, z, α, β, γ]` (Z-Y-X Euler angles, radians).
pub fn target_from_array(t: &[f64; 6]) -> IsometryMatrix3<f64> {
    let r = ZyxEuler {
        alpha: t[3],
        beta: t[4],
        gamma: t[5],
        degenerate: false,
    }
    .to_rotation();
    IsometryMatrix3::from_parts(
        nalgebra::Translation3::new(t[0], t[1], t[2]),
        nalgebra::Rotation3::from_matrix_unchecked(r),
    )
}

/// `[x, y, z, α, β, γ]` of a pose.
pub fn target_to_array(pose: &IsometryMatrix3<f64>) -> [f64; 6] {
    let e = ZyxEuler::from_rotation(pose.rotation.matrix());
    let p = pose.translation.vector;
    [p.x, p.y, p.z, e.alpha, e.beta, e.gamma]
}
