//! Elapsed time, where the platform has a clock. `std::time::Instant::now()` traps on
//! `wasm32-unknown-unknown` (no clock without JavaScript imports, and calling an import would
//! need `unsafe`): there a [`Stopwatch`] reads 0 s and the page times its calls itself. Everywhere
//! else it is `Instant`. (The `web-time` crate would read `performance.now()`, but only through
//! `wasm-bindgen`'s JavaScript glue, which the binding does not use.)

/// Whether this build has a clock (false on `wasm32-unknown-unknown`).
pub const HAS_CLOCK: bool = !cfg!(all(target_arch = "wasm32", target_os = "unknown"));

/// Time since it was started.
#[derive(Clone, Copy, Debug)]
pub struct Stopwatch {
    #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
    start: std::time::Instant,
}

impl Stopwatch {
    /// Starts now.
    #[must_use]
    pub fn start() -> Self {
        Self {
            #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
            start: std::time::Instant::now(),
        }
    }

    /// Seconds since [`Stopwatch::start`] (0 without a clock).
    #[must_use]
    pub fn seconds(&self) -> f64 {
        #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
        {
            self.start.elapsed().as_secs_f64()
        }
        #[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
        {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stopwatch_runs_forward_where_there_is_a_clock() {
        let watch = Stopwatch::start();
        let a = watch.seconds();
        let b = watch.seconds();
        const { assert!(HAS_CLOCK) };
        assert!(a >= 0.0 && b >= a, "{a} {b}");
    }
}
