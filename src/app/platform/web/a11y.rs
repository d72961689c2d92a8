//! The page for screen readers and the keyboard: egui's AccessKit tree mirrored into
//! invisible DOM elements over the canvas (eframe's web runner drops the tree), each at its
//! widget's place with its role, name, value and state. The browser builds its
//! accessibility tree from them, so a screen reader finds every control.
//!
//! The two sides stay in step both ways: a screen reader's focus or click on an element
//! becomes an AccessKit action request for egui, and while the DOM focus is in the mirror
//! its keys go to egui (Tab moves egui's focus, and the DOM focus follows it to that
//! widget's element). egui sends the whole tree every frame; an element is touched only
//! when what it shows changed (a hash of its role, name, value, state, bounds and children).

use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};

use egui::accesskit::{Action, ActionRequest, Node, NodeId, Role, Toggled, TreeId, TreeUpdate};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::wake;

/// One mirrored node: its element, the hash of what the element shows and its children.
struct Mirrored {
    el: web_sys::HtmlElement,
    shown: u64,
    children: u64,
    seen: u64,
}

/// The mirror's DOM side.
struct Mirror {
    root: web_sys::HtmlElement,
    nodes: HashMap<NodeId, Mirrored>,
    focus: Option<NodeId>,
    pass: u64,
}

/// The most time between two trees while nothing asks for one (a pointer drag's frames).
const TREE_EVERY_MS: f64 = 500.0;

thread_local! {
    /// When egui last built its tree for the mirror (`performance.now()`, ms).
    static LAST_TREE: std::cell::Cell<f64> = const { std::cell::Cell::new(f64::NEG_INFINITY) };
    static MIRROR: RefCell<Option<Mirror>> = const { RefCell::new(None) };
    /// Events from the page for egui's next pass (action requests, keys).
    static EVENTS: RefCell<Vec<egui::Event>> = const { RefCell::new(Vec::new()) };
    /// The live region: its element, what it said last and when (ms), and the canvas's
    /// name it was given.
    static LIVE: RefCell<Option<(web_sys::HtmlElement, String, f64, &'static str)>> = const { RefCell::new(None) };
    /// The reach sentence the live region said last, alone or in its whole sentence.
    static LIVE_REACH: RefCell<String> = const { RefCell::new(String::new()) };
    /// The nodes that label another (its `labelled_by`), and those found this pass.
    static LABELS: RefCell<Vec<NodeId>> = const { RefCell::new(Vec::new()) };
    static NEW_LABELS: RefCell<Vec<NodeId>> = const { RefCell::new(Vec::new()) };
    /// A script asked for the tree on the next pass (`window.armlab.mirrorNow()`).
    static TREE_ASKED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// This pass builds the tree for the mirror.
    static TREE_PASS: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Whether this pass builds egui's tree for the mirror.
pub fn tree_this_pass() -> bool {
    TREE_PASS.with(std::cell::Cell::get)
}

/// The next pass builds the tree and the mirror follows it, as after a key: for scripts
/// that read the mirror (`window.armlab.mirrorNow()`) without waiting for the next tree.
pub fn ask_for_tree() {
    TREE_ASKED.with(|t| t.set(true));
    wake();
}

/// The egui plugin that feeds the mirror from each pass's tree and the page's requests
/// back into egui.
struct Plugin;

impl egui::Plugin for Plugin {
    fn debug_name(&self) -> &'static str {
        "a11y mirror"
    }

    fn input_hook(&mut self, ctx: &egui::Context, input: &mut egui::RawInput) {
        let from_page = EVENTS.with(|e| {
            let mut e = e.borrow_mut();
            let any = !e.is_empty();
            input.events.append(&mut e);
            any
        });
        let from_page = super::skip::step(ctx, input) || TREE_ASKED.with(|t| t.take()) || from_page;
        if focus_in_mirror() {
            // The canvas lost the DOM focus to the mirror, yet the keys are egui's.
            input.focused = true;
        }
        // egui builds the tree (and the mirror follows it) on a pass with a key or a
        // request from the page, so that focus and values follow the keyboard at once, and
        // otherwise at most every TREE_EVERY_MS, and not while a pointer button is held:
        // a drag's frames cost what they cost without the mirror (screen readers and the
        // keyboard hold no button), the tree follows once the button is let go, and a
        // screen reader reads a value a fraction of a second late.
        let keys = input
            .events
            .iter()
            .any(|e| matches!(e, egui::Event::Key { .. }));
        let held = ctx.input(|i| i.pointer.any_down());
        let now = crate::app::platform::clock::now_ms();
        let last = LAST_TREE.with(std::cell::Cell::get);
        let tree = from_page || keys || (!held && now - last >= TREE_EVERY_MS);
        TREE_PASS.with(|t| t.set(tree));
        if tree {
            LAST_TREE.with(|t| t.set(now));
            ctx.enable_accesskit();
        } else {
            ctx.disable_accesskit();
            let wait = (TREE_EVERY_MS - (now - last)).max(0.0) as u64;
            ctx.request_repaint_after(std::time::Duration::from_millis(wait));
        }
    }

    fn output_hook(&mut self, ctx: &egui::Context, output: &mut egui::FullOutput) {
        let Some(update) = output.platform_output.accesskit_update.as_ref() else {
            return;
        };
        let scale = ctx.zoom_factor();
        let to_focus =
            MIRROR.with(|m| m.borrow_mut().as_mut().and_then(|m| m.apply(update, scale)));
        // Outside the borrow: focusing fires the mirror's focusin listener.
        if let Some(el) = to_focus {
            let _ = el.focus();
        }
    }
}

/// Starts the mirror: egui builds its AccessKit tree from now on, and the page gets the
/// mirror's container (`#armlab_a11y`) with its listeners.
///
/// A page that set `window.armlabNoMirror` before the app started goes without (the
/// frame-time benchmark compares the two).
pub fn install(ctx: &egui::Context) {
    let Some(window) = web_sys::window() else {
        return;
    };
    if js_sys::Reflect::get(&window, &"armlabNoMirror".into()).is_ok_and(|v| v.is_truthy()) {
        return;
    }
    let Some(doc) = window.document() else {
        return;
    };
    let Some(root) = doc
        .create_element("div")
        .ok()
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
    else {
        return;
    };
    root.set_id("armlab_a11y");
    if let Some(live) = doc
        .create_element("div")
        .ok()
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
    {
        live.set_id("armlab_live");
        // A polite live region read whole, without the status role: Orca's Say all read an
        // element with that role as "statusbar" alone, not its sentence; a plain element
        // with the two properties the role implies (polite, atomic) is read as text there
        // and announced the same way when it changes.
        let _ = live.set_attribute("aria-live", "polite");
        let _ = live.set_attribute("aria-atomic", "true");
        let _ = root.append_child(&live);
        LIVE.with(|l| *l.borrow_mut() = Some((live, String::new(), f64::NEG_INFINITY, "")));
    }
    let Some(body) = doc.body() else {
        return;
    };
    if body.append_child(&root).is_err() {
        return;
    }
    super::skip::install(&doc, &body);
    listen(&root, "click", |e| request(e, Action::Click));
    listen(&root, "focusin", |e| request(e, Action::Focus));
    listen(&root, "keydown", |e| key(e, true));
    listen(&root, "keyup", |e| key(e, false));
    MIRROR.with(|m| {
        *m.borrow_mut() = Some(Mirror {
            root,
            nodes: HashMap::new(),
            focus: None,
            pass: 0,
        });
    });
    ctx.enable_accesskit();
    ctx.add_plugin(Plugin);
}

/// The least time between two sentences of the live region, so that a drag is not read
/// out frame by frame.
const LIVE_EVERY_MS: f64 = 1000.0;

/// Keeps the live region saying what the 3D view shows: `words` is asked for at most once
/// a second and written only when it changed (a screen reader reads each change out).
/// While the target is `dragging` (by the pointer or held keys), only a change of `reach`
/// is said, and the whole of `words` once the drag ends: a long sentence every second
/// would drown the drag. The canvas gets `name` and `description` (in the interface's
/// language).
pub fn describe(
    ctx: &egui::Context,
    (name, description): (&'static str, &str),
    dragging: bool,
    reach: impl FnOnce() -> String,
    words: impl FnOnce() -> String,
) {
    LIVE.with(|l| {
        let mut l = l.borrow_mut();
        let Some((live, said, at, named)) = l.as_mut() else {
            return;
        };
        if !std::ptr::eq(*named, name)
            && let Some(canvas) = live
                .owner_document()
                .and_then(|d| d.get_element_by_id("armlab_canvas"))
        {
            let _ = canvas.set_attribute("aria-label", name);
            let _ = canvas.set_attribute("aria-description", description);
            // eframe's hidden text field beside the canvas takes the keys while no control
            // has them (the 3D view's): it is said by the view's name, not as a nameless
            // "entry".
            if let Some(keys) = canvas.next_element_sibling() {
                let _ = keys.set_attribute("aria-labelledby", "armlab_canvas");
            }
            *named = name;
        }
        let now = crate::app::platform::clock::now_ms();
        if now - *at < LIVE_EVERY_MS {
            // A change within the second is said when it ends.
            ctx.request_repaint_after(std::time::Duration::from_millis(LIVE_EVERY_MS as u64));
            return;
        }
        let (text, reach) = if dragging {
            let reach = reach();
            if reach.is_empty() || LIVE_REACH.with(|r| *r.borrow() == reach) {
                return;
            }
            (reach.clone(), reach)
        } else {
            (words(), reach())
        };
        if text != *said {
            live.set_text_content(Some(&text));
            *said = text;
            *at = now;
            LIVE_REACH.with(|r| *r.borrow_mut() = reach);
        }
    });
}

/// Adds a listener for the page's lifetime.
pub(super) fn listen(el: &web_sys::HtmlElement, name: &str, f: fn(web_sys::Event)) {
    let closure = Closure::<dyn FnMut(web_sys::Event)>::new(f);
    let _ = el.add_event_listener_with_callback(name, closure.as_ref().unchecked_ref());
    closure.forget();
}

/// Whether the DOM focus is on one of the mirror's elements.
fn focus_in_mirror() -> bool {
    web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.active_element())
        .is_some_and(|a| a.closest("#armlab_a11y").ok().flatten().is_some())
}

/// The node an event's element mirrors.
fn target_node(e: &web_sys::Event) -> Option<NodeId> {
    let el = e.target()?.dyn_into::<web_sys::Element>().ok()?;
    let el = el.closest("[data-n]").ok()??;
    el.get_attribute("data-n")?.parse().ok().map(NodeId)
}

/// Queues an action request for the node under `e` and wakes the app.
fn request(e: web_sys::Event, action: Action) {
    let Some(node) = target_node(&e) else {
        return;
    };
    let focused = MIRROR.with(|m| m.try_borrow().ok().and_then(|m| m.as_ref()?.focus));
    if action == Action::Focus && focused == Some(node) {
        return;
    }
    push(egui::Event::AccessKitActionRequest(ActionRequest {
        action,
        target_tree: TreeId::ROOT,
        target_node: node,
        data: None,
    }));
}

/// Queues an event for egui's next pass and wakes the app.
fn push(event: egui::Event) {
    EVENTS.with(|e| e.borrow_mut().push(event));
    wake();
}

/// A key in the mirror goes to egui as if the canvas had it; its default (scrolling the
/// page, the browser's own Tab) is kept from the page, except browser shortcuts.
fn key(e: web_sys::Event, pressed: bool) {
    let Some(e) = e.dyn_ref::<web_sys::KeyboardEvent>() else {
        return;
    };
    let name = e.key();
    let modifiers = egui::Modifiers {
        alt: e.alt_key(),
        ctrl: e.ctrl_key(),
        shift: e.shift_key(),
        mac_cmd: false,
        command: e.ctrl_key() || e.meta_key(),
    };
    let shortcut = modifiers.command && !matches!(name.as_str(), "a" | "A" | "z" | "Z");
    if !shortcut {
        e.prevent_default();
    }
    if let Some(key) = egui::Key::from_name(&name) {
        push(egui::Event::Key {
            key,
            physical_key: None,
            pressed,
            repeat: e.repeat(),
            modifiers,
        });
    }
    if pressed && !modifiers.command && name.chars().count() == 1 && name != " " {
        push(egui::Event::Text(name));
    }
}

impl Mirror {
    /// Brings the elements in step with `update` (egui's whole tree) at `scale` CSS pixels
    /// per point; returns the element to give the DOM focus when egui's focus moved while
    /// the DOM focus was in the mirror.
    fn apply(&mut self, update: &TreeUpdate, scale: f32) -> Option<web_sys::HtmlElement> {
        self.pass += 1;
        let pass = self.pass;
        let mut reorder = Vec::new();
        for (id, node) in &update.nodes {
            let (shown, children) = hashes(node, scale);
            let entry = self.nodes.entry(*id).or_insert_with(|| Mirrored {
                el: new_element(*id),
                shown: shown ^ 1,
                children: children ^ 1,
                seen: pass,
            });
            entry.seen = pass;
            if entry.shown != shown {
                entry.shown = shown;
                show(&entry.el, node, scale);
            }
            if entry.children != children {
                entry.children = children;
                reorder.push((*id, node.children().to_vec()));
            }
        }
        for (id, children) in reorder {
            let Some(parent) = self.nodes.get(&id).map(|m| m.el.clone()) else {
                continue;
            };
            if !children.is_empty() && parent.first_element_child().is_none() {
                // A text gaining parts (egui gives a label its text once it is drawn in
                // sight) keeps only theirs: its own words besides would name the control it
                // labels twice, "Preset Preset".
                parent.set_text_content(None);
            }
            for child in children {
                if let Some(c) = self.nodes.get(&child) {
                    let _ = parent.append_child(&c.el);
                }
            }
        }
        self.nodes.retain(|_, m| {
            let keep = m.seen == pass;
            if !keep {
                m.el.remove();
            }
            keep
        });
        if let Some(root) = update.tree.as_ref().and_then(|t| self.nodes.get(&t.root))
            && root.el.parent_element().is_none()
        {
            let _ = self.root.append_child(&root.el);
        }
        hide_new_labels();
        self.focus =
            Some(update.focus).filter(|f| self.nodes.get(f).is_some_and(|m| m.el.tab_index() >= 0));
        self.focus_target()
    }

    /// Where the DOM focus should go so that it follows egui's: the focused widget's
    /// element when the DOM focus is in the mirror, or on the canvas and the widget is no
    /// text field (eframe gives those its own text input); back to the canvas when egui's
    /// focus left the widgets.
    fn focus_target(&self) -> Option<web_sys::HtmlElement> {
        let active = web_sys::window()?.document()?.active_element()?;
        let in_mirror = active.closest("#armlab_a11y").ok().flatten().is_some();
        let on_canvas = active.id() == "armlab_canvas";
        let target = match self.focus.and_then(|f| self.nodes.get(&f)) {
            Some(m)
                if in_mirror
                    || (on_canvas && m.el.get_attribute("role").as_deref() != Some("textbox")) =>
            {
                m.el.clone()
            }
            None if in_mirror => active
                .owner_document()?
                .get_element_by_id("armlab_canvas")?
                .dyn_into()
                .ok()?,
            _ => return None,
        };
        (*target != active).then_some(target)
    }
}

/// A new element for node `id`.
fn new_element(id: NodeId) -> web_sys::HtmlElement {
    let doc = web_sys::window()
        .and_then(|w| w.document())
        .expect("the mirror runs in a page");
    let el = doc
        .create_element("div")
        .ok()
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
        .expect("a div is an HtmlElement");
    let _ = el.set_attribute("data-n", &id.0.to_string());
    el.set_id(&format!("a11y{}", id.0));
    el
}

/// The hashes of what node's element shows and of its children's order.
fn hashes(node: &Node, scale: f32) -> (u64, u64) {
    let mut h = std::hash::DefaultHasher::new();
    (node.role() as u32).hash(&mut h);
    node.label().hash(&mut h);
    node.value().hash(&mut h);
    node.description().hash(&mut h);
    node.labelled_by().iter().for_each(|n| n.0.hash(&mut h));
    (node.row_count(), node.column_count()).hash(&mut h);
    (node.row_index_text(), node.column_index_text()).hash(&mut h);
    for v in [
        node.numeric_value(),
        node.min_numeric_value(),
        node.max_numeric_value(),
    ] {
        v.map(f64::to_bits).hash(&mut h);
    }
    node.toggled().map(|t| t as u8).hash(&mut h);
    (node.is_expanded(), node.is_selected(), node.is_disabled()).hash(&mut h);
    node.supports_action(Action::Focus).hash(&mut h);
    px(node, scale).hash(&mut h);
    let mut c = std::hash::DefaultHasher::new();
    node.children().iter().for_each(|n| n.0.hash(&mut c));
    (h.finish(), c.finish())
}

/// The node's bounds in whole CSS pixels: left, top, width, height.
fn px(node: &Node, scale: f32) -> [i32; 4] {
    node.bounds().map_or([0; 4], |b| {
        let s = f64::from(scale);
        let r = |v: f64| (v * s).round() as i32;
        [r(b.x0), r(b.y0), r(b.x1 - b.x0), r(b.y1 - b.y0)]
    })
}

/// The ARIA role of an AccessKit role; `None` for a plain container or text.
fn aria_role(role: Role) -> Option<&'static str> {
    Some(match role {
        Role::Button | Role::DefaultButton | Role::DisclosureTriangle => "button",
        Role::CheckBox => "checkbox",
        Role::RadioButton => "radio",
        Role::Slider => "slider",
        Role::SpinButton => "spinbutton",
        Role::TextInput | Role::MultilineTextInput | Role::SearchInput => "textbox",
        Role::ComboBox => "combobox",
        Role::Link => "link",
        Role::Tab => "tab",
        Role::TabList => "tablist",
        Role::TabPanel => "tabpanel",
        Role::Menu => "menu",
        Role::MenuBar => "menubar",
        Role::MenuItem => "menuitem",
        Role::Table | Role::Grid => "table",
        Role::Row => "row",
        Role::Cell | Role::GridCell => "cell",
        Role::ColumnHeader => "columnheader",
        Role::RowHeader => "rowheader",
        Role::Heading => "heading",
        Role::Image => "img",
        Role::ProgressIndicator => "progressbar",
        Role::Window | Role::Dialog => "dialog",
        Role::Group | Role::Pane => "group",
        Role::Canvas => "img",
        // A column's edge: a focusable separator whose value is the column's width (the
        // arrow keys step it while it has the focus: panels::shell).
        Role::Splitter => "separator",
        _ => return None,
    })
}

/// Writes node's role, name, value, state and place into its element.
fn show(el: &web_sys::HtmlElement, node: &Node, scale: f32) {
    // A matrix stays a label in egui's tree (the UI tests read it so) with its rows and
    // columns counted: here its element holds a table.
    let matrix = node.row_count().is_some() && node.column_count().is_some();
    let name = node.label().unwrap_or_default();
    let role = if matrix {
        None
    } else if node.role() == Role::Window && name.is_empty() {
        // egui's root is a window with no title: a dialog without a name would be said
        // before every control; a titled window stays a dialog.
        None
    } else {
        aria_role(node.role())
    };
    let set = |k: &str, v: Option<&str>| {
        let _ = match v {
            Some(v) => el.set_attribute(k, v),
            None => el.remove_attribute(k),
        };
    };
    set("role", role);
    hide_labels(node);
    if matrix {
        table(el, node);
    } else if role.is_some() {
        set("aria-label", Some(name).filter(|n| !n.is_empty()));
        let by: Vec<String> = node
            .labelled_by()
            .iter()
            .map(|n| format!("a11y{}", n.0))
            .collect();
        let by = Some(by.join(" ")).filter(|b| !b.is_empty() && name.is_empty());
        set("aria-labelledby", by.as_deref());
    } else if node.children().is_empty() {
        // A plain text node's words are its text (egui keeps a label's words as its value).
        el.set_text_content(node.value().or(node.label()));
        let label = el.id().strip_prefix("a11y").and_then(|n| n.parse().ok());
        if label.is_some_and(|n| LABELS.with(|l| l.borrow().contains(&NodeId(n)))) {
            let _ = el.set_attribute("aria-hidden", "true");
        }
    }
    states(el, node, role);
    if node.supports_action(Action::Focus) {
        el.set_tab_index(0);
    } else {
        let _ = el.remove_attribute("tabindex");
    }
    let [x, y, w, h] = px(node, scale);
    el.style()
        .set_css_text(&format!("left:{x}px;top:{y}px;width:{w}px;height:{h}px"));
}

/// Sets (or, given `None`, removes) an attribute.
fn set(el: &web_sys::Element, k: &str, v: Option<&str>) {
    let _ = match v {
        Some(v) => el.set_attribute(k, v),
        None => el.remove_attribute(k),
    };
}

/// Writes node's value and states (checked, pressed, expanded, selected, disabled).
fn states(el: &web_sys::HtmlElement, node: &Node, role: Option<&str>) {
    let set = |k: &str, v: Option<&str>| set(el, k, v);
    // A separator is a column's resize handle: vertical, its value the column's share of
    // the window.
    let separator = role == Some("separator");
    let num = |v: Option<f64>| v.map(|v| format!("{v}"));
    let ranged = separator || matches!(role, Some("slider" | "spinbutton" | "progressbar"));
    set("aria-orientation", separator.then_some("vertical"));
    set(
        "aria-valuenow",
        num(node.numeric_value()).filter(|_| ranged).as_deref(),
    );
    set(
        "aria-valuemin",
        num(node.min_numeric_value()).filter(|_| ranged).as_deref(),
    );
    set(
        "aria-valuemax",
        num(node.max_numeric_value()).filter(|_| ranged).as_deref(),
    );
    set("aria-valuetext", node.value().filter(|_| ranged));
    // A text field's and a combo box's value is their text in the browser's tree (a combo
    // box's `aria-valuetext` is not read): the text typed, the choice shown.
    if matches!(role, Some("textbox" | "combobox")) && node.children().is_empty() {
        el.set_text_content(node.value());
    }
    let checked = node.toggled().map(|t| match t {
        Toggled::True => "true",
        Toggled::False => "false",
        Toggled::Mixed => "mixed",
    });
    set(
        if role == Some("button") {
            "aria-pressed"
        } else {
            "aria-checked"
        },
        checked,
    );
    set(
        "aria-expanded",
        node.is_expanded().map(|e| if e { "true" } else { "false" }),
    );
    let selected = node.is_selected().filter(|_| role == Some("tab"));
    set(
        "aria-selected",
        selected.map(|s| if s { "true" } else { "false" }),
    );
    set("aria-disabled", node.is_disabled().then_some("true"));
}

/// A matrix as a table inside its node's element: its caption (the node's description),
/// its column and row headers (the node's `column_index_text` and `row_index_text`, each
/// list separated by `|`), and its entries from its text (a label's value), the matrix as
/// plain text, row by row (`row_count` × `column_count` numbers).
///
/// A change of what it says makes the table anew and puts it in the old one's place at
/// once: for a screen reader that is two events, where writing each changed entry was two
/// per entry, and the fourteen tables of a six-joint arm changing together were more
/// events than Orca takes in at once (it drops what comes while its queue holds a hundred:
/// the live region's sentence too). The table moving (the panel scrolled) keeps it.
fn table(el: &web_sys::HtmlElement, node: &Node) {
    let (rows, columns) = (
        node.row_count().unwrap_or(0),
        node.column_count().unwrap_or(0),
    );
    let text = node.value().or(node.label()).unwrap_or_default();
    let entries: Vec<&str> = text.split_whitespace().collect();
    if rows == 0 || entries.len() != rows * columns {
        let _ = el.remove_attribute("data-said");
        el.set_text_content(Some(text));
        return;
    }
    let mut h = std::hash::DefaultHasher::new();
    (text, node.description(), rows, columns).hash(&mut h);
    (node.row_index_text(), node.column_index_text()).hash(&mut h);
    let said = h.finish().to_string();
    if el.get_attribute("data-said").as_deref() == Some(said.as_str()) {
        return;
    }
    let _ = el.set_attribute("data-said", &said);
    // Both lists of headers, or neither.
    let headed =
        headers(node.row_index_text(), rows).zip(headers(node.column_index_text(), columns));
    // The caption is the table's first line and its name, as an HTML table's caption is:
    // Orca's table commands say the caption, other screen readers and their lists of
    // tables the name. (Orca's Say all says both, as it does for any captioned HTML table;
    // hidden from reading, the caption was not said by Orca's table commands at all.)
    let caption_id = format!("{}c", el.id());
    let caption = escaped(node.description().unwrap_or_default());
    let mut html = format!(
        "<div role=table aria-labelledby={caption_id}><div role=caption id={caption_id}>{caption}</div>"
    );
    let cell = |html: &mut String, role: &str, words: &str| {
        html.push_str(&format!("<div role={role}>{}</div>", escaped(words)));
    };
    if let Some((_, column_headers)) = &headed {
        // Over the row headers, the header row's first cell heads their column: empty.
        html.push_str("<div role=row>");
        for words in std::iter::once(&"").chain(column_headers) {
            cell(&mut html, "columnheader", words);
        }
        html.push_str("</div>");
    }
    for (r, row) in entries.chunks(columns).enumerate() {
        html.push_str("<div role=row>");
        if let Some((row_headers, _)) = &headed {
            cell(&mut html, "rowheader", row_headers[r]);
        }
        for entry in row {
            cell(&mut html, "cell", entry);
        }
        html.push_str("</div>");
    }
    html.push_str("</div>");
    el.set_inner_html(&html);
}

/// `words` as HTML text: a robot file's joint names are in some captions.
fn escaped(words: &str) -> String {
    words
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The `n` headers in `list` (separated by `|`); `None` when there are not `n`.
fn headers(list: Option<&str>, n: usize) -> Option<Vec<&str>> {
    let headers: Vec<&str> = list?.split('|').collect();
    (headers.len() == n).then_some(headers)
}

/// Marks the plain labels that name node (its `labelled_by`) to be hidden from the tree,
/// so that a screen reader says a joint's name with its slider and its field, not once
/// more alone: a label shown later finds itself in `LABELS`, one already made is hidden by
/// [`hide_new_labels`] once the pass has put the elements in the page.
fn hide_labels(node: &Node) {
    for id in node.labelled_by() {
        if LABELS.with(|l| !l.borrow().contains(id)) {
            LABELS.with(|l| l.borrow_mut().push(*id));
            NEW_LABELS.with(|l| l.borrow_mut().push(*id));
        }
    }
}

/// Hides the labels [`hide_labels`] found this pass.
fn hide_new_labels() {
    let Some(doc) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    for id in NEW_LABELS.with(|l| std::mem::take(&mut *l.borrow_mut())) {
        if let Some(el) = doc.get_element_by_id(&format!("a11y{}", id.0)) {
            let _ = el.set_attribute("aria-hidden", "true");
        }
    }
}
