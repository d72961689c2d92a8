//! The 3D viewport: orbit (left drag), pan (right or middle drag, or shift + left), zoom
//! (wheel, pinch); the target marker is dragged in the view plane by its ball, along an
//! axis by its arrow, and turned by its rings (5D and full-pose tasks). Every frame of a
//! drag runs the IK warm-started at the current q.

use eframe::egui_wgpu::RenderState;
use egui::{Color32, Pos2, Rect, Sense};
use nalgebra::{Point3, Rotation3, Unit, Vector3};

use crate::kinematics::Task;
use crate::render::SceneRenderer;

use super::scene::{self, MarkerLook, handle_px};
use super::{ArmLabApp, hook, ik_panel, style};

/// A grabbable part of the target marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Handle {
    /// The centre ball: moves the target in the view plane.
    Ball,
    /// An arrow: moves the target along that axis (0 = x, 1 = y, 2 = z).
    Axis(usize),
    /// A ring: turns the target about that axis.
    Ring(usize),
}

#[derive(Debug, Clone)]
enum Drag {
    Orbit,
    Pan,
    Marker {
        handle: Handle,
        start_target: nalgebra::IsometryMatrix3<f64>,
        start_pointer: Pos2,
        /// The world point under the pointer at the start (plane or axis drags).
        start_hit: Point3<f64>,
    },
}

/// Interaction state of the viewport.
#[derive(Debug, Clone, Default)]
pub struct ViewportState {
    drag: Option<Drag>,
    hover: Option<Handle>,
    /// The link highlight comes from the matrices panel (not from the 3D hover).
    pub link_hover_from_panel: bool,
    /// Screen points (egui points, window coordinates) for `window.armlab.screenPoint`.
    pub points: Vec<(String, [f32; 2])>,
    /// The viewport rectangle last frame.
    pub rect: Option<Rect>,
    /// Grid spacing last drawn (robot units), for the scale label and tests.
    pub grid_step: f64,
    /// Whether the 3D picture was drawn by the wgpu renderer last frame.
    pub rendered: bool,
}

impl ViewportState {
    /// True while the user drags the target marker.
    pub fn dragging(&self) -> bool {
        matches!(self.drag, Some(Drag::Marker { .. }))
    }

    /// A named screen point, if visible.
    pub fn point(&self, name: &str) -> Option<[f32; 2]> {
        self.points.iter().find(|(n, _)| n == name).map(|(_, p)| *p)
    }
}

/// The axes the marker's arrows and rings use: world axes for position-only targets,
/// the target's own axes otherwise.
fn marker_axes(app: &ArmLabApp) -> [Vector3<f64>; 3] {
    match app.session.task {
        Task::Position => [Vector3::x(), Vector3::y(), Vector3::z()],
        _ => {
            let r = app.target.rotation.matrix();
            [0, 1, 2].map(|c| r.column(c).into_owned())
        }
    }
}

struct Geometry {
    size: [f64; 2],
    origin: Pos2,
    px: f64,
}

impl Geometry {
    fn project(
        &self,
        camera: &crate::render::camera::OrbitCamera,
        p: &Point3<f64>,
    ) -> Option<Pos2> {
        camera
            .project(p, self.size)
            .map(|s| Pos2::new(self.origin.x + s[0] as f32, self.origin.y + s[1] as f32))
    }

    fn ray(
        &self,
        camera: &crate::render::camera::OrbitCamera,
        pos: Pos2,
    ) -> (Point3<f64>, Vector3<f64>) {
        camera.ray(
            [
                (pos.x - self.origin.x) as f64,
                (pos.y - self.origin.y) as f64,
            ],
            self.size,
        )
    }
}

fn dist_to_segment(p: Pos2, a: Pos2, b: Pos2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_sq().max(1e-6)).clamp(0.0, 1.0);
    (a + ab * t - p).length()
}

fn ring_points(centre: &Point3<f64>, dir: &Vector3<f64>, radius: f64) -> Vec<Point3<f64>> {
    let (u, w) = scene::perpendiculars(dir);
    (0..=48)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 48.0;
            centre + (u * t.cos() + w * t.sin()) * radius
        })
        .collect()
}

/// Which handle is under `pos`, if any (ball first, then arrows, then rings).
fn pick(
    app: &ArmLabApp,
    g: &Geometry,
    pos: Pos2,
    axes: &[Vector3<f64>; 3],
    rings: bool,
) -> Option<Handle> {
    let cam = &app.camera;
    let centre = Point3::from(app.target.translation.vector);
    let c = g.project(cam, &centre)?;
    if (c - pos).length() <= handle_px::BALL as f32 + 5.0 {
        return Some(Handle::Ball);
    }
    let mut best: Option<(f32, Handle)> = None;
    for (i, dir) in axes.iter().enumerate() {
        if let Some(tip) = g.project(cam, &(centre + dir * (handle_px::ARROW * g.px))) {
            let d = dist_to_segment(pos, c, tip);
            if d < 9.0 && best.is_none_or(|(b, _)| d < b) {
                best = Some((d, Handle::Axis(i)));
            }
        }
    }
    if best.is_some() {
        return best.map(|(_, h)| h);
    }
    if rings {
        for (i, dir) in axes.iter().enumerate() {
            let pts: Vec<Pos2> = ring_points(&centre, dir, handle_px::RING * g.px)
                .iter()
                .filter_map(|p| g.project(cam, p))
                .collect();
            for pair in pts.windows(2) {
                let d = dist_to_segment(pos, pair[0], pair[1]);
                if d < 7.0 && best.is_none_or(|(b, _)| d < b) {
                    best = Some((d, Handle::Ring(i)));
                }
            }
        }
    }
    best.map(|(_, h)| h)
}

/// Closest point on the line (p0, dir) to the ray (o, r).
fn closest_on_line(
    p0: &Point3<f64>,
    dir: &Vector3<f64>,
    o: &Point3<f64>,
    r: &Vector3<f64>,
) -> Option<Point3<f64>> {
    let w = p0 - o;
    let (a, b, c) = (dir.dot(dir), dir.dot(r), r.dot(r));
    let (d, e) = (dir.dot(&w), r.dot(&w));
    let denom = a * c - b * b;
    if denom.abs() < 1e-9 * a * c {
        return None; // The axis points at the camera: no well-defined motion.
    }
    let s = (b * e - c * d) / denom;
    Some(p0 + dir * s)
}

fn plane_hit(
    point: &Point3<f64>,
    normal: &Vector3<f64>,
    o: &Point3<f64>,
    r: &Vector3<f64>,
) -> Option<Point3<f64>> {
    let denom = normal.dot(r);
    if denom.abs() < 1e-9 {
        return None;
    }
    let t = normal.dot(&(point - o)) / denom;
    (t > 0.0).then(|| o + r * t)
}

/// Shows the viewport and handles its input.
pub fn show(
    app: &mut ArmLabApp,
    ui: &mut egui::Ui,
    render_state: Option<&RenderState>,
    renderer: Option<&mut SceneRenderer>,
) {
    let rect = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    app.viewport.rect = Some(rect);
    let size = [rect.width().max(1.0) as f64, rect.height().max(1.0) as f64];
    let centre = Point3::from(app.target.translation.vector);
    let px = app.camera.world_per_pixel(size[1]) * (app.camera.eye() - centre).norm()
        / app.camera.distance;
    let g = Geometry {
        size,
        origin: rect.min,
        px,
    };
    let axes = marker_axes(app);
    let rings = app.session.task != Task::Position;

    // --- Input -------------------------------------------------------------------------
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
            app.camera.zoom((scroll.y as f64 * 0.0015).exp());
        }
        if zoom != 1.0 {
            app.camera.zoom(zoom as f64);
        }
    }
    let pointer = response.hover_pos().or(response.interact_pointer_pos());
    if response.drag_started() {
        let press = ui.input(|i| i.pointer.press_origin()).or(pointer);
        let primary = response.dragged_by(egui::PointerButton::Primary);
        let handle = press
            .filter(|_| primary && !shift)
            .and_then(|p| pick(app, &g, p, &axes, rings));
        app.viewport.drag = Some(match (handle, press) {
            (Some(handle), Some(p)) => {
                let (o, r) = g.ray(&app.camera, p);
                let forward = (app.camera.focus - app.camera.eye()).normalize();
                let start_hit = match handle {
                    Handle::Axis(i) => closest_on_line(&centre, &axes[i], &o, &r).unwrap_or(centre),
                    _ => plane_hit(&centre, &forward, &o, &r).unwrap_or(centre),
                };
                Drag::Marker {
                    handle,
                    start_target: app.target,
                    start_pointer: p,
                    start_hit,
                }
            }
            _ if primary && !shift => Drag::Orbit,
            _ => Drag::Pan,
        });
    }
    if response.dragged() {
        let delta = response.drag_delta();
        match app.viewport.drag.clone() {
            Some(Drag::Orbit) if multi.is_none() => {
                app.camera.orbit(delta.x as f64, delta.y as f64);
            }
            Some(Drag::Pan) => app.camera.pan(delta.x as f64, delta.y as f64, size[1]),
            Some(Drag::Marker {
                handle,
                start_target,
                start_pointer,
                start_hit,
            }) => {
                if let Some(p) = pointer {
                    let (o, r) = g.ray(&app.camera, p);
                    let start_centre = Point3::from(start_target.translation.vector);
                    let mut target = start_target;
                    match handle {
                        Handle::Ball => {
                            let forward = (app.camera.focus - app.camera.eye()).normalize();
                            if let Some(hit) = plane_hit(&start_hit, &forward, &o, &r) {
                                target.translation.vector = start_centre.coords + (hit - start_hit);
                            }
                        }
                        Handle::Axis(i) => {
                            if let Some(hit) = closest_on_line(&start_hit, &axes[i], &o, &r) {
                                target.translation.vector = start_centre.coords + (hit - start_hit);
                            }
                        }
                        Handle::Ring(i) => {
                            if let Some(c) = g.project(&app.camera, &start_centre) {
                                let a0 = (start_pointer - c).angle();
                                let a1 = (p - c).angle();
                                let to_eye = (app.camera.eye() - start_centre).normalize();
                                let facing = if axes[i].dot(&to_eye) >= 0.0 {
                                    1.0
                                } else {
                                    -1.0
                                };
                                let angle = -(a1 - a0) as f64 * facing;
                                let rot = Rotation3::from_axis_angle(
                                    &Unit::new_normalize(axes[i]),
                                    angle,
                                );
                                target.rotation = rot * start_target.rotation;
                            }
                        }
                    }
                    app.set_target(target);
                }
            }
            Some(Drag::Orbit) | None => {}
        }
    }
    if let Some(mt) = multi {
        // Two fingers: pan with their centre, pinch already zooms.
        let d = mt.translation_delta;
        app.camera.pan(d.x as f64, d.y as f64, size[1]);
    }
    if app.viewport.dragging() {
        // Every frame of the drag, including frames where the pointer rests: the arm
        // keeps converging (each call moves each joint by at most the per-call limit).
        let t0 = hook::now_ms();
        ik_panel::drag_solve(app);
        app.timing.ik_ms += hook::now_ms() - t0;
        if !app.ik.reached && !app.ik.unreachable {
            ui.ctx().request_repaint();
        }
    }
    if response.drag_stopped() {
        app.viewport.drag = None;
    }
    app.viewport.hover = match &app.viewport.drag {
        Some(Drag::Marker { handle, .. }) => Some(*handle),
        _ => response
            .hover_pos()
            .and_then(|p| pick(app, &g, p, &axes, rings)),
    };
    // Hovering a link in 3D highlights its matrix.
    if !app.viewport.link_hover_from_panel {
        app.hovered_link = match (
            app.viewport.drag.is_none() && app.viewport.hover.is_none(),
            response.hover_pos(),
        ) {
            (true, Some(p)) => hovered_link(app, &g, p),
            _ => None,
        };
    }

    // --- Drawing -------------------------------------------------------------------------
    let painter = ui.painter_at(rect);
    let presentation = app.settings.presentation;
    let marker_color = if app.ik.reached {
        style::REACHED
    } else if app.ik.unreachable {
        style::UNREACHABLE
    } else {
        style::PENDING
    };
    let look = MarkerLook {
        color: marker_color.to_array(),
        axes,
        rings,
        active: app.viewport.hover,
    };
    let bg = style::background(presentation);
    app.viewport.rendered = false;
    if let (Some(rs), Some(r)) = (render_state, renderer) {
        let ppp = ui.ctx().pixels_per_point();
        let px_size = [
            (rect.width() * ppp).round() as u32,
            (rect.height() * ppp).round() as u32,
        ];
        let t0 = hook::now_ms();
        let (scene, step) = scene::build(&scene::SceneInput {
            robot: &app.session.robot,
            fk: &app.fk,
            camera: &app.camera,
            viewport_px: size,
            show_frames: app.settings.show_frames,
            highlighted_link: app.hovered_link,
            target: &app.target,
            marker: &look,
            background: [bg.r(), bg.g(), bg.b()],
        });
        app.viewport.grid_step = step;
        let t1 = hook::now_ms();
        let texture = r.render(rs, px_size, &scene);
        app.timing.scene_ms += t1 - t0;
        app.timing.render_ms += hook::now_ms() - t1;
        painter.image(
            texture,
            rect,
            Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0)),
            Color32::WHITE,
        );
        app.viewport.rendered = true;
    } else {
        painter.rect_filled(rect, 0.0, bg);
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "The 3D view needs WebGPU, WebGL2 or Vulkan.",
            egui::FontId::proportional(16.0),
            style::ERROR,
        );
    }

    // Labels over the picture.
    let unit = app.session.robot.length_unit.symbol();
    let small = egui::FontId::proportional(if presentation { 15.0 } else { 12.0 });
    let text_color = if presentation {
        Color32::WHITE
    } else {
        Color32::from_gray(200)
    };
    painter.text(
        rect.left_bottom() + egui::vec2(10.0, -10.0),
        egui::Align2::LEFT_BOTTOM,
        format!(
            "grid {} {unit}   ·   drag: orbit   right-drag: pan   wheel: zoom",
            trim_number(app.viewport.grid_step)
        ),
        small.clone(),
        text_color,
    );
    let status = if app.ik.reached {
        ("target reached", style::REACHED)
    } else if app.ik.unreachable {
        (
            "target out of reach: the arm stretches toward it",
            style::UNREACHABLE,
        )
    } else {
        ("drag the target ball, its arrows or rings", style::PENDING)
    };
    painter.text(
        rect.left_top() + egui::vec2(10.0, 10.0),
        egui::Align2::LEFT_TOP,
        status.0,
        small.clone(),
        status.1,
    );
    if let Some(link) = app.hovered_link
        && let Some(joint) = app.session.robot.joints.get(link.wrapping_sub(1))
    {
        painter.text(
            rect.right_top() + egui::vec2(-10.0, 10.0),
            egui::Align2::RIGHT_TOP,
            format!(
                "joint {link}: {} — A_{link} and T_0{link} highlighted",
                joint.name
            ),
            small,
            style::HIGHLIGHT,
        );
    }

    // Screen points for the browser tests.
    let mut points = Vec::new();
    if let Some(c) = g.project(&app.camera, &centre) {
        points.push(("target".to_string(), [c.x, c.y]));
    }
    for (i, name) in ["x", "y", "z"].iter().enumerate() {
        let along = centre + axes[i] * ((handle_px::ARROW - 18.0) * px);
        if let Some(p) = g.project(&app.camera, &along) {
            points.push((format!("target-{name}"), [p.x, p.y]));
        }
        if rings {
            let (u, _) = scene::perpendiculars(&axes[i]);
            if let Some(p) = g.project(&app.camera, &(centre + u * (handle_px::RING * px))) {
                points.push((format!("ring-{name}"), [p.x, p.y]));
            }
        }
    }
    if let Some(t) = g.project(&app.camera, &Point3::from(app.fk.tool_position())) {
        points.push(("tool".to_string(), [t.x, t.y]));
    }
    let base = Point3::from(app.session.robot.world_from_base.translation.vector);
    if let Some(b) = g.project(&app.camera, &base) {
        points.push(("base".to_string(), [b.x, b.y]));
    }
    app.viewport.points.extend(points);
    if response.hovered() && app.viewport.hover.is_some() {
        ui.ctx().set_cursor_icon(egui::CursorIcon::Grab);
    }
}

fn hovered_link(app: &ArmLabApp, g: &Geometry, p: Pos2) -> Option<usize> {
    let mut prev = Point3::from(app.session.robot.world_from_base.translation.vector);
    let mut best: Option<(f32, usize)> = None;
    for (i, frame) in app.fk.base_from_frames.iter().enumerate() {
        let o = Point3::from(frame.translation.vector);
        if let (Some(a), Some(b)) = (g.project(&app.camera, &prev), g.project(&app.camera, &o)) {
            let d = dist_to_segment(p, a, b);
            if d < 10.0 && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, i + 1));
            }
        }
        prev = o;
    }
    best.map(|(_, i)| i)
}

fn trim_number(v: f64) -> String {
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
