//! The regular grid (algorithm.md §9.2 "Regular grid", §11 "The voxel DDA"): the scene's box
//! cut into equal cells, each listing the primitives whose box overlaps it, walked cell by cell
//! by the DDA of Amanatides & Woo (1987), one code for 2D and 3D.
//!
//! The resolution aims at [`CELLS_PER_PRIM`] cells per primitive ([`heuristic_resolution`]),
//! unless `--grid` gives it. A primitive goes into every cell its slightly grown box overlaps, so
//! a box on a cell boundary is in both cells (numerics I7). The walk ([`Grid::walk`]) stops once
//! the best hit lies within the current cell, the lecture's pitfall (I6), and steps on ties in
//! the order x, y, z (I3).

use super::{object_ref, prim_bounds, Mailbox, Prim, Visitor};
use crate::bounds::aabb::Aabb;
use crate::geom::ray::Ray;
use crate::geom::slab::{box_crossing, culling_hit, widen_exit};
use crate::geom::Vector;
use crate::record::event::Event;
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::Dim;

/// λ, the cells per primitive the heuristic aims at.
pub const CELLS_PER_PRIM: f64 = 4.0;
/// The most cells along one axis chosen by the heuristic.
pub const MAX_CELLS_PER_AXIS: usize = 256;
/// The most cells a grid may have (`--grid` included).
pub const MAX_CELLS: usize = 1 << 24;

/// A built grid: cell lists in compressed rows (`start[c] .. start[c + 1]` of `items`).
#[derive(Clone, Debug)]
pub struct Grid<V> {
    bounds: Aabb<V>,
    n: [usize; 3],
    width: V,
    inv_width: V,
    start: Vec<u32>,
    items: Vec<u32>,
    prims: Vec<Prim>,
}

/// The heuristic resolution for `count` primitives in `bounds`: about [`CELLS_PER_PRIM`]·N
/// cells, as cubic as the box allows. Along each axis of non-zero extent `n_a = round(e_a·s)`
/// with `s = (λ·N / Π e_a)^(1/D)` over those D axes, clamped to `[1, MAX_CELLS_PER_AXIS]`; an
/// axis of zero extent (a flat scene) gets one cell.
#[must_use]
pub fn heuristic_resolution<V: Vector>(bounds: &Aabb<V>, count: usize) -> Vec<usize> {
    let e = bounds.extent();
    let axes: Vec<usize> = (0..V::DIM).filter(|&a| e[a] > 0.0).collect();
    if axes.is_empty() || count == 0 {
        return vec![1; V::DIM];
    }
    let volume: f64 = axes.iter().map(|&a| e[a]).product();
    let s = (CELLS_PER_PRIM * count as f64 / volume).powf(1.0 / axes.len() as f64);
    (0..V::DIM)
        .map(|a| {
            if e[a] > 0.0 {
                // Finite and ≥ 1 after the clamp.
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let n = (e[a] * s).round().clamp(1.0, MAX_CELLS_PER_AXIS as f64) as usize;
                n
            } else {
                1
            }
        })
        .collect()
}

impl<V: Dim> Grid<V> {
    /// The grid over `prims`, `resolution` cells per axis or the heuristic's.
    #[must_use]
    pub fn build(scene: &Scene<V>, prims: &[Prim], resolution: Option<&[usize]>) -> Self {
        let boxes: Vec<Aabb<V>> = prims.iter().map(|&p| prim_bounds(scene, p)).collect();
        let bounds = boxes.iter().fold(Aabb::empty(), |b, x| b.union(x));
        let n = resolution.map_or_else(|| heuristic_resolution(&bounds, prims.len()), <[usize]>::to_vec);
        Self::from_boxes(prims.to_vec(), &boxes, bounds, &n)
    }

    /// The grid of `n` cells per axis over `bounds`, holding `prims` with their boxes.
    ///
    /// # Panics
    /// If `n` has not one entry per axis.
    #[must_use]
    pub fn from_boxes(prims: Vec<Prim>, boxes: &[Aabb<V>], bounds: Aabb<V>, n: &[usize]) -> Self {
        assert_eq!(n.len(), V::DIM, "one cell count per axis");
        let mut cells = [1usize; 3];
        for a in 0..V::DIM {
            cells[a] = n[a].max(1);
        }
        let e = bounds.extent();
        let (mut width, mut inv_width) = (V::ZERO, V::ZERO);
        for a in 0..V::DIM {
            width[a] = e[a] / cells[a] as f64;
            inv_width[a] = if width[a] > 0.0 { 1.0 / width[a] } else { 0.0 };
        }
        let mut g = Self { bounds, n: cells, width, inv_width, start: Vec::new(), items: Vec::new(), prims };
        if g.prims.is_empty() || bounds.is_empty() {
            return g;
        }
        let total: usize = cells[..V::DIM].iter().product();
        let mut counts = vec![0u32; total + 1];
        let ranges: Vec<([usize; 3], [usize; 3])> = boxes.iter().map(|b| g.cell_range(b)).collect();
        for pass in 0..2 {
            for (k, &(lo, hi)) in ranges.iter().enumerate() {
                let id = u32::try_from(k).expect("fewer than 2^32 primitives");
                each_cell(cells, lo, hi, |c| {
                    if pass == 0 {
                        counts[c] += 1;
                    } else {
                        counts[c] -= 1;
                        g.items[counts[c] as usize] = id;
                    }
                });
            }
            if pass == 0 {
                // Prefix sums: counts[c] becomes the end of cell c's list, filled backwards.
                let mut sum = 0;
                for c in &mut counts {
                    sum += *c;
                    *c = sum;
                }
                g.items = vec![0; sum as usize];
            }
        }
        // Now counts[c] is the start of cell c; counts[total] the end of the last.
        counts[total] = u32::try_from(g.items.len()).expect("fewer than 2^32 cell entries");
        g.start = counts;
        // Lists in primitive order, so that a cell's tests (and its events) read in index order.
        for c in 0..total {
            g.items[g.start[c] as usize..g.start[c + 1] as usize].sort_unstable();
        }
        g
    }

    /// The grid's box.
    #[must_use]
    pub fn bounds(&self) -> Aabb<V> {
        self.bounds
    }

    /// The cells per axis.
    #[must_use]
    pub fn resolution(&self) -> Vec<usize> {
        self.n[..V::DIM].to_vec()
    }

    /// The cell range `[lo, hi]` per axis that a box overlaps, grown by the insertion slack: the
    /// (closed) box grown by `10⁻⁹` of a cell plus `2⁻³⁶` of the grid's largest coordinate. So a
    /// box touching a cell boundary is in both cells (numerics I7), and a primitive that is in no
    /// visited cell lies strictly beyond them by more than any rounding of its t.
    fn cell_range(&self, b: &Aabb<V>) -> ([usize; 3], [usize; 3]) {
        let m = self.bounds.min.max_abs().max(self.bounds.max.max_abs());
        let world_pad = m * (1.0 / (1u64 << 36) as f64);
        let (mut lo, mut hi) = ([0; 3], [0; 3]);
        for a in 0..V::DIM {
            let pad = 1e-9 + world_pad * self.inv_width[a];
            let f_lo = (b.min[a] - self.bounds.min[a]) * self.inv_width[a] - pad;
            let f_hi = (b.max[a] - self.bounds.min[a]) * self.inv_width[a] + pad;
            lo[a] = self.clamp_cell(f_lo.floor(), a);
            hi[a] = self.clamp_cell(f_hi.floor(), a);
        }
        (lo, hi)
    }

    /// A cell coordinate clamped to `[0, n_a − 1]` (NaN goes to 0).
    fn clamp_cell(&self, f: f64, a: usize) -> usize {
        let top = (self.n[a] - 1) as f64;
        // Clamped into [0, n − 1] first, so the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let c = if f >= 0.0 { f.min(top) as usize } else { 0 };
        c
    }

    fn index(&self, c: [usize; 3]) -> usize {
        cell_index(self.n, c)
    }

    /// The Amanatides–Woo walk, handing each visited cell's untested primitives to the visitor.
    ///
    /// Clip the ray to the grid's box (exit widened, §11), canonicalise `−0` to `+0` (numerics
    /// I2), find the start cell from the entry point, clamped to the grid (I4). Per axis `tMax` is
    /// the t of the next boundary and `tDelta = w/|D_a|` (∞ on a parallel axis, I1). Then
    /// repeatedly: test the cell's primitives not yet tested by this ray (the mailbox); stop once
    /// the best hit lies within the cell (`t ≤` the cell's exit, the lecture's pitfall, I6) or the
    /// ray leaves the grid; else step along the axis with the smallest tMax, **ties in the order
    /// x, y, z** (algorithm.md §11; pbrt steps the later axis, numerics I3), `tMax += tDelta`. At
    /// most `Σ n_a + 3` cells are visited, so even a NaN ray ends (I9).
    #[inline(never)]
    pub fn walk<R: Recorder<V>, W: Visitor<V>>(
        &self,
        scene: &Scene<V>,
        ray: &Ray<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        if self.start.is_empty() {
            return;
        }
        // −0 + 0 = +0: a negative zero must not choose a step (numerics I2).
        let mut dir = ray.dir;
        for a in 0..V::DIM {
            dir[a] += 0.0;
        }
        let o = ray.origin;
        let clip = box_crossing(&Ray::new(o, dir), self.bounds.min, self.bounds.max, |_, _| {});
        if !culling_hit(clip.t_in, clip.t_out) {
            return;
        }
        let t_exit_grid = widen_exit(clip.t_out);
        let t0 = clip.t_in.max(0.0);
        let entry = o + dir * t0;
        let mut cell = [0usize; 3];
        let mut step = [0i64; 3];
        let mut t_max = [f64::INFINITY; 3];
        let mut t_delta = [f64::INFINITY; 3];
        for a in 0..V::DIM {
            cell[a] = self.clamp_cell(((entry[a] - self.bounds.min[a]) * self.inv_width[a]).floor(), a);
            let boundary = |k: usize| self.bounds.min[a] + k as f64 * self.width[a];
            if dir[a] > 0.0 {
                step[a] = 1;
                t_max[a] = (boundary(cell[a] + 1) - o[a]) / dir[a];
                t_delta[a] = self.width[a] / dir[a];
            } else if dir[a] < 0.0 {
                step[a] = -1;
                t_max[a] = (boundary(cell[a]) - o[a]) / dir[a];
                t_delta[a] = -self.width[a] / dir[a];
            }
        }
        let cap = self.n.iter().sum::<usize>() + 3;
        Mailbox::with(self.prims.len(), |mailbox| {
            for _ in 0..cap {
                // The axis of the smallest tMax; strict `<` keeps the first on a tie (x, y, z).
                let axis = (1..V::DIM).fold(0, |best, a| if t_max[a] < t_max[best] { a } else { best });
                let cell_exit = t_max[axis].min(t_exit_grid);
                stats.tests.voxel += 1;
                let c = self.index(cell);
                let mut tested = Vec::new();
                let mut done = false;
                for &k in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    if !mailbox.first_visit(k as usize) {
                        continue;
                    }
                    let prim = self.prims[k as usize];
                    if R::ENABLED {
                        tested.push(prim);
                    }
                    if visitor.visit(prim, stats, rec) {
                        done = true;
                        break;
                    }
                }
                rec.event(|| Event::VoxelStep {
                    cell: cell[..V::DIM].iter().map(|&x| i64::try_from(x).unwrap_or(i64::MAX)).collect(),
                    t_max: t_max[..V::DIM].to_vec(),
                    t_delta: t_delta[..V::DIM].to_vec(),
                    objects: tested.iter().map(|&p| object_ref(scene, p)).collect(),
                });
                // The pitfall: a hit counts only once it lies within the current cell.
                if done || visitor.bound() <= cell_exit || t_max[axis] >= t_exit_grid {
                    return;
                }
                let next = i64::try_from(cell[axis]).unwrap_or(i64::MAX) + step[axis];
                match usize::try_from(next) {
                    Ok(x) if x < self.n[axis] => cell[axis] = x,
                    _ => return,
                }
                t_max[axis] += t_delta[axis];
            }
        });
    }
}

/// The row-major index of a cell (x fastest).
fn cell_index(n: [usize; 3], c: [usize; 3]) -> usize {
    (c[2] * n[1] + c[1]) * n[0] + c[0]
}

/// Calls `f` with the index of every cell in the range `[lo, hi]` (inclusive, per axis).
fn each_cell(n: [usize; 3], lo: [usize; 3], hi: [usize; 3], mut f: impl FnMut(usize)) {
    for z in lo[2]..=hi[2] {
        for y in lo[1]..=hi[1] {
            for x in lo[0]..=hi[0] {
                f(cell_index(n, [x, y, z]));
            }
        }
    }
}
