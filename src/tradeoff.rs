//! What accuracy costs, measured: one scene rendered under many settings, each compared with a
//! reference that differs from it in one thing only, so that a row's error is the error of what
//! it varies. The three sweeps (sampling, depth, structure), their references and the output are
//! product.md "whitted tradeoff"; the constants below hold their numbers.
//!
//! A setting's cost is counted (rays and tests by kind, the render's own stats) and timed
//! ([`Timing`] over `runs` renders). The Pareto front is decided on the rays traced, which neither
//! the machine nor its load changes. The errors are taken on the linear colours clamped to
//! [0, 1], what the image file shows before its 8-bit rounding ([`compare`]).

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
/// Renders per setting when `--runs` is not given: enough for a median and a spread.
pub const DEFAULT_RUNS: u32 = 5;
/// The sampling sweep's reference: adaptive, threshold 0, K = 3 (81 shared samples per pixel
/// area).
pub const REFERENCE_SAMPLING: Sampling = Sampling::Adaptive { threshold: 0.0, max_level: 3 };
/// The depth sweep's reference `max_depth` (the scene's own if deeper).
pub const REFERENCE_DEPTH: u32 = 16;
/// The structure sweep's reference: brute force, every object tested by every ray.
pub const REFERENCE_ACCEL: AccelKind = AccelKind::None;
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

impl Setting {
    /// The scene's own render: centre sampling, its `max_depth`, the BVH.
    #[must_use]
    pub fn scene_render(depth: u32) -> Self {
        Self { sampling: Sampling::Center, depth, accel: AccelKind::Bvh }
    }
}

/// What a sweep varies; its settings keep the rest at the scene's render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sweep {
    /// The sampling mode.
    Sampling,
    /// The `max_depth`.
    Depth,
    /// The acceleration structure.
    Accel,
}

impl Sweep {
    /// The three sweeps, in the order they are measured and shown.
    pub const ALL: [Self; 3] = [Self::Sampling, Self::Depth, Self::Accel];

    /// A short name: `sampling`, `depth`, `structure` (the plot files' and JSON keys).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Sampling => "sampling",
            Self::Depth => "depth",
            Self::Accel => "structure",
        }
    }

    /// The settings of this sweep for a scene whose own `max_depth` is `depth`, in order:
    /// centre, corners, then adaptive at every level of [`LEVELS`] × threshold of [`THRESHOLDS`];
    /// the depths 0 … 8 (and `depth` if deeper); every structure but the reference's.
    #[must_use]
    pub fn settings(self, depth: u32) -> Vec<Setting> {
        let base = Setting::scene_render(depth);
        match self {
            Self::Sampling => {
                let adaptive = LEVELS.into_iter().flat_map(|max_level| {
                    THRESHOLDS.map(|threshold| Sampling::Adaptive { threshold, max_level })
                });
                [Sampling::Center, Sampling::Corners]
                    .into_iter()
                    .chain(adaptive)
                    .map(|sampling| Setting { sampling, ..base })
                    .collect()
            }
            Self::Depth => (0..=DEPTHS_UP_TO)
                .chain((depth > DEPTHS_UP_TO).then_some(depth))
                .map(|depth| Setting { depth, ..base })
                .collect(),
            Self::Accel => AccelKind::ALL
                .into_iter()
                .filter(|k| *k != REFERENCE_ACCEL)
                .map(|accel| Setting { accel, ..base })
                .collect(),
        }
    }

    /// The reference of this sweep: the scene's render with only this sweep's field changed.
    #[must_use]
    pub fn reference(self, depth: u32) -> Setting {
        let base = Setting::scene_render(depth);
        match self {
            Self::Sampling => Setting { sampling: REFERENCE_SAMPLING, ..base },
            Self::Depth => Setting { depth: depth.max(REFERENCE_DEPTH), ..base },
            Self::Accel => Setting { accel: REFERENCE_ACCEL, ..base },
        }
    }

    /// A setting of this sweep by the one thing it varies: `adaptive 0.1, K = 2`, `max_depth 3`,
    /// `grid`.
    #[must_use]
    pub fn setting_name(self, setting: &Setting) -> String {
        match self {
            Self::Sampling => sampling_name(setting.sampling),
            Self::Depth => format!("max_depth {}", setting.depth),
            Self::Accel => setting.accel.name().to_owned(),
        }
    }
}

/// A sampling mode in a few words: `center`, `corners`, `adaptive 0.1, K = 2`.
#[must_use]
pub fn sampling_name(sampling: Sampling) -> String {
    match sampling {
        Sampling::Adaptive { threshold, max_level } => format!("adaptive {threshold}, K = {max_level}"),
        other => other.name().to_owned(),
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

/// The trace times of a setting's renders, seconds: their spread and median.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timing {
    /// The fastest render.
    pub min: f64,
    /// The median (the mean of the middle two for an even count).
    pub median: f64,
    /// The slowest render.
    pub max: f64,
}

impl Timing {
    /// The timing of some renders' times (none: all zero).
    #[must_use]
    pub fn of(mut times: Vec<f64>) -> Self {
        times.sort_by(f64::total_cmp);
        let n = times.len();
        let median = match n {
            0 => 0.0,
            n if n % 2 == 1 => times[n / 2],
            n => 0.5 * (times[n / 2 - 1] + times[n / 2]),
        };
        Self { min: times.first().copied().unwrap_or(0.0), median, max: times.last().copied().unwrap_or(0.0) }
    }
}

/// One setting, measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measured {
    /// What was rendered.
    pub setting: Setting,
    /// The trace times over the runs.
    pub time: Timing,
    /// Rays and tests of one render (the same in every run).
    pub stats: Stats,
    /// Pixels computed (a 2D strip counts its one row).
    pub pixels: u64,
    /// Against the sweep's reference.
    pub error: ImageError,
}

impl Measured {
    /// `n` (rays of some kind) per computed pixel.
    #[must_use]
    pub fn per_pixel(&self, n: u64) -> f64 {
        n as f64 / self.pixels.max(1) as f64
    }
    /// Rays of every kind per computed pixel: the cost the Pareto front is decided on.
    #[must_use]
    pub fn rays_per_pixel(&self) -> f64 {
        self.per_pixel(self.stats.rays.total())
    }
    /// Intersection tests of every kind (objects, bounding volumes, nodes, cells).
    #[must_use]
    pub fn tests(&self) -> u64 {
        let t = self.stats.tests;
        t.object + t.bound + t.node + t.voxel
    }
    /// Intersection tests per ray.
    #[must_use]
    pub fn tests_per_ray(&self) -> f64 {
        self.tests() as f64 / self.stats.rays.total().max(1) as f64
    }
    /// Reflected and transmitted rays: those `max_depth` limits.
    #[must_use]
    pub fn secondary(&self) -> u64 {
        self.stats.rays.reflected + self.stats.rays.transmitted
    }
}

/// One sweep, measured: its reference and its rows, each compared with that reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// What the sweep varies.
    pub sweep: Sweep,
    /// The reference render, measured like the rows (its error is zero).
    pub reference: Measured,
    /// The settings of [`Sweep::settings`], in that order.
    pub rows: Vec<Measured>,
}

impl Measurement {
    /// The indices of the rows on the Pareto front of (rays traced, RMSE): no other row traces
    /// at most as many rays with at most the error, fewer or less in one; ordered by rays.
    #[must_use]
    pub fn pareto_front(&self) -> Vec<usize> {
        pareto_front(&self.rows)
    }

    /// A line per row saying why its result is what it is, computed from the counts.
    #[must_use]
    pub fn reasons(&self) -> Vec<String> {
        (0..self.rows.len()).map(|i| self.reason(i)).collect()
    }

    fn reason(&self, i: usize) -> String {
        match self.sweep {
            Sweep::Sampling => self.sampling_reason(i),
            Sweep::Depth => self.depth_reason(i),
            Sweep::Accel => self.accel_reason(i),
        }
    }

    /// Sampling: the samples a pixel, and the row that beats it if one does.
    fn sampling_reason(&self, i: usize) -> String {
        let m = &self.rows[i];
        let r = m.stats.rays;
        let out = format!(
            "{:.2} primary rays a pixel, each with its tree: {:.2} rays a pixel in all",
            m.per_pixel(r.primary),
            m.rays_per_pixel()
        );
        let beaten_by = (0..self.rows.len())
            .filter(|&j| dominates(&self.rows[j], m))
            .min_by_key(|&j| self.rows[j].stats.rays.total());
        let front = self.pareto_front();
        let before =
            front.iter().position(|&j| j == i).and_then(|k| k.checked_sub(1)).map(|k| &self.rows[front[k]]);
        let name = |r: &Measured| self.sweep.setting_name(&r.setting);
        let why = match (beaten_by, before) {
            _ if m.error.rmse == 0.0 => "the reference's image, exactly".to_owned(),
            (Some(j), _) => {
                let b = &self.rows[j];
                format!(
                    "off the front: {} traces {:.2} rays a pixel for an RMSE of {:.5}",
                    name(b),
                    b.rays_per_pixel(),
                    b.error.rmse
                )
            }
            (None, Some(b)) => format!(
                "on the front: {:.0} % less error than {} for {:.2}× its rays",
                100.0 * (1.0 - m.error.rmse / b.error.rmse),
                name(b),
                m.stats.rays.total() as f64 / b.stats.rays.total().max(1) as f64
            ),
            (None, None) => "on the front, with the fewest rays".to_owned(),
        };
        format!("{out}; {why}")
    }

    /// Depth: the rays of level `d`, from the row at `d − 1`, and those the reference traces
    /// beyond `d`.
    fn depth_reason(&self, i: usize) -> String {
        let m = &self.rows[i];
        let d = m.setting.depth;
        let below = self.rows.iter().find(|p| d > 0 && p.setting.depth == d - 1);
        let level = match below {
            _ if d == 0 => "ray casting: primary and shadow rays only".to_owned(),
            Some(p) if p.stats == m.stats => {
                format!("max_depth {} → {d} changes nothing: no ray of this scene reaches level {d}", d - 1)
            }
            Some(p) => format!(
                "level {d} adds {:.3} reflected and {:.3} transmitted rays a pixel",
                m.per_pixel(m.stats.rays.reflected - p.stats.rays.reflected.min(m.stats.rays.reflected)),
                m.per_pixel(
                    m.stats.rays.transmitted - p.stats.rays.transmitted.min(m.stats.rays.transmitted)
                ),
            ),
            None => format!("levels 0 … {d}"),
        };
        let deeper = self.reference.secondary().saturating_sub(m.secondary());
        let past = if deeper == 0 {
            format!("no ray goes past level {d}, so the image is the reference's")
        } else {
            format!(
                "the reference traces {:.3} more reflected and transmitted rays a pixel past level {d}",
                m.per_pixel(deeper)
            )
        };
        format!("{level}; {past}")
    }

    /// Structure: the error (0 by design), and the tests per ray against brute force's.
    fn accel_reason(&self, i: usize) -> String {
        let m = &self.rows[i];
        let t = m.stats.tests;
        let same = if m.error == ImageError::default() {
            "error 0: a structure changes which objects a ray is tested against, never which one it hits first"
        } else {
            "differs from brute force: a structure must not change a pixel (a bug)"
        };
        format!(
            "{same}; {:.2} tests a ray ({} objects, {} bounds, {} nodes, {} cells), {:.2}× brute force's {:.2}",
            m.tests_per_ray(),
            t.object,
            t.bound,
            t.node,
            t.voxel,
            m.tests() as f64 / self.reference.tests().max(1) as f64,
            self.reference.tests_per_ray(),
        )
    }
}

/// The whole measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct Tradeoff {
    /// The scene's own render, the centre of every sweep.
    pub base: Setting,
    /// The sweeps of [`Sweep::ALL`], in that order.
    pub sweeps: Vec<Measurement>,
    /// Renders per setting.
    pub runs: usize,
}

/// Renders `setting` `runs` times (at least once) in the current rayon pool: the times and the
/// last render.
fn measure<V: Dim>(scene: &Scene<V>, setting: Setting, runs: usize) -> (Timing, Rendered) {
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
    (Timing::of(times), rendered)
}

/// The settings `run` renders, in order, each with whether it is a sweep's reference: for the
/// progress line's count.
#[must_use]
pub fn plan(depth: u32) -> Vec<(Setting, bool)> {
    Sweep::ALL
        .into_iter()
        .flat_map(|s| {
            std::iter::once((s.reference(depth), true))
                .chain(s.settings(depth).into_iter().map(|x| (x, false)))
        })
        .collect()
}

/// Measures every sweep of the scene, `runs` renders a setting, in the current rayon pool;
/// `progress` hears each setting as it starts (a sweep's reference first, `true`).
pub fn run<V: Dim>(
    scene: &Scene<V>,
    runs: usize,
    mut progress: impl FnMut(Sweep, &Setting, bool),
) -> Tradeoff {
    let depth = scene.max_depth;
    let sweeps = Sweep::ALL
        .into_iter()
        .map(|sweep| {
            let setting = sweep.reference(depth);
            progress(sweep, &setting, true);
            let (time, image) = measure(scene, setting, runs);
            let reference = Measured {
                setting,
                time,
                stats: image.stats,
                pixels: image.pixels,
                error: ImageError::default(),
            };
            let rows = sweep
                .settings(depth)
                .into_iter()
                .map(|setting| {
                    progress(sweep, &setting, false);
                    let (time, rendered) = measure(scene, setting, runs);
                    Measured {
                        setting,
                        time,
                        stats: rendered.stats,
                        pixels: rendered.pixels,
                        error: compare(&rendered.image, &image.image),
                    }
                })
                .collect();
            Measurement { sweep, reference, rows }
        })
        .collect();
    Tradeoff { base: Setting::scene_render(depth), sweeps, runs }
}

/// Whether `a` beats `b`: at most its rays and its RMSE, fewer or less in one.
fn dominates(a: &Measured, b: &Measured) -> bool {
    let (ra, rb) = (a.stats.rays.total(), b.stats.rays.total());
    ra <= rb && a.error.rmse <= b.error.rmse && (ra < rb || a.error.rmse < b.error.rmse)
}

/// The indices of the rows that no other row beats on (rays traced, RMSE), ordered by rays.
#[must_use]
pub fn pareto_front(rows: &[Measured]) -> Vec<usize> {
    let mut front: Vec<usize> =
        (0..rows.len()).filter(|&i| !rows.iter().any(|other| dominates(other, &rows[i]))).collect();
    front.sort_by(|&a, &b| rows[a].stats.rays.total().cmp(&rows[b].stats.rays.total()).then(a.cmp(&b)));
    front
}

#[cfg(test)]
// These tests pin exact results on purpose.
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::record::stats::RayCounts;
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
    fn each_setting_differs_from_its_reference_in_its_sweep_only() {
        for depth in [0, 4, 20] {
            for sweep in Sweep::ALL {
                let reference = sweep.reference(depth);
                for s in sweep.settings(depth) {
                    assert_eq!(s.accel != reference.accel, sweep == Sweep::Accel, "{sweep:?} {s:?}");
                    assert_eq!(s.sampling != reference.sampling, sweep == Sweep::Sampling, "{sweep:?} {s:?}");
                    if sweep == Sweep::Depth {
                        // Only a scene deeper than the reference's 16 meets it, with its own depth.
                        assert!(s.depth != reference.depth || s.depth == depth, "{s:?}");
                    } else {
                        assert_eq!(s.depth, reference.depth, "{sweep:?} {s:?}");
                    }
                }
            }
        }
        // 2 + 9 sampling modes; depths 0 … 8 (a deeper scene adds its own); 4 structures.
        assert_eq!(Sweep::Sampling.settings(4).len(), 11);
        let depths = |d| Sweep::Depth.settings(d).iter().map(|s| s.depth).collect::<Vec<_>>();
        assert_eq!(depths(4), (0..=8).collect::<Vec<_>>());
        assert_eq!(depths(20), (0..=8).chain([20]).collect::<Vec<_>>());
        assert_eq!(Sweep::Depth.reference(20).depth, 20);
        assert_eq!(Sweep::Accel.settings(4).len(), 4);
        assert_eq!(plan(4).len(), 3 + 11 + 9 + 4);
    }

    fn row(depth: u32, primary: u64, reflected: u64, rmse: f64) -> Measured {
        Measured {
            setting: Setting { depth, ..Setting::scene_render(depth) },
            time: Timing::default(),
            stats: Stats {
                rays: RayCounts { primary, reflected, ..RayCounts::default() },
                ..Stats::default()
            },
            pixels: 1,
            error: ImageError { rmse, ..ImageError::default() },
        }
    }

    #[test]
    fn the_pareto_front_keeps_what_nothing_beats_on_rays() {
        // 0 cheap and rough, 1 beaten by 0, 2 dear and exact, 3 between, 4 a tie of 3.
        let rows =
            [row(1, 1, 0, 0.5), row(1, 2, 0, 0.6), row(1, 9, 0, 0.0), row(1, 3, 0, 0.2), row(1, 3, 0, 0.2)];
        assert_eq!(pareto_front(&rows), vec![0, 3, 4, 2]);
        let mut rows = rows.to_vec();
        for (row, threshold) in rows.iter_mut().zip([0.5, 0.4, 0.0, 0.2, 0.1]) {
            row.setting.sampling = Sampling::Adaptive { threshold, max_level: 2 };
        }
        let m = Measurement { sweep: Sweep::Sampling, reference: row(1, 9, 0, 0.0), rows };
        let why = m.reasons();
        assert!(why[0].ends_with("on the front, with the fewest rays"), "{}", why[0]);
        assert!(why[1]
            .ends_with("off the front: adaptive 0.5, K = 2 traces 1.00 rays a pixel for an RMSE of 0.50000"));
        assert!(why[3].ends_with("on the front: 60 % less error than adaptive 0.5, K = 2 for 3.00× its rays"));
        assert!(why[2].ends_with("the reference's image, exactly"), "{}", why[2]);
    }

    #[test]
    fn a_depth_that_adds_no_ray_says_so() {
        // Level 1 adds 2 reflected rays; level 2 none; the reference traces 1 more past them.
        let rows = vec![row(0, 4, 0, 0.3), row(1, 4, 2, 0.1), row(2, 4, 2, 0.1)];
        let m = Measurement { sweep: Sweep::Depth, reference: row(16, 4, 3, 0.0), rows };
        let why = m.reasons();
        assert!(why[0].starts_with("ray casting"), "{}", why[0]);
        assert!(why[1].starts_with("level 1 adds 2.000 reflected"), "{}", why[1]);
        assert!(why[2].starts_with("max_depth 1 → 2 changes nothing: no ray of this scene reaches level 2"));
        assert!(
            why[2].ends_with("1.000 more reflected and transmitted rays a pixel past level 2"),
            "{}",
            why[2]
        );
        let exact = Measurement { reference: row(16, 4, 2, 0.0), ..m };
        assert!(exact.reasons()[2].contains("no ray goes past level 2"));
    }

    #[test]
    fn timing_keeps_the_spread_and_the_median() {
        assert_eq!(Timing::of(vec![2.0, 10.0, 1.0]), Timing { min: 1.0, median: 2.0, max: 10.0 });
        assert_eq!(Timing::of(vec![3.0, 1.0, 2.0, 10.0]).median, 2.5);
        assert_eq!(Timing::of(vec![]), Timing::default());
    }
}
