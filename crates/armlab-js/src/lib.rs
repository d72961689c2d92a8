//! The JavaScript API (feature `js`): the functions of [`armlab_api`] exported through
//! wasm-bindgen. Each takes and returns JSON text; a bad request throws an `Error` whose
//! message is the core's sentence.

use armlab_text::Sentence;
use wasm_bindgen::prelude::*;

use armlab_api as api;

fn to_js(result: Result<String, api::ApiError>) -> Result<String, JsError> {
    result.map_err(|e| JsError::new(&e.to_string()))
}

/// The presets as JSON: `[{"id", "name", "dof", "convention", "length_unit"}]`.
#[wasm_bindgen]
pub fn presets() -> String {
    api::presets()
}

/// A robot's file as JSON. Request: `{"robot": "ur10"}` or `{"robot": {...}}`.
#[wasm_bindgen]
pub fn robot(request: &str) -> Result<String, JsError> {
    to_js(api::robot(request))
}

/// Forward kinematics. Request: `{"robot": "ur10", "q": [0, 0, 0, 0, 0, 0]}`.
#[wasm_bindgen]
pub fn fk(request: &str) -> Result<String, JsError> {
    to_js(api::fk(request))
}

/// Geometric and numerical Jacobians with measures.
/// Request: `{"robot": "ur10", "q": [...], "task": "full"}`.
#[wasm_bindgen]
pub fn jacobian(request: &str) -> Result<String, JsError> {
    to_js(api::jacobian(request))
}

/// Inverse kinematics (see `api::ik` for the request and the response).
/// Request: `{"robot": "ur10", "q": [...], "target": [[...4×4]], "task": "full",
/// "method": "dls", "drag": false, "settings": {...}}`.
#[wasm_bindgen]
pub fn ik(request: &str) -> Result<String, JsError> {
    to_js(api::ik(request))
}

#[wasm_bindgen]
extern "C" {
    /// `performance.now()` (milliseconds), the benchmark's clock.
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

/// The IK benchmark (TRAC-IK protocol) timed with `performance.now()`; prints the same
/// JSON as the native `ikbench` binary. Request: `{"samples": 10000, "budget": 1000,
/// "seed": 20240601}` (all optional).
#[wasm_bindgen]
pub fn ik_benchmark(request: &str) -> Result<String, JsError> {
    let now = || performance_now() * 1e-3;
    armlab_bench::ik::run_json(request, &now).map_err(|e| JsError::new(&e.to_string()))
}

/// The workspace benchmark (UR10, FK + manipulability, σ_min apart; docs/kinematics.md
/// §12) timed with `performance.now()`; the same JSON as the native `workspacebench`.
/// Arguments: samples per run and runs per measure.
#[wasm_bindgen]
pub fn workspace_benchmark(samples: u32, repeats: u32) -> String {
    let now = || performance_now() * 1e-3;
    let report = armlab_bench::workspace::workspace_report(
        (samples as usize).clamp(1, 10_000_000),
        (repeats as usize).clamp(1, 100),
        &now,
        None,
    );
    report.to_string()
}

/// A URDF text (one serial chain) as an ArmLab robot file (JSON): a standard DH table
/// with base and tool transforms, in metres (docs/kinematics.md §16.2). Feature `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen]
pub fn urdf_to_robot(urdf: &str) -> Result<String, JsError> {
    armlab_urdf::robot_from_urdf(urdf)
        .map(|robot| armlab_core::robot_to_json(&robot))
        .map_err(|e| JsError::new(&e.to_string()))
}

/// An ArmLab robot file (JSON) as URDF text, in metres (docs/kinematics.md §16.1).
/// Feature `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen]
pub fn robot_to_urdf(robot: &str) -> Result<String, JsError> {
    let robot = armlab_core::robot_from_json(robot)
        .map_err(|e| JsError::new(&e.sentence(armlab_text::Lang::En)))?;
    armlab_urdf::robot_to_urdf(&robot).map_err(|e| JsError::new(&e.to_string()))
}

/// For the page's URDF upload (the page loads this module only then): a URDF text as
/// `{"robot": <robot file>, "meshes": N}`, N the file's mesh visuals (ArmLab reads the
/// joints, not the visuals, and draws its own parts). A bad file throws the core's
/// sentence naming the element, in `lang` (`en` or `fi`; another id reads as `en`).
/// Feature `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen]
pub fn urdf_import(urdf: &str, lang: &str) -> Result<String, JsError> {
    let lang = armlab_text::Lang::from_id(lang).unwrap_or_default();
    let robot = armlab_urdf::robot_from_urdf(urdf).map_err(|e| JsError::new(&e.sentence(lang)))?;
    Ok(format!(
        "{{\"robot\":{},\"meshes\":{}}}",
        armlab_core::robot_to_json(&robot),
        armlab_urdf::mesh_visuals(urdf)
    ))
}

/// For the page's collision check (the page loads this module only once checks are on):
/// a request of numbers as `kinematics::collision_wire` writes it (the posed parts, the
/// floor switch and the keep-out boxes) checked with the collision library; the report's
/// numbers. A malformed request throws a sentence.
#[wasm_bindgen]
pub fn collide_parts(request: &[f64]) -> Result<Vec<f64>, JsError> {
    armlab_core::collision_wire::check_request(request).map_err(|e| JsError::new(&e.to_string()))
}
