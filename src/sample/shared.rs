//! Sharing samples across a whole image (algorithm.md §8: "every sample is traced once and shared
//! by all squares and pixels that touch it", keyed by integer lattice coordinates, never floats).
//!
//! A pixel row is rendered left to right by one thread. Its samples are of three kinds:
//! - on the lattice row `y = j·2^K` (its bottom edge) or `(j + 1)·2^K` (its top edge): shared with
//!   the pixel row below or above, which another thread may render at the same time. Each such
//!   lattice row is a [`Line`] of `OnceLock`s: the first thread to need a point traces it, any
//!   other waits for that colour.
//! - on the vertical edge `x = i·2^K` between two pixels of the row: carried from pixel `i − 1` to
//!   pixel `i` (the `left` column of [`Scratch`]).
//! - inside the pixel: private.
//!
//! Each pixel memoises what it read in [`Scratch`] (stamped, so nothing is cleared per pixel), and
//! the number of distinct points it read is its rays-per-pixel count. Memory: the lines of one band
//! of rows (see `render`) and, per thread, one pixel's `(2^K + 1)²` memo.

use super::adaptive::{subdivide, NoSquares, SampleSource};
use super::corners::Lattice;
use crate::record::NoRecorder;
use crate::scene::material::Rgb;
use crate::shape::Dim;
use crate::trace::Tracer;
use std::sync::OnceLock;

/// One lattice row `y` of the image, `Nx·2^K + 1` points, each traced at most once by whichever
/// thread asks first.
#[derive(Debug)]
pub struct Line(Vec<OnceLock<Rgb>>);

impl Line {
    /// An empty line of `len` points.
    #[must_use]
    pub fn new(len: usize) -> Self {
        Self((0..len).map(|_| OnceLock::new()).collect())
    }
    /// Forgets every colour (the line is reused for another lattice row).
    pub fn clear(&mut self) {
        for cell in &mut self.0 {
            cell.take();
        }
    }
    /// Points traced so far.
    #[must_use]
    pub fn traced(&self) -> usize {
        self.0.iter().filter(|c| c.get().is_some()).count()
    }
}

/// One thread's per-pixel memory: a memo of the pixel's `(2^K + 1)^dims` local points, valid where
/// its stamp equals the current pixel's, and the left edge carried from the previous pixel.
#[derive(Debug)]
pub struct Scratch {
    side: usize,
    memo: Vec<Rgb>,
    stamp: Vec<u32>,
    current: u32,
    left: Vec<Option<Rgb>>,
}

impl Scratch {
    /// The memory for pixels of `lattice`.
    #[must_use]
    pub fn new(lattice: Lattice) -> Self {
        let side = lattice.scale as usize + 1;
        let points = if lattice.dims() == 1 { side } else { side * side };
        Self {
            side,
            memo: vec![Rgb::BLACK; points],
            stamp: vec![0; points],
            current: 0,
            left: vec![None; side],
        }
    }
    fn index(&self, a: u32, b: u32) -> usize {
        b as usize * self.side + a as usize
    }
    /// Starts a new pixel: every memo entry becomes stale.
    fn next_pixel(&mut self) {
        if self.current == u32::MAX {
            self.stamp.fill(0);
            self.current = 0;
        }
        self.current += 1;
    }
    /// After pixel `i`: its right edge `a = 2^K` becomes pixel `i + 1`'s left edge.
    fn carry_right_edge(&mut self, dims: usize) {
        let rows = if dims == 1 { 1 } else { self.side };
        for b in 0..rows {
            // Point (2^K, b) of the memo.
            let k = b * self.side + self.side - 1;
            self.left[b] = (self.stamp[k] == self.current).then(|| self.memo[k]);
        }
    }
}

/// The lattice rows below and above one pixel row (none on a 2D scene's line).
#[derive(Clone, Copy, Debug)]
pub struct Edges<'l> {
    /// `y = j·2^K`.
    pub bottom: &'l Line,
    /// `y = (j + 1)·2^K`.
    pub top: &'l Line,
}

/// Renders pixel row `j` with the subdivision rule `(threshold, K)`: writes each pixel's colour to
/// `pixels` and, if given, the number of distinct samples it read to `used`.
#[allow(clippy::too_many_arguments)]
pub fn render_row<V: Dim>(
    tracer: &mut Tracer<'_, V, NoRecorder>,
    lattice: Lattice,
    (threshold, max_level): (f64, u32),
    j: usize,
    edges: Option<Edges<'_>>,
    scratch: &mut Scratch,
    pixels: &mut [Rgb],
    mut used: Option<&mut [u32]>,
) {
    let dims = lattice.dims();
    scratch.left.fill(None);
    for (i, pixel) in pixels.iter_mut().enumerate() {
        scratch.next_pixel();
        let mut source = RowSource { tracer, lattice, i, j, edges, scratch, used: 0 };
        *pixel = subdivide(&mut source, &mut NoSquares, dims, threshold, max_level);
        let count = source.used;
        if let Some(used) = used.as_deref_mut() {
            used[i] = count;
        }
        scratch.carry_right_edge(dims);
    }
}

/// The samples of pixel `(i, j)` during a render.
struct RowSource<'r, 't, 's, V: Dim> {
    tracer: &'r mut Tracer<'s, V, NoRecorder>,
    lattice: Lattice,
    i: usize,
    j: usize,
    edges: Option<Edges<'t>>,
    scratch: &'r mut Scratch,
    used: u32,
}

impl<V: Dim> RowSource<'_, '_, '_, V> {
    /// Traces the primary ray through global lattice point `(x, y)`.
    fn trace(tracer: &mut Tracer<'_, V, NoRecorder>, lattice: Lattice, x: u64, y: u64) -> Rgb {
        let camera = &tracer.scene.camera;
        let (u, v) = lattice.uv(camera, x, y);
        let ray = camera.primary_ray(u, v);
        tracer.trace_primary(&ray, &[u, v][..lattice.dims()])
    }
}

impl<V: Dim> SampleSource for RowSource<'_, '_, '_, V> {
    #[inline]
    fn color(&mut self, a: u32, b: u32) -> Rgb {
        let k = self.scratch.index(a, b);
        if self.scratch.stamp[k] == self.scratch.current {
            return self.scratch.memo[k];
        }
        let (x, y) = self.lattice.global(self.i, self.j, a, b);
        let (tracer, lattice) = (&mut *self.tracer, self.lattice);
        let line = match self.edges {
            Some(e) if b == 0 => Some(e.bottom),
            Some(e) if b == lattice.scale => Some(e.top),
            _ => None,
        };
        let color = match (line, self.scratch.left[b as usize]) {
            // A lattice row shared with the pixel row below or above.
            (Some(line), _) => {
                // x ≤ Nx·2^K, the index of a point that exists.
                #[allow(clippy::cast_possible_truncation)]
                let cell = &line.0[x as usize];
                *cell.get_or_init(|| Self::trace(tracer, lattice, x, y))
            }
            // The left edge, already read by the pixel to the left.
            (None, Some(c)) if a == 0 => c,
            _ => Self::trace(tracer, lattice, x, y),
        };
        self.scratch.memo[k] = color;
        self.scratch.stamp[k] = self.scratch.current;
        self.used += 1;
        color
    }
}
