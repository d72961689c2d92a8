//! The JavaScript API (feature `js`): the functions of [`crate::api`] exported through
//! wasm-bindgen. Each takes and returns JSON text; a bad request throws an `Error` whose
//! message is the core's sentence.

use wasm_bindgen::prelude::*;

use crate::api;

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
