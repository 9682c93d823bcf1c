//! Whitted's adaptive subdivision (algorithm.md §8.2): if the corner colours of a square differ
//! too much, split it into 4 sub-squares and trace their new corners; repeat per sub-square until
//! the colours agree within the threshold or level K is reached; the pixel is the area-weighted
//! mean of its leaf squares, each the mean of its 4 corners. In 2D a square is an interval (2 ends,
//! 2 halves). The samples come from a [`SampleSource`] (the image's shared lattice, or one traced
//! pixel), so this one recursion serves `render` and `trace`.
//!
//! `subdivide` is the one recursion, over a `Rule<N>` (N = 4 corners, 2 on a 2D line, a constant);
//! `splits` is the convention, and `unsplit` its level-0 decision on references, which a render
//! takes before the recursion. A `SampleSource` gives `color` and the `corners` a render reads from
//! its edge rows; a `SquareSink` observes the squares.

use super::corners::corner_mean;
use crate::scene::material::Rgb;

/// Gives the colour of the pixel's local lattice point `(a, b)`, `0 ≤ a, b ≤ 2^K` (`b = 0` in 2D).
pub trait SampleSource {
    /// The colour of the sample at `(a, b)`, traced once whatever the number of calls.
    fn color(&mut self, a: u32, b: u32) -> Rgb;
    /// The pixel's `N` corners at `0` and `side = 2^K`, in the order lower-left, lower-right,
    /// upper-left, upper-right (2D: the two ends): by default read through
    /// [`SampleSource::color`] in that order; a render reads them straight from its edge rows.
    #[inline(always)]
    fn corners<const N: usize>(&mut self, side: u32) -> [Rgb; N] {
        std::array::from_fn(|k| self.color(CORNERS[k].0 * side, CORNERS[k].1 * side))
    }
    /// A square reads `(a, b)` again, whose colour its parent already holds (the trace records
    /// it as reused; rendering does nothing).
    #[inline(always)]
    fn reuse(&mut self, _a: u32, _b: u32, _color: Rgb) {}
}

/// A square of the subdivision, as the recursion decided it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Square {
    /// Local lattice coordinates of its lower-left corner.
    pub a: u32,
    /// Local lattice coordinates of its lower-left corner (0 in 2D).
    pub b: u32,
    /// Its side in lattice units, `2^(K − level)`.
    pub side: u32,
    /// Its level: 0 for the pixel.
    pub level: u32,
    /// The largest channel spread of its corners.
    pub spread: f64,
    /// Whether it is split.
    pub split: bool,
}

/// Observes the squares in pre-order (for the trace document); `render` uses [`NoSquares`].
pub trait SquareSink {
    /// False for [`NoSquares`]: then a level-K square's spread, which decides nothing, is not
    /// computed.
    const RECORDS: bool;
    /// A square was decided; returns a handle for [`SquareSink::close`].
    fn open(&mut self, square: &Square) -> usize;
    /// The square's colour is known.
    fn close(&mut self, handle: usize, color: Rgb);
}

/// Keeps no squares (rendering).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoSquares;

impl SquareSink for NoSquares {
    const RECORDS: bool = false;
    #[inline(always)]
    fn open(&mut self, _square: &Square) -> usize {
        0
    }
    #[inline(always)]
    fn close(&mut self, _handle: usize, _color: Rgb) {}
}

/// The convention of §8.2: a square is split while `max over channels of (max − min of its
/// corners) ≥ threshold`, on the unclamped linear colours, and while its level is below K.
/// Threshold 0 therefore splits everything down to level K, `+∞` never splits.
#[must_use]
pub fn splits(spread: f64, level: u32, threshold: f64, max_level: u32) -> bool {
    level < max_level && spread >= threshold
}

/// A pixel that §8.2 does not split at level 0 (its corners agree within the threshold, or
/// K = 0): the mean of its `N` corners, given in [`SampleSource::corners`]' order; `None` if it
/// splits. The decision and the sum [`subdivide`] makes for such a pixel, on references, so that
/// a render decides most pixels where its edge rows hold their corners, without copying them.
#[inline(always)]
#[must_use]
pub fn unsplit<const N: usize>(corners: [&Rgb; N], threshold: f64, max_level: u32) -> Option<Rgb> {
    (!splits(Rgb::spread(corners), 0, threshold, max_level)).then(|| corner_mean(corners))
}

/// The level at which local point `(a, b)` first appears: the pixel's corners are level 0, the
/// new corners of the k-th subdivision level k. With `2^K` steps a side, that is
/// `K − min(trailing zeros of a, of b, K)`.
#[must_use]
pub fn sample_level(a: u32, b: u32, max_level: u32) -> u32 {
    max_level - a.trailing_zeros().min(b.trailing_zeros()).min(max_level)
}

/// The colour of one pixel: the subdivision of its square `[0, 2^K]²` (2D: `[0, 2^K]`), the
/// area-weighted mean of the leaves `Σ 4^(−level)·(mean of the leaf's corners)` (2D: `2^(−level)`),
/// computed as nested means: a split square is the mean of its children, visited lower-left,
/// lower-right, upper-left, upper-right, so the sum is always taken in the same order.
pub fn subdivide(
    source: &mut impl SampleSource,
    sink: &mut impl SquareSink,
    dims: usize,
    threshold: f64,
    max_level: u32,
) -> Rgb {
    if dims == 1 {
        Rule::<2> { threshold, max_level }.pixel(source, sink)
    } else {
        Rule::<4> { threshold, max_level }.pixel(source, sink)
    }
}

/// The fixed parameters of one subdivision, whose squares have `N` corners: 4, or 2 on a 2D
/// scene's line (a constant, so that every loop over corners is unrolled).
#[derive(Clone, Copy)]
struct Rule<const N: usize> {
    threshold: f64,
    max_level: u32,
}

/// The corners of a square, in the order lower-left, lower-right, upper-left, upper-right, as
/// offsets in half sides (2D: the first two); also its children's lower-left corners, in the
/// order they are visited.
pub(super) const CORNERS: [(u32, u32); 4] = [(0, 0), (1, 0), (0, 1), (1, 1)];

/// One read of a split square's point by a child: the point's index `3·gy + gx` in the square's
/// 3×3 grid, and whether no earlier read (nor the parent's corners) holds it yet.
#[derive(Clone, Copy)]
struct Read {
    point: u32,
    first: bool,
}

/// The reads of a split square's children, child by child (lower-left, lower-right, upper-left,
/// upper-right) and corner by corner, in the order the recursion makes them, decided at compile
/// time: so a child's corner costs no test of whether a sibling already read it.
const fn reads<const N: usize>() -> [[Read; N]; N] {
    let mut held = [false; 9];
    let mut k = 0;
    while k < N {
        held[(6 * CORNERS[k].1 + 2 * CORNERS[k].0) as usize] = true;
        k += 1;
    }
    let mut out = [[Read { point: 0, first: false }; N]; N];
    let mut child = 0;
    while child < N {
        let mut k = 0;
        while k < N {
            let point = 3 * (CORNERS[child].1 + CORNERS[k].1) + CORNERS[child].0 + CORNERS[k].0;
            out[child][k] = Read { point, first: !held[point as usize] };
            held[point as usize] = true;
            k += 1;
        }
        child += 1;
    }
    out
}

/// The most new points a split square has: its 4 edge midpoints and its centre (2D: 1).
pub(super) const MOST_NEW: usize = 5;

/// A split square's new points, as offsets in half sides, in the order its children first read
/// them ([`reads`]): the bottom, left, centre, right and top points (2D: the middle), the first
/// `count` of the array, with `count`.
pub(super) const fn new_points<const N: usize>() -> ([(u32, u32); MOST_NEW], usize) {
    let reads = reads::<N>();
    let mut out = [(0, 0); MOST_NEW];
    let (mut count, mut child) = (0, 0);
    while child < N {
        let mut k = 0;
        while k < N {
            let read = reads[child][k];
            if read.first {
                out[count] = (read.point % 3, read.point / 3);
                count += 1;
            }
            k += 1;
        }
        child += 1;
    }
    (out, count)
}

impl<const N: usize> Rule<N> {
    /// The pixel: reads its corners, then subdivides (a render decides the pixels that do not
    /// split before, with [`unsplit`]).
    #[inline(always)]
    fn pixel<S: SquareSink>(self, source: &mut impl SampleSource, sink: &mut S) -> Rgb {
        let side = 1 << self.max_level;
        let corners = source.corners::<N>(side);
        self.square(source, sink, (0, 0), side, 0, corners)
    }

    /// One square whose corners are known: decide, then either the mean of its corners or the
    /// mean of its children. A split square's 3×3 points (2D: 3) hold its corners and, as the
    /// children read them in order ([`reads`]), the 5 (2D: 1) new ones, so a child gets what a
    /// sibling read without asking the source again (which still sees it:
    /// [`SampleSource::reuse`]).
    fn square<S: SquareSink>(
        self,
        source: &mut impl SampleSource,
        sink: &mut S,
        (a, b): (u32, u32),
        side: u32,
        level: u32,
        corners: [Rgb; N],
    ) -> Rgb {
        let decides = level < self.max_level;
        let spread = if decides || S::RECORDS { Rgb::spread(&corners) } else { 0.0 };
        let split = decides && splits(spread, level, self.threshold, self.max_level);
        let handle = sink.open(&Square { a, b, side, level, spread, split });
        let color = if split {
            let half = side / 2;
            // The square's 3×3 points (2D: 3), row by row; READS says which are read first.
            let mut points = [Rgb::BLACK; 9];
            for (k, (dx, dy)) in CORNERS[..N].iter().enumerate() {
                points[(6 * dy + 2 * dx) as usize] = corners[k];
            }
            let reads = const { reads::<N>() };
            let mut children = [Rgb::BLACK; N];
            for (child, (cx, cy)) in CORNERS[..N].iter().enumerate() {
                let mut own = [Rgb::BLACK; N];
                for (k, read) in reads[child].iter().enumerate() {
                    let (gx, gy) = (read.point % 3, read.point / 3);
                    let (x, y) = (a + gx * half, b + gy * half);
                    let slot = &mut points[read.point as usize];
                    own[k] = if read.first {
                        *slot = source.color(x, y);
                        *slot
                    } else {
                        source.reuse(x, y, *slot);
                        *slot
                    };
                }
                children[child] =
                    self.square(source, sink, (a + cx * half, b + cy * half), half, level + 1, own);
            }
            corner_mean(&children)
        } else {
            corner_mean(&corners)
        };
        sink.close(handle, color);
        color
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// A pixel whose left part (local a < edge) is white and the rest black: a vertical edge.
    struct Edge {
        edge: f64,
        scale: f64,
        traced: HashMap<(u32, u32), u32>,
    }

    impl SampleSource for Edge {
        fn color(&mut self, a: u32, b: u32) -> Rgb {
            *self.traced.entry((a, b)).or_default() += 1;
            if f64::from(a) / self.scale < self.edge {
                Rgb::grey(1.0)
            } else {
                Rgb::BLACK
            }
        }
    }

    #[test]
    fn levels_of_points() {
        assert_eq!(sample_level(0, 0, 2), 0);
        assert_eq!(sample_level(4, 4, 2), 0);
        assert_eq!(sample_level(2, 0, 2), 1);
        assert_eq!(sample_level(2, 2, 2), 1);
        assert_eq!(sample_level(1, 2, 2), 2);
        assert_eq!(sample_level(3, 3, 2), 2);
        assert_eq!(sample_level(0, 0, 0), 0);
    }

    #[test]
    fn new_points_are_the_midpoints_and_centre_in_reading_order() {
        assert_eq!(new_points::<4>(), ([(1, 0), (0, 1), (1, 1), (2, 1), (1, 2)], 5));
        assert_eq!(new_points::<2>().0[..new_points::<2>().1], [(1, 0)]);
    }

    #[test]
    fn h1_threshold_zero_splits_to_level_k_and_inf_never() {
        assert!(splits(0.0, 0, 0.0, 2));
        assert!(!splits(0.0, 2, 0.0, 2));
        assert!(!splits(1e300, 0, f64::INFINITY, 8));
        assert!(!splits(1.0, 0, 0.5, 0));
    }

    #[test]
    fn unsplit_is_the_level_0_decision_and_mean() {
        let g = Rgb([0.25, 0.5, 0.75]);
        let h = Rgb([0.5, 0.5, 0.75]);
        // Spread 0.25: split at a threshold of 0.25 (≥), not at 0.5, never with K = 0.
        assert_eq!(unsplit([&g, &g, &g, &h], 0.25, 2), None);
        let mean = Some(Rgb([0.3125, 0.5, 0.75]));
        assert_eq!(unsplit([&g, &g, &g, &h], 0.5, 2), mean);
        assert_eq!(unsplit([&g, &g, &g, &h], 0.0, 0), mean);
        assert_eq!(unsplit([&g, &h], 0.5, 3), Some(Rgb([0.375, 0.5, 0.75])));
        // What subdivide gives for a pixel its corners do not split: a uniform one.
        let mut white = Edge { edge: 2.0, scale: 4.0, traced: HashMap::new() };
        let w = Rgb::grey(1.0);
        assert_eq!(unsplit([&w; 4], 0.1, 2), Some(subdivide(&mut white, &mut NoSquares, 2, 0.1, 2)));
    }

    #[test]
    fn an_edge_at_a_third_gives_the_area_of_its_leaves() {
        // K = 2, 4 steps a side, edge at a = 4/3 · … : white for a/4 < 1/3, i.e. a ∈ {0, 1}.
        let mut src = Edge { edge: 1.0 / 3.0, scale: 4.0, traced: HashMap::new() };
        let c = subdivide(&mut src, &mut NoSquares, 2, 0.5, 2);
        // Level 0 splits (white and black corners); its left quarters split again; the right
        // quarters are black leaves. Left column of level-2 squares: corners a = 0, 1 → white
        // leaves (area 1/16 each, 4 of them in the left column); column a = 1..2 → mixed: half.
        // Columns of level-2 squares: [0,1] white, [1,2] half → per row of 4 small squares
        // 1 + 0.5 = 1.5 of 4 → 1.5/4 = 0.375.
        assert_eq!(c, Rgb::grey(0.375));
        assert!(src.traced.values().all(|n| *n >= 1));
    }

    #[test]
    fn intervals_in_2d() {
        let mut src = Edge { edge: 0.3, scale: 2.0, traced: HashMap::new() };
        // K = 1: the interval [0, 2] splits once: [0, 1] is (white, black) → 0.5, [1, 2] black.
        let c = subdivide(&mut src, &mut NoSquares, 1, 0.1, 1);
        assert_eq!(c, Rgb::grey(0.25));
        assert_eq!(src.traced.len(), 3);
    }
}
