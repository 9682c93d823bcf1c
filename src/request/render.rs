//! An image and its statistics (`whitted render`): the structure built and the image rendered,
//! each timed (0 s where there is no clock, see `clock`), and the object `render --json` prints.

use super::Failure;
use crate::accel::{Accel, AccelOptions};
use crate::clock::Stopwatch;
use crate::doc::float;
use crate::render::{check_fits, render_as, RenderConfig, Rendered, EDGE_MEMORY};
use crate::sample::Sampling;
use crate::scene::Scene;
use crate::shape::Dim;
use serde_json::{json, Value};

/// A finished render.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The image, as the bytes of its file (all a command line or a page shows of it: 3 bytes a
    /// pixel, not 24), and its statistics.
    pub rendered: Rendered<[u8; 3]>,
    /// Seconds to build the structure.
    pub build_seconds: f64,
    /// Seconds to render.
    pub seconds: f64,
    /// The structure's name (`--accel`).
    pub accel: &'static str,
    /// The sampling rendered with.
    pub sampling: Sampling,
}

/// How to render: what `--depth`, `--aa` and `--accel` chose, the strip's rows of a resized 2D
/// scene, and a progress callback (pixel rows done) for a bar.
#[derive(Clone, Copy)]
pub struct Job<'a> {
    /// `--depth`, else the scene's `max_depth`.
    pub depth: Option<u32>,
    /// The sampling.
    pub sampling: Sampling,
    /// The structure's options.
    pub accel: &'a AccelOptions,
    /// The rows of a 2D strip (`options::resize`'s answer).
    pub strip_rows: Option<usize>,
    /// Called with the rows finished, from any thread.
    pub progress: Option<&'a (dyn Fn(u64) + Sync)>,
}

/// Builds the structure and renders the scene (in the current rayon pool), after checking that
/// the image fits (`render::check_fits`).
///
/// # Errors
/// Bad input: an image too large, naming `--size`.
pub fn run<V: Dim>(scene: &Scene<V>, job: &Job<'_>) -> Result<Outcome, Failure> {
    let config = RenderConfig {
        sampling: job.sampling,
        max_depth: job.depth.unwrap_or(scene.max_depth),
        strip_rows: job.strip_rows,
        rays_per_pixel: false,
        progress: job.progress,
        edge_memory: EDGE_MEMORY,
    };
    check_fits(scene, &config, rayon::current_num_threads())
        .map_err(|e| Failure::input(format!("render: {e}")))?;
    let build = Stopwatch::start();
    let accel = Accel::build_for_render(scene, job.accel);
    let build_seconds = build.seconds();
    let watch = Stopwatch::start();
    let rendered = render_as(scene, &accel, &config);
    let seconds = watch.seconds();
    Ok(Outcome { rendered, build_seconds, seconds, accel: accel.kind().name(), sampling: job.sampling })
}

impl Outcome {
    /// The object `whitted render --json` prints: `pixels`, `samples`, `load_seconds`,
    /// `build_seconds`, `seconds`, `threads`, `accel`, `aa`, `width`, `height`, `output` (when
    /// a file was written), `rays`, `tests`, and `threshold`, `max_level` for adaptive sampling.
    #[must_use]
    pub fn json(&self, load_seconds: f64, threads: usize, output: Option<&str>) -> Value {
        let rays = self.rendered.stats.rays;
        let mut doc = json!({
            "pixels": self.rendered.pixels,
            "samples": rays.primary,
            "load_seconds": load_seconds,
            "build_seconds": self.build_seconds,
            "seconds": self.seconds,
            "threads": threads,
            "accel": self.accel,
            "aa": self.sampling.name(),
            "width": self.rendered.image.width,
            "height": self.rendered.image.height,
        });
        if let Some(path) = output {
            doc["output"] = json!(path);
        }
        let st = crate::doc::stats(&self.rendered.stats);
        doc["rays"] = st["rays"].clone();
        doc["tests"] = st["tests"].clone();
        if let Sampling::Adaptive { threshold, max_level } = self.sampling {
            doc["threshold"] = float(threshold);
            doc["max_level"] = json!(max_level);
        }
        doc
    }
}
