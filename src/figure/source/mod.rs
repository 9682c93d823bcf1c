//! What a figure reads (product.md "Diagrams": drawn from a recorded trace): the traces of the
//! pixels or rays a figure shows, recorded with `EventLog`. This is the only part of `figure` that
//! runs the tracer; the kinds (`figure::kinds`) only read what it recorded. A kind that needs a
//! pixel and is given none gets a telling one, found by scanning recorded traces of a grid of
//! pixels for the events it draws (a refraction, a blocked shadow ray, a large ray tree).
//!
//! `record` turns an `Aim` (a pixel, a ray, or `Auto`) and `TraceOptions` (depth, structure,
//! sampling) into a `FigureInput`: the `FigureTrace` logs (with a pixel's samples for `adaptive`),
//! a render's `Counts` (for `heat-map`), the built `Accel` whose `layout()` the structure kinds
//! draw, and the `focus` object of the volume kinds. `Auto` says why it chose its pixel in a
//! `Pick`.

use crate::accel::{Accel, AccelKind, AccelOptions, Layout};
use crate::bounds::{kdop, BoundingVolume, VolumeKind};
use crate::complexity::{self, Cost};
use crate::geom::quadratic::half_b_discriminant;
use crate::geom::ray::Ray;
use crate::image::Image;
use crate::memory::budget;
use crate::record::event::{Event, RayKind};
use crate::record::EventLog;
use crate::render::{check_fits, render, RenderConfig};
use crate::sample::{trace_pixel, PixelTrace, Sampling, DEFAULT_MAX_LEVEL, DEFAULT_THRESHOLD};
use crate::scene::camera::Projection;
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use crate::shape::Shape;
use crate::trace::Tracer;

use super::kinds::projections;
use super::plane::Planar;
use super::style::RAY_WIDTH;
use super::{FigureError, FigureKind};

mod logs;
pub use logs::*;

/// What to trace for a figure: the pixel or ray asked for, or none (the figure picks).
#[derive(Clone, Debug, PartialEq)]
pub enum Aim<V> {
    /// Nothing given: the figure picks a telling pixel.
    Auto,
    /// Pixel `(i, j)`: column from the left, row from the bottom (`j = 0` in 2D); inside the image.
    Pixel(usize, usize),
    /// A ray given by hand, traced as a primary ray.
    Ray(Ray<V>),
}

/// How the traced pixel was chosen; the caption says it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pick {
    /// Given on the command line or in the lesson.
    Given,
    /// The figure's default pixel (no scan needed).
    Default,
    /// A pixel off the centre, in the upper right.
    OffCentre,
    /// A 2D pixel right of the centre.
    OffCentreRow,
    /// The pixel whose primary hit refracts at the clearest angle.
    Refraction,
    /// A pixel whose trace has a total internal reflection.
    Tir,
    /// The pixel whose trace has a shadow ray stopped by an occluder.
    BlockedShadow,
    /// The pixel whose trace shows the most kinds of rays.
    Rich,
    /// The pixel whose primary hit is lit with the clearest N, L, H, V.
    Lit,
    /// A pixel whose primary hit the light reaches, nothing in between.
    LitDirectly,
    /// The pixel whose primary hit is lit with the clearest N, L, H, V, although two of them lie
    /// closer than [`MIN_APART_DEG`]: no pixel tried keeps them apart.
    LitCrowded,
    /// The pixel whose adaptive subdivision mixes the most levels.
    Subdivided,
    /// The pixel whose primary ray's walk through the structure is the most telling.
    Walk,
    /// A pixel whose primary ray meets the volume.
    VolumeHit,
    /// A pixel whose primary ray misses the volume, nearest to meeting it.
    VolumeMiss,
}

/// Where a traced primary ray came from.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    /// A pixel centre and its `(u, v)` (`[u]` in 2D).
    Pixel {
        /// Column, from the left.
        i: usize,
        /// Row, from the bottom.
        j: usize,
        /// The window coordinates of its centre.
        uv: Vec<f64>,
    },
    /// A ray given by hand.
    Ray,
}

/// One recorded trace: one or several primary rays (the roots of `log`).
#[derive(Clone, Debug)]
pub struct FigureTrace<V> {
    /// The primary rays' targets, one per root of `log`, in order.
    pub targets: Vec<Target>,
    /// Every event and ray node.
    pub log: EventLog<V>,
    /// The colour of each root.
    pub colors: Vec<Rgb>,
    /// The depth limit the trace ran with.
    pub max_depth: u32,
    /// The projection the primary rays were made with.
    pub projection: Projection,
    /// How the pixel was chosen.
    pub pick: Pick,
    /// A pixel traced with samples (`adaptive`): its samples and squares.
    pub samples: Option<PixelTrace>,
}

/// Everything a figure reads besides the scene.
#[derive(Clone, Debug)]
pub struct FigureInput<V: Dim> {
    /// The scene's name (its file stem), for the caption.
    pub scene_name: String,
    /// The traces: the main one first; `projections` has the orthographic then the perspective
    /// one; `refraction` may add a second trace that shows a total internal reflection.
    pub traces: Vec<FigureTrace<V>>,
    /// The primary rays of every pixel of a whole render (`heat-map`).
    pub counts: Option<Counts>,
    /// The structure the traces were recorded with (its volumes, nodes or cells are drawn).
    pub accel: Accel<V>,
    /// The object a figure is about (`slab-test`, `kay-kajiya`: the bounded object tested;
    /// `discriminant`: the sphere).
    pub focus: Option<usize>,
    /// `discriminant`: the lecture's quadratic of each of its rays, in the order traced.
    pub quadratics: Vec<Quadratic>,
    /// `jagged-edges`: the two renders and the crop it shows.
    pub jagged: Option<Jagged>,
    /// `complexity`: what each structure cost on each crowd of n objects.
    pub costs: Vec<Cost>,
}

/// The quadratic `t² + b·t + c = 0` of a ray and a sphere (`a = D·D = 1`, D unit), as the
/// lecture writes it: `b = 2b'` and `Δ = b² − 4c = 4Δ'` from the tracer's own half-b form
/// (`geom::quadratic::half_b_discriminant`, §11).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quadratic {
    /// `b = 2·D·(O − C)`.
    pub b: f64,
    /// `Δ = b² − 4c`.
    pub delta: f64,
}

/// One whole render of `jagged-edges`.
#[derive(Clone, Debug)]
pub struct Rendering {
    /// How its pixels were sampled.
    pub sampling: Sampling,
    /// Its linear colours.
    pub image: Image,
    /// The primary rays it traced (shared samples once).
    pub primary: u64,
}

/// `jagged-edges`: the scene rendered with one ray per pixel and supersampled, and the crop of
/// pixels both panels show.
#[derive(Clone, Debug)]
pub struct Jagged {
    /// The centre-sampled render, then the supersampled one.
    pub renders: [Rendering; 2],
    /// The crop's lower-left pixel `(i, j)`, rows from the bottom.
    pub corner: (usize, usize),
    /// The crop's size in pixels, across and up.
    pub size: (usize, usize),
}

impl Jagged {
    /// How many pixels of the crop the two renders colour differently (as the PNG would show
    /// them: one byte per channel).
    #[must_use]
    pub fn changed(&self) -> usize {
        let [a, b] = &self.renders;
        let (i0, j0) = self.corner;
        let mut n = 0;
        for j in j0..j0 + self.size.1 {
            for i in i0..i0 + self.size.0 {
                n += usize::from(differs(a.image.get(i, j), b.image.get(i, j)));
            }
        }
        n
    }
}

/// Whether two linear colours differ in the file's bytes.
fn differs(a: Rgb, b: Rgb) -> bool {
    (0..3).any(|k| crate::image::to_byte(a.0[k]) != crate::image::to_byte(b.0[k]))
}

/// The primary rays that entered each pixel of a render.
#[derive(Clone, Debug, PartialEq)]
pub struct Counts {
    /// The sampling mode rendered with.
    pub sampling: Sampling,
    /// Per pixel, `[j·Nx + i]` with j from the bottom: the distinct samples whose colour entered it.
    pub per_pixel: Vec<u32>,
    /// The primary rays traced for the whole image (shared samples once).
    pub traced: u64,
}

/// Options of the tracing a figure reads.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceOptions {
    /// Overrides the scene's `max_depth`.
    pub depth: Option<u32>,
    /// The structure that finds hits; the kinds that draw one (`slab-test`, `kay-kajiya`, `bvh`,
    /// `grid-dda`, `octree`) use theirs, keeping only the grid's cells.
    pub accel: AccelOptions,
    /// How pixels become primary rays, for the kinds that show sampling (`adaptive`, `heat-map`);
    /// the others trace the pixel's centre.
    pub sampling: Sampling,
}

impl TraceOptions {
    /// The scene's own depth, brute force, one ray through each pixel centre.
    pub const SCENE: Self = Self {
        depth: None,
        accel: AccelOptions { kind: AccelKind::None, volume: VolumeKind::Aabb, grid: None },
        sampling: Sampling::Center,
    };
    /// The adaptive subdivision of the lecture's figure: the defaults of `--threshold` (0.1) and
    /// `--max-level` (2).
    pub const ADAPTIVE: Sampling =
        Sampling::Adaptive { threshold: DEFAULT_THRESHOLD, max_level: DEFAULT_MAX_LEVEL };
}

/// Records the traces that figure `kind` reads, for `aim` in `scene` (named `scene_name`).
///
/// # Errors
/// A pixel outside the image, or a given pixel (or a whole scan) whose trace lacks what the
/// kind draws (a refraction for `refraction`, a hit for `local-model` and `shadows`).
pub fn record<V: Planar>(
    kind: FigureKind,
    scene: &Scene<V>,
    scene_name: &str,
    aim: &Aim<V>,
    tracing: &TraceOptions,
) -> Result<FigureInput<V>, FigureError> {
    let cam = &scene.camera;
    if let Aim::Pixel(i, j) = *aim {
        if i >= cam.nx || j >= cam.ny {
            return Err(FigureError(format!(
                "pixel ({i}, {j}) is outside the image: i must be < {}, j < {}",
                cam.nx, cam.ny
            )));
        }
    }
    let structure =
        |kind: AccelKind, volume: VolumeKind| AccelOptions { kind, volume, grid: tracing.accel.grid.clone() };
    let options = match kind {
        FigureKind::SlabTest => structure(AccelKind::Bounds, VolumeKind::Aabb),
        FigureKind::KayKajiya => structure(AccelKind::Bounds, VolumeKind::Kdop),
        FigureKind::Bvh => structure(AccelKind::Bvh, VolumeKind::Aabb),
        FigureKind::GridDda => structure(AccelKind::Grid, VolumeKind::Aabb),
        FigureKind::Octree => structure(AccelKind::Octree, VolumeKind::Aabb),
        // Every ray tests the sphere, even the one that misses its box.
        FigureKind::Discriminant => structure(AccelKind::None, VolumeKind::Aabb),
        _ => tracing.accel.clone(),
    };
    check_memory(kind, scene)?;
    let accel = Accel::build_with(scene, &options);
    let depth = tracing.depth.unwrap_or(scene.max_depth);
    let tracer = FigureTracer { scene, accel: &accel, depth };
    let (mut counts, mut focus) = (None, None);
    let (mut quadratics, mut jagged, mut costs) = (Vec::new(), None, Vec::new());
    let traces = match kind {
        FigureKind::Projections => projections(&tracer, aim),
        FigureKind::BackwardRays => {
            // The score reads only the primary ray and its shadow rays, which no depth changes:
            // the scan traces the primary rays alone (max_depth 0), the pixel picked at `depth`.
            let primary_only = FigureTracer { depth: 0, ..tracer };
            let main = tracer.aimed_by(aim, Pick::LitDirectly, || primary_only.scan(lit_directly_score));
            if lit_directly_score(&main.log).is_none() {
                return Err(FigureError(missing(aim, "hit that a light reaches with nothing in between")));
            }
            vec![main]
        }
        FigureKind::CameraFrame => match aim {
            // Off the centre, so that S and the window's centre are two points.
            Aim::Auto => {
                let (i, j) = ((3 * cam.nx) / 4, (2 * cam.ny) / 3);
                let pick = if V::DIM == 2 { Pick::OffCentreRow } else { Pick::OffCentre };
                vec![tracer.pixel(i, j, pick)]
            }
            _ => vec![tracer.aimed(aim, Pick::Default, |_| None)],
        },
        FigureKind::Discriminant => {
            let (traces, sphere, found) = discriminant_rays(&tracer, aim)?;
            focus = Some(sphere);
            quadratics = found;
            traces
        }
        FigureKind::JaggedEdges => {
            let sampling = match tracing.sampling {
                Sampling::Center => TraceOptions::ADAPTIVE,
                other => other,
            };
            jagged = Some(jagged_renders(scene, &accel, depth, sampling, aim)?);
            Vec::new()
        }
        FigureKind::Complexity => {
            costs = complexity::measure(scene, &complexity::SIZES, complexity::FIGURE_WIDTH);
            Vec::new()
        }
        FigureKind::UvMap => match aim {
            Aim::Auto => {
                // Off the centre and in the upper half, so that the rows visibly count from the bottom.
                let (i, j) = ((3 * cam.nx) / 4, (2 * cam.ny) / 3);
                let pick = if V::DIM == 2 { Pick::OffCentreRow } else { Pick::OffCentre };
                vec![tracer.pixel(i, j, pick)]
            }
            _ => vec![tracer.aimed(aim, Pick::Default, |_| None)],
        },
        FigureKind::Refraction => {
            let main = tracer.aimed(aim, Pick::Refraction, refraction_score);
            if !has(&main.log, |e| matches!(e, Event::Refract { .. } | Event::TotalInternalReflection { .. }))
            {
                return Err(FigureError(missing(aim, "refraction or total internal reflection")));
            }
            let mut traces = vec![main];
            if !has(&traces[0].log, |e| matches!(e, Event::TotalInternalReflection { .. })) {
                if let Some((i, j)) = tracer.scan(tir_score) {
                    traces.push(tracer.pixel(i, j, Pick::Tir));
                }
            }
            traces
        }
        FigureKind::LocalModel => {
            let mut main = tracer.aimed(aim, Pick::Lit, |log| lit_score(scene, log));
            if first_hit(&main.log).is_none() {
                return Err(FigureError(missing(aim, "hit")));
            }
            // The best pixel may still draw two vectors one over the other: the caption says so.
            let crowded =
                main.log.nodes.first().and_then(vectors_apart_deg).is_none_or(|a| a < MIN_APART_DEG);
            if main.pick == Pick::Lit && crowded {
                main.pick = Pick::LitCrowded;
            }
            vec![main]
        }
        FigureKind::Shadows => {
            let main = tracer.aimed(aim, Pick::BlockedShadow, shadow_score);
            if !has(&main.log, |e| matches!(e, Event::ShadowRay { .. })) {
                return Err(FigureError(missing(aim, "shadow ray")));
            }
            vec![main]
        }
        FigureKind::Rays | FigureKind::RayTree => vec![tracer.aimed(aim, Pick::Rich, rich_score)],
        FigureKind::Adaptive => {
            // The centre alone has nothing to subdivide: the figure's own adaptive rule then.
            let sampling = match tracing.sampling {
                Sampling::Center => TraceOptions::ADAPTIVE,
                other => other,
            };
            vec![tracer.sampled(aim, sampling)?]
        }
        FigureKind::HeatMap => {
            let config = RenderConfig {
                sampling: tracing.sampling,
                rays_per_pixel: true,
                ..RenderConfig::centers(depth)
            };
            check_fits(scene, &config, rayon::current_num_threads()).map_err(FigureError)?;
            let rendered = render(scene, &accel, &config);
            let per_pixel = rendered.rays_per_pixel.unwrap_or_default();
            counts =
                Some(Counts { sampling: tracing.sampling, per_pixel, traced: rendered.stats.rays.primary });
            Vec::new()
        }
        FigureKind::SlabTest | FigureKind::KayKajiya => {
            let (traces, object) = bound_pair(&tracer, aim)?;
            focus = Some(object);
            traces
        }
        FigureKind::Bvh | FigureKind::Octree => vec![tracer.aimed(aim, Pick::Walk, tree_score)],
        FigureKind::GridDda => vec![tracer.aimed(aim, Pick::Walk, grid_score)],
    };
    if let Some(full) = traces.iter().find(|t| t.log.overflowed()) {
        let why = full.log.overflow_cause(depth, scene.worst_tree_rays(depth));
        return Err(FigureError(why));
    }
    Ok(FigureInput {
        scene_name: scene_name.to_owned(),
        traces,
        counts,
        accel,
        focus,
        quadratics,
        jagged,
        costs,
    })
}

/// About how many bytes a figure takes per part of the scene (an object, a mesh's triangle): its
/// outline and label in the display list, its share of the structure and of the drawn hierarchy,
/// the SVG or PNG made of them. Measured: `figure bvh` of 10^5 small spheres peaked at 276 MB.
pub const FIGURE_BYTES_PER_PART: u64 = 3 << 10;

/// Refuses, before the structure is built, a figure whose drawing would need more than the memory
/// budget: `parts · FIGURE_BYTES_PER_PART`, the parts counted from the scene.
fn check_memory<V: Dim>(kind: FigureKind, scene: &Scene<V>) -> Result<(), FigureError> {
    let parts: u64 = scene.objects.iter().map(|o| o.shape.parts() as u64).sum();
    let what = format!("a {} figure of {parts} objects and triangles", kind.name());
    budget()
        .check(parts.saturating_mul(FIGURE_BYTES_PER_PART), &what, "draw a scene with fewer objects")
        .map_err(FigureError)
}

/// The message for a trace that lacks what a figure draws.
fn missing<V>(aim: &Aim<V>, what: &str) -> String {
    match aim {
        Aim::Pixel(i, j) => {
            format!("the trace of pixel ({i}, {j}) has no {what}; omit --pixel to let the figure pick one")
        }
        Aim::Ray(_) => format!("the trace of the given ray has no {what}"),
        Aim::Auto => format!("no pixel of the scene has {what} in its trace"),
    }
}

/// True iff some event of `log` satisfies `test`.
fn has<V>(log: &EventLog<V>, test: impl Fn(&Event<V>) -> bool) -> bool {
    log.events.iter().any(|l| test(&l.event))
}

/// The tracer, set up once for all the pixels a figure traces.
#[derive(Clone, Copy)]
struct FigureTracer<'a, V: Dim> {
    scene: &'a Scene<V>,
    accel: &'a Accel<V>,
    depth: u32,
}

impl<V: Dim> FigureTracer<'_, V> {
    /// Traces the primary rays of `targets` into one log.
    fn trace(&self, scene: &Scene<V>, rays: &[(Ray<V>, Target)], depth: u32, pick: Pick) -> FigureTrace<V> {
        let mut tracer = Tracer::new(scene, self.accel, EventLog::new());
        tracer.max_depth = depth;
        let mut colors = Vec::new();
        for (ray, target) in rays {
            let uv = match target {
                Target::Pixel { uv, .. } => uv.clone(),
                Target::Ray => Vec::new(),
            };
            colors.push(tracer.trace_primary(ray, &uv));
        }
        FigureTrace {
            targets: rays.iter().map(|(_, t)| t.clone()).collect(),
            log: tracer.recorder,
            colors,
            max_depth: depth,
            projection: scene.camera.projection,
            pick,
            samples: None,
        }
    }

    /// Pixel `(i, j)` traced with its samples (`sampling` samples corners).
    fn pixel_samples(&self, i: usize, j: usize, sampling: Sampling, pick: Pick) -> FigureTrace<V> {
        let mut tracer = Tracer::new(self.scene, self.accel, EventLog::new());
        tracer.max_depth = self.depth;
        let traced = trace_pixel(&mut tracer, sampling, i, j);
        let (u, v) = self.scene.camera.pixel_center(i, j);
        let uv = if V::DIM == 2 { vec![u] } else { vec![u, v] };
        FigureTrace {
            targets: vec![Target::Pixel { i, j, uv }],
            colors: vec![traced.color],
            log: tracer.recorder,
            max_depth: self.depth,
            projection: self.scene.camera.projection,
            pick,
            samples: Some(traced),
        }
    }

    /// `adaptive`: the given pixel, or the one whose subdivision splits the most squares.
    fn sampled(&self, aim: &Aim<V>, sampling: Sampling) -> Result<FigureTrace<V>, FigureError> {
        match aim {
            Aim::Pixel(i, j) => Ok(self.pixel_samples(*i, *j, sampling, Pick::Given)),
            Aim::Ray(_) => Err(FigureError("adaptive subdivides a pixel: give --pixel, not --ray".into())),
            Aim::Auto => {
                // A subdivision that mixes levels (some squares split, some not) shows the rule
                // best: the most distinct leaf levels, then the most splits.
                let best = self.best_pixel(|i, j| {
                    let t = self.pixel_samples(i, j, sampling, Pick::Given);
                    let squares = t.samples.as_ref().map_or(&[][..], |s| &s.squares[..]);
                    let splits = squares.iter().filter(|q| q.split).count();
                    let mut levels: Vec<u32> = squares.iter().filter(|q| !q.split).map(|q| q.level).collect();
                    levels.sort_unstable();
                    levels.dedup();
                    (splits > 0).then_some(100.0 * levels.len() as f64 + splits as f64)
                });
                Ok(match best {
                    Some((i, j)) => self.pixel_samples(i, j, sampling, Pick::Subdivided),
                    None => {
                        let (i, j) = default_pixel(self.scene);
                        self.pixel_samples(i, j, sampling, Pick::Default)
                    }
                })
            }
        }
    }

    /// The primary ray of pixel `(i, j)` of `scene`'s camera and its target.
    fn pixel_ray(scene: &Scene<V>, i: usize, j: usize) -> (Ray<V>, Target) {
        let cam = &scene.camera;
        let (u, v) = cam.pixel_center(i, j);
        let uv = if V::DIM == 2 { vec![u] } else { vec![u, v] };
        (cam.primary_ray(u, v), Target::Pixel { i, j, uv })
    }

    /// The trace of one pixel.
    fn pixel(&self, i: usize, j: usize, pick: Pick) -> FigureTrace<V> {
        self.trace(self.scene, &[Self::pixel_ray(self.scene, i, j)], self.depth, pick)
    }

    /// The trace of `aim`; with [`Aim::Auto`], of the pixel with the best `score` (picked as
    /// `why`), or the default pixel when no pixel scores.
    fn aimed(&self, aim: &Aim<V>, why: Pick, score: impl Fn(&EventLog<V>) -> Option<f64>) -> FigureTrace<V> {
        self.aimed_by(aim, why, || self.scan(score))
    }

    /// The trace of `aim`; with [`Aim::Auto`], of the pixel `pick` finds (picked as `why`), or the
    /// default pixel when it finds none.
    fn aimed_by(
        &self,
        aim: &Aim<V>,
        why: Pick,
        pick: impl FnOnce() -> Option<(usize, usize)>,
    ) -> FigureTrace<V> {
        match aim {
            Aim::Pixel(i, j) => self.pixel(*i, *j, Pick::Given),
            Aim::Ray(ray) => self.trace(self.scene, &[(*ray, Target::Ray)], self.depth, Pick::Given),
            Aim::Auto => match pick() {
                Some((i, j)) => self.pixel(i, j, why),
                None => {
                    let (i, j) = default_pixel(self.scene);
                    self.pixel(i, j, Pick::Default)
                }
            },
        }
    }

    /// The pixel of a coarse grid (at most 48 × 36 candidates) whose trace scores highest; ties
    /// go to the pixel nearest the image's centre.
    fn scan(&self, score: impl Fn(&EventLog<V>) -> Option<f64>) -> Option<(usize, usize)> {
        self.best_pixel(|i, j| score(&self.pixel(i, j, Pick::Given).log))
    }

    /// The pixel of a coarse grid (at most 48 × 36 candidates) with the highest `score`; ties go
    /// to the pixel nearest the image's centre.
    fn best_pixel(&self, score: impl Fn(usize, usize) -> Option<f64>) -> Option<(usize, usize)> {
        let cam = &self.scene.camera;
        let (sx, sy) = ((cam.nx / 48).max(1), (cam.ny / 36).max(1));
        let centre = (cam.nx as f64 / 2.0, cam.ny as f64 / 2.0);
        let mut best: Option<(f64, f64, (usize, usize))> = None;
        for j in (sy / 2..cam.ny).step_by(sy) {
            for i in (sx / 2..cam.nx).step_by(sx) {
                let Some(s) = score(i, j) else { continue };
                let d = (i as f64 + 0.5 - centre.0).hypot(j as f64 + 0.5 - centre.1);
                if best.is_none_or(|(bs, bd, _)| s > bs || ((s - bs).abs() < 1e-12 && d < bd)) {
                    best = Some((s, d, (i, j)));
                }
            }
        }
        best.map(|(_, _, p)| p)
    }
}

/// The default pixel: the centre one, `(⌊Nx/2⌋, ⌊Ny/2⌋)`.
#[must_use]
pub fn default_pixel<V: Dim>(scene: &Scene<V>) -> (usize, usize) {
    (scene.camera.nx / 2, scene.camera.ny / 2)
}

/// At most this many primary rays per projection in `projections`.
const PROJECTION_RAYS: usize = 9;

/// `projections`: the same pixels traced (primary rays only) with an orthographic and a
/// perspective camera of the same window: spread columns of the given pixel's row (the middle
/// row by default). Where the image has more columns than the figure draws, each is the column
/// nearest its evenly spread place whose two rays keep clear of what they pass ([`clear_columns`]).
fn projections<V: Planar>(rec: &FigureTracer<'_, V>, aim: &Aim<V>) -> Vec<FigureTrace<V>> {
    let cam = &rec.scene.camera;
    let row = match aim {
        Aim::Pixel(_, j) => *j,
        _ => cam.ny / 2,
    };
    let n = cam.nx.min(PROJECTION_RAYS);
    let even: Vec<usize> = (0..n)
        .map(|k| {
            // Evenly spread over [0, Nx − 1], ends included.
            if n == 1 {
                cam.nx / 2
            } else {
                (k * (cam.nx - 1) + (n - 1) / 2) / (n - 1)
            }
        })
        .collect();
    let pick = if matches!(aim, Aim::Pixel(..)) { Pick::Given } else { Pick::Default };
    let scenes = [Projection::Orthographic, Projection::Perspective].map(|projection| {
        let mut scene = rec.scene.clone();
        scene.camera.projection = projection;
        scene
    });
    let traced = |columns: &[usize]| -> Vec<FigureTrace<V>> {
        scenes
            .iter()
            .map(|scene| {
                let rays: Vec<(Ray<V>, Target)> =
                    columns.iter().map(|&i| FigureTracer::pixel_ray(scene, i, row)).collect();
                rec.trace(scene, &rays, 0, pick)
            })
            .collect()
    };
    let first = traced(&even);
    if n == cam.nx {
        // Every column is drawn: nothing to choose.
        return first;
    }
    let columns = clear_columns(rec, &scenes, row, &even, &first);
    if columns == even {
        first
    } else {
        traced(&columns)
    }
}

/// The least clearance, in reference pixels at slide size, between a drawn primary ray of
/// `projections` and an object's outline it passes: 3 ray widths (issue 32: a ray that grazes
/// what it misses reads as a hit), with a third more for the estimate of the scale.
const CLEAR_PX: f64 = 3.0 * RAY_WIDTH * 1.3;
/// At most this many columns of a row are tried by [`clear_columns`] (evenly spread, with the
/// evenly spread ones the figure would draw).
const CLEAR_CANDIDATES: usize = 64;

/// The columns `projections` draws: for each evenly spread column of `even` (traced in `first`),
/// in order, the nearest column not yet taken, within half their spacing, whose orthographic and
/// perspective rays both pass every object they do not hit by at least [`CLEAR_PX`] at the
/// figure's estimated slide scale (`kinds::projections::slide_scale`), so that no ray seems to
/// touch what it misses; none for a column whose reach holds no clear one (the figure draws
/// fewer rays), and `even` itself when no column is clear.
fn clear_columns<V: Planar>(
    rec: &FigureTracer<'_, V>,
    scenes: &[Scene<V>; 2],
    row: usize,
    even: &[usize],
    first: &[FigureTrace<V>],
) -> Vec<usize> {
    let [ortho, persp] = first else { return even.to_vec() };
    let cam = &rec.scene.camera;
    let v_row = cam.pixel_center(0, row).1;
    let extent = projections::extent(rec.scene, ortho, persp, v_row);
    let need = CLEAR_PX / projections::slide_scale(&extent);
    let planes = scenes.each_ref().map(|s| projections::row_plane(s, s.camera.projection, v_row));
    let clearance = |i: usize| {
        scenes
            .iter()
            .zip(&planes)
            .map(|(scene, plane)| {
                let one = rec.trace(scene, &[FigureTracer::pixel_ray(scene, i, row)], 0, Pick::Default);
                projections::ray_clearance(rec.scene, plane, &one, 0, extent.y_far)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let tried = CLEAR_CANDIDATES.min(cam.nx);
    let mut candidates: Vec<usize> = (0..tried)
        .map(|k| (k * (cam.nx - 1) + (tried - 1) / 2) / (tried - 1).max(1))
        .chain(even.iter().copied())
        .collect();
    candidates.sort_unstable();
    candidates.dedup();
    let mut clear: Vec<usize> = candidates.into_iter().filter(|i| clearance(*i) >= need).collect();
    if clear.is_empty() {
        return even.to_vec();
    }
    // A column's reach: half the spacing of the evenly spread ones (at least one column).
    let reach = ((cam.nx - 1) / (2 * (even.len() - 1).max(1))).max(1);
    let mut columns = Vec::new();
    for &c in even {
        let nearest = (0..clear.len()).min_by_key(|k| clear[*k].abs_diff(c));
        if let Some(k) = nearest.filter(|k| clear[*k].abs_diff(c) <= reach) {
            columns.push(clear.remove(k));
        }
    }
    if columns.is_empty() {
        return even.to_vec();
    }
    columns.sort_unstable();
    columns
}

/// `refraction`: the score of [`refraction_node`].
fn refraction_score<V: Dim>(log: &EventLog<V>) -> Option<f64> {
    refraction_node(log).map(|(_, s)| s)
}

/// A total internal reflection anywhere in the trace.
fn tir_score<V: Dim>(log: &EventLog<V>) -> Option<f64> {
    has(log, |e| matches!(e, Event::TotalInternalReflection { .. })).then_some(1.0)
}

/// `shadows`: the score of a blocked shadow ray of [`shadow_node`] (none when nothing blocks).
fn shadow_score<V: Dim>(log: &EventLog<V>) -> Option<f64> {
    shadow_node(log).filter(|(_, s)| *s > 0.0).map(|(_, s)| s)
}

/// `rays` and `ray-tree`: the most kinds of rays, then the fewest nodes that show them (a smaller
/// tree makes a clearer figure).
fn rich_score<V: Dim>(log: &EventLog<V>) -> Option<f64> {
    let kinds = [RayKind::Primary, RayKind::Reflected, RayKind::Transmitted]
        .iter()
        .filter(|k| log.nodes.iter().any(|n| n.start.kind == **k))
        .count();
    let blocked = has(log, |e| matches!(e, Event::ShadowRay { occluders, .. } if !occluders.is_empty()));
    let shadows = has(log, |e| matches!(e, Event::ShadowRay { .. }));
    let roles = kinds + usize::from(blocked) + usize::from(shadows);
    first_hit(log)?;
    Some(100.0 * roles as f64 - log.nodes.len().min(60) as f64)
}

/// The least angle between two of N, V, L, H that `local-model`'s pick accepts, in degrees: closer
/// vectors would be drawn one over the other at slide size.
pub const MIN_APART_DEG: f64 = 10.0;

/// The score `local-model`'s pick adds when N, V, L, H are [`MIN_APART_DEG`] apart: more than the
/// other terms together (at most 2 + 2 + 3 + 2), so a pixel that keeps them apart always wins.
const APART_WEIGHT: f64 = 10.0;

/// `local-model`: the primary hit lit by a light, on an opaque object with a highlight (ks > 0)
/// if there is one and a visible specular term, with N·L near 0.6 and N·V near 0.8, so that N,
/// L, H and V fan out.
fn lit_score<V: Dim>(scene: &Scene<V>, log: &EventLog<V>) -> Option<f64> {
    let node = log.nodes.first()?;
    let hit = node.end.as_ref()?.hit?;
    // Vectors drawn one over the other outweigh every other merit.
    let apart = if vectors_apart_deg(node)? >= MIN_APART_DEG { APART_WEIGHT } else { 0.0 };
    let material = scene.material_of(hit.object.index);
    let kind = if material.transmits() { 0.0 } else { 1.0 } + if material.ks > 0.0 { 1.0 } else { 0.0 };
    let n_dot_v = node.start.direction.dot(hit.normal).abs();
    node.lights
        .iter()
        .filter(|t| t.lum > 0.0 && t.shadow.is_some_and(|s| s > 0.0))
        .map(|t| {
            // A visible highlight: the specular term (N·H)^n·ks·… of at least 0.2 counts fully.
            let highlight = (t.specular.0.iter().copied().fold(0.0, f64::max) * 5.0).min(1.0);
            apart + 2.0 * kind + 3.0 * highlight + 2.0 - (t.n_dot_l - 0.6).abs() - (n_dot_v - 0.8).abs()
        })
        .reduce(f64::max)
}

/// `slab-test` and `kay-kajiya`: a pixel whose primary ray meets an object's volume and one whose
/// primary ray misses the same volume by a visible margin (its [`clearance`] nearest a quarter of
/// the volume's size, and at least an eighth), and that object. A given pixel is the first
/// of the two (its hit object, or the first volume it meets, is the one drawn).
fn bound_pair<V: Dim>(
    rec: &FigureTracer<'_, V>,
    aim: &Aim<V>,
) -> Result<(Vec<FigureTrace<V>>, usize), FigureError> {
    let first = match aim {
        Aim::Auto => {
            // The pixel nearest the centre whose primary ray hits an object inside its volume.
            let best = rec.best_pixel(|i, j| {
                let t = rec.pixel(i, j, Pick::Given);
                let object = first_hit(&t.log)
                    .and_then(|k| t.log.nodes[k].end.as_ref()?.hit)
                    .map(|h| h.object.index)?;
                bound_test_of(&t.log, object).filter(|b| b.hit).map(|_| 1.0)
            });
            let (i, j) = best.unwrap_or_else(|| default_pixel(rec.scene));
            rec.pixel(i, j, if best.is_some() { Pick::VolumeHit } else { Pick::Default })
        }
        Aim::Pixel(i, j) => rec.pixel(*i, *j, Pick::Given),
        Aim::Ray(ray) => rec.trace(rec.scene, &[(*ray, Target::Ray)], rec.depth, Pick::Given),
    };
    let hit_object =
        first_hit(&first.log).and_then(|k| first.log.nodes[k].end.as_ref()?.hit).map(|h| h.object.index);
    let focus = hit_object.filter(|o| bound_test_of(&first.log, *o).is_some()).or_else(|| {
        search_events(&first.log, 0).find_map(|e| match e {
            Event::BoundTest { object: Some(o), hit: true, .. } => Some(o.index),
            _ => None,
        })
    });
    let Some(focus) = focus else {
        return Err(FigureError(missing(aim, "bounding volume it meets (give a pixel whose ray meets one)")));
    };
    // The partner: a miss of the same volume (the lecture's blue ray) that passes it by a
    // visible margin, as near as possible to a quarter of the volume's size.
    let volume = match rec.accel.layout() {
        Layout::Volumes(entries) => entries.iter().find(|(p, _)| p.object() == focus).map(|(_, v)| *v),
        _ => None,
    };
    // In 3D the figure draws the plane of the two axes the first ray moves most along, through
    // the volume's centre (`kinds::slabs`): the miss must show there, so the clearance is that of
    // the ray moved into that plane (its component along the dropped axis set to the centre's).
    let dropped = first
        .log
        .nodes
        .first()
        .map(|n| n.start.direction)
        .filter(|_| V::DIM == 3)
        .map(|d| (0..V::DIM).fold(0, |m, a| if d[a].abs() < d[m].abs() { a } else { m }));
    let near_miss = rec.best_pixel(|i, j| {
        let t = rec.pixel(i, j, Pick::Given);
        let BoundTestOf { t_in, t_out, hit, .. } = bound_test_of(&t.log, focus)?;
        let finite = t_in.is_finite() && t_out.is_finite() && t_out > 0.0;
        let ray = &t.log.nodes.first()?.start;
        let (mut origin, mut direction) = (ray.origin, ray.direction);
        if let (Some(a), Some(v)) = (dropped, volume) {
            origin[a] = volume_centre(&v)[a];
            direction[a] = 0.0;
            direction = direction.try_unit()?;
        }
        let (gap, size) = clearance(&volume?, origin, direction)?;
        let share = gap / size;
        (!hit && finite && share >= MISS_CLEARANCE_MIN).then_some(-(share - MISS_CLEARANCE).abs())
    });
    let mut traces = vec![first];
    if let Some((i, j)) = near_miss {
        traces.push(rec.pixel(i, j, Pick::VolumeMiss));
    }
    Ok((traces, focus))
}

/// The clearance `bound_pair` aims its missing ray at, as a share of the volume's size: far
/// enough to be seen as a miss at slide size, near enough to be a near miss.
const MISS_CLEARANCE: f64 = 0.25;
/// The least clearance a missing ray of `bound_pair` may have (a ray within a hair of the
/// volume looks like a hit).
const MISS_CLEARANCE_MIN: f64 = 0.12;

/// A volume's centre: its sphere's, its box's, or a k-DOP's along its first slabs (the axes).
fn volume_centre<V: Dim>(volume: &BoundingVolume<V>) -> V {
    match volume {
        BoundingVolume::Sphere { center, .. } => *center,
        BoundingVolume::Aabb(b) => b.centroid(),
        BoundingVolume::Kdop(k) => {
            let mut c = V::ZERO;
            for a in 0..V::DIM {
                c[a] = (k.lo[a] + k.hi[a]) / 2.0;
            }
            c
        }
    }
}

/// How far the ray `origin + t·direction`, `t ≥ 0`, passes outside `volume`, and the volume's
/// size (its widest slab): `min_t max_k max(lo_k − n_k·r(t), n_k·r(t) − hi_k) / |n_k|` (the
/// largest overshoot of a slab, a lower bound of the distance), or for a sphere the distance
/// from its centre to the ray less its radius. The overshoot is convex in t (a maximum of
/// linear functions), so a ternary search finds its least value. None for an empty volume.
#[must_use]
pub fn clearance<V: Dim>(volume: &BoundingVolume<V>, origin: V, direction: V) -> Option<(f64, f64)> {
    /// Halvings of the ternary search: (2/3)^200 of the range is far below any drawn length.
    const STEPS: usize = 200;
    let slabs: Vec<(V, f64, f64)> = match volume {
        BoundingVolume::Sphere { center, radius } => {
            let t = (*center - origin).dot(direction).max(0.0);
            let gap = (origin + direction * t - *center).length() - radius;
            return Some((gap, 2.0 * radius));
        }
        BoundingVolume::Aabb(b) => (0..V::DIM).map(|a| (V::axis(a), b.min[a], b.max[a])).collect(),
        BoundingVolume::Kdop(k) => {
            (0..kdop::slab_count::<V>()).map(|s| (kdop::normal::<V>(s), k.lo[s], k.hi[s])).collect()
        }
    };
    if slabs.iter().any(|(_, lo, hi)| !(lo <= hi)) {
        return None;
    }
    let size = slabs.iter().map(|(n, lo, hi)| (hi - lo) / n.length()).fold(0.0, f64::max);
    let over = |t: f64| {
        let p = origin + direction * t;
        slabs
            .iter()
            .map(|(n, lo, hi)| (lo - n.dot(p)).max(n.dot(p) - hi) / n.length())
            .fold(f64::MIN, f64::max)
    };
    // Beyond the farthest corner's distance, every overshoot only grows.
    let reach = slabs
        .iter()
        .map(|(n, lo, hi)| (n.dot(origin).abs() + lo.abs().max(hi.abs())) / n.length())
        .sum::<f64>();
    let (mut a, mut b) = (0.0, 2.0 * reach + 1.0);
    for _ in 0..STEPS {
        let (m1, m2) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
        if over(m1) <= over(m2) {
            b = m2;
        } else {
            a = m1;
        }
    }
    Some((over(0.5 * (a + b)), size))
}

/// What a walk ending at a hit adds to a hierarchy walk's score: half a node, so it only breaks
/// ties between walks that test as much, in favour of one that finds its object in a leaf.
const WALK_HIT_BONUS: f64 = 0.5;

/// `bvh` and `octree`: a primary ray that enters several nodes and passes others by,
/// `10·min(entered, 6) + min(missed, 6)`, and [`WALK_HIT_BONUS`] when it hits.
fn tree_score<V>(log: &EventLog<V>) -> Option<f64> {
    let (mut entered, mut missed) = (0usize, 0usize);
    for e in search_events(log, 0) {
        if let Event::NodeVisit { t_in, t_out, .. } = e {
            if met(*t_in, *t_out) {
                entered += 1;
            } else {
                missed += 1;
            }
        }
    }
    let hit = if first_hit(log) == Some(0) { WALK_HIT_BONUS } else { 0.0 };
    (entered > 1).then(|| 10.0 * entered.min(6) as f64 + missed.min(6) as f64 + hit)
}

/// `grid-dda`: a walk of several cells, best one that shows the pitfall (a hit found in a cell
/// that lies beyond it).
fn grid_score<V>(log: &EventLog<V>) -> Option<f64> {
    let steps = search_events(log, 0).filter(|e| matches!(e, Event::VoxelStep { .. })).count();
    let pitfall = grid_pitfall(log).is_some();
    (steps > 1).then(|| if pitfall { 100.0 } else { 0.0 } + steps.min(12) as f64)
}

/// `backward`: a primary hit that a light reaches with nothing in between (`s = 1`, `lum = 1`),
/// the light path S → I → O of the lecture; the larger N·L the better.
fn lit_directly_score<V: Dim>(log: &EventLog<V>) -> Option<f64> {
    let node = log.nodes.first()?;
    node.end.as_ref()?.hit?;
    log.events
        .iter()
        .filter_map(|l| match &l.event {
            Event::ShadowRay { light, occluders, .. } if l.ray == Some(0) && occluders.is_empty() => {
                node.lights.iter().find(|t| t.light == *light).map(|t| t.n_dot_l)
            }
            _ => None,
        })
        .reduce(f64::max)
}

/// The distances from the sphere's centre of the three rays of `discriminant`, in radii: one
/// that misses (Δ < 0), the tangent (Δ = 0) and one through the sphere (Δ > 0).
pub const DISCRIMINANT_OFFSETS: [f64; 3] = [1.5, 1.0, 0.5];

/// What `discriminant` traced: its trace, the sphere's index and each ray's quadratic.
type DiscriminantRays<V> = (Vec<FigureTrace<V>>, usize, Vec<Quadratic>);

/// How far before the sphere's centre, in radii, the rays of `discriminant` start.
pub const DISCRIMINANT_START: f64 = 3.0;

/// `discriminant`: a sphere of the scene (the one the given pixel's or ray's primary ray hits,
/// else the first sphere listed) and three rays along the camera's viewing direction −w, in the
/// plane of −w and u through its centre C, at distances [`DISCRIMINANT_OFFSETS`] from C along u
/// (origin `C − 3r·D + k·r·u`): traced as primary rays (ray casting), each with its quadratic.
/// With −w and u along the axes and simple numbers, the tangent's Δ is exactly 0.
fn discriminant_rays<V: Dim>(
    rec: &FigureTracer<'_, V>,
    aim: &Aim<V>,
) -> Result<DiscriminantRays<V>, FigureError> {
    let sphere_of = |k: usize| match &rec.scene.objects[k].shape {
        Shape::Sphere(s) => Some((s.center, s.radius)),
        _ => None,
    };
    let aimed = match aim {
        Aim::Auto => None,
        _ => {
            let t = rec.aimed(aim, Pick::Given, |_| None);
            first_hit(&t.log).and_then(|k| t.log.nodes[k].end.as_ref()?.hit).map(|h| h.object.index)
        }
    };
    let Some(object) = aimed
        .filter(|k| sphere_of(*k).is_some())
        .or_else(|| (0..rec.scene.objects.len()).find(|k| sphere_of(*k).is_some()))
    else {
        return Err(FigureError(format!("no sphere in the scene: {}", missing(aim, "sphere"))));
    };
    let (center, radius) = sphere_of(object).ok_or_else(|| FigureError("not a sphere".into()))?;
    let frame = &rec.scene.camera.frame;
    let (dir, across) = (-frame.w, frame.u);
    let rays: Vec<(Ray<V>, Target)> = DISCRIMINANT_OFFSETS
        .iter()
        .map(|k| {
            let origin = center - dir * (DISCRIMINANT_START * radius) + across * (k * radius);
            (Ray::new(origin, dir), Target::Ray)
        })
        .collect();
    let quadratics = rays
        .iter()
        .map(|(ray, _)| {
            let (half_b, quarter) = half_b_discriminant(ray, center, radius);
            Quadratic { b: 2.0 * half_b, delta: 4.0 * quarter }
        })
        .collect();
    // The rays are the figure's own, not a pixel it picked: nothing to say on stderr.
    Ok((vec![rec.trace(rec.scene, &rays, 0, Pick::Given)], object, quadratics))
}

/// The pixels across and up of the crop `jagged-edges` shows (16:9 on a slide's two panels).
pub const JAGGED_CROP: (usize, usize) = (16, 12);

/// `jagged-edges`: the whole image rendered with one ray per pixel and with `sampling`, and a
/// crop of [`JAGGED_CROP`] pixels (fewer in a smaller image; one row in 2D): centred on the
/// given pixel, else the one where the two renders differ in the most pixels (ties to the crop
/// nearest the centre).
fn jagged_renders<V: Dim>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    depth: u32,
    sampling: Sampling,
    aim: &Aim<V>,
) -> Result<Jagged, FigureError> {
    if matches!(aim, Aim::Ray(_)) {
        return Err(FigureError("jagged-edges shows pixels: give --pixel, not --ray".into()));
    }
    let one = |sampling: Sampling| -> Result<Rendering, FigureError> {
        let config = RenderConfig { sampling, strip_rows: Some(1), ..RenderConfig::centers(depth) };
        check_fits(scene, &config, rayon::current_num_threads()).map_err(FigureError)?;
        let r = render(scene, accel, &config);
        Ok(Rendering { sampling, image: r.image, primary: r.stats.rays.primary })
    };
    let renders = [one(Sampling::Center)?, one(sampling)?];
    let cam = &scene.camera;
    let size = (JAGGED_CROP.0.min(cam.nx), if V::DIM == 2 { 1 } else { JAGGED_CROP.1.min(cam.ny) });
    let corner = match aim {
        Aim::Pixel(i, j) => (
            i.saturating_sub(size.0 / 2).min(cam.nx - size.0),
            j.saturating_sub(size.1 / 2).min(cam.ny - size.1),
        ),
        _ => {
            // Changed pixels, summed over every crop through a table of prefix sums.
            let (nx, ny) = (cam.nx, cam.ny);
            let mut sums = vec![0usize; (nx + 1) * (ny + 1)];
            for j in 0..ny {
                for i in 0..nx {
                    let c = usize::from(differs(renders[0].image.get(i, j), renders[1].image.get(i, j)));
                    sums[(j + 1) * (nx + 1) + i + 1] =
                        c + sums[j * (nx + 1) + i + 1] + sums[(j + 1) * (nx + 1) + i]
                            - sums[j * (nx + 1) + i];
                }
            }
            let at = |i: usize, j: usize| sums[j * (nx + 1) + i];
            let centre = ((nx - size.0) as f64 / 2.0, (ny - size.1) as f64 / 2.0);
            let mut best: Option<(usize, f64, (usize, usize))> = None;
            for j in 0..=ny - size.1 {
                for i in 0..=nx - size.0 {
                    let n = at(i + size.0, j + size.1) + at(i, j) - at(i + size.0, j) - at(i, j + size.1);
                    let d = (i as f64 - centre.0).hypot(j as f64 - centre.1);
                    if best.is_none_or(|(bn, bd, _)| n > bn || (n == bn && d < bd)) {
                        best = Some((n, d, (i, j)));
                    }
                }
            }
            best.map_or((0, 0), |(_, _, c)| c)
        }
    };
    Ok(Jagged { renders, corner, size })
}
