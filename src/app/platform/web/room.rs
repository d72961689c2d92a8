//! The lecture room's side of the page: whether the page came from a classroom server
//! (which marks the page it serves), the one WebSocket to it
//! (`classroom/ws`), reconnected with backoff while the page is in a class, and the
//! lecturer's control token kept in localStorage per class. The messages are
//! [`armlab_room`]'s JSON; what they mean is the app's classroom state.

use std::cell::{Cell, RefCell};

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::{wake, warn_on_failure};
use crate::app::platform::clock::now_ms;

/// The mark of a classroom server's page (crates/armlab-classroom adds it).
const MARK: &str = "meta[name=armlab-classroom]";
/// The server's WebSocket, beside the page.
const SOCKET_PATH: &str = "classroom/ws";
/// The localStorage key of a class's control token: this prefix and the join code.
const TOKEN_KEY: &str = "armlab.class.";
/// The first wait before reconnecting; it doubles per failure up to [`MAX_RETRY_MS`].
const FIRST_RETRY_MS: f64 = 500.0;
/// The longest wait before reconnecting (a restarted server is found within it).
const MAX_RETRY_MS: f64 = 8000.0;

/// What happened to the socket since the app last looked.
#[derive(Debug, Clone, PartialEq)]
pub enum SocketEvent {
    /// The connection opened.
    Opened,
    /// A text message arrived.
    Text(String),
    /// The connection closed (or failed to open).
    Closed,
}

/// The open (or opening) socket and the class generation it serves.
struct Socket {
    socket: web_sys::WebSocket,
    generation: u32,
    /// The handlers, kept as long as the socket may call them.
    _on_state: [Closure<dyn Fn()>; 2],
    _on_message: Closure<dyn Fn(web_sys::MessageEvent)>,
}

thread_local! {
    /// Whether the page came from a classroom server (`None` until the page looked).
    static AVAILABLE: Cell<Option<bool>> = const { Cell::new(None) };
    static SOCKET: RefCell<Option<Socket>> = const { RefCell::new(None) };
    /// Events of the current socket, oldest first.
    static EVENTS: RefCell<Vec<SocketEvent>> = const { RefCell::new(Vec::new()) };
    /// Failed connections in a row, and when the next try may start.
    static RETRY: Cell<(u32, f64)> = const { Cell::new((0, 0.0)) };
}

/// Notes whether a classroom server served the page: its `index.html` carries the mark
/// `<meta name="armlab-classroom">` in its head. A static host's page has none and asks
/// nothing (a request it answered with "not found" would be a console error on every
/// visit).
pub fn probe(window: &web_sys::Window) {
    let marked = window
        .document()
        .and_then(|d| d.query_selector(MARK).ok().flatten())
        .is_some();
    AVAILABLE.with(|a| a.set(Some(marked)));
}

/// Whether the page has looked for the classroom server's mark.
pub fn answered() -> bool {
    AVAILABLE.with(Cell::get).is_some()
}

/// Whether the page came from a classroom server (`false` until it answered).
pub fn available() -> bool {
    AVAILABLE.with(Cell::get).unwrap_or(false)
}

/// An address beside the page (`ws:`/`wss:` for the socket).
fn address(path: &str, socket: bool) -> Result<String, JsValue> {
    let base = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.base_uri().ok().flatten())
        .ok_or_else(|| JsValue::from_str("no document"))?;
    let url = web_sys::Url::new_with_base(path, &base)?;
    if socket {
        url.set_protocol(if url.protocol() == "https:" {
            "wss:"
        } else {
            "ws:"
        });
    }
    url.set_hash("");
    Ok(url.href())
}

/// Keeps the socket as the app wants it: none when `wanted` is `None`, else one serving
/// class generation `wanted` (a new generation closes the old socket), reopened after a
/// failure with a doubling wait. Returns what happened since the last call, and when the
/// app should look again (ms) while a reconnection waits.
pub fn keep(wanted: Option<u32>) -> (Vec<SocketEvent>, Option<f64>) {
    let current = SOCKET.with(|s| s.borrow().as_ref().map(|s| s.generation));
    if current.is_some() && current != wanted {
        close();
    }
    let mut events = EVENTS.with(|e| std::mem::take(&mut *e.borrow_mut()));
    if events.contains(&SocketEvent::Closed) {
        // Closed: the socket goes; the next try waits (none after a clean open).
        take_socket();
        let (failures, _) = RETRY.with(Cell::get);
        let wait = (FIRST_RETRY_MS * 2f64.powi(failures.min(5) as i32)).min(MAX_RETRY_MS);
        // A little randomness: a restarted server is not met by every page at once.
        let jitter = 1.0 + 0.25 * js_sys::Math::random();
        RETRY.with(|r| r.set((failures + 1, now_ms() + wait * jitter)));
        // Events of the closed socket after the close are stale.
        if let Some(at) = events.iter().position(|e| *e == SocketEvent::Closed) {
            events.truncate(at + 1);
        }
    }
    if events.contains(&SocketEvent::Opened) {
        RETRY.with(|r| r.set((0, 0.0)));
    }
    let Some(generation) = wanted else {
        return (events, None);
    };
    let open = SOCKET.with(|s| s.borrow().is_some());
    let (_, at) = RETRY.with(Cell::get);
    let now = now_ms();
    if !open {
        if now < at {
            return (events, Some(at - now));
        }
        if let Err(e) = connect(generation) {
            warn_on_failure::<()>(Err(e), "connecting to the classroom server");
            EVENTS.with(|e| e.borrow_mut().push(SocketEvent::Closed));
            return (events, Some(FIRST_RETRY_MS));
        }
    }
    (events, None)
}

/// Opens the socket for class generation `generation`.
fn connect(generation: u32) -> Result<(), JsValue> {
    let socket = web_sys::WebSocket::new(&address(SOCKET_PATH, true)?)?;
    let push = |event: SocketEvent| {
        EVENTS.with(|e| e.borrow_mut().push(event));
        wake();
    };
    let on_open = Closure::<dyn Fn()>::new(move || push(SocketEvent::Opened));
    let on_message =
        Closure::<dyn Fn(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
            if let Some(text) = e.data().as_string() {
                push(SocketEvent::Text(text));
            }
        });
    let on_close = Closure::<dyn Fn()>::new(move || push(SocketEvent::Closed));
    socket.set_onopen(Some(on_open.as_ref().unchecked_ref()));
    socket.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    // An error is followed by a close: the close alone counts.
    socket.set_onclose(Some(on_close.as_ref().unchecked_ref()));
    SOCKET.with(|s| {
        *s.borrow_mut() = Some(Socket {
            socket,
            generation,
            _on_state: [on_open, on_close],
            _on_message: on_message,
        })
    });
    Ok(())
}

/// Closes the socket, if any, and forgets its events. Its handlers are unset first: the
/// browser never calls them once they are dropped.
fn close() {
    if let Some(old) = take_socket() {
        warn_on_failure(old.close(), "closing the classroom connection");
    }
    EVENTS.with(|e| e.borrow_mut().clear());
    RETRY.with(|r| r.set((0, 0.0)));
}

/// Takes the socket out, its handlers unset.
fn take_socket() -> Option<web_sys::WebSocket> {
    let old = SOCKET.with(|s| s.borrow_mut().take())?;
    old.socket.set_onopen(None);
    old.socket.set_onmessage(None);
    old.socket.set_onclose(None);
    Some(old.socket)
}

/// Sends a text message on the open socket (dropped when none is open: the app resends
/// what matters when the connection opens again).
pub fn send(text: &str) {
    SOCKET.with(|s| {
        if let Some(s) = s.borrow().as_ref() {
            warn_on_failure(
                s.socket.send_with_str(text),
                "sending to the classroom server",
            );
        }
    });
}

/// The control token kept for class `code` in this browser, if any.
pub fn token(code: &str) -> Option<String> {
    web_sys::window()?
        .local_storage()
        .ok()
        .flatten()?
        .get_item(&format!("{TOKEN_KEY}{code}"))
        .ok()
        .flatten()
}

/// Keeps the control token of class `code` in this browser (a reload keeps control).
pub fn keep_token(code: &str, token: &str) {
    if let Some(Ok(Some(storage))) = web_sys::window().map(|w| w.local_storage()) {
        warn_on_failure(
            storage.set_item(&format!("{TOKEN_KEY}{code}"), token),
            "keeping the class's control in localStorage",
        );
    }
}
