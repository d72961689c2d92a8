//! UI tests of the app through egui_kittest (native only, `app` feature): what a person
//! sees and does. The harness renders with wgpu on the machine's Vulkan adapter (lavapipe
//! here), so the 3D viewport runs its real pipeline.
#![cfg(not(target_arch = "wasm32"))]

use armlab_text::Sentence;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

use armlab::app::ArmLabApp;
use armlab::app::panels::Panel;
use armlab::app::panels::ik::IkPanel;
use armlab::app::panels::joints::JointsPanel;
use armlab::app::screen_points::ScreenPoints;
use armlab::app::state::model::{MessageKind, Model};
use armlab_core::ik::Reach;
use armlab_session::session::Session;

const SIZE: [f32; 2] = [1400.0, 860.0];

/// The screens people use (projectors, laptops, a portrait tablet, a phone), each with the
/// least share of the width the 3D view keeps there (the narrow layout gives it all).
const SCREENS: [([f32; 2], f32); 6] = [
    ([1024.0, 768.0], 0.5),
    ([1280.0, 720.0], 0.5),
    ([1366.0, 768.0], 0.5),
    ([1920.0, 1080.0], 0.5),
    ([820.0, 1180.0], 0.99),
    ([390.0, 844.0], 0.99),
];

#[path = "../app_harness/mod.rs"]
mod app_harness;
mod basics;
mod classroom;
mod exercise;
mod fit;
mod keyboard;
mod motion;
mod overlays;
mod panels;
mod paths;
mod screens;
mod zoom;

fn harness(hash: &str) -> Harness<'static, ArmLabApp> {
    app_harness::open_app(hash, SIZE)
}

fn tool_x(h: &Harness<'_, ArmLabApp>) -> f64 {
    h.state().model().fk().tool_position().x
}

/// The 3D view's pixels (RGBA, row by row), as egui's painter shows them this frame.
fn view_pixels(h: &mut Harness<'_, ArmLabApp>) -> Vec<u8> {
    let rect = h.state().viewport().rect().expect("the view was laid out");
    let image = h.render().expect("a frame");
    let rect = rect * h.ctx.pixels_per_point();
    let xs = (rect.left().ceil() as u32)..(rect.right().floor() as u32).min(image.width());
    let ys = (rect.top().ceil() as u32)..(rect.bottom().floor() as u32).min(image.height());
    ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
        .flat_map(|(x, y)| image.get_pixel(x, y).0)
        .collect()
}

/// A panel drawn alone over a model, as egui's demo app tests each demo alone.
struct Alone<P> {
    model: Model,
    panel: P,
    points: ScreenPoints,
}

fn alone<P: Panel + 'static>(preset: &str, panel: P) -> Harness<'static, Alone<P>> {
    let model = Model::new(Session::for_preset(preset).expect("a preset"));
    let mut h = Harness::builder()
        .with_size([420.0, 520.0])
        .with_context_setup(armlab::app::widgets::style::install_fonts)
        .build_ui_state(
            |ui, s: &mut Alone<P>| {
                s.points.clear();
                s.panel.ui(&mut s.model, ui, &mut s.points);
            },
            Alone {
                model,
                panel,
                points: ScreenPoints::default(),
            },
        );
    h.run_steps(2);
    h
}

/// The app at a screen size, one frame more settled (the columns take their widths).
fn harness_at(hash: &str, size: [f32; 2]) -> Harness<'static, ArmLabApp> {
    let mut h = app_harness::open_app(hash, size);
    h.run_steps(1);
    h
}

/// The view's share of the window's width, and whether the named points lie in the view.
fn view_share_and_points(h: &Harness<'_, ArmLabApp>, width: f32) -> f32 {
    let app = h.state();
    let rect = app.viewport().rect().expect("the view was laid out");
    for name in ["base", "tool", "target"] {
        let [x, y] = app.points().get(name).expect("the point is drawn");
        assert!(
            rect.contains(egui::pos2(x, y)),
            "{name} ({x}, {y}) lies in the view {rect:?}"
        );
    }
    // The view's width in CSS pixels (points times the zoom) against the window's.
    rect.width() * h.ctx.zoom_factor() / width
}

/// The controls of a column (buttons, menus, check boxes, fold headers) that end past its
/// visible edge: clipped, so a person reads "Solutions of th" or misses a button.
fn clipped_controls(h: &Harness<'_, ArmLabApp>, column: egui::Rect) -> Vec<String> {
    let mut clipped = Vec::new();
    for role in [
        Role::Button,
        Role::ComboBox,
        Role::CheckBox,
        Role::DisclosureTriangle,
    ] {
        for node in h.query_all_by_role(role) {
            let rect = node.rect();
            // Below the screen's foot the column scrolls: what shows there is not judged.
            let inside = rect.left() > column.left()
                && rect.left() < column.right()
                && rect.top() > column.top()
                && rect.bottom() < column.bottom();
            if inside && rect.right() > column.right() + 0.5 {
                let label = node.accesskit_node().label().unwrap_or_default();
                clipped.push(format!(
                    "{label:?} ends at {:.0} > {:.0}",
                    rect.right(),
                    column.right()
                ));
            }
        }
    }
    clipped
}

/// A finger's events as the browser delivers them (eframe's touch handlers): the press or
/// move of the primary pointer, then the touch itself.
fn finger(phase: egui::TouchPhase, pos: egui::Pos2) -> Vec<egui::Event> {
    let pointer = match phase {
        egui::TouchPhase::Start => egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed: true,
            modifiers: egui::Modifiers::NONE,
        },
        egui::TouchPhase::Move => egui::Event::PointerMoved(pos),
        egui::TouchPhase::End | egui::TouchPhase::Cancel => egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed: false,
            modifiers: egui::Modifiers::NONE,
        },
    };
    let touch = egui::Event::Touch {
        device_id: egui::TouchDeviceId(1),
        id: egui::TouchId(1),
        phase,
        pos,
        force: None,
    };
    vec![pointer, touch]
}

// --- The editor keeps q, the DH-table exercise, predict then reveal ----------------------

/// Types `text` over the `index`-th text input (the DH cells come first in table order).
/// A press and a release of the primary button at `at`, a frame after each.
fn click_at(h: &mut Harness<'_, ArmLabApp>, at: egui::Pos2) {
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
        h.run_steps(1);
    }
}

/// Folds the tool orientation and the Jacobian and ticks "symbolic": the symbolic
/// matrices come into sight. Returns a point over the Matrices panel to scroll it.
fn show_symbolic(h: &mut Harness<'_, ArmLabApp>) -> egui::Pos2 {
    for fold in ["Tool orientation", "Jacobian"] {
        h.get_by_label(fold).click();
        h.run_steps(2);
    }
    h.get_by_label("symbolic").click();
    h.run_steps(2);
    h.get_by_label("symbolic").rect().center()
}

fn type_into_cell(h: &mut Harness<'_, ArmLabApp>, index: usize, text: &str) {
    let cells: Vec<_> = h.query_all_by_role(Role::TextInput).collect();
    cells[index].focus();
    drop(cells);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text(text.into()));
    h.run_steps(2);
}

/// Bad text in waypoint 1's x gets a sentence and the last good x stays; a good value is
/// taken.
fn edit_waypoint_1_x(h: &mut Harness<'_, ArmLabApp>) {
    // Bad text in waypoint 1's x: a sentence, and the last good x stays.
    let x0 = h.state().model().paths().waypoints().poses()[0]
        .translation
        .x;
    let inputs: Vec<_> = h
        .query_all_by_role(Role::TextInput)
        .filter(|n| n.accesskit_node().label().as_deref() == Some("Waypoint 1: x, y, z (mm)"))
        .collect();
    assert_eq!(inputs.len(), 3, "x, y and z of waypoint 1");
    inputs[0].focus();
    drop(inputs);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text("12,5x".into()));
    h.run_steps(2);
    assert!(
        h.query_by_label("\"12,5x\" is not a number.").is_some(),
        "the sentence shows"
    );
    assert_eq!(
        h.state().model().paths().waypoints().poses()[0]
            .translation
            .x,
        x0
    );
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.event(egui::Event::Text(format!("{}", (x0 + 10.0).round())));
    h.run_steps(2);
    let x1 = h.state().model().paths().waypoints().poses()[0]
        .translation
        .x;
    assert_eq!(x1, (x0 + 10.0).round(), "a good value is taken");
}

/// Visits the two waypoints in joint space: Move turns on, the arm sets off toward
/// waypoint 1, goes on to waypoint 2 and rests there.
fn visit_the_waypoints_in_joint_space(h: &mut Harness<'_, ArmLabApp>) {
    // Visit in joint space: move turns on and the arm sets off toward waypoint 1, then
    // goes on to waypoint 2 and rests there.
    h.get_by_label("Joint space").click();
    h.get_by_label("Visit").click();
    h.run_steps(4);
    let model = h.state().model();
    assert!(model.motion().on(), "Visit turns Move on");
    assert!(model.paths().visit().is_some(), "the visit is under way");
    assert!(h.query_by_label("Visiting: waypoint 1 of 2.").is_some());
    assert!(model.motion().trail().len() >= 2, "the trail draws");
    let mut on_to_the_second = false;
    let mut frames = 4;
    while frames < 600 {
        let model = h.state().model();
        if model.paths().finished() && !model.motion().moving() {
            break;
        }
        on_to_the_second |= h.query_by_label("Visiting: waypoint 2 of 2.").is_some();
        h.run_steps(1);
        frames += 1;
    }
    let model = h.state().model();
    assert!(
        model.paths().finished() && !model.motion().moving(),
        "the visit ends within {frames} frames"
    );
    assert!(on_to_the_second, "waypoint 1 was reached, the arm went on");
    let last = model.paths().waypoints().poses()[1].translation.vector;
    let off = (model.fk().tool_position() - last).norm();
    assert!(off < 0.01, "the tool rests {off} mm from waypoint 2");
}

/// The DH table's cells that a person cannot read whole at this screen: past the visible
/// edge of `column` (sideways), or narrower than their text.
fn hidden_dh_cells(h: &Harness<'_, ArmLabApp>, column: egui::Rect) -> Vec<String> {
    let font = egui::TextStyle::Body.resolve(&h.ctx.global_style());
    let mut hidden = Vec::new();
    for node in h.query_all_by_role(Role::TextInput) {
        let rect = node.rect();
        let text = node.accesskit_node().value().unwrap_or_default();
        let width = h
            .ctx
            .fonts_mut(|f| f.layout_no_wrap(text.to_string(), font.clone(), egui::Color32::WHITE))
            .size()
            .x;
        if rect.left() < column.left() - 0.5 || rect.right() > column.right() + 0.5 {
            hidden.push(format!(
                "{text:?} at x {:.0}..{:.0}",
                rect.left(),
                rect.right()
            ));
        } else if rect.width() < width + 12.0 {
            hidden.push(format!(
                "{text:?} cut: {:.0} wide for {width:.0}",
                rect.width()
            ));
        }
    }
    hidden
}

/// What of the left column runs into the view (its unclipped rectangle crosses the view's
/// left edge: cut where a person sees it) or stands a letter per line, with the fold
/// `fold` open.
fn left_column_overflow(h: &Harness<'_, ArmLabApp>, fold: &str) -> Vec<String> {
    let view = h.state().viewport().rect().expect("the view was laid out");
    let mut found = Vec::new();
    for node in h.query_all(egui_kittest::kittest::by().include_labels()) {
        let Some(b) = node.accesskit_node().bounding_box() else {
            continue;
        };
        let r = egui::Rect::from_min_max(
            egui::pos2(b.x0 as f32, b.y0 as f32),
            egui::pos2(b.x1 as f32, b.y1 as f32),
        );
        let ak = node.accesskit_node();
        let text = ak.label().or(ak.value()).unwrap_or_default();
        // The top bar and the column's resize handle are not the column's content.
        if r.top() < view.top() || ak.role() == Role::Splitter || r.top() > view.bottom() {
            continue;
        }
        if r.left() < view.left() - 1.0 && r.right() > view.left() + 1.0 {
            found.push(format!("{fold}: {text:?} runs to x {:.0}", r.right()));
        }
        if text.chars().count() >= 3 && r.width() < 20.0 && r.height() > 40.0 {
            found.push(format!("{fold}: {text:?} a letter per line"));
        }
    }
    found
}
