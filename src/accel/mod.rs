//! Acceleration structures (algorithm.md §7 "Cost", §9 "Fewer intersection tests"): every one
//! answers the same two questions — the nearest hit of a ray, and the occluders of a shadow
//! segment — and must give exactly the answer of brute force (`list`): the same object, the same
//! t bit for bit, equal t broken by the object index, then the triangle index (§6).
//!
//! The structures see *primitives* ([`Prim`]): every bounded object is one, except a mesh,
//! whose triangles are one each. Unbounded objects (planes, 2D lines) are never inside a
//! structure: they are tested first, directly, and their hit bounds the search.
//!
//! Each structure walks its primitives in its own order and hands each to a [`Visitor`]:
//! [`Nearest`] keeps the nearest hit by `(t, object, triangle)`, so the order of visits never
//! changes the answer; [`Shadow`] collects occluders with `0 < t < d_L`. A structure may skip
//! whatever starts beyond the visitor's [`Visitor::bound`] (with the slack of [`beyond`]).
//!
//! `test_prim` is the one counted, recorded object test (`test_prim_t` when only t is needed);
//! `node_skip` records a prune by `beyond`; `Mailbox` keeps a primitive from being tested twice by
//! one ray. `Shadow` ends at an opaque occluder, takes each transparent one once and reports them
//! in index order, collected in an inline `PrimSet`. `Layout` and `TreeNode` show a built
//! structure's volumes, nodes or cells to the figures. The unbounded objects are kept as copies,
//! tested through `Visitor::visit_plane`.

pub mod bvh;
pub mod grid;
pub mod list;
pub mod octree;
pub mod volumes;

use crate::bounds::aabb::Aabb;
use crate::bounds::{BoundHit, BoundingVolume, Hull, VolumeKind};
use crate::geom::ray::Ray;
use crate::geom::slab::culling_hit;
use crate::record::event::{Event, ObjectRef};
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::plane::Plane;
use crate::shape::{Dim, Facet, Found, Shape, SurfaceHit};
use std::cell::RefCell;

/// The `--accel` choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelKind {
    /// Brute force: every object, in index order (§7: `O(n)` per ray).
    None,
    /// A bounding volume per primitive (§9.1), tested before the primitive.
    Bounds,
    /// A bounding volume hierarchy (§9.3).
    Bvh,
    /// A regular grid walked by the 3D DDA (§9.2).
    Grid,
    /// An octree (a quadtree in 2D) (§9.2, adaptive).
    Octree,
}

impl AccelKind {
    /// Every kind, in the order of the lecture.
    pub const ALL: [Self; 5] = [Self::None, Self::Bounds, Self::Bvh, Self::Grid, Self::Octree];
    /// The name used on the command line and in statistics.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Bounds => "bounds",
            Self::Bvh => "bvh",
            Self::Grid => "grid",
            Self::Octree => "octree",
        }
    }
    /// The kind of a name, if any.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// How to build a structure: its kind and the options of some kinds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AccelOptions {
    /// Which structure.
    pub kind: AccelKind,
    /// The per-primitive volume of [`AccelKind::Bounds`].
    pub volume: VolumeKind,
    /// The grid's cells per axis (`--grid NX,NY,NZ`); `None` for the heuristic of `grid`.
    pub grid: Option<Vec<usize>>,
}

impl AccelOptions {
    /// `kind` with the default options: axis-aligned boxes, the grid's own resolution.
    #[must_use]
    pub fn of(kind: AccelKind) -> Self {
        Self { kind, volume: VolumeKind::Aabb, grid: None }
    }
}

/// A primitive: part `part` of object `object` (a mesh triangle, or the object itself, part 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Prim {
    /// Index in the scene's `objects`.
    pub object: u32,
    /// The part: a mesh's triangle (by its position in the mesh), else 0.
    pub part: u32,
}

impl Prim {
    /// The object index as `usize`.
    #[must_use]
    pub fn object(self) -> usize {
        self.object as usize
    }
    /// The part index as `usize`.
    #[must_use]
    pub fn part(self) -> usize {
        self.part as usize
    }
}

/// The structure itself.
#[derive(Clone, Debug)]
enum Structure<V: Dim> {
    List,
    Bounds(volumes::Volumes<V>),
    Bvh(bvh::Bvh<V>),
    Grid(grid::Grid<V>),
    Octree(octree::Octree<V>),
}

/// A built structure as a figure draws it: its volumes, its nodes or its cells.
#[derive(Clone, Debug)]
pub enum Layout<'a, V: Dim> {
    /// Brute force: nothing to draw.
    List,
    /// One bounding volume per primitive, in object order.
    Volumes(&'a [(Prim, BoundingVolume<V>)]),
    /// A hierarchy (BVH, octree): entry `k` is the node that `node_visit` events call `k`.
    Tree(Vec<TreeNode<V>>),
    /// A regular grid: its box and its cells per axis.
    Grid {
        /// The grid's box.
        bounds: Aabb<V>,
        /// Cells per axis.
        cells: Vec<usize>,
    },
}

/// A node of a hierarchy, for drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeNode<V> {
    /// Its box.
    pub bounds: Aabb<V>,
    /// Its depth (the root is 0).
    pub depth: u32,
    /// Its children's node numbers (none for a leaf).
    pub children: Vec<usize>,
    /// A leaf's primitives.
    pub prims: Vec<Prim>,
}

/// A built acceleration structure over a scene's objects.
#[derive(Clone, Debug)]
pub struct Accel<V: Dim> {
    kind: AccelKind,
    /// Unbounded objects (planes; lines in 2D), tested before the structure, each with a copy
    /// of its plane so that the test every ray makes needs no lookup in the scene.
    unbounded: Vec<(Prim, Plane<V>)>,
    structure: Structure<V>,
}

impl<V: Dim> Accel<V> {
    /// Builds the structure of `kind`, default options, over `scene` (complete and valid).
    #[must_use]
    pub fn build(scene: &Scene<V>, kind: AccelKind) -> Self {
        Self::build_with(scene, &AccelOptions::of(kind))
    }
    /// Builds the structure `options` describe over `scene`.
    #[must_use]
    pub fn build_with(scene: &Scene<V>, options: &AccelOptions) -> Self {
        let mut unbounded = Vec::new();
        let mut prims = Vec::new();
        for (index, object) in scene.objects.iter().enumerate() {
            let object_index = u32::try_from(index).expect("fewer than 2^32 objects");
            if object.shape.bounds().is_none() {
                let Shape::Plane(plane) = object.shape else { unreachable!("only a plane is unbounded") };
                unbounded.push((Prim { object: object_index, part: 0 }, plane));
                continue;
            }
            for part in 0..object.shape.parts() {
                prims.push(Prim {
                    object: object_index,
                    part: u32::try_from(part).expect("fewer than 2^32 parts"),
                });
            }
        }
        let structure = match options.kind {
            AccelKind::None => Structure::List,
            AccelKind::Bounds => Structure::Bounds(volumes::Volumes::build(scene, &prims, options.volume)),
            AccelKind::Bvh => Structure::Bvh(bvh::Bvh::build(scene, prims)),
            AccelKind::Grid => Structure::Grid(grid::Grid::build(scene, &prims, options.grid.as_deref())),
            AccelKind::Octree => Structure::Octree(octree::Octree::build(scene, &prims)),
        };
        Self { kind: options.kind, unbounded, structure }
    }
    /// Which structure this is.
    #[must_use]
    pub fn kind(&self) -> AccelKind {
        self.kind
    }
    /// The grid's cells per axis, when this is a grid.
    #[must_use]
    pub fn grid_resolution(&self) -> Option<Vec<usize>> {
        match &self.structure {
            Structure::Grid(g) => Some(g.resolution()),
            _ => None,
        }
    }

    /// The built structure as the figures draw it (read only; `figure::kinds` never walks it).
    #[must_use]
    pub fn layout(&self) -> Layout<'_, V> {
        match &self.structure {
            Structure::List => Layout::List,
            Structure::Bounds(v) => Layout::Volumes(v.entries()),
            Structure::Bvh(b) => Layout::Tree(b.tree()),
            Structure::Grid(g) => Layout::Grid { bounds: g.bounds(), cells: g.resolution() },
            Structure::Octree(o) => Layout::Tree(o.tree()),
        }
    }

    /// Walks primitives through `visitor`: unbounded objects first, then the structure.
    fn search<R: Recorder<V>, W: Visitor<V>>(
        &self,
        scene: &Scene<V>,
        ray: &Ray<V>,
        visitor: &mut W,
        stats: &mut Stats,
        rec: &mut R,
    ) {
        if let Structure::List = self.structure {
            list::walk(scene, visitor, stats, rec);
            return;
        }
        for (prim, plane) in &self.unbounded {
            if visitor.visit_plane(*prim, plane, stats, rec) {
                return;
            }
        }
        // The BVH, the default, walks inline, in the recursion's own frame. The other structures'
        // walks are out of line (`#[inline(never)]` on each), so that the recursion's hot code
        // stays compact: 2–5 % faster on Whitted's scene in every sampling mode, and within the
        // noise (±2 %) on the sphere lattice and the mesh (35eb3bd; bench/README.md, "Decisions
        // that were measured").
        match &self.structure {
            Structure::List => {}
            Structure::Bounds(v) => v.walk(scene, ray, visitor, stats, rec),
            Structure::Bvh(b) => b.walk(ray, visitor, stats, rec),
            Structure::Grid(g) => g.walk(scene, ray, visitor, stats, rec),
            Structure::Octree(o) => o.walk(ray, visitor, stats, rec),
        }
    }

    /// The nearest hit with `t > 0`; equal t goes to the smaller object index, then the smaller
    /// triangle index (§6).
    #[inline]
    pub fn nearest<R: Recorder<V>>(
        &self,
        scene: &Scene<V>,
        ray: &Ray<V>,
        stats: &mut Stats,
        rec: &mut R,
    ) -> Option<(ObjectRef, SurfaceHit<V>)> {
        let mut visitor = Nearest::new(scene, ray);
        self.search(scene, ray, &mut visitor, stats, rec);
        visitor.found()
    }

    /// Reports each distinct object with a hit at `0 < t < d_L` to `on`, until `on` returns
    /// false. An opaque occluder ends the search at once; transparent ones are reported once
    /// each (a mesh is one object, however many of its triangles the segment crosses), in
    /// object-index order, so that `s = Π kt` is the same product whatever the structure.
    #[inline]
    pub fn occluders<R: Recorder<V>>(
        &self,
        scene: &Scene<V>,
        ray: &Ray<V>,
        d_l: f64,
        stats: &mut Stats,
        rec: &mut R,
        mut on: impl FnMut(ObjectRef) -> bool,
    ) {
        let mut visitor = Shadow { scene, ray, d_l, transparent: PrimSet::default(), opaque: None };
        self.search(scene, ray, &mut visitor, stats, rec);
        let opaque = visitor.opaque;
        for &prim in visitor.transparent.sorted() {
            if !on(object_ref(scene, prim)) {
                return;
            }
        }
        if let Some(prim) = opaque {
            on(object_ref(scene, prim));
        }
    }
}

/// How an acceleration structure hands primitives to the question being answered.
pub trait Visitor<V: Dim> {
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
}

impl<'a, V: Dim> Nearest<'a, V> {
    /// The question for `ray`, nothing found yet.
    #[must_use]
    pub fn new(scene: &'a Scene<V>, ray: &'a Ray<V>) -> Self {
        Self { scene, ray, best_t: f64::INFINITY, best: None }
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
        let found = test_prim_found(self.scene, prim, self.ray, stats, rec);
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
        if R::ENABLED {
            return self.visit(prim, stats, rec);
        }
        stats.tests.object += 1;
        self.offer(prim, plane.hit_t(self.ray).map(Found::At));
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
}

impl<V: Dim> Visitor<V> for Shadow<'_, V> {
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
        let t = test_prim_t(self.scene, prim, self.ray, stats, rec);
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
        if R::ENABLED {
            return self.visit(prim, stats, rec);
        }
        stats.tests.object += 1;
        self.offer(prim, plane.hit_t(self.ray))
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

/// [`test_prim`] as the nearest-hit search keeps it ([`Shape::part_found`]): the same count, the
/// same event, the same hit, but a sphere's or plane's point and normal wait for the nearest.
#[inline(always)]
pub fn test_prim_found<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    prim: Prim,
    ray: &Ray<V>,
    stats: &mut Stats,
    rec: &mut R,
) -> Option<Found<V>> {
    if R::ENABLED {
        return test_prim(scene, prim, ray, stats, rec).map(Found::Hit);
    }
    stats.tests.object += 1;
    scene.objects[prim.object()].shape.part_found(prim.part(), ray)
}

/// [`test_prim`] for a question that needs only t (a shadow segment): the same count, the same
/// event, the same t, but spheres and planes skip their point and normal.
#[inline(always)]
pub fn test_prim_t<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    prim: Prim,
    ray: &Ray<V>,
    stats: &mut Stats,
    rec: &mut R,
) -> Option<f64> {
    if R::ENABLED {
        return test_prim(scene, prim, ray, stats, rec).map(|h| h.t);
    }
    stats.tests.object += 1;
    scene.objects[prim.object()].shape.part_hit_t(prim.part(), ray)
}

/// The bounds of a primitive, grown by a few ulps so that rounding in `C ± r` never leaves part
/// of the object outside (`None` only for unbounded objects, which are never primitives).
#[must_use]
pub fn prim_bounds<V: Dim>(scene: &Scene<V>, prim: Prim) -> Aabb<V> {
    let (min, max) =
        scene.objects[prim.object()].shape.part_bounds(prim.part()).unwrap_or((V::ZERO, V::ZERO));
    Aabb::new(min, max).padded()
}

/// What a bounding volume is fitted around, for a primitive.
#[must_use]
pub fn prim_hull<V: Dim>(scene: &Scene<V>, prim: Prim) -> Hull<V> {
    use crate::shape::Parts;
    match &scene.objects[prim.object()].shape {
        Shape::Sphere(s) => Hull::Ball { center: s.center, radius: s.radius },
        Shape::Box(b) => Hull::Points(
            (0..1usize << V::DIM)
                .map(|corner| {
                    let mut p = b.min;
                    for a in 0..V::DIM {
                        if corner >> a & 1 == 1 {
                            p[a] = b.max[a];
                        }
                    }
                    p
                })
                .collect(),
        ),
        Shape::Facet(f) => Hull::Points(f.points()),
        Shape::Mesh(m) => Hull::Points(m.points(prim.part())),
        Shape::Plane(_) => Hull::Points(vec![V::ZERO]),
    }
}

/// §11, the prune test of every traversal: a node or cell entered at `t_in` can hold nothing
/// that beats `bound` when `t_in·(1 − 2⁻⁴⁰) > bound` (for `t_in > 0`). The slack of 2⁻⁴⁰ (about
/// 10⁻¹²) covers the rounding of the box's t (3 roundings) and of any object's own t, so a
/// primitive whose computed t ties or beats the bound is never skipped: pruning changes the
/// number of tests, never the answer.
#[inline]
#[must_use]
pub fn beyond(t_in: f64, bound: f64) -> bool {
    const SLACK: f64 = 1.0 / (1u64 << 40) as f64;
    t_in - t_in.abs() * SLACK > bound
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
