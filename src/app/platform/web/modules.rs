//! The lazily loaded modules: the URDF module (fetched by the visit's first URDF file or
//! download), the collision check's use of it (dist/urdf/ holds the collision library;
//! the page's own wasm does not), with its state and retry, and the symbolic matrices, the
//! DH exercise's verdicts and the join link's QR code it makes (the page's own wasm holds
//! neither the symbolic algebra, the exercise's check nor a QR encoder).

use std::cell::{Cell, RefCell};
use std::thread::LocalKey;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::{js_error_text, wake};
use crate::app::platform::Answer;
use crate::app::platform::exercise::Checked;
use crate::app::platform::symbolic::Tables;
use armlab_core::exercise::Verdict;
use std::rc::Rc;

use armlab_core::symbolic::EntryText;
use armlab_core::symbolic_tables::SymbolicTables;
use armlab_room::QrModules;

thread_local! {
    /// The URDF module's import: started by the first URDF file or download, kept for the
    /// visit, forgotten when it failed (a later try fetches it again).
    static URDF_MODULE: RefCell<Option<js_sys::Promise>> = const { RefCell::new(None) };
    /// How many imports of the URDF module failed in this visit.
    static MODULE_FAILURES: Cell<u32> = const { Cell::new(0) };
    /// The collision check's side of the module: its `collide_parts` once loaded.
    static COLLIDE: RefCell<CollideModule> = const { RefCell::new(CollideModule::Idle) };
    /// The symbolic tables of the robot last asked for (its robot file) and where they are.
    static SYMBOLIC: Slot<Rc<SymbolicTables>> = const { RefCell::new(None) };
    /// The exercise check last asked for (the reference's and the student's robot files)
    /// and where it is.
    static CHECK: Slot<Verdict> = const { RefCell::new(None) };
    /// The QR code of the text last asked for and where it is (failed, too, for a text too
    /// long for a QR code).
    static QR: Slot<Rc<QrModules>> = const { RefCell::new(None) };
}

/// The URDF module's glue, beside the page (tools/setup.sh, `build_urdf_module`).
const URDF_MODULE_PATH: &str = "urdf/armlab_urdf.js";

/// Starts importing the URDF module: its namespace once its wasm is instantiated.
fn import_urdf_module() -> Result<js_sys::Promise, String> {
    let base = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.base_uri().ok().flatten())
        .ok_or("no document")?;
    let url =
        web_sys::Url::new_with_base(URDF_MODULE_PATH, &base).map_err(|e| js_error_text(&e))?;
    // A browser may keep a failed import of an address for the visit: a later try asks
    // for another one.
    let failed = MODULE_FAILURES.with(Cell::get);
    if failed > 0 {
        url.set_search(&format!("try={failed}"));
    }
    let url = url.href();
    // A dynamic import, which a function body may hold; the absolute address leaves
    // nothing to resolve against the caller. A release build's glue hands on the page's
    // decoder and its wasm's address (web/build/pack-wasm.mjs): the module starts from its
    // wasm packed with xz, or, where that fails, from the wasm itself; other builds' glue
    // from the wasm.
    let import = js_sys::Function::new_with_args(
        "url",
        "return import(url).then(function (m) {\
           var started = m.startPacked ? m.startPacked(m.default, m.wasmUrl) : m.default();\
           return started.then(function () { return m; });\
         });",
    );
    import
        .call1(&JsValue::NULL, &url.into())
        .map_err(|e| js_error_text(&e))?
        .dyn_into::<js_sys::Promise>()
        .map_err(|_| "the import gave no promise".to_string())
}

/// The URDF module, imported on the first call of the visit (`on_import` runs when this
/// call starts the import: the robot panel says that it loads).
pub(super) async fn urdf_module(on_import: impl FnOnce()) -> Result<JsValue, String> {
    let started = URDF_MODULE.with(|m| m.borrow().clone());
    let promise = match started {
        Some(promise) => promise,
        None => {
            on_import();
            let promise = import_urdf_module()?;
            URDF_MODULE.with(|m| *m.borrow_mut() = Some(promise.clone()));
            promise
        }
    };
    let loaded = wasm_bindgen_futures::JsFuture::from(promise).await;
    loaded.map_err(|e| {
        URDF_MODULE.with(|m| *m.borrow_mut() = None);
        MODULE_FAILURES.with(|f| f.set(f.get() + 1));
        js_error_text(&e)
    })
}

/// Calls the URDF module's function `name` with text arguments; its text answer, or what
/// it threw.
pub(super) fn call_urdf_module(
    module: &JsValue,
    name: &str,
    args: &[&str],
) -> Result<String, String> {
    let function = module_function(module, name)?;
    let args: js_sys::Array = args.iter().map(|a| JsValue::from_str(a)).collect();
    let answer = function
        .apply(&JsValue::NULL, &args)
        .map_err(|e| js_error_text(&e))?;
    answer
        .as_string()
        .ok_or_else(|| format!("{name} gave no text"))
}

/// The module's function `name`.
fn module_function(module: &JsValue, name: &str) -> Result<js_sys::Function, String> {
    js_sys::Reflect::get(module, &name.into())
        .map_err(|e| js_error_text(&e))?
        .dyn_into()
        .map_err(|_| format!("the URDF module has no {name}"))
}

/// The collision check's use of the module (dist/urdf/, which holds the collision
/// library; the page's own wasm does not).
enum CollideModule {
    /// Not asked for yet (or failed, and the checks went on again).
    Idle,
    /// Being fetched.
    Loading,
    /// Loaded: its `collide_parts`.
    Ready(js_sys::Function),
    /// Could not be loaded, or its check threw: the words.
    Failed(String),
}

/// Starts loading the module for the collision check.
fn load_collision_module() {
    COLLIDE.with(|c| *c.borrow_mut() = CollideModule::Loading);
    wasm_bindgen_futures::spawn_local(async {
        let state = match urdf_module(|| ())
            .await
            .and_then(|m| module_function(&m, "collide_parts"))
        {
            Ok(f) => CollideModule::Ready(f),
            Err(e) => CollideModule::Failed(e),
        };
        COLLIDE.with(|c| *c.borrow_mut() = state);
        wake();
    });
}

/// Checks `parts` in the module (synchronously once it is loaded; the first call of the
/// visit starts loading it and answers `None`, as every call does until it is there).
pub fn collide_parts(
    checker: &armlab_core::collision::CollisionChecker,
    parts: &[armlab_core::parts::Part],
    tolerance: f64,
) -> Option<armlab_core::collision::CollisionReport> {
    use armlab_core::collision_wire::{decode_report, encode_request};
    let function = COLLIDE.with(|c| match &*c.borrow() {
        CollideModule::Ready(f) => Some(f.clone()),
        _ => None,
    });
    let Some(function) = function else {
        if COLLIDE.with(|c| matches!(*c.borrow(), CollideModule::Idle)) {
            load_collision_module();
        }
        return None;
    };
    let request = encode_request(parts, tolerance, checker.floor, checker.keep_outs());
    let answer = function
        .call1(&JsValue::NULL, &js_sys::Float64Array::from(&request[..]))
        .map_err(|e| js_error_text(&e))
        .and_then(|a| {
            let numbers = js_sys::Float64Array::new(&a).to_vec();
            decode_report(&numbers, parts.len()).map_err(|e| e.to_string())
        });
    answer
        .map_err(|e| COLLIDE.with(|c| *c.borrow_mut() = CollideModule::Failed(e)))
        .ok()
}

/// The collision module's state for the Motion panel.
pub fn collision_module_state() -> crate::app::platform::checker::CheckerState {
    use crate::app::platform::checker::CheckerState;
    COLLIDE.with(|c| match &*c.borrow() {
        CollideModule::Ready(_) => CheckerState::Ready,
        CollideModule::Idle | CollideModule::Loading => CheckerState::Loading,
        CollideModule::Failed(e) => CheckerState::Failed(e.clone()),
    })
}

/// After a failure: the next check fetches the module again.
pub fn retry_collision_module() {
    COLLIDE.with(|c| {
        let mut c = c.borrow_mut();
        if matches!(*c, CollideModule::Failed(_)) {
            *c = CollideModule::Idle;
        }
    });
}

/// One answer the module makes, kept for the key (a robot file, a text) it was last asked
/// for.
type Slot<T> = RefCell<Option<(String, Answer<T>)>>;

/// The answer for `key` in `slot`: the one kept when `key` was asked last; otherwise `key`
/// takes the slot as loading and the module is asked (`ask` with the module, once it is
/// loaded, and `key`), and its answer fills the slot when it comes, if `key` is still the
/// one asked for (the robot may have changed meanwhile: its own request is under way). The
/// frame is woken then. A frame that finds its answer kept allocates nothing.
fn from_module<T: Clone + 'static>(
    slot: &'static LocalKey<Slot<T>>,
    key: &str,
    ask: fn(&JsValue, &str) -> Result<T, String>,
) -> Answer<T> {
    let known = slot.with(|s| match &*s.borrow() {
        Some((asked, answer)) if asked == key => Some(answer.clone()),
        _ => None,
    });
    if let Some(answer) = known {
        return answer;
    }
    let key = key.to_string();
    slot.with(|s| *s.borrow_mut() = Some((key.clone(), Answer::Loading)));
    wasm_bindgen_futures::spawn_local(async move {
        let answer = match urdf_module(|| ()).await.and_then(|m| ask(&m, &key)) {
            Ok(made) => Answer::Ready(made),
            Err(e) => Answer::Failed(e),
        };
        slot.with(|s| {
            if let Some((asked, kept)) = &mut *s.borrow_mut()
                && *asked == key
            {
                *kept = answer;
            }
        });
        wake();
    });
    Answer::Loading
}

/// After a failure kept in `slot`: the next call asks the module again.
fn forget_failure<T>(slot: &'static LocalKey<Slot<T>>) {
    slot.with(|s| {
        let mut s = s.borrow_mut();
        if matches!(&*s, Some((_, Answer::Failed(_)))) {
            *s = None;
        }
    });
}

/// The symbolic tables of `robot`, from the module: the first call for a robot starts
/// making them (and loading the module) and answers [`Answer::Loading`], as every call does
/// until the answer is there.
pub fn symbolic_tables(robot: &armlab_core::Robot) -> Tables {
    from_module(
        &SYMBOLIC,
        &armlab_core::robot_to_json(robot),
        |module, file| {
            let text = call_urdf_module(module, "symbolic_tables", &[file])?;
            SymbolicTables::from_text(&text)
                .map(Rc::new)
                .ok_or_else(|| "unreadable tables".to_string())
        },
    )
}

/// The verdict on `student`'s table against `reference`, from the module: the first call
/// for the pair starts the check (and loading the module) and answers
/// [`Answer::Loading`], as every call does until the answer is there.
pub fn check_table(reference: &armlab_core::Robot, student: &armlab_core::Robot) -> Checked {
    // The two robot files apart by a NUL, which JSON text never holds unescaped.
    let files = [reference, student]
        .map(armlab_core::robot_to_json)
        .join("\0");
    from_module(&CHECK, &files, |module, files| {
        let (reference, student) = files.split_once('\0').ok_or("no student's table")?;
        let answer = module_function(module, "check_table")?
            .call2(&JsValue::NULL, &reference.into(), &student.into())
            .map_err(|e| js_error_text(&e))?;
        let numbers = js_sys::Float64Array::new(&answer).to_vec();
        armlab_core::exercise_wire::decode_verdict(&numbers)
            .ok_or_else(|| "an unreadable verdict".to_string())
    })
}

/// After a failure: the next check asks the module again.
pub fn retry_check() {
    forget_failure(&CHECK);
}

/// The QR code of `text`, from the module: the first call for a text starts making it
/// (and loading the module) and answers `None`, as every call does until it is there. A
/// text too long for a QR code, or a module that failed, stays `None` for that text.
pub fn qr_code(text: &str) -> Option<Rc<QrModules>> {
    let answer = from_module(&QR, text, |module, text| {
        let code = call_urdf_module(module, "qr_code", &[text])?;
        QrModules::from_text(&code)
            .map(Rc::new)
            .ok_or_else(|| "too long for a QR code".to_string())
    });
    match answer {
        Answer::Ready(code) => Some(code),
        Answer::Loading | Answer::Failed(_) => None,
    }
}

/// After a failure: the next call asks the module again.
pub fn retry_symbolic_tables() {
    forget_failure(&SYMBOLIC);
}

/// The symbolic tables' state for the test hook (see `platform::symbolic`).
pub fn symbolic_state_text() -> String {
    SYMBOLIC.with(|s| match &*s.borrow() {
        None => "idle".to_string(),
        Some((_, Tables::Loading)) => "loading".to_string(),
        Some((_, Tables::Failed(why))) => format!("failed: {why}"),
        Some((_, Tables::Ready(tables))) => {
            let last = tables.base_from_frames.last();
            let position: Vec<&str> = (0..3)
                .filter_map(|r| match &last?.entry(r, 3)?.text {
                    EntryText::Shown { plain, .. } => Some(plain.as_str()),
                    EntryText::TooLong { .. } => Some("…"),
                })
                .collect();
            format!("ready: {}", position.join(" | "))
        }
    })
}
