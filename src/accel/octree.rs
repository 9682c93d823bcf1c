//! The octree, a quadtree in 2D (algorithm.md §9.2 "Adaptive (octree)"): the scene's box, made
//! a cube (a square), split into 2^D equal children recursively; a primitive is listed in every
//! leaf its (closed) box overlaps.
//!
//! **Stopping** (algorithm.md §9 and §11): a node stays a leaf when it holds at most one
//! primitive, at depth [`MAX_DEPTH`] = 8, or when splitting would separate nothing (every child
//! that holds primitives would hold all of the node's: overlapping objects can never be
//! separated); and, so that overlapping objects cannot fill memory, once the tree has
//! [`NODES_PER_PRIM`]·N + 4096 nodes (the tree is built breadth first, so the budget ends the
//! deepest level evenly).
//!
//! **Traversal**: from the root, a node whose box the ray misses is skipped with its subtree;
//! the children a ray enters are visited in the order it enters them (by `t_in`, ties by child
//! index), each skipped when it starts beyond the best hit ([`super::beyond`]); a primitive in
//! several leaves is tested once (the mailbox). `node_visit` events, one per node box tested.

use super::{beyond, node_skip, node_visit, prim_bounds, Mailbox, Prim, TreeNode, Visitor};
use crate::bounds::aabb::Aabb;
use crate::geom::ray::Ray;
use crate::geom::slab::RecipRay;
use crate::geom::Vector;
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::Dim;

/// The deepest level (the root is level 0).
pub const MAX_DEPTH: u32 = 8;
/// The node budget per primitive.
pub const NODES_PER_PRIM: usize = 64;

/// A node: a leaf over `items[start .. start + count]` or an inner node whose 2^D children are
/// consecutive from `first_child`.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Leaf { start: u32, count: u32 },
    Inner { first_child: u32 },
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Node<V> {
    bounds: Aabb<V>,
    kind: Kind,
}

/// A built octree (quadtree).
#[derive(Clone, Debug)]
pub struct Octree<V> {
    nodes: Vec<Node<V>>,
    items: Vec<u32>,
    prims: Vec<Prim>,
}

impl<V: Dim> Octree<V> {
    /// The tree over `prims`.
    #[must_use]
    pub fn build(scene: &Scene<V>, prims: &[Prim]) -> Self {
        let boxes: Vec<Aabb<V>> = prims.iter().map(|&p| prim_bounds(scene, p)).collect();
        Self::from_boxes(prims.to_vec(), &boxes)
    }

    /// The tree over primitives with the given boxes.
    #[must_use]
    pub fn from_boxes(prims: Vec<Prim>, boxes: &[Aabb<V>]) -> Self {
        let mut tree = Self { nodes: Vec::new(), items: Vec::new(), prims };
        let scene_box = boxes.iter().fold(Aabb::empty(), |b, x| b.union(x));
        if scene_box.is_empty() {
            return tree;
        }
        // A cube around the scene's box (a square in 2D).
        let half = (0..V::DIM).fold(0.0, |m: f64, a| m.max(scene_box.extent()[a])) * 0.5;
        let c = scene_box.centroid();
        let root = Aabb::new(c - V::splat(half), c + V::splat(half)).union(&scene_box);
        let all: Vec<u32> = (0..u32::try_from(boxes.len()).expect("fewer than 2^32 primitives")).collect();
        let budget = NODES_PER_PRIM * boxes.len() + 4096;
        tree.nodes.push(Node { bounds: root, kind: Kind::Leaf { start: 0, count: 0 } });
        // Breadth first, so that a budget that runs out stops the deepest level everywhere
        // rather than whole late branches.
        let mut queue = std::collections::VecDeque::from([(0usize, all, 0u32)]);
        while let Some((index, list, depth)) = queue.pop_front() {
            queue.extend(tree.fill(index, &list, boxes, depth, budget));
        }
        tree
    }

    /// Makes node `index` a leaf over `list`, or splits it and returns its children's work.
    fn fill(
        &mut self,
        index: usize,
        list: &[u32],
        boxes: &[Aabb<V>],
        depth: u32,
        budget: usize,
    ) -> Vec<(usize, Vec<u32>, u32)> {
        let bounds = self.nodes[index].bounds;
        let children = 1usize << V::DIM;
        let mut split = list.len() > 1 && depth < MAX_DEPTH && self.nodes.len() + children <= budget;
        let mut lists = Vec::new();
        if split {
            lists = (0..children)
                .map(|k| {
                    let child = child_box(&bounds, k);
                    list.iter().copied().filter(|&i| boxes[i as usize].overlaps(&child)).collect::<Vec<u32>>()
                })
                .collect();
            // Nothing separated: every non-empty child would hold them all.
            split = lists.iter().any(|l: &Vec<u32>| !l.is_empty() && l.len() < list.len());
        }
        if !split {
            let start = u32::try_from(self.items.len()).expect("fewer than 2^32 entries");
            self.items.extend_from_slice(list);
            let count = u32::try_from(list.len()).expect("fewer than 2^32 entries");
            self.nodes[index].kind = Kind::Leaf { start, count };
            return Vec::new();
        }
        let first = self.nodes.len();
        for k in 0..children {
            self.nodes.push(Node { bounds: child_box(&bounds, k), kind: Kind::Leaf { start: 0, count: 0 } });
        }
        self.nodes[index].kind =
            Kind::Inner { first_child: u32::try_from(first).expect("fewer than 2^32 nodes") };
        lists.into_iter().enumerate().map(|(k, l)| (first + k, l, depth + 1)).collect()
    }

    /// Number of nodes.
    #[must_use]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The nodes for drawing, by their index (the number `node_visit` events give them).
    #[must_use]
    pub fn tree(&self) -> Vec<TreeNode<V>> {
        let mut depth = vec![0u32; self.nodes.len()];
        let mut out = Vec::with_capacity(self.nodes.len());
        for (index, node) in self.nodes.iter().enumerate() {
            let (children, prims) = match node.kind {
                Kind::Leaf { start, count } => {
                    let items = &self.items[start as usize..(start + count) as usize];
                    (Vec::new(), items.iter().map(|&k| self.prims[k as usize]).collect())
                }
                Kind::Inner { first_child } => {
                    let first = first_child as usize;
                    let children: Vec<usize> = (first..first + (1 << V::DIM)).collect();
                    for &c in &children {
                        depth[c] = depth[index] + 1;
                    }
                    (children, Vec::new())
                }
            };
            out.push(TreeNode { bounds: node.bounds, depth: depth[index], children, prims });
        }
        out
    }

    /// Ordered traversal, handing each reached leaf's untested primitives to the visitor.
    #[inline(never)]
    pub fn walk<R: Recorder<V>, W: Visitor<V>>(
        &self,
        ray: &Ray<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let r = RecipRay::new(ray);
        let b = &self.nodes[0].bounds;
        if !node_visit("octree", r.box_interval(b.min, b.max), (0, 0), stats, rec).hit {
            return;
        }
        Mailbox::with(self.prims.len(), |mailbox| {
            self.visit(0, 0, &r, visitor, stats, rec, mailbox);
        });
    }

    /// Visits node `index` (its box already hit); true when the search is over.
    #[allow(clippy::too_many_arguments)] // The walk's state, passed down the recursion.
    fn visit<R: Recorder<V>, W: Visitor<V>>(
        &self,
        index: usize,
        depth: u32,
        ray: &RecipRay<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
        mailbox: &mut Mailbox,
    ) -> bool {
        match self.nodes[index].kind {
            Kind::Leaf { start, count } => {
                for &k in &self.items[start as usize..(start + count) as usize] {
                    if mailbox.first_visit(k as usize) && visitor.visit(self.prims[k as usize], stats, rec) {
                        return true;
                    }
                }
                false
            }
            Kind::Inner { first_child } => {
                let mut entered = [(0.0f64, 0usize); 8];
                let mut n = 0;
                for k in 0..1usize << V::DIM {
                    let child = first_child as usize + k;
                    let b = &self.nodes[child].bounds;
                    let h =
                        node_visit("octree", ray.box_interval(b.min, b.max), (child, depth + 1), stats, rec);
                    if h.hit {
                        entered[n] = (h.t_in, child);
                        n += 1;
                    }
                }
                // In the order the ray enters them; ties by child index.
                entered[..n].sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                for (k, &(t_in, child)) in entered[..n].iter().enumerate() {
                    if beyond(t_in, visitor.bound()) {
                        // Sorted by entry: every child from here on lies beyond too.
                        for &(t, c) in &entered[k..n] {
                            node_skip("octree", c, t, visitor.bound(), rec);
                        }
                        break;
                    }
                    if self.visit(child, depth + 1, ray, visitor, stats, rec, mailbox) {
                        return true;
                    }
                }
                false
            }
        }
    }
}

/// Child `k` of a box: bit `a` of k picks the upper half along axis a.
fn child_box<V: Vector>(b: &Aabb<V>, k: usize) -> Aabb<V> {
    let mid = b.centroid();
    let (mut lo, mut hi) = (b.min, mid);
    for a in 0..V::DIM {
        if k >> a & 1 == 1 {
            lo[a] = mid[a];
            hi[a] = b.max[a];
        }
    }
    Aabb::new(lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn cube(c: DVec3, r: f64) -> Aabb<DVec3> {
        Aabb::new(c - DVec3::splat(r), c + DVec3::splat(r))
    }

    #[test]
    fn i8_a_box_on_the_split_plane_is_in_both_children() {
        let boxes = [cube(DVec3::ZERO, 0.1), cube(DVec3::splat(-1.0), 0.1), cube(DVec3::splat(1.0), 0.1)];
        let prims = (0..3).map(|i| Prim { object: i, part: 0 }).collect();
        let t = Octree::from_boxes(prims, &boxes);
        let holding_0 = t
            .nodes
            .iter()
            .filter(|n| match n.kind {
                Kind::Leaf { start, count } => t.items[start as usize..(start + count) as usize].contains(&0),
                Kind::Inner { .. } => false,
            })
            .count();
        assert!(holding_0 >= 8, "the centre box touches all 8 children: {holding_0}");
    }

    #[test]
    fn i8_identical_objects_stop_splitting() {
        let boxes = [cube(DVec3::ZERO, 1.0), cube(DVec3::ZERO, 1.0)];
        let prims = (0..2).map(|i| Prim { object: i, part: 0 }).collect();
        let t = Octree::from_boxes(prims, &boxes);
        assert_eq!(t.node_count(), 1, "nothing to separate: the root is a leaf");
    }
}
