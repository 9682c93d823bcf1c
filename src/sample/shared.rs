//! Sharing samples across a whole image (algorithm.md §8: "every sample is traced once and shared
//! by all squares and pixels that touch it", keyed by integer lattice coordinates, never floats).
//!
//! One thread renders a pixel row (`breadth::render_row`). The row's pixel corners are traced
//! with the lattice row they lie on ([`EdgeRow`]). The other points of its bottom and top lattice
//! rows are shared with the pixel row below or above, which another thread may render at the
//! same time: the first thread to need a point traces it, any other waits ([`Line`]), and a
//! thread that traces several at once claims them first ([`Claims`]). [`EdgeRows`] makes and
//! drops the edge rows, so memory holds only those in use (see `render`).

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
    pub(super) fn get_or_trace(&self, x: usize, trace: impl FnOnce() -> Rgb) -> Rgb {
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
                READY => return self.color(),
                EMPTY if self.claim() => {
                    let unwinding = Unwinding(&self.state);
                    let color = trace();
                    std::mem::forget(unwinding);
                    self.fill(color);
                    return color;
                }
                _ => std::thread::yield_now(),
            }
        }
    }
    /// The channels of a traced point (once its [`READY`] state is read).
    #[inline]
    fn color(&self) -> Rgb {
        Rgb(self.bits.each_ref().map(|b| f64::from_bits(b.load(Ordering::Relaxed))))
    }
    /// Whether this thread takes the point to trace: true if it was [`EMPTY`] (it is now
    /// [`TRACING`], and [`Point::fill`] must follow).
    #[inline]
    fn claim(&self) -> bool {
        self.state.compare_exchange(EMPTY, TRACING, Ordering::Acquire, Ordering::Acquire).is_ok()
    }
    /// A claimed point's colour: its channels, then (`Release`) its [`READY`] state.
    #[inline]
    fn fill(&self, color: Rgb) {
        for (bits, channel) in self.bits.iter().zip(color.0) {
            bits.store(channel.to_bits(), Ordering::Relaxed);
        }
        self.state.store(READY, Ordering::Release);
    }
}

/// What a thread that wants a point of a [`Line`] finds there ([`Claims::claim`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Claim {
    /// The point's colour: some thread traced it.
    Traced(Rgb),
    /// The point is this thread's to trace.
    Mine,
    /// Another thread is tracing it: wait for it with [`Line::get_or_trace`] (once this thread's
    /// own claims are filled, so that no two threads wait for each other).
    Theirs,
}

/// The points a thread claimed on [`Line`]s to trace together, each with the index of its colour
/// in the batch: filled at once by [`Claims::fill`]; put back to [`EMPTY`] if dropped before
/// (a trace that unwinds), so that a waiting thread traces them itself instead of waiting for
/// ever.
#[derive(Debug, Default)]
pub(super) struct Claims<'l> {
    points: Vec<(&'l Point, usize)>,
}

impl<'l> Claims<'l> {
    /// Point `x` of `line`: its colour, or claimed now for batch index `at`, or another thread's.
    #[inline]
    pub(super) fn claim(&mut self, line: &'l Line, x: usize, at: usize) -> Claim {
        let point = &line.points[x];
        match point.state.load(Ordering::Acquire) {
            READY => Claim::Traced(point.color()),
            EMPTY if point.claim() => {
                self.points.push((point, at));
                Claim::Mine
            }
            _ => Claim::Theirs,
        }
    }
    /// Every claimed point's colour from the batch's `colors`; no claim is left.
    pub(super) fn fill(&mut self, colors: &[Rgb]) {
        for (point, at) in self.points.drain(..) {
            point.fill(colors[at]);
        }
    }
}

impl Drop for Claims<'_> {
    fn drop(&mut self) {
        for (point, _) in &self.points {
            point.state.store(EMPTY, Ordering::Release);
        }
    }
}

/// A lattice row `y = j·2^K` on a pixel-row boundary: its `Nx + 1` pixel corners, traced when
/// the row is made, and for K > 0 its finer points, traced on demand. Every corner is needed, so
/// all are traced at once and read as plain colours.
#[derive(Debug)]
pub struct EdgeRow {
    /// The colours of the corners `(i·2^K, y)`, `i = 0 … Nx`.
    pub(super) corners: Vec<Rgb>,
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
pub(super) fn trace_point<V: Dim>(
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

impl<'l> Edges<'l> {
    /// The shared line that holds the pixel row's local lattice row `b`: the finer points of the
    /// bottom (`b = 0`) or the top (`b = 2^K`) edge row; none inside the pixel row, nor on a 2D
    /// scene's line (whose finer points are each inside one pixel).
    pub(super) fn line(&self, lattice: Lattice, b: u32) -> Option<&'l Line> {
        let row = if b == 0 {
            self.bottom
        } else if b == lattice.scale && lattice.dims() == 2 {
            self.top
        } else {
            return None;
        };
        row.finer.as_ref()
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
