//! The bounding volume hierarchy (algorithm.md §9.3 "BVH"): leaves hold a few primitives, inner
//! nodes the box of their two children; a ray that misses a node's box skips its whole subtree.
//!
//! **Build** (deterministic: the same scene gives the same tree on any machine and any number
//! of threads): top-down, binned surface-area heuristic. At each node the primitives' centroids
//! are sorted into [`BINS`] equal bins along each axis (along the longest axis only for groups
//! of more than [`ALL_AXES_BELOW`]); the split between bins minimising
//! `C_trav + (S(L)·C_L + S(R)·C_R)/S(P)` (S: surface area in 3D, perimeter in 2D; C: the summed
//! test costs of a side's primitives, [`crate::shape::Shape::test_cost`], a triangle test costing
//! 1 and a node visit [`C_TRAV`]) wins, ties to the lower axis and bin. A node becomes a leaf when
//! it holds one primitive, or at most [`MAX_LEAF`] and no split beats testing them all. From depth [`BALANCE_DEPTH`] on, or when every centroid coincides, the split is at the
//! median (by centroid, then by index), which bounds the depth by `BALANCE_DEPTH + 33`. The top
//! levels of large trees build their two subtrees in parallel; the result does not depend on it.
//!
//! **Traversal**: front to back. Both children's boxes are tested (`node_visit` events, one
//! node test each; an inner node stores them side by side, so both are tested in one pass); the
//! nearer is visited first, the farther kept on a stack with its entry `t_in`; a node is skipped
//! when its entry lies beyond the best hit so far ([`super::beyond`]), so the walk stops as soon
//! as the nearest hit is closer than the next node.
//!
//! A tree that is one leaf (a small scene) is visited without the stack.

use super::binned;
use super::wide::{to_open, Binary, Child, WideBvh, WideNode, WIDTH};
use super::{beyond, node_skip, node_visit, prim_bounds, Prim, TreeNode, Visitor};
use crate::bounds::aabb::Aabb;
use crate::geom::ray::Ray;
use crate::geom::slab::RecipRay;
use crate::geom::Vector;
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::Dim;
use arrayvec::ArrayVec;

/// Centroid bins per axis.
pub const BINS: usize = 12;
/// The most primitives a leaf holds when the SAH prefers not to split.
pub const MAX_LEAF: usize = 4;
/// Groups of more primitives than this are binned along their longest axis only.
pub const ALL_AXES_BELOW: usize = 64;
/// The cost of visiting a node (two box tests), in triangle tests (each primitive's own cost is
/// [`crate::shape::Shape::test_cost`]).
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
    /// The render's wide copy of the inner nodes ([`Bvh::widen`]), walked when no recorder
    /// listens.
    wide: Option<WideBvh>,
}

/// A primitive as the builder sees it: its box, its index and the cost of testing it. The
/// builder reorders these records themselves (not indices to them), so every pass reads memory
/// in order; the centroid is the box's centre, recomputed where needed (cheaper than 24 more
/// bytes per primitive).
#[derive(Clone, Copy, Debug)]
struct Item<V> {
    bounds: Aabb<V>,
    prim: u32,
    /// [`crate::shape::Shape::test_cost`] (an `f32` fits beside `prim` at no size).
    cost: f32,
}

impl<V: Vector> Item<V> {
    #[inline]
    fn centroid(&self) -> V {
        self.bounds.centroid()
    }
}

/// A builder's record of a primitive, and how a group of records is split: the exact [`Item`]s
/// of small scenes, or the compact records of large ones ([`super::binned`]). The driver
/// ([`build_into`]) is the same for both.
pub(super) trait Split<V>: Copy + Send + Sync {
    /// What a group's split needs to know of the group (its box, the box of its centroids),
    /// found when its parent was split.
    type Group: Copy + Send + Sync;
    /// The group of `items`, in one pass (the root's; the median split's sides).
    fn group(items: &[Self]) -> Self::Group;
    /// The group's box: its node's.
    fn bounds(group: &Self::Group) -> Aabb<V>;
    /// The index of the primitive in the build's list.
    fn prim(&self) -> u32;
    /// Where to split `items` (more than one, reordering them) and both sides' groups, or `None`
    /// for a leaf.
    fn split(
        items: &mut [Self],
        depth: u32,
        group: &Self::Group,
    ) -> Option<(usize, Self::Group, Self::Group)>;
}

/// Groups of at least this many primitives have their two subtrees built in parallel (rayon),
/// down to [`PARALLEL_DEPTH`] levels, when the pool has more than one thread; the tree is the
/// same whatever the number of threads.
const PARALLEL_MIN: usize = 1 << 16;
/// How many levels fork (at most 2^PARALLEL_DEPTH tasks).
const PARALLEL_DEPTH: u32 = 3;
/// Whether the build may fork at all: not in the WebAssembly module, which runs on one thread,
/// so that the forks' code stays out of it (its size budget, 3 MB).
const FORKS: bool = !cfg!(target_arch = "wasm32");

/// Appends the subtree over `items` (at `base` of the whole list; `group` their group) to
/// `out`, depth first: an inner node's `start` is the index of its right child in `out`, a
/// leaf's the position of its first item in the whole list.
fn build_into<V: Vector, T: Split<V>>(
    out: &mut Vec<Built<V>>,
    items: &mut [T],
    base: usize,
    depth: u32,
    group: T::Group,
) {
    let (index, n) = (out.len(), items.len());
    let bounds = T::bounds(&group);
    out.push(Built { bounds, start: to_u32(base), count: to_u32(n) });
    if n == 1 {
        return;
    }
    let Some((mid, left, right)) = T::split(items, depth, &group) else {
        return;
    };
    let (left_items, right_items) = items.split_at_mut(mid);
    // With one thread (a pinned benchmark), no fork: the tree is the same, without the copy of
    // the right subtree's list.
    let fork = FORKS && n >= PARALLEL_MIN && depth < PARALLEL_DEPTH && rayon::current_num_threads() > 1;
    let right_start = if fork {
        // The left subtree goes straight into `out`, the right one into its own list, appended
        // after. Reserved here, on the calling thread, so that the memory comes from the
        // allocator's main arena (where the scene's parse left free memory) rather than a
        // worker's fresh one.
        let mut right_nodes = Vec::with_capacity(right_items.len());
        rayon::join(
            || build_into(out, left_items, base, depth + 1, left),
            || build_into(&mut right_nodes, right_items, base + mid, depth + 1, right),
        );
        let right_start = out.len();
        out.extend(right_nodes.into_iter().map(|mut b| {
            if b.count == 0 {
                b.start += to_u32(right_start);
            }
            b
        }));
        right_start
    } else {
        build_into(out, left_items, base, depth + 1, left);
        let right_start = out.len();
        build_into(out, right_items, base + mid, depth + 1, right);
        right_start
    };
    out[index] = Built { bounds, start: to_u32(right_start), count: 0 };
}

/// A child of a wide node in [`wide_into`]: `len` items at `offset` in the node's, their group's
/// box and its surface (which decides which child opens first, as in the collapse), the child's
/// depth in the binary tree, and its split (`None`: a leaf).
struct Kid<V, G> {
    offset: usize,
    len: usize,
    depth: u32,
    bounds: Aabb<V>,
    area: f64,
    split: Option<(usize, G, G)>,
}

/// The binary node over `items[offset .. offset + len]` (group `group`, at `depth`), split as
/// [`build_into`] splits it.
fn kid<V: Vector, T: Split<V>>(
    items: &mut [T],
    offset: usize,
    len: usize,
    depth: u32,
    group: T::Group,
) -> Kid<V, T::Group> {
    let bounds = T::bounds(&group);
    let split = if len == 1 { None } else { T::split(&mut items[offset..offset + len], depth, &group) };
    Kid { offset, len, depth, area: bounds.surface(), bounds, split }
}

/// An inner child's subtree for [`run_jobs`]: its lane, its items, its depth, its place in the
/// whole list, its split, and the list its wide nodes go to.
type Job<'a, T, G> = (usize, &'a mut [T], u32, usize, (usize, G, G), Vec<WideNode>);

/// Builds each job's subtree into its own list, halves of the jobs in parallel.
fn run_jobs<V: Vector, T: Split<V>>(jobs: &mut [Job<'_, T, T::Group>]) {
    match jobs {
        [] => {}
        [(_, items, depth, base, split, out)] => {
            wide_into::<V, T>(out, items, *base, *depth, *split);
        }
        _ => {
            let (a, b) = jobs.split_at_mut(jobs.len() / 2);
            rayon::join(|| run_jobs::<V, T>(a), || run_jobs::<V, T>(b));
        }
    }
}

/// Room reserved for the wide nodes of `n` primitives, so that the list never moves: at most
/// one a binary inner node, i.e. fewer than the leaves, and a leaf of one primitive is rare
/// (in practice about `n / 6`; only the pages written count in memory).
fn wide_capacity(n: usize) -> usize {
    n / 2 + 1
}

/// Appends the wide node of the binary inner node over `items` (at `base` of the whole list, at
/// `depth`, split into `left` of `mid` items and `right`) and, after it, the wide nodes of its
/// inner children, depth first; returns its index. The children are those of
/// [`WideBvh::collapse`]: the node's two, then, while fewer than [`WIDTH`], the inner child of
/// largest surface (the first on a tie) replaced by its two, each split when it is made. Since
/// a group's split depends only on its records and depth, and both builds hand every group the
/// same records in the same order, the nodes are the collapse's, node for node. Large groups
/// build their inner children's subtrees in parallel ([`PARALLEL_MIN`]); the nodes are the same
/// on any number of threads.
fn wide_into<V: Vector, T: Split<V>>(
    nodes: &mut Vec<WideNode>,
    items: &mut [T],
    base: usize,
    depth: u32,
    (mid, left, right): (usize, T::Group, T::Group),
) -> u32 {
    let n = items.len();
    let mut kids: ArrayVec<Kid<V, T::Group>, WIDTH> = ArrayVec::new();
    kids.push(kid(items, 0, mid, depth + 1, left));
    kids.push(kid(items, mid, n - mid, depth + 1, right));
    while kids.len() < WIDTH {
        let Some(open) = to_open(kids.iter().map(|k| (k.split.is_some(), k.area))) else {
            break;
        };
        let opened = kids.remove(open);
        let Some((m, l, r)) = opened.split else { unreachable!("an inner child was chosen") };
        kids.push(kid(items, opened.offset, m, opened.depth + 1, l));
        kids.push(kid(items, opened.offset + m, opened.len - m, opened.depth + 1, r));
    }
    let index = nodes.len();
    nodes.push(WideNode::new(kids.iter().map(|k| {
        let link = if k.split.is_some() {
            Child { start: 0, count: 0 }
        } else {
            Child { start: to_u32(base + k.offset), count: to_u32(k.len) }
        };
        (k.bounds.min, k.bounds.max, link)
    })));
    let fork = FORKS && n >= PARALLEL_MIN && rayon::current_num_threads() > 1;
    if fork {
        // Each inner child's items, apart: the children's ranges are disjoint.
        let mut order: ArrayVec<usize, WIDTH> = (0..kids.len()).collect();
        order.sort_unstable_by_key(|&k| kids[k].offset);
        let mut jobs = Vec::new();
        let (mut rest, mut at) = (&mut *items, 0);
        for &k in &order {
            let (_, tail) = std::mem::take(&mut rest).split_at_mut(kids[k].offset - at);
            let (mine, tail) = tail.split_at_mut(kids[k].len);
            (rest, at) = (tail, kids[k].offset + kids[k].len);
            if let Some(split) = kids[k].split.take() {
                // Reserved on the calling thread, as in `build_into`.
                let out = Vec::with_capacity(wide_capacity(mine.len()));
                jobs.push((k, mine, kids[k].depth, base + kids[k].offset, split, out));
            }
        }
        jobs.sort_unstable_by_key(|job| job.0);
        run_jobs::<V, T>(&mut jobs);
        let subtrees = jobs.into_iter().map(|(lane, _, _, _, _, out)| (lane, out));
        for (lane, subtree) in subtrees {
            let at = to_u32(nodes.len());
            nodes[index].set_start(lane, at);
            nodes.extend(subtree.into_iter().map(|mut node| {
                node.shift(at);
                node
            }));
        }
    } else {
        for (lane, k) in kids.into_iter().enumerate() {
            if let Some(split) = k.split {
                let at =
                    wide_into(nodes, &mut items[k.offset..k.offset + k.len], base + k.offset, k.depth, split);
                nodes[index].set_start(lane, at);
            }
        }
    }
    to_u32(index)
}

/// Room on a walk's stack of pending `(link, depth, t_in)`: a walk keeps at most one pending
/// (farther) child per level below the root, and the depth is at most `BALANCE_DEPTH + 33`.
const STACK_SIZE: usize = BALANCE_DEPTH as usize + 40;

impl<V: Dim> Bvh<V> {
    /// Builds the tree over `prims` (their boxes from the scene): more than
    /// [`binned::LARGE`] of them by the compact build of [`super::binned`], fewer (every lesson
    /// scene) by the exact one. With `for_render`, the tree is the one a render walks: with its
    /// wide copy ([`Bvh::widen`]); a large tree then has the wide nodes alone, built directly
    /// ([`Bvh::wide_from_items`]), without the binary nodes that only a recorder reads.
    #[must_use]
    pub fn build(scene: &Scene<V>, prims: Vec<Prim>, for_render: bool) -> Self {
        let cost = |p: Prim| {
            #[allow(clippy::cast_possible_truncation)] // 0.25 and 1 are exact in f32
            let cost = scene.objects[p.object()].shape.test_cost() as f32;
            cost
        };
        if prims.len() > binned::LARGE {
            if let Some(records) = binned::records(prims.iter().map(|&p| (prim_bounds(scene, p), cost(p)))) {
                return if for_render {
                    Self::wide_from_items(prims, records)
                } else {
                    Self::from_items(prims, records)
                };
            }
        }
        let items = prims
            .iter()
            .enumerate()
            .map(|(i, &p)| Item { bounds: prim_bounds(scene, p), prim: to_u32(i), cost: cost(p) })
            .collect();
        let mut tree = Self::from_items(prims, items);
        if for_render {
            tree.widen();
        }
        tree
    }

    /// Builds the tree over primitives with the given boxes (each costing one triangle test),
    /// as [`Bvh::build`] does.
    #[must_use]
    pub fn from_boxes(prims: Vec<Prim>, boxes: Vec<Aabb<V>>, for_render: bool) -> Self {
        if boxes.len() > binned::LARGE {
            if let Some(records) = binned::records(boxes.iter().map(|&b| (b, 1.0))) {
                return if for_render {
                    Self::wide_from_items(prims, records)
                } else {
                    Self::from_items(prims, records)
                };
            }
        }
        let items = boxes
            .into_iter()
            .enumerate()
            .map(|(i, bounds)| Item { bounds, prim: to_u32(i), cost: 1.0 })
            .collect();
        let mut tree = Self::from_items(prims, items);
        if for_render {
            tree.widen();
        }
        tree
    }

    /// The render's tree over primitives given as builder records, built straight into wide
    /// nodes: the very nodes, lanes and primitive order that [`Bvh::from_items`] then
    /// [`Bvh::widen`] give (every group is split by the same call on the same records; see
    /// [`wide_into`]), without the binary nodes in between. Such a tree has no binary nodes:
    /// [`Bvh::walk`] takes the wide walk even for a recorder (no `node_visit` events), and
    /// [`Bvh::tree`] shows the root alone.
    fn wide_from_items<T: Split<V>>(prims: Vec<Prim>, mut items: Vec<T>) -> Self {
        let n = prims.len();
        if n == 0 {
            return Self::from_items(prims, items);
        }
        let group = T::group(&items);
        let root_box = T::bounds(&group);
        let split = if n == 1 { None } else { T::split(&mut items, 0, &group) };
        let (root, wide) = match split {
            None => (Link { start: 0, count: to_u32(n), id: 0 }, None),
            Some(split) => {
                let mut nodes = Vec::with_capacity(wide_capacity(n));
                wide_into(&mut nodes, &mut items, 0, 0, split);
                (Link { start: 0, count: 0, id: 0 }, Some(WideBvh::from_nodes(nodes)))
            }
        };
        let order: Vec<u32> = items.iter().map(T::prim).collect();
        drop(items);
        let prims = order.iter().map(|&i| prims[i as usize]).collect();
        Self { root_box, root, nodes: Vec::new(), prims, wide }
    }

    /// Builds the tree over primitives given as builder records (box and index into `prims`).
    fn from_items<T: Split<V>>(prims: Vec<Prim>, mut items: Vec<T>) -> Self {
        let n = prims.len();
        let empty = Link { start: 0, count: 0, id: 0 };
        if n == 0 {
            return Self { root_box: Aabb::empty(), root: empty, nodes: Vec::new(), prims, wide: None };
        }
        let (order, built) = {
            let mut built = Vec::with_capacity(n);
            let group = T::group(&items);
            build_into(&mut built, &mut items, 0, 0, group);
            let order: Vec<u32> = items.iter().map(T::prim).collect();
            drop(items);
            (order, built)
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
        Self { root_box: built[0].bounds, root: link(0), nodes, prims, wide: None }
    }

    /// Adds the wide copy of the inner nodes that the walk takes when no recorder listens
    /// ([`WideBvh`]); the binary tree, its numbers and its recorded walk stay as they are. A
    /// tree that is one leaf has no inner node to widen.
    pub fn widen(&mut self) {
        if self.root.count > 0 || self.prims.is_empty() || self.wide.is_some() {
            return;
        }
        let nodes = &self.nodes;
        let children = |i: u32| {
            let node = &nodes[i as usize];
            [0, 1].map(|k| {
                let (b, l) = (node.boxes[k], node.links[k]);
                Binary {
                    min: b.min,
                    max: b.max,
                    area: b.surface(),
                    link: Child { start: l.start, count: l.count },
                }
            })
        };
        self.wide = Some(WideBvh::collapse(self.root.start, children));
    }

    /// The wide copy, once [`Bvh::widen`] has made it.
    #[must_use]
    pub fn wide(&self) -> Option<&WideBvh> {
        self.wide.as_ref()
    }

    /// Number of nodes (leaves and inner nodes) of the binary tree; 1 (the root) for a render's
    /// tree built without one ([`Bvh::wide_from_items`]).
    #[must_use]
    pub fn node_count(&self) -> usize {
        if self.prims.is_empty() {
            0
        } else {
            2 * self.nodes.len() + 1
        }
    }

    /// The nodes for drawing, by their `node_visit` number (depth-first order, the root 0); the
    /// root alone, holding every primitive, for a render's tree without binary nodes.
    #[must_use]
    pub fn tree(&self) -> Vec<TreeNode<V>> {
        let mut out = vec![None; self.node_count()];
        if out.is_empty() {
            return Vec::new();
        }
        if self.nodes.is_empty() && self.root.count == 0 {
            let all = self.prims.clone();
            return vec![TreeNode { bounds: self.root_box, depth: 0, children: Vec::new(), prims: all }];
        }
        let mut stack = vec![(self.root, self.root_box, 0u32)];
        while let Some((link, bounds, depth)) = stack.pop() {
            let (children, prims) = if link.count > 0 {
                let start = link.start as usize;
                (Vec::new(), self.prims[start..start + link.count as usize].to_vec())
            } else {
                let node = &self.nodes[link.start as usize];
                for (child, b) in node.links.iter().zip(&node.boxes) {
                    stack.push((*child, *b, depth + 1));
                }
                (node.links.iter().map(|l| l.id as usize).collect(), Vec::new())
            };
            out[link.id as usize] = Some(TreeNode { bounds, depth, children, prims });
        }
        out.into_iter().flatten().collect()
    }

    /// Hands a leaf's primitives to the visitor; true when the search is over. A plain loop:
    /// `Iter::any` was compiled out of line, outside the recursion's frame (one copy per question).
    #[inline(always)]
    fn visit_leaf<R: Recorder<V>, W: Visitor<V>>(
        &self,
        leaf: Link,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) -> bool {
        let start = leaf.start as usize;
        for prim in &self.prims[start..start + leaf.count as usize] {
            if visitor.visit(*prim, stats, rec) {
                return true;
            }
        }
        false
    }

    /// A tree that is one leaf (a small scene): its root box and its primitives, in the order
    /// [`Bvh::walk`] visits them (none for a scene without bounded objects, whose walk tests no
    /// box); `None` for a tree with inner nodes.
    #[must_use]
    pub fn one_leaf(&self) -> Option<(&Aabb<V>, &[Prim])> {
        if self.prims.is_empty() {
            return Some((&self.root_box, &[]));
        }
        (self.root.count > 0).then(|| {
            let start = self.root.start as usize;
            (&self.root_box, &self.prims[start..start + self.root.count as usize])
        })
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
        // A ray that starts in the closed root box (a secondary or shadow ray of most scenes)
        // meets it: every slab's interval then holds t = 0, so t_in ≤ 0 ≤ t_out, the culling test
        // passes and nothing is pruned. When no recorder wants the interval, the node test is
        // counted without computing it, and the ray's reciprocals wait for an inner node.
        let mut recip = None;
        let root_t_in = if !R::ENABLED && self.root_box.holds(ray.origin) {
            stats.tests.node += 1;
            0.0
        } else {
            let r = recip.insert(RecipRay::new(ray));
            let root =
                node_visit("bvh", r.box_interval(self.root_box.min, self.root_box.max), (0, 0), stats, rec);
            if !root.hit {
                return;
            }
            if beyond(root.t_in, visitor.bound()) {
                node_skip("bvh", 0, root.t_in, visitor.bound(), rec);
                return;
            }
            root.t_in
        };
        if self.root.count > 0 {
            // A tree that is one leaf (a small scene): its primitives, without the stack.
            self.visit_leaf(self.root, visitor, stats, rec);
            return;
        }
        let r = recip.unwrap_or_else(|| RecipRay::new(ray));
        if let Some(wide) = &self.wide {
            // A render's tree without binary nodes is walked wide even when a recorder listens.
            if !R::ENABLED || self.nodes.is_empty() {
                wide.walk(&self.prims, &r, visitor, stats, rec);
                return;
            }
        }
        // On the walk's own stack, never initialised: a walk neither allocates nor clears.
        let mut stack: ArrayVec<(Link, u32, f64), STACK_SIZE> = ArrayVec::new();
        stack.push((self.root, 0, root_t_in));
        while let Some((link, depth, t_in)) = stack.pop() {
            if beyond(t_in, visitor.bound()) {
                node_skip("bvh", link.id as usize, t_in, visitor.bound(), rec);
                continue;
            }
            if link.count > 0 {
                if self.visit_leaf(link, visitor, stats, rec) {
                    return;
                }
                continue;
            }
            let node = &self.nodes[link.start as usize];
            let [l, rr] = node.links;
            let [bl, br] = &node.boxes;
            let [il, ir] = r.box_pair_interval([bl.min, br.min], [bl.max, br.max]);
            let hl = node_visit("bvh", il, (l.id as usize, depth + 1), stats, rec);
            let hr = node_visit("bvh", ir, (rr.id as usize, depth + 1), stats, rec);
            // Push the farther first, so the nearer is popped first (a tie keeps left first).
            let (near, far, h_near, h_far) =
                if hr.t_in < hl.t_in { (rr, l, hr, hl) } else { (l, rr, hl, hr) };
            for (child, h) in [(far, h_far), (near, h_near)] {
                if h.hit && !beyond(h.t_in, visitor.bound()) {
                    stack.push((child, depth + 1, h.t_in));
                } else if h.hit {
                    node_skip("bvh", child.id as usize, h.t_in, visitor.bound(), rec);
                }
            }
        }
    }
}

/// The exact build's group: the box of the items and the box of their centroids.
type Boxes<V> = (Aabb<V>, Aabb<V>);

impl<V: Vector> Split<V> for Item<V> {
    type Group = Boxes<V>;

    /// The box of `items` and the box of their centroids, in one pass.
    fn group(items: &[Self]) -> Boxes<V> {
        let (mut bounds, mut cbox) = (Aabb::empty(), Aabb::empty());
        for it in items {
            bounds = bounds.union(&it.bounds);
            let c = it.centroid();
            cbox = cbox.union(&Aabb::new(c, c));
        }
        (bounds, cbox)
    }

    fn bounds(group: &Boxes<V>) -> Aabb<V> {
        group.0
    }

    fn prim(&self) -> u32 {
        self.prim
    }

    fn split(
        items: &mut [Self],
        depth: u32,
        (bounds, cbox): &Boxes<V>,
    ) -> Option<(usize, Boxes<V>, Boxes<V>)> {
        let mid = split_items(items, depth, bounds, cbox)?;
        Some((mid, Self::group(&items[..mid]), Self::group(&items[mid..])))
    }
}

/// Where to split `items` (reordering them), or `None` for a leaf.
fn split_items<V: Vector>(
    items: &mut [Item<V>],
    depth: u32,
    bounds: &Aabb<V>,
    cbox: &Aabb<V>,
) -> Option<usize> {
    let count = items.len();
    let axis = cbox.longest_axis();
    if depth >= BALANCE_DEPTH || !(cbox.extent()[axis] > 0.0) {
        return (count > MAX_LEAF || depth >= BALANCE_DEPTH).then(|| median(items, axis));
    }
    let BinSplit { cost, axis, bin } = best_bin_split(items, cbox, bounds);
    // A leaf costs the tests of all its primitives; summed only where a leaf may be chosen
    // (otherwise one more pass over every item at every level of the build).
    if count <= MAX_LEAF {
        let leaf: f64 = items.iter().map(|it| f64::from(it.cost)).sum();
        if cost >= leaf {
            return None;
        }
    }
    // Partition by bin: those left of the split first.
    let (cmin, scale) = bin_map(cbox, axis);
    let mut mid = 0;
    for k in 0..count {
        if bin_of(items[k].centroid()[axis], cmin, scale) <= bin {
            items.swap(mid, k);
            mid += 1;
        }
    }
    if mid == 0 || mid == count {
        return Some(median(items, axis));
    }
    Some(mid)
}

/// The best binned SAH split of `items` over every axis. All axes are binned in one pass over
/// the primitives.
fn best_bin_split<V: Vector>(items: &[Item<V>], cbox: &Aabb<V>, bounds: &Aabb<V>) -> BinSplit {
    let parent = bounds.surface();
    // Large groups are binned along their longest axis only, small ones along every axis.
    let longest = cbox.longest_axis();
    let mut maps: [Option<(f64, f64)>; 3] = [None; 3];
    for (axis, map) in maps.iter_mut().enumerate().take(V::DIM) {
        let used = items.len() <= ALL_AXES_BELOW || axis == longest;
        *map = (used && cbox.extent()[axis] > 0.0).then(|| bin_map(cbox, axis));
    }
    let mut counts = [[0usize; BINS]; 3];
    let mut costs = [[0.0f64; BINS]; 3];
    let mut boxes = [[Aabb::empty(); BINS]; 3];
    for it in items {
        let (c, b) = (it.centroid(), &it.bounds);
        for (axis, map) in maps.iter().enumerate() {
            if let Some((cmin, scale)) = map {
                let k = bin_of(c[axis], *cmin, *scale);
                counts[axis][k] += 1;
                costs[axis][k] += f64::from(it.cost);
                boxes[axis][k] = boxes[axis][k].union(b);
            }
        }
    }
    let mut best = BinSplit { cost: f64::INFINITY, axis: 0, bin: 0 };
    for axis in (0..V::DIM).filter(|&a| maps[a].is_some()) {
        let (counts, costs, boxes) = (&counts[axis], &costs[axis], &boxes[axis]);
        // Sweep from the right: the area, count and test cost of bins b+1.. .
        let mut right_area = [0.0; BINS];
        let mut right_count = [0usize; BINS];
        let mut right_cost = [0.0; BINS];
        let (mut acc, mut n, mut c) = (Aabb::empty(), 0, 0.0);
        for b in (1..BINS).rev() {
            acc = acc.union(&boxes[b]);
            n += counts[b];
            c += costs[b];
            right_area[b] = acc.surface();
            right_count[b] = n;
            right_cost[b] = c;
        }
        let (mut acc, mut n, mut c) = (Aabb::empty(), 0, 0.0);
        for b in 0..BINS - 1 {
            acc = acc.union(&boxes[b]);
            n += counts[b];
            c += costs[b];
            if n == 0 || right_count[b + 1] == 0 {
                continue;
            }
            let (cl, cr) = (c, right_cost[b + 1]);
            let cost = if parent > 0.0 {
                C_TRAV + (acc.surface() * cl + right_area[b + 1] * cr) / parent
            } else {
                // A flat or point-like group: every box has measure 0; split evenly.
                C_TRAV + f64::max(cl, cr)
            };
            if cost < best.cost {
                best = BinSplit { cost, axis, bin: b };
            }
        }
    }
    best
}

/// Splits `items` at its middle, by centroid along `axis` then by index.
fn median<V: Vector>(items: &mut [Item<V>], axis: usize) -> usize {
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| {
        a.centroid()[axis].total_cmp(&b.centroid()[axis]).then(a.prim.cmp(&b.prim))
    });
    mid
}

/// A binned SAH split: what [`Bvh`]'s build chooses among.
#[derive(Clone, Copy, Debug)]
struct BinSplit {
    /// Its SAH cost.
    cost: f64,
    /// The axis binned.
    axis: usize,
    /// The last bin of the left side.
    bin: usize,
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

    /// Asserts that `t` holds every primitive once, each inside its leaf's box (`boxes[object]`),
    /// every child box inside its parent's, and leaves of at most `MAX_LEAF` primitives.
    fn assert_sound(t: &Bvh<DVec3>, boxes: &[Aabb<DVec3>]) {
        let mut seen: Vec<u32> = t.prims.iter().map(|p| p.object).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..to_u32(boxes.len())).collect::<Vec<_>>());
        let mut parents = vec![t.root_box; t.nodes.len()];
        for (i, n) in t.nodes.iter().enumerate() {
            for (b, l) in n.boxes.iter().zip(n.links) {
                assert_eq!(parents[i].union(b), parents[i]);
                if l.count > 0 {
                    assert!(l.count as usize <= MAX_LEAF);
                    for p in &t.prims[l.start as usize..(l.start + l.count) as usize] {
                        assert_eq!(b.union(&boxes[p.object()]), *b, "{p:?} outside its leaf");
                    }
                } else {
                    parents[l.start as usize] = *b;
                }
            }
        }
    }

    #[test]
    fn build_is_deterministic_and_covers_every_primitive_once() {
        let prims: Vec<Prim> = (0..1000).map(|i| Prim { object: i, part: 0 }).collect();
        let boxes: Vec<Aabb<DVec3>> = (0..1000).map(cube).collect();
        let a = Bvh::from_boxes(prims.clone(), boxes.clone(), false);
        let b = Bvh::from_boxes(prims, boxes.clone(), false);
        assert_eq!(a.nodes, b.nodes);
        assert_eq!(a.prims, b.prims);
        assert_sound(&a, &boxes);
    }

    #[test]
    fn the_binned_build_is_the_same_on_any_number_of_threads_and_sound() {
        // Enough boxes for the compact build and for its top levels to fork; coordinates with
        // many digits, so that every box is rounded outward to f32.
        let n = PARALLEL_MIN + 1000;
        assert!(n > binned::LARGE);
        let prims: Vec<Prim> = (0..to_u32(n)).map(|i| Prim { object: i, part: 0 }).collect();
        let boxes: Vec<Aabb<DVec3>> = (0..n)
            .map(|i| {
                let x = (i as f64 * 0.618_033_988_749_894_9).fract();
                let p = DVec3::new(x * 97.3, (x * 7.77).fract() * 11.1, i as f64 * 1e-3 / 3.0);
                Aabb::new(p, p + DVec3::new(0.01, 0.02 / 3.0, 0.1 / 7.0))
            })
            .collect();
        let build = |threads, for_render| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| Bvh::from_boxes(prims.clone(), boxes.clone(), for_render))
        };
        let (mut a, b) = (build(1, false), build(2, false));
        assert_eq!(a.nodes, b.nodes);
        assert_eq!(a.prims, b.prims);
        assert_sound(&a, &boxes);
        // The render's tree built straight into wide nodes is the binary tree's collapse, node
        // for node, on any number of threads, and has no binary nodes.
        a.widen();
        let collapsed = a.wide().expect("a wide tree");
        assert!(collapsed.node_count() > 1000, "{} wide nodes", collapsed.node_count());
        for threads in [1, 2] {
            let direct = build(threads, true);
            assert!(direct.nodes.is_empty(), "{threads} threads: no binary node");
            assert_eq!(direct.wide(), Some(collapsed), "{threads} threads");
            assert_eq!((direct.root_box, direct.root), (a.root_box, a.root), "{threads} threads");
            assert_eq!(direct.prims, a.prims, "{threads} threads");
        }
    }

    #[test]
    fn cheap_primitives_share_a_leaf_where_costly_ones_split() {
        // Two unit-sized objects 3 apart. Spheres (test cost 0.25): a leaf costs 0.5, a split
        // 0.5 + (6·0.25 + 6·0.25)/18 ≈ 0.67, so one leaf. Flat triangles (cost 1): a leaf costs
        // 2, a split 0.5 + (2·1 + 2·1)/8 = 1, so a root over two leaves.
        let scene = |kind: &str| {
            let objects = if kind == "sphere" {
                r#"{"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
                   {"type": "sphere", "center": [3, 0, 0], "radius": 0.5}"#
            } else {
                r#"{"type": "triangle", "vertices": [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0, 0.5, 0]]},
                   {"type": "triangle", "vertices": [[2.5, -0.5, 0], [3.5, -0.5, 0], [3, 0.5, 0]]}"#
            };
            let camera = r#""eye": [0, 0, 5], "center": [0, 0, 0], "window": {"l": -1, "r": 1, "b": -1, "t": 1}, "resolution": [4, 4]"#;
            let text = format!(r#"{{"camera": {{{camera}}}, "objects": [{objects}]}}"#);
            match crate::scene::load::load_str(&text) {
                Ok(crate::scene::AnyScene::Space(s)) => s,
                other => panic!("{other:?}"),
            }
        };
        let prims = vec![Prim { object: 0, part: 0 }, Prim { object: 1, part: 0 }];
        let spheres = Bvh::build(&scene("sphere"), prims.clone(), false);
        assert_eq!((spheres.nodes.len(), spheres.root.count), (0, 2), "one leaf of both spheres");
        let triangles = Bvh::build(&scene("triangle"), prims, false);
        assert_eq!((triangles.nodes.len(), triangles.root.count), (1, 0), "a root over two leaves");
    }

    #[test]
    fn identical_boxes_split_at_the_median() {
        let prims: Vec<Prim> = (0..100).map(|i| Prim { object: i, part: 0 }).collect();
        let boxes = vec![Aabb::new(DVec3::ZERO, DVec3::ONE); 100];
        let t = Bvh::from_boxes(prims, boxes, false);
        assert!(t.nodes.iter().flat_map(|n| n.links).all(|l| l.count as usize <= MAX_LEAF));
    }
}
