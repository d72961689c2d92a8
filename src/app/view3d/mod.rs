//! The 3D viewport: orbit (left drag), pan (right or middle drag, or shift + left), zoom
//! (wheel, pinch); the target marker is dragged in the view plane by its ball, along an
//! axis by its arrow, and turned by its rings (5D and full-pose tasks). Every frame of a
//! drag asks the model for an IK step warm-started at the current q.
//!
//! The viewport owns its interaction state, the camera and the renderer. A frame runs in
//! named steps: input (camera and marker drags; the marker geometry is the pure
//! [`marker`] module), the IK step, the scene, the overlay text, and the test points.

pub mod convention;
pub mod exercise;
mod frame_labels;
mod ghosts;
pub mod jacobian;
pub mod keys;
pub mod labels;
pub mod marker;
mod motion;
mod over_frames;
pub mod overlay;
pub mod paths;
pub mod predictions;
pub mod scene;
pub mod workspace;

use eframe::egui_wgpu::RenderState;
use egui::emath::GuiRounding;
use egui::{Color32, Pos2, Rect, Sense};
use nalgebra::{Point3, Vector3};

use crate::render::camera::{OrbitCamera, StandardView};
use crate::render::{Scene, SceneRenderer};
use armlab_core::Task;

use crate::app::platform::clock;
use crate::app::platform::clock::FrameTime;
use crate::app::screen_points::ScreenPoints;
use crate::app::state::model::{HoverSource, Model};
use crate::app::widgets::style;
use armlab_session::settings::{CameraPose, Overlay, OverlaySet};
use jacobian::JacobianScene;
use marker::{Handle, MarkerDrag, ViewGeometry, dist_to_segment, drag_marker, pick};
use marker::{handle_px, perpendiculars};
use scene::MarkerLook;

/// What the top bar asks of the 3D view.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewAction {
    /// Frame the arm.
    Fit,
    /// A standard view direction.
    View(StandardView),
    /// Zoom by [`keys::ZOOM_STEP`] a press, closer (1) or back (−1): pinch's alternative.
    Zoom(i8),
    /// A one-pointer drag off the target pans (true) or orbits (false): the two-finger
    /// pan's alternative for one finger.
    DragPans(bool),
}

/// What the pointer is dragging.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Drag {
    Orbit,
    Pan,
    Marker(MarkerDrag),
}

/// The 3D view: camera, interaction state and renderer.
pub struct Viewport {
    camera: OrbitCamera,
    renderer: Option<SceneRenderer>,
    drag: Option<Drag>,
    /// Whether a primary drag off the target pans instead of orbiting ([`ViewAction::DragPans`]).
    drag_pans: bool,
    hover: Option<Handle>,
    /// The model's reframe count and the view's size the camera last framed the arm at.
    framed_at: Option<(u64, egui::Vec2)>,
    /// Whether the camera last framed the workspace cloud (it reframes when the cloud is
    /// switched on or off).
    framed_cloud: bool,
    /// The model's camera-load count last applied (a link's camera).
    camera_loaded: u64,
    rect: Option<Rect>,
    grid_step: f64,
    rendered: bool,
    /// Where and when (egui's input time, s) the press of the current drag began: a
    /// release near it soon after is a click (on a ghost arm).
    press: Option<(egui::Pos2, f64)>,
    /// The labels drawn over the picture last frame.
    labels: Vec<labels::Placed>,
    /// Where the pointer was at the drag's last frame: the camera turns by the pointer's
    /// own path from the press, never by egui's delta from wherever the pointer was
    /// last seen (a click with no move before it would jump by that distance).
    pointer: Option<egui::Pos2>,
    /// The room's predicted tool points, drawn while a point question is open.
    predictions: predictions::Predictions,
}

/// A press released within this distance (points) of where it began is a click.
const CLICK_DISTANCE: f32 = 6.0;
/// ... and within this time (s).
const CLICK_SECONDS: f64 = 0.8;

impl Viewport {
    /// A viewport drawing with wgpu when a render state is given (none: a placeholder
    /// sentence, for tests of the logic).
    pub fn new(render_state: Option<&RenderState>) -> Self {
        Viewport {
            camera: OrbitCamera::default(),
            renderer: render_state.map(SceneRenderer::new),
            drag: None,
            drag_pans: false,
            hover: None,
            framed_at: None,
            framed_cloud: false,
            camera_loaded: 0,
            rect: None,
            grid_step: 0.0,
            rendered: false,
            press: None,
            labels: Vec::new(),
            pointer: None,
            predictions: predictions::Predictions::default(),
        }
    }

    /// True while the user drags the target marker.
    pub fn dragging(&self) -> bool {
        matches!(self.drag, Some(Drag::Marker(_)))
    }

    /// Whether the 3D picture was drawn by the wgpu renderer last frame.
    pub fn rendered(&self) -> bool {
        self.rendered
    }

    /// The 3D render passes drawn so far (frames whose scene changed; 0 without a
    /// renderer).
    pub fn scene_passes(&self) -> u64 {
        self.renderer.as_ref().map_or(0, SceneRenderer::passes)
    }

    /// Sets the room's predicted tool points to draw (none outside a point question).
    pub fn set_predictions(&mut self, predictions: predictions::Predictions) {
        self.predictions = predictions;
    }

    /// Whether the 3D picture shown is a moving one: drawn by a software renderer while
    /// the scene changes, with fewer pixels and samples than at rest.
    pub fn moving_picture(&self) -> bool {
        self.renderer.as_ref().is_some_and(SceneRenderer::moving)
    }

    /// Draws moving scenes as on a software renderer, whatever the adapter (the page
    /// does so by itself on SwiftShader).
    pub fn adapt_to_software(&mut self) {
        if let Some(renderer) = self.renderer.as_mut() {
            renderer.adapt_to_software();
        }
    }

    /// The view's rectangle last frame (egui points).
    pub fn rect(&self) -> Option<Rect> {
        self.rect
    }

    /// The labels drawn over the picture last frame: the exercise's axes and dimensions,
    /// or the DH frames' axis names.
    pub fn labels(&self) -> &[labels::Placed] {
        &self.labels
    }

    /// The grid spacing last drawn (robot units).
    pub fn grid_step(&self) -> f64 {
        self.grid_step
    }

    /// The camera.
    pub fn camera(&self) -> &OrbitCamera {
        &self.camera
    }

    /// Whether a one-pointer drag off the target pans the view ([`ViewAction::DragPans`]).
    pub fn drag_pans(&self) -> bool {
        self.drag_pans
    }

    /// Carries out what the top bar asked.
    pub fn apply(&mut self, action: ViewAction, ctx: &egui::Context) {
        match action {
            // A zoom keeps the framing: framing anew would undo it.
            ViewAction::Zoom(n) => self.camera.zoom(keys::ZOOM_STEP.powi(n.into())),
            ViewAction::View(view) => self.camera.set_view(view),
            ViewAction::DragPans(on) => self.drag_pans = on,
            ViewAction::Fit => {}
        }
        if matches!(action, ViewAction::Fit | ViewAction::View(_)) {
            self.framed_at = None;
        }
        ctx.request_repaint();
    }

    /// Frames the robot (a sphere of 0.85 reach about a point above the base, or with the
    /// workspace cloud shown the sphere of its reach about the base) for the view's aspect
    /// ratio, so a narrow or wide view keeps the whole arm in sight. The exercise frames
    /// its drawing as the arm stands, with room for the labels: the student reads lengths
    /// off it. Otherwise it then steps back until the tool and the target lie an arrow's
    /// length inside the view and above the hint lines at its foot: a planar arm stretched
    /// along the floor lies outside the usual sphere, and its target's arrows ran over the
    /// hint.
    fn fit(&mut self, model: &Model, size: egui::Vec2) {
        let reach = model.robot().reach();
        let base = model.robot().world_from_base.translation.vector;
        let aspect = (size.x / size.y.max(1.0)) as f64;
        // The workspace cloud lies within the reach of the base, below it too.
        self.framed_cloud = model.settings().overlays.contains(Overlay::Workspace);
        if model.exercise().is_some() {
            let points = exercise::drawing_points(model.robot(), model.fk());
            let (centre, radius) = exercise::bounds(&points);
            self.camera.fit(Point3::from(centre), radius, aspect);
            fill_view(&mut self.camera, &points, size);
        } else {
            if self.framed_cloud {
                self.camera.fit(Point3::from(base), reach, aspect);
            } else {
                let centre = Point3::from(base + Vector3::new(0.0, 0.0, reach * 0.35));
                self.camera.fit(centre, reach * 0.85, aspect);
            }
            self.step_back_to_show_handles(model, size);
        }
        self.framed_at = Some((model.reframes(), size));
    }

    /// Zooms out in small steps until the tool and the target lie an arrow's length inside
    /// the view and above its hint lines.
    fn step_back_to_show_handles(&mut self, model: &Model, size: egui::Vec2) {
        let (w, h) = (f64::from(size.x), f64::from(size.y));
        let arrow = marker::handle_px::ARROW + 10.0;
        let hint = 45.0;
        let shown = [
            model.target().translation.vector,
            model.fk().tool_position(),
        ];
        for _ in 0..30 {
            let clear = shown.iter().all(|p| {
                self.camera
                    .project(&Point3::from(*p), [w, h])
                    .is_some_and(|[x, y]| {
                        x > arrow && x < w - arrow && y > arrow && y < h - arrow - hint
                    })
            });
            if clear {
                break;
            }
            self.camera.zoom(1.0 / 1.05);
        }
    }

    /// Whether to frame anew: on load, on a robot change, on Fit, when the view's size
    /// changes and when the workspace cloud is switched on or off.
    fn needs_fit(&self, model: &Model, size: egui::Vec2) -> bool {
        let cloud = model.settings().overlays.contains(Overlay::Workspace);
        self.framed_at != Some((model.reframes(), size)) || self.framed_cloud != cloud
    }

    /// Shows the viewport and handles its input.
    pub fn ui(
        &mut self,
        model: &mut Model,
        ui: &mut egui::Ui,
        points: &mut ScreenPoints,
        render_state: Option<&RenderState>,
        timing: &mut FrameTime,
    ) {
        let rect = on_pixels(ui.available_rect_before_wrap(), ui.pixels_per_point());
        self.take_link_camera(model, rect.size());
        if self.needs_fit(model, rect.size()) {
            self.fit(model, rect.size());
        }
        // Drags only: a widget that also senses clicks waits to see whether a press is a
        // click, and on a touch screen egui turns a finger held still past the click time
        // (0.8 s) into a long press and drops that drag, so a student who rests a finger on
        // the target before moving it would move nothing. The view has no click action.
        let response = ui.allocate_rect(rect, Sense::drag());
        self.rect = Some(rect);
        let axes = marker_axes(model);
        self.handle_input(model, ui, &response, &axes);
        if keys::handle_keys(&mut self.camera, model, ui.ctx()) {
            ui.ctx().request_repaint();
        }
        if self.dragging() {
            // Every frame of the drag, including frames where the pointer rests: the arm
            // keeps converging (each step moves each joint by at most the per-call limit).
            let t0 = clock::now_ms();
            model.drag_step();
            timing.ik_ms += clock::now_ms() - t0;
            if model.ik().reach == armlab_core::ik::Reach::Pending {
                ui.ctx().request_repaint();
            }
        }
        if response.drag_stopped() {
            self.drag_stopped(model, ui, rect);
        }
        over_frames::advance_motion(model, ui, timing);
        self.update_hover(model, &response, &axes);
        over_frames::fill_overlays(model, ui, timing);
        self.draw_scene(model, ui, rect, render_state, &axes, timing);
        let touch = ui.spacing().interact_size.y >= style::TOUCH_TARGET;
        overlay::draw(model, &ui.painter_at(rect), rect, self.grid_step, touch);
        overlay::cloud_legend(model, &ui.painter_at(rect), rect, points);
        let view = view_geometry(&self.camera, model, rect);
        let project = |p: &Point3<f64>| {
            view.project(p)
                .map(|s| egui::pos2(s[0] as f32, s[1] as f32))
        };
        self.labels = draw_labels(model, &ui.painter_at(rect), rect, &project);
        paths::draw_in_view(model, &ui.painter_at(rect), &project);
        self.publish_points(model, rect, &axes, points);
        if response.hovered() && self.hover.is_some() {
            ui.ctx().set_cursor_icon(egui::CursorIcon::Grab);
        }
        let pose = self.camera_pose();
        if model.camera() != Some(pose) {
            model.note_camera(pose);
        }
    }

    /// A press and release without movement (egui's click) on a ghost arm moves the arm
    /// to that solution; on the target it was only a grab.
    fn drag_stopped(&mut self, model: &mut Model, ui: &egui::Ui, rect: Rect) {
        let grabbed = self.dragging();
        self.drag = None;
        // egui's own click flag, or a release near the press and soon after it: in
        // the browser egui reports no click for a widget that senses drags only.
        let (now, at, egui_click) =
            ui.input(|i| (i.time, i.pointer.interact_pos(), i.pointer.any_click()));
        let near_press = self.press.take().zip(at).is_some_and(|((p, t), at)| {
            at.distance(p) <= CLICK_DISTANCE && now - t <= CLICK_SECONDS
        });
        let click = (egui_click || near_press).then_some(at);
        if let (false, Some(Some(at))) = (grabbed, click) {
            let view = view_geometry(&self.camera, model, rect);
            if let Some(i) = ghosts::pick(model, &view, to_array(at)) {
                let q = model
                    .branches()
                    .and_then(|b| b.rows.get(i))
                    .map(|r| r.q.clone());
                if let Some(q) = q {
                    model.set_q_exact(q);
                }
            }
        }
    }

    /// Where the camera is, as a link writes it.
    pub fn camera_pose(&self) -> CameraPose {
        let c = &self.camera;
        CameraPose {
            yaw: c.yaw,
            pitch: c.pitch,
            distance: c.distance,
            focus: [c.focus.x, c.focus.y, c.focus.z],
        }
    }

    /// Takes the camera a link named (instead of framing the arm), once per link.
    fn take_link_camera(&mut self, model: &Model, size: egui::Vec2) {
        if self.camera_loaded == model.camera_loads() {
            return;
        }
        self.camera_loaded = model.camera_loads();
        if let Some(pose) = model.camera() {
            self.camera.yaw = pose.yaw;
            self.camera.pitch = pose.pitch;
            self.camera.distance = pose.distance;
            self.camera.focus = Point3::from(pose.focus);
            self.framed_at = Some((model.reframes(), size));
        }
    }

    /// Wheel and pinch zoom, orbit, pan, two-finger pan, and marker drags.
    fn handle_input(
        &mut self,
        model: &mut Model,
        ui: &egui::Ui,
        response: &egui::Response,
        axes: &[Vector3<f64>; 3],
    ) {
        let (shift, scroll, zoom, multi) = ui.input(|i| {
            (
                i.modifiers.shift,
                i.smooth_scroll_delta,
                i.zoom_delta(),
                i.multi_touch(),
            )
        });
        if response.hovered() {
            if scroll.y != 0.0 {
                self.camera.zoom((scroll.y as f64 * 0.0015).exp());
            }
            if zoom != 1.0 {
                self.camera.zoom(zoom as f64);
            }
        }
        if response.drag_started() {
            let press = ui
                .input(|i| i.pointer.press_origin())
                .or(response.hover_pos())
                .or(response.interact_pointer_pos());
            let primary = response.dragged_by(egui::PointerButton::Primary);
            self.drag = Some(self.start_drag(model, press, primary && !shift, axes));
            self.press = press.map(|p| (p, ui.input(|i| i.time)));
            self.pointer = press;
        }
        let height = response.rect.height().max(1.0) as f64;
        if response.dragged() {
            let now = response.interact_pointer_pos();
            let delta = match (self.pointer, now) {
                (Some(before), Some(now)) => now - before,
                _ => egui::Vec2::ZERO,
            };
            self.pointer = now.or(self.pointer);
            match self.drag {
                Some(Drag::Orbit) if multi.is_none() => {
                    self.camera.orbit(delta.x as f64, delta.y as f64);
                }
                Some(Drag::Pan) => self.camera.pan(delta.x as f64, delta.y as f64, height),
                Some(Drag::Marker(drag)) => {
                    let pointer = response.hover_pos().or(response.interact_pointer_pos());
                    if let Some(p) = pointer {
                        let view = view_geometry(&self.camera, model, response.rect);
                        let target = drag_marker(&drag, axes, &view, to_array(p));
                        model.set_target(target);
                    }
                }
                Some(Drag::Orbit) | None => {}
            }
        }
        if let Some(mt) = multi {
            // Two fingers: pan with their centre, pinch already zooms.
            let d = mt.translation_delta;
            self.camera.pan(d.x as f64, d.y as f64, height);
        }
    }

    /// What a new drag holds: a marker handle under the press, else orbit or pan.
    fn start_drag(
        &self,
        model: &Model,
        press: Option<Pos2>,
        primary: bool,
        axes: &[Vector3<f64>; 3],
    ) -> Drag {
        let Some(rect) = self.rect else {
            return Drag::Orbit;
        };
        let view = view_geometry(&self.camera, model, rect);
        let rings = model.task() != Task::Position;
        let grabbed = press.filter(|_| primary).and_then(|p| {
            pick(model.target(), axes, rings, &view, to_array(p)).map(|handle| (handle, p))
        });
        match grabbed {
            Some((handle, p)) => Drag::Marker(MarkerDrag::start(
                handle,
                model.target(),
                axes,
                &view,
                to_array(p),
            )),
            None if primary && !self.drag_pans => Drag::Orbit,
            None => Drag::Pan,
        }
    }

    /// The handle under the pointer (or held), and the link under the pointer, which
    /// highlights its matrices.
    fn update_hover(
        &mut self,
        model: &mut Model,
        response: &egui::Response,
        axes: &[Vector3<f64>; 3],
    ) {
        let view = view_geometry(&self.camera, model, response.rect);
        let rings = model.task() != Task::Position;
        self.hover = match &self.drag {
            Some(Drag::Marker(drag)) => Some(drag.handle),
            _ => response
                .hover_pos()
                .and_then(|p| pick(model.target(), axes, rings, &view, to_array(p))),
        };
        let link = match (
            self.drag.is_none() && self.hover.is_none(),
            response.hover_pos(),
        ) {
            (true, Some(p)) => hovered_link(model, &view, to_array(p)),
            _ => None,
        };
        if model.hover_source() != Some(HoverSource::Matrices) {
            model.set_hovered_link(link, HoverSource::View);
        }
        let column = match (self.drag.is_none(), response.hover_pos()) {
            (true, Some(p)) => hovered_column(model, &view, to_array(p)),
            _ => None,
        };
        model.set_hovered_column(column, HoverSource::View);
    }

    /// Builds the scene from the model and has the renderer draw it into the view.
    fn draw_scene(
        &mut self,
        model: &Model,
        ui: &egui::Ui,
        rect: Rect,
        render_state: Option<&RenderState>,
        axes: &[Vector3<f64>; 3],
        timing: &mut FrameTime,
    ) {
        let painter = ui.painter_at(rect);
        let presentation = model.settings().presentation;
        let bg = style::background(presentation);
        self.rendered = false;
        let Some(rs) = render_state.filter(|_| self.renderer.is_some()) else {
            painter.rect_filled(rect, 0.0, bg);
            painter.text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                "The 3D view needs WebGPU, WebGL2 or Vulkan.",
                egui::FontId::proportional(16.0),
                style::ERROR,
            );
            return;
        };
        let look = MarkerLook {
            color: style::reach_color(model.shown_reach()).to_array(),
            axes: *axes,
            rings: model.task() != Task::Position,
            active: self.hover,
        };
        let ppp = ui.ctx().pixels_per_point();
        let px_size = [
            (rect.width() * ppp).round() as u32,
            (rect.height() * ppp).round() as u32,
        ];
        let t0 = clock::now_ms();
        let (scene, step) = self.scene(model, rect, &look, bg);
        self.grid_step = step;
        let t1 = clock::now_ms();
        let Some(renderer) = self.renderer.as_mut() else {
            return;
        };
        let drawn = renderer.render(rs, px_size, &scene, ui.input(|i| i.time));
        timing.scene_ms += t1 - t0;
        timing.render_ms += clock::now_ms() - t1;
        if let Some(s) = drawn.sharpen_in {
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(s));
        }
        painter.image(
            drawn.texture,
            rect,
            Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0)),
            Color32::WHITE,
        );
        self.rendered = true;
    }

    /// The scene of this frame: the arm, frames, grid and marker, then the overlays the
    /// model shows (Jacobian, cloud, directions, the other convention, ghosts, the room's
    /// predictions, the motion lab's trail, keep-out boxes and paths), colliding parts red.
    /// Also the grid's spacing.
    fn scene(&self, model: &Model, rect: Rect, look: &MarkerLook, bg: Color32) -> (Scene, f64) {
        let (mut scene, step) = scene::build(&scene::SceneInput {
            robot: model.robot(),
            fk: model.fk(),
            camera: &self.camera,
            viewport_px: [rect.width().max(1.0) as f64, rect.height().max(1.0) as f64],
            // The DH frames would show the exercise's hidden table.
            show_frames: model.settings().show_frames && !model.table_hidden(),
            highlighted_link: model.hovered_link(),
            target: model.target(),
            marker: look,
            background: [bg.r(), bg.g(), bg.b()],
        });
        if model.settings().overlays != OverlaySet::NONE {
            jacobian::instances(&jacobian_scene(model), &mut scene.instances);
        }
        workspace::instances(model, &mut scene.instances);
        workspace::direction_instances(model, &mut scene.instances);
        if !model.table_hidden() {
            convention::instances(model, model.robot().reach(), &mut scene.instances);
        }
        ghosts::instances(model, &mut scene.instances);
        predictions::instances(
            &self.predictions,
            model.robot().reach(),
            &mut scene.instances,
        );
        motion::trail_lines(model, &mut scene.lines);
        motion::keep_out_instances(model, &mut scene.instances);
        paths::scene_parts(model, &mut scene.lines, &mut scene.instances);
        // The arm's parts come first in the scene, in the core's part order.
        for (instance, red) in scene.instances.iter_mut().zip(model.motion().colliding()) {
            if *red {
                instance.color = [230, 60, 50, 255];
            }
        }
        (scene, step)
    }

    /// Screen points for the browser tests: the marker's handles, the tool and the base.
    fn publish_points(
        &self,
        model: &Model,
        rect: Rect,
        axes: &[Vector3<f64>; 3],
        points: &mut ScreenPoints,
    ) {
        let view = view_geometry(&self.camera, model, rect);
        let centre = Point3::from(model.target().translation.vector);
        let mut add = |name: String, p: &Point3<f64>| {
            if let Some(s) = view.project(p) {
                points.insert(name, egui::pos2(s[0] as f32, s[1] as f32));
            }
        };
        add("target".into(), &centre);
        let rings = model.task() != Task::Position;
        for (i, name) in ["x", "y", "z"].iter().enumerate() {
            add(
                format!("target-{name}"),
                &(centre + axes[i] * ((handle_px::ARROW - 18.0) * view.px)),
            );
            if rings {
                let (u, _) = perpendiculars(&axes[i]);
                add(
                    format!("ring-{name}"),
                    &(centre + u * (handle_px::RING * view.px)),
                );
            }
        }
        ghosts::points(model, &mut add);
        paths::points(model, &mut add);
        add("tool".into(), &Point3::from(model.fk().tool_position()));
        let base = model.robot().world_from_base.translation.vector;
        add("base".into(), &Point3::from(base));
    }
}

/// The labels over the picture: the exercise's joint axes and dimensions, or the DH
/// frames' axis names when the frames are drawn.
fn draw_labels(
    model: &Model,
    painter: &egui::Painter,
    rect: Rect,
    project: &dyn Fn(&Point3<f64>) -> Option<Pos2>,
) -> Vec<labels::Placed> {
    if model.exercise().is_some() {
        exercise::draw_in_view(model, painter, rect, project)
    } else if model.settings().show_frames && !model.table_hidden() {
        frame_labels::draw_in_view(model, painter, rect, project)
    } else {
        Vec::new()
    }
}

/// The share of the view's width and height the exercise's drawing fills when framed;
/// the rest is room for its labels.
const EXERCISE_FILL: f64 = 0.72;

/// `rect` on whole pixels: the view's picture is drawn at its size in pixels and shown
/// one texel to a pixel, sharp (egui places panels on 1/32 of a point). Out of line:
/// inlined into the view's `ui` it cost the page about 60 B more.
#[inline(never)]
fn on_pixels(rect: Rect, ppp: f32) -> Rect {
    rect.round_to_pixels(ppp)
}

/// Pans and zooms so the picture of `points` is centred in a view of `size` and fills
/// [`EXERCISE_FILL`] of it in its tighter direction: a sphere around the points leaves a
/// flat or tall arm small. A few rounds, as perspective moves the picture with distance.
fn fill_view(camera: &mut OrbitCamera, points: &[Vector3<f64>], size: egui::Vec2) {
    let s = [size.x as f64, size.y.max(1.0) as f64];
    for _ in 0..4 {
        let Some(px) = points
            .iter()
            .map(|p| camera.project(&Point3::from(*p), s))
            .collect::<Option<Vec<_>>>()
        else {
            return;
        };
        let (lo, hi) = px.iter().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1])],
                    [hi[0].max(p[0]), hi[1].max(p[1])],
                )
            },
        );
        let scale = ((hi[0] - lo[0]) / s[0]).max((hi[1] - lo[1]) / s[1]) / EXERCISE_FILL;
        if !(scale.is_finite() && scale > 1e-6) {
            return;
        }
        let centre = [(lo[0] + hi[0]) * 0.5, (lo[1] + hi[1]) * 0.5];
        camera.pan(s[0] * 0.5 - centre[0], s[1] * 0.5 - centre[1], s[1]);
        camera.zoom(1.0 / scale);
    }
}

/// The view's geometry this frame: the camera, the view's placement, and the world length
/// of one point at the target's depth.
fn view_geometry<'a>(camera: &'a OrbitCamera, model: &Model, rect: Rect) -> ViewGeometry<'a> {
    let size = [rect.width().max(1.0) as f64, rect.height().max(1.0) as f64];
    let centre = Point3::from(model.target().translation.vector);
    let px = camera.world_per_pixel(size[1]) * (camera.eye() - centre).norm() / camera.distance;
    ViewGeometry {
        camera,
        size,
        origin: [rect.min.x as f64, rect.min.y as f64],
        px,
    }
}

fn to_array(p: Pos2) -> [f64; 2] {
    [p.x as f64, p.y as f64]
}

/// The axes the marker's arrows and rings use: world axes for position-only targets,
/// the target's own axes otherwise.
fn marker_axes(model: &Model) -> [Vector3<f64>; 3] {
    match model.task() {
        Task::Position => [Vector3::x(), Vector3::y(), Vector3::z()],
        _ => {
            let r = model.target().rotation.matrix();
            [0, 1, 2].map(|c| r.column(c).into_owned())
        }
    }
}

/// The link (1-based) whose segment between consecutive frame origins is under `at`.
/// The Jacobian column whose arrow passes within 8 points of `at`, when the arrows are
/// drawn.
fn hovered_column(model: &Model, view: &ViewGeometry<'_>, at: [f64; 2]) -> Option<usize> {
    if !model.settings().overlays.contains(Overlay::JacobianColumns) {
        return None;
    }
    let scene = jacobian_scene(model);
    let tool = view.project(&scene.tool)?;
    let mut best: Option<(f64, usize)> = None;
    for (i, tip) in jacobian::column_tips(&scene).iter().enumerate() {
        if let Some(b) = view.project(tip) {
            let d = dist_to_segment(at, tool, b);
            if d < 8.0 && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, i));
            }
        }
    }
    best.map(|(_, i)| i)
}

/// What the Jacobian overlays are drawn from this frame.
fn jacobian_scene(model: &Model) -> JacobianScene<'_> {
    JacobianScene {
        jacobian: model.jacobian(),
        tool: Point3::from(model.fk().tool_position()),
        reach: model.robot().reach(),
        overlays: model.settings().overlays,
        hovered: model.hovered_column(),
        robot: model.robot(),
        q: model.q(),
        task: model.task(),
        speeds: model.joint_speeds(),
        lost: model.lost_direction(),
    }
}

fn hovered_link(model: &Model, view: &ViewGeometry<'_>, at: [f64; 2]) -> Option<usize> {
    let mut prev = Point3::from(model.robot().world_from_base.translation.vector);
    let mut best: Option<(f64, usize)> = None;
    for (i, frame) in model.fk().base_from_frames.iter().enumerate() {
        let o = Point3::from(frame.translation.vector);
        if let (Some(a), Some(b)) = (view.project(&prev), view.project(&o)) {
            let d = dist_to_segment(at, a, b);
            if d < 10.0 && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, i + 1));
            }
        }
        prev = o;
    }
    best.map(|(_, i)| i)
}
