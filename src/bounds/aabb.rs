//! The axis-aligned bounding box (algorithm.md §9 "Axis-aligned box (slab test)", §11 "Bounding
//! volumes cull conservatively"): the box algebra the structures are built from (empty, grow,
//! union, extent, centroid, surface measure) and the closed slab test through `geom::slab`.

use super::BoundHit;
use crate::geom::ray::Ray;
use crate::geom::slab::{box_crossing, culling_hit, GAMMA3};
use crate::geom::Vector;

/// The box `[min, max]`; empty when `min > max` on some axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<V> {
    /// The lower corner.
    pub min: V,
    /// The upper corner.
    pub max: V,
}

impl<V: Vector> Aabb<V> {
    /// The empty box `[+∞, −∞]`, the identity of [`Aabb::union`].
    #[must_use]
    pub fn empty() -> Self {
        Self { min: V::splat(f64::INFINITY), max: V::splat(f64::NEG_INFINITY) }
    }
    /// The box `[min, max]`.
    #[must_use]
    pub fn new(min: V, max: V) -> Self {
        Self { min, max }
    }
    /// The smallest box holding every point.
    pub fn around(points: impl IntoIterator<Item = V>) -> Self {
        points.into_iter().fold(Self::empty(), |b, p| b.union(&Self::new(p, p)))
    }
    /// True when `p` lies in the closed box: `min ≤ p ≤ max` on every axis.
    #[inline]
    #[must_use]
    pub fn holds(&self, p: V) -> bool {
        (0..V::DIM).all(|a| self.min[a] <= p[a] && p[a] <= self.max[a])
    }
    /// True when it holds no point.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        (0..V::DIM).any(|a| !(self.min[a] <= self.max[a]))
    }
    /// The smallest box holding both (min and max are exact: no rounding). Written with plain
    /// comparisons: a valid scene has no NaN, and the builders call this millions of times.
    #[inline]
    #[must_use]
    pub fn union(&self, other: &Self) -> Self {
        let (mut min, mut max) = (self.min, self.max);
        for a in 0..V::DIM {
            if other.min[a] < min[a] {
                min[a] = other.min[a];
            }
            if other.max[a] > max[a] {
                max[a] = other.max[a];
            }
        }
        Self { min, max }
    }
    /// `max − min` per axis (0 for an empty box).
    #[must_use]
    pub fn extent(&self) -> V {
        let mut e = self.max - self.min;
        for a in 0..V::DIM {
            e[a] = e[a].max(0.0);
        }
        e
    }
    /// The axis of the largest extent (the first on a tie).
    #[must_use]
    pub fn longest_axis(&self) -> usize {
        let e = self.extent();
        (1..V::DIM).fold(0, |best, a| if e[a] > e[best] { a } else { best })
    }
    /// The centre `(min + max)/2`.
    #[must_use]
    pub fn centroid(&self) -> V {
        (self.min + self.max) * 0.5
    }
    /// The measure a random line hits it in proportion to (the SAH's weight): half the surface
    /// area in 3D, half the perimeter in 2D.
    #[must_use]
    pub fn surface(&self) -> f64 {
        let e = self.extent();
        if V::DIM == 2 {
            e[0] + e[1]
        } else {
            e[0] * e[1] + e[1] * e[2] + e[2] * e[0]
        }
    }
    /// Closed overlap: the boxes share at least one point.
    #[must_use]
    pub fn overlaps(&self, other: &Self) -> bool {
        (0..V::DIM).all(|a| self.min[a] <= other.max[a] && other.min[a] <= self.max[a])
    }
    /// The box grown by a few ulps of its largest coordinate, so that a corner computed with
    /// rounding (`C ± r` of a sphere) still lies inside: tight up to rounding (§11).
    #[must_use]
    pub fn padded(&self) -> Self {
        let m = self.min.max_abs().max(self.max.max_abs());
        let pad = m * 2.0 * GAMMA3;
        Self { min: self.min - V::splat(pad), max: self.max + V::splat(pad) }
    }

    /// The slab test of §9, closed (§11): every axis's interval through `each`, and the hit
    /// decision of a culling volume, `max t_near ≤ (min t_far)·(1 + 2γ₃)`, exit ≥ 0.
    pub fn test(&self, ray: &Ray<V>, mut each: impl FnMut([f64; 2])) -> BoundHit {
        let c = box_crossing(ray, self.min, self.max, |_, s| each([s.t_near, s.t_far]));
        BoundHit { t_in: c.t_in, t_out: c.t_out, hit: culling_hit(c.t_in, c.t_out) }
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::geom::slab::RecipRay;
    use glam::{DVec2, DVec3};

    const INF: f64 = f64::INFINITY;

    #[test]
    fn a_box_holds_its_faces_and_corners_and_nothing_beyond() {
        let b = Aabb::new(DVec3::new(-1.0, 0.0, 2.0), DVec3::new(1.0, 0.5, 3.0));
        for p in [DVec3::new(0.0, 0.25, 2.5), DVec3::new(-1.0, 0.0, 2.0), DVec3::new(1.0, 0.5, 3.0)] {
            assert!(b.holds(p), "{p}");
        }
        let above = DVec3::new(0.0, 0.5f64.next_up(), 2.5);
        assert!(!b.holds(above) && !b.holds(DVec3::new(0.0, 0.25, 1.0)));
        // A ray from any point it holds meets it at t_in ≤ 0 ≤ t_out (what the BVH relies on
        // when it skips computing the root's interval).
        let ray = Ray::new(DVec3::new(1.0, 0.5, 2.0), DVec3::new(0.6, -0.8, 0.0));
        let (t_in, t_out) = RecipRay::new(&ray).box_interval(b.min, b.max);
        assert!(t_in <= 0.0 && 0.0 <= t_out, "{t_in} {t_out}");
        assert!(!Aabb::<DVec2>::empty().holds(DVec2::ZERO));
    }

    fn test3(o: [f64; 3], d: [f64; 3], min: [f64; 3], max: [f64; 3]) -> (BoundHit, Vec<[f64; 2]>) {
        let b = Aabb::new(DVec3::from(min), DVec3::from(max));
        let ray = Ray::new(DVec3::from(o), DVec3::from(d));
        let mut intervals = Vec::new();
        let hit = b.test(&ray, |i| intervals.push(i));
        // The traversal's reciprocal form (`accel::node_visit`) decides the same on these exact
        // cases.
        let (t_in, t_out) = RecipRay::new(&ray).box_interval(b.min, b.max);
        assert_eq!(culling_hit(t_in, t_out), hit.hit, "{o:?} {d:?}");
        (hit, intervals)
    }

    const B: ([f64; 3], [f64; 3]) = ([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);

    #[test]
    fn a1_ray_along_a_box_edge_hits_with_parallel_inside_slabs() {
        let (h, iv) = test3([0.0; 3], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(h.hit);
        assert_eq!((h.t_in, h.t_out), (1.0, 2.0));
        assert_eq!(iv, vec![[1.0, 2.0], [-INF, INF], [-INF, INF]]);
        let (h, iv) = test3([0.0, 1.5, 0.5], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(!h.hit);
        assert_eq!(iv[1], [INF, -INF]);
    }

    #[test]
    fn a2_ray_in_a_face_plane() {
        assert!(!test3([5.0, 1.0, 0.5], [1.0, 0.0, 0.0], B.0, B.1).0.hit);
        let (h, _) = test3([0.0, 1.0, 0.5], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(h.hit);
        assert_eq!((h.t_in, h.t_out), (1.0, 2.0));
    }

    #[test]
    fn a3_negative_zero_components_change_nothing() {
        for o in [[0.0, 0.5, 0.5], [0.0, 0.0, 0.5]] {
            let (plus, _) = test3(o, [1.0, 0.0, 0.0], B.0, B.1);
            let (minus, _) = test3(o, [1.0, -0.0, -0.0], B.0, B.1);
            assert_eq!(plus, minus);
            assert!(minus.hit);
        }
    }

    #[test]
    fn a4_corner_touch_is_a_hit() {
        let d = 0.707_106_781_186_547_5;
        let (h, _) = test3([0.0; 3], [d, d, 0.0], [1.0, 0.0, -1.0], [2.0, 1.0, 1.0]);
        assert!(h.hit);
        assert_eq!(h.t_in, std::f64::consts::SQRT_2);
        assert_eq!(h.t_in, h.t_out);
    }

    #[test]
    fn a5_zero_thickness_box_is_hit() {
        let (h, _) = test3([0.5, 1.0, 0.5], [0.0, -1.0, 0.0], [0.0; 3], [1.0, 0.0, 1.0]);
        assert!(h.hit);
        assert_eq!((h.t_in, h.t_out), (1.0, 1.0));
    }

    #[test]
    fn a6_origin_inside_is_a_bound_hit() {
        let (h, _) = test3([1.5, 0.5, 0.5], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(h.hit);
        assert_eq!((h.t_in, h.t_out), (-0.5, 0.5));
    }

    #[test]
    fn a7_edge_hit_interval() {
        let d = std::f64::consts::FRAC_1_SQRT_2;
        let (h, iv) = test3([-1.0, -1.0, 0.5], [d, d, 0.0], [0.0; 3], [1.0; 3]);
        assert!(h.hit);
        assert_eq!(iv[0], iv[1], "x and y slabs tie at the edge");
    }

    #[test]
    fn a8_large_coordinates_in_f64() {
        let (h, _) = test3([0.0, 0.5, 0.5], [1.0, 0.0, 0.0], [1e8, 0.0, 0.0], [1e8 + 1.0, 1.0, 1.0]);
        assert!(h.hit);
        assert_eq!((h.t_in, h.t_out), (1e8, 100_000_001.0));
    }

    #[test]
    fn widening_keeps_a_hit_lost_to_one_rounding() {
        // t_in one ulp above t_out: a rounding artefact that the widened exit absorbs.
        let t = 1.0_f64;
        let above = f64::from_bits(t.to_bits() + 1);
        assert!(culling_hit(above, t));
        assert!(!culling_hit(1.1, 1.0));
    }

    #[test]
    fn algebra_in_2d() {
        let a = Aabb::new(DVec2::ZERO, DVec2::new(2.0, 1.0));
        let b = Aabb::new(DVec2::new(2.0, 0.0), DVec2::new(3.0, 3.0));
        assert!(a.overlaps(&b), "closed: touching boxes overlap");
        assert_eq!(a.union(&b), Aabb::new(DVec2::ZERO, DVec2::new(3.0, 3.0)));
        assert_eq!(a.surface(), 3.0);
        assert_eq!(a.longest_axis(), 0);
        assert!(Aabb::<DVec2>::empty().is_empty());
        assert_eq!(Aabb::<DVec2>::empty().extent(), DVec2::ZERO);
    }
}
