//! Acceleration structures (algorithm.md §7 "Cost", §9 "Fewer intersection tests"): every one
//! answers the same two questions — the nearest hit of a ray, and the occluders of a shadow
//! segment — and must give exactly the answer of brute force (`list`): the same object, the same
//! t bit for bit, equal t broken by the object index, then the triangle index (§6).
//!
//! The structures see *primitives* ([`Prim`]): every bounded object is one, except a mesh,
//! whose triangles are one each. Unbounded objects (planes, 2D lines) are never inside a
//! structure: they are tested first, directly, and their hit bounds the search; they are kept
//! as copies, tested through `Visitor::visit_plane`.
//!
//! Each structure walks its primitives in its own order and hands each to a [`Visitor`]
//! (`walk`: the questions [`Nearest`] and [`Shadow`], the counted tests, the prune test
//! [`beyond`]); a structure may skip whatever starts beyond the visitor's [`Visitor::bound`].
//! `layout` shows a built structure's volumes, nodes or cells to the figures ([`Layout`],
//! [`TreeNode`]). This file: the kinds and options, [`Accel`] (build, then `nearest` and
//! `occluders` through one `search`), and what a structure's build reads of a primitive
//! ([`prim_bounds`], [`prim_hull`]).

pub mod binned;
pub mod bvh;
pub mod grid;
pub mod layout;
pub mod list;
pub mod octree;
// The packets serve the render's run-time SIMD (`crate::trace::packet`), on x86-64 only: elsewhere
// (the WebAssembly module) every ray is searched alone.
#[cfg(target_arch = "x86_64")]
pub mod packet;
pub mod volumes;
pub mod walk;
pub mod wide;

pub use layout::{Layout, TreeNode};
pub use walk::{
    beyond, object_ref, test_prim, test_prim_found, test_prim_t, Mailbox, Nearest, Shadow, Visitor,
};
pub(crate) use walk::{node_skip, node_visit};

use crate::bounds::aabb::Aabb;
use crate::bounds::Hull;
use crate::bounds::VolumeKind;
use crate::geom::ray::Ray;
use crate::record::event::ObjectRef;
use crate::record::stats::Stats;
use crate::record::Recorder;
use crate::scene::Scene;
use crate::shape::plane::Plane;
use crate::shape::{Dim, Facet, Shape, SurfaceHit};

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
        Self::build_in(scene, options, false)
    }

    /// Builds the structure `options` describe over `scene` as a render walks it, without a
    /// recorder: the answers of [`Accel::build_with`] then [`Accel::for_render`], the same wide
    /// nodes, but a BVH of more than [`binned::LARGE`] primitives is built straight into its
    /// wide nodes, without the binary tree that only the recorded walk and the figures read (a
    /// recorder walking it sees no `node_visit` event; `layout` shows its root alone).
    #[must_use]
    pub fn build_for_render(scene: &Scene<V>, options: &AccelOptions) -> Self {
        Self::build_in(scene, options, true)
    }

    fn build_in(scene: &Scene<V>, options: &AccelOptions, for_render: bool) -> Self {
        let mut unbounded = Vec::new();
        // Sized once: a million triangles' list grown by doubling copied itself.
        let mut prims = Vec::with_capacity(scene.objects.iter().map(|o| o.shape.parts()).sum());
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
            AccelKind::Bvh => Structure::Bvh(bvh::Bvh::build(scene, prims, for_render)),
            AccelKind::Grid => Structure::Grid(grid::Grid::build(scene, &prims, options.grid.as_deref())),
            AccelKind::Octree => Structure::Octree(octree::Octree::build(scene, &prims)),
        };
        Self { kind: options.kind, unbounded, structure }
    }
    /// This structure as a render walks it: a BVH gains its wide copy ([`wide::WideBvh`]), which
    /// the walk takes when no recorder listens; every answer is the same, bit for bit, and the
    /// recorded walk (the traces' `node_visit` events, the figures) keeps the binary tree. Only
    /// the count of node tests differs (one per child box of a wide node).
    /// [`Accel::build_for_render`] gives the same wide tree in one step.
    #[must_use]
    pub fn for_render(mut self) -> Self {
        if let Structure::Bvh(b) = &mut self.structure {
            b.widen();
        }
        self
    }
    /// The wide nodes of a BVH made for a render ([`Accel::for_render`]), if it has them.
    #[must_use]
    pub fn wide_nodes(&self) -> Option<usize> {
        match &self.structure {
            Structure::Bvh(b) => b.wide().map(wide::WideBvh::node_count),
            _ => None,
        }
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
        on: impl FnMut(ObjectRef) -> bool,
    ) {
        let mut visitor = Shadow::new(scene, ray, d_l);
        self.search(scene, ray, &mut visitor, stats, rec);
        visitor.report(on);
    }
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
