//! Bounding volumes (algorithm.md §9 "Bounding volumes", §11 "Bounding volumes cull
//! conservatively"): a sphere, an axis-aligned box, a Kay–Kajiya k-DOP, each fitted around one
//! object and each cheaper to test than the object. Every test is closed (a touch is a hit),
//! never produces NaN, reports the interval of each axis or slab, and widens its exit by
//! `t_out·(1 + 2γ₃)` so that rounding never culls an object the ray meets.

pub mod aabb;
pub mod kdop;

use crate::geom::quadratic::{sphere_roots, SphereRoots};
use crate::geom::ray::Ray;
use crate::geom::slab::{culling_hit, GAMMA3};
use crate::geom::Vector;
use aabb::Aabb;
use kdop::Kdop;

/// What a bounding-volume test found: `[t_in, t_out]` and the culling decision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundHit {
    /// Where the ray enters the volume (`max t_near`).
    pub t_in: f64,
    /// Where it leaves (`min t_far`).
    pub t_out: f64,
    /// `t_in ≤ t_out·(1 + 2γ₃)` and `t_out·(1 + 2γ₃) ≥ 0`.
    pub hit: bool,
}

/// The `--bounds` choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VolumeKind {
    /// A bounding sphere.
    Sphere,
    /// An axis-aligned box.
    Aabb,
    /// Kay–Kajiya slabs.
    Kdop,
}

impl VolumeKind {
    /// The name on the command line and in `bound_test` events.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Sphere => "sphere",
            Self::Aabb => "aabb",
            Self::Kdop => "kdop",
        }
    }
    /// The kind of a name, if any.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::Sphere, Self::Aabb, Self::Kdop].into_iter().find(|k| k.name() == name)
    }
}

/// What a volume is fitted around: a sphere's own centre and radius, or a set of vertices.
#[derive(Clone, Debug, PartialEq)]
pub enum Hull<V> {
    /// A sphere or circle.
    Ball {
        /// Centre.
        center: V,
        /// Radius.
        radius: f64,
    },
    /// The vertices of a convex hull's generators (box corners, polygon or triangle vertices).
    Points(Vec<V>),
}

/// A bounding volume around one object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BoundingVolume<V> {
    /// `|x − C| ≤ r`.
    Sphere {
        /// Centre.
        center: V,
        /// Radius.
        radius: f64,
    },
    /// `min ≤ x ≤ max`.
    Aabb(Aabb<V>),
    /// `lo_k ≤ n_k·x ≤ hi_k`.
    Kdop(Kdop<V>),
}

impl<V: Vector> BoundingVolume<V> {
    /// The volume of `kind` fitted around `hull`. A sphere around points is centred on their
    /// box's centre with the farthest point on it; every fit is widened by its own rounding, so
    /// it is tight up to a few ulps.
    #[must_use]
    pub fn fit(kind: VolumeKind, hull: &Hull<V>) -> Self {
        match (kind, hull) {
            (VolumeKind::Sphere, Hull::Ball { center, radius }) => {
                Self::Sphere { center: *center, radius: *radius }
            }
            (VolumeKind::Sphere, Hull::Points(ps)) => {
                let center = Aabb::around(ps.iter().copied()).centroid();
                let radius = ps.iter().fold(0.0, |r: f64, p| r.max((*p - center).length()));
                Self::Sphere { center, radius: radius * (1.0 + 4.0 * GAMMA3) }
            }
            (VolumeKind::Aabb, Hull::Ball { center, radius }) => {
                let r = V::splat(*radius);
                Self::Aabb(Aabb::new(*center - r, *center + r).padded())
            }
            (VolumeKind::Aabb, Hull::Points(ps)) => Self::Aabb(Aabb::around(ps.iter().copied())),
            (VolumeKind::Kdop, Hull::Ball { center, radius }) => {
                Self::Kdop(Kdop::around_sphere(*center, *radius))
            }
            (VolumeKind::Kdop, Hull::Points(ps)) => Self::Kdop(Kdop::around(ps)),
        }
    }
    /// Which kind it is.
    #[must_use]
    pub fn kind(&self) -> VolumeKind {
        match self {
            Self::Sphere { .. } => VolumeKind::Sphere,
            Self::Aabb(_) => VolumeKind::Aabb,
            Self::Kdop(_) => VolumeKind::Kdop,
        }
    }
    /// The ray against the volume, every interval through `each`: per axis (box), per slab pair
    /// (k-DOP), or the roots `[t1, t2]` of `|O + t·D − C|² = r²` (sphere; none on a miss, and a
    /// tangent's one root as `[t, t]`).
    pub fn test(&self, ray: &Ray<V>, mut each: impl FnMut([f64; 2])) -> BoundHit {
        match self {
            Self::Sphere { center, radius } => {
                let (t_in, t_out) = match sphere_roots(ray, *center, *radius) {
                    SphereRoots::None => (f64::INFINITY, f64::NEG_INFINITY),
                    SphereRoots::One(t) => (t, t),
                    SphereRoots::Two(a, b) => (a, b),
                };
                if t_in <= t_out {
                    each([t_in, t_out]);
                }
                BoundHit { t_in, t_out, hit: culling_hit(t_in, t_out) }
            }
            Self::Aabb(b) => b.test(ray, each),
            Self::Kdop(k) => k.test(ray, each),
        }
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn every_kind_holds_its_object_and_culls_a_far_ray() {
        let corners: Vec<DVec3> = (0..8)
            .map(|i| DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
            .collect();
        for hull in [Hull::Ball { center: DVec3::ZERO, radius: 1.0 }, Hull::Points(corners)] {
            for kind in [VolumeKind::Sphere, VolumeKind::Aabb, VolumeKind::Kdop] {
                let v = BoundingVolume::fit(kind, &hull);
                assert_eq!(v.kind(), kind);
                let centre = match &hull {
                    Hull::Ball { center, .. } => *center,
                    Hull::Points(_) => DVec3::splat(0.5),
                };
                let at = Ray::new(centre + DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z);
                assert!(v.test(&at, |_| {}).hit, "{kind:?}");
                let away = Ray::new(centre + DVec3::new(3.0, 0.0, 5.0), DVec3::NEG_Z);
                assert!(!v.test(&away, |_| {}).hit, "{kind:?}");
            }
        }
    }

    #[test]
    fn sphere_volume_reports_its_roots() {
        let v = BoundingVolume::fit(VolumeKind::Sphere, &Hull::Ball { center: DVec3::ZERO, radius: 1.0 });
        let mut iv = Vec::new();
        let h = v.test(&Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z), |i| iv.push(i));
        assert_eq!(iv, vec![[4.0, 6.0]]);
        assert_eq!((h.t_in, h.t_out), (4.0, 6.0));
        let mut iv = Vec::new();
        let h = v.test(&Ray::new(DVec3::new(0.0, 2.0, 5.0), DVec3::NEG_Z), |i| iv.push(i));
        assert!(!h.hit && iv.is_empty());
        // A tangent is one root, a closed hit.
        assert!(v.test(&Ray::new(DVec3::new(0.0, 1.0, 5.0), DVec3::NEG_Z), |_| {}).hit);
    }
}
