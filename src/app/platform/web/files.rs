//! Files in and out of the page: downloads (robot files, URDF), the file chooser, files
//! dropped on the page, and the [`FileEvent`]s they give the robot panel on a later frame.

use std::cell::RefCell;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::modules::{call_urdf_module, urdf_module};
use super::{wake, warn_on_failure};

thread_local! {
    /// What picked or dropped files and URDF downloads gave, waiting for the next frame.
    static FILE_EVENTS: RefCell<Vec<FileEvent>> = const { RefCell::new(Vec::new()) };
}

/// Offers `text` as a download named `name` (a robot file: JSON).
pub fn download(name: &str, text: &str) -> Result<(), String> {
    download_typed(name, text, "application/json")
}

/// Offers `text` as a download named `name`, of the MIME type `mime`.
fn download_typed(name: &str, text: &str, mime: &str) -> Result<(), String> {
    let fail = |e: JsValue| super::js_error_text(&e);
    let window = web_sys::window().ok_or("no window")?;
    let document = window.document().ok_or("no document")?;
    let parts = js_sys::Array::of1(&JsValue::from_str(text));
    let bag = web_sys::BlobPropertyBag::new();
    bag.set_type(mime);
    let blob = web_sys::Blob::new_with_str_sequence_and_options(&parts, &bag).map_err(fail)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(fail)?;
    let a: web_sys::HtmlAnchorElement = document
        .create_element("a")
        .map_err(fail)?
        .dyn_into()
        .map_err(|_| "no anchor")?;
    a.set_href(&url);
    a.set_download(name);
    a.click();
    warn_on_failure(
        web_sys::Url::revoke_object_url(&url),
        "releasing the download's address",
    );
    Ok(())
}

/// What a picked or dropped file, or a URDF download, gave: the robot panel takes these
/// with [`take_file_events`] on the next frame.
#[derive(Debug, Clone, PartialEq)]
pub enum FileEvent {
    /// A robot file's text (JSON).
    Robot(String),
    /// The URDF module is being fetched (the visit's first URDF file or download).
    UrdfLoading,
    /// A URDF file made into a robot file by the URDF module.
    Urdf {
        /// The robot file (JSON).
        robot: String,
        /// How many mesh visuals the URDF file has (ArmLab draws its own parts).
        meshes: usize,
    },
    /// A URDF file that gives no robot: the core's sentence naming the element.
    UrdfRejected(String),
    /// The URDF module could not be loaded: the browser's words.
    UrdfUnavailable(String),
    /// The robot was offered as a URDF download under this name.
    UrdfSaved(String),
    /// The URDF download failed: why.
    UrdfSaveFailed(String),
}

fn push_file_event(event: FileEvent) {
    FILE_EVENTS.with(|f| f.borrow_mut().push(event));
    wake();
}

/// What files and URDF downloads gave since the last call, in order.
pub fn take_file_events() -> Vec<FileEvent> {
    FILE_EVENTS.with(|f| std::mem::take(&mut *f.borrow_mut()))
}

/// Tells the robot panel that the URDF module is being fetched.
fn announce_loading() {
    push_file_event(FileEvent::UrdfLoading);
}

/// A URDF text through the URDF module, in the interface's language.
async fn import_urdf(text: String) {
    let lang = super::lang().id();
    let event = match urdf_module(announce_loading).await {
        Err(e) => FileEvent::UrdfUnavailable(e),
        Ok(module) => match call_urdf_module(&module, "urdf_import", &[&text, lang]) {
            Err(sentence) => FileEvent::UrdfRejected(sentence),
            Ok(answer) => {
                let value: serde_json::Value =
                    serde_json::from_str(&answer).unwrap_or(serde_json::Value::Null);
                match (
                    value.get("robot"),
                    value.get("meshes").and_then(|m| m.as_u64()),
                ) {
                    (Some(robot), Some(meshes)) => FileEvent::Urdf {
                        robot: robot.to_string(),
                        meshes: usize::try_from(meshes).unwrap_or(usize::MAX),
                    },
                    _ => FileEvent::UrdfUnavailable(format!(
                        "urdf_import answered {}",
                        armlab_text::echo::text_within(&answer, 40)
                    )),
                }
            }
        },
    };
    push_file_event(event);
}

/// Offers the robot (its robot file, JSON) as a URDF download named `name` once the URDF
/// module is there; the outcome arrives as a [`FileEvent`].
pub fn download_urdf(name: String, robot: String) {
    wasm_bindgen_futures::spawn_local(async move {
        let event = match urdf_module(announce_loading).await {
            Err(e) => FileEvent::UrdfUnavailable(e),
            Ok(module) => match call_urdf_module(&module, "robot_to_urdf", &[&robot])
                .and_then(|text| download_typed(&name, &text, "application/xml"))
            {
                Ok(()) => FileEvent::UrdfSaved(name),
                Err(e) => FileEvent::UrdfSaveFailed(e),
            },
        };
        push_file_event(event);
    });
}

/// Whether a file is URDF: named `.urdf`, or XML (a robot file is JSON and starts with
/// `{`).
fn is_urdf(name: &str, text: &str) -> bool {
    let named = std::path::Path::new(name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("urdf"));
    named
        || text
            .trim_start_matches('\u{feff}')
            .trim_start()
            .starts_with('<')
}

/// A picked or dropped file's text: a URDF file goes through the URDF module first.
fn receive_file(name: &str, text: String) {
    if is_urdf(name, &text) {
        wasm_bindgen_futures::spawn_local(import_urdf(text));
    } else {
        push_file_event(FileEvent::Robot(text));
    }
}

/// Opens the browser's file chooser for a robot file (`.json`) or a URDF file (`.urdf`);
/// what the chosen file gives arrives through [`take_file_events`] on a later frame.
pub fn open_file_chooser() {
    let Some(document) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    let Ok(input) = document.create_element("input") else {
        return;
    };
    let Ok(input) = input.dyn_into::<web_sys::HtmlInputElement>() else {
        return;
    };
    input.set_type("file");
    input.set_accept(".json,.urdf,application/json");
    let reader_input = input.clone();
    let on_change = Closure::<dyn Fn()>::new(move || {
        let Some(file) = reader_input.files().and_then(|f| f.get(0)) else {
            return;
        };
        let name = file.name();
        let promise = file.text();
        wasm_bindgen_futures::spawn_local(async move {
            if let Ok(text) = wasm_bindgen_futures::JsFuture::from(promise).await
                && let Some(text) = text.as_string()
            {
                receive_file(&name, text);
            }
        });
    });
    input.set_onchange(Some(on_change.as_ref().unchecked_ref()));
    on_change.forget();
    input.click();
}

/// Reads a file dropped on the page; what it gives arrives through [`take_file_events`].
pub fn read_dropped_file(file: egui::DroppedFileHandle) {
    wasm_bindgen_futures::spawn_local(async move {
        if let Ok(bytes) = file.bytes_async().await {
            let name = file.path().to_string_lossy().into_owned();
            receive_file(&name, String::from_utf8_lossy(&bytes).into_owned());
        }
    });
}
