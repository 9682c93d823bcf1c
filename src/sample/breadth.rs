//! Whitted's adaptive subdivision (algorithm.md §8.2) of a render's pixel row, breadth first:
//! the squares of the row that split at level L give their new points, all traced together in
//! packets ([`Tracer::trace_window_points`]), and only then are the squares of level L + 1
//! decided, each once. A pixel's colour is then summed by [`subdivide`]'s recursion over the
//! stored colours, so its arithmetic is the recursion's and its bytes those of a depth-first
//! render; `trace` and anything recorded keep the depth-first recursion, which traces a sample
//! when a square first reads it.
//!
//! A row is taken in chunks of pixels ([`Scratch`]: all of a 640-pixel row at K = 2), each a
//! dense lattice of the colours of its points, stamped so that nothing is cleared per chunk. The
//! points of the edge between two pixels are one column of it, and a chunk's last column is
//! carried to the next chunk's first. A point on the pixel row's bottom or top edge is shared
//! with the pixel row below or above through the edge rows' [`Line`]s: read if traced, else
//! claimed and traced with the level's batch, or, if another thread is tracing it, awaited once
//! this thread's own claims are filled. So every sample is traced once, as in the recursion.

use super::adaptive::{new_points, splits, subdivide, unsplit, NoSquares, SampleSource, CORNERS};
use super::corners::Lattice;
use super::shared::{trace_point, Claim, Claims, Edges, Line};
use crate::record::NoRecorder;
use crate::scene::material::Rgb;
use crate::shape::Dim;
use crate::trace::Tracer;

/// The most lattice points a chunk holds: 2 MiB of [`Memo`]s a thread, whatever K.
const CHUNK_POINTS: usize = 1 << 16;

/// One point of a chunk's lattice: its colour, valid when `stamp` is the current chunk's.
#[derive(Clone, Copy, Debug, Default)]
struct Memo {
    stamp: u32,
    color: Rgb,
}

/// One thread's memory for the pixel rows of a lattice: a chunk's lattice of colours and, per
/// level below K, the squares of the chunk that split at it; the level's batch of points to
/// trace; the per-pixel marks that count distinct samples when asked.
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
    /// The chunk's points, row by row.
    memo: Vec<Memo>,
    /// The current chunk's stamp.
    current: u32,
    /// Per level `L < K`, the lower-left points of the chunk's squares that split at `L`.
    split: Vec<Vec<(u32, u32)>>,
    /// The level's points to trace: their window coordinates, their places in `memo`, and their
    /// colours once traced.
    batch: Batch,
    /// Per local point of the pixel being summed, the stamp of the pixel that last read it.
    seen: Vec<u32>,
    /// The stamp of the pixel being summed.
    seen_current: u32,
}

/// A level's points to trace, in the order gathered.
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
        let side = lattice.scale as usize + 1;
        let rows = if lattice.dims() == 1 { 1 } else { side };
        let pixels = (CHUNK_POINTS / (side * rows)).clamp(1, lattice.nx.max(1));
        let width = pixels * lattice.scale as usize + 1;
        Self {
            scale: lattice.scale,
            pixels,
            width,
            rows,
            memo: vec![Memo::default(); width * rows],
            current: 0,
            split: vec![Vec::new(); lattice.max_level.max(1) as usize],
            batch: Batch::default(),
            seen: vec![0; side * rows],
            seen_current: 0,
        }
    }
    /// The bytes of one thread's [`Scratch`] for `lattice` (its lattice of colours, the most).
    #[must_use]
    pub fn bytes(lattice: Lattice) -> usize {
        let side = lattice.scale as usize + 1;
        let rows = if lattice.dims() == 1 { 1 } else { side };
        let pixels = (CHUNK_POINTS / (side * rows)).clamp(1, lattice.nx.max(1));
        (pixels * lattice.scale as usize + 1) * rows * std::mem::size_of::<Memo>()
    }
    /// Starts a new chunk: every point becomes stale, but for the last column of the previous
    /// chunk if `carry`, which becomes the first column (the edge the chunks share).
    fn next_chunk(&mut self, carry: bool) {
        if self.current == u32::MAX {
            // Renumbered, so that the current chunk's points stay valid: 1, and the others 0.
            for m in &mut self.memo {
                m.stamp = u32::from(m.stamp == self.current);
            }
            self.current = 1;
        }
        let previous = self.current;
        self.current += 1;
        if carry {
            for b in 0..self.rows {
                let last = self.memo[b * self.width + self.width - 1];
                if last.stamp == previous {
                    self.memo[b * self.width] = Memo { stamp: self.current, color: last.color };
                }
            }
        }
        for level in &mut self.split {
            level.clear();
        }
    }
    /// The index in `memo` of chunk point `(a, b)`.
    #[inline]
    fn index(&self, a: u32, b: u32) -> usize {
        b as usize * self.width + a as usize
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
        if lattice.dims() == 1 {
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
            if let Some(color) = unsplit(corners, threshold, max_level) {
                *pixel = color;
                if let Some(used) = used.as_deref_mut() {
                    used[k] = n;
                }
                continue;
            }
            // k < pixels ≤ CHUNK_POINTS: a lattice column of the chunk.
            #[allow(clippy::cast_possible_truncation)]
            let a = k as u32 * s;
            for (c, (dx, dy)) in CORNERS[..N].iter().enumerate() {
                let at = scratch.index(a + dx * s, dy * s);
                scratch.memo[at] = Memo { stamp: scratch.current, color: *corners[c] };
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
        let split = std::mem::take(&mut scratch.split[0]);
        for &(a, _) in &split {
            let k = (a / s) as usize;
            let mut stored = Stored::new(scratch, a, used.is_some());
            pixels[k] = subdivide(&mut stored, &mut NoSquares, self.lattice.dims(), threshold, max_level);
            if let (Some(used), Some(count)) = (used.as_deref_mut(), stored.count) {
                used[k] = count;
            }
        }
        scratch.split[0] = split;
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
        let Scratch { memo, current, split, batch, width, .. } = scratch;
        let (current, width) = (*current, *width);
        batch.us.clear();
        batch.vs.clear();
        batch.at.clear();
        let mut theirs: Vec<(&Line, u64, u64, usize)> = Vec::new();
        for &(x, y) in &split[level as usize] {
            for &(dx, dy) in &offsets[..count] {
                let (a, b) = (x + dx * half, y + dy * half);
                let at = b as usize * width + a as usize;
                if memo[at].stamp == current {
                    continue;
                }
                memo[at].stamp = current;
                let (gx, gy) = lattice.global(self.first, self.j, a, b);
                if let Some(line) = self.edges.line(lattice, b) {
                    // gx ≤ Nx·2^K: the index of a point of the line.
                    #[allow(clippy::cast_possible_truncation)]
                    match claims.claim(line, gx as usize, batch.us.len()) {
                        Claim::Traced(color) => {
                            memo[at].color = color;
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
            memo[at].color = color;
        }
        for (line, gx, gy, at) in theirs {
            #[allow(clippy::cast_possible_truncation)]
            let color = line.get_or_trace(gx as usize, || trace_point(tracer, (lattice, axes), gx, gy));
            memo[at].color = color;
        }
    }
}

/// The squares of level `level + 1`, children of those that split at `level`, that split in
/// turn (§8.2's rule on their corners, given in the recursion's order), in the order visited.
fn decide<const N: usize>(scratch: &mut Scratch, (threshold, max_level): (f64, u32), level: u32) {
    let half = scratch.scale >> (level + 1);
    let Scratch { memo, split, width, .. } = scratch;
    let (done, next) = split.split_at_mut(level as usize + 1);
    let (parents, children) = (&done[level as usize], &mut next[0]);
    for &(x, y) in parents {
        for &(cx, cy) in &CORNERS[..N] {
            let (a, b) = (x + cx * half, y + cy * half);
            let corners: [&Rgb; N] = std::array::from_fn(|k| {
                let (dx, dy) = CORNERS[k];
                &memo[(b + dy * half) as usize * *width + (a + dx * half) as usize].color
            });
            if splits(Rgb::spread(corners), level + 1, threshold, max_level) {
                children.push((a, b));
            }
        }
    }
}

/// The stored samples of one split pixel, whose lower-left point is chunk column `a`, read by
/// [`subdivide`] to sum it; `count` the distinct samples read, if asked.
struct Stored<'s> {
    scratch: &'s mut Scratch,
    a: u32,
    count: Option<u32>,
}

impl SampleSource for Stored<'_> {
    #[inline]
    fn color(&mut self, a: u32, b: u32) -> Rgb {
        let scratch = &mut *self.scratch;
        let memo = scratch.memo[scratch.index(self.a + a, b)];
        debug_assert_eq!(memo.stamp, scratch.current, "a point the levels traced");
        if let Some(count) = &mut self.count {
            let side = scratch.scale as usize + 1;
            let seen = &mut scratch.seen[b as usize * side + a as usize];
            if *seen != scratch.seen_current {
                *seen = scratch.seen_current;
                *count += 1;
            }
        }
        memo.color
    }
}

impl Stored<'_> {
    /// A source for the pixel at chunk column `a`, counting its distinct samples if `count`.
    fn new(scratch: &mut Scratch, a: u32, count: bool) -> Stored<'_> {
        if count {
            if scratch.seen_current == u32::MAX {
                scratch.seen.fill(0);
                scratch.seen_current = 0;
            }
            scratch.seen_current += 1;
        }
        Stored { scratch, a, count: count.then_some(0) }
    }
}
