//! A plane in 3D, a line in 2D (algorithm.md §3): `(X − P)·N = 0` with the given unit normal as
//! the outward side. Unbounded, so never placed inside an acceleration structure.

use super::SurfaceHit;
use crate::geom::ray::Ray;
use crate::geom::Vector;

/// The plane through `point` with unit `normal`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<V> {
    /// A point P of the plane.
    pub point: V,
    /// The unit normal N (the outward side).
    pub normal: V,
}

impl<V: Vector> Plane<V> {
    /// The two terms of `t = ((P − O)·N)/(D·N)`, where the ray's line meets the plane:
    /// `((P − O)·N, D·N)`. A 2D polygon's edges take their t from it too, through the line of the
    /// edge, so an edge lying on a line object meets a ray at exactly the line's t (§6 then
    /// settles the tie).
    #[inline(always)]
    #[must_use]
    pub fn crossing_terms(&self, ray: &Ray<V>) -> (f64, f64) {
        ((self.point - ray.origin).dot(self.normal), ray.dir.dot(self.normal))
    }
    /// The root `t = (P − O)·N / (D·N)`, when finite; a ray parallel to the plane (in it or
    /// not, `D·N = ±0`) has none.
    #[inline]
    fn root(&self, ray: &Ray<V>) -> Option<f64> {
        let (num, denom) = self.crossing_terms(ray);
        let t = num / denom;
        // Written so that NaN and ±∞ fail (numerics C1, C2).
        t.is_finite().then_some(t)
    }
    /// The hit with `t > 0`; I re-projected by subtracting its signed distance to the plane.
    #[inline]
    pub fn hit(&self, ray: &Ray<V>) -> Option<SurfaceHit<V>> {
        self.hit_t(ray).map(|t| self.surface_at(ray, t))
    }
    /// The hit at a `t` that [`Plane::hit_t`] accepted, I re-projected onto the plane.
    #[inline]
    pub fn surface_at(&self, ray: &Ray<V>, t: f64) -> SurfaceHit<V> {
        let raw = ray.at(t);
        let point = raw - self.normal * (raw - self.point).dot(self.normal);
        SurfaceHit { t, point, normal: self.normal }
    }
    /// The t of [`Plane::hit`] alone (a shadow ray needs no point).
    #[inline]
    pub fn hit_t(&self, ray: &Ray<V>) -> Option<f64> {
        // The terms of `crossing_terms`, written out: through the call the compiler lays the
        // render's search out worse (+0.3 % instructions on Whitted's scene, callgrind). The
        // polygon test `an_edge_on_a_line_meets_a_ray_at_the_lines_t_bit_for_bit` holds the two
        // to one t. t = num/denom > 0 needs num and denom of one strict sign; otherwise (behind,
        // parallel, on the plane, NaN) there is no hit and no division.
        let (num, denom) = ((self.point - ray.origin).dot(self.normal), ray.dir.dot(self.normal));
        if !((num > 0.0 && denom > 0.0) || (num < 0.0 && denom < 0.0)) {
            return None;
        }
        // Same signs, so t > 0 (or +∞ from an underflowing denominator, which §11's finite-t
        // acceptance turns away, numerics C2).
        let t = num / denom;
        (t.is_finite() && t > 0.0).then_some(t)
    }
    /// The one root, if any.
    #[must_use]
    pub fn roots(&self, ray: &Ray<V>) -> Vec<f64> {
        self.root(ray).into_iter().collect()
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn c1_c2_parallel_rays_miss_without_nan() {
        let p = Plane { point: DVec3::ZERO, normal: DVec3::Y };
        for (o, d) in
            [(DVec3::Y, DVec3::X), (DVec3::ZERO, DVec3::X), (DVec3::Y, DVec3::new(-1.0, -0.0, -0.0))]
        {
            let ray = Ray::new(o, d);
            assert!(p.hit(&ray).is_none());
            assert!(p.roots(&ray).is_empty());
        }
    }
}
