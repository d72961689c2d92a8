//! The browser side: starting eframe on the canvas, the loading and error messages, the
//! URL hash and localStorage, and the `window.armlab` test hook; downloads and uploads are
//! in [`files`], the lazily loaded modules in [`modules`].

pub mod files;
pub mod modules;

use std::cell::{Cell, RefCell};

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use crate::app::ArmLabApp;

const STORAGE_KEY: &str = "armlab.session";

/// What `window.armlab` reads, written each frame.
struct Published {
    /// `state()`'s JSON.
    state: String,
    /// Named screen points in egui points.
    points: Vec<(String, [f32; 2])>,
    /// The 3D view's rectangle (x, y, width, height) in egui points.
    view_rect: Option<[f32; 4]>,
    /// CSS pixels per egui point.
    css_per_point: f32,
}

thread_local! {
    static HOOK: RefCell<Published> = const {
        RefCell::new(Published { state: String::new(), points: Vec::new(), view_rect: None, css_per_point: 1.0 })
    };
    /// Whether a script has asked for `window.armlab.state()`: until then no frame builds
    /// its JSON (about 30 µs natively, 7 % of a dragging frame's app time), which no
    /// visitor reads.
    static STATE_WANTED: Cell<bool> = const { Cell::new(false) };
    /// Recent frame times for `window.armlab.frameTimes()`.
    static FRAMES: RefCell<Vec<crate::app::platform::clock::FrameTime>> = const { RefCell::new(Vec::new()) };
    /// A hash the page asked the app to open (back/forward, `window.armlab.open`).
    static PENDING_HASH: RefCell<Option<String>> = const { RefCell::new(None) };
    /// The page's canvas, looked up once.
    static CANVAS: RefCell<Option<Option<web_sys::HtmlCanvasElement>>> = const { RefCell::new(None) };
    /// The egui context, to wake the app when something arrives from the page.
    static CTX: RefCell<Option<egui::Context>> = const { RefCell::new(None) };
    /// The hash last written to the address bar and localStorage, and when.
    static STORED: RefCell<(String, f64)> = const { RefCell::new((String::new(), f64::NEG_INFINITY)) };
    /// A changed hash waiting for its turn to be written.
    static PENDING_STORE: RefCell<Option<String>> = const { RefCell::new(None) };
    /// The hash last written to localStorage, and when.
    static SAVED: RefCell<(String, f64)> = const { RefCell::new((String::new(), f64::NEG_INFINITY)) };
    /// The model's robot-change count at the last frame.
    static ROBOT_CHANGES: Cell<u64> = const { Cell::new(0) };
    /// The interface language at the last frame, for the crash sentence.
    static LANG: Cell<armlab_text::Lang> = const { Cell::new(armlab_text::Lang::En) };
    /// Set by `window.armlab.panicForTest()`: the next frame panics.
    static PANIC_REQUESTED: Cell<bool> = const { Cell::new(false) };
    /// `performance.now()` at the first drawn frame.
    static FIRST_FRAME: RefCell<Option<f64>> = const { RefCell::new(None) };
}

/// Logs a failed browser call as a console warning (the app goes on without it).
fn warn_on_failure<T>(result: Result<T, JsValue>, what: &str) {
    if let Err(e) = result {
        log::warn!("{what} failed: {e:?}");
    }
}

/// The interface language at the last frame.
fn lang() -> armlab_text::Lang {
    LANG.with(Cell::get)
}

fn wake() {
    CTX.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint();
        }
    });
}

fn set_message(text: &str, error: bool) {
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
fn install_crash_screen() {
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
    let restore = js_sys::Function::new_no_args(&format!(
        "var s = null; try {{ s = localStorage.getItem('{STORAGE_KEY}'); }} catch (e) {{}} \
         if (s) history.replaceState(null, '', '#' + s); location.reload();"
    ));
    if let Some(button) = button.dyn_ref::<web_sys::HtmlElement>() {
        button.set_onclick(Some(&restore));
    }
    warn_on_failure(el.append_child(&button), "showing the Reload button");
}

/// Starts the app on `#armlab_canvas`; replaces the loading text by the app, or by a
/// sentence when the browser has no WebGL2 (the page draws through wgpu's WebGL2 backend).
pub fn start() {
    eframe::WebLogger::init(log::LevelFilter::Warn).ok();
    wasm_bindgen_futures::spawn_local(async {
        let Some(window) = web_sys::window() else {
            return;
        };
        let Some(canvas) = window
            .document()
            .and_then(|d| d.get_element_by_id("armlab_canvas"))
            .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
        else {
            set_message("ArmLab could not find its canvas on this page.", true);
            return;
        };
        let hash = window.location().hash().unwrap_or_default();
        let stored = window
            .local_storage()
            .ok()
            .flatten()
            .and_then(|s| s.get_item(STORAGE_KEY).ok().flatten())
            .unwrap_or_default();
        // A link wins; without one, the last session returns.
        let opening = if hash.trim_start_matches('#').is_empty() {
            stored
        } else {
            hash
        };
        let options = eframe::WebOptions {
            // eframe listens to touchmove on the document, where browsers make listeners
            // passive: preventing a pointer move's default there only logs "Unable to
            // preventDefault inside passive event listener". The canvas's CSS
            // `touch-action: none` already keeps the page from scrolling or zooming.
            should_prevent_default: Box::new(|e| !matches!(e, egui::Event::PointerMoved(_))),
            ..eframe::WebOptions::default()
        };
        let preferences = browser_preferences(&window);
        // WebRunner::new installs eframe's panic hook; ours runs after it.
        let runner = eframe::WebRunner::new();
        install_crash_screen();
        let result = runner
            .start(
                canvas,
                options,
                Box::new(move |cc| Ok(Box::new(ArmLabApp::new_with(cc, &opening, preferences)))),
            )
            .await;
        match result {
            Ok(()) => {
                set_message("", false);
                install_hook(&window);
                install_hashchange(&window);
            }
            Err(e) => {
                let detail = e.as_string().unwrap_or_else(|| format!("{e:?}"));
                set_message(
                    &format!(
                        "ArmLab needs WebGL2 to draw the robot, and this browser does not offer it \
                         (or has it switched off). Try a current Chrome, Edge, Firefox or Safari, or enable \
                         hardware acceleration. Details: {detail}"
                    ),
                    true,
                );
            }
        }
    });
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

/// The browser's languages (`navigator.languages`) and whether its main pointer is a
/// finger (`(pointer: coarse)`).
fn browser_preferences(window: &web_sys::Window) -> crate::app::Preferences {
    let navigator = window.navigator();
    let tags: Vec<String> = navigator
        .languages()
        .iter()
        .filter_map(|v| v.as_string())
        .chain(navigator.language())
        .collect();
    let touch = window
        .match_media("(pointer: coarse)")
        .ok()
        .flatten()
        .is_some_and(|m| m.matches());
    crate::app::Preferences {
        lang: armlab_text::Lang::from_tags(tags.iter().map(String::as_str)),
        touch,
    }
}

/// Writes the link hash into the address bar (without a history entry) and localStorage
/// when it has changed: not while a pointer is held, and at most four times a second.
/// localStorage alone (what a reload after a crash restores) is written at once after
/// every robot or DH-table change, and at most once a second during a drag.
///
/// A drag changes the hash every frame, and `history.replaceState` and localStorage are
/// synchronous calls that take 5–20 ms each in Chromium; writing them in every frame of a
/// drag would be most of the frame time. The release writes the final state; a change made
/// within the quarter second waits for a frame requested for then, and leaving the page
/// (`pagehide`) writes whatever is still waiting.
pub fn store_hash(app: &ArmLabApp, ctx: &egui::Context) {
    const INTERVAL_MS: f64 = 250.0;
    const HELD_INTERVAL_MS: f64 = 1000.0;
    let now = crate::app::platform::clock::now_ms();
    let held = ctx.input(|i| i.pointer.any_down());
    let changes = app.model().robot_changes();
    let robot_changed = ROBOT_CHANGES.with(|c| c.replace(changes) != changes);
    if held {
        let saved_at = SAVED.with(|s| s.borrow().1);
        if robot_changed || now - saved_at >= HELD_INTERVAL_MS {
            let hash = app.hash();
            if SAVED.with(|s| s.borrow().0 != hash) {
                write_storage(&hash, now);
            }
        }
        return;
    }
    let hash = app.hash();
    if robot_changed && SAVED.with(|s| s.borrow().0 != hash) {
        write_storage(&hash, now);
    }
    let wait = STORED.with(|s| {
        let s = s.borrow();
        (s.0 != hash).then_some(INTERVAL_MS - (now - s.1))
    });
    match wait {
        None => PENDING_STORE.with(|p| *p.borrow_mut() = None),
        Some(ms) if ms > 0.0 => {
            PENDING_STORE.with(|p| *p.borrow_mut() = Some(hash));
            ctx.request_repaint_after(std::time::Duration::from_secs_f64(ms / 1e3));
        }
        Some(_) => {
            write_hash(&hash);
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

fn write_hash(hash: &str) {
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
        write_storage(hash, crate::app::platform::clock::now_ms());
    }
}

/// Keeps the session in localStorage (what the page opens without a link).
fn write_storage(hash: &str, now: f64) {
    let Some(window) = web_sys::window() else {
        return;
    };
    SAVED.with(|s| *s.borrow_mut() = (hash.to_string(), now));
    match window.local_storage() {
        Ok(Some(storage)) => warn_on_failure(
            storage.set_item(STORAGE_KEY, hash),
            "keeping the session in localStorage",
        ),
        Ok(None) => log::warn!("keeping the session failed: this browser has no localStorage"),
        Err(e) => warn_on_failure::<()>(Err(e), "reaching localStorage"),
    }
}

/// Publishes the state and screen points for `window.armlab`, and opens a hash the page
/// asked for; its own time goes into the frame's [`crate::app::platform::clock::FrameTime::hook_ms`].
pub fn publish(app: &mut ArmLabApp, ctx: &egui::Context) {
    let start = crate::app::platform::clock::now_ms();
    CTX.with(|c| {
        if c.borrow().is_none() {
            *c.borrow_mut() = Some(ctx.clone());
        }
    });
    LANG.with(|l| l.set(app.model().settings().lang));
    if PANIC_REQUESTED.with(Cell::take) {
        panic!("a panic asked for by window.armlab.panicForTest()");
    }
    if let Some(hash) = PENDING_HASH.with(|p| p.borrow_mut().take()) {
        app.open_hash(&hash);
    }
    // egui points to CSS pixels: the canvas fills the page from (0, 0).
    let css_per_point = ctx.pixels_per_point() / ctx.native_pixels_per_point().unwrap_or(1.0);
    let state = if STATE_WANTED.with(Cell::get) {
        app.state_json()
    } else {
        String::new()
    };
    HOOK.with(|h| {
        *h.borrow_mut() = Published {
            state,
            points: app.points().all().to_vec(),
            view_rect: app
                .viewport()
                .rect()
                .map(|r| [r.min.x, r.min.y, r.width(), r.height()]),
            css_per_point,
        }
    });
    FIRST_FRAME.with(|f| {
        if f.borrow().is_none() && app.viewport().rendered() {
            *f.borrow_mut() = Some(crate::app::platform::clock::now_ms());
        }
    });
    if let Some(mut t) = app.frame_times().back().copied() {
        t.hook_ms = crate::app::platform::clock::now_ms() - start;
        FRAMES.with(|f| {
            let mut f = f.borrow_mut();
            if f.len() >= 5000 {
                f.remove(0);
            }
            f.push(t);
        });
    }
}

fn install_hook(window: &web_sys::Window) {
    let obj = js_sys::Object::new();
    // The first call asks for a frame that builds the state, and gets "" (as before the
    // first frame): scripts wait for a state that has `rendered`.
    let state = Closure::<dyn Fn() -> String>::new(|| {
        if !STATE_WANTED.with(|w| w.replace(true)) {
            wake();
        }
        HOOK.with(|h| h.borrow().state.clone())
    });
    set_field(&obj, "state", &state.into_js_value());
    set_field(&obj, "screenPoint", &screen_point_fn());
    set_field(&obj, "frameTimes", &frame_times_fn());
    set_field(&obj, "viewRect", &view_rect_fn());
    let open = Closure::<dyn Fn(String)>::new(|hash: String| {
        PENDING_HASH.with(|p| *p.borrow_mut() = Some(hash));
        wake();
    });
    set_field(&obj, "open", &open.into_js_value());
    let first = Closure::<dyn Fn() -> JsValue>::new(|| {
        FIRST_FRAME.with(|f| f.borrow().map_or(JsValue::NULL, JsValue::from))
    });
    set_field(&obj, "firstFrameAt", &first.into_js_value());
    // The wasm memory's size in bytes (for the soak test: it only grows, in steps).
    let memory = Closure::<dyn Fn() -> JsValue>::new(|| {
        js_sys::Reflect::get(&wasm_bindgen::memory(), &"buffer".into())
            .and_then(|buffer| js_sys::Reflect::get(&buffer, &"byteLength".into()))
            .unwrap_or(JsValue::NULL)
    });
    set_field(&obj, "memoryBytes", &memory.into_js_value());
    install_workspace_benchmark(&obj);
    install_collision_benchmark(&obj);
    // For the browser test of the crash screen: the next frame panics.
    let panic = Closure::<dyn Fn()>::new(|| {
        PANIC_REQUESTED.with(|p| p.set(true));
        wake();
    });
    set_field(&obj, "panicForTest", &panic.into_js_value());
    set_field(window, "armlab", &obj);
}

/// `window.armlab.screenPoint(name)`: the named point's CSS position `{x, y}`, or null.
fn screen_point_fn() -> JsValue {
    Closure::<dyn Fn(String) -> JsValue>::new(|name: String| {
        HOOK.with(|h| {
            let h = h.borrow();
            match h.points.iter().find(|(n, _)| *n == name) {
                Some((_, p)) => {
                    let o = js_sys::Object::new();
                    let k = h.css_per_point;
                    set_field(&o, "x", &((p[0] * k) as f64).into());
                    set_field(&o, "y", &((p[1] * k) as f64).into());
                    o.into()
                }
                None => JsValue::NULL,
            }
        })
    })
    .into_js_value()
}

/// `window.armlab.frameTimes()`: the frames' times since the last call (and forgets them).
fn frame_times_fn() -> JsValue {
    Closure::<dyn Fn() -> js_sys::Array>::new(|| {
        let taken = FRAMES.with(|f| std::mem::take(&mut *f.borrow_mut()));
        taken
            .iter()
            .map(|t| {
                let o = js_sys::Object::new();
                for (key, ms) in [
                    ("app", t.app_ms),
                    ("ik", t.ik_ms),
                    ("scene", t.scene_ms),
                    ("render", t.render_ms),
                    ("workspace", t.workspace_ms),
                    ("motion", t.motion_ms),
                    ("motion_steps", t.motion_steps),
                    ("hook", t.hook_ms),
                ] {
                    set_field(&o, key, &ms.into());
                }
                JsValue::from(o)
            })
            .collect()
    })
    .into_js_value()
}

/// `window.armlab.viewRect()`: the 3D view's rectangle in CSS pixels, or null.
fn view_rect_fn() -> JsValue {
    Closure::<dyn Fn() -> JsValue>::new(|| {
        HOOK.with(|h| {
            let h = h.borrow();
            let Some(r) = h.view_rect else {
                return JsValue::NULL;
            };
            let o = js_sys::Object::new();
            for (key, v) in ["x", "y", "width", "height"].into_iter().zip(r) {
                set_field(&o, key, &f64::from(v * h.css_per_point).into());
            }
            o.into()
        })
    })
    .into_js_value()
}

/// `window.armlab.workspaceBenchmark(samples)`: the workspace benchmark in the page
/// (printed by the browser test, not asserted): the UR10's cloud of `samples`
/// tool positions with manipulability (the determinant) and, separately, with σ_min;
/// milliseconds each, one thread.
fn install_workspace_benchmark(obj: &js_sys::Object) {
    let bench = Closure::<dyn Fn(u32) -> JsValue>::new(|samples: u32| {
        use armlab_core::workspace::{WorkspaceCloud, WorkspaceMeasure};
        let Ok(robot) = armlab_core::preset("ur10") else {
            return JsValue::NULL;
        };
        let o = js_sys::Object::new();
        for (key, measure) in [
            ("manipulability_ms", WorkspaceMeasure::Manipulability),
            ("sigma_min_ms", WorkspaceMeasure::SigmaMin),
        ] {
            let start = crate::app::platform::clock::now_ms();
            let mut cloud = WorkspaceCloud::new(&robot, measure, samples as usize, 0x5eed);
            cloud.fill(samples as usize);
            let ms = crate::app::platform::clock::now_ms() - start;
            set_field(&o, key, &ms.into());
            set_field(&o, "samples", &(cloud.len() as f64).into());
        }
        o.into()
    });
    set_field(obj, "workspaceBenchmark", &bench.into_js_value());
}

/// `window.armlab.collisionBenchmark(robot, poses)`: the collision check's cost per pose
/// in the page (printed by the browser test, not asserted), as the native `motionbench`
/// measures it: `poses` random poses of a preset, each its frames, its parts and the
/// check of the floor and the parts through the collision module (the numbers there and
/// back included); `null` until the module is loaded.
fn install_collision_benchmark(obj: &js_sys::Object) {
    let bench = Closure::<dyn Fn(String, u32) -> JsValue>::new(|id: String, poses: u32| {
        use armlab_core::collision::CollisionChecker;
        let (Ok(robot), Ok(mut checker)) = (
            armlab_core::preset(&id),
            CollisionChecker::new(true, Vec::new()),
        ) else {
            return JsValue::NULL;
        };
        let mut rng = armlab_core::rng::SplitMix64::new(7);
        let qs: Vec<Vec<f64>> = (0..poses.max(1))
            .map(|_| rng.joint_vector(&robot))
            .collect();
        let Ok(mut fk) = armlab_core::ForwardKinematics::new(&robot, &robot.home()) else {
            return JsValue::NULL;
        };
        let (mut colliding, start) = (0usize, crate::app::platform::clock::now_ms());
        for q in &qs {
            fk.update(&robot, q);
            match checker.check_with(&robot, &fk, modules::collide_parts) {
                Some(report) => colliding += usize::from(!report.is_free()),
                None => return JsValue::NULL,
            }
        }
        let us = 1e3 * (crate::app::platform::clock::now_ms() - start) / qs.len() as f64;
        let o = js_sys::Object::new();
        set_field(&o, "robot", &id.into());
        set_field(&o, "poses", &(qs.len() as f64).into());
        set_field(&o, "parts", &(checker.parts().len() as f64).into());
        set_field(&o, "us_per_pose_fk_parts_and_check", &us.into());
        let share = colliding as f64 / qs.len() as f64;
        set_field(&o, "colliding_fraction_of_random_poses", &share.into());
        o.into()
    });
    set_field(obj, "collisionBenchmark", &bench.into_js_value());
}

/// Sets `object[key] = value`, logging a failure.
fn set_field(object: &JsValue, key: &str, value: &JsValue) {
    warn_on_failure(
        js_sys::Reflect::set(object, &key.into(), value),
        &format!("setting {key} on a page object"),
    );
}

/// Opens links the page navigates to (back/forward, an edited address) and writes a
/// waiting hash when the page is left.
fn install_hashchange(window: &web_sys::Window) {
    let on_change = Closure::<dyn Fn()>::new(|| {
        if let Some(hash) = web_sys::window().and_then(|w| w.location().hash().ok()) {
            PENDING_HASH.with(|p| *p.borrow_mut() = Some(hash));
            wake();
        }
    });
    warn_on_failure(
        window.add_event_listener_with_callback("hashchange", on_change.as_ref().unchecked_ref()),
        "listening for link changes",
    );
    on_change.forget();
    let on_leave = Closure::<dyn Fn()>::new(|| {
        if let Some(hash) = PENDING_STORE.with(|p| p.borrow_mut().take()) {
            write_hash(&hash);
        }
    });
    warn_on_failure(
        window.add_event_listener_with_callback("pagehide", on_leave.as_ref().unchecked_ref()),
        "listening for the page being left",
    );
    on_leave.forget();
}

/// A thrown JS value's words: an `Error`'s message, or the value as text.
fn js_error_text(e: &JsValue) -> String {
    e.dyn_ref::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .or_else(|| e.as_string())
        .unwrap_or_else(|| format!("{e:?}"))
}
