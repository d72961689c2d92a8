//! `window.armlab`, the browser tests' hook: what the last frame published (the state's
//! JSON once a script asked for it, the screen points, the 3D view's rectangle), the
//! frames' times, and the benchmarks and test switches the page offers scripts.

use std::cell::{Cell, RefCell};

use wasm_bindgen::prelude::*;

use super::{set_field, wake};
use crate::app::platform::clock::{FrameTime, now_ms};

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
    /// What the last frame published.
    static HOOK: RefCell<Published> = const {
        RefCell::new(Published { state: String::new(), points: Vec::new(), view_rect: None, css_per_point: 1.0 })
    };
    /// Whether a script has asked for `window.armlab.state()`: until then no frame builds
    /// its JSON (about 30 µs natively, 7 % of a dragging frame's app time), which no
    /// visitor reads.
    static STATE_WANTED: Cell<bool> = const { Cell::new(false) };
    /// Recent frame times for `window.armlab.frameTimes()`.
    static FRAMES: RefCell<Vec<FrameTime>> = const { RefCell::new(Vec::new()) };
    /// Set by `window.armlab.panicForTest()`: the next frame panics.
    static PANIC_REQUESTED: Cell<bool> = const { Cell::new(false) };
    /// `window.armlab.classroom()`'s JSON, as the last frame wrote it.
    static CLASSROOM: RefCell<String> = const { RefCell::new(String::new()) };
    /// Whether a script has asked for `window.armlab.classroom()`: until then no frame
    /// builds its JSON (as for `state()`).
    static CLASSROOM_WANTED: Cell<bool> = const { Cell::new(false) };
    /// `performance.now()` at the first drawn frame.
    static FIRST_FRAME: RefCell<Option<f64>> = const { RefCell::new(None) };
}

/// Panics when `window.armlab.panicForTest()` asked for it (the browser test of the crash
/// screen).
pub fn panic_if_asked() {
    if PANIC_REQUESTED.with(Cell::take) {
        panic!("a panic asked for by window.armlab.panicForTest()");
    }
}

/// Publishes a frame for `window.armlab`: the state's JSON (`state` is called only once a
/// script has asked for it), the named screen points and the 3D view's rectangle (egui
/// points), whether the view has drawn (the first such frame is `firstFrameAt`), and the
/// frame's times, `last`, whose `hook_ms` becomes the time since `started_ms` (when the
/// app began publishing).
pub fn publish(
    ctx: &egui::Context,
    state: impl FnOnce() -> String,
    points: &[(String, [f32; 2])],
    view_rect: Option<egui::Rect>,
    rendered: bool,
    last: Option<FrameTime>,
    started_ms: f64,
) {
    // egui points to CSS pixels: the canvas fills the page from (0, 0).
    let css_per_point = ctx.pixels_per_point() / ctx.native_pixels_per_point().unwrap_or(1.0);
    let state = if STATE_WANTED.with(Cell::get) {
        state()
    } else {
        String::new()
    };
    HOOK.with(|h| {
        *h.borrow_mut() = Published {
            state,
            points: points.to_vec(),
            view_rect: view_rect.map(|r| [r.min.x, r.min.y, r.width(), r.height()]),
            css_per_point,
        }
    });
    FIRST_FRAME.with(|f| {
        if f.borrow().is_none() && rendered {
            *f.borrow_mut() = Some(now_ms());
        }
    });
    if let Some(mut t) = last {
        t.hook_ms = now_ms() - started_ms;
        FRAMES.with(|f| {
            let mut f = f.borrow_mut();
            if f.len() >= 5000 {
                f.remove(0);
            }
            f.push(t);
        });
    }
}

/// Publishes the lecture room's state for `window.armlab.classroom()`.
/// `json` is called only once a script has asked for it.
pub fn publish_classroom(json: impl FnOnce() -> String) {
    if CLASSROOM_WANTED.with(Cell::get) {
        CLASSROOM.with(|c| *c.borrow_mut() = json());
    }
}

/// Sets `window.armlab` (docs/test-hook.md lists its functions).
pub fn install(window: &web_sys::Window) {
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
    let open = Closure::<dyn Fn(String)>::new(super::storage::open_later);
    set_field(&obj, "open", &open.into_js_value());
    let first = Closure::<dyn Fn() -> JsValue>::new(|| {
        FIRST_FRAME.with(|f| f.borrow().map_or(JsValue::NULL, JsValue::from))
    });
    set_field(&obj, "firstFrameAt", &first.into_js_value());
    // As `state()`: the first call asks for a frame that builds the JSON, and gets "".
    let classroom = Closure::<dyn Fn() -> String>::new(|| {
        if !CLASSROOM_WANTED.with(|w| w.replace(true)) {
            wake();
        }
        CLASSROOM.with(|c| c.borrow().clone())
    });
    set_field(&obj, "classroom", &classroom.into_js_value());
    // The wasm memory's size in bytes (for the soak test: it only grows, in steps).
    let memory = Closure::<dyn Fn() -> JsValue>::new(|| {
        js_sys::Reflect::get(&wasm_bindgen::memory(), &"buffer".into())
            .and_then(|buffer| js_sys::Reflect::get(&buffer, &"byteLength".into()))
            .unwrap_or(JsValue::NULL)
    });
    set_field(&obj, "memoryBytes", &memory.into_js_value());
    let mirror = Closure::<dyn Fn()>::new(super::a11y::ask_for_tree);
    set_field(&obj, "mirrorNow", &mirror.into_js_value());
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
            let start = now_ms();
            let mut cloud = WorkspaceCloud::new(&robot, measure, samples as usize, 0x5eed);
            cloud.fill(samples as usize);
            let ms = now_ms() - start;
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
        let (mut colliding, start) = (0usize, now_ms());
        for q in &qs {
            fk.update(&robot, q);
            match checker.check_with(&robot, &fk, super::modules::collide_parts) {
                Some(report) => colliding += usize::from(!report.is_free()),
                None => return JsValue::NULL,
            }
        }
        let us = 1e3 * (now_ms() - start) / qs.len() as f64;
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
