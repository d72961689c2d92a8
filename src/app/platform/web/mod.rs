//! The browser side, below the app: the page's message box and crash screen, the canvas's
//! size, and the helpers its submodules share (waking the app, setting a page object's
//! field, a thrown value's words). The app in the page (`crate::app::page`) starts eframe
//! and feeds these modules each frame; nothing here knows the app.
//!
//! - [`storage`]: the address bar and localStorage.
//! - [`hook`]: `window.armlab`, the browser tests' hook.
//! - [`files`]: downloads, the file chooser, dropped files.
//! - [`modules`]: the lazily loaded modules (URDF, collisions, symbolic matrices, QR codes).
//! - [`room`]: the lecture room's connection to a classroom server.
//! - [`a11y`]: the accessibility tree mirrored into the page for screen readers.
//! - [`skip`]: the skip links to the 3D view and to each open panel.

pub mod a11y;
pub mod files;
pub mod hook;
pub mod modules;
pub mod room;
pub mod skip;
pub mod storage;

use std::cell::{Cell, RefCell};

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

thread_local! {
    /// The page's canvas, looked up once.
    static CANVAS: RefCell<Option<Option<web_sys::HtmlCanvasElement>>> = const { RefCell::new(None) };
    /// The egui context, to wake the app when something arrives from the page.
    static CTX: RefCell<Option<egui::Context>> = const { RefCell::new(None) };
    /// The interface language at the last frame, for the crash sentence.
    static LANG: Cell<armlab_text::Lang> = const { Cell::new(armlab_text::Lang::En) };
}

/// Keeps what the page's callbacks need from the frame: the egui context (to wake the app
/// when something arrives from the page) and the interface language (for the crash
/// sentence and the URDF module's sentences), and gives the page that language when it
/// changes.
pub fn remember_frame(ctx: &egui::Context, lang: armlab_text::Lang) {
    CTX.with(|c| {
        if c.borrow().is_none() {
            *c.borrow_mut() = Some(ctx.clone());
        }
    });
    if LANG.with(|l| l.replace(lang)) != lang {
        page_language(lang);
    }
}

/// Gives the page the interface's language: `<html lang>`, so that a screen reader's
/// synthesiser reads the words with that language's rules, and the document's title.
fn page_language(lang: armlab_text::Lang) {
    let Some(doc) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    if let Some(html) = doc.document_element() {
        warn_on_failure(
            html.set_attribute("lang", lang.id()),
            "setting the page's language",
        );
    }
    doc.set_title(armlab_text::text(lang, armlab_text::Key::PageTitle));
}

/// The interface language at the last frame.
fn lang() -> armlab_text::Lang {
    LANG.with(Cell::get)
}

/// Logs a failed browser call as a console warning (the app goes on without it).
fn warn_on_failure<T>(result: Result<T, JsValue>, what: &str) {
    if let Err(e) = result {
        log::warn!("{what} failed: {e:?}");
    }
}

/// Asks for a frame, once the app has drawn one (something arrived from the page).
fn wake() {
    CTX.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint();
        }
    });
}

/// Shows `text` in the page's message box over the canvas (an error in its error style),
/// or hides the box when `text` is empty.
pub fn set_message(text: &str, error: bool) {
    let Some(doc) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    if let Some(el) = doc.get_element_by_id("armlab_message") {
        el.set_text_content(Some(text));
        el.set_class_name(if error { "error" } else { "" });
        if let Some(el) = el.dyn_ref::<web_sys::HtmlElement>() {
            warn_on_failure(
                el.style()
                    .set_property("display", if text.is_empty() { "none" } else { "flex" }),
                "showing the page's message",
            );
        }
    }
}

/// Shows a sentence and a Reload button over the frozen app when the app panics.
///
/// The page's wasm is built with `panic = "abort"`: after the panic hook the module traps
/// and eframe stops drawing, so the hook is the last moment code of ours runs. It chains
/// eframe's hook (which logs the panic), then writes the message with plain DOM calls.
/// The session is already in localStorage (written after every robot change and during
/// drags), and the button puts it back into the address bar before reloading: the address
/// bar may be up to a quarter second behind.
pub fn install_crash_screen() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        previous(info);
        let lang = lang();
        let what: String = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic".to_string());
        let what = armlab_text::echo::text_within(&what, 80);
        show_crash(
            &armlab_text::fill(lang, armlab_text::Key::CrashSentence, &[&what]),
            armlab_text::text(lang, armlab_text::Key::CrashReload),
        );
    }));
}

/// The crash sentence and its Reload button in the page's message box.
fn show_crash(sentence: &str, reload: &str) {
    let Some(doc) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    let Some(el) = doc.get_element_by_id("armlab_message") else {
        return;
    };
    set_message(sentence, true);
    el.set_class_name("error crash");
    let Ok(button) = doc.create_element("button") else {
        return;
    };
    button.set_id("armlab_reload");
    button.set_text_content(Some(reload));
    // Without a link the page opens the session in localStorage, which is newer than the
    // address bar (written at most four times a second, and not while a pointer is held).
    let restore = js_sys::Function::new_no_args(
        "history.replaceState(null, '', location.pathname + location.search); location.reload();",
    );
    if let Some(button) = button.dyn_ref::<web_sys::HtmlElement>() {
        button.set_onclick(Some(&restore));
    }
    warn_on_failure(el.append_child(&button), "showing the Reload button");
}

/// Measures the canvas once per frame: keeps its backing store at its CSS size times the
/// device pixel ratio and returns its width in CSS pixels. Asks for another frame when it
/// resized the canvas (the next frame draws at the new size).
///
/// eframe sizes the backing store from the ResizeObserver's `devicePixelContentBoxSize`;
/// where a browser reports that size in CSS pixels (Chromium's device emulation does), the
/// canvas gets a ratio's worth too few pixels, and since eframe maps the pointer from CSS
/// pixels but the screen from canvas pixels, the pointer and the picture disagree (at
/// ratio 2 the UI is drawn twice too large and a tap lands at half its place). A real
/// device reports device pixels, within a pixel of the product, and is left alone.
pub fn measure_canvas(ctx: &egui::Context) -> Option<f32> {
    let canvas = CANVAS.with(|c| {
        c.borrow_mut()
            .get_or_insert_with(|| {
                web_sys::window()
                    .and_then(|w| w.document())
                    .and_then(|d| d.get_element_by_id("armlab_canvas"))
                    .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
            })
            .clone()
    })?;
    let (css_w, css_h) = (canvas.client_width(), canvas.client_height());
    let dpr = ctx.native_pixels_per_point().unwrap_or(1.0) as f64;
    let want = |css: i32| (f64::from(css) * dpr).round() as u32;
    let (w, h) = (want(css_w), want(css_h));
    let off = |have: u32, want: u32| have.abs_diff(want) > 2;
    if w > 0 && h > 0 && (off(canvas.width(), w) || off(canvas.height(), h)) {
        canvas.set_width(w);
        canvas.set_height(h);
        ctx.request_repaint();
    }
    (css_w > 0).then_some(css_w as f32)
}

/// Whether the user's system asks for reduced motion
/// (`(prefers-reduced-motion: reduce)`); natively there is no such setting.
pub fn prefers_reduced_motion(window: &web_sys::Window) -> bool {
    window
        .match_media("(prefers-reduced-motion: reduce)")
        .ok()
        .flatten()
        .is_some_and(|m| m.matches())
}

/// Sets `object[key] = value`, logging a failure.
fn set_field(object: &JsValue, key: &str, value: &JsValue) {
    warn_on_failure(
        js_sys::Reflect::set(object, &key.into(), value),
        &format!("setting {key} on a page object"),
    );
}

/// A thrown JS value's words: an `Error`'s message, a string, the value as JSON, or its
/// type. Not `{:?}`: the page is built with `Debug` printing nothing.
pub(crate) fn js_error_text(e: &JsValue) -> String {
    e.dyn_ref::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .or_else(|| e.as_string())
        .or_else(|| js_sys::JSON::stringify(e).ok()?.as_string())
        .or_else(|| e.js_typeof().as_string())
        .unwrap_or_default()
}
