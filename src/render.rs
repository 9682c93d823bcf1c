//! The whole image (algorithm.md §6 "for each pixel", §8 "more primary rays"): the pixels of the
//! chosen [`Sampling`] mode, rows in parallel (rayon), traced with `NoRecorder` only, so rendering
//! never pays for a trace. A 2D scene renders its one row and repeats it down a strip
//! `max(1, Nx/8)` rows tall.
//!
//! With corners or adaptive sampling the pixel rows run in parallel too, in jobs of consecutive
//! rows, each row between two edge rows (the lattice rows on pixel-row boundaries) that it shares
//! with the pixel rows below and above (`sample::shared`): an edge row is made by the first pixel
//! row that needs it and dropped when the second is done, so every sample is traced exactly once
//! and memory never holds the whole refined lattice. A pixel row's subdivision runs breadth first
//! (`sample::breadth`), in a thread's `Scratch`, which its jobs lend one after another (`Lent`).
//! Each sample's colour depends only on its lattice point and each pixel sums its squares in a
//! fixed order, so the image and the counts are the same for any number of threads.
//!
//! With `center` sampling each pixel row is one rayon job. No job waits at a barrier: rows are
//! written in place into the image, and a job's size comes from `job_rows` (small jobs, so that a
//! thread out of work takes the next one). Nothing large is written serially: an edge row is
//! allocated by the thread that first traces it, the blank image by every thread (`Image::new`).
//!
//! Each pixel's colour is computed in `f64`, a row at a time, into the caller's [`Pixel`]s
//! (`Pixel::colours`, `Pixel::keep`): linear colours ([`render`], for whatever measures or
//! compares colours) traced in place, or the 8-bit bytes of the file ([`render_as`] with
//! `[u8; 3]`, for `whitted render` and the page) traced into a thread's row of colours and then
//! converted, which spares the render 21 of 24 bytes a pixel and their first-touch page faults.
//! The tracing code is the same whatever the pixel type: one copy of it in the program.

use crate::accel::Accel;
use crate::geom::ray::Ray;
use crate::image::{Image, Pixel};
use crate::record::stats::Stats;
use crate::record::NoRecorder;
use crate::sample::breadth::{render_row, Scratch};
use crate::sample::corners::{Axes, Lattice};
use crate::sample::shared::{EdgeRow, EdgeRows, Edges};
use crate::sample::Sampling;
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use crate::trace::Tracer;
use rayon::prelude::*;
use std::ops::Range;
use std::sync::{Mutex, PoisonError};

/// What a render produced, its image of pixels `P` (linear colours unless asked otherwise).
#[derive(Clone, Debug)]
pub struct Rendered<P = Rgb> {
    /// The image.
    pub image: Image<P>,
    /// Rays and tests, summed over threads (`rays.primary` = the samples traced).
    pub stats: Stats,
    /// Pixels computed (a 2D strip counts its one row).
    pub pixels: u64,
    /// If asked for: per computed pixel, `[j·Nx + i]` with j from the bottom (a 2D scene: its one
    /// row, Nx entries), the number of distinct primary-ray samples whose colour entered the pixel.
    /// A sample shared by several pixels (a corner, a point on an edge) counts once for **every**
    /// pixel that read it, whoever traced it; a sample on the edge that a pixel did not need does
    /// not count for it. So the sum over pixels exceeds `rays.primary` where samples are shared:
    /// 1 per pixel with `center`, 4 with `corners`, 4 to `(2^K + 1)²` with `adaptive`.
    pub rays_per_pixel: Option<Vec<u32>>,
}

/// How to render.
#[derive(Clone, Copy)]
pub struct RenderConfig<'a> {
    /// The sampling mode.
    pub sampling: Sampling,
    /// Children are spawned by a node at level n iff `n ≤ max_depth` (the scene's, or `--depth`).
    pub max_depth: u32,
    /// The rows of a 2D scene's strip (default [`strip_height`]).
    pub strip_rows: Option<usize>,
    /// Whether to count the samples of each pixel ([`Rendered::rays_per_pixel`]).
    pub rays_per_pixel: bool,
    /// Called with the number of pixel rows finished, from any thread (a progress bar).
    pub progress: Option<&'a (dyn Fn(u64) + Sync)>,
    /// About how many bytes the edge rows that wait between jobs of pixel rows may take (corners
    /// and adaptive sampling; default [`EDGE_MEMORY`]): what bounds the memory of a deep
    /// `--max-level`.
    pub edge_memory: usize,
}

impl RenderConfig<'_> {
    /// The lecture's render: one ray through each pixel centre, the given depth, no counts, no
    /// progress.
    #[must_use]
    pub fn centers(max_depth: u32) -> Self {
        Self {
            sampling: Sampling::Center,
            max_depth,
            strip_rows: None,
            rays_per_pixel: false,
            progress: None,
            edge_memory: EDGE_MEMORY,
        }
    }
}

/// The most worker threads `--threads` may ask for.
pub const MAX_THREADS: u32 = 1024;
/// The most pixels an image may have (16 384² = 2^28), whatever each axis allows.
pub const MAX_PIXELS: u64 = 1 << 28;
/// The most memory a render may need ([`memory_needed`]), 8 GiB: refused above, before any work
/// (and less where the machine gives less: `memory::budget`).
pub use crate::memory::MAX_MEMORY;
/// Bytes a written pixel costs beside its linear colour: the 8-bit RGB copy and, at worst, as
/// many bytes again of PNG stream.
const PNG_BYTES_PER_PIXEL: u64 = 6;

/// About how many bytes a render of `scene` (its camera already resized) needs with `config` on
/// `threads` threads: the linear image and its PNG, the per-pixel counts if asked, and for corners
/// or adaptive sampling the lattice's u, v tables, the edge rows (two per thread in progress,
/// plus `edge_memory` of rows waiting between jobs) and each thread's [`Scratch`]. It counts the
/// linear image, 24 bytes a pixel, also for a render that keeps only the file's bytes
/// ([`render_as`]): an over-estimate, so that one refusal holds for every caller.
#[must_use]
pub fn memory_needed<V: Dim>(scene: &Scene<V>, config: &RenderConfig<'_>, threads: usize) -> u64 {
    let cam = &scene.camera;
    let pixels = cam.nx as u64 * image_height(scene, config) as u64;
    let rgb = std::mem::size_of::<Rgb>() as u64;
    let mut bytes = pixels.saturating_mul(rgb + PNG_BYTES_PER_PIXEL);
    if config.rays_per_pixel {
        bytes = bytes.saturating_add(pixels.saturating_mul(std::mem::size_of::<u32>() as u64));
    }
    if let Some((_, max_level)) = config.sampling.rule() {
        let lattice = Lattice::new(cam, max_level);
        let scale = 1u64 << max_level;
        let axes = (cam.nx as u64 * scale + 1).saturating_add(cam.ny as u64 * scale + 1);
        let in_flight = 2 * (threads as u64 + 1);
        bytes = bytes
            .saturating_add(axes.saturating_mul(std::mem::size_of::<f64>() as u64))
            .saturating_add(in_flight.saturating_mul(EdgeRow::bytes(lattice) as u64))
            .saturating_add((threads as u64).saturating_mul(Scratch::bytes(lattice) as u64))
            .saturating_add(config.edge_memory as u64);
    }
    bytes
}

/// Refuses, before any work, a render that cannot fit: more than [`MAX_PIXELS`] pixels, or more
/// bytes by [`memory_needed`] than the process's budget (`memory::budget`: [`MAX_MEMORY`], or
/// less where the machine gives less).
///
/// # Errors
/// The size asked, what it needs and the limit, worded for a person who will change `--size`.
pub fn check_fits<V: Dim>(scene: &Scene<V>, config: &RenderConfig<'_>, threads: usize) -> Result<(), String> {
    let cam = &scene.camera;
    let height = image_height(scene, config);
    let pixels = cam.nx as u64 * height as u64;
    if pixels > MAX_PIXELS {
        return Err(format!(
            "{}x{height} is {pixels} pixels, more than the limit of {MAX_PIXELS}: choose a smaller --size",
            cam.nx
        ));
    }
    let needed = memory_needed(scene, config, threads);
    let what = format!("{}x{height} with {} sampling", cam.nx, config.sampling.name());
    crate::memory::budget().check(needed, &what, "choose a smaller --size (or --max-level)")
}

/// The rows of the image a render writes: the camera's Ny, or a 2D scene's strip.
fn image_height<V: Dim>(scene: &Scene<V>, config: &RenderConfig<'_>) -> usize {
    let nx = scene.camera.nx;
    if V::DIM == 2 {
        config.strip_rows.unwrap_or_else(|| strip_height(nx))
    } else {
        scene.camera.ny
    }
}

/// Height of the strip a 2D scene renders to: `max(1, Nx/8)` (product.md).
#[must_use]
pub fn strip_height(nx: usize) -> usize {
    (nx / 8).max(1)
}

/// Renders every pixel centre of the scene's camera in the current rayon pool; a 2D scene's row
/// is repeated `strip_rows` times (default [`strip_height`]).
#[must_use]
pub fn render_centers<V: Dim>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    max_depth: u32,
    strip_rows: Option<usize>,
) -> Rendered {
    render(scene, accel, &RenderConfig { strip_rows, ..RenderConfig::centers(max_depth) })
}

/// Renders the scene's image with `config`'s sampling in the current rayon pool.
#[must_use]
pub fn render<V: Dim>(scene: &Scene<V>, accel: &Accel<V>, config: &RenderConfig<'_>) -> Rendered {
    render_as(scene, accel, config)
}

/// [`render`] into pixels `P`: each pixel's colour is computed as [`render`] computes it, then
/// kept as `P` ([`Pixel::from_linear`]). `[u8; 3]`, the bytes of a file, keeps an eighth of the
/// memory, and its trace touches an eighth of the fresh pages.
#[must_use]
pub fn render_as<V: Dim, P: Pixel>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    config: &RenderConfig<'_>,
) -> Rendered<P> {
    let cam = &scene.camera;
    let height = image_height(scene, config);
    let mut image = Image::<P>::new(cam.nx, height);
    // Rows are written in place: the computed rows are the first Ny of the image.
    let computed = &mut image.pixels[..cam.nx * cam.ny];
    let (stats, counts) = match config.sampling.rule() {
        None => {
            let stats = center_rows(scene, accel, config, computed);
            (stats, config.rays_per_pixel.then(|| vec![1; cam.nx * cam.ny]))
        }
        Some(rule) => {
            let mut counts = config.rays_per_pixel.then(|| vec![0; cam.nx * cam.ny]);
            let stats = lattice_rows(scene, accel, config, rule, computed, counts.as_deref_mut());
            (stats, counts)
        }
    };
    if V::DIM == 2 {
        let first: Vec<_> = image.pixels[..cam.nx].to_vec();
        for j in 1..height {
            image.pixels[j * cam.nx..(j + 1) * cam.nx].copy_from_slice(&first);
        }
    }
    Rendered { image, stats, pixels: (cam.nx * cam.ny) as u64, rays_per_pixel: counts }
}

/// Sums the statistics of the rows (integer counts: the order does not matter).
fn total(rows: Vec<Stats>) -> Stats {
    let mut sum = Stats::default();
    for s in rows {
        sum += s;
    }
    sum
}

/// §2: one ray through each pixel centre, `u = l + (r − l)·(i + 0.5)/Nx`; rows in parallel.
fn center_rows<V: Dim, P: Pixel>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    config: &RenderConfig<'_>,
    pixels: &mut [P],
) -> Stats {
    let cam = &scene.camera;
    let us = column_us(scene);
    let rows: Vec<Stats> = pixels
        .par_chunks_mut(cam.nx)
        .enumerate()
        // Every row its own rayon job, so that a thread that runs out of rows takes the next one
        // (rayon's default leaves, 60 to 120 rows of 480 on two threads, could leave one thread
        // idle for the last sixth of a render).
        .with_max_len(1)
        .map_init(
            || (tracer(scene, accel, config.max_depth), Vec::with_capacity(cam.nx), vec![Rgb::BLACK; cam.nx]),
            |(tracer, rays, scratch), (j, row)| {
                center_row(tracer, &us, j, P::colours(row, scratch), rays);
                P::keep(row, scratch);
                if let Some(progress) = config.progress {
                    progress(1);
                }
                std::mem::take(&mut tracer.stats)
            },
        )
        .collect();
    total(rows)
}

/// Each column's u of a centre-sampled image, `u = l + (r − l)·(i + 0.5)/Nx`, computed once:
/// not a division per pixel at the head of every primary ray's chain (the same values, as
/// `pixel_center` computes u from i alone and v from j alone).
fn column_us<V: Dim>(scene: &Scene<V>) -> Vec<f64> {
    let cam = &scene.camera;
    (0..cam.nx).map(|i| cam.pixel_center(i, 0).0).collect()
}

/// §2 for the pixels of row `j` whose columns' u are `us`, into `row`
/// ([`Tracer::trace_window_row`], `rays` its room for the rays made one at a time).
fn center_row<V: Dim>(
    tracer: &mut Tracer<'_, V, NoRecorder>,
    us: &[f64],
    j: usize,
    row: &mut [Rgb],
    rays: &mut Vec<Ray<V>>,
) {
    let v = tracer.scene.camera.pixel_center(0, j).1;
    tracer.trace_window_row(us, v, rays, row);
}

/// A band of the image, on the calling thread, for a page that shows a render's progress
/// (`web/`): pixel rows `range` (j from the bottom) of a 3D image, or pixels `range` (i) of a 2D
/// scene's one row, in any sampling mode. Its colours are those [`render`] writes there (§2, §8:
/// each sample's colour depends on its lattice point alone) and its rays and tests those its
/// samples took, so that the bands of an image summed are the whole render. With corners and
/// adaptive sampling the band before this one shares its last edge (a lattice row, or a pixel
/// end) and counted its samples there: this band first traces again, uncounted, what that band's
/// last row traced on the edge (or the end), then counts only the rest. Parts of `range` past the
/// image are left out. The image is `width × height` with its rows from the bottom: `Nx × rows`
/// in 3D, `pixels × 1` in 2D.
#[must_use]
pub fn band<V: Dim>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    (sampling, max_depth): (Sampling, u32),
    range: Range<usize>,
) -> (Image, Stats) {
    let cam = &scene.camera;
    let flat = V::DIM == 2;
    let len = if flat { cam.nx } else { cam.ny };
    let range = range.start.min(len)..range.end.min(len);
    let (width, height) = if flat { (range.len(), 1) } else { (cam.nx, range.len()) };
    let mut image = Image { width, height, pixels: vec![Rgb::default(); width * height] };
    let mut counted = tracer(scene, accel, max_depth);
    match sampling.rule() {
        None => {
            let (us, mut rays) = (column_us(scene), Vec::with_capacity(cam.nx));
            if flat {
                center_row(&mut counted, &us[range], 0, &mut image.pixels, &mut rays);
            } else {
                for (j, row) in range.zip(image.pixels.chunks_mut(cam.nx)) {
                    center_row(&mut counted, &us, j, row, &mut rays);
                }
            }
        }
        Some(_) if range.is_empty() => {}
        Some(rule) => {
            let mut quiet = tracer(scene, accel, max_depth);
            lattice_band(scene, (&mut counted, &mut quiet), rule, range, &mut image.pixels);
        }
    }
    (image, counted.stats)
}

/// [`band`]'s lattice modes: the band's rows (or a 2D line's pixels) into `pixels`, their samples
/// counted by `counted`, the shared edge below the band traced again by `quiet`.
fn lattice_band<'s, V: Dim>(
    scene: &Scene<V>,
    (counted, quiet): (&mut Tracer<'s, V, NoRecorder>, &mut Tracer<'s, V, NoRecorder>),
    rule: (f64, u32),
    range: Range<usize>,
    pixels: &mut [Rgb],
) {
    let lattice = Lattice::new(&scene.camera, rule.1);
    let mut scratch = Scratch::new(lattice);
    // `lattice.dims() = V::DIM − 1`: asked of V, so that each dimension builds only its own.
    if V::DIM == 2 {
        // A 2D scene's line: pixels share only their ends (the finer points lie inside one pixel).
        let axes = Axes::new(lattice, &scene.camera);
        let ends = range.start..=range.end;
        let edge = EdgeRow::trace_ends((&mut *counted, quiet), (lattice, &axes), ends, range.start > 0);
        let edges = Edges { bottom: &edge, top: &edge, axes: &axes };
        render_row(counted, lattice, rule, (range.start, 0), edges, &mut scratch, pixels, None);
        return;
    }
    let edges = EdgeRows::new(lattice, &scene.camera);
    let mut row = |tracer: &mut Tracer<'s, V, NoRecorder>, j: usize, out: &mut [Rgb]| {
        let top = edges.acquire(tracer, j + 1);
        let bottom = edges.acquire(tracer, j);
        let pair = Edges { bottom: &bottom, top: &top, axes: edges.axes() };
        render_row(tracer, lattice, rule, (0, j), pair, &mut scratch, out, None);
        edges.release(j);
        edges.release(j + 1);
    };
    if let Some(below) = range.start.checked_sub(1) {
        row(quiet, below, &mut vec![Rgb::default(); lattice.nx]);
    }
    for (k, out) in pixels.chunks_mut(lattice.nx).enumerate() {
        row(counted, range.start + k, out);
    }
}

fn tracer<'s, V: Dim>(scene: &'s Scene<V>, accel: &'s Accel<V>, max_depth: u32) -> Tracer<'s, V, NoRecorder> {
    let mut tracer = Tracer::new(scene, accel, NoRecorder);
    tracer.max_depth = max_depth;
    tracer
}

/// The default of [`RenderConfig::edge_memory`]: 8 MiB. An edge row shared by two rayon jobs of
/// pixel rows waits in memory until the second job reaches it; this budget sets the fewest pixel
/// rows a job takes ([`job_rows`]), which bounds how many jobs, and so how many waiting rows, there
/// can be. A 640x480 image at K = 2 (97 KB an edge row) runs in jobs of at least 6 rows.
pub const EDGE_MEMORY: usize = 8 << 20;

/// The pixel rows of a rayon job of a lattice render (rayon halves a range while both halves are
/// at least this long, so a job takes `job` to `2·job − 1` rows): enough that `Ny / job` edge
/// rows fit `budget` bytes, but at most `Ny / (2·threads)`, so that every thread has work. Jobs
/// run their rows bottom to top; a thread that runs out takes the next job, so the last to
/// finish is short.
fn job_rows(lattice: Lattice, budget: usize, threads: usize) -> usize {
    let wanted = (lattice.ny * EdgeRow::bytes(lattice)).div_ceil(budget.max(1));
    let most = (lattice.ny / (2 * threads.max(1))).max(1);
    wanted.clamp(1, most)
}

/// §8: corners and adaptive sampling on the shared lattice. Pixel rows run in parallel, in jobs of
/// consecutive rows ([`job_rows`]); a pixel row asks [`EdgeRows`] for its top edge row, then its
/// bottom one (so a job's first row makes its own top row while the job below may still be
/// making the row they share), and releases both when done. Each pixel's sample count goes to
/// `counts` when asked for.
fn lattice_rows<V: Dim, P: Pixel>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    config: &RenderConfig<'_>,
    rule: (f64, u32),
    pixels: &mut [P],
    counts: Option<&mut [u32]>,
) -> Stats {
    let lattice = Lattice::new(&scene.camera, rule.1);
    let nx = lattice.nx;
    // `lattice.dims() = V::DIM − 1`: asked of V, so that each dimension builds only its own.
    if V::DIM == 2 {
        // A 2D scene: one line of intervals; its corners are its pixels' ends.
        let mut tracer = tracer(scene, accel, config.max_depth);
        let axes = Axes::new(lattice, &scene.camera);
        let edge = EdgeRow::trace(&mut tracer, (lattice, &axes), 0, false);
        let edges = Edges { bottom: &edge, top: &edge, axes: &axes };
        let mut scratch = Scratch::new(lattice);
        let mut colours = vec![Rgb::BLACK; pixels.len()];
        let out = P::colours(pixels, &mut colours);
        lattice_row(&mut tracer, &mut scratch, lattice, rule, config, 0, edges, (out, counts));
        P::keep(pixels, &colours);
        return tracer.stats;
    }
    let edges = EdgeRows::new(lattice, &scene.camera);
    let rows = Rows { scene, accel, config, rule, lattice, edges, spares: Mutex::new(Vec::new()) };
    match counts {
        Some(counts) => {
            rows.run(pixels.par_chunks_mut(nx).zip(counts.par_chunks_mut(nx)).map(|(p, c)| (p, Some(c))))
        }
        None => rows.run(pixels.par_chunks_mut(nx).map(|p| (p, None))),
    }
}

/// What every pixel row of a lattice render shares.
struct Rows<'a, V: Dim> {
    scene: &'a Scene<V>,
    accel: &'a Accel<V>,
    config: &'a RenderConfig<'a>,
    rule: (f64, u32),
    lattice: Lattice,
    edges: EdgeRows,
    /// The [`Scratch`]es of jobs that ended, for the next jobs ([`Lent`]).
    spares: Mutex<Vec<Scratch>>,
}

/// A rayon job's [`Scratch`], taken from the render's spares (made if there is none) and given
/// back when the job ends: so a render makes one a thread, not one a job (a 640-pixel row's is
/// 0.4 MB, all written when it is made).
struct Lent<'s> {
    scratch: Option<Scratch>,
    spares: &'s Mutex<Vec<Scratch>>,
}

impl<'s> Lent<'s> {
    /// A spare of `spares`, or a new one for `lattice`.
    fn take(spares: &'s Mutex<Vec<Scratch>>, lattice: Lattice) -> Self {
        let spare = spares.lock().unwrap_or_else(PoisonError::into_inner).pop();
        Self { scratch: Some(spare.unwrap_or_else(|| Scratch::new(lattice))), spares }
    }
    /// The scratch, held until the job ends.
    fn get(&mut self) -> &mut Scratch {
        self.scratch.as_mut().expect("held until dropped")
    }
}

impl Drop for Lent<'_> {
    fn drop(&mut self) {
        if let Some(scratch) = self.scratch.take() {
            self.spares.lock().unwrap_or_else(PoisonError::into_inner).push(scratch);
        }
    }
}

impl<V: Dim> Rows<'_, V> {
    /// Renders the pixel rows `rows` gives, bottom to top (each with its counts, if asked for).
    fn run<'p, P: Pixel>(
        &self,
        rows: impl IndexedParallelIterator<Item = (&'p mut [P], Option<&'p mut [u32]>)>,
    ) -> Stats {
        let (lattice, edges) = (self.lattice, &self.edges);
        let job = job_rows(lattice, self.config.edge_memory, rayon::current_num_threads());
        let stats: Vec<Stats> = rows
            .enumerate()
            .with_min_len(job)
            .with_max_len(job)
            .map_init(
                || {
                    let tracer = tracer(self.scene, self.accel, self.config.max_depth);
                    (tracer, Lent::take(&self.spares, lattice), vec![Rgb::BLACK; lattice.nx])
                },
                |(tracer, scratch, colours), (j, (row, counts))| {
                    let out = P::colours(row, colours);
                    let top = edges.acquire(tracer, j + 1);
                    let bottom = edges.acquire(tracer, j);
                    let pair = Edges { bottom: &bottom, top: &top, axes: edges.axes() };
                    lattice_row(
                        tracer,
                        scratch.get(),
                        lattice,
                        self.rule,
                        self.config,
                        j,
                        pair,
                        (out, counts),
                    );
                    P::keep(row, colours);
                    edges.release(j);
                    edges.release(j + 1);
                    std::mem::take(&mut tracer.stats)
                },
            )
            .collect();
        total(stats)
    }
}

/// One pixel row of the lattice modes, into its colours and per-pixel counts.
// The inputs of `render_row` plus the progress callback; a struct would only rename them.
#[allow(clippy::too_many_arguments)]
fn lattice_row<V: Dim>(
    tracer: &mut Tracer<'_, V, NoRecorder>,
    scratch: &mut Scratch,
    lattice: Lattice,
    rule: (f64, u32),
    config: &RenderConfig<'_>,
    j: usize,
    edges: Edges<'_>,
    (pixels, counts): (&mut [Rgb], Option<&mut [u32]>),
) {
    render_row(tracer, lattice, rule, (0, j), edges, scratch, pixels, counts);
    if let Some(progress) = config.progress {
        progress(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::camera::Camera;
    use crate::scene::load::load_str;
    use crate::scene::AnyScene;

    fn camera(nx: usize, ny: usize) -> Camera<glam::DVec3> {
        let text = format!(
            r#"{{"camera": {{"eye": [0,0,5], "center": [0,0,0], "window": {{"l": -1, "r": 1, "b": -1, "t": 1}}, "resolution": [{nx}, {ny}]}}}}"#
        );
        let Ok(AnyScene::Space(scene)) = load_str(&text) else { panic!("a 3D scene") };
        scene.camera
    }

    #[test]
    fn jobs_keep_waiting_edge_rows_within_the_budget_and_every_thread_busy() {
        // 640x480 at K = 2: 2 561 cells of 32 bytes and 641 corners of 24 bytes an edge row,
        // 97 kB; 480 of them are 46.7 MB, so 8 MiB asks for jobs of at least 6 rows.
        let wide = camera(640, 480);
        assert_eq!(EdgeRow::bytes(Lattice::new(&wide, 2)), 2561 * 32 + 641 * 24);
        assert_eq!(job_rows(Lattice::new(&wide, 2), EDGE_MEMORY, 2), 6);
        // With corners (15 kB a row) every row fits: one-row jobs.
        assert_eq!(job_rows(Lattice::new(&wide, 0), EDGE_MEMORY, 2), 1);
        // A deep level on a wide image: the budget would want one job; two threads get 4.
        let hd = camera(1920, 1080);
        assert_eq!(job_rows(Lattice::new(&hd, 8), EDGE_MEMORY, 2), 270);
        // Fewer rows than threads: one-row jobs.
        assert_eq!(job_rows(Lattice::new(&camera(8, 3), 8), 1, 4), 1);
    }

    /// Every mode's sampling, at a level deep enough that edges shared between bands hold finer
    /// points.
    const MODES: [Sampling; 3] =
        [Sampling::Center, Sampling::Corners, Sampling::Adaptive { threshold: 0.05, max_level: 2 }];

    /// Renders `scene` whole and in bands of `size` (rows in 3D, pixels in 2D) in each of
    /// [`MODES`]: the bands' pixels laid side by side and their counts summed are the render's.
    fn bands_are_the_render<V: Dim>(scene: &Scene<V>, size: usize) {
        let accel = Accel::build_with(scene, &crate::accel::AccelOptions::of(crate::accel::AccelKind::Bvh));
        let cam = &scene.camera;
        let len = if V::DIM == 2 { cam.nx } else { cam.ny };
        for sampling in MODES {
            let config = RenderConfig { sampling, ..RenderConfig::centers(scene.max_depth) };
            let whole = render(scene, &accel, &config);
            if matches!(sampling, Sampling::Adaptive { .. }) {
                // Some pixels split: finer points lie on the edges the bands share.
                let corners = (cam.nx + 1) * if V::DIM == 2 { 1 } else { cam.ny + 1 };
                assert!(whole.stats.rays.primary > corners as u64, "{:?}", whole.stats.rays);
            }
            let mut pixels = Vec::new();
            let mut stats = Stats::default();
            for start in (0..len).step_by(size) {
                let (band, counted) = band(scene, &accel, (sampling, scene.max_depth), start..start + size);
                assert_eq!(band.pixels.len(), (len - start).min(size) * if V::DIM == 2 { 1 } else { cam.nx });
                pixels.extend(band.pixels);
                stats += counted;
            }
            assert_eq!(pixels, whole.image.pixels[..cam.nx * cam.ny], "{}", sampling.name());
            assert_eq!(stats, whole.stats, "{}", sampling.name());
        }
    }

    #[test]
    fn bands_of_rows_are_the_render_and_its_counts_in_every_mode() {
        let text = r#"{"camera": {"eye": [0,0,5], "center": [0,0,0], "resolution": [9, 7],
            "window": {"l": -1, "r": 1, "b": -0.8, "t": 0.8}},
            "lights": [{"position": [3, 3, 3]}],
            "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": {"ks": 0.5}},
                        {"type": "plane", "point": [0,-1,0], "normal": [0,1,0]}]}"#;
        let Ok(AnyScene::Space(scene)) = load_str(text) else { panic!("a 3D scene") };
        bands_are_the_render(&scene, 3);
    }

    #[test]
    fn bands_of_a_2d_line_are_its_render_and_its_counts_in_every_mode() {
        let text = r#"{"camera": {"eye": [0,0], "center": [0,-1], "resolution": [23],
            "window": {"l": -1, "r": 1}},
            "lights": [{"position": [3, 3]}],
            "objects": [{"type": "sphere", "center": [0,-4], "radius": 1, "material": {"ks": 0.5}},
                        {"type": "plane", "point": [0,-6], "normal": [0,1]}]}"#;
        let Ok(AnyScene::Flat(scene)) = load_str(text) else { panic!("a 2D scene") };
        bands_are_the_render(&scene, 5);
    }
}
