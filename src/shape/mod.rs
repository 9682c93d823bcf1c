//! Primitives (algorithm.md §3 "Outward normals", §9, §11 "Roots", "Triangles"): each gives every
//! root along a ray (for the trace), the nearest hit with its outward normal, its bounds and its
//! scale (for the spawn offset). Spheres, planes and boxes are one code for 2D and 3D; the flat
//! primitives differ by dimension and sit behind [`Dim::Facet`].
//!
//! A `Shape` is found through its parts: `parts` and `part_hit` see a mesh's triangles, else the
//! object itself (`Parts` is a many-part object). A sphere's or plane's hit is kept as its t
//! (`part_found`, `Found`); its I and N are computed once, for the nearest, by `surface`.
//! A mesh's triangle tests share what depends on the ray alone (`Parts::prepare`: the
//! triangle test's shear), computed once per ray by the search (`part_found_prepared`).

pub mod aabox;
pub mod mesh;
pub mod plane;
pub mod polygon;
pub mod sphere;
pub mod triangle;

use crate::geom::ray::Ray;
use crate::geom::Vector;
use glam::{DVec2, DVec3};

/// A dimension: its vector type and the flat primitive it knows (3D triangles, 2D polygons).
pub trait Dim: Vector {
    /// The flat primitive of this dimension: a watertight triangle in 3D, a polygon or segment in 2D.
    type Facet: Facet<Self>;
    /// A triangle mesh in 3D; in 2D a type with no values.
    type Mesh: Parts<Self>;
    /// `"2D"` or `"3D"`.
    const NAME: &'static str;
}

impl Dim for DVec3 {
    type Facet = triangle::Triangle;
    type Mesh = mesh::Mesh;
    const NAME: &'static str = "3D";
}

impl Dim for DVec2 {
    type Facet = polygon::Polygon;
    type Mesh = mesh::NoMesh;
    const NAME: &'static str = "2D";
}

/// Where a ray meets a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit<V> {
    /// Distance along the (unit) ray.
    pub t: f64,
    /// The hit point I, re-projected onto the surface.
    pub point: V,
    /// The outward unit normal N at I (§3).
    pub normal: V,
}

/// What the nearest-hit search keeps of a primitive's hit until it knows the nearest: the whole
/// hit where finding I and N again would mean testing again (boxes, flat primitives, meshes), and
/// `t` alone for spheres and planes, whose I and N follow from `t`
/// ([`Shape::surface`]): a ray that meets the floor and then a sphere in front of it computes
/// one surface, not two, and the search copies a `t`, not a whole hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Found<V> {
    /// A sphere's or a plane's hit at this `t`.
    At(f64),
    /// The whole hit.
    Hit(SurfaceHit<V>),
}

impl<V> Found<V> {
    /// The hit's distance.
    #[inline(always)]
    pub fn t(&self) -> f64 {
        match self {
            Self::At(t) => *t,
            Self::Hit(hit) => hit.t,
        }
    }
}

/// A flat primitive: the dimension-specific part of [`Shape`].
pub trait Facet<V>: Clone + std::fmt::Debug + Send + Sync + 'static {
    /// The nearest hit with `t > 0`, with the outward normal.
    fn hit(&self, ray: &Ray<V>) -> Option<SurfaceHit<V>>;
    /// Every root along the ray's line, ascending, whatever its sign.
    fn roots(&self, ray: &Ray<V>) -> Vec<f64>;
    /// The axis-aligned bounds `(min, max)`.
    fn bounds(&self) -> (V, V);
    /// The largest |coordinate| of its vertices (the object scale of the spawn offset, §11).
    fn scale(&self) -> f64;
    /// Its vertices (for fitting bounding volumes).
    fn points(&self) -> Vec<V>;
    /// A short name for messages and `check`: `triangle`, `segment`, `polygon`.
    fn kind(&self) -> &'static str;
    /// Whether the primitive itself shares a point with the closed box `[lo, hi]` (its bounding
    /// box may overlap a box it does not reach).
    fn meets_box(&self, lo: V, hi: V) -> bool;
}

/// An object made of many parts (a mesh's triangles), each tested on its own.
pub trait Parts<V>: Clone + std::fmt::Debug + Send + Sync + 'static {
    /// How many parts.
    fn count(&self) -> usize;
    /// The nearest hit of part `k` with `t > 0`.
    fn hit(&self, k: usize, ray: &Ray<V>) -> Option<SurfaceHit<V>>;
    /// Every root of part `k`, ascending.
    fn roots(&self, k: usize, ray: &Ray<V>) -> Vec<f64>;
    /// The axis-aligned bounds of part `k`.
    fn bounds(&self, k: usize) -> (V, V);
    /// The vertices of part `k`.
    fn points(&self, k: usize) -> Vec<V>;
    /// The part's index in its file (a mesh triangle's index in the OBJ).
    fn id(&self, k: usize) -> usize;
    /// The largest |coordinate| of all its vertices (the spawn offset's object scale, §11).
    fn scale(&self) -> f64;
    /// Degenerate parts skipped when it was built.
    fn skipped(&self) -> usize;
    /// Whether part `k` itself shares a point with the closed box `[lo, hi]`.
    fn meets_box(&self, k: usize, lo: V, hi: V) -> bool;
    /// What every test of one ray against these parts shares, computed once per ray
    /// ([`Parts::prepare`]): a mesh's triangle shear; nothing elsewhere.
    type Prepared: Copy;
    /// The shared part of `ray`'s tests.
    fn prepare(ray: &Ray<V>) -> Self::Prepared;
    /// [`Parts::hit`] with `prepared = prepare(ray)`: the same hit, bit for bit.
    fn hit_prepared(&self, k: usize, ray: &Ray<V>, prepared: &Self::Prepared) -> Option<SurfaceHit<V>>;
    /// `hit_prepared(k, ray, prepared).map(|h| h.t)`, without I and N: what a shadow ray asks.
    fn hit_t_prepared(&self, k: usize, ray: &Ray<V>, prepared: &Self::Prepared) -> Option<f64>;
}

/// What a ray's tests of a mesh's triangles share ([`Parts::prepare`]).
pub type MeshPrepared<V> = <<V as Dim>::Mesh as Parts<V>>::Prepared;

/// A primitive of a scene, in 2D or 3D.
#[derive(Clone, Debug)]
pub enum Shape<V: Dim> {
    /// A sphere (a circle in 2D).
    Sphere(sphere::Sphere<V>),
    /// A plane (a line in 2D); unbounded.
    Plane(plane::Plane<V>),
    /// An axis-aligned box (a rectangle in 2D).
    Box(aabox::AaBox<V>),
    /// A triangle in 3D; a triangle, segment or polygon in 2D.
    Facet(V::Facet),
    /// A triangle mesh (3D only): one object of many triangles.
    Mesh(V::Mesh),
}

impl<V: Dim> Shape<V> {
    /// The nearest hit with `t > 0`.
    #[inline]
    pub fn hit(&self, ray: &Ray<V>) -> Option<SurfaceHit<V>> {
        match self {
            Self::Sphere(s) => s.hit(ray),
            Self::Plane(p) => p.hit(ray),
            Self::Box(b) => b.hit(ray),
            Self::Facet(f) => f.hit(ray),
            Self::Mesh(m) => {
                // The nearest triangle; strict `<` keeps the smaller index on equal t (§6).
                let mut best: Option<SurfaceHit<V>> = None;
                for k in 0..m.count() {
                    if let Some(h) = m.hit(k, ray) {
                        if best.is_none_or(|b| h.t < b.t) {
                            best = Some(h);
                        }
                    }
                }
                best
            }
        }
    }
    /// Every root along the ray's line, ascending, whatever its sign (the `object_test` event).
    #[must_use]
    pub fn roots(&self, ray: &Ray<V>) -> Vec<f64> {
        match self {
            Self::Sphere(s) => s.roots(ray),
            Self::Plane(p) => p.roots(ray),
            Self::Box(b) => b.roots(ray),
            Self::Facet(f) => f.roots(ray),
            Self::Mesh(m) => {
                let mut all: Vec<f64> = (0..m.count()).flat_map(|k| m.roots(k, ray)).collect();
                all.sort_by(f64::total_cmp);
                all
            }
        }
    }
    /// The axis-aligned bounds, or `None` for an unbounded plane.
    #[must_use]
    pub fn bounds(&self) -> Option<(V, V)> {
        match self {
            Self::Sphere(s) => Some((s.center - V::splat(s.radius), s.center + V::splat(s.radius))),
            Self::Plane(_) => None,
            Self::Box(b) => Some((b.min, b.max)),
            Self::Facet(f) => Some(f.bounds()),
            Self::Mesh(m) => {
                let first = m.bounds(0);
                Some((1..m.count()).fold(first, |(lo, hi), k| {
                    let (a, b) = m.bounds(k);
                    (lo.min_by_axis(a), hi.max_by_axis(b))
                }))
            }
        }
    }
    /// The object scale of the spawn offset, §11: sphere `‖C‖∞ + r`, plane `‖point‖∞`, box and
    /// flat primitives the largest |coordinate| of their vertices.
    #[must_use]
    pub fn scale(&self) -> f64 {
        match self {
            Self::Sphere(s) => s.center.max_abs() + s.radius,
            Self::Plane(p) => p.point.max_abs(),
            Self::Box(b) => b.min.max_abs().max(b.max.max_abs()),
            Self::Facet(f) => f.scale(),
            Self::Mesh(m) => m.scale(),
        }
    }
    /// Whether the object itself, not only its bounding box, shares a point with the closed box
    /// `[lo, hi]`: what tells an object listed in a grid cell because it reaches into the cell
    /// from one listed only because its box does (insertion is by boxes, algorithm.md §9).
    /// A sphere by Arvo's test, the squared distance from its centre to the box
    /// `Σ (c_a − clamp(c_a, lo_a, hi_a))² ≤ r²`; a plane when the box's corners lie on both
    /// sides of it or on it; a box by its intervals; flat primitives and meshes by separating
    /// axes ([`Facet::meets_box`]).
    #[must_use]
    pub fn meets_box(&self, lo: V, hi: V) -> bool {
        match self {
            Self::Sphere(s) => {
                let d = s.center - s.center.max_by_axis(lo).min_by_axis(hi);
                d.dot(d) <= s.radius * s.radius
            }
            Self::Plane(p) => {
                let (mut below, mut above) = (false, false);
                for k in 0..(1usize << V::DIM) {
                    let mut corner = lo;
                    for a in 0..V::DIM {
                        if k & (1 << a) != 0 {
                            corner[a] = hi[a];
                        }
                    }
                    let side = (corner - p.point).dot(p.normal);
                    below |= side <= 0.0;
                    above |= side >= 0.0;
                }
                below && above
            }
            Self::Box(b) => (0..V::DIM).all(|a| b.min[a] <= hi[a] && lo[a] <= b.max[a]),
            Self::Facet(f) => f.meets_box(lo, hi),
            Self::Mesh(m) => (0..m.count()).any(|k| m.meets_box(k, lo, hi)),
        }
    }

    /// The type name as the scene file writes it (`circle` and `line` are the 2D names).
    #[must_use]
    pub fn kind(&self) -> &'static str {
        match (self, V::DIM) {
            (Self::Sphere(_), 2) => "circle",
            (Self::Sphere(_), _) => "sphere",
            (Self::Plane(_), 2) => "line",
            (Self::Plane(_), _) => "plane",
            (Self::Box(_), 2) => "rectangle",
            (Self::Box(_), _) => "box",
            (Self::Facet(f), _) => f.kind(),
            (Self::Mesh(_), _) => "mesh",
        }
    }

    /// What one ray test of a part costs, in watertight-triangle tests, for the BVH's surface
    /// area heuristic (where a node visit, two box tests, costs [`crate::accel::bvh::C_TRAV`]).
    /// Chosen by the trace phase's instruction counts on the bench scenes (bench/README.md):
    /// spheres at 0.25 made the Whitted scene and the sphere lattices 3.6–4.2 % cheaper, and
    /// triangles at 1 keep the mesh trees as they were. Boxes are priced like spheres and 2D
    /// polygons like triangles by analogy, not measured.
    #[must_use]
    pub fn test_cost(&self) -> f64 {
        match self {
            Self::Sphere(_) | Self::Plane(_) | Self::Box(_) => 0.25,
            Self::Facet(_) | Self::Mesh(_) => 1.0,
        }
    }

    /// How many parts the acceleration structures see: a mesh's triangles, else 1.
    #[must_use]
    pub fn parts(&self) -> usize {
        match self {
            Self::Mesh(m) => m.count(),
            _ => 1,
        }
    }
    /// The nearest hit of part `k` with `t > 0` (the object itself when it has one part): one
    /// dispatch on the shape, inlined into every structure's visitor (the hot path of a render).
    #[inline(always)]
    pub fn part_hit(&self, k: usize, ray: &Ray<V>) -> Option<SurfaceHit<V>> {
        match self {
            Self::Sphere(s) => s.hit(ray),
            Self::Plane(p) => p.hit(ray),
            Self::Box(b) => b.hit(ray),
            Self::Facet(f) => f.hit(ray),
            Self::Mesh(m) => m.hit(k, ray),
        }
    }
    /// `part_hit(k, ray).map(|h| h.t)`, without computing I and N where the shape can skip them
    /// (spheres, planes): what a shadow ray asks.
    #[inline(always)]
    pub fn part_hit_t(&self, k: usize, ray: &Ray<V>) -> Option<f64> {
        match self {
            Self::Sphere(s) => s.hit_t(ray),
            Self::Plane(p) => p.hit_t(ray),
            _ => self.part_hit(k, ray).map(|h| h.t),
        }
    }
    /// [`Shape::part_found`] for a ray whose shared part is `prepared` (computed on the first
    /// mesh it meets): the same answer, bit for bit, a mesh's triangle tests sharing the ray's
    /// shear.
    #[inline(always)]
    pub fn part_found_prepared(
        &self,
        k: usize,
        ray: &Ray<V>,
        prepared: &mut Option<MeshPrepared<V>>,
    ) -> Option<Found<V>> {
        match self {
            Self::Mesh(m) => {
                let p = prepared.get_or_insert_with(|| V::Mesh::prepare(ray));
                m.hit_prepared(k, ray, p).map(Found::Hit)
            }
            _ => self.part_found(k, ray),
        }
    }
    /// [`Shape::part_hit_t`] for a ray whose shared part is `prepared` (see
    /// [`Shape::part_found_prepared`]).
    #[inline(always)]
    pub fn part_hit_t_prepared(
        &self,
        k: usize,
        ray: &Ray<V>,
        prepared: &mut Option<MeshPrepared<V>>,
    ) -> Option<f64> {
        match self {
            Self::Mesh(m) => {
                let p = prepared.get_or_insert_with(|| V::Mesh::prepare(ray));
                m.hit_t_prepared(k, ray, p)
            }
            _ => self.part_hit_t(k, ray),
        }
    }
    /// [`Shape::part_hit`] as the nearest-hit search keeps it (see [`Found`]).
    #[inline(always)]
    pub fn part_found(&self, k: usize, ray: &Ray<V>) -> Option<Found<V>> {
        match self {
            Self::Sphere(s) => s.hit_t(ray).map(Found::At),
            Self::Plane(p) => p.hit_t(ray).map(Found::At),
            _ => self.part_hit(k, ray).map(Found::Hit),
        }
    }
    /// The hit that [`Shape::part_found`] found: for `Found::At(t)` the sphere's or plane's
    /// I and N at `t`, computed as [`Shape::part_hit`] computes them (the same value).
    #[inline]
    pub fn surface(&self, ray: &Ray<V>, found: Found<V>) -> SurfaceHit<V> {
        match (self, found) {
            (_, Found::Hit(hit)) => hit,
            (Self::Sphere(s), Found::At(t)) => s.surface_at(ray, t),
            (Self::Plane(p), Found::At(t)) => p.surface_at(ray, t),
            // `part_found` gives `At` for spheres and planes only; a bare point stays harmless.
            (_, Found::At(t)) => SurfaceHit { t, point: ray.at(t), normal: V::ZERO },
        }
    }
    /// Every root of part `k`, ascending.
    #[must_use]
    pub fn part_roots(&self, k: usize, ray: &Ray<V>) -> Vec<f64> {
        match self {
            Self::Mesh(m) => m.roots(k, ray),
            _ => self.roots(ray),
        }
    }
    /// The axis-aligned bounds of part `k`, or `None` for an unbounded plane.
    #[must_use]
    pub fn part_bounds(&self, k: usize) -> Option<(V, V)> {
        match self {
            Self::Mesh(m) => Some(m.bounds(k)),
            _ => self.bounds(),
        }
    }
    /// The index that names part `k` in traces: a mesh triangle's OBJ index, else `None`.
    #[must_use]
    pub fn part_id(&self, k: usize) -> Option<usize> {
        match self {
            Self::Mesh(m) => Some(m.id(k)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_object_meets_a_box_only_where_it_reaches_not_where_its_bounding_box_does() {
        use crate::shape::aabox::AaBox;
        use crate::shape::polygon::Polygon;
        use crate::shape::sphere::Sphere;
        use crate::shape::triangle::Triangle;
        // A unit circle and the box at its bounding square's corner: the square overlaps, the
        // circle does not (the corner (0.8, 0.8) is 1.13 from the centre).
        let circle: Shape<DVec2> = Shape::Sphere(Sphere { center: DVec2::ZERO, radius: 1.0 });
        assert!(!circle.meets_box(DVec2::splat(0.8), DVec2::splat(2.0)));
        assert!(circle.meets_box(DVec2::splat(0.7), DVec2::splat(2.0)));
        // A diagonal segment and a box in the corner of its bounding box.
        let seg: Shape<DVec2> = Shape::Facet(Polygon::segment(DVec2::ZERO, DVec2::splat(4.0)).unwrap());
        assert!(!seg.meets_box(DVec2::new(3.0, 0.0), DVec2::new(4.0, 1.0)));
        assert!(seg.meets_box(DVec2::new(1.0, 0.0), DVec2::new(2.0, 1.0)));
        // A closed triangle holding the whole box, and one whose edges pass by it.
        let tri = Polygon::closed(vec![DVec2::ZERO, DVec2::new(10.0, 0.0), DVec2::new(0.0, 10.0)]).unwrap();
        let tri: Shape<DVec2> = Shape::Facet(tri);
        assert!(tri.meets_box(DVec2::splat(1.0), DVec2::splat(2.0)));
        assert!(!tri.meets_box(DVec2::splat(6.0), DVec2::splat(7.0)));
        // Boxes by their intervals, closed.
        let b: Shape<DVec2> = Shape::Box(AaBox { min: DVec2::ZERO, max: DVec2::ONE });
        assert!(b.meets_box(DVec2::ONE, DVec2::splat(2.0)));
        assert!(!b.meets_box(DVec2::new(1.0, 1.5), DVec2::splat(2.0)));
        // A 3D triangle across the plane x + y + z = 3: the box at its bounding box's far corner
        // lies beyond its plane; one at the origin side of it is cut.
        let t =
            Triangle::new(DVec3::new(3.0, 0.0, 0.0), DVec3::new(0.0, 3.0, 0.0), DVec3::new(0.0, 0.0, 3.0));
        let t: Shape<DVec3> = Shape::Facet(t.unwrap());
        assert!(!t.meets_box(DVec3::splat(2.0), DVec3::splat(3.0)));
        assert!(t.meets_box(DVec3::splat(0.5), DVec3::splat(1.5)));
        assert!(!t.meets_box(DVec3::splat(0.0), DVec3::splat(0.9)));
        // A plane meets the boxes it cuts or touches.
        let floor: Shape<DVec3> = Shape::Plane(plane::Plane { point: DVec3::ZERO, normal: DVec3::Y });
        assert!(floor.meets_box(DVec3::splat(-1.0), DVec3::splat(1.0)));
        assert!(floor.meets_box(DVec3::ZERO, DVec3::ONE));
        assert!(!floor.meets_box(DVec3::new(0.0, 0.5, 0.0), DVec3::ONE));
    }
    use crate::shape::plane::Plane;
    use crate::shape::sphere::Sphere;
    use glam::{DVec2, DVec3};

    /// `part_found` then `surface` is `part_hit`, bit for bit, on the shapes that defer their
    /// surface: the nearest-hit search must not change a hit by keeping only its t.
    fn found_then_surface_is_the_hit<V: Dim>(shapes: &[Shape<V>], rays: &[Ray<V>]) -> usize {
        let mut hits = 0;
        for shape in shapes {
            for ray in rays {
                let deferred = shape.part_found(0, ray).map(|f| shape.surface(ray, f));
                assert_eq!(deferred, shape.part_hit(0, ray), "{shape:?} {ray:?}");
                hits += usize::from(deferred.is_some());
            }
        }
        hits
    }

    /// Deterministic directions and origins around the unit cell, with numerics.md's edge cases.
    fn rays3() -> Vec<Ray<DVec3>> {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        let mut rays: Vec<Ray<DVec3>> = (0..400)
            .filter_map(|_| {
                let o = DVec3::new(next(), next(), next()) * 3.0;
                let d = DVec3::new(next(), next(), next()).try_unit()?;
                Some(Ray::new(o, d))
            })
            .collect();
        // Tangent (B1), from the surface (B1), from the centre, parallel to the plane (C1),
        // huge and tiny scales (B2, B3).
        rays.push(Ray::new(DVec3::new(-2.0, 1.0, 0.0), DVec3::X));
        rays.push(Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::X));
        rays.push(Ray::new(DVec3::ZERO, DVec3::Z));
        rays.push(Ray::new(DVec3::new(0.0, -1.25, 3.0), DVec3::NEG_Z));
        rays.push(Ray::new(DVec3::new(0.5, 0.0, 1e8), DVec3::NEG_Z));
        rays.push(Ray::new(DVec3::new(0.5e-8, 0.0, 0.0), DVec3::NEG_Z));
        rays
    }

    #[test]
    fn deferred_surfaces_equal_the_hits() {
        let shapes = vec![
            Shape::Sphere(Sphere { center: DVec3::ZERO, radius: 1.0 }),
            Shape::Sphere(Sphere { center: DVec3::new(0.45, 0.2, 0.9), radius: 0.75 }),
            Shape::Sphere(Sphere { center: DVec3::new(0.0, 0.0, -1.0), radius: 1e-8 }),
            Shape::Plane(Plane { point: DVec3::new(0.0, -1.25, 0.0), normal: DVec3::Y }),
            Shape::Plane(Plane {
                point: DVec3::new(0.3, 0.1, -0.2),
                normal: DVec3::new(1.0, 2.0, 2.0) / 3.0,
            }),
        ];
        let hits = found_then_surface_is_the_hit(&shapes, &rays3());
        assert!(hits > 300, "{hits} hits: the rays must exercise the hit path");
        let circle = [
            Shape::Sphere(Sphere { center: DVec2::new(0.2, -0.1), radius: 0.8 }),
            Shape::Plane(Plane { point: DVec2::ZERO, normal: DVec2::Y }),
        ];
        let rays2: Vec<Ray<DVec2>> = (0..64)
            .map(|k| {
                let a = f64::from(k) * 0.02 - 0.6;
                Ray::new(DVec2::new(-2.0, 0.5 - f64::from(k) * 0.02), DVec2::new(a.cos(), a.sin()))
            })
            .collect();
        assert!(found_then_surface_is_the_hit(&circle, &rays2) > 10);
    }
}
