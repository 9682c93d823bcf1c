//! The BVH's build for large scenes (more than [`LARGE`] primitives: a mesh, a crowd): the same
//! top-down binned surface-area heuristic as [`super::bvh`]'s exact build, on compact records and
//! with fewer passes, so that a million triangles build in a fraction of the time and memory.
//! Scenes of at most [`LARGE`] primitives (every lesson scene) keep the exact build, node for
//! node: their figures, traces and snapshots do not depend on this file.
//!
//! What differs from the exact build:
//! - **A primitive is a [`Record`] of 32 bytes** (56 in the exact build): its box in `f32`
//!   rounded outward (each `min` down, each `max` up, [`down_to_f32`], [`up_to_f32`]), its index
//!   and its test cost. Every record's box holds the exact one, so every node's box does too: a
//!   ray reaches every primitive it would reach in an exact tree, and the exact `f64` test of
//!   the primitive decides each hit. The tree differs from the exact build's (other boxes, other
//!   bins), the answers do not: the nearest `(t, object, part)` is kept whatever the order of
//!   the visits (§6). A box beyond `f32`'s range (a coordinate above 3.4·10³⁸) sends the whole
//!   scene to the exact build.
//! - **Centroids doubled**, `c = min + max`: binning needs only their order, not the halving.
//! - **Two passes a level**: the binning pass gives both sides' boxes (the union of their bins),
//!   and the partition (in place, without a branch) gives both sides' centroid boxes as it
//!   moves the records; the exact build reads its items a third time for the boxes. In a large
//!   group the partition compares each coordinate with the split bin's last one
//!   ([`last_of_bin`]) instead of computing its bin.
//! - **Fewer bins for small groups**: 4 for at most 4 records, 8 for at most 8 (the bins' sweep
//!   is most of a small group's cost), else [`BINS`].
//!
//! The bins ([`BINS`] an axis, every axis for groups of at most [`ALL_AXES_BELOW`] records, the
//! longest above), the SAH `C_trav + (S(L)·C_L + S(R)·C_R)/S(P)` (here in `f32`), the leaf rule,
//! the median split from depth [`BALANCE_DEPTH`] on or when every centroid coincides, the ties
//! (lower axis, lower bin) and the parallel top levels are the exact build's; the tree is the
//! same on any machine and any number of threads.

use super::bvh::{Split, ALL_AXES_BELOW, BALANCE_DEPTH, BINS, C_TRAV, MAX_LEAF};
use super::wide::{down_to_f32, up_to_f32};
use crate::bounds::aabb::Aabb;
use crate::geom::Vector;
use arrayvec::ArrayVec;
use glam::{BVec3A, Vec3A};

/// Scenes of more primitives than this take this build; the others the exact one.
pub const LARGE: usize = 1024;
/// [`C_TRAV`] in the precision of this build's SAH.
#[allow(clippy::cast_possible_truncation)] // 0.5 is exact in f32
const C_TRAV_F32: f32 = C_TRAV as f32;

/// A primitive as this build sees it: its box in `f32` rounded outward, its index in the build's
/// list and the cost of testing it ([`crate::shape::Shape::test_cost`]). 32 bytes, two to a
/// cache line.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(16))]
pub(super) struct Record {
    min: [f32; 3],
    cost: f32,
    max: [f32; 3],
    prim: u32,
}

impl Record {
    /// The record of primitive `prim` with box `bounds`, `None` when the box does not fit in
    /// `f32`. In 2D the third coordinate is 0.
    fn new<V: Vector>(bounds: &Aabb<V>, prim: usize, cost: f32) -> Option<Self> {
        let (mut min, mut max) = ([0.0f32; 3], [0.0f32; 3]);
        for a in 0..V::DIM {
            min[a] = down_to_f32(bounds.min[a]);
            max[a] = up_to_f32(bounds.max[a]);
        }
        let fits = min.iter().chain(&max).all(|x| x.is_finite());
        let prim = u32::try_from(prim).expect("fewer than 2^32 primitives");
        fits.then_some(Self { min, cost, max, prim })
    }

    #[inline]
    fn lo(&self) -> Vec3A {
        Vec3A::from_array(self.min)
    }

    #[inline]
    fn hi(&self) -> Vec3A {
        Vec3A::from_array(self.max)
    }

    /// Twice the centroid, `min + max`.
    #[inline]
    fn centroid2(&self) -> Vec3A {
        self.lo() + self.hi()
    }
}

/// The records of primitives `0, 1, …` given by their boxes and test costs, or `None` when a box
/// does not fit in `f32`. The list is sized once, from the iterator's length (a list grown by
/// doubling copied itself and touched twice its pages).
pub(super) fn records<V: Vector>(
    boxes: impl ExactSizeIterator<Item = (Aabb<V>, f32)>,
) -> Option<Vec<Record>> {
    let mut out = Vec::with_capacity(boxes.len());
    for (i, (b, cost)) in boxes.enumerate() {
        out.push(Record::new(&b, i, cost)?);
    }
    Some(out)
}

/// What a group's split needs: the box of its records and the box of their doubled centroids.
#[derive(Clone, Copy, Debug)]
pub(super) struct Group {
    lo: Vec3A,
    hi: Vec3A,
    c_lo: Vec3A,
    c_hi: Vec3A,
}

/// A bin, or a run of bins: the box of its records, how many, and their summed test cost.
#[derive(Clone, Copy, Debug)]
struct Bin {
    lo: Vec3A,
    hi: Vec3A,
    count: u32,
    cost: f32,
}

impl Bin {
    /// No record: the empty box `[+∞, −∞]`.
    const EMPTY: Self = Self { lo: Vec3A::INFINITY, hi: Vec3A::NEG_INFINITY, count: 0, cost: 0.0 };

    #[inline]
    fn add(&mut self, r: &Record) {
        self.lo = self.lo.min(r.lo());
        self.hi = self.hi.max(r.hi());
        self.count += 1;
        self.cost += r.cost;
    }

    #[inline]
    fn merge(&self, other: &Self) -> Self {
        Self {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
            count: self.count + other.count,
            cost: self.cost + other.cost,
        }
    }
}

/// The measure the SAH weighs a box by: half the surface area in 3D, half the perimeter in 2D
/// (as [`Aabb::surface`]).
#[inline]
fn surface<V: Vector>(lo: Vec3A, hi: Vec3A) -> f32 {
    let e = (hi - lo).max(Vec3A::ZERO);
    if V::DIM == 2 {
        e.x + e.y
    } else {
        e.x * e.y + e.y * e.z + e.z * e.x
    }
}

/// The axis of the largest extent among the first `V::DIM` (the first on a tie).
fn longest<V: Vector>(extent: Vec3A) -> usize {
    (1..V::DIM).fold(0, |best, a| if extent[a] > extent[best] { a } else { best })
}

/// `2²³`: an `f32` in `[0, 2²²)` plus this is the integer nearest it, in the low bits.
const ROUNDER: f32 = 8_388_608.0;

/// The bins of a doubled centroid `c` on each axis, `n_bins` a side: `(c − lo)·scale − ½` clamped to
/// `[0, n_bins − 1]` and rounded to the nearest integer (ties to even), i.e. `⌊(c − lo)·scale⌋`
/// but for ties. A NaN (an axis of zero extent: `0·∞`) lands in bin 0. The binning and the
/// partition both call this, so a record lands on the same side in both.
#[inline]
fn bins_of(c: Vec3A, lo: Vec3A, scale: Vec3A, n_bins: usize) -> [usize; 3] {
    let last = Vec3A::splat(n_bins as f32 - 1.0);
    // `max` first: it turns a NaN into 0 (the second operand wins, in SIMD and in scalar).
    let f = ((c - lo) * scale - Vec3A::splat(0.5)).max(Vec3A::ZERO).min(last) + Vec3A::splat(ROUNDER);
    f.to_array().map(|x| (x.to_bits() - ROUNDER.to_bits()) as usize)
}

/// The bin of doubled centroid coordinate `c` on an axis of finite `scale` (`last` = the bin
/// count − 1): [`bins_of`]'s lane in scalar arithmetic, the same operations in the same order (no
/// NaN can arise on such an axis), so the same bin.
#[inline]
fn bin_on_axis(c: f32, lo: f32, scale: f32, last: f32) -> usize {
    let f = ((c - lo) * scale - 0.5).max(0.0).min(last) + ROUNDER;
    (f.to_bits() - ROUNDER.to_bits()) as usize
}

/// `x`'s place in the order of finite `f32`s, as an integer (`f32::total_cmp`'s key; it is its
/// own inverse, [`from_order`]).
fn order_of(x: f32) -> i64 {
    let b = x.to_bits().cast_signed();
    i64::from(b ^ ((b >> 31).cast_unsigned() >> 1).cast_signed())
}

/// The `f32` at place `k` of [`order_of`].
fn from_order(k: i64) -> f32 {
    let b = i32::try_from(k).expect("a place of order_of");
    f32::from_bits((b ^ ((b >> 31).cast_unsigned() >> 1).cast_signed()).cast_unsigned())
}

/// The largest doubled centroid coordinate in `[lo, hi]` (the axis's centroid range, `lo` in bin
/// 0) whose bin ([`bin_on_axis`]) is at most `bin`. The bin does not decrease as the coordinate
/// grows (every step of it rounds monotonically), so a record goes left exactly when its
/// coordinate is at most this: the partition compares once instead of computing the bin. Found
/// by bisection over the `f32`s between `lo` and `hi`.
fn last_of_bin(bin: usize, lo: f32, hi: f32, scale: f32, last: f32) -> f32 {
    let left = |c: f32| bin_on_axis(c, lo, scale, last) <= bin;
    if left(hi) {
        return hi;
    }
    // left(from_order(a)) holds, left(from_order(b)) does not.
    let (mut a, mut b) = (order_of(lo), order_of(hi));
    while b - a > 1 {
        let m = a + (b - a) / 2;
        if left(from_order(m)) {
            a = m;
        } else {
            b = m;
        }
    }
    from_order(a)
}

/// The axes binned: those of non-zero centroid extent (finite `scale`); of a group of more than
/// [`ALL_AXES_BELOW`] records, the longest of them only (as the exact build).
fn axes_binned<V: Vector>(n: usize, scale: Vec3A) -> [bool; 3] {
    let finite = [0, 1, 2].map(|a| a < V::DIM && scale[a].is_finite());
    if n <= ALL_AXES_BELOW {
        return finite;
    }
    // The least scale is the largest extent.
    let longest = (0..V::DIM).filter(|&a| finite[a]).fold(None, |b: Option<usize>, a| match b {
        Some(b) if scale[b] <= scale[a] => Some(b),
        _ => Some(a),
    });
    [0, 1, 2].map(|a| Some(a) == longest)
}

/// The split the SAH chose: its axis, the last bin of the left side, both sides' bins.
struct Best {
    axis: usize,
    bin: usize,
    left: Bin,
    right: Bin,
}

impl<V: Vector> Split<V> for Record {
    type Group = Group;

    fn group(items: &[Self]) -> Group {
        let mut g = Group {
            lo: Vec3A::INFINITY,
            hi: Vec3A::NEG_INFINITY,
            c_lo: Vec3A::INFINITY,
            c_hi: Vec3A::NEG_INFINITY,
        };
        for r in items {
            let c = r.centroid2();
            g.lo = g.lo.min(r.lo());
            g.hi = g.hi.max(r.hi());
            g.c_lo = g.c_lo.min(c);
            g.c_hi = g.c_hi.max(c);
        }
        g
    }

    fn bounds(group: &Group) -> Aabb<V> {
        let (mut min, mut max) = (V::ZERO, V::ZERO);
        for a in 0..V::DIM {
            min[a] = f64::from(group.lo[a]);
            max[a] = f64::from(group.hi[a]);
        }
        Aabb::new(min, max)
    }

    fn prim(&self) -> u32 {
        self.prim
    }

    fn split(items: &mut [Self], depth: u32, group: &Group) -> Option<(usize, Group, Group)> {
        let n = items.len();
        let extent = (group.c_hi - group.c_lo).max(Vec3A::ZERO);
        let axis = longest::<V>(extent);
        if depth >= BALANCE_DEPTH || !(extent[axis] > 0.0) {
            return (n > MAX_LEAF || depth >= BALANCE_DEPTH).then(|| median::<V>(items, axis));
        }
        // Fewer bins than records would leave most of them empty (and cost their sweep).
        let choice = match n {
            ..=4 => split_binned::<V>(items, group, extent, 4),
            5..=8 => split_binned::<V>(items, group, extent, 8),
            _ => split_binned::<V>(items, group, extent, BINS),
        };
        match choice {
            Choice::Leaf => None,
            Choice::Split(mid, left, right) => Some((mid, left, right)),
            Choice::Median => Some(median::<V>(items, axis)),
        }
    }
}

/// What the SAH decided for a group.
enum Choice {
    /// Testing every record is cheaper than any split.
    Leaf,
    /// Split at `mid` (after the partition), with both sides' groups.
    Split(usize, Group, Group),
    /// No split leaves records on both sides: the median's.
    Median,
}

/// The SAH's choice for `items` (centroid extent `extent`, not zero on some axis), binned into
/// `n_bins` (at most [`BINS`]) bins an axis; a split is made (the records partitioned). The bin
/// count is a value, not a const parameter: one copy of the code serves 4, 8 and 12 bins (the
/// WebAssembly module carried three, 120 KB).
fn split_binned<V: Vector>(items: &mut [Record], group: &Group, extent: Vec3A, n_bins: usize) -> Choice {
    let n = items.len();
    let scale = Vec3A::splat(n_bins as f32) / extent;
    let Some((cost, best)) = best_split::<V>(items, group, scale, n_bins) else {
        return Choice::Median;
    };
    if n <= MAX_LEAF && cost >= items.iter().map(|r| r.cost).sum::<f32>() {
        return Choice::Leaf;
    }
    // A record goes left when its bin is at most the split's. In a large group, the same test
    // is one comparison: its coordinate at most the split bin's last one ([`last_of_bin`]).
    let (axis, bin) = (best.axis, best.bin);
    let (mid, left, right) = if n > ALL_AXES_BELOW {
        let last = n_bins as f32 - 1.0;
        let t = last_of_bin(bin, group.c_lo[axis], group.c_hi[axis], scale[axis], last);
        let t = Vec3A::splat(t);
        partition(items, |c| c.cmple(t).bitmask() >> axis & 1 == 1)
    } else {
        partition(items, |c| bins_of(c, group.c_lo, scale, n_bins)[axis] <= bin)
    };
    debug_assert_eq!(mid, best.left.count as usize);
    let side = |b: &Bin, (c_lo, c_hi)| Group { lo: b.lo, hi: b.hi, c_lo, c_hi };
    Choice::Split(mid, side(&best.left, left), side(&best.right, right))
}

/// Lomuto's partition without a branch (which side a record goes is a coin toss for the branch
/// predictor): every record is swapped with the first of the right side, which then grows by one
/// unless the record goes left (`goes_left` of its doubled centroid). The centroid box of each
/// side grows by a lane-wise select. Returns the left side's length and both sides' centroid
/// boxes.
#[inline]
fn partition(
    items: &mut [Record],
    goes_left: impl Fn(Vec3A) -> bool,
) -> (usize, (Vec3A, Vec3A), (Vec3A, Vec3A)) {
    let mut mid = 0;
    let (mut left_lo, mut left_hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
    let (mut right_lo, mut right_hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
    for k in 0..items.len() {
        let c = items[k].centroid2();
        let left = goes_left(c);
        let mask = BVec3A::splat(left);
        left_lo = Vec3A::select(mask, left_lo.min(c), left_lo);
        left_hi = Vec3A::select(mask, left_hi.max(c), left_hi);
        right_lo = Vec3A::select(mask, right_lo, right_lo.min(c));
        right_hi = Vec3A::select(mask, right_hi, right_hi.max(c));
        items.swap(mid, k);
        mid += usize::from(left);
    }
    (mid, (left_lo, left_hi), (right_lo, right_hi))
}

/// Bins `items` along every axis of non-zero centroid extent (`n_bins` bins a side, at most
/// [`BINS`]; `scale`: bins per unit of doubled centroid) and sweeps each axis's splits for the
/// least SAH cost; that cost and the split, `None` when no split leaves records on both sides.
/// Only the bins of the axes in use are initialised.
fn best_split<V: Vector>(
    items: &[Record],
    group: &Group,
    scale: Vec3A,
    n_bins: usize,
) -> Option<(f32, Best)> {
    let used = axes_binned::<V>(items.len(), scale);
    let parent = surface::<V>(group.lo, group.hi);
    // The bins of axis a are `all[a * n_bins ..][.. n_bins]`, for the axes used.
    let mut all: ArrayVec<Bin, { 3 * BINS }> = ArrayVec::new();
    let mut axes: ArrayVec<usize, 3> = ArrayVec::new();
    if items.len() > ALL_AXES_BELOW {
        let axis = used.iter().position(|&u| u)?;
        axes.push(axis);
        // Two sets of bins, the records taken in pairs: neighbouring records (a mesh's triangles
        // in file order) often share a bin, and each update of a bin waits for the last one.
        // Merged after: the same boxes and counts, and the same costs (sums of quarters below
        // 2²² are exact in f32 in any order).
        all.extend((0..2 * n_bins).map(|_| Bin::EMPTY));
        let bin = |r: &Record| bins_of(r.centroid2(), group.c_lo, scale, n_bins)[axis];
        let mut pairs = items.chunks_exact(2);
        for pair in &mut pairs {
            all[bin(&pair[0])].add(&pair[0]);
            all[n_bins + bin(&pair[1])].add(&pair[1]);
        }
        for r in pairs.remainder() {
            all[bin(r)].add(r);
        }
        for k in 0..n_bins {
            all[k] = all[k].merge(&all[n_bins + k]);
        }
        all.truncate(n_bins);
    } else {
        axes.extend((0..V::DIM).filter(|&a| used[a]));
        all.extend((0..axes.len() * n_bins).map(|_| Bin::EMPTY));
        for r in items {
            let k = bins_of(r.centroid2(), group.c_lo, scale, n_bins);
            for (at, &axis) in axes.iter().enumerate() {
                all[at * n_bins + k[axis]].add(r);
            }
        }
    }
    // The least cost, its axis (as a place in `axes`) and the last bin of its left side.
    let mut best: Option<(f32, usize, usize)> = None;
    for at in 0..axes.len() {
        sweep::<V>(at, &all[at * n_bins..][..n_bins], parent, &mut best);
    }
    let (cost, at, bin) = best?;
    let bins = &all[at * n_bins..][..n_bins];
    let left = bins[..=bin].iter().fold(Bin::EMPTY, |acc, b| acc.merge(b));
    let right = bins[bin + 1..].iter().rev().fold(Bin::EMPTY, |acc, b| acc.merge(b));
    Some((cost, Best { axis: axes[at], bin, left, right }))
}

/// Sweeps the splits between `bins` (those of axis place `at`) for the SAH, keeping in `best`
/// the least cost `(cost, at, bin)`: a cost below the best so far wins (ties to the lower axis and
/// bin).
fn sweep<V: Vector>(at: usize, bins: &[Bin], parent: f32, best: &mut Option<(f32, usize, usize)>) {
    let n_bins = bins.len();
    // Sweep from the right: the measure, count and test cost of bins b.. .
    let mut right_area = [0.0f32; BINS];
    let mut right_count = [0u32; BINS];
    let mut right_cost = [0.0f32; BINS];
    let mut acc = Bin::EMPTY;
    for b in (1..n_bins).rev() {
        acc = acc.merge(&bins[b]);
        right_area[b] = surface::<V>(acc.lo, acc.hi);
        right_count[b] = acc.count;
        right_cost[b] = acc.cost;
    }
    let mut left = Bin::EMPTY;
    for b in 0..n_bins - 1 {
        left = left.merge(&bins[b]);
        if left.count == 0 || right_count[b + 1] == 0 {
            continue;
        }
        let cost = if parent > 0.0 {
            C_TRAV_F32
                + (surface::<V>(left.lo, left.hi) * left.cost + right_area[b + 1] * right_cost[b + 1])
                    / parent
        } else {
            // A flat or point-like group: every box has measure 0; split evenly.
            C_TRAV_F32 + left.cost.max(right_cost[b + 1])
        };
        if best.is_none_or(|x| cost < x.0) {
            *best = Some((cost, at, b));
        }
    }
}

/// Splits `items` at its middle, by doubled centroid along `axis` then by index, with both
/// sides' groups.
fn median<V: Vector>(items: &mut [Record], axis: usize) -> (usize, Group, Group) {
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| {
        a.centroid2()[axis].total_cmp(&b.centroid2()[axis]).then(a.prim.cmp(&b.prim))
    });
    let (left, right) = items.split_at(mid);
    (mid, <Record as Split<V>>::group(left), <Record as Split<V>>::group(right))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn a_record_holds_its_box_and_takes_32_bytes() {
        assert_eq!(std::mem::size_of::<Record>(), 32);
        let b = Aabb::new(DVec3::new(0.1, -1e-30, 1.0), DVec3::new(0.3, 2.0 / 3.0, 1e30));
        let r = Record::new(&b, 7, 1.0).unwrap();
        for a in 0..3 {
            assert!(f64::from(r.min[a]) <= b.min[a] && b.max[a] <= f64::from(r.max[a]), "axis {a}: {r:?}");
        }
        let far = Aabb::new(DVec3::ZERO, DVec3::splat(1e39));
        assert_eq!(Record::new(&far, 0, 1.0), None, "beyond f32: the exact build");
    }

    #[test]
    fn the_scalar_bin_and_the_threshold_agree_with_the_lanes() {
        // Centroid ranges with many digits, crossing zero, tiny and huge; every bin count.
        let ranges = [(0.1f32, 0.7f32), (-3.3, 2.9), (-1e-30, 1e-30), (1e20, 3e20), (5.0, 5.000_01)];
        for (lo, hi) in ranges {
            for n_bins in [4usize, 8, BINS] {
                let scale = n_bins as f32 / (hi - lo);
                let last = n_bins as f32 - 1.0;
                let lanes = Vec3A::new(lo, lo, lo);
                let thresholds: Vec<f32> = (0..n_bins).map(|b| last_of_bin(b, lo, hi, scale, last)).collect();
                for k in 0..=1000 {
                    let c = lo + (hi - lo) * (k as f32 / 1000.0);
                    let c = c.clamp(lo, hi);
                    let bin = bin_on_axis(c, lo, scale, last);
                    assert_eq!(
                        bin,
                        bins_of(Vec3A::splat(c), lanes, Vec3A::splat(scale), n_bins)[1],
                        "{c} in [{lo}, {hi}]"
                    );
                    for (b, &t) in thresholds.iter().enumerate() {
                        assert_eq!(bin <= b, c <= t, "{c}, bin {b} ends at {t}");
                    }
                }
                // Each threshold is the last coordinate of its side: the next f32 goes right.
                for (b, &t) in thresholds.iter().enumerate() {
                    assert!(bin_on_axis(t, lo, scale, last) <= b);
                    assert!(
                        t.to_bits() == hi.to_bits() || bin_on_axis(t.next_up(), lo, scale, last) > b,
                        "bin {b}: {t}"
                    );
                }
            }
        }
    }
}
