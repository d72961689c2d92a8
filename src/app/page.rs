//! The app in the page: starting [`ArmLabApp`] on the canvas with the browser's
//! preferences, and each frame keeping its link and session (the address bar,
//! localStorage) and publishing it for `window.armlab`. The page's side of each lives in
//! [`crate::app::platform::web`], which knows no app.

use wasm_bindgen::JsCast;

use crate::app::platform::clock::now_ms;
use crate::app::platform::web::{self, hook, room, storage};
use crate::app::{ArmLabApp, DITHERING, Preferences};

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
            web::set_message("ArmLab could not find its canvas on this page.", true);
            return;
        };
        // A link wins; without one, the last session returns.
        let link = window.location().hash().unwrap_or_default();
        let stored = storage::stored_session(&window);
        let options = eframe::WebOptions {
            // eframe listens to touchmove on the document, where browsers make listeners
            // passive: preventing a pointer move's default there only logs "Unable to
            // preventDefault inside passive event listener". The canvas's CSS
            // `touch-action: none` already keeps the page from scrolling or zooming.
            should_prevent_default: Box::new(|e| !matches!(e, egui::Event::PointerMoved(_))),
            dithering: DITHERING,
            ..eframe::WebOptions::default()
        };
        let preferences = browser_preferences(&window);
        // WebRunner::new installs eframe's panic hook; ours runs after it.
        let runner = eframe::WebRunner::new();
        web::install_crash_screen();
        let result = runner
            .start(
                canvas,
                options,
                Box::new(move |cc| {
                    web::a11y::install(&cc.egui_ctx);
                    let app = ArmLabApp::new_with(cc, &link, Some(&stored), preferences);
                    Ok(Box::new(app))
                }),
            )
            .await;
        match result {
            Ok(()) => {
                web::set_message("", false);
                hook::install(&window);
                storage::install_hashchange(&window);
                room::probe(&window);
            }
            Err(e) => {
                let detail = web::js_error_text(&e);
                web::set_message(
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

/// The browser's languages (`navigator.languages`), whether its main pointer is a
/// finger (`(pointer: coarse)`) and whether it asks for reduced motion.
fn browser_preferences(window: &web_sys::Window) -> Preferences {
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
    Preferences {
        lang: armlab_text::Lang::from_tags(tags.iter().map(String::as_str)),
        touch,
        reduced_motion: web::prefers_reduced_motion(window),
    }
}

/// Keeps the app's link in the address bar and its session in localStorage, at the pace
/// [`storage::store`] describes (the hash is built only when it may be written).
pub fn store_hash(app: &ArmLabApp, ctx: &egui::Context) {
    storage::store(
        || app.link_in_room(),
        || app.stored_session(),
        app.model().robot_changes(),
        ctx,
    );
}

/// Publishes the state and screen points for `window.armlab`, and opens a hash the page
/// asked for; its own time goes into the frame's
/// [`crate::app::platform::clock::FrameTime::hook_ms`].
pub fn publish(app: &mut ArmLabApp, ctx: &egui::Context) {
    let start = now_ms();
    web::remember_frame(ctx, app.model().settings().lang);
    hook::panic_if_asked();
    if let Some(hash) = storage::take_pending_hash() {
        app.open_hash(&hash);
    }
    let app = &*app;
    hook::publish_classroom(|| app.classroom_json());
    let lang = app.model().settings().lang;
    let canvas = (
        armlab_text::text(lang, armlab_text::Key::CanvasName),
        armlab_text::text(lang, armlab_text::Key::CanvasDescription),
    );
    let words = crate::app::state::view_words::view_words;
    web::a11y::describe(
        ctx,
        canvas,
        moving_target(app, ctx),
        || crate::app::state::view_words::reach_words(app.model()),
        || words(app.model()),
    );
    web::skip::update(
        armlab_text::text(lang, armlab_text::Key::SkipLinks),
        skip_links(app),
    );
    hook::publish(
        ctx,
        || app.state_json(),
        app.points().all(),
        app.viewport().rect(),
        app.viewport().rendered(),
        app.frame_times().back().copied(),
        start,
    );
}

/// The page's skip links: where each leads (the 3D view, then each panel drawn this frame,
/// to its first widget), what they say hashed (the language and the panels), and their
/// words in the interface's language, made only when that hash changed.
fn skip_links(
    app: &ArmLabApp,
) -> (
    Vec<Option<egui::Id>>,
    u64,
    impl FnOnce() -> Vec<String> + '_,
) {
    use std::hash::{Hash, Hasher};
    let lang = app.model().settings().lang;
    let anchors = &app.panels.anchors;
    let targets = std::iter::once(None)
        .chain(anchors.iter().map(|(_, first)| Some(*first)))
        .collect();
    let mut said = std::hash::DefaultHasher::new();
    lang.hash(&mut said);
    anchors.iter().for_each(|(kind, _)| kind.hash(&mut said));
    let words = move || {
        use armlab_text::Key;
        let view = armlab_text::text(lang, Key::SkipToView).to_owned();
        let panels = anchors.iter().map(|(kind, _)| {
            let title = armlab_text::text(lang, crate::app::panels::shell::title(*kind));
            armlab_text::fill(lang, Key::SkipToPanel, &[&title])
        });
        std::iter::once(view).chain(panels).collect()
    };
    (targets, said.finish(), words)
}

/// Whether the target is being moved: dragged by the pointer, or by a held arrow or page
/// key while no control has the keyboard (the view's keys move the target then).
fn moving_target(app: &ArmLabApp, ctx: &egui::Context) -> bool {
    use egui::Key;
    const KEYS: [Key; 6] = [
        Key::ArrowLeft,
        Key::ArrowRight,
        Key::ArrowUp,
        Key::ArrowDown,
        Key::PageUp,
        Key::PageDown,
    ];
    app.viewport().dragging()
        || (ctx.memory(|m| m.focused().is_none())
            && ctx.input(|i| !i.modifiers.alt && KEYS.iter().any(|k| i.key_down(*k))))
}

/// The lecture room, each frame before the panels: a link's `class=` part once the page
/// knows whether a classroom server serves it, the connection kept as the room wants it,
/// the server's messages applied, and the lecturer's state and every waiting message sent.
pub fn pump_room(app: &mut ArmLabApp, ctx: &egui::Context) {
    if !app.classroom().available() && room::available() {
        app.classroom_mut().set_available(true);
    }
    if room::answered()
        && let Some(link) = app.take_class_link()
    {
        app.open_class_link(link, room::token);
    }
    let classroom = app.classroom();
    let wanted = classroom.wants_connection().then(|| classroom.generation());
    let (events, wait) = room::keep(wanted);
    for event in events {
        match event {
            room::SocketEvent::Opened => {
                let state = app.room_state();
                app.classroom_mut().on_open(state);
            }
            room::SocketEvent::Text(text) => {
                let Ok(message) = armlab_room::read_server(&text) else {
                    continue;
                };
                if let Some(effect) = app.classroom_mut().receive(message) {
                    app.apply_room_effect(effect, room::keep_token);
                }
            }
            room::SocketEvent::Closed => app.classroom_mut().on_close(),
        }
    }
    let wait = wait.or_else(|| app.tick_room(now_ms()));
    for message in app.classroom_mut().take_outbox() {
        room::send(&message.to_json());
    }
    if let Some(ms) = wait {
        ctx.request_repaint_after(std::time::Duration::from_secs_f64(ms / 1e3));
    }
}
