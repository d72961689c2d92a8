//! The browser's zoom at 200 % on every screen: the page gets half the screen's CSS pixels
//! each way (twice the pixel ratio), and egui lays out one point per CSS pixel, so the app
//! at half the screen's size in points is what a person sees at 200 %. Nothing may be lost:
//! every named control of the accessibility tree is seen whole inside the window at some
//! point while a person opens the narrow layout's menu and each panel and scrolls each
//! column or sheet to its end (a table, which scrolls sideways, in part). The browser test
//! `web/tests/zoom.test.mjs` walks one of these screens in the page itself, through
//! Chromium's zoom and the DOM mirror.

use std::collections::BTreeMap;

use super::*;
use armlab_session::settings::PanelKind;
use egui_kittest::kittest::by;

/// The roles a person operates or reads entry by entry: those the mirror gives the page as
/// button, slider, spin button, check box, combo box, text box, radio, tab, link, menu item
/// or table.
const CONTROL_ROLES: [Role; 13] = [
    Role::Button,
    Role::DefaultButton,
    Role::DisclosureTriangle,
    Role::Slider,
    Role::SpinButton,
    Role::CheckBox,
    Role::ComboBox,
    Role::TextInput,
    Role::RadioButton,
    Role::Tab,
    Role::Link,
    Role::MenuItem,
    Role::Table,
];

const PANELS: [PanelKind; 5] = [
    PanelKind::Joints,
    PanelKind::Ik,
    PanelKind::Robot,
    PanelKind::Matrices,
    PanelKind::Motion,
];

/// Every named control met so far (by node and name), with where it was first seen whole;
/// `None` while it has not been.
type Walk = BTreeMap<String, Option<String>>;

/// Records the named controls of the tree now and which are seen whole; returns where
/// they are (to tell whether a scroll moved anything) and whether one not seen yet lies
/// past the window's right edge at a height in sight (the column scrolls sideways to it).
fn look(
    h: &Harness<'_, ArmLabApp>,
    walk: &mut Walk,
    window: egui::Rect,
    at: &str,
) -> (String, bool) {
    let mut places = String::new();
    let mut wide = false;
    let controls = by().predicate(|n| CONTROL_ROLES.contains(&n.role()));
    for node in h.query_all(controls) {
        let role = node.accesskit_node().role();
        let Some(name) = node.accesskit_node().label().filter(|n| !n.is_empty()) else {
            continue;
        };
        let rect = node.rect();
        let key = format!("{:?} {role:?} {name:?}", node.accesskit_node().id());
        let seen = if role == Role::Table {
            rect.intersects(window)
        } else {
            window.expand(0.5).contains_rect(rect) && rect.width() >= 1.0
        };
        let entry = walk.entry(key).or_insert(None);
        if seen && entry.is_none() {
            *entry = Some(at.to_string());
        }
        wide |= entry.is_none()
            && rect.right() > window.right() + 0.5
            && rect.top() < window.bottom()
            && rect.bottom() > 0.0;
        places.push_str(&format!(
            "{:?}@{:.0} ",
            node.accesskit_node().id(),
            rect.top()
        ));
    }
    (places, wide)
}

/// Turns the wheel by `delta` points over `over` in steps under egui's smoothing threshold,
/// so that the scroll lands in one frame, then lets the column take it.
fn scroll(h: &mut Harness<'_, ArmLabApp>, over: egui::Pos2, delta: egui::Vec2) {
    h.event(egui::Event::PointerMoved(over));
    let steps = (delta.length() / 7.5).ceil().max(1.0);
    for _ in 0..steps as usize {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: delta / steps,
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: egui::Modifiers::NONE,
        });
    }
    h.run_steps(2);
}

/// Scrolls the column or sheet under `over`, `tall` points of it in sight, to its end in
/// steps of three fifths of that (a control up to two fifths as tall is whole in one of two
/// neighbouring looks), and sideways where a control not seen yet lies past the right
/// edge; then back to its top.
fn scroll_through(
    h: &mut Harness<'_, ArmLabApp>,
    walk: &mut Walk,
    window: egui::Rect,
    (over, tall): (egui::Pos2, f32),
    at: &str,
) {
    let step = (tall * 0.6).max(60.0);
    let mut before = String::new();
    let mut steps = 0.0;
    for _ in 0..80 {
        scroll(h, over, egui::vec2(0.0, -step));
        steps += 1.0;
        let (after, wide) = look(h, walk, window, &format!("{at}, scrolled"));
        if wide {
            scroll(h, over, egui::vec2(-SIDEWAYS, 0.0));
            look(h, walk, window, &format!("{at}, scrolled sideways"));
            scroll(h, over, egui::vec2(SIDEWAYS, 0.0));
        }
        if after == before {
            break;
        }
        before = after;
    }
    scroll(h, over, egui::vec2(0.0, step * steps));
}

/// How far a column scrolls sideways to show what lies past its right edge: more than the
/// widest matrix is wider than the narrowest column.
const SIDEWAYS: f32 = 800.0;

/// The walk of one screen at 200 %: its controls and those never seen whole.
fn walk_at_200_percent(screen: [f32; 2]) -> (usize, Vec<String>) {
    let size = [screen[0] / 2.0, screen[1] / 2.0];
    let mut h = harness_at("#robot=ur10&q=0,-1.1,1.2,-1.5,-1.2,0.3&task=position", size);
    // Scrolls land at once, so each look sees where a step put the column.
    h.state_mut().model_mut().set_reduced_motion(true);
    let window = egui::Rect::from_min_size(egui::Pos2::ZERO, size.into());
    let mut walk = Walk::new();
    look(&h, &mut walk, window, "first");
    let view = h.state().viewport().rect().expect("the view was laid out");
    let tab = |h: &Harness<'_, ArmLabApp>, kind: PanelKind| {
        let name = format!("tab-{}", kind.id());
        let [x, y] = h.state().points().get(&name).expect("the tab is drawn");
        egui::pos2(x, y)
    };
    if tab(&h, PanelKind::Joints).y > view.bottom() {
        h.get_by_label("≡ Menu").click();
        h.run_steps(3);
        look(&h, &mut walk, window, "menu");
        h.key_press(egui::Key::Escape);
        h.run_steps(3);
        for kind in PANELS {
            let at = tab(&h, kind);
            click_at(&mut h, at);
            h.run_steps(2);
            assert_eq!(h.state().sheet(), Some(kind), "{size:?}: the sheet opened");
            let name = format!("{kind:?}");
            look(&h, &mut walk, window, &name);
            let view = h.state().viewport().rect().expect("the view was laid out");
            let sheet = (view.bottom(), at.y.min(size[1]) - 20.0);
            let over = egui::pos2(size[0] / 2.0, (sheet.0 + sheet.1) / 2.0);
            scroll_through(&mut h, &mut walk, window, (over, sheet.1 - sheet.0), &name);
            click_at(&mut h, at);
            h.run_steps(2);
        }
    } else {
        let middle = view.center().y;
        let left = egui::pos2(view.left() / 2.0, middle);
        let right = egui::pos2((view.right() + size[0]) / 2.0, middle);
        scroll_through(
            &mut h,
            &mut walk,
            window,
            (left, view.height()),
            "left column",
        );
        scroll_through(
            &mut h,
            &mut walk,
            window,
            (right, view.height()),
            "right column",
        );
    }
    let lost = walk
        .iter()
        .filter(|(_, at)| at.is_none())
        .map(|(key, _)| key.clone())
        .collect();
    (walk.len(), lost)
}

/// The walk of `SCREENS[i]` asserted: its controls counted and each seen whole. One test
/// per screen, so that the walks (several seconds each) run beside the other tests.
fn every_control_is_seen_whole_at_200_percent(i: usize) {
    let (screen, _) = SCREENS[i];
    let (controls, never) = walk_at_200_percent(screen);
    println!("ZOOM200 {screen:?}: {controls} controls, never seen whole: {never:?}");
    assert!(controls >= 40, "{screen:?}: {controls} named controls");
    assert!(
        never.is_empty(),
        "{screen:?}: never seen whole at 200 %: {never:#?}"
    );
}

// The six tests below are SCREENS, in its order.
const _: () = assert!(SCREENS.len() == 6);

#[test]
fn at_200_percent_zoom_every_control_is_seen_whole_on_a_1024x768_projector() {
    every_control_is_seen_whole_at_200_percent(0);
}

#[test]
fn at_200_percent_zoom_every_control_is_seen_whole_on_a_1280x720_projector() {
    every_control_is_seen_whole_at_200_percent(1);
}

#[test]
fn at_200_percent_zoom_every_control_is_seen_whole_on_a_1366x768_laptop() {
    every_control_is_seen_whole_at_200_percent(2);
}

#[test]
fn at_200_percent_zoom_every_control_is_seen_whole_on_a_1920x1080_laptop() {
    every_control_is_seen_whole_at_200_percent(3);
}

#[test]
fn at_200_percent_zoom_every_control_is_seen_whole_on_a_portrait_tablet() {
    every_control_is_seen_whole_at_200_percent(4);
}

#[test]
fn at_200_percent_zoom_every_control_is_seen_whole_on_a_phone() {
    every_control_is_seen_whole_at_200_percent(5);
}
