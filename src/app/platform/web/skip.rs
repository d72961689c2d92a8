//! Skip links: the first things Tab reaches on the page, one to the 3D view and one to each
//! open panel. They are real links (`<a href>` in a `<nav>` before the canvas), so a screen
//! reader announces them as links and lists them with the page's links; the page's CSS
//! keeps them out of sight until one has the focus.
//!
//! Following one gives the canvas the DOM focus and then, over egui's next passes, the
//! keyboard to its place: the 3D view takes egui's focus from every widget (so the arrow
//! keys move the target), a panel gives it to its first control (its title row's close
//! button, then one Tab on), whose mirrored element the DOM focus follows.

use std::cell::{Cell, RefCell};

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::Closure;

/// Where a link leads: the 3D view, or a panel given by its first widget.
type Target = Option<egui::Id>;

/// The links on the page and where each leads.
struct Links {
    nav: web_sys::HtmlElement,
    /// The hash of what the links say, as `update` was given it.
    said: Option<u64>,
    targets: Vec<Target>,
}

/// A followed link's steps still to take in egui's passes.
#[derive(Clone, Copy)]
enum Pending {
    /// Take the focus from the widgets, or give it to this widget.
    Focus(Target),
    /// Then move it one widget on, as Tab does.
    Next,
}

thread_local! {
    static LINKS: RefCell<Option<Links>> = const { RefCell::new(None) };
    static PENDING: RefCell<Option<Pending>> = const { RefCell::new(None) };
    /// Whether a skip link has had the focus yet, and whether a widget had egui's focus
    /// at the last pass.
    static VISITED: Cell<bool> = const { Cell::new(false) };
    static WIDGET_FOCUSED: Cell<bool> = const { Cell::new(false) };
}

/// Puts the (still empty) list of skip links first in the page's body.
pub(super) fn install(doc: &web_sys::Document, body: &web_sys::HtmlElement) {
    let Some(nav) = doc
        .create_element("nav")
        .ok()
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
    else {
        return;
    };
    nav.set_id("armlab_skip");
    if body
        .insert_before(&nav, body.first_child().as_ref())
        .is_err()
    {
        return;
    }
    super::a11y::listen(&nav, "click", follow);
    super::a11y::listen(&nav, "focusin", |_| VISITED.with(|v| v.set(true)));
    // Before the keys reach the canvas's own listener.
    let first_tab = Closure::<dyn FnMut(web_sys::KeyboardEvent)>::new(first_tab);
    if let Some(window) = web_sys::window() {
        let _ = window.add_event_listener_with_callback_and_bool(
            "keydown",
            first_tab.as_ref().unchecked_ref(),
            true,
        );
    }
    first_tab.forget();
    LINKS.with(|l| {
        *l.borrow_mut() = Some(Links {
            nav,
            said: None,
            targets: Vec::new(),
        });
    });
}

/// Keeps the links in step with the frame: `label` names the list; `targets` is where each
/// link leads (`None`: the 3D view), `said` a hash of what they say, and `words` their
/// words, asked for only when `said` changed (the page is touched only then).
pub fn update(
    label: &str,
    (targets, said, words): (Vec<Target>, u64, impl FnOnce() -> Vec<String>),
) {
    LINKS.with(|l| {
        let mut l = l.borrow_mut();
        let Some(l) = l.as_mut() else {
            return;
        };
        l.targets = targets;
        if l.said == Some(said) {
            return;
        }
        l.said = Some(said);
        let _ = l.nav.set_attribute("aria-label", label);
        l.nav.set_inner_html("");
        let Some(doc) = l.nav.owner_document() else {
            return;
        };
        for (i, name) in words().iter().enumerate() {
            if let Ok(a) = doc.create_element("a") {
                let _ = a.set_attribute("href", "#armlab_canvas");
                let _ = a.set_attribute("data-skip", &i.to_string());
                a.set_text_content(Some(name));
                let _ = l.nav.append_child(&a);
            }
        }
    });
}

/// The page starts with the canvas focused (so that the keys work at once), which puts the
/// links behind it in the Tab order: until one of them has had the focus, Tab on the
/// canvas with no widget focused goes to the first link instead of egui's first widget.
fn first_tab(e: web_sys::KeyboardEvent) {
    let on_canvas = e
        .target()
        .and_then(|t| t.dyn_into::<web_sys::Element>().ok())
        .is_some_and(|t| t.id() == "armlab_canvas");
    if e.key() != "Tab"
        || e.shift_key()
        || e.alt_key()
        || e.ctrl_key()
        || e.meta_key()
        || !on_canvas
        || VISITED.with(Cell::get)
        || WIDGET_FOCUSED.with(Cell::get)
    {
        return;
    }
    let first = LINKS.with(|l| {
        l.borrow()
            .as_ref()?
            .nav
            .first_element_child()?
            .dyn_into::<web_sys::HtmlElement>()
            .ok()
    });
    if let Some(first) = first {
        e.prevent_default();
        e.stop_immediate_propagation();
        let _ = first.focus();
    }
}

/// A link followed (a click, or Enter on it): the page keeps its address (the link's hash
/// would open another session), the canvas gets the DOM focus and egui the rest.
fn follow(e: web_sys::Event) {
    let Some(i) = e
        .target()
        .and_then(|t| t.dyn_into::<web_sys::Element>().ok())
        .and_then(|t| t.closest("[data-skip]").ok().flatten())
        .and_then(|a| a.get_attribute("data-skip"))
        .and_then(|i| i.parse::<usize>().ok())
    else {
        return;
    };
    e.prevent_default();
    let Some(target) = LINKS.with(|l| l.borrow().as_ref()?.targets.get(i).copied()) else {
        return;
    };
    if let Some(canvas) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("armlab_canvas"))
        .and_then(|c| c.dyn_into::<web_sys::HtmlElement>().ok())
    {
        let _ = canvas.focus();
    }
    PENDING.with(|p| *p.borrow_mut() = Some(Pending::Focus(target)));
    super::wake();
}

/// A followed link's next step in this pass; returns whether there was one (the mirror
/// then follows egui's focus at once).
pub(super) fn step(ctx: &egui::Context, input: &mut egui::RawInput) -> bool {
    WIDGET_FOCUSED.with(|f| f.set(ctx.memory(|m| m.focused().is_some())));
    let Some(pending) = PENDING.with(|p| p.borrow_mut().take()) else {
        return false;
    };
    input.focused = true;
    match pending {
        Pending::Focus(None) => ctx.memory_mut(|m| {
            if let Some(id) = m.focused() {
                m.surrender_focus(id);
            }
        }),
        Pending::Focus(Some(id)) => {
            ctx.memory_mut(|m| m.request_focus(id));
            PENDING.with(|p| *p.borrow_mut() = Some(Pending::Next));
            ctx.request_repaint();
        }
        Pending::Next => {
            for pressed in [true, false] {
                input.events.push(egui::Event::Key {
                    key: egui::Key::Tab,
                    physical_key: None,
                    pressed,
                    repeat: false,
                    modifiers: egui::Modifiers::NONE,
                });
            }
        }
    }
    true
}
