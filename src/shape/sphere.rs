//! A sphere in 3D, a circle in 2D (algorithm.md §9 "Sphere", §11 "Roots"): one function on
//! `geom::quadratic`; the normal is `(I − C)/r` and the hit point is re-projected onto the surface.

use super::SurfaceHit;
use crate::geom::quadratic::sphere_roots;
use crate::geom::ray::Ray;
use crate::geom::Vector;

/// A sphere (circle) with centre C and radius r > 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere<V> {
    /// The centre C.
    pub center: V,
    /// The radius r > 0.
    pub radius: f64,
}

impl<V: Vector> Sphere<V> {
    /// The least root `t > 0` of `|O + t·D − C|² = r²`; I re-projected as `C + r·(I − C)/|I − C|`.
    #[inline]
    pub fn hit(&self, ray: &Ray<V>) -> Option<SurfaceHit<V>> {
        self.hit_t(ray).map(|t| self.surface_at(ray, t))
    }
    /// The hit at a `t` that [`Sphere::hit_t`] accepted: `N = (I − C)/|I − C|` for the raw
    /// `I = O + t·D`, and I re-projected as `C + r·N`.
    #[inline]
    pub fn surface_at(&self, ray: &Ray<V>, t: f64) -> SurfaceHit<V> {
        let radial = ray.at(t) - self.center;
        // `hit_t` accepted t only where I − C normalises; the fallback is never taken.
        let normal = radial.try_unit().unwrap_or(radial);
        SurfaceHit { t, point: self.center + normal * self.radius, normal }
    }
    /// The t of [`Sphere::hit`] without its point and normal (a shadow ray needs only t; the
    /// nearest-hit search computes them once, for the nearest).
    #[inline]
    pub fn hit_t(&self, ray: &Ray<V>) -> Option<f64> {
        let (t, radial) = self.crossing(ray)?;
        // `try_unit` fails exactly on a zero or non-finite vector.
        let m = radial.max_abs();
        (m > 0.0 && m.is_finite()).then_some(t)
    }
    /// The least root `t > 0` and `I − C` for the raw `I = O + t·D`.
    #[inline(always)]
    fn crossing(&self, ray: &Ray<V>) -> Option<(f64, V)> {
        // An origin outside (c = |f|² − r² > 0) with the centre behind (b' = f·D > 0): then
        // q = −(b' + √Δ') < 0 and c/q < 0, no root is positive, and the roots need not be found.
        let f = ray.origin - self.center;
        if f.dot(ray.dir) > 0.0 && f.dot(f) - self.radius * self.radius > 0.0 {
            return None;
        }
        let t = sphere_roots(ray, self.center, self.radius).nearest_positive()?;
        Some((t, ray.at(t) - self.center))
    }
    /// Every real root, ascending; a tangent gives one.
    #[must_use]
    pub fn roots(&self, ray: &Ray<V>) -> Vec<f64> {
        sphere_roots(ray, self.center, self.radius).to_vec()
    }
}
