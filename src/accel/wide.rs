//! The render's BVH: the lesson's binary tree ([`super::bvh`]) collapsed into a tree of up to
//! [`WIDTH`] children a node, walked only when no recorder listens (the recording walk, its
//! `node_visit` events and the figures keep the binary tree, node for node).
//!
//! **Collapse**: a wide node starts from a binary inner node's two children and, while it has
//! fewer than [`WIDTH`], replaces its inner child of largest surface by that child's two
//! children. A leaf is a leaf of the binary tree: a range of the binary tree's primitives, which
//! are already in leaf order (no copy). A large scene's render builds the same nodes without the
//! binary tree ([`super::bvh`]'s `wide_into`, opening children in the same order).
//!
//! **Boxes in `f32`, rounded outward**: each child box's `min` is rounded down and its `max` up
//! (`f32::next_down`, `f32::next_up` where the nearest `f32` falls inside), so the stored box
//! holds the binary tree's `f64` box. The slab test converts them back to `f64` (exactly) and
//! takes the binary walk's very formula `t = (x − O)·(1/D)` with its widened exit
//! ([`crate::geom::slab::culling_hit`]) and its prune ([`super::beyond`]): a larger box gives an
//! earlier entry and a later exit, so every primitive the binary walk reaches is reached here
//! too. An oblique ray's far planes take the widening inside their reciprocal
//! ([`crate::geom::slab::far_recip`], one multiplication a plane instead of two), which gives an
//! exit at least the widened one, so this still holds. The exact `f64` primitive test still
//! decides every hit. Since [`super::Nearest`] keeps the least `(t, object, part)` whatever the
//! order of visits, and [`super::Shadow`] reports its occluders sorted, the answers are those of
//! the binary walk, bit for bit.
//!
//! **Layout**: per node, per axis, per side (`min`, `max`), the [`WIDTH`] children's planes side
//! by side (`[f32; 4]`), so the test of all children is one loop over lanes that the compiler
//! vectorises, and a slab's near side is an index the ray chose once; a node is two cache lines.
//! An unused lane holds the empty box `[+∞, −∞]`, which no ray meets.
//!
//! **Walk**: the hit children are visited nearest entry first: the nearest next, the others
//! pushed farthest first on a stack of `(child, t_in)`; a child whose entry lies beyond the
//! visitor's bound is never pushed, and one popped is dropped when the bound has come nearer
//! since. Every child box tested counts as one node test. The ray's reciprocals are the binary
//! walk's, computed once per ray.

use super::{beyond, Prim, Visitor};
use crate::geom::slab::{admits, far_recip, widen_exit, RecipRay};
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::shape::Dim;
use arrayvec::ArrayVec;

/// Children per node.
pub const WIDTH: usize = 4;

/// The side of [`WideNode`]'s planes that holds the boxes' `min`.
const MIN: usize = 0;
/// The side that holds the boxes' `max`.
const MAX: usize = 1;

/// The ray as the wide walk's slab test reads it, made once per walk: plain arrays (indexing a
/// vector by a run-time axis went through a `match` per slab) and, per axis, the side of every
/// box the ray enters by, [`MIN`] when `1/d ≥ 0`, else [`MAX`] (the sign test
/// `box_pair_interval` makes per node, made once). Only an oblique ray reads it.
struct SlabSides {
    /// `O` per axis.
    origin: [f64; 3],
    /// `1/D` per axis, for the near planes.
    inv_dir: [f64; 3],
    /// `1/D` per axis with the exit's widening folded in ([`far_recip`]), for the far planes.
    inv_far: [f64; 3],
    /// The near side per axis; the far side is `MAX − near`.
    near: [usize; 3],
}

impl SlabSides {
    #[inline(always)]
    fn new<V: Dim>(r: &RecipRay<V>) -> Self {
        let mut sides = SlabSides { origin: [0.0; 3], inv_dir: [0.0; 3], inv_far: [0.0; 3], near: [MIN; 3] };
        for axis in 0..V::DIM {
            sides.origin[axis] = r.origin[axis];
            sides.inv_dir[axis] = r.inv_dir[axis];
            sides.inv_far[axis] = far_recip(r.inv_dir[axis]);
            // As a branch: `usize::from(1/d < 0)` cost 3 % more of mesh-100k's instructions.
            sides.near[axis] = if r.inv_dir[axis] < 0.0 { MAX } else { MIN };
        }
        sides
    }
}

/// A child reference: an inner node `nodes[start]` (count 0) or a leaf over
/// `prims[start .. start + count]` of the binary tree's primitives.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Child {
    pub(crate) start: u32,
    pub(crate) count: u32,
}

/// A wide node: its children's boxes, axis by axis and lane by lane, and their references.
#[derive(Clone, Debug, PartialEq)]
#[repr(align(64))]
pub(crate) struct WideNode {
    /// `planes[axis][MIN][lane]`, the box's `min` rounded down to `f32`, and
    /// `planes[axis][MAX][lane]`, its `max` rounded up: a side is an index, so the walk picks a
    /// slab's near side by the ray's [`SlabSides::near`] without a branch.
    planes: [[[f32; WIDTH]; 2]; 3],
    /// Each lane's [`Child::start`].
    start: [u32; WIDTH],
    /// Each lane's [`Child::count`]: a leaf holds at most `bvh::MAX_LEAF` primitives.
    count: [u16; WIDTH],
    /// Lanes in use (the rest hold the empty box).
    len: u32,
}

impl WideNode {
    /// The node of the given lanes (at most [`WIDTH`]): each child's box, rounded outward to
    /// `f32`, and its reference; the lanes left hold the empty box.
    pub(crate) fn new<V: crate::geom::Vector>(lanes: impl Iterator<Item = (V, V, Child)>) -> Self {
        let mut wide = WideNode {
            planes: [[[f32::INFINITY; WIDTH], [f32::NEG_INFINITY; WIDTH]]; 3],
            start: [0; WIDTH],
            count: [0; WIDTH],
            len: 0,
        };
        for (lane, (min, max, link)) in lanes.enumerate() {
            for axis in 0..V::DIM {
                wide.planes[axis][MIN][lane] = down_to_f32(min[axis]);
                wide.planes[axis][MAX][lane] = up_to_f32(max[axis]);
            }
            wide.start[lane] = link.start;
            wide.count[lane] = u16::try_from(link.count).expect("a leaf holds at most MAX_LEAF primitives");
            wide.len += 1;
        }
        wide
    }

    /// Lane `lane`'s child.
    #[inline(always)]
    fn child(&self, lane: usize) -> Child {
        Child { start: self.start[lane], count: u32::from(self.count[lane]) }
    }

    /// Points lane `lane` at inner node `node`.
    pub(crate) fn set_start(&mut self, lane: usize, node: u32) {
        self.start[lane] = node;
    }

    /// Moves every inner child's index by `offset` (a subtree appended at `offset`).
    pub(crate) fn shift(&mut self, offset: u32) {
        for lane in 0..self.len as usize {
            if self.count[lane] == 0 {
                self.start[lane] += offset;
            }
        }
    }
}

/// Which child a wide node opens next, of its children given as `(inner, area)`: the inner
/// child of largest surface, the first on a tie; `None` when every child is a leaf. The collapse
/// and the BVH's direct build both open by this rule, so they make the same nodes.
pub(crate) fn to_open(kids: impl Iterator<Item = (bool, f64)>) -> Option<usize> {
    kids.enumerate()
        .filter(|(_, (inner, _))| *inner)
        .reduce(|a, b| if b.1 .1 > a.1 .1 { b } else { a })
        .map(|(k, _)| k)
}

/// The collapsed tree: node 0 is the root (the binary root's box is tested by the caller).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WideBvh {
    nodes: Vec<WideNode>,
}

/// A child of a node being collapsed, as the binary tree gives it: its box (in `f64`), and
/// either a leaf range or a binary inner node to open or to collapse into a wide node.
pub(crate) struct Binary<V> {
    pub(crate) min: V,
    pub(crate) max: V,
    /// The surface area (perimeter in 2D) that decides which child opens first.
    pub(crate) area: f64,
    /// A leaf's range (count > 0), or a binary inner node's index (count 0).
    pub(crate) link: Child,
}

/// `x` rounded down to an `f32` (`x` itself when exact): the largest `f32` not above it.
#[must_use]
pub fn down_to_f32(x: f64) -> f32 {
    // Rounding to nearest, then one step down when that went above.
    #[allow(clippy::cast_possible_truncation)]
    let f = x as f32;
    if f64::from(f) > x {
        f.next_down()
    } else {
        f
    }
}

/// `x` rounded up to an `f32`: the smallest `f32` not below it.
#[must_use]
pub fn up_to_f32(x: f64) -> f32 {
    #[allow(clippy::cast_possible_truncation)]
    let f = x as f32;
    if f64::from(f) < x {
        f.next_up()
    } else {
        f
    }
}

/// Room on the walk's stack: at most `WIDTH − 1` pending children per level, and the binary
/// tree's depth (at most `BALANCE_DEPTH + 33`) bounds the wide tree's.
const STACK_SIZE: usize = (WIDTH - 1) * (super::bvh::BALANCE_DEPTH as usize + 40);

impl WideBvh {
    /// Collapses a binary tree, given as `children(node)` (the two children of binary inner node
    /// `node`), from the binary root's inner node `root`.
    pub(crate) fn collapse<V: Dim>(root: u32, children: impl Fn(u32) -> [Binary<V>; 2]) -> Self {
        let mut nodes = Vec::new();
        Self::collapse_into(&mut nodes, root, &children);
        Self { nodes }
    }

    /// Appends the wide node of binary inner node `node` (and, after it, its subtrees); returns
    /// its index.
    fn collapse_into<V: Dim>(
        nodes: &mut Vec<WideNode>,
        node: u32,
        children: &impl Fn(u32) -> [Binary<V>; 2],
    ) -> u32 {
        let mut kids: ArrayVec<Binary<V>, WIDTH> = children(node).into_iter().collect();
        while kids.len() < WIDTH {
            let Some(open) = to_open(kids.iter().map(|k| (k.link.count == 0, k.area))) else {
                break;
            };
            let opened = kids.remove(open);
            kids.extend(children(opened.link.start));
        }
        let index = nodes.len();
        nodes.push(WideNode::new(kids.iter().map(|kid| (kid.min, kid.max, kid.link))));
        for (lane, kid) in kids.iter().enumerate() {
            if kid.link.count == 0 {
                let at = Self::collapse_into(nodes, kid.link.start, children);
                nodes[index].start[lane] = at;
            }
        }
        u32::try_from(index).expect("fewer than 2^32 nodes")
    }

    /// The tree of `nodes`, node 0 its root, made elsewhere in the collapse's order (the
    /// BVH's direct build, [`super::bvh`]).
    pub(crate) fn from_nodes(nodes: Vec<WideNode>) -> Self {
        Self { nodes }
    }

    /// Number of wide nodes.
    #[must_use]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Bytes the nodes take.
    #[must_use]
    pub fn bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<WideNode>()
    }

    /// `[t_in, t_out·(1 + 2γ₃)]` of every lane's box, by the binary walk's formula in `f64`; an
    /// oblique ray's exits at least that, by [`far_recip`].
    #[inline(always)]
    fn intervals<V: Dim>(
        node: &WideNode,
        r: &RecipRay<V>,
        sides: &SlabSides,
    ) -> ([f64; WIDTH], [f64; WIDTH]) {
        let mut t_in = [f64::NEG_INFINITY; WIDTH];
        let mut t_out = [f64::INFINITY; WIDTH];
        if r.oblique {
            for axis in 0..V::DIM {
                let (o, inv, inv_far) = (sides.origin[axis], sides.inv_dir[axis], sides.inv_far[axis]);
                let near = &node.planes[axis][sides.near[axis]];
                let far = &node.planes[axis][MAX - sides.near[axis]];
                for lane in 0..WIDTH {
                    let tn = (f64::from(near[lane]) - o) * inv;
                    let tf = (f64::from(far[lane]) - o) * inv_far;
                    t_in[lane] = if tn > t_in[lane] { tn } else { t_in[lane] };
                    t_out[lane] = if tf < t_out[lane] { tf } else { t_out[lane] };
                }
            }
        } else {
            for lane in 0..WIDTH {
                let (mut lo, mut hi) = (r.origin, r.origin);
                for axis in 0..V::DIM {
                    lo[axis] = f64::from(node.planes[axis][MIN][lane]);
                    hi[axis] = f64::from(node.planes[axis][MAX][lane]);
                }
                let (t, t_exit) = r.box_interval(lo, hi);
                (t_in[lane], t_out[lane]) = (t, widen_exit(t_exit));
            }
        }
        (t_in, t_out)
    }

    /// Front-to-back walk from the root, whose box the ray met at `root_t_in` (not beyond the
    /// visitor's bound), handing every leaf's primitives (of `prims`, the binary tree's) to the
    /// visitor; `r` is the ray. The nearest hit child of a node is walked next without going
    /// through the stack. A visitor without [`Visitor::NEAREST_FIRST`] gets the children in
    /// lane order instead (any-hit): same answer, no sorting.
    pub(crate) fn walk<V: Dim, R: Recorder<V>, W: Visitor<V>>(
        &self,
        prims: &[Prim],
        r: &RecipRay<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        let mut stack: ArrayVec<(Child, f64), STACK_SIZE> = ArrayVec::new();
        let mut child = Child { start: 0, count: 0 };
        let sides = SlabSides::new(r);
        loop {
            if child.count > 0 {
                let start = child.start as usize;
                if prims[start..start + child.count as usize].iter().any(|p| visitor.visit(*p, stats, rec)) {
                    return;
                }
            } else {
                let node = &self.nodes[child.start as usize];
                stats.tests.node += u64::from(node.len);
                let (t_in, t_out) = Self::intervals(node, r, &sides);
                let bound = visitor.bound();
                // Each branch below writes out its own lane test (`admits` and `beyond`): one
                // closure shared by both cost 80.97 → 86.95 M instructions on mesh-100k
                // (callgrind, 160x120), a `filter` over the lanes 89.2 M.
                if !W::NEAREST_FIRST {
                    // Any-hit (a shadow segment): the hit lanes in lane order, as Embree's any-hit
                    // walk takes them, each pushed when the next is found, the last walked next
                    // (no arrays to fill and copy: 2.8 % of mesh-100k's instructions).
                    let mut last: Option<(Child, f64)> = None;
                    for lane in 0..WIDTH {
                        let t = t_in[lane];
                        if admits(t, t_out[lane]) && !beyond(t, bound) {
                            if let Some(earlier) = last {
                                stack.push(earlier);
                            }
                            last = Some((node.child(lane), t));
                        }
                    }
                    if let Some((next, _)) = last {
                        child = next;
                        continue;
                    }
                } else {
                    // The hit lanes, farthest entry first (an insertion sort of at most WIDTH).
                    let mut hit_t = [0.0; WIDTH];
                    let mut hit_c = [Child::default(); WIDTH];
                    let mut n = 0;
                    for lane in 0..WIDTH {
                        let t = t_in[lane];
                        if admits(t, t_out[lane]) && !beyond(t, bound) {
                            let mut at = n;
                            while at > 0 && hit_t[at - 1] < t {
                                hit_t[at] = hit_t[at - 1];
                                hit_c[at] = hit_c[at - 1];
                                at -= 1;
                            }
                            hit_t[at] = t;
                            hit_c[at] = node.child(lane);
                            n += 1;
                        }
                    }
                    if n > 0 {
                        for k in 0..n - 1 {
                            stack.push((hit_c[k], hit_t[k]));
                        }
                        child = hit_c[n - 1];
                        continue;
                    }
                }
            }
            // The next pending child whose entry the bound has not passed since it was pushed
            // (a bound that never moves was checked at the push).
            loop {
                let Some((next, t_in)) = stack.pop() else {
                    return;
                };
                if !W::NEAREST_FIRST || !beyond(t_in, visitor.bound()) {
                    child = next;
                    break;
                }
            }
        }
    }
}

#[cfg(test)]
// Rounding is exact by nature: these tests pin the very f32s.
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn a_wide_node_is_two_cache_lines() {
        assert_eq!(std::mem::size_of::<WideNode>(), 128);
    }

    #[test]
    fn rounding_to_f32_is_outward_and_exact_when_it_can_be() {
        for x in [0.1, -0.1, 1.0 / 3.0, -2.5, 1e30, -1e-30, 0.0, 16_777_217.0] {
            let (lo, hi) = (down_to_f32(x), up_to_f32(x));
            assert!(f64::from(lo) <= x && x <= f64::from(hi), "{x}");
            assert!(hi == lo || hi == lo.next_up(), "{x}: adjacent f32s");
        }
        assert_eq!(down_to_f32(0.5), 0.5);
        assert_eq!(up_to_f32(0.5), 0.5);
        assert_eq!(down_to_f32(f64::INFINITY), f32::INFINITY);
        assert_eq!(up_to_f32(f64::NEG_INFINITY), f32::NEG_INFINITY);
        // Beyond f32's range: down to the largest finite, up to infinity.
        assert_eq!(down_to_f32(1e300), f32::MAX);
        assert_eq!(up_to_f32(1e300), f32::INFINITY);
    }
}
