//! Whitted's adaptive subdivision (algorithm.md §8.2) of a render's pixel row, breadth first:
//! the squares of the row that split at level L give their new points, all traced together in
//! packets ([`Tracer::trace_window_points`]), and only then are the squares of level L + 1
//! decided, each once. Then each split square's colour is summed, deepest level first, in the
//! arithmetic of [`super::adaptive::subdivide`]'s recursion, so that a pixel's bytes are those
//! of a depth-first render; `trace` and anything recorded keep the depth-first recursion, which
//! traces a sample when a square first reads it.
//!
//! A row is taken in chunks of pixels ([`Scratch`]: all of a 640-pixel row at K = 2), each a
//! dense lattice of the colours of its points, stamped so that nothing is cleared per chunk. The
//! points of the edge between two pixels are one column of it, and a chunk's last column is
//! carried to the next chunk's first. A point on the pixel row's bottom or top edge is shared
//! with the pixel row below or above through the edge rows' [`Line`]s: read if traced, else
//! claimed and traced with the level's batch, or, if another thread is tracing it, awaited once
//! this thread's own claims are filled. So every sample is traced once, as in the recursion.

use super::adaptive::{new_points, splits, unsplit, CORNERS};
use super::corners::{corner_mean, Lattice};
use super::shared::{trace_point, Claim, Claims, Edges, Line};
use crate::record::NoRecorder;
use crate::scene::material::Rgb;
use crate::shape::Dim;
use crate::trace::Tracer;

/// The most lattice points a chunk holds: 1.8 MiB of colours and stamps a thread, whatever K.
const CHUNK_POINTS: usize = 1 << 16;

/// One thread's memory for the pixel rows of a lattice: a chunk's lattice of colours and, per
/// level below K, the squares of the chunk that split at it and their colours; the level's
/// batch of points to trace.
#[derive(Debug)]
pub struct Scratch {
    /// `2^K`.
    scale: u32,
    /// Pixels a chunk: as many as [`CHUNK_POINTS`] allow, at least 1, at most `Nx`.
    pixels: usize,
    /// Columns of a chunk's lattice, `pixels·2^K + 1`.
    width: usize,
    /// Rows of a chunk's lattice: `2^K + 1`, or 1 on a 2D scene's line.
    rows: usize,
    /// The colours of the chunk's points, row by row, valid where `stamps` holds `current`.
    colors: Vec<Rgb>,
    /// Per point of `colors`, the stamp of the chunk that last gave it a colour.
    stamps: Vec<u32>,
    /// The current chunk's stamp.
    current: u32,
    /// Per level `L < K`, the lower-left points of the chunk's squares that split at `L`, in the
    /// order decided (a parent's children together, in the order the recursion visits them).
    split: Vec<Vec<(u32, u32)>>,
    /// Per level, the colours of the squares of `split`, in the same order.
    sums: Vec<Vec<Rgb>>,
    /// The level's points to trace.
    batch: Batch,
}

/// A level's points to trace, in the order gathered: their window coordinates, their places in
/// [`Scratch::colors`], and their colours once traced.
#[derive(Debug, Default)]
struct Batch {
    us: Vec<f64>,
    vs: Vec<f64>,
    at: Vec<usize>,
    colors: Vec<Rgb>,
}

impl Scratch {
    /// The memory for pixel rows of `lattice`.
    #[must_use]
    pub fn new(lattice: Lattice) -> Self {
        let (pixels, rows) = Self::chunk(lattice);
        let width = pixels * lattice.scale as usize + 1;
        let levels = lattice.max_level.max(1) as usize;
        Self {
            scale: lattice.scale,
            pixels,
            width,
            rows,
            colors: vec![Rgb::BLACK; width * rows],
            stamps: vec![0; width * rows],
            current: 0,
            split: vec![Vec::new(); levels],
            sums: vec![Vec::new(); levels],
            batch: Batch::default(),
        }
    }
    /// The bytes of one thread's [`Scratch`] for `lattice` (its lattice, the most of it).
    #[must_use]
    pub fn bytes(lattice: Lattice) -> usize {
        let (pixels, rows) = Self::chunk(lattice);
        let point = std::mem::size_of::<Rgb>() + std::mem::size_of::<u32>();
        (pixels * lattice.scale as usize + 1) * rows * point
    }
    /// The pixels of a chunk of `lattice` and the rows of its lattice: each pixel holds
    /// `(2^K + 1)^dims` points, a chunk at most [`CHUNK_POINTS`] (but one pixel, at least).
    fn chunk(lattice: Lattice) -> (usize, usize) {
        let side = lattice.scale as usize + 1;
        let rows = if lattice.dims() == 1 { 1 } else { side };
        ((CHUNK_POINTS / (side * rows)).clamp(1, lattice.nx.max(1)), rows)
    }
    /// Starts a new chunk: every point becomes stale, but for the last column of the previous
    /// chunk if `carry`, which becomes the first column (the edge the chunks share).
    fn next_chunk(&mut self, carry: bool) {
        if self.current == u32::MAX {
            // Renumbered, so that the current chunk's points stay valid: 1, and the others 0.
            for stamp in &mut self.stamps {
                *stamp = u32::from(*stamp == self.current);
            }
            self.current = 1;
        }
        let previous = self.current;
        self.current += 1;
        if carry {
            for b in 0..self.rows {
                let (first, last) = (b * self.width, (b + 1) * self.width - 1);
                if self.stamps[last] == previous {
                    self.stamps[first] = self.current;
                    self.colors[first] = self.colors[last];
                }
            }
        }
        for level in &mut self.split {
            level.clear();
        }
    }
    /// The index in the chunk's lattice of point `(a, b)`.
    #[inline]
    fn index(&self, a: u32, b: u32) -> usize {
        b as usize * self.width + a as usize
    }
    /// Whether chunk point `(a, b)` has its colour (or is gathered to be traced) in this chunk.
    #[inline]
    fn known(&self, a: u32, b: u32) -> bool {
        self.stamps[self.index(a, b)] == self.current
    }
}

/// Renders pixel row `j` with the subdivision rule `(threshold, K)` between its traced edge rows:
/// writes the colour of pixel `first + k` to `pixels[k]` and, if asked, the number of distinct
/// samples it read to `used[k]` (a whole row starts at `first = 0`; a band of a 2D scene's line
/// elsewhere).
// Tracer, lattice, rule, row, edges, scratch and the two outputs are all distinct; a struct
// would only rename them.
#[allow(clippy::too_many_arguments)]
pub fn render_row<V: Dim>(
    tracer: &mut Tracer<'_, V, NoRecorder>,
    lattice: Lattice,
    rule: (f64, u32),
    (first, j): (usize, usize),
    edges: Edges<'_>,
    scratch: &mut Scratch,
    pixels: &mut [Rgb],
    mut used: Option<&mut [u32]>,
) {
    let mut claims = Claims::default();
    let size = scratch.pixels;
    for (c, chunk) in pixels.chunks_mut(size).enumerate() {
        scratch.next_chunk(c > 0);
        let start = c * size;
        let used = used.as_deref_mut().map(|u| &mut u[start..start + chunk.len()]);
        let row = Chunk { lattice, rule, first: first + start, j, edges };
        // `lattice.dims() = V::DIM − 1`: asked of V, so that each dimension builds only its own.
        if V::DIM == 2 {
            row.render::<2, V>(tracer, scratch, &mut claims, chunk, used);
        } else {
            row.render::<4, V>(tracer, scratch, &mut claims, chunk, used);
        }
    }
}

/// A chunk of a pixel row: its lattice, rule, first pixel `(first, j)` and edge rows.
#[derive(Clone, Copy)]
struct Chunk<'e> {
    lattice: Lattice,
    rule: (f64, u32),
    first: usize,
    j: usize,
    edges: Edges<'e>,
}

impl<'e> Chunk<'e> {
    /// The chunk's pixels, whose squares have `N` corners, into `pixels` (and `used`): the level-0
    /// decision of each from its edge rows' corners, the levels of the pixels that split, and
    /// their sums.
    fn render<const N: usize, V: Dim>(
        self,
        tracer: &mut Tracer<'_, V, NoRecorder>,
        scratch: &mut Scratch,
        claims: &mut Claims<'e>,
        pixels: &mut [Rgb],
        mut used: Option<&mut [u32]>,
    ) {
        let (threshold, max_level) = self.rule;
        let s = scratch.scale;
        let (b, t) = (&self.edges.bottom.corners, &self.edges.top.corners);
        #[allow(clippy::cast_possible_truncation)] // N is 2 or 4
        let n = N as u32;
        for (k, pixel) in pixels.iter_mut().enumerate() {
            let i = self.first + k;
            // Corner c is (c & 1, c >> 1) in pixel units: lower-left, lower-right, upper-left, …
            let corners: [&Rgb; N] = std::array::from_fn(|c| if c < 2 { &b[i + c] } else { &t[i + c - 2] });
            if let Some(used) = used.as_deref_mut() {
                used[k] = n;
            }
            if let Some(color) = unsplit(corners, threshold, max_level) {
                *pixel = color;
                continue;
            }
            // k < pixels ≤ CHUNK_POINTS: a lattice column of the chunk.
            #[allow(clippy::cast_possible_truncation)]
            let a = k as u32 * s;
            for (c, (dx, dy)) in CORNERS[..N].iter().enumerate() {
                let at = scratch.index(a + dx * s, dy * s);
                scratch.stamps[at] = scratch.current;
                scratch.colors[at] = *corners[c];
            }
            scratch.split[0].push((a, 0));
        }
        for level in 0..max_level {
            if scratch.split[level as usize].is_empty() {
                break;
            }
            self.trace_level::<N, V>(tracer, scratch, claims, level);
            if level + 1 < max_level {
                decide::<N>(scratch, self.rule, level);
            }
        }
        if max_level == 0 {
            return;
        }
        sum::<N>(scratch, max_level);
        for (&(a, _), &color) in scratch.split[0].iter().zip(&scratch.sums[0]) {
            pixels[(a / s) as usize] = color;
        }
        if let Some(used) = used {
            count::<N>(scratch, max_level, used);
        }
    }

    /// The new points of the squares that split at `level`, each not yet known traced once: read
    /// from a shared line if traced there, else gathered (and a shared one claimed) and traced in
    /// one batch; a shared point another thread is tracing is awaited after.
    fn trace_level<const N: usize, V: Dim>(
        self,
        tracer: &mut Tracer<'_, V, NoRecorder>,
        scratch: &mut Scratch,
        claims: &mut Claims<'e>,
        level: u32,
    ) {
        let (lattice, axes) = (self.lattice, self.edges.axes);
        let half = scratch.scale >> (level + 1);
        let (offsets, count) = const { new_points::<N>() };
        let Scratch { colors, stamps, current, split, batch, width, .. } = scratch;
        let (current, width) = (*current, *width);
        batch.us.clear();
        batch.vs.clear();
        batch.at.clear();
        let mut theirs: Vec<(&Line, u64, u64, usize)> = Vec::new();
        for &(x, y) in &split[level as usize] {
            for &(dx, dy) in &offsets[..count] {
                let (a, b) = (x + dx * half, y + dy * half);
                let at = b as usize * width + a as usize;
                if stamps[at] == current {
                    continue;
                }
                stamps[at] = current;
                let (gx, gy) = lattice.global(self.first, self.j, a, b);
                if let Some(line) = self.edges.line(lattice, b) {
                    // gx ≤ Nx·2^K: the index of a point of the line.
                    #[allow(clippy::cast_possible_truncation)]
                    match claims.claim(line, gx as usize, batch.us.len()) {
                        Claim::Traced(color) => {
                            colors[at] = color;
                            continue;
                        }
                        Claim::Theirs => {
                            theirs.push((line, gx, gy, at));
                            continue;
                        }
                        Claim::Mine => {}
                    }
                }
                let (u, v) = axes.uv(gx, gy);
                batch.us.push(u);
                batch.vs.push(v);
                batch.at.push(at);
            }
        }
        batch.colors.clear();
        batch.colors.resize(batch.us.len(), Rgb::BLACK);
        tracer.trace_window_points(&batch.us, &batch.vs, &mut batch.colors);
        claims.fill(&batch.colors);
        for (&at, &color) in batch.at.iter().zip(&batch.colors) {
            colors[at] = color;
        }
        for (line, gx, gy, at) in theirs {
            #[allow(clippy::cast_possible_truncation)]
            let color = line.get_or_trace(gx as usize, || trace_point(tracer, (lattice, axes), gx, gy));
            colors[at] = color;
        }
    }
}

/// The colours of a square's corners, whose lower-left point is `(a, b)` and side `side`, in
/// the order lower-left, lower-right, upper-left, upper-right (2D: the first two).
#[inline]
fn corners_of<const N: usize>(scratch: &Scratch, (a, b): (u32, u32), side: u32) -> [Rgb; N] {
    std::array::from_fn(|k| scratch.colors[scratch.index(a + CORNERS[k].0 * side, b + CORNERS[k].1 * side)])
}

/// The squares of level `level + 1`, children of those that split at `level`, that split in
/// turn (§8.2's rule on their corners, given in the recursion's order), in the order visited.
fn decide<const N: usize>(scratch: &mut Scratch, (threshold, max_level): (f64, u32), level: u32) {
    let half = scratch.scale >> (level + 1);
    let mut children = std::mem::take(&mut scratch.split[level as usize + 1]);
    for &(x, y) in &scratch.split[level as usize] {
        for &(cx, cy) in &CORNERS[..N] {
            let child = (x + cx * half, y + cy * half);
            if splits(Rgb::spread(&corners_of::<N>(scratch, child, half)), level + 1, threshold, max_level) {
                children.push(child);
            }
        }
    }
    scratch.split[level as usize + 1] = children;
}

/// The colours of the chunk's split squares, deepest level first: a split square's is
/// `corner_mean` of its children's, visited lower-left, lower-right, upper-left, upper-right, a
/// child's the colour of its own split or, for a leaf, `corner_mean` of its corners. The sums
/// and the order of `subdivide`'s recursion: a split child is the next of the level below, whose
/// squares were decided in this order.
fn sum<const N: usize>(scratch: &mut Scratch, max_level: u32) {
    for level in (0..max_level as usize).rev() {
        let half = scratch.scale >> (level + 1);
        let mut out = std::mem::take(&mut scratch.sums[level]);
        out.clear();
        let (below, below_sums) = match scratch.split.get(level + 1) {
            Some(split) if level + 1 < max_level as usize => (&split[..], &scratch.sums[level + 1][..]),
            _ => (&[][..], &[][..]),
        };
        let mut next = 0;
        for &(x, y) in &scratch.split[level] {
            let children: [Rgb; N] = std::array::from_fn(|c| {
                let child = (x + CORNERS[c].0 * half, y + CORNERS[c].1 * half);
                if below.get(next) == Some(&child) {
                    next += 1;
                    below_sums[next - 1]
                } else {
                    corner_mean(&corners_of::<N>(scratch, child, half))
                }
            });
            out.push(corner_mean(&children));
        }
        scratch.sums[level] = out;
    }
}

/// Adds to each split pixel's `used` (its `N` corners already) the distinct points its split
/// squares gave: a square's 5 new points (2D: 1), less its left and bottom midpoints where the
/// square beside it in the same pixel split too (its centre traced), which gave them first.
fn count<const N: usize>(scratch: &Scratch, max_level: u32, used: &mut [u32]) {
    let s = scratch.scale;
    let (_, new) = const { new_points::<N>() };
    for level in 0..max_level as usize {
        let half = s >> (level + 1);
        for &(x, y) in &scratch.split[level] {
            let beside = |(a, b): (u32, u32)| N == 4 && scratch.known(a, b);
            let left = x % s != 0 && beside((x - half, y + half));
            let below = y % s != 0 && beside((x + half, y - half));
            #[allow(clippy::cast_possible_truncation)] // at most 5
            let fresh = new as u32 - u32::from(left) - u32::from(below);
            used[(x / s) as usize] += fresh;
        }
    }
}

/// The breadth-first render against the depth-first recursion: every pixel's colour bit for bit,
/// its count of distinct samples, and the rays and tests, on one thread and two.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{Accel, AccelKind, AccelOptions};
    use crate::record::stats::Stats;
    use crate::render::{render, RenderConfig};
    use crate::sample::adaptive::{subdivide, NoSquares, SampleSource};
    use crate::sample::Sampling;
    use crate::scene::load::load_str;
    use crate::scene::{fixtures, AnyScene, Scene};
    use proptest::prelude::*;
    use std::collections::{HashMap, HashSet};

    /// Pixel `(i, j)`'s samples for the recursion: each lattice point of the image traced once,
    /// one ray at a time, whichever pixel reads it first; the pixel's distinct points in `read`.
    struct Once<'r, 's, V: Dim> {
        tracer: &'r mut Tracer<'s, V, NoRecorder>,
        traced: &'r mut HashMap<(u64, u64), Rgb>,
        read: HashSet<(u32, u32)>,
        lattice: Lattice,
        pixel: (usize, usize),
    }

    impl<V: Dim> SampleSource for Once<'_, '_, V> {
        fn color(&mut self, a: u32, b: u32) -> Rgb {
            self.read.insert((a, b));
            let (x, y) = self.lattice.global(self.pixel.0, self.pixel.1, a, b);
            let (tracer, lattice) = (&mut *self.tracer, self.lattice);
            *self.traced.entry((x, y)).or_insert_with(|| {
                let (u, v) = lattice.uv(&tracer.scene.camera, x, y);
                tracer.trace_primary(&tracer.scene.camera.primary_ray(u, v), &[])
            })
        }
    }

    /// The recursion's image (each colour's bits), per-pixel counts and statistics.
    type Rendered = (Vec<[u64; 3]>, Vec<u32>, Stats);

    /// Every pixel of `scene` by [`subdivide`] with the rule `(threshold, K)`, rows from the bottom.
    fn depth_first<V: Dim>(
        scene: &Scene<V>,
        accel: &Accel<V>,
        (threshold, max_level): (f64, u32),
    ) -> Rendered {
        let lattice = Lattice::new(&scene.camera, max_level);
        let mut tracer = Tracer::new(scene, accel, NoRecorder);
        tracer.max_depth = scene.max_depth;
        let mut traced = HashMap::new();
        let (mut colors, mut counts) = (Vec::new(), Vec::new());
        for j in 0..lattice.ny {
            for i in 0..lattice.nx {
                let mut source = Once {
                    tracer: &mut tracer,
                    traced: &mut traced,
                    read: HashSet::new(),
                    lattice,
                    pixel: (i, j),
                };
                let color = subdivide(&mut source, &mut NoSquares, lattice.dims(), threshold, max_level);
                colors.push(color.0.map(f64::to_bits));
                counts.push(u32::try_from(source.read.len()).expect("at most (2^8 + 1)² points"));
            }
        }
        (colors, counts, tracer.stats)
    }

    /// The render's pixels (each colour's bits), per-pixel counts and statistics on `threads`.
    fn breadth_first<V: Dim>(
        scene: &Scene<V>,
        accel: &Accel<V>,
        rule: (f64, u32),
        threads: usize,
    ) -> Rendered {
        let sampling = Sampling::adaptive(rule.0, rule.1).expect("a valid rule");
        let config =
            RenderConfig { sampling, rays_per_pixel: true, ..RenderConfig::centers(scene.max_depth) };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a pool");
        let out = pool.install(|| render(scene, accel, &config));
        let computed = scene.camera.nx * scene.camera.ny;
        let colors = out.image.pixels[..computed].iter().map(|c| c.0.map(f64::to_bits)).collect();
        (colors, out.rays_per_pixel.expect("asked for"), out.stats)
    }

    /// The render agrees with the recursion on `scene` for each rule, on one thread and on two;
    /// returns the most samples a pixel read.
    fn agree<V: Dim>(scene: &Scene<V>, rules: &[(f64, u32)]) -> u32 {
        let mut most = 0;
        let accel = Accel::build_for_render(scene, &AccelOptions::of(AccelKind::Bvh));
        for &rule in rules {
            let (colors, counts, stats) = depth_first(scene, &accel, rule);
            assert!(stats.rays.primary > 0);
            most = most.max(counts.iter().copied().max().unwrap_or(0));
            if rule.0 == 0.0 {
                // Every square splits down to level K: all (2^K + 1)^dims points of every pixel.
                let all = ((1 << rule.1) + 1u32).pow(u32::try_from(V::DIM - 1).expect("1 or 2"));
                assert!(counts.iter().all(|&n| n == all), "threshold 0 at K = {}", rule.1);
            }
            for threads in [1, 2] {
                let (bfs_colors, bfs_counts, bfs_stats) = breadth_first(scene, &accel, rule, threads);
                let differ = bfs_colors.iter().zip(&colors).position(|(a, b)| a != b);
                assert_eq!(differ, None, "the first pixel that differs, rule {rule:?}, {threads} threads");
                assert_eq!(bfs_counts, counts, "samples per pixel, rule {rule:?}, {threads} threads");
                assert_eq!(bfs_stats, stats, "rule {rule:?}, {threads} threads");
            }
        }
        most
    }

    /// Thresholds 0 (every square splits), the lecture's 0.3 and +∞ (none does), K = 0 … 3.
    fn rules() -> Vec<(f64, u32)> {
        [0.0, 0.3, f64::INFINITY].into_iter().flat_map(|t| (0..=3).map(move |k| (t, k))).collect()
    }

    fn space(text: &str, (nx, ny): (usize, usize)) -> Scene<glam::DVec3> {
        let Ok(AnyScene::Space(mut scene)) = load_str(text) else { panic!("a 3D scene") };
        (scene.camera.nx, scene.camera.ny) = (nx, ny);
        scene
    }

    #[test]
    fn the_lecture_scene_is_the_recursion_s() {
        let scene = space(include_str!("../../scenes/whitted.json"), (40, 30));
        assert_eq!(agree(&scene, &rules()), 9 * 9, "threshold 0 at K = 3");
    }

    #[test]
    fn a_2d_line_is_the_recursion_s() {
        let Ok(AnyScene::Flat(scene)) = load_str(&fixtures::line(61)) else { panic!("a 2D scene") };
        assert_eq!(agree(&scene, &rules()), 9, "threshold 0 at K = 3");
    }

    #[test]
    fn deep_levels_take_a_row_in_chunks_that_share_their_edges() {
        let scene = space(include_str!("../../scenes/whitted.json"), (9, 5));
        // K = 7: (2^7 + 1)² points a pixel, 3 pixels a chunk; K = 8: one pixel a chunk.
        assert_eq!(Scratch::new(Lattice::new(&scene.camera, 7)).pixels, 3);
        assert_eq!(Scratch::new(Lattice::new(&scene.camera, 8)).pixels, 1);
        // Some pixels split below level 2 (more than its 25 points).
        assert!(agree(&scene, &[(0.3, 7), (0.3, 8)]) > 25);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(16))]
        /// Random spheres over a random checkered plane, random lights and eye, a random rule.
        #[test]
        fn random_scenes_are_the_recursion_s(
            spheres in fixtures::random_spheres(),
            lights in fixtures::random_lights(),
            eye in fixtures::random_eye(),
            rule in (0.0..0.6f64, 0..=3u32),
        ) {
            let (objects, lights) = (fixtures::objects((0.0, 1.0, 0.0), &spheres), fixtures::lights(&lights));
            let text = format!(
                r#"{{ "camera": {{ "eye": [{}, {}, {}], "center": [0, 0, 0], "up": [0, 1, 0],
                    "window": {{ "l": -2, "r": 2, "b": -1.5, "t": 1.5 }}, "resolution": [21, 13] }},
                    "max_depth": 3, "lights": [ {} ], "objects": [ {} ] }}"#,
                eye.0, eye.1, eye.2, lights, objects
            );
            agree(&space(&text, (21, 13)), &[rule]);
        }
    }
}
