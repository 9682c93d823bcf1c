//! Sphere and circle roots (algorithm.md §9 "Sphere", §11 "Roots"): the half-b form with the
//! discriminant taken from the perpendicular distance, stable against cancellation.

use super::ray::Ray;
use super::Vector;

/// The real roots of `|O + t·D − C|² = r²` for a unit `D`, ascending; a tangent gives one root.
///
/// §11: with `f = O − C`, `b' = f·D`, `Δ' = r² − |f − b'·D|²`; miss if `Δ' < 0`; else
/// `q = −(b' + sign(b')·√Δ')`, roots `q` and `c/q` with `c = |f|² − r²` (if `q = 0`, both are
/// `−b'`). `Δ' = 0` (tangent) is one root, `−b'`.
#[must_use]
pub fn sphere_roots<V: Vector>(ray: &Ray<V>, center: V, radius: f64) -> SphereRoots {
    let f = ray.origin - center;
    let (b, delta) = half_b_discriminant(ray, center, radius);
    if !(delta >= 0.0) {
        return SphereRoots::None;
    }
    if delta == 0.0 {
        return SphereRoots::One(-b);
    }
    let q = -(b + delta.sqrt().copysign(if b >= 0.0 { 1.0 } else { -1.0 }));
    if q == 0.0 {
        return SphereRoots::One(-b);
    }
    let c = f.dot(f) - radius * radius;
    let (t0, t1) = (q, c / q);
    SphereRoots::Two(t0.min(t1), t0.max(t1))
}

/// `b'` and `Δ'` of the half-b form of `|O + t·D − C|² = r²` for a unit `D` (§11):
/// `f = O − C`, `b' = f·D`, `Δ' = r² − |f − b'·D|²`, the squared half-chord. In the lecture's
/// form `t² + b·t + c = 0` (`a = D·D = 1`) these are `b = 2b'` and `Δ = b² − 4ac = 4Δ'`.
#[must_use]
pub fn half_b_discriminant<V: Vector>(ray: &Ray<V>, center: V, radius: f64) -> (f64, f64) {
    let f = ray.origin - center;
    let b = f.dot(ray.dir);
    let perp = f - ray.dir * b;
    (b, radius * radius - perp.dot(perp))
}

/// The real roots of the sphere equation, ascending.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SphereRoots {
    /// Δ' < 0: the line misses.
    None,
    /// Δ' = 0 (tangent) or the degenerate `q = 0`: one root.
    One(f64),
    /// Two distinct roots `t1 ≤ t2`.
    Two(f64, f64),
}

impl SphereRoots {
    /// The least root with `t > 0` (§11: the ray starts at its offset origin, so no other `t_min`).
    #[must_use]
    pub fn nearest_positive(self) -> Option<f64> {
        match self {
            Self::None => None,
            Self::One(t) => (t > 0.0).then_some(t),
            Self::Two(t0, t1) => {
                if t0 > 0.0 {
                    Some(t0)
                } else if t1 > 0.0 {
                    Some(t1)
                } else {
                    None
                }
            }
        }
    }
    /// Every root, ascending, whatever its sign (for the `object_test` event).
    #[must_use]
    pub fn to_vec(self) -> Vec<f64> {
        match self {
            Self::None => vec![],
            Self::One(t) => vec![t],
            Self::Two(a, b) => vec![a, b],
        }
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    fn ray3(o: [f64; 3], d: [f64; 3]) -> Ray<DVec3> {
        Ray::new(DVec3::from(o), DVec3::from(d))
    }

    #[test]
    fn b1_tangent_is_one_root() {
        let r = sphere_roots(&ray3([-2.0, 1.0, 0.0], [1.0, 0.0, 0.0]), DVec3::ZERO, 1.0);
        assert_eq!(r, SphereRoots::One(2.0));
        assert_eq!(r.nearest_positive(), Some(2.0));
    }

    #[test]
    fn b1_tangent_from_the_touch_point_misses_without_nan() {
        let r = sphere_roots(&ray3([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]), DVec3::ZERO, 1.0);
        assert_eq!(r.nearest_positive(), None);
        assert!(r.to_vec().iter().all(|t| t.is_finite()));
    }

    #[test]
    fn b2_unit_sphere_far_away() {
        let c = DVec3::new(0.0, 0.0, -1e8);
        let r = sphere_roots(&ray3([0.5, 0.0, 0.0], [0.0, 0.0, -1.0]), c, 1.0);
        let t = r.nearest_positive().unwrap();
        assert!((t - 99_999_999.133_974_6).abs() < 1e-6, "{t}");
        let r = sphere_roots(&ray3([0.0, 0.0, 0.0], [0.0, 0.0, -1.0]), c, 1.0);
        // Exact: 99 999 999; c = |f|² − r² rounds (1e16 − 1 is not an f64), so allow one ulp.
        let t = r.nearest_positive().unwrap();
        assert!((t - 99_999_999.0).abs() <= 1.5e-8, "{t}");
        let r = sphere_roots(&ray3([1.001, 0.0, 0.0], [0.0, 0.0, -1.0]), c, 1.0);
        assert_eq!(r, SphereRoots::None);
    }

    #[test]
    fn b3_tiny_sphere() {
        let c = DVec3::new(0.0, 0.0, -1.0);
        let r = sphere_roots(&ray3([0.5e-8, 0.0, 0.0], [0.0, 0.0, -1.0]), c, 1e-8);
        let t = r.nearest_positive().unwrap();
        assert!((t - 0.999_999_991_339_746).abs() < 1e-15, "{t}");
    }

    #[test]
    fn b4_root_selection() {
        let r = sphere_roots(&ray3([0.0; 3], [0.0, 0.0, 1.0]), DVec3::ZERO, 1.0);
        assert_eq!(r, SphereRoots::Two(-1.0, 1.0));
        assert_eq!(r.nearest_positive(), Some(1.0));
        let r = sphere_roots(&ray3([0.0, 0.0, 5.0], [0.0, 0.0, 1.0]), DVec3::ZERO, 1.0);
        assert_eq!(r, SphereRoots::Two(-6.0, -4.0));
        assert_eq!(r.nearest_positive(), None);
    }

    #[test]
    fn circle_uses_the_same_code() {
        let ray = Ray::new(DVec2::new(-5.0, 0.0), DVec2::new(1.0, 0.0));
        assert_eq!(sphere_roots(&ray, DVec2::ZERO, 1.0), SphereRoots::Two(4.0, 6.0));
    }
}
