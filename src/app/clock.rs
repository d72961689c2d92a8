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
