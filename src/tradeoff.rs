//! What accuracy costs, measured (product.md `whitted tradeoff`): one scene rendered under many
//! settings — sampling mode (§8), recursion depth (§6), acceleration structure (§7, §9) — each
//! timed and counted, and its image compared with a reference image of the same scene (adaptive
//! sampling with threshold 0 and K = 3, i.e. every one of the 81 lattice points of a pixel's area,
//! area-weighted, and `max_depth` 16).
//!
//! The settings vary one thing at a time around the scene's own render (centre sampling, the
//! scene's `max_depth`, the BVH): the sampling modes, then the depths, then the structures. The
//! errors are taken on the linear colours clamped to [0, 1], what the image file shows before its
//! 8-bit rounding: the root mean square and the largest difference over pixels and channels, and
//! the share of pixels with a channel off by more than 1/255.

use crate::accel::{Accel, AccelKind, AccelOptions};
use crate::clock::Stopwatch;
use crate::image::Image;
use crate::record::stats::Stats;
use crate::render::{render, RenderConfig, Rendered};
use crate::sample::Sampling;
use crate::scene::Scene;
use crate::shape::Dim;

/// The most renders of one setting `--runs` may ask for: medians steady well before this.
pub const MAX_RUNS: u32 = 100;
/// The reference: adaptive, threshold 0, K = 3 (81 shared samples per pixel area).
pub const REFERENCE_SAMPLING: Sampling = Sampling::Adaptive { threshold: 0.0, max_level: 3 };
/// The reference's `max_depth`.
pub const REFERENCE_DEPTH: u32 = 16;
/// The adaptive thresholds of the sampling sweep.
pub const THRESHOLDS: [f64; 3] = [0.3, 0.1, 0.03];
/// The adaptive levels K of the sampling sweep.
pub const LEVELS: [u32; 3] = [1, 2, 3];
/// The deepest `max_depth` the depth sweep visits one by one (a deeper scene adds its own).
pub const DEPTHS_UP_TO: u32 = 8;

/// One way to render the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setting {
    /// The sampling mode.
    pub sampling: Sampling,
    /// The `max_depth`.
    pub depth: u32,
    /// The acceleration structure.
    pub accel: AccelKind,
}

/// The settings of a scene whose own `max_depth` is `depth`: centre, corners and adaptive at
/// every threshold × level of [`THRESHOLDS`] × [`LEVELS`]; then the depths 0 … `min(depth, 8)`
/// (and `depth` itself if deeper); then every structure, each with the others at the scene's
/// render, which is listed once.
#[must_use]
pub fn settings(depth: u32) -> Vec<Setting> {
    let base = Setting { sampling: Sampling::Center, depth, accel: AccelKind::Bvh };
    let mut out = vec![base, Setting { sampling: Sampling::Corners, ..base }];
    for max_level in LEVELS {
        for threshold in THRESHOLDS {
            out.push(Setting { sampling: Sampling::Adaptive { threshold, max_level }, ..base });
        }
    }
    let depths = (0..=depth.min(DEPTHS_UP_TO)).chain((depth > DEPTHS_UP_TO).then_some(depth));
    out.extend(depths.filter(|d| *d != depth).map(|d| Setting { depth: d, ..base }));
    out.extend(
        AccelKind::ALL.into_iter().filter(|k| *k != base.accel).map(|accel| Setting { accel, ..base }),
    );
    out
}

/// A sampling mode in a few words: `center`, `corners`, `adaptive 0.1, K = 2`.
#[must_use]
pub fn sampling_name(sampling: Sampling) -> String {
    match sampling {
        Sampling::Adaptive { threshold, max_level } => format!("adaptive {threshold}, K = {max_level}"),
        other => other.name().to_owned(),
    }
}

/// Which of the three sweeps a setting belongs to: what it changes from the scene's render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sweep {
    /// The sampling mode (the scene's render itself belongs here).
    Sampling,
    /// The `max_depth`.
    Depth,
    /// The acceleration structure.
    Accel,
}

impl Sweep {
    /// The sweep of `setting`, from how it differs from the scene's render `base`.
    #[must_use]
    pub fn of(setting: &Setting, base: &Setting) -> Self {
        if setting.depth != base.depth {
            Self::Depth
        } else if setting.accel != base.accel {
            Self::Accel
        } else {
            Self::Sampling
        }
    }
}

/// A setting by what it changes from the scene's render `base`: `max_depth 3`, `grid`, or its
/// sampling ([`sampling_name`]).
#[must_use]
pub fn setting_name(setting: &Setting, base: &Setting) -> String {
    match Sweep::of(setting, base) {
        Sweep::Depth => format!("max_depth {}", setting.depth),
        Sweep::Accel => setting.accel.name().to_owned(),
        Sweep::Sampling => sampling_name(setting.sampling),
    }
}

/// How an image differs from the reference (clamped linear colours).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImageError {
    /// `sqrt(mean over pixels and channels of (a − b)²)`.
    pub rmse: f64,
    /// The largest `|a − b|` over pixels and channels.
    pub max: f64,
    /// The share of pixels (0 … 1) with some channel `|a − b| > 1/255`.
    pub off: f64,
}

/// Compares two images of the same size, channel by channel, after clamping both to [0, 1].
///
/// # Panics
/// If the sizes differ (a caller's bug: both come from the same camera).
#[must_use]
pub fn compare(image: &Image, reference: &Image) -> ImageError {
    assert_eq!((image.width, image.height), (reference.width, reference.height), "images of one camera");
    let (mut sum, mut max, mut off) = (0.0_f64, 0.0_f64, 0_usize);
    for (a, b) in image.pixels.iter().zip(&reference.pixels) {
        let mut pixel_max = 0.0_f64;
        for c in 0..3 {
            let d = (a.0[c].clamp(0.0, 1.0) - b.0[c].clamp(0.0, 1.0)).abs();
            sum += d * d;
            pixel_max = pixel_max.max(d);
        }
        max = max.max(pixel_max);
        off += usize::from(pixel_max > 1.0 / 255.0);
    }
    let pixels = image.pixels.len().max(1) as f64;
    ImageError { rmse: (sum / (3.0 * pixels)).sqrt(), max, off: off as f64 / pixels }
}

/// One setting, measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measured {
    /// What was rendered.
    pub setting: Setting,
    /// The median trace time over the runs, seconds.
    pub seconds: f64,
    /// Rays and tests of one render.
    pub stats: Stats,
    /// Pixels computed (a 2D strip counts its one row).
    pub pixels: u64,
    /// Against the reference.
    pub error: ImageError,
}

impl Measured {
    /// `n` (rays of some kind) per computed pixel.
    #[must_use]
    pub fn per_pixel(&self, n: u64) -> f64 {
        n as f64 / self.pixels.max(1) as f64
    }
    /// Rays of every kind per computed pixel.
    #[must_use]
    pub fn rays_per_pixel(&self) -> f64 {
        self.per_pixel(self.stats.rays.total())
    }
    /// Intersection tests (objects, bounding volumes, nodes, cells) per ray.
    #[must_use]
    pub fn tests_per_ray(&self) -> f64 {
        let t = self.stats.tests;
        (t.object + t.bound + t.node + t.voxel) as f64 / self.stats.rays.total().max(1) as f64
    }
}

/// The whole measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct Tradeoff {
    /// The reference render, measured like the others (its error is zero).
    pub reference: Measured,
    /// Every setting of [`settings`], in that order.
    pub rows: Vec<Measured>,
    /// Renders per setting (the time is their median).
    pub runs: usize,
}

/// Renders `setting` `runs` times (at least once) in the current rayon pool: the median trace
/// time and the last render.
fn measure<V: Dim>(scene: &Scene<V>, setting: Setting, runs: usize) -> (f64, Rendered) {
    let accel = Accel::build_with(scene, &AccelOptions::of(setting.accel));
    let config = RenderConfig { sampling: setting.sampling, ..RenderConfig::centers(setting.depth) };
    let timed = || {
        let watch = Stopwatch::start();
        let rendered = render(scene, &accel, &config);
        (watch.seconds(), rendered)
    };
    let (first, mut rendered) = timed();
    let mut times = vec![first];
    for _ in 1..runs {
        let (seconds, again) = timed();
        times.push(seconds);
        rendered = again;
    }
    times.sort_by(f64::total_cmp);
    (median(&times), rendered)
}

/// The median of sorted values (the mean of the middle two for an even count).
fn median(sorted: &[f64]) -> f64 {
    match sorted.len() {
        0 => 0.0,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// Measures every setting of the scene against the reference, `runs` renders each, in the
/// current rayon pool; `progress` hears each setting as it starts (the reference first).
pub fn run<V: Dim>(scene: &Scene<V>, runs: usize, mut progress: impl FnMut(&Setting)) -> Tradeoff {
    let reference_setting =
        Setting { sampling: REFERENCE_SAMPLING, depth: REFERENCE_DEPTH, accel: AccelKind::Bvh };
    progress(&reference_setting);
    let (seconds, reference_image) = measure(scene, reference_setting, runs);
    let reference = Measured {
        setting: reference_setting,
        seconds,
        stats: reference_image.stats,
        pixels: reference_image.pixels,
        error: ImageError::default(),
    };
    let rows = settings(scene.max_depth)
        .into_iter()
        .map(|setting| {
            progress(&setting);
            let (seconds, rendered) = measure(scene, setting, runs);
            Measured {
                setting,
                seconds,
                stats: rendered.stats,
                pixels: rendered.pixels,
                error: compare(&rendered.image, &reference_image.image),
            }
        })
        .collect();
    Tradeoff { reference, rows, runs }
}

/// The indices of the rows on the Pareto front of (time, RMSE): no other row is at least as fast
/// and at least as accurate while better in one; ordered by time.
#[must_use]
pub fn pareto_front(rows: &[Measured]) -> Vec<usize> {
    let dominates = |a: &Measured, b: &Measured| {
        a.seconds <= b.seconds
            && a.error.rmse <= b.error.rmse
            && (a.seconds < b.seconds || a.error.rmse < b.error.rmse)
    };
    let mut front: Vec<usize> =
        (0..rows.len()).filter(|&i| !rows.iter().any(|other| dominates(other, &rows[i]))).collect();
    front.sort_by(|&a, &b| rows[a].seconds.total_cmp(&rows[b].seconds).then(a.cmp(&b)));
    front
}

#[cfg(test)]
// These tests pin exact results on purpose.
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::scene::material::Rgb;

    fn image(values: &[[f64; 3]]) -> Image {
        Image { width: values.len(), height: 1, pixels: values.iter().map(|v| Rgb(*v)).collect() }
    }

    #[test]
    fn the_error_is_taken_on_clamped_channels() {
        let reference = image(&[[0.5, 0.5, 0.5], [1.0, 0.0, 0.2], [0.0, 0.0, 0.0]]);
        // Pixel 0 is off by 0.1 in red; pixel 1 by nothing visible (2 clamps to 1, −1 to 0);
        // pixel 2 by 1/510 in blue, under 1/255.
        let test = image(&[[0.6, 0.5, 0.5], [2.0, -1.0, 0.2], [0.0, 0.0, 1.0 / 510.0]]);
        let e = compare(&test, &reference);
        let sum = 0.1_f64.powi(2) + (1.0_f64 / 510.0).powi(2);
        assert!((e.rmse - (sum / 9.0).sqrt()).abs() < 1e-15, "{}", e.rmse);
        assert!((e.max - 0.1).abs() < 1e-15);
        assert_eq!(e.off, 1.0 / 3.0);
        assert_eq!(compare(&reference, &reference), ImageError::default());
    }

    #[test]
    fn settings_vary_one_thing_at_a_time_and_list_the_scene_render_once() {
        let s = settings(4);
        // 2 + 9 sampling modes, depths 0..=3 (4 is the scene's), 4 other structures.
        assert_eq!(s.len(), 11 + 4 + 4);
        let base = s[0];
        assert_eq!(base, Setting { sampling: Sampling::Center, depth: 4, accel: AccelKind::Bvh });
        assert_eq!(s.iter().filter(|x| **x == base).count(), 1);
        for x in &s[1..] {
            let changed = usize::from(x.sampling != base.sampling)
                + usize::from(x.depth != base.depth)
                + usize::from(x.accel != base.accel);
            assert_eq!(changed, 1, "{x:?}");
        }
        // A deep scene: 0..=8 and its own depth.
        let deep: Vec<u32> = settings(20).iter().map(|x| x.depth).filter(|d| *d != 20).collect();
        assert_eq!(deep, (0..=8).collect::<Vec<_>>());
    }

    #[test]
    fn the_pareto_front_keeps_what_nothing_beats() {
        let row = |seconds: f64, rmse: f64| Measured {
            setting: Setting { sampling: Sampling::Center, depth: 1, accel: AccelKind::None },
            seconds,
            stats: Stats::default(),
            pixels: 1,
            error: ImageError { rmse, ..ImageError::default() },
        };
        // 0 fast and rough, 1 dominated by 0, 2 slow and exact, 3 between, 4 a tie of 3.
        let rows = [row(1.0, 0.5), row(2.0, 0.6), row(9.0, 0.0), row(3.0, 0.2), row(3.0, 0.2)];
        assert_eq!(pareto_front(&rows), vec![0, 3, 4, 2]);
        assert_eq!(median(&[1.0, 2.0, 10.0]), 2.0);
        assert_eq!(median(&[1.0, 2.0, 3.0, 10.0]), 2.5);
    }
}
