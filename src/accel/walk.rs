//! The walk's side of every structure: the question a walk answers, handed each primitive it
//! reaches through a [`Visitor`]. [`Nearest`] keeps the nearest hit by `(t, object, triangle)`,
//! so the order of visits never changes the answer; [`Shadow`] collects occluders with
//! `0 < t < d_L`, ends at an opaque one, takes each transparent one once and reports them in
//! index order, collected in an inline `PrimSet`. An unbounded object (a plane) is tested through
//! [`Visitor::visit_plane`], one code for both questions ([`TakesT`]).
//!
//! `test_prim` is the one counted, recorded object test (`test_prim_found` and `test_prim_t`
//! when the surface or only t is needed); `node_visit` counts and records a hierarchy node's box
//! test, `node_skip` a prune by [`beyond`]; `Mailbox` keeps a primitive from being tested twice
//! by one ray.

use super::Prim;
use crate::bounds::BoundHit;
use crate::geom::ray::Ray;
use crate::geom::slab::culling_hit;
use crate::record::event::{Event, ObjectRef};
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::plane::Plane;
use crate::shape::{Dim, Found, MeshPrepared, SurfaceHit};
use std::cell::RefCell;

/// How an acceleration structure hands primitives to the question being answered.
pub trait Visitor<V: Dim> {
    /// Whether the answer gains from meeting primitives nearest first: true when a hit found
    /// shrinks [`Visitor::bound`] (the nearest hit), false when the bound never moves (a shadow
    /// segment, which any occluder ends). A walk may then take the children in any order.
    const NEAREST_FIRST: bool = true;
    /// Hits at `t` beyond this cannot change the answer: a structure may skip what lies beyond.
    fn bound(&self) -> f64;
    /// Tests a primitive; true when the search is over.
    fn visit<R: Recorder<V>>(&mut self, prim: Prim, stats: &mut Stats, rec: &mut R) -> bool;
    /// [`Visitor::visit`] of an unbounded object, whose plane the caller holds (a visitor may
    /// test it without looking the object up).
    #[inline(always)]
    fn visit_plane<R: Recorder<V>>(
        &mut self,
        prim: Prim,
        _plane: &Plane<V>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> bool {
        self.visit(prim, stats, rec)
    }
}

/// A question that can take a bare `t` for a primitive (a plane's hit, whose point and normal
/// can wait): what lets [`visit_plane_t`] answer both questions with one code.
pub trait TakesT<V: Dim> {
    /// The ray being asked about.
    fn ray(&self) -> &Ray<V>;
    /// Takes a hit of `prim` at `t` (`None`: a miss); true when the search is over.
    fn take_t(&mut self, prim: Prim, t: Option<f64>) -> bool;
}

/// [`Visitor::visit_plane`] of [`Nearest`] and [`Shadow`]: with a recorder, the recorded
/// [`Visitor::visit`]; without, the plane's `t` from the copy the caller holds, counted as one
/// object test like every other, and no lookup in the scene.
#[inline(always)]
fn visit_plane_t<V: Dim, R: Recorder<V>, W: Visitor<V> + TakesT<V>>(
    visitor: &mut W,
    prim: Prim,
    plane: &Plane<V>,
    stats: &mut Stats,
    rec: &mut R,
) -> bool {
    if R::ENABLED {
        return visitor.visit(prim, stats, rec);
    }
    stats.tests.object += 1;
    let t = plane.hit_t(visitor.ray());
    visitor.take_t(prim, t)
}

/// The nearest-hit question: keeps the least `(t, object, part)`.
pub struct Nearest<'a, V: Dim> {
    scene: &'a Scene<V>,
    ray: &'a Ray<V>,
    /// The t of `best` (`+∞` while there is none): what [`Visitor::bound`] answers before every
    /// node and primitive. Kept beside `best` on purpose: reading it out of the `Option` cost
    /// 1.6 % more instructions on mesh-100k (callgrind).
    best_t: f64,
    /// The nearest so far, its surface left to compute where it can wait ([`Found`]).
    best: Option<(Prim, Found<V>)>,
    /// What the ray's mesh tests share, computed at the first
    /// ([`crate::shape::Shape::part_found_prepared`]).
    prepared: Option<MeshPrepared<V>>,
}

impl<'a, V: Dim> Nearest<'a, V> {
    /// The question for `ray`, nothing found yet.
    #[must_use]
    pub fn new(scene: &'a Scene<V>, ray: &'a Ray<V>) -> Self {
        Self { scene, ray, best_t: f64::INFINITY, best: None, prepared: None }
    }
    /// The nearest hit found, named as traces name it.
    #[must_use]
    pub fn found(self) -> Option<(ObjectRef, SurfaceHit<V>)> {
        let (scene, ray) = (self.scene, self.ray);
        self.best.map(|(prim, found)| {
            (object_ref(scene, prim), scene.objects[prim.object()].shape.surface(ray, found))
        })
    }
}

impl<V: Dim> Visitor<V> for Nearest<'_, V> {
    #[inline]
    fn bound(&self) -> f64 {
        self.best_t
    }
    #[inline(always)]
    fn visit<R: Recorder<V>>(&mut self, prim: Prim, stats: &mut Stats, rec: &mut R) -> bool {
        let found = test_prim_found(self.scene, prim, self.ray, &mut self.prepared, stats, rec);
        self.offer(prim, found);
        false
    }
    #[inline(always)]
    fn visit_plane<R: Recorder<V>>(
        &mut self,
        prim: Prim,
        plane: &Plane<V>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> bool {
        visit_plane_t(self, prim, plane, stats, rec)
    }
}

impl<V: Dim> TakesT<V> for Nearest<'_, V> {
    #[inline(always)]
    fn ray(&self) -> &Ray<V> {
        self.ray
    }
    #[inline(always)]
    fn take_t(&mut self, prim: Prim, t: Option<f64>) -> bool {
        self.offer(prim, t.map(Found::At));
        false
    }
}

impl<V: Dim> Nearest<'_, V> {
    /// Keeps `hit` if it is nearer than the best so far.
    #[inline(always)]
    fn offer(&mut self, prim: Prim, found: Option<Found<V>>) {
        if let Some(found) = found {
            let t = found.t();
            // §6: equal t goes to the smaller object, then the smaller triangle.
            #[allow(clippy::float_cmp)] // An exact tie is exactly what the rule is about.
            let closer =
                t < self.best_t || (t == self.best_t && self.best.as_ref().is_none_or(|(p, _)| prim < *p));
            if closer {
                self.best_t = t;
                self.best = Some((prim, found));
            }
        }
    }
}

/// The shadow question: occluders with `0 < t < d_L` (§11 "Shadow rays are segments").
pub struct Shadow<'a, V: Dim> {
    scene: &'a Scene<V>,
    ray: &'a Ray<V>,
    d_l: f64,
    /// Transparent occluders found, one primitive per object.
    transparent: PrimSet,
    /// The opaque occluder that ended the search.
    opaque: Option<Prim>,
    /// What the ray's mesh tests share, computed at the first
    /// ([`crate::shape::Shape::part_hit_t_prepared`]).
    prepared: Option<MeshPrepared<V>>,
}

impl<V: Dim> Visitor<V> for Shadow<'_, V> {
    // The bound is d_L throughout, and the answer (an opaque occluder, else the set of
    // transparent ones) does not depend on the order of the visits.
    const NEAREST_FIRST: bool = false;
    #[inline]
    fn bound(&self) -> f64 {
        self.d_l
    }
    #[inline(always)]
    fn visit<R: Recorder<V>>(&mut self, prim: Prim, stats: &mut Stats, rec: &mut R) -> bool {
        // An object already found multiplies s once: its other triangles need no test.
        if self.transparent.has_object(prim.object) {
            return false;
        }
        let t = test_prim_t(self.scene, prim, self.ray, &mut self.prepared, stats, rec);
        self.offer(prim, t)
    }
    #[inline(always)]
    fn visit_plane<R: Recorder<V>>(
        &mut self,
        prim: Prim,
        plane: &Plane<V>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> bool {
        visit_plane_t(self, prim, plane, stats, rec)
    }
}

impl<V: Dim> TakesT<V> for Shadow<'_, V> {
    #[inline(always)]
    fn ray(&self) -> &Ray<V> {
        self.ray
    }
    #[inline(always)]
    fn take_t(&mut self, prim: Prim, t: Option<f64>) -> bool {
        self.offer(prim, t)
    }
}

impl<'a, V: Dim> Shadow<'a, V> {
    /// The question for the segment of `ray` over `0 < t < d_l`, nothing found yet.
    #[must_use]
    pub fn new(scene: &'a Scene<V>, ray: &'a Ray<V>, d_l: f64) -> Self {
        Self { scene, ray, d_l, transparent: PrimSet::default(), opaque: None, prepared: None }
    }
    /// Reports the occluders found to `on`, until it returns false: the transparent ones in
    /// object-index order, then the opaque one that ended the search. By reference: moving the
    /// question out by value made every shadow ray copy it (a `memcpy` call).
    pub fn report(&mut self, mut on: impl FnMut(ObjectRef) -> bool) {
        let scene = self.scene;
        for &prim in self.transparent.sorted() {
            if !on(object_ref(scene, prim)) {
                return;
            }
        }
        if let Some(prim) = self.opaque {
            on(object_ref(scene, prim));
        }
    }
}

impl<V: Dim> Shadow<'_, V> {
    /// Takes the primitive's hit at `t` if it lies on the segment; true when it ends the search.
    #[inline(always)]
    fn offer(&mut self, prim: Prim, t: Option<f64>) -> bool {
        let Some(t) = t else {
            return false;
        };
        if !(t < self.d_l) {
            return false;
        }
        if self.scene.material_of(prim.object()).transmits() {
            self.transparent.push(prim);
            false
        } else {
            self.opaque = Some(prim);
            true
        }
    }
}

/// The transparent occluders of one shadow ray, one primitive per object: a handful at most in
/// any real scene, so the first [`PrimSet::INLINE`] live on the stack and a shadow ray allocates
/// nothing (the heap holds the rest of a segment through many glass objects).
#[derive(Debug, Default)]
struct PrimSet {
    inline: [Prim; PrimSet::INLINE],
    len: usize,
    spill: Vec<Prim>,
}

impl PrimSet {
    /// How many primitives fit without allocating.
    const INLINE: usize = 4;
    /// Whether a primitive of `object` is in the set.
    #[inline(always)]
    fn has_object(&self, object: u32) -> bool {
        let of = |p: &Prim| p.object == object;
        self.inline[..self.len].iter().any(of) || (!self.spill.is_empty() && self.spill.iter().any(of))
    }
    /// Adds a primitive (of an object not yet in the set).
    #[inline]
    fn push(&mut self, prim: Prim) {
        if self.len < Self::INLINE {
            self.inline[self.len] = prim;
            self.len += 1;
        } else {
            self.spill.push(prim);
        }
    }
    /// The primitives in ascending order (by object: the order of `s = Π kt`).
    #[inline(always)]
    fn sorted(&mut self) -> &[Prim] {
        if self.len <= 1 && self.spill.is_empty() {
            // Nearly every shadow ray: nothing or one object to order.
            return &self.inline[..self.len];
        }
        self.sort_many()
    }
    /// [`PrimSet::sorted`] of two or more primitives.
    #[cold]
    fn sort_many(&mut self) -> &[Prim] {
        if !self.spill.is_empty() {
            self.spill.extend_from_slice(&self.inline[..self.len]);
            self.len = 0;
            self.spill.sort_unstable();
            return &self.spill;
        }
        let set = &mut self.inline[..self.len];
        set.sort_unstable();
        set
    }
}

/// How a primitive is named in traces: its object, and for a mesh its triangle's OBJ index.
#[must_use]
pub fn object_ref<V: Dim>(scene: &Scene<V>, prim: Prim) -> ObjectRef {
    ObjectRef { index: prim.object(), triangle: scene.objects[prim.object()].shape.part_id(prim.part()) }
}

/// One ray–primitive test, counted and recorded (`object_test` with every root).
#[inline(always)]
pub fn test_prim<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    prim: Prim,
    ray: &Ray<V>,
    stats: &mut Stats,
    rec: &mut R,
) -> Option<SurfaceHit<V>> {
    stats.tests.object += 1;
    let shape = &scene.objects[prim.object()].shape;
    let hit = shape.part_hit(prim.part(), ray);
    rec.event(|| Event::ObjectTest {
        object: object_ref(scene, prim),
        roots: shape.part_roots(prim.part(), ray),
        accepted: hit.map(|h| h.t),
    });
    hit
}

/// A hierarchy node's box met by the ray over `[t_in, t_out]` (BVH, octree): counted as one node
/// test, recorded as a `node_visit` event, with the culling decision of [`culling_hit`].
#[inline(always)]
pub(crate) fn node_visit<V: Dim, R: Recorder<V>>(
    structure: &'static str,
    (t_in, t_out): (f64, f64),
    (node, depth): (usize, u32),
    stats: &mut Stats,
    rec: &mut R,
) -> BoundHit {
    stats.tests.node += 1;
    rec.event(|| Event::NodeVisit { structure, node, depth, t_in, t_out });
    BoundHit { t_in, t_out, hit: culling_hit(t_in, t_out) }
}

/// A hierarchy node whose box the ray met at `t_in`, skipped because `t_in` lies beyond
/// `t_best` ([`beyond`]): recorded as a `node_skip` event, so that a figure can tell it from a
/// missed box.
#[inline(always)]
pub(crate) fn node_skip<V: Dim, R: Recorder<V>>(
    structure: &'static str,
    node: usize,
    t_in: f64,
    t_best: f64,
    rec: &mut R,
) {
    rec.event(|| Event::NodeSkip { structure, node, t_in, t_best });
}

/// [`test_prim`] as the nearest-hit search keeps it ([`crate::shape::Shape::part_found`]): the
/// same count, the same event, the same hit, but a sphere's or plane's point and normal wait for
/// the nearest, and a mesh's triangles share the ray's `prepared` shear.
#[inline(always)]
pub fn test_prim_found<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    prim: Prim,
    ray: &Ray<V>,
    prepared: &mut Option<MeshPrepared<V>>,
    stats: &mut Stats,
    rec: &mut R,
) -> Option<Found<V>> {
    if R::ENABLED {
        return test_prim(scene, prim, ray, stats, rec).map(Found::Hit);
    }
    stats.tests.object += 1;
    scene.objects[prim.object()].shape.part_found_prepared(prim.part(), ray, prepared)
}

/// [`test_prim`] for a question that needs only t (a shadow segment): the same count, the same
/// event, the same t, but spheres, planes and mesh triangles skip their point and normal, and a
/// mesh's triangles share the ray's `prepared` shear.
#[inline(always)]
pub fn test_prim_t<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    prim: Prim,
    ray: &Ray<V>,
    prepared: &mut Option<MeshPrepared<V>>,
    stats: &mut Stats,
    rec: &mut R,
) -> Option<f64> {
    if R::ENABLED {
        return test_prim(scene, prim, ray, stats, rec).map(|h| h.t);
    }
    stats.tests.object += 1;
    scene.objects[prim.object()].shape.part_hit_t_prepared(prim.part(), ray, prepared)
}

/// §11, the prune test of every traversal: a node or cell entered at `t_in` can hold nothing
/// that beats `bound` when `t_in·(1 − 2⁻⁴⁰) > bound` (for `t_in > 0`). The slack of 2⁻⁴⁰ (about
/// 10⁻¹²) covers the rounding of the box's t (3 roundings) and of any object's own t, so a
/// primitive whose computed t ties or beats the bound is never skipped: pruning changes the
/// number of tests, never the answer. A bound is never negative (a hit's t, a light's
/// distance, or +∞), so a `t_in ≤ 0` is never beyond it, and the one product decides.
#[inline]
#[must_use]
pub fn beyond(t_in: f64, bound: f64) -> bool {
    /// `1 − 2⁻⁴⁰`, exact in `f64`.
    const KEEP: f64 = 1.0 - 1.0 / (1u64 << 40) as f64;
    debug_assert!(bound >= 0.0, "a bound is never negative");
    t_in * KEEP > bound
}

thread_local! {
    /// The mailbox of the grid and the octree (Amanatides & Woo): per thread, a stamp per
    /// primitive; a primitive was tested by the current ray iff its stamp equals the ray's.
    static MAILBOX: RefCell<Mailbox> = const { RefCell::new(Mailbox { ray: 0, stamps: Vec::new() }) };
}

/// Remembers which primitives the current ray has tested, so none is tested twice.
pub struct Mailbox {
    ray: u32,
    stamps: Vec<u32>,
}

impl Mailbox {
    /// Runs `f` with this thread's mailbox emptied for a new ray over `n` primitives.
    pub fn with<T>(n: usize, f: impl FnOnce(&mut Mailbox) -> T) -> T {
        MAILBOX.with(|cell| {
            let mut m = cell.borrow_mut();
            if m.stamps.len() < n {
                m.stamps.resize(n, 0);
            }
            m.ray = m.ray.wrapping_add(1);
            if m.ray == 0 {
                // After 2^32 rays the stamps could repeat: start afresh.
                m.stamps.iter_mut().for_each(|s| *s = 0);
                m.ray = 1;
            }
            f(&mut m)
        })
    }
    /// True the first time primitive `i` is offered for the current ray.
    #[inline]
    pub fn first_visit(&mut self, i: usize) -> bool {
        let fresh = self.stamps[i] != self.ray;
        self.stamps[i] = self.ray;
        fresh
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_prune_is_the_slack_subtracted_for_every_bound_a_walk_has() {
        // The earlier form `t − |t|·2⁻⁴⁰ > bound`: the same decision whenever bound ≥ 0.
        let slack = 1.0 / (1u64 << 40) as f64;
        let ts = [
            -1e300,
            -2.5,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            5e-324,
            1e-310,
            1e-12,
            0.5,
            1.0,
            3.0,
            1e15,
            1e300,
            f64::INFINITY,
        ];
        for &t in &ts {
            for bound in ts.iter().map(|b: &f64| b.abs()).chain([1.0 - 1e-12, 3.0 * (1.0 - slack)]) {
                for t in [t, t.next_up(), t.next_down()] {
                    if t == f64::INFINITY {
                        // The earlier form made ∞ − ∞ = NaN and kept a box entered at +∞.
                        assert_eq!(beyond(t, bound), bound < f64::INFINITY);
                    } else {
                        assert_eq!(beyond(t, bound), t - t.abs() * slack > bound, "{t:e} {bound:e}");
                    }
                }
            }
        }
    }

    fn prim(object: u32) -> Prim {
        Prim { object, part: 0 }
    }

    #[test]
    fn a_prim_set_sorts_by_object_inline_and_spilled() {
        let mut few = PrimSet::default();
        for o in [7, 2, 5] {
            few.push(prim(o));
        }
        assert!(few.has_object(5) && !few.has_object(3));
        assert_eq!(few.sorted(), &[prim(2), prim(5), prim(7)]);
        // More than the inline capacity: the rest goes to the heap, and order still holds.
        let mut many = PrimSet::default();
        for o in [9, 1, 8, 3, 6, 0, 4] {
            many.push(prim(o));
        }
        assert!((0..10).all(|o| many.has_object(o) == [9, 1, 8, 3, 6, 0, 4].contains(&o)));
        let objects: Vec<u32> = many.sorted().iter().map(|p| p.object).collect();
        assert_eq!(objects, [0, 1, 3, 4, 6, 8, 9]);
    }
}
