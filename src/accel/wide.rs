//! The render's BVH: the lesson's binary tree ([`super::bvh`]) collapsed into a tree of up to
//! [`WIDTH`] children a node, walked only when no recorder listens (the recording walk, its
//! `node_visit` events and the figures keep the binary tree, node for node).
//!
//! **Collapse**: a wide node starts from a binary inner node's two children and, while it has
//! fewer than [`WIDTH`], replaces its inner child of largest surface by that child's two
//! children. A leaf is a leaf of the binary tree: a range of the binary tree's primitives, which
//! are already in leaf order (no copy).
//!
//! **Boxes in `f32`, rounded outward**: each child box's `min` is rounded down and its `max` up
//! (`f32::next_down`, `f32::next_up` where the nearest `f32` falls inside), so the stored box
//! holds the binary tree's `f64` box. A larger box gives an earlier entry and a later exit than
//! the binary walk's formula `t = (x − O)·(1/D)` with its widened exit
//! ([`crate::geom::slab::culling_hit`]) and its prune ([`super::beyond`]), so every primitive the
//! binary walk reaches is reached here too, and the exact `f64` primitive test still decides
//! every hit. Since [`super::Nearest`] keeps the least `(t, object, part)` whatever the order of
//! visits, and [`super::Shadow`] reports its occluders sorted, the answers are those of the
//! binary walk, bit for bit.
//!
//! **Slab test in `f32`**: an oblique ray inside [`F32_RANGE`] tests the boxes in `f32`
//! ([`RecipRay32::box_lanes`](crate::geom::slab::RecipRay32::box_lanes)), its interval widened by a relative margin and a per-ray one so
//! that it holds the `f64` interval of the same box (`lo ≤ t_in`, `hi ≥ t_out·(1 + 2γ₃)`, the
//! bound is derived at [`RecipRay32`](crate::geom::slab::RecipRay32)): it admits every child the `f64` test admits, and its
//! entry `lo` prunes only what the `f64` entry prunes. Other rays (axis-parallel: `1/d = ±∞`;
//! beyond the range) take the `f64` test, converting the `f32` boxes exactly.
//!
//! **Layout**: per node, per axis, the [`WIDTH`] children's bounds side by side (`[f32; 4]`), so
//! the test of all children is one loop over lanes that the compiler vectorises; a node is two
//! cache lines. An unused lane holds the point box at 0, never read (the walk reads the first
//! `len` lanes), so that no lane's arithmetic meets an infinity.
//!
//! **Walk**: the hit children are visited nearest entry first: the nearest next, the others
//! pushed farthest first on a stack of `(child, t_in)`; a child whose entry lies beyond the
//! visitor's bound is never pushed, and one popped is dropped when the bound has come nearer
//! since. Every child box tested counts as one node test. The ray's reciprocals are the binary
//! walk's, computed once per ray, and rounded to `f32` once per ray.

use super::{beyond, Prim, Visitor};
use crate::geom::slab::{culling_hit, RecipRay, F32_RANGE};
pub use crate::geom::slab::{down_to_f32, up_to_f32};
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::shape::Dim;
use arrayvec::ArrayVec;

/// Children per node.
pub const WIDTH: usize = 4;

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
    /// `planes[axis][0][lane]`, the box's `min` rounded down to `f32`, and
    /// `planes[axis][1][lane]`, its `max` rounded up.
    planes: [[[f32; WIDTH]; 2]; 3],
    /// Each lane's [`Child::start`].
    start: [u32; WIDTH],
    /// Each lane's [`Child::count`]: a leaf holds at most `bvh::MAX_LEAF` primitives.
    count: [u16; WIDTH],
    /// Lanes in use: the first `len`; the rest hold the point box at 0 and are never read.
    len: u16,
    /// The lanes in use as bits (lane `k` is bit `k`): `2^len − 1`.
    used: u16,
}

/// The collapsed tree: node 0 is the root (the binary root's box is tested by the caller).
#[derive(Clone, Debug, Default)]
pub struct WideBvh {
    nodes: Vec<WideNode>,
    /// Every box plane lies within [`F32_RANGE`], so the `f32` slab test may decide
    /// ([`crate::geom::slab::RecipRay32`]); otherwise every ray takes the `f64` test.
    in_f32_range: bool,
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

/// Room on the walk's stack: at most `WIDTH − 1` pending children per level, and the binary
/// tree's depth (at most `BALANCE_DEPTH + 33`) bounds the wide tree's.
const STACK_SIZE: usize = (WIDTH - 1) * (super::bvh::BALANCE_DEPTH as usize + 40);

impl WideBvh {
    /// Collapses a binary tree, given as `children(node)` (the two children of binary inner node
    /// `node`), from the binary root's inner node `root`.
    pub(crate) fn collapse<V: Dim>(root: u32, children: impl Fn(u32) -> [Binary<V>; 2]) -> Self {
        let mut nodes = Vec::new();
        Self::collapse_into(&mut nodes, root, &children);
        let in_f32_range = nodes.iter().all(|n| {
            (0..n.len as usize).all(|lane| {
                (0..V::DIM).all(|a| {
                    let (lo, hi) = (f64::from(n.planes[a][0][lane]), f64::from(n.planes[a][1][lane]));
                    lo.abs() <= F32_RANGE && hi.abs() <= F32_RANGE
                })
            })
        });
        Self { nodes, in_f32_range }
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
            // Open the inner child of largest surface (the first on a tie).
            let Some(open) = (0..kids.len()).filter(|&k| kids[k].link.count == 0).reduce(|a, b| {
                if kids[b].area > kids[a].area {
                    b
                } else {
                    a
                }
            }) else {
                break;
            };
            let opened = kids.remove(open);
            kids.extend(children(opened.link.start));
        }
        let index = nodes.len();
        let mut wide = WideNode {
            planes: [[[0.0; WIDTH]; 2]; 3],
            start: [0; WIDTH],
            count: [0; WIDTH],
            len: u16::try_from(kids.len()).unwrap_or(0),
            used: u16::try_from((1u32 << kids.len()) - 1).unwrap_or(0),
        };
        for (lane, kid) in kids.iter().enumerate() {
            for axis in 0..V::DIM {
                wide.planes[axis][0][lane] = down_to_f32(kid.min[axis]);
                wide.planes[axis][1][lane] = up_to_f32(kid.max[axis]);
            }
            wide.start[lane] = kid.link.start;
            wide.count[lane] =
                u16::try_from(kid.link.count).expect("a leaf holds at most MAX_LEAF primitives");
        }
        nodes.push(wide);
        for (lane, kid) in kids.iter().enumerate() {
            if kid.link.count == 0 {
                let at = Self::collapse_into(nodes, kid.link.start, children);
                nodes[index].start[lane] = at;
            }
        }
        u32::try_from(index).expect("fewer than 2^32 nodes")
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

    /// Which lanes the binary walk's `f64` test admits ([`culling_hit`]; lane `k` is bit `k`),
    /// and their entries: the binary walk's very formula, `t = (x − O)·(1/D)` in `f64`. The test
    /// of rays without an `f32` twin (axis-parallel ones, or out of [`F32_RANGE`]).
    #[inline(always)]
    fn lanes_f64<V: Dim>(node: &WideNode, r: &RecipRay<V>) -> (u32, [f64; WIDTH]) {
        let mut t_in = [f64::NEG_INFINITY; WIDTH];
        let mut t_out = [f64::INFINITY; WIDTH];
        if r.oblique {
            for axis in 0..V::DIM {
                let (o, inv) = (r.origin[axis], r.inv_dir[axis]);
                // The near plane of the slab by the sign of 1/d, as `box_pair_interval` does.
                let [min, max] = &node.planes[axis];
                let (near, far) = if inv >= 0.0 { (min, max) } else { (max, min) };
                for lane in 0..WIDTH {
                    let tn = (f64::from(near[lane]) - o) * inv;
                    let tf = (f64::from(far[lane]) - o) * inv;
                    t_in[lane] = if tn > t_in[lane] { tn } else { t_in[lane] };
                    t_out[lane] = if tf < t_out[lane] { tf } else { t_out[lane] };
                }
            }
        } else {
            for lane in 0..WIDTH {
                let (mut lo, mut hi) = (r.origin, r.origin);
                for axis in 0..V::DIM {
                    lo[axis] = f64::from(node.planes[axis][0][lane]);
                    hi[axis] = f64::from(node.planes[axis][1][lane]);
                }
                (t_in[lane], t_out[lane]) = r.box_interval(lo, hi);
            }
        }
        let hits =
            (0..WIDTH).fold(0, |bits, lane| bits | u32::from(culling_hit(t_in[lane], t_out[lane])) << lane);
        (hits, t_in)
    }

    /// Front-to-back walk from the root, whose box the ray met (not beyond the visitor's
    /// bound), handing every leaf's primitives (of `prims`, the binary tree's) to the visitor;
    /// `r` is the ray. Boxes are tested in `f32` when the ray and the tree allow it
    /// ([`RecipRay::to_f32`], [`WideBvh::in_f32_range`]), in `f64` otherwise.
    pub(crate) fn walk<V: Dim, R: Recorder<V>, W: Visitor<V>>(
        &self,
        prims: &[Prim],
        r: &RecipRay<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        match r.to_f32().filter(|_| self.in_f32_range) {
            Some(r32) => {
                self.walk_by(prims, |node| r32.box_hits(V::DIM, &node.planes), visitor, stats, rec);
            }
            None => self.walk_by(prims, |node| Self::lanes_f64(node, r), visitor, stats, rec),
        }
    }

    /// The walk, with `lanes(node)` telling which children the ray meets and where it enters
    /// them (an entry never later than the `f64` walk's, so [`beyond`] prunes only what the
    /// binary walk prunes). The nearest hit child of a node is walked next without going
    /// through the stack.
    #[inline(always)]
    fn walk_by<V: Dim, R: Recorder<V>, W: Visitor<V>, T: Copy + Into<f64>>(
        &self,
        prims: &[Prim],
        lanes: impl Fn(&WideNode) -> (u32, [T; WIDTH]),
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        let mut stack: ArrayVec<(Child, f64), STACK_SIZE> = ArrayVec::new();
        let mut child = Child { start: 0, count: 0 };
        loop {
            if child.count > 0 {
                let start = child.start as usize;
                if prims[start..start + child.count as usize].iter().any(|p| visitor.visit(*p, stats, rec)) {
                    return;
                }
            } else {
                let node = &self.nodes[child.start as usize];
                stats.tests.node += u64::from(node.len);
                let (hits, t_in) = lanes(node);
                let bound = visitor.bound();
                // The nearest hit lane goes next; the others wait on the stack (so two hits, the
                // most common case after one, are ordered exactly; more are pushed as they come).
                let mut next: Option<(Child, f64)> = None;
                let mut bits = u32::from(node.used) & hits;
                while bits != 0 {
                    let lane = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let t: f64 = t_in[lane].into();
                    if beyond(t, bound) {
                        continue;
                    }
                    let hit = (Child { start: node.start[lane], count: u32::from(node.count[lane]) }, t);
                    match next {
                        Some(near) if near.1 <= t => stack.push(hit),
                        Some(near) => {
                            stack.push(near);
                            next = Some(hit);
                        }
                        None => next = Some(hit),
                    }
                }
                if let Some((near, _)) = next {
                    child = near;
                    continue;
                }
            }
            // The next pending child whose entry the bound has not passed since it was pushed.
            loop {
                let Some((next, t_in)) = stack.pop() else {
                    return;
                };
                if !beyond(t_in, visitor.bound()) {
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
