//! The whole image (algorithm.md §6 "for each pixel", §8 "more primary rays"): the pixels of the
//! chosen [`Sampling`] mode, rows in parallel (rayon), traced with `NoRecorder` only, so rendering
//! never pays for a trace. A 2D scene renders its one row and repeats it down a strip
//! `max(1, Nx/8)` rows tall.
//!
//! With corners or adaptive sampling the image is rendered in bands of pixel rows: the corners of
//! the band's edge rows are traced first, then the pixel rows run in parallel and share the finer
//! points of the edge rows between them (`sample::shared`); the band's top edge row is carried
//! into the next band, so every sample is traced exactly once, and memory holds one band's edge
//! rows, never the whole refined lattice. Each sample's colour depends
//! only on its lattice point and each pixel sums its squares in a fixed order, so the image and the
//! counts are the same for any number of threads.

use crate::accel::Accel;
use crate::image::Image;
use crate::record::NoRecorder;
use crate::sample::corners::Lattice;
use crate::sample::shared::{render_row, EdgeRow, Edges, Scratch};
use crate::sample::Sampling;
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use crate::trace::stats::Stats;
use crate::trace::Tracer;
use rayon::prelude::*;

/// What a render produced.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The image.
    pub image: Image,
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
    /// About how many bytes the edge rows of one band of pixel rows may take (corners and
    /// adaptive sampling; default [`BAND_MEMORY`]): what bounds the memory of a deep `--max-level`.
    pub band_memory: usize,
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
            band_memory: BAND_MEMORY,
        }
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
    let cam = &scene.camera;
    let height = if V::DIM == 2 { config.strip_rows.unwrap_or_else(|| strip_height(cam.nx)) } else { cam.ny };
    let mut image = Image::new(cam.nx, height);
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
fn center_rows<V: Dim>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    config: &RenderConfig<'_>,
    pixels: &mut [Rgb],
) -> Stats {
    let cam = &scene.camera;
    let rows: Vec<Stats> = pixels
        .par_chunks_mut(cam.nx)
        .enumerate()
        .map_init(
            || tracer(scene, accel, config.max_depth),
            |tracer, (j, row)| {
                for (i, pixel) in row.iter_mut().enumerate() {
                    let (u, v) = cam.pixel_center(i, j);
                    *pixel = tracer.trace_primary(&cam.primary_ray(u, v), &[]);
                }
                if let Some(progress) = config.progress {
                    progress(1);
                }
                std::mem::take(&mut tracer.stats)
            },
        )
        .collect();
    total(rows)
}

fn tracer<'s, V: Dim>(scene: &'s Scene<V>, accel: &'s Accel<V>, max_depth: u32) -> Tracer<'s, V, NoRecorder> {
    let mut tracer = Tracer::new(scene, accel, NoRecorder);
    tracer.max_depth = max_depth;
    tracer
}

/// The default of [`RenderConfig::band_memory`]: 2 MiB. A smaller budget keeps a band's edge
/// rows in cache and reuses their pages band after band; a larger one buys fewer bands (fewer
/// waits between the two phases of a band). An edge row's cells are allocated and initialised in
/// full (by the thread that first traces the row), however few of them the subdivision reads.
/// Measured at 640x480 (medians of 15 alternating runs, bench/README.md): with corners, 2 MiB
/// (4 bands) took 6 % less trace time than 8 MiB (one band, 2 100 more page faults) on one
/// thread and 3 % less on two; adaptive sampling (K = 2) did not move beyond the noise.
pub const BAND_MEMORY: usize = 2 << 20;

/// Pixel rows per band: as many as fit `budget` bytes of edge rows (each `Nx + 1` corner colours
/// and, for K > 0, `Nx·2^K + 1` shared cells), between 2 and 1024. With the default budget a
/// 640x480 image renders in bands of 136 rows with corners (15 KB an edge row) and of 21 rows
/// at K = 2 (97 KB an edge row); a 1920-pixel-wide one at K = 8, 491 521 cells a row, in bands of
/// 2 rows (47 MB: the 2-row minimum exceeds the budget there).
fn band_rows(lattice: Lattice, budget: usize) -> usize {
    let corners = (lattice.nx + 1) * std::mem::size_of::<Rgb>();
    let cells = if lattice.max_level > 0 {
        lattice.row_len() * std::mem::size_of::<std::sync::OnceLock<Rgb>>()
    } else {
        0
    };
    (budget / (corners + cells)).clamp(2, 1024).min(lattice.ny)
}

/// §8: corners and adaptive sampling on the shared lattice, band after band of pixel rows: first
/// the corners of the band's edge rows (in parallel over rows), then its pixel rows (in parallel).
/// Each pixel's sample count goes to `counts` when asked for, else to a band-sized scratch.
fn lattice_rows<V: Dim>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    config: &RenderConfig<'_>,
    rule: (f64, u32),
    pixels: &mut [Rgb],
    mut counts: Option<&mut [u32]>,
) -> Stats {
    let lattice = Lattice::new(&scene.camera, rule.1);
    let nx = lattice.nx;
    let new_tracer = || tracer(scene, accel, config.max_depth);
    if lattice.dims() == 1 {
        // A 2D scene: one line of intervals; its corners are its pixels' ends.
        let mut tracer = new_tracer();
        let mut edge = EdgeRow::new(lattice, false);
        edge.trace_corners(&mut tracer, lattice, 0);
        let edges = Edges { bottom: &edge, top: &edge };
        let mut scratch = Scratch::new(lattice);
        let mut unused = Vec::new();
        let counts = counts.unwrap_or_else(|| {
            unused.resize(nx, 0);
            &mut unused
        });
        lattice_row(&mut tracer, &mut scratch, lattice, rule, config, 0, edges, (pixels, counts));
        return tracer.stats;
    }
    let band = band_rows(lattice, config.band_memory);
    let mut edge_rows: Vec<EdgeRow> = (0..=band).map(|_| EdgeRow::new(lattice, true)).collect();
    let mut stats = Vec::new();
    let mut unused_counts = Vec::new();
    let mut j0 = 0;
    while j0 < lattice.ny {
        let n = band.min(lattice.ny - j0);
        // The first band traces its bottom edge row too; later ones carry it from the band below.
        let first = usize::from(j0 > 0);
        let traced: Vec<Stats> = edge_rows[first..=n]
            .par_iter_mut()
            .enumerate()
            .map_init(new_tracer, |tracer, (k, row)| {
                row.trace_corners(tracer, lattice, j0 + first + k);
                std::mem::take(&mut tracer.stats)
            })
            .collect();
        stats.extend(traced);
        let edge_ref = &edge_rows;
        let band_pixels = pixels[j0 * nx..(j0 + n) * nx].par_chunks_mut(nx);
        let band_counts = match counts.as_deref_mut() {
            Some(all) => &mut all[j0 * nx..(j0 + n) * nx],
            None => {
                unused_counts.resize(n * nx, 0);
                &mut unused_counts[..n * nx]
            }
        }
        .par_chunks_mut(nx);
        let rows: Vec<Stats> = band_pixels
            .zip(band_counts)
            .enumerate()
            .map_init(
                || (new_tracer(), Scratch::new(lattice)),
                |(tracer, scratch), (k, row)| {
                    let edges = Edges { bottom: &edge_ref[k], top: &edge_ref[k + 1] };
                    lattice_row(tracer, scratch, lattice, rule, config, j0 + k, edges, row);
                    std::mem::take(&mut tracer.stats)
                },
            )
            .collect();
        stats.extend(rows);
        // The band's top edge row is the next band's bottom one.
        edge_rows.swap(0, n);
        j0 += n;
    }
    total(stats)
}

/// One pixel row of the lattice modes, into its pixels and per-pixel counts.
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
    (pixels, counts): (&mut [Rgb], &mut [u32]),
) {
    render_row(tracer, lattice, rule, j, edges, scratch, pixels, counts);
    if let Some(progress) = config.progress {
        progress(1);
    }
}
