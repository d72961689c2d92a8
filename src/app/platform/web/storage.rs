//! The address bar and localStorage: the link written as the state changes (at a pace a
//! drag can afford), the session kept for a reload as its JSON, and the links the page
//! navigates to.

use std::cell::{Cell, OnceCell, RefCell};

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::{wake, warn_on_failure};
use crate::app::platform::clock::now_ms;

/// The localStorage key of the last session (its JSON).
const STORAGE_KEY: &str = "armlab.session";

thread_local! {
    /// A hash the page asked the app to open (back/forward, `window.armlab.open`).
    static PENDING_HASH: RefCell<Option<String>> = const { RefCell::new(None) };
    /// The hash last written to the address bar and localStorage, and when.
    static STORED: RefCell<(String, f64)> = const { RefCell::new((String::new(), f64::NEG_INFINITY)) };
    /// A changed hash waiting for its turn to be written, with its session's JSON.
    static PENDING_STORE: RefCell<Option<(String, String)>> = const { RefCell::new(None) };
    /// The hash last written to localStorage, and when.
    static SAVED: RefCell<(String, f64)> = const { RefCell::new((String::new(), f64::NEG_INFINITY)) };
    /// The model's robot-change count at the last frame.
    static ROBOT_CHANGES: Cell<u64> = const { Cell::new(0) };
}

/// The session kept in localStorage (what the page opens without a link), or "".
pub fn stored_session(window: &web_sys::Window) -> String {
    window
        .local_storage()
        .ok()
        .flatten()
        .and_then(|s| s.get_item(STORAGE_KEY).ok().flatten())
        .unwrap_or_default()
}

/// The hash the page asked the app to open since the last call (back/forward, an edited
/// address, `window.armlab.open`), if any.
pub fn take_pending_hash() -> Option<String> {
    PENDING_HASH.with(|p| p.borrow_mut().take())
}

/// Asks the app to open `hash` on its next frame.
pub(super) fn open_later(hash: String) {
    PENDING_HASH.with(|p| *p.borrow_mut() = Some(hash));
    wake();
}

/// Writes the link hash into the address bar (without a history entry) and localStorage
/// when it has changed: not while a pointer is held, and at most four times a second.
/// localStorage alone (what a reload after a crash restores) is written at once after
/// every robot or DH-table change, and at most once a second during a drag.
///
/// `hash` builds the state's link hash, only when this needs it (at most once a call;
/// while a pointer is held, only when localStorage is due), and `make_json` the session's JSON
/// that localStorage keeps, only when it is written or waits to be. `robot_changes` is the
/// model's count of robot changes so far. The hash tells whether the state changed: the
/// JSON carries the same session.
///
/// A drag changes the hash every frame, and `history.replaceState` and localStorage are
/// synchronous calls that take 5–20 ms each in Chromium; writing them in every frame of a
/// drag would be most of the frame time. The release writes the final state; a change made
/// within the quarter second waits for a frame requested for then, and leaving the page
/// (`pagehide`) writes whatever is still waiting.
pub fn store(
    hash: impl FnOnce() -> String,
    make_json: impl Fn() -> String,
    robot_changes: u64,
    ctx: &egui::Context,
) {
    const INTERVAL_MS: f64 = 250.0;
    const HELD_INTERVAL_MS: f64 = 1000.0;
    let now = now_ms();
    let made = OnceCell::new();
    let json = || made.get_or_init(&make_json).clone();
    let held = ctx.input(|i| i.pointer.any_down());
    let robot_changed = ROBOT_CHANGES.with(|c| c.replace(robot_changes) != robot_changes);
    if held {
        let saved_at = SAVED.with(|s| s.borrow().1);
        if robot_changed || now - saved_at >= HELD_INTERVAL_MS {
            let hash = hash();
            if SAVED.with(|s| s.borrow().0 != hash) {
                write_storage(&hash, &json(), now);
            }
        }
        return;
    }
    let hash = hash();
    if robot_changed && SAVED.with(|s| s.borrow().0 != hash) {
        write_storage(&hash, &json(), now);
    }
    let wait = STORED.with(|s| {
        let s = s.borrow();
        (s.0 != hash).then_some(INTERVAL_MS - (now - s.1))
    });
    match wait {
        None => PENDING_STORE.with(|p| *p.borrow_mut() = None),
        Some(ms) if ms > 0.0 => {
            PENDING_STORE.with(|p| *p.borrow_mut() = Some((hash, json())));
            ctx.request_repaint_after(std::time::Duration::from_secs_f64(ms / 1e3));
        }
        Some(_) => {
            write_hash(&hash, json);
            PENDING_STORE.with(|p| *p.borrow_mut() = None);
            STORED.with(|s| {
                let mut s = s.borrow_mut();
                // The first write only records the opened state: it does not delay the
                // user's first change (a click and then a reload must keep the click).
                let at = if s.0.is_empty() {
                    f64::NEG_INFINITY
                } else {
                    now
                };
                *s = (hash, at);
            });
        }
    }
}

/// Writes the hash into the address bar, and the session's JSON (made by `json`) into
/// localStorage unless it already holds this state.
fn write_hash(hash: &str, json: impl FnOnce() -> String) {
    let Some(window) = web_sys::window() else {
        return;
    };
    match window.history() {
        Ok(history) => warn_on_failure(
            history.replace_state_with_url(&JsValue::NULL, "", Some(&format!("#{hash}"))),
            "writing the link into the address bar",
        ),
        Err(e) => warn_on_failure::<()>(Err(e), "reaching the browser history"),
    }
    if SAVED.with(|s| s.borrow().0 != hash) {
        write_storage(hash, &json(), now_ms());
    }
}

/// Keeps the session's JSON in localStorage (what the page opens without a link), noting
/// the hash of the state it holds.
fn write_storage(hash: &str, json: &str, now: f64) {
    let Some(window) = web_sys::window() else {
        return;
    };
    SAVED.with(|s| *s.borrow_mut() = (hash.to_string(), now));
    match window.local_storage() {
        Ok(Some(storage)) => warn_on_failure(
            storage.set_item(STORAGE_KEY, json),
            "keeping the session in localStorage",
        ),
        Ok(None) => log::warn!("keeping the session failed: this browser has no localStorage"),
        Err(e) => warn_on_failure::<()>(Err(e), "reaching localStorage"),
    }
}

/// Opens links the page navigates to (back/forward, an edited address) and writes a
/// waiting hash when the page is left.
pub fn install_hashchange(window: &web_sys::Window) {
    let on_change = Closure::<dyn Fn()>::new(|| {
        if let Some(hash) = web_sys::window().and_then(|w| w.location().hash().ok()) {
            open_later(hash);
        }
    });
    warn_on_failure(
        window.add_event_listener_with_callback("hashchange", on_change.as_ref().unchecked_ref()),
        "listening for link changes",
    );
    on_change.forget();
    let on_leave = Closure::<dyn Fn()>::new(|| {
        if let Some((hash, json)) = PENDING_STORE.with(|p| p.borrow_mut().take()) {
            write_hash(&hash, || json);
        }
    });
    warn_on_failure(
        window.add_event_listener_with_callback("pagehide", on_leave.as_ref().unchecked_ref()),
        "listening for the page being left",
    );
    on_leave.forget();
}
