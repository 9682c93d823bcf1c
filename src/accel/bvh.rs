//! The bounding volume hierarchy (algorithm.md §9.3 "BVH"): leaves hold a few primitives, inner
//! nodes the box of their two children; a ray that misses a node's box skips its whole subtree.
//!
//! **Build** (deterministic: the same scene gives the same tree on any machine and any number
//! of threads): top-down, binned surface-area heuristic. At each node the primitives' centroids
//! are sorted into [`BINS`] equal bins along each axis; the split between bins minimising
//! `C_trav + (S(L)·N_L + S(R)·N_R)/S(P)` (S: surface area in 3D, perimeter in 2D; one object
//! test costs 1, a node visit [`C_TRAV`]) wins, ties to the lower axis and bin. A node becomes a
//! leaf when it holds one primitive, or at most [`MAX_LEAF`] and no split beats testing them
//! all. Below depth [`BALANCE_DEPTH`], or when every centroid coincides, the split is at the
//! median (by centroid, then by index), which bounds the depth by `BALANCE_DEPTH + 33`.
//!
//! **Traversal**: front to back. Both children's boxes are tested (`node_visit` events, one
//! node test each); the nearer is visited first, the farther kept on a stack with its entry
//! `t_in`; a node is skipped when its entry lies beyond the best hit so far ([`super::beyond`]),
//! so the walk stops as soon as the nearest hit is closer than the next node.

use super::{beyond, prim_bounds, Prim, Visitor};
use crate::bounds::aabb::Aabb;
use crate::bounds::BoundHit;
use crate::geom::ray::Ray;
use crate::geom::slab::RecipRay;
use crate::geom::Vector;
use crate::record::event::Event;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::Dim;
use crate::trace::stats::Stats;

/// Centroid bins per axis.
pub const BINS: usize = 12;
/// The most primitives a leaf holds when the SAH prefers not to split.
pub const MAX_LEAF: usize = 4;
/// The cost of visiting a node, in object tests.
pub const C_TRAV: f64 = 0.5;
/// From this depth on, splits are at the median.
pub const BALANCE_DEPTH: u32 = 40;

/// A node of the tree as built: a leaf over `prims[start .. start + count]`, or (count 0) an
/// inner node whose children are the next node and node `start`. Node numbers in `node_visit`
/// events are indices in this depth-first order (the root is 0).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Built<V> {
    bounds: Aabb<V>,
    start: u32,
    count: u32,
}

/// A child as the traversal sees it: a leaf over `prims[start .. start + count]` (count > 0)
/// or the inner node `nodes[start]` (count 0); `id` is its number in depth-first order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Link {
    start: u32,
    count: u32,
    id: u32,
}

/// An inner node with both children's boxes side by side, so one read gives both tests.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node<V> {
    boxes: [Aabb<V>; 2],
    links: [Link; 2],
}

/// A built BVH: the root's box and link, inner nodes, primitives in leaf order.
#[derive(Clone, Debug)]
pub struct Bvh<V> {
    root_box: Aabb<V>,
    root: Link,
    nodes: Vec<Node<V>>,
    prims: Vec<Prim>,
}

/// What the builder works on.
struct Builder<V> {
    boxes: Vec<Aabb<V>>,
    centroids: Vec<V>,
    order: Vec<u32>,
    nodes: Vec<Built<V>>,
}

thread_local! {
    /// The traversal stack of this thread's walks: pending `(link, depth, t_in)`, reused so that
    /// a walk neither allocates nor clears a large array.
    static STACK: std::cell::RefCell<Vec<(Link, u32, f64)>> = const { std::cell::RefCell::new(Vec::new()) };
}

impl<V: Dim> Bvh<V> {
    /// Builds the tree over `prims` (their boxes from the scene).
    #[must_use]
    pub fn build(scene: &Scene<V>, prims: Vec<Prim>) -> Self {
        let boxes: Vec<Aabb<V>> = prims.iter().map(|&p| prim_bounds(scene, p)).collect();
        Self::from_boxes(prims, boxes)
    }

    /// Builds the tree over primitives with the given boxes.
    #[must_use]
    pub fn from_boxes(prims: Vec<Prim>, boxes: Vec<Aabb<V>>) -> Self {
        let n = prims.len();
        let empty = Link { start: 0, count: 0, id: 0 };
        if n == 0 {
            return Self { root_box: Aabb::empty(), root: empty, nodes: Vec::new(), prims };
        }
        let (order, built) = {
            let centroids = boxes.iter().map(Aabb::centroid).collect();
            let order = (0..to_u32(n)).collect();
            let mut b = Builder { boxes, centroids, order, nodes: Vec::with_capacity(n) };
            b.node(0, n, 0);
            (b.order, b.nodes)
        };
        let prims = order.iter().map(|&i| prims[i as usize]).collect();
        // Inner nodes get consecutive indices in depth-first order.
        let mut inner_index = vec![0u32; built.len()];
        let mut count = 0;
        for (i, b) in built.iter().enumerate() {
            if b.count == 0 {
                inner_index[i] = count;
                count += 1;
            }
        }
        let link = |j: usize| {
            let b = built[j];
            let start = if b.count > 0 { b.start } else { inner_index[j] };
            Link { start, count: b.count, id: to_u32(j) }
        };
        let nodes = (0..built.len())
            .filter(|&i| built[i].count == 0)
            .map(|i| {
                let (l, r) = (i + 1, built[i].start as usize);
                Node { boxes: [built[l].bounds, built[r].bounds], links: [link(l), link(r)] }
            })
            .collect();
        Self { root_box: built[0].bounds, root: link(0), nodes, prims }
    }

    /// Number of nodes (leaves and inner nodes).
    #[must_use]
    pub fn node_count(&self) -> usize {
        if self.prims.is_empty() {
            0
        } else {
            2 * self.nodes.len() + 1
        }
    }

    /// One child's box against the ray: counted, recorded.
    #[inline(always)]
    fn test_box<R: Recorder<V>>(
        bounds: &Aabb<V>,
        id: u32,
        depth: u32,
        ray: &RecipRay<V>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> BoundHit {
        stats.tests.node += 1;
        let h = bounds.cull(ray);
        rec.event(|| Event::NodeVisit {
            structure: "bvh",
            node: id as usize,
            depth,
            t_in: h.t_in,
            t_out: h.t_out,
        });
        h
    }

    /// Front-to-back traversal, handing the primitives of every leaf reached to the visitor.
    pub fn walk<R: Recorder<V>, W: Visitor<V>>(
        &self,
        ray: &Ray<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        if self.prims.is_empty() {
            return;
        }
        let r = RecipRay::new(ray);
        let root = Self::test_box(&self.root_box, 0, 0, &r, stats, rec);
        if !root.hit {
            return;
        }
        STACK.with(|cell| {
            let mut stack = cell.borrow_mut();
            stack.clear();
            stack.push((self.root, 0, root.t_in));
            while let Some((link, depth, t_in)) = stack.pop() {
                if beyond(t_in, visitor.bound()) {
                    continue;
                }
                if link.count > 0 {
                    let start = link.start as usize;
                    for p in &self.prims[start..start + link.count as usize] {
                        if visitor.visit(*p, stats, rec) {
                            return;
                        }
                    }
                    continue;
                }
                let node = &self.nodes[link.start as usize];
                let [l, rr] = node.links;
                let hl = Self::test_box(&node.boxes[0], l.id, depth + 1, &r, stats, rec);
                let hr = Self::test_box(&node.boxes[1], rr.id, depth + 1, &r, stats, rec);
                // Push the farther first, so the nearer is popped first (a tie keeps left first).
                let (near, far, h_near, h_far) =
                    if hr.t_in < hl.t_in { (rr, l, hr, hl) } else { (l, rr, hl, hr) };
                for (child, h) in [(far, h_far), (near, h_near)] {
                    if h.hit && !beyond(h.t_in, visitor.bound()) {
                        stack.push((child, depth + 1, h.t_in));
                    }
                }
            }
        });
    }
}

impl<V: Vector> Builder<V> {
    /// Builds the node over `order[lo..hi]` and its subtree; returns nothing, the node is pushed
    /// at the index it had when called.
    fn node(&mut self, lo: usize, hi: usize, depth: u32) {
        let index = self.nodes.len();
        let bounds = self.order[lo..hi].iter().fold(Aabb::empty(), |b, &i| b.union(&self.boxes[i as usize]));
        let leaf = Built { bounds, start: to_u32(lo), count: to_u32(hi - lo) };
        self.nodes.push(leaf);
        let count = hi - lo;
        if count == 1 {
            return;
        }
        let Some(mid) = self.split(lo, hi, depth, &bounds) else {
            return;
        };
        self.node(lo, mid, depth + 1);
        let right = self.nodes.len();
        self.node(mid, hi, depth + 1);
        self.nodes[index] = Built { bounds, start: to_u32(right), count: 0 };
    }

    /// Where to split `order[lo..hi]` (reordering it), or `None` for a leaf.
    fn split(&mut self, lo: usize, hi: usize, depth: u32, bounds: &Aabb<V>) -> Option<usize> {
        let count = hi - lo;
        let cbox = Aabb::around(self.order[lo..hi].iter().map(|&i| self.centroids[i as usize]));
        let axis = cbox.longest_axis();
        if depth >= BALANCE_DEPTH || !(cbox.extent()[axis] > 0.0) {
            return (count > MAX_LEAF || depth >= BALANCE_DEPTH).then(|| self.median(lo, hi, axis));
        }
        let (cost, axis, bin) = self.best_bin_split(lo, hi, &cbox, bounds);
        if count <= MAX_LEAF && cost >= count as f64 {
            return None;
        }
        // Partition by bin: those left of the split first.
        let (cmin, scale) = bin_map(&cbox, axis);
        let mut mid = lo;
        for k in lo..hi {
            let c = self.centroids[self.order[k] as usize][axis];
            if bin_of(c, cmin, scale) <= bin {
                self.order.swap(mid, k);
                mid += 1;
            }
        }
        if mid == lo || mid == hi {
            return Some(self.median(lo, hi, axis));
        }
        Some(mid)
    }

    /// The best binned SAH split over every axis: `(cost, axis, last bin of the left side)`.
    fn best_bin_split(&self, lo: usize, hi: usize, cbox: &Aabb<V>, bounds: &Aabb<V>) -> (f64, usize, usize) {
        let parent = bounds.surface();
        let mut best = (f64::INFINITY, 0, 0);
        for axis in 0..V::DIM {
            if !(cbox.extent()[axis] > 0.0) {
                continue;
            }
            let (cmin, scale) = bin_map(cbox, axis);
            let mut counts = [0usize; BINS];
            let mut boxes = [Aabb::empty(); BINS];
            for &i in &self.order[lo..hi] {
                let b = bin_of(self.centroids[i as usize][axis], cmin, scale);
                counts[b] += 1;
                boxes[b] = boxes[b].union(&self.boxes[i as usize]);
            }
            // Sweep from the right: the area and count of bins b+1.. .
            let mut right_area = [0.0; BINS];
            let mut right_count = [0usize; BINS];
            let (mut acc, mut n) = (Aabb::empty(), 0);
            for b in (1..BINS).rev() {
                acc = acc.union(&boxes[b]);
                n += counts[b];
                right_area[b] = acc.surface();
                right_count[b] = n;
            }
            let (mut acc, mut n) = (Aabb::empty(), 0);
            for b in 0..BINS - 1 {
                acc = acc.union(&boxes[b]);
                n += counts[b];
                let (nl, nr) = (n, right_count[b + 1]);
                if nl == 0 || nr == 0 {
                    continue;
                }
                let cost = if parent > 0.0 {
                    C_TRAV + (acc.surface() * nl as f64 + right_area[b + 1] * nr as f64) / parent
                } else {
                    // A flat or point-like group: every box has measure 0; split evenly.
                    C_TRAV + nl.max(nr) as f64
                };
                if cost < best.0 {
                    best = (cost, axis, b);
                }
            }
        }
        best
    }

    /// Splits `order[lo..hi]` at its middle, by centroid along `axis` then by index.
    fn median(&mut self, lo: usize, hi: usize, axis: usize) -> usize {
        let mid = lo + (hi - lo) / 2;
        let centroids = &self.centroids;
        self.order[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
            centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis]).then(a.cmp(&b))
        });
        mid
    }
}

/// The bin map of an axis: `(min, BINS / extent)`.
fn bin_map<V: Vector>(cbox: &Aabb<V>, axis: usize) -> (f64, f64) {
    (cbox.min[axis], BINS as f64 / cbox.extent()[axis])
}

/// The bin of a centroid coordinate, clamped to the last bin.
#[inline]
fn bin_of(c: f64, cmin: f64, scale: f64) -> usize {
    // A non-negative value below BINS: truncation is the floor.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let b = ((c - cmin) * scale).max(0.0) as usize;
    b.min(BINS - 1)
}

fn to_u32(x: usize) -> u32 {
    u32::try_from(x).expect("fewer than 2^32 primitives")
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn cube(i: u32) -> Aabb<DVec3> {
        let p = DVec3::new(f64::from(i % 10), f64::from(i / 10 % 10), f64::from(i / 100));
        Aabb::new(p, p + DVec3::splat(0.5))
    }

    #[test]
    fn build_is_deterministic_and_covers_every_primitive_once() {
        let prims: Vec<Prim> = (0..1000).map(|i| Prim { object: i, part: 0 }).collect();
        let boxes: Vec<Aabb<DVec3>> = (0..1000).map(cube).collect();
        let a = Bvh::from_boxes(prims.clone(), boxes.clone());
        let b = Bvh::from_boxes(prims, boxes);
        assert_eq!(a.nodes, b.nodes);
        assert_eq!(a.prims, b.prims);
        let mut seen: Vec<u32> = a.prims.iter().map(|p| p.object).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..1000).collect::<Vec<_>>());
        // Every leaf is small and every child box lies inside its parent's.
        let mut parents = vec![a.root_box; a.nodes.len()];
        for (i, n) in a.nodes.iter().enumerate() {
            for (b, l) in n.boxes.iter().zip(n.links) {
                assert_eq!(parents[i].union(b), parents[i]);
                if l.count > 0 {
                    assert!(l.count as usize <= MAX_LEAF);
                } else {
                    parents[l.start as usize] = *b;
                }
            }
        }
    }

    #[test]
    fn identical_boxes_split_at_the_median() {
        let prims: Vec<Prim> = (0..100).map(|i| Prim { object: i, part: 0 }).collect();
        let boxes = vec![Aabb::new(DVec3::ZERO, DVec3::ONE); 100];
        let t = Bvh::from_boxes(prims, boxes);
        assert!(t.nodes.iter().flat_map(|n| n.links).all(|l| l.count as usize <= MAX_LEAF));
    }
}
