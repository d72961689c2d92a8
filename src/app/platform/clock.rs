//! The app's clock, for its own frame timing (the core has no clock).

/// Milliseconds from an arbitrary origin, for the app's own frame timing (the core has
/// no clock). `performance.now()` on the web, `Instant` natively.
pub fn now_ms() -> f64 {
    #[cfg(target_arch = "wasm32")]
    {
        // The clock object is looked up once. Looking up `window.performance` through
        // wasm-bindgen in every call would take about 2 % of a drag frame's main-thread
        // time in a CPU profile of the page (a frame reads the clock about ten times).
        thread_local! {
            static PERFORMANCE: Option<web_sys::Performance> =
                web_sys::window().and_then(|w| w.performance());
        }
        PERFORMANCE.with(|p| p.as_ref().map_or(0.0, |p| p.now()))
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        use std::sync::OnceLock;
        static START: OnceLock<std::time::Instant> = OnceLock::new();
        START
            .get_or_init(std::time::Instant::now)
            .elapsed()
            .as_secs_f64()
            * 1e3
    }
}

/// Main-thread milliseconds of one frame of the app, in parts.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrameTime {
    /// The app's own work: egui layout of every panel, scene preparation and IK; all of
    /// the frame except `render_ms`.
    pub app_ms: f64,
    /// Of `app_ms`: the IK step of a drag.
    pub ik_ms: f64,
    /// Of `app_ms`: building the scene (instances, lines, camera).
    pub scene_ms: f64,
    /// Encoding and submitting the 3D view's draw calls to wgpu (GPU work issued from the
    /// main thread: on WebGL2 these are the GL calls).
    pub render_ms: f64,
    /// Of `app_ms`: filling the workspace cloud (at most about 4 ms a frame).
    pub workspace_ms: f64,
    /// Of `app_ms`: the motion simulation's steps (and their collision checks).
    pub motion_ms: f64,
    /// The simulation steps (1 ms each) run in the frame.
    pub motion_steps: f64,
    /// After `app_ms`, not part of it: publishing the frame for the browser tests' hook
    /// (`window.armlab`), which writes the whole state as JSON in every frame once a script
    /// has asked for it. A person's frames never pay this; a test's do, so it is kept
    /// apart from the app's time and reported on its own.
    pub hook_ms: f64,
}
