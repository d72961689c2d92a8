//! The JavaScript API: the functions of [`armlab_api`] exported through
//! wasm-bindgen.
//!
//! A request is a plain object or its JSON text. An object is answered with an object,
//! a text with JSON text, so that callers written for the text API keep working:
//! `fk({robot: 'ur10'})` gives `{tool, position, …}`, `fk('{"robot": "ur10"}')` gives
//! that object's JSON. A bad request throws an `Error` whose message is the core's
//! sentence; an argument of another kind (a number, `true`, `undefined`, `null`, an
//! array) throws an `Error` whose sentence says what the function takes.
//!
//! Objects cross as JSON text, written and read by the JS engine (`JSON.stringify`,
//! `JSON.parse`): the API parses with serde_json either way, and a serde adapter for JS
//! values (serde-wasm-bindgen) made the Node package's wasm 18.8 kB larger (6.9 kB gzip)
//! for the same result.
//!
//! The package's TypeScript declarations are written here (`TYPES`) rather than
//! generated: wasm-bindgen would declare every `JsValue` as `any`.

use js_sys::{Array, Float64Array, JSON};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use armlab_api as api;
#[cfg(feature = "urdf")]
use armlab_text::Sentence;
use armlab_text::echo::{self, Number};
use armlab_text::{Key, Lang, fill, text};

/// How a request came, and so how its answer goes back.
#[derive(Clone, Copy)]
enum Form {
    /// JSON text: answered with JSON text.
    Text,
    /// A JS object: answered with a JS object.
    Object,
}

/// What a function takes, for the sentence on an argument of another kind.
#[derive(Clone, Copy)]
enum Takes {
    /// A request object; the example is shown in the sentence.
    Request(&'static str),
    /// A robot file object.
    #[cfg(feature = "urdf")]
    RobotFile,
    /// The text of a URDF file.
    #[cfg(feature = "urdf")]
    Urdf,
    /// A list of numbers.
    Numbers,
}

/// The JS API answers in English, as the JSON API does.
const LANG: Lang = Lang::En;

/// An argument as the sentence names it: "the number 5", "nothing (undefined)", ….
fn given(value: &JsValue) -> String {
    if let Some(n) = value.as_f64() {
        fill(LANG, Key::ApiGotNumber, &[&Number(n)])
    } else if let Some(b) = value.as_bool() {
        fill(LANG, Key::ApiGotBoolean, &[&b])
    } else if value.is_undefined() {
        text(LANG, Key::ApiGotUndefined).into()
    } else if value.is_null() {
        text(LANG, Key::ApiGotNull).into()
    } else if Array::is_array(value) {
        text(LANG, Key::ApiGotList).into()
    } else if value.is_string() {
        text(LANG, Key::ApiGotText).into()
    } else if value.is_object() {
        text(LANG, Key::ApiGotObject).into()
    } else {
        let kind = value.js_typeof().as_string().unwrap_or_default();
        fill(LANG, Key::ApiGotOther, &[&echo::text(&kind)])
    }
}

/// The error of an argument of the wrong kind given to the function `name`.
fn wrong_argument(name: &str, takes: Takes, value: &JsValue) -> JsError {
    let given = given(value);
    let sentence = match takes {
        Takes::Request(example) => fill(LANG, Key::ApiTakesRequest, &[&name, &example, &given]),
        #[cfg(feature = "urdf")]
        Takes::RobotFile => fill(LANG, Key::ApiTakesRobotFile, &[&name, &given]),
        #[cfg(feature = "urdf")]
        Takes::Urdf => fill(LANG, Key::ApiTakesUrdf, &[&name, &given]),
        Takes::Numbers => fill(LANG, Key::ApiTakesNumbers, &[&name, &given]),
    };
    JsError::new(&sentence)
}

/// The words of a thrown JS value: an `Error`'s message, or the value as text.
fn thrown_text(e: &JsValue) -> String {
    e.dyn_ref::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .or_else(|| e.as_string())
        .unwrap_or_default()
}

/// A request that `JSON.stringify` could not write (a BigInt, a cycle): the API's own
/// sentence for a request that is not JSON.
fn not_json(reason: &str) -> JsError {
    let error = api::ApiError::Request(format!("not JSON ({})", echo::text_within(reason, 80)));
    JsError::new(&error.to_string())
}

/// A request as JSON text, and the form its answer takes: a text is taken as it is, an
/// object (not an array) is written as JSON; anything else is the wrong kind.
fn request_text(name: &str, takes: Takes, value: &JsValue) -> Result<(String, Form), JsError> {
    if let Some(text) = value.as_string() {
        return Ok((text, Form::Text));
    }
    if !value.is_object() || Array::is_array(value) {
        return Err(wrong_argument(name, takes, value));
    }
    let written = JSON::stringify(value).map_err(|e| not_json(&thrown_text(&e)))?;
    // An object whose `toJSON` gives undefined is written as undefined, not as text.
    let text = JsValue::from(written)
        .as_string()
        .ok_or_else(|| not_json("JSON.stringify gave no text"))?;
    Ok((text, Form::Object))
}

/// An answer (JSON text) in the form its request came in.
fn answer(text: String, form: Form) -> Result<JsValue, JsError> {
    match form {
        Form::Text => Ok(JsValue::from(text)),
        Form::Object => JSON::parse(&text).map_err(|e| JsError::new(&thrown_text(&e))),
    }
}

/// Calls `function` of the JSON API with the request `value` (an object or JSON text).
fn call(
    name: &str,
    example: &'static str,
    value: &JsValue,
    function: fn(&str) -> Result<String, api::ApiError>,
) -> Result<JsValue, JsError> {
    let (request, form) = request_text(name, Takes::Request(example), value)?;
    let out = function(&request).map_err(|e| JsError::new(&e.to_string()))?;
    answer(out, form)
}

/// The presets: `[{id, name, dof, convention, length_unit}]`.
#[wasm_bindgen(skip_typescript)]
pub fn presets() -> Result<JsValue, JsError> {
    answer(api::presets(), Form::Object)
}

/// A robot's file. Request: `{robot: "ur10"}` or `{robot: {...}}`.
#[wasm_bindgen(skip_typescript)]
pub fn robot(request: JsValue) -> Result<JsValue, JsError> {
    call("robot", "{robot: \"ur10\"}", &request, api::robot)
}

/// Forward kinematics. Request: `{robot: "ur10", q: [0, 0, 0, 0, 0, 0]}`.
#[wasm_bindgen(skip_typescript)]
pub fn fk(request: JsValue) -> Result<JsValue, JsError> {
    call(
        "fk",
        "{robot: \"ur10\", q: [0, 0, 0, 0, 0, 0]}",
        &request,
        api::fk,
    )
}

/// Geometric and numerical Jacobians with measures.
/// Request: `{robot: "ur10", q: [...], task: "full"}`.
#[wasm_bindgen(skip_typescript)]
pub fn jacobian(request: JsValue) -> Result<JsValue, JsError> {
    call(
        "jacobian",
        "{robot: \"ur10\", q: [0, 0, 0, 0, 0, 0], task: \"full\"}",
        &request,
        api::jacobian,
    )
}

/// Inverse kinematics (see `api::ik` for the request and the response).
/// Request: `{robot: "ur10", q: [...], target: [[...4×4]], task: "full",
/// method: "dls", drag: false, settings: {...}}`.
#[wasm_bindgen(skip_typescript)]
pub fn ik(request: JsValue) -> Result<JsValue, JsError> {
    call(
        "ik",
        "{robot: \"ur10\", target: {position: [800, -200, 400]}}",
        &request,
        api::ik,
    )
}

#[wasm_bindgen]
extern "C" {
    /// `performance.now()` (milliseconds), the benchmark's clock.
    #[wasm_bindgen(js_namespace = performance, js_name = now)]
    fn performance_now() -> f64;
}

/// The IK benchmark (TRAC-IK protocol) timed with `performance.now()`; the same report
/// as the native `ikbench` binary. Request: `{samples: 10000, budget: 1000, seed:
/// 20240601}` (all optional; no argument for the defaults).
#[wasm_bindgen(skip_typescript)]
pub fn ik_benchmark(request: JsValue) -> Result<JsValue, JsError> {
    let (request, form) = if request.is_undefined() || request.is_null() {
        (String::new(), Form::Object)
    } else {
        request_text("ik_benchmark", Takes::Request("{samples: 1000}"), &request)?
    };
    let now = || performance_now() * 1e-3;
    let report =
        armlab_bench::ik::run_json(&request, &now).map_err(|e| JsError::new(&e.to_string()))?;
    answer(report, form)
}

/// The workspace benchmark (UR10, FK + manipulability, σ_min apart; docs/kinematics.md
/// §12) timed with `performance.now()`; the same report as the native `workspacebench`.
/// Arguments: samples per run and runs per measure.
#[wasm_bindgen(skip_typescript)]
pub fn workspace_benchmark(samples: u32, repeats: u32) -> Result<JsValue, JsError> {
    let now = || performance_now() * 1e-3;
    let report = armlab_bench::workspace::workspace_report(
        (samples as usize).clamp(1, 10_000_000),
        (repeats as usize).clamp(1, 100),
        &now,
        None,
    );
    answer(report.to_string(), Form::Object)
}

/// The text of a URDF file, or the sentence on another kind of argument.
#[cfg(feature = "urdf")]
fn urdf_text(name: &str, value: &JsValue) -> Result<String, JsError> {
    value
        .as_string()
        .ok_or_else(|| wrong_argument(name, Takes::Urdf, value))
}

/// A URDF text (one serial chain) as an ArmLab robot file (JSON text): a standard DH
/// table with base and tool transforms, in metres (docs/kinematics.md §14.2). Feature
/// `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen(skip_typescript)]
pub fn urdf_to_robot(urdf: JsValue) -> Result<String, JsError> {
    let urdf = urdf_text("urdf_to_robot", &urdf)?;
    armlab_urdf::robot_from_urdf(&urdf)
        .map(|robot| armlab_core::robot_to_json(&robot))
        .map_err(|e| JsError::new(&e.to_string()))
}

/// An ArmLab robot file (an object or its JSON text) as URDF text, in metres
/// (docs/kinematics.md §14.1). Feature `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen(skip_typescript)]
pub fn robot_to_urdf(robot: JsValue) -> Result<String, JsError> {
    let (robot, _) = request_text("robot_to_urdf", Takes::RobotFile, &robot)?;
    let robot =
        armlab_core::robot_from_json(&robot).map_err(|e| JsError::new(&e.sentence(Lang::En)))?;
    armlab_urdf::robot_to_urdf(&robot).map_err(|e| JsError::new(&e.to_string()))
}

/// For the page's URDF upload (the page loads this module only then): a URDF text as
/// `{"robot": <robot file>, "meshes": N}` (JSON text), N the file's mesh visuals (ArmLab
/// reads the joints, not the visuals, and draws its own parts). A bad file throws the
/// core's sentence naming the element, in `lang` (`en` or `fi`; another id, or none,
/// reads as `en`). Feature `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen(skip_typescript)]
pub fn urdf_import(urdf: JsValue, lang: JsValue) -> Result<String, JsError> {
    let urdf = urdf_text("urdf_import", &urdf)?;
    let lang = lang
        .as_string()
        .and_then(|id| Lang::from_id(&id))
        .unwrap_or_default();
    let robot = armlab_urdf::robot_from_urdf(&urdf).map_err(|e| JsError::new(&e.sentence(lang)))?;
    Ok(format!(
        "{{\"robot\":{},\"meshes\":{}}}",
        armlab_core::robot_to_json(&robot),
        armlab_urdf::mesh_visuals(&urdf)
    ))
}

/// For the page's symbolic matrices (the page loads this module only when they are
/// shown): a robot file (JSON text, as the page writes its robot) as the matrices panel's
/// symbolic tables (`armlab_core::symbolic_tables::SymbolicTables::to_text`). A bad
/// robot file throws the core's sentence. Feature `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen(skip_typescript)]
pub fn symbolic_tables(robot: JsValue) -> Result<String, JsError> {
    let robot = robot
        .as_string()
        .ok_or_else(|| wrong_argument("symbolic_tables", Takes::RobotFile, &robot))?;
    symbolic_tables_json(&robot).map_err(|e| JsError::new(&e))
}

/// What [`symbolic_tables`] answers, or the sentence it throws.
#[cfg(feature = "urdf")]
fn symbolic_tables_json(robot: &str) -> Result<String, String> {
    let robot = armlab_core::robot_from_json(robot).map_err(|e| e.sentence(Lang::En))?;
    Ok(armlab_core::symbolic_tables::symbolic_tables(&robot).to_text())
}

/// For the page's DH exercise (the page loads this module when a table is checked): the
/// exercise's robot file and the student's (JSON text, as the page writes a robot)
/// checked by `armlab_core::exercise::check_table`; the verdict's numbers
/// (`armlab_core::exercise_wire`). A bad robot file throws the core's sentence. Feature
/// `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen(skip_typescript)]
pub fn check_table(reference: JsValue, student: JsValue) -> Result<Vec<f64>, JsError> {
    let file = |v: &JsValue| {
        let text = v
            .as_string()
            .ok_or_else(|| wrong_argument("check_table", Takes::RobotFile, v))?;
        armlab_core::robot_from_json(&text).map_err(|e| JsError::new(&e.sentence(Lang::En)))
    };
    let verdict = armlab_core::exercise::check_table(&file(&reference)?, &file(&student)?);
    Ok(armlab_core::exercise_wire::encode_verdict(&verdict))
}

/// For the lecture room's join window (the page loads this module when a lecturer's
/// page shows it): the QR code of `text` (the join link) as lines of `1` (dark) and `0`
/// (light) modules (`armlab_room::QrModules::to_text`); "" when the text is too long for
/// a QR code. Feature `urdf`.
#[cfg(feature = "urdf")]
#[wasm_bindgen(skip_typescript)]
pub fn qr_code(text: String) -> String {
    armlab_room::QrModules::encode(&text)
        .map(|code| code.to_text())
        .unwrap_or_default()
}

/// For the page's collision check (the page loads this module only once checks are on):
/// a request of numbers (a `Float64Array` or an array of numbers) as
/// `kinematics::collision_wire` writes it (the posed parts, the floor switch and the
/// keep-out boxes) checked with the collision library; the report's numbers. A malformed
/// request throws a sentence.
#[wasm_bindgen(skip_typescript)]
pub fn collide_parts(request: JsValue) -> Result<Vec<f64>, JsError> {
    let numbers = if let Some(array) = request.dyn_ref::<Float64Array>() {
        array.to_vec()
    } else if let Some(list) = request.dyn_ref::<Array>() {
        list.iter()
            .map(|v| v.as_f64())
            .collect::<Option<Vec<f64>>>()
            .ok_or_else(|| wrong_argument("collide_parts", Takes::Numbers, &request))?
    } else {
        return Err(wrong_argument("collide_parts", Takes::Numbers, &request));
    };
    armlab_core::collision_wire::check_request(&numbers).map_err(|e| JsError::new(&e.to_string()))
}

/// The package's TypeScript declarations: the requests and answers of each function
/// (the exports themselves skip wasm-bindgen's, which would say `any`). A string request
/// is answered with a string: each function is declared twice.
#[wasm_bindgen(typescript_custom_section)]
const TYPES: &'static str = r#"
/** A preset id (`"ur10"`, `"panda"`, … as `presets()` lists them) or a whole robot file. */
export type RobotRef = string | RobotFile;

/** A robot file (assets/robots/README.md): angles in degrees, lengths in `length_unit`. */
export interface RobotFile {
  format?: string;
  name: string;
  description?: string;
  convention: "standard" | "modified";
  length_unit: "mm" | "m";
  joints: RobotJoint[];
  base?: { xyz: number[]; rpy_deg: number[] };
  tool?: { xyz: number[]; rpy_deg: number[] };
  keep_out?: { centre: number[]; size: number[] }[];
}

/** One joint of a robot file: its DH row, limits and home. */
export interface RobotJoint {
  name?: string;
  type: "revolute" | "prismatic";
  theta_deg: number;
  d: number;
  a: number;
  alpha_deg: number;
  min_deg?: number;
  max_deg?: number;
  min?: number;
  max?: number;
  home?: number;
  max_speed?: number;
  max_acceleration?: number;
}

/** A matrix as its rows. */
export type Rows = number[][];

/** One entry of `presets()`. */
export interface PresetSummary {
  id: string;
  name: string;
  dof: number;
  convention: "standard" | "modified";
  length_unit: "mm" | "m";
}

/** `robot(request)`: the robot file of a preset, or a robot file normalised. */
export interface RobotRequest {
  robot: RobotRef;
}

/** `fk(request)`: `q` in radians and length units; the robot's home pose when absent. */
export interface FkRequest {
  robot: RobotRef;
  q?: number[];
}

/** Three angles (radians) about three axes; `degenerate` at a gimbal lock. */
export interface EulerAngles {
  alpha: number;
  beta: number;
  gamma: number;
  degenerate: boolean;
}

/** The tool's orientation in four forms (radians). */
export interface OrientationForms {
  zyx_euler: EulerAngles;
  xyz_fixed: EulerAngles;
  angle_axis: { angle: number; axis: [number, number, number]; degenerate: boolean };
  /** e1, e2, e3, e4 (the scalar last). */
  euler_parameters: [number, number, number, number];
}

/** The answer of `fk`. */
export interface FkResponse {
  robot: string;
  length_unit: "mm" | "m";
  q: number[];
  /** T_0n (the tool frame included) as 4 rows. */
  tool: Rows;
  position: [number, number, number];
  orientation: OrientationForms;
  /** Every A_i as 4 rows. */
  links: Rows[];
  /** Every T_0i as 4 rows. */
  frames: Rows[];
}

/** The rows a task takes from the Jacobian. */
export type Task = "position" | "axis-x" | "axis-y" | "axis-z" | "full";

/** `jacobian(request)`: the task defaults to `"full"`. */
export interface JacobianRequest extends FkRequest {
  task?: Task;
}

/** The answer of `jacobian`: the measures are of the scaled task rows, `displayed` of the rows as shown. */
export interface JacobianResponse {
  robot: string;
  /** 6×n rows, the linear rows first. */
  geometric: Rows;
  /** 6×n rows by central differences. */
  numerical: Rows;
  /** The task's rows, unscaled. */
  task_rows: Rows;
  singular_values: number[];
  manipulability: number;
  /** Only for a square task Jacobian. */
  determinant: number | null;
  /** null when exactly singular. */
  condition_number: number | null;
  near_singular: boolean;
  length_scale: number;
  displayed: {
    manipulability: number;
    determinant: number | null;
    condition_number: number | null;
  };
}

/** The tool pose `ik` aims at: 4×4 rows, a position with an optional 3×3 rotation, or the pose FK(q). */
export type IkTarget =
  | Rows
  | { position: [number, number, number]; rotation?: Rows }
  | { q: number[] };

/** The settings of an `ik` request (all optional). */
export interface IkSettings {
  position_tolerance?: number;
  orientation_tolerance?: number;
  /** Per attempt; lowered to the call's cap. */
  max_iterations?: number;
  /** Iterations per call; lowered to the call's cap. */
  budget?: number;
  restarts?: number;
  seed?: number;
  /** Radians per call, or null for no limit. */
  max_joint_change?: number | null;
  /** Record every iteration in the answer's `trace`. */
  trace?: boolean;
  wrap?: boolean;
  objective?: "half-squared" | "squared";
}

/** `ik(request)`: `q` is the seed (the home pose when absent). */
export interface IkRequest extends FkRequest {
  target: IkTarget;
  task?: Task;
  method?: "dls" | "pinv" | "gradient" | "closed" | "closed-form";
  /** The fixed step of `"gradient"`; adaptive when absent or null. */
  alpha?: number | null;
  jacobian?: "geometric" | "numerical";
  /** One drag frame: moves at most `settings.max_joint_change` (0.1 rad by default). */
  drag?: boolean;
  settings?: IkSettings;
}

/** One iteration of a traced `ik` run. */
export interface IkStep {
  q: number[];
  raw_q: number[];
  error: number;
  position_error: number;
  orientation_error: number;
  step: number;
  damping: number;
  accepted: boolean;
  restart: boolean;
}

/** One branch of the closed form. */
export interface ClosedFormSolution {
  q: number[];
  /** The branch id, such as `"right-up-noflip"`. */
  label: string;
  within_limits: boolean;
  singular: boolean;
  exact: boolean;
  free_joints: number[];
  coincident: string[];
}

/** The answer of `ik`; `family` and `solutions` only for the closed form. */
export interface IkResponse {
  robot: string;
  method: "dls" | "pinv" | "gradient" | "closed";
  q: number[];
  success: boolean;
  unreachable: boolean;
  singular: boolean;
  clipped: boolean;
  within_limits: boolean;
  /** In the robot's length unit. */
  position_error: number;
  /** Radians. */
  orientation_error: number;
  iterations: number;
  restarts: number;
  /** FK(q) as 4 rows. */
  tool: Rows;
  wrapped_q: number[];
  /** Empty unless `settings.trace`. */
  trace: IkStep[];
  family?: string;
  solutions?: ClosedFormSolution[];
}

/** `ik_benchmark(request)`: all optional. */
export interface IkBenchmarkRequest {
  samples?: number;
  budget?: number;
  seed?: number;
  solver_tolerance?: number;
}

/** A benchmark's report, as the native benchmark binary prints it. */
export type BenchmarkReport = { [field: string]: unknown };

/** The presets. */
export function presets(): PresetSummary[];
/** A robot's file: an object for an object, JSON text for JSON text. */
export function robot(request: RobotRequest): RobotFile;
export function robot(request: string): string;
/** Forward kinematics: an object for an object, JSON text for JSON text. */
export function fk(request: FkRequest): FkResponse;
export function fk(request: string): string;
/** Jacobians and their measures: an object for an object, JSON text for JSON text. */
export function jacobian(request: JacobianRequest): JacobianResponse;
export function jacobian(request: string): string;
/** Inverse kinematics: an object for an object, JSON text for JSON text. */
export function ik(request: IkRequest): IkResponse;
export function ik(request: string): string;
/** The IK benchmark: an object for an object or nothing, JSON text for JSON text. */
export function ik_benchmark(request?: IkBenchmarkRequest): BenchmarkReport;
export function ik_benchmark(request: string): string;
/** The workspace benchmark: samples per run, runs per measure. */
export function workspace_benchmark(samples: number, repeats: number): BenchmarkReport;
/** The page's collision check: the request's numbers in, the report's numbers out. */
export function collide_parts(request: Float64Array | number[]): Float64Array;
"#;

/// The declarations of the URDF functions.
#[cfg(feature = "urdf")]
#[wasm_bindgen(typescript_custom_section)]
const URDF_TYPES: &'static str = r#"
/** A URDF text as a robot file (JSON text). Built with the feature `urdf`. */
export function urdf_to_robot(urdf: string): string;
/** A robot file (an object or its JSON text) as URDF text. Built with the feature `urdf`. */
export function robot_to_urdf(robot: RobotFile | string): string;
/** A URDF text as `{"robot", "meshes"}` (JSON text); errors in `lang` ("en", "fi"). Built with the feature `urdf`. */
export function urdf_import(urdf: string, lang?: string): string;
/** The page's symbolic matrices: a robot file (JSON text) in, its symbolic tables (the page's text form) out. Built with the feature `urdf`. */
export function symbolic_tables(robot: string): string;
"#;

#[cfg(all(test, feature = "urdf"))]
mod tests {
    use super::symbolic_tables_json;
    use armlab_core::symbolic_tables::{SymbolicTables, symbolic_tables};

    /// The page sends its robot as a robot file and reads the tables back: for every
    /// preset they are the ones the core makes from the robot itself, to the last digit.
    #[test]
    fn symbolic_tables_through_the_robot_file_are_the_cores() {
        for id in armlab_core::preset_ids() {
            let robot = armlab_core::preset(id).expect("preset");
            let answer = symbolic_tables_json(&armlab_core::robot_to_json(&robot)).expect(id);
            let tables = SymbolicTables::from_text(&answer).expect(id);
            assert_eq!(tables, symbolic_tables(&robot), "{id}");
        }
    }

    #[test]
    fn a_bad_robot_file_is_a_sentence() {
        let e = symbolic_tables_json("\u{7b}\"dh\": 5\u{7d}").expect_err("not a robot");
        assert!(!e.is_empty() && !e.contains("panick"), "{e}");
        assert!(symbolic_tables_json("not json").is_err());
    }
}
