//! Sharing samples across a whole image (algorithm.md §8: "every sample is traced once and shared
//! by all squares and pixels that touch it", keyed by integer lattice coordinates, never floats).
//!
//! One thread renders a pixel row left to right ([`render_row`]). The row's pixel corners are
//! traced with the lattice row they lie on ([`EdgeRow`]). The other points of its bottom and top
//! lattice rows are shared with the pixel row below or above, which another thread may render at
//! the same time: the first thread to need a point traces it, any other waits ([`Line`]). The
//! points of the edge between two pixels are carried to the next pixel, and those inside a pixel
//! are private ([`Scratch`]). [`EdgeRows`] makes and drops the edge rows, so memory holds only
//! those in use (see `render`).

use super::adaptive::{subdivide, unsplit, NoSquares, SampleSource};
use super::corners::{Axes, Lattice};
use crate::geom::ray::Ray;
use crate::record::NoRecorder;
use crate::scene::camera::Camera;
use crate::scene::material::Rgb;
use crate::shape::Dim;
use crate::trace::Tracer;
use std::sync::atomic::{AtomicU64, AtomicU8, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// The points of one lattice row, `Nx·2^K + 1` of them, each traced at most once by whichever
/// thread asks first (the corners are not kept here: see [`EdgeRow`]).
#[derive(Debug)]
pub struct Line {
    points: Vec<Point>,
}

impl Line {
    /// An empty line of `len` points.
    #[must_use]
    pub fn new(len: usize) -> Self {
        Self { points: (0..len).map(|_| Point::default()).collect() }
    }
    /// The colour of point `x`, traced by `trace` if no thread has traced it yet.
    fn get_or_trace(&self, x: usize, trace: impl FnOnce() -> Rgb) -> Rgb {
        self.points[x].get_or_trace(trace)
    }
}

/// One shared point of a [`Line`]: empty, being traced by one thread, or holding its colour.
/// What a `OnceLock<Rgb>` would do, with a one-load read and no destructor (a line of them is
/// freed at once). Two threads want the same point only where two jobs of pixel rows meet, both
/// at that point at once: the second yields its CPU until the first has the colour.
#[derive(Debug, Default)]
struct Point {
    state: AtomicU8,
    /// The colour's channels, as `f64::to_bits`.
    bits: [AtomicU64; 3],
}

/// [`Point::state`]s.
const EMPTY: u8 = 0;
const TRACING: u8 = 1;
const READY: u8 = 2;

/// Puts a point back to [`EMPTY`] if its trace unwinds, so that a waiting thread traces it itself
/// (and meets the same panic) instead of waiting for ever.
struct Unwinding<'p>(&'p AtomicU8);

impl Drop for Unwinding<'_> {
    fn drop(&mut self) {
        self.0.store(EMPTY, Ordering::Release);
    }
}

impl Point {
    /// The colour, traced now by `trace` if no thread has traced it yet, else read (after the
    /// tracing thread's `Release`, so its channels are all there).
    #[inline]
    fn get_or_trace(&self, trace: impl FnOnce() -> Rgb) -> Rgb {
        loop {
            match self.state.load(Ordering::Acquire) {
                READY => return Rgb(self.bits.each_ref().map(|b| f64::from_bits(b.load(Ordering::Relaxed)))),
                EMPTY
                    if self
                        .state
                        .compare_exchange(EMPTY, TRACING, Ordering::Acquire, Ordering::Acquire)
                        .is_ok() =>
                {
                    let unwinding = Unwinding(&self.state);
                    let color = trace();
                    for (bits, channel) in self.bits.iter().zip(color.0) {
                        bits.store(channel.to_bits(), Ordering::Relaxed);
                    }
                    std::mem::forget(unwinding);
                    self.state.store(READY, Ordering::Release);
                    return color;
                }
                _ => std::thread::yield_now(),
            }
        }
    }
}

/// A lattice row `y = j·2^K` on a pixel-row boundary: its `Nx + 1` pixel corners, traced when
/// the row is made, and for K > 0 its finer points, traced on demand. Every corner is needed, so
/// all are traced at once and read as plain colours.
#[derive(Debug)]
pub struct EdgeRow {
    /// The colours of the corners `(i·2^K, y)`, `i = 0 … Nx`.
    corners: Vec<Rgb>,
    /// The finer points, shared by the two pixel rows the edge row bounds (None when K = 0, and
    /// on a 2D scene's line, whose finer points are each inside one pixel).
    finer: Option<Line>,
}

impl EdgeRow {
    /// Pixel-row boundary `j` with its corners traced (§8.1: `Nx + 1` rays); `shared` if its finer
    /// points are shared by two pixel rows.
    pub fn trace<V: Dim>(
        tracer: &mut Tracer<'_, V, NoRecorder>,
        (lattice, axes): (Lattice, &Axes),
        j: usize,
        shared: bool,
    ) -> Self {
        let s = u64::from(lattice.scale);
        // The row's corners are a row of the window: `primary_at`'s rays, made as they are traced.
        let us: Vec<f64> = (0..=lattice.nx).map(|i| axes.uv(i as u64 * s, 0).0).collect();
        let v = axes.uv(0, j as u64 * s).1;
        let mut corners = vec![Rgb::BLACK; us.len()];
        tracer.trace_window_row(&us, v, &mut Vec::new(), &mut corners);
        let finer = (shared && lattice.max_level > 0).then(|| Line::new(lattice.row_len()));
        Self { corners, finer }
    }
    /// A 2D scene's line (`j = 0`) with only the pixel ends `columns` traced, for a band of its
    /// pixels: the first end by `quiet` when `quiet_first` (the band to its left counted it), the
    /// others by `tracer`; the ends outside `columns` are black and never read by the band.
    pub fn trace_ends<'s, V: Dim>(
        (tracer, quiet): (&mut Tracer<'s, V, NoRecorder>, &mut Tracer<'s, V, NoRecorder>),
        (lattice, axes): (Lattice, &Axes),
        columns: std::ops::RangeInclusive<usize>,
        quiet_first: bool,
    ) -> Self {
        let s = u64::from(lattice.scale);
        let first = *columns.start();
        let mut corners = vec![Rgb::default(); lattice.nx + 1];
        for i in columns {
            let by = if quiet_first && i == first { &mut *quiet } else { &mut *tracer };
            corners[i] = trace_point(by, (lattice, axes), i as u64 * s, 0);
        }
        Self { corners, finer: None }
    }
    /// The bytes of one edge row of `lattice` (corners and finer points).
    #[must_use]
    pub fn bytes(lattice: Lattice) -> usize {
        let corners = (lattice.nx + 1) * std::mem::size_of::<Rgb>();
        let finer = if lattice.max_level > 0 { lattice.row_len() * std::mem::size_of::<Point>() } else { 0 };
        corners + finer
    }
}

/// Every edge row of an image, `j = 0 … Ny`, each made (its corners traced) by the first pixel row
/// that asks for it, whichever thread runs that row, and dropped when the last of the pixel rows
/// it bounds (one at the image's edges, else two) is done with it. So every sample is traced
/// once, and memory holds only the edge rows of the pixel rows in progress and those that wait
/// for their second pixel row.
#[derive(Debug)]
pub struct EdgeRows {
    lattice: Lattice,
    axes: Axes,
    rows: Vec<SharedRow>,
}

/// One edge row of [`EdgeRows`]: absent until asked for, and again once its readers are done.
#[derive(Debug)]
struct SharedRow {
    row: Mutex<Option<Arc<EdgeRow>>>,
    /// The pixel rows that have not yet released it.
    readers: AtomicU8,
}

impl EdgeRows {
    /// The edge rows of a 3D image on `lattice` of `camera`'s window, none made yet.
    #[must_use]
    pub fn new<V: Dim>(lattice: Lattice, camera: &Camera<V>) -> Self {
        let ny = lattice.ny;
        let rows = (0..=ny)
            .map(|j| SharedRow {
                row: Mutex::new(None),
                readers: AtomicU8::new(if j == 0 || j == ny { 1 } else { 2 }),
            })
            .collect();
        Self { lattice, axes: Axes::new(lattice, camera), rows }
    }
    /// The window coordinates of the lattice's columns and rows.
    #[must_use]
    pub fn axes(&self) -> &Axes {
        &self.axes
    }
    /// Edge row `j`, made now by `tracer` if no pixel row has asked for it before. A pixel row
    /// that asks while another thread is making it waits for it.
    pub fn acquire<V: Dim>(&self, tracer: &mut Tracer<'_, V, NoRecorder>, j: usize) -> Arc<EdgeRow> {
        let mut slot = self.rows[j].row.lock().unwrap_or_else(PoisonError::into_inner);
        Arc::clone(
            slot.get_or_insert_with(|| Arc::new(EdgeRow::trace(tracer, (self.lattice, &self.axes), j, true))),
        )
    }
    /// A pixel row is done with edge row `j`: the last one drops it.
    pub fn release(&self, j: usize) {
        if self.rows[j].readers.fetch_sub(1, Ordering::AcqRel) == 1 {
            self.rows[j].row.lock().unwrap_or_else(PoisonError::into_inner).take();
        }
    }
}

/// Traces the primary ray through global lattice point `(x, y)`.
fn trace_point<V: Dim>(
    tracer: &mut Tracer<'_, V, NoRecorder>,
    (lattice, axes): (Lattice, &Axes),
    x: u64,
    y: u64,
) -> Rgb {
    let (ray, uv) = primary_at(&tracer.scene.camera, axes, x, y);
    tracer.trace_primary(&ray, &uv[..lattice.dims()])
}

/// The primary ray through global lattice point `(x, y)`, and its `(u, v)`.
#[inline]
fn primary_at<V: Dim>(camera: &Camera<V>, axes: &Axes, x: u64, y: u64) -> (Ray<V>, [f64; 2]) {
    let (u, v) = axes.uv(x, y);
    (camera.primary_ray(u, v), [u, v])
}

/// One memoised local point: valid when `stamp` is the current pixel's.
#[derive(Clone, Copy, Debug, Default)]
struct Memo {
    stamp: u32,
    color: Rgb,
}

/// One thread's per-pixel memory: a memo of the pixel's `(2^K + 1)^dims` local points (stamped, so
/// nothing is cleared per pixel), and the left edge carried from the previous pixel.
#[derive(Debug)]
pub struct Scratch {
    side: usize,
    memo: Vec<Memo>,
    current: u32,
    left: Vec<Option<Rgb>>,
    /// Whether `left` may hold a colour (else it is all `None`).
    left_any: bool,
}

impl Scratch {
    /// The memory for pixels of `lattice`.
    #[must_use]
    pub fn new(lattice: Lattice) -> Self {
        let side = lattice.scale as usize + 1;
        let points = if lattice.dims() == 1 { side } else { side * side };
        Self {
            side,
            memo: vec![Memo::default(); points],
            current: 0,
            left: vec![None; side],
            left_any: false,
        }
    }
    /// Starts a new pixel: every memo entry becomes stale.
    fn next_pixel(&mut self) {
        if self.current == u32::MAX {
            self.memo.fill(Memo::default());
            self.current = 0;
        }
        self.current += 1;
    }
    /// After pixel `i`: its right edge `a = 2^K`, `0 < b < 2^K`, becomes pixel `i + 1`'s left edge
    /// (the ends `b = 0`, `b = 2^K` are on the edge rows). `read_inside`: whether the pixel read
    /// any point besides its corners (if not, it read none of its right edge either).
    #[inline]
    fn carry_right_edge(&mut self, dims: usize, read_inside: bool) {
        if dims == 1 {
            // A 2D scene's pixel has no vertical edge but its right end, a corner.
            return;
        }
        if !read_inside {
            if self.left_any {
                self.left.fill(None);
                self.left_any = false;
            }
            return;
        }
        for b in 1..self.side - 1 {
            let m = self.memo[b * self.side + self.side - 1];
            self.left[b] = (m.stamp == self.current).then_some(m.color);
        }
        self.left_any = true;
    }
}

/// What a pixel row reads besides its own samples: the edge rows below and above it (a 2D
/// scene's line: its one row, twice), and where the lattice's points lie on the window.
#[derive(Clone, Copy, Debug)]
pub struct Edges<'l> {
    /// `y = j·2^K`.
    pub bottom: &'l EdgeRow,
    /// `y = (j + 1)·2^K`.
    pub top: &'l EdgeRow,
    /// The window coordinates of the lattice's columns and rows.
    pub axes: &'l Axes,
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
    (threshold, max_level): (f64, u32),
    (first, j): (usize, usize),
    edges: Edges<'_>,
    scratch: &mut Scratch,
    pixels: &mut [Rgb],
    mut used: Option<&mut [u32]>,
) {
    let dims = lattice.dims();
    scratch.left.fill(None);
    scratch.left_any = false;
    let (b, t) = (&edges.bottom.corners, &edges.top.corners);
    for (k, pixel) in pixels.iter_mut().enumerate() {
        let i = first + k;
        // Most pixels are not split (every pixel with K = 0): their corners decide them where
        // the edge rows hold them, unread by the subdivision (which would read the same corners
        // in the same order and split nothing).
        let quiet = if dims == 1 {
            unsplit([&b[i], &b[i + 1]], threshold, max_level)
        } else {
            unsplit([&b[i], &b[i + 1], &t[i], &t[i + 1]], threshold, max_level)
        };
        let count = if let Some(color) = quiet {
            *pixel = color;
            scratch.carry_right_edge(dims, false);
            1 << dims
        } else {
            scratch.next_pixel();
            let mut source = RowSource { tracer, lattice, i, j, edges, scratch, used: 0 };
            *pixel = subdivide(&mut source, &mut NoSquares, dims, threshold, max_level);
            let count = source.used;
            // A pixel split at level 0 has read points inside it.
            scratch.carry_right_edge(dims, true);
            count
        };
        if let Some(used) = used.as_deref_mut() {
            used[k] = count;
        }
    }
}

/// The samples of pixel `(i, j)` during a render.
struct RowSource<'r, 't, 's, V: Dim> {
    tracer: &'r mut Tracer<'s, V, NoRecorder>,
    lattice: Lattice,
    i: usize,
    j: usize,
    edges: Edges<'t>,
    scratch: &'r mut Scratch,
    used: u32,
}

impl<V: Dim> SampleSource for RowSource<'_, '_, '_, V> {
    /// The pixel corners, traced with their edge rows: `subdivide` reads them once per pixel
    /// (squares pass their corners down, and never ask [`SampleSource::color`] for them).
    #[inline(always)]
    fn corners<const N: usize>(&mut self, _side: u32) -> [Rgb; N] {
        let (i, edges) = (self.i, self.edges);
        #[allow(clippy::cast_possible_truncation)] // N is 2 or 4
        let n = N as u32;
        self.used += n;
        // Corner k is (k & 1, k >> 1) in pixel units: lower-left, lower-right, upper-left, …
        std::array::from_fn(|k| {
            let row = if k < 2 { edges.bottom } else { edges.top };
            row.corners[i + (k & 1)]
        })
    }
    #[inline]
    fn color(&mut self, a: u32, b: u32) -> Rgb {
        let lattice = self.lattice;
        let s = lattice.scale;
        debug_assert!(
            !((a == 0 || a == s) && (b == 0 || (b == s && lattice.dims() == 2))),
            "a pixel corner is read through `corners`"
        );
        let side = self.scratch.side;
        let k = b as usize * side + a as usize;
        let memo = self.scratch.memo[k];
        if memo.stamp == self.scratch.current {
            return memo.color;
        }
        let row = if b == 0 {
            Some(self.edges.bottom)
        } else if b == s && lattice.dims() == 2 {
            Some(self.edges.top)
        } else {
            None
        };
        let color = match row {
            // A finer point of an edge row shared with the pixel row below or above.
            Some(EdgeRow { finer: Some(line), .. }) => {
                let (x, y) = lattice.global(self.i, self.j, a, b);
                // x ≤ Nx·2^K: the index of a point of the line.
                #[allow(clippy::cast_possible_truncation)]
                let index = x as usize;
                let (tracer, axes) = (&mut *self.tracer, self.edges.axes);
                line.get_or_trace(index, || trace_point(tracer, (lattice, axes), x, y))
            }
            // The left edge, already read by the pixel to the left.
            None if a == 0 && self.scratch.left[b as usize].is_some() => {
                self.scratch.left[b as usize].unwrap_or_default()
            }
            // Inside the pixel (or an edge point no neighbour read).
            _ => {
                let (x, y) = lattice.global(self.i, self.j, a, b);
                trace_point(self.tracer, (lattice, self.edges.axes), x, y)
            }
        };
        self.scratch.memo[k] = Memo { stamp: self.scratch.current, color };
        self.used += 1;
        color
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{Accel, AccelKind};
    use crate::scene::load::load_str;
    use crate::scene::AnyScene;

    #[test]
    fn a_shared_point_is_traced_once_whichever_threads_ask() {
        use std::sync::atomic::AtomicU32;
        let line = Line::new(1000);
        let traced: Vec<AtomicU32> = (0..1000).map(|_| AtomicU32::new(0)).collect();
        let read = |x: usize| {
            line.get_or_trace(x, || {
                traced[x].fetch_add(1, Ordering::Relaxed);
                std::thread::yield_now();
                Rgb([x as f64, -0.0, f64::MIN_POSITIVE])
            })
        };
        // Two threads read every point, one from each end, so they meet in the middle.
        let (ups, downs) = std::thread::scope(|s| {
            let up = s.spawn(|| (0..1000).map(read).collect::<Vec<_>>());
            let down = s.spawn(|| (0..1000).rev().map(read).collect::<Vec<_>>());
            (up.join().unwrap(), down.join().unwrap())
        });
        assert!(traced.iter().all(|n| n.load(Ordering::Relaxed) == 1));
        for (x, c) in ups.iter().enumerate() {
            assert_eq!(c.0.map(f64::to_bits), downs[999 - x].0.map(f64::to_bits));
            assert_eq!(c.0.map(f64::to_bits), Rgb([x as f64, -0.0, f64::MIN_POSITIVE]).0.map(f64::to_bits));
        }
    }

    #[test]
    fn a_point_whose_trace_panicked_is_traced_again() {
        let line = Line::new(1);
        let failed = std::panic::catch_unwind(|| line.get_or_trace(0, || panic!("a trace that fails")));
        assert!(failed.is_err());
        assert_eq!(line.get_or_trace(0, || Rgb::grey(0.5)), Rgb::grey(0.5));
        assert_eq!(line.get_or_trace(0, || Rgb::grey(1.0)), Rgb::grey(0.5), "traced once it succeeded");
    }

    #[test]
    fn an_edge_row_is_made_once_and_dropped_after_its_last_reader() {
        let text = r#"{"camera": {"eye": [0,0,5], "center": [0,0,0],
            "window": {"l": -1, "r": 1, "b": -1, "t": 1}, "resolution": [4, 3]},
            "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1}]}"#;
        let Ok(AnyScene::Space(scene)) = load_str(text) else { panic!("a 3D scene") };
        let accel = Accel::build(&scene, AccelKind::None);
        let mut tracer = Tracer::new(&scene, &accel, NoRecorder);
        let lattice = Lattice::new(&scene.camera, 2);
        let rows = EdgeRows::new(lattice, &scene.camera);
        let held = |j: usize| rows.rows[j].row.lock().unwrap().is_some();
        // Edge row 1 bounds pixel rows 0 and 1: made by the first to ask, its corners traced once.
        let first = rows.acquire(&mut tracer, 1);
        let second = rows.acquire(&mut tracer, 1);
        assert!(Arc::ptr_eq(&first, &second));
        assert_eq!(tracer.stats.rays.primary, 5, "Nx + 1 corners");
        rows.release(1);
        assert!(held(1), "one reader left");
        rows.release(1);
        assert!(!held(1), "dropped by its last reader");
        // Edge rows 0 and Ny bound one pixel row each.
        let _bottom = rows.acquire(&mut tracer, 0);
        rows.release(0);
        assert!(!held(0));
        assert_eq!(tracer.stats.rays.primary, 10);
    }
}
