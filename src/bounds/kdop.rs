//! Kay–Kajiya slabs (algorithm.md §9 "Kay–Kajiya slabs"): a convex polytope bounded by pairs of
//! parallel planes `lo_k ≤ n_k·x ≤ hi_k`, fitted tight around an object. The normals, written
//! unnormalised so that integer coordinates give exact extents: in 2D the lecture's 4 pairs at
//! 0°, 45°, 90°, 135° — (1, 0), (1, 1), (0, 1), (−1, 1); in 3D the 7 of the convention — the
//! axes and the diagonals (±1, ±1, 1). Per slab `t = (lo − n·O)/(n·D)` by `geom::slab`; a miss as
//! soon as `max t_near > min t_far`.

use super::BoundHit;
use crate::geom::ray::Ray;
use crate::geom::slab::{culling_hit, slab_interval, GAMMA3};
use crate::geom::Vector;

/// The most slab pairs of any dimension (7, in 3D).
pub const MAX_SLABS: usize = 7;

const NORMALS_2D: [[f64; 3]; 4] = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];
const NORMALS_3D: [[f64; 3]; 7] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [1.0, -1.0, 1.0],
    [-1.0, -1.0, 1.0],
];

/// The number of slab pairs in this dimension: 4 in 2D, 7 in 3D.
#[must_use]
pub fn slab_count<V: Vector>() -> usize {
    if V::DIM == 2 {
        NORMALS_2D.len()
    } else {
        NORMALS_3D.len()
    }
}

/// The k-th slab normal n_k (unnormalised).
#[must_use]
pub fn normal<V: Vector>(k: usize) -> V {
    let n = if V::DIM == 2 { NORMALS_2D[k] } else { NORMALS_3D[k] };
    let mut v = V::ZERO;
    for a in 0..V::DIM {
        v[a] = n[a];
    }
    v
}

/// A k-DOP: per slab pair `[lo_k, hi_k]` of `n_k·x`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kdop<V> {
    /// Lower extents (only the first [`slab_count`] are used).
    pub lo: [f64; MAX_SLABS],
    /// Upper extents.
    pub hi: [f64; MAX_SLABS],
    _dim: std::marker::PhantomData<V>,
}

impl<V: Vector> Kdop<V> {
    /// The k-DOP with the given extents (the first [`slab_count`] entries).
    #[must_use]
    pub fn new(lo: [f64; MAX_SLABS], hi: [f64; MAX_SLABS]) -> Self {
        Self { lo, hi, _dim: std::marker::PhantomData }
    }
    /// Tight around the points: `lo_k = min n_k·p`, `hi_k = max n_k·p`. The normals' entries are
    /// 0 and ±1, so only the additions of `n_k·p` round; an extent they rounded is widened by
    /// `2γ₃·Σ|n_i·p_i|`, an exact one (integer coordinates) is kept exact.
    #[must_use]
    pub fn around(points: &[V]) -> Self {
        let mut lo = [f64::INFINITY; MAX_SLABS];
        let mut hi = [f64::NEG_INFINITY; MAX_SLABS];
        for k in 0..slab_count::<V>() {
            let n = normal::<V>(k);
            for p in points {
                let (x, exact) = exact_dot(n, *p);
                let pad = if exact { 0.0 } else { 2.0 * GAMMA3 * magnitude(n, *p) };
                lo[k] = lo[k].min(x - pad);
                hi[k] = hi[k].max(x + pad);
            }
        }
        Self::new(lo, hi)
    }
    /// Tight around a sphere: `n_k·C ± r·|n_k|`, widened by their rounding.
    #[must_use]
    pub fn around_sphere(center: V, radius: f64) -> Self {
        let mut lo = [0.0; MAX_SLABS];
        let mut hi = [0.0; MAX_SLABS];
        for k in 0..slab_count::<V>() {
            let n = normal::<V>(k);
            let reach = radius * n.length();
            let pad = 2.0 * GAMMA3 * (magnitude(n, center) + reach);
            let c = n.dot(center);
            lo[k] = c - reach - pad;
            hi[k] = c + reach + pad;
        }
        Self::new(lo, hi)
    }
    /// The slab test, closed (§9, §11): every pair's interval through `each`, entry `max t_near`,
    /// exit `min t_far`, and the culling decision with the widened exit.
    pub fn test(&self, ray: &Ray<V>, mut each: impl FnMut([f64; 2])) -> BoundHit {
        let (mut t_in, mut t_out) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in 0..slab_count::<V>() {
            let n = normal::<V>(k);
            let s = slab_interval(n.dot(ray.origin), n.dot(ray.dir), self.lo[k], self.hi[k]);
            each([s.t_near, s.t_far]);
            t_in = t_in.max(s.t_near);
            t_out = t_out.min(s.t_far);
        }
        BoundHit { t_in, t_out, hit: culling_hit(t_in, t_out) }
    }
}

/// `n·p` by successive additions, and whether none of them rounded (Knuth's TwoSum).
fn exact_dot<V: Vector>(n: V, p: V) -> (f64, bool) {
    let mut sum = 0.0;
    let mut exact = true;
    for a in 0..V::DIM {
        let term = n[a] * p[a];
        let s = sum + term;
        let bb = s - sum;
        #[allow(clippy::float_cmp)] // TwoSum's error term is exactly zero iff the sum is exact.
        let no_error = (sum - (s - bb)) + (term - bb) == 0.0;
        exact &= no_error && s.is_finite();
        sum = s;
    }
    (sum, exact)
}

/// `Σ|n_i·p_i|`, the size of the terms of `n·p` (its rounding is relative to this).
fn magnitude<V: Vector>(n: V, p: V) -> f64 {
    (0..V::DIM).map(|a| (n[a] * p[a]).abs()).sum()
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    const INF: f64 = f64::INFINITY;

    #[test]
    fn a9a_parallel_diagonal_slab_in_2d_is_inside_never_nan() {
        // The unit square's exact extents: x ∈ [0,1], x+y ∈ [0,2], y ∈ [0,1], −x+y ∈ [−1,1].
        let mut lo = [0.0; MAX_SLABS];
        let mut hi = [0.0; MAX_SLABS];
        (lo[..4]).copy_from_slice(&[0.0, 0.0, 0.0, -1.0]);
        (hi[..4]).copy_from_slice(&[1.0, 2.0, 1.0, 1.0]);
        let k = Kdop::<DVec2>::new(lo, hi);
        let fitted = Kdop::<DVec2>::around(&[DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]);
        assert_eq!(fitted.lo[..4], k.lo[..4], "integer extents stay exact");
        assert_eq!(fitted.hi[..4], k.hi[..4]);
        let ray = Ray::new(DVec2::new(0.0, -1.0), DVec2::new(1.0, 1.0).normalize());
        let mut iv = Vec::new();
        let h = k.test(&ray, |i| iv.push(i));
        assert!(h.hit, "the corner (1, 0) is touched");
        assert!((h.t_in - std::f64::consts::SQRT_2).abs() < 1e-15);
        assert!((h.t_out - std::f64::consts::SQRT_2).abs() < 1e-15);
        assert_eq!(iv[3], [-INF, INF], "the 135° slab is parallel and inside");
        assert!(iv.iter().flatten().all(|t| !t.is_nan()));
        assert!((iv[1][0] - 1.0 / std::f64::consts::SQRT_2).abs() < 1e-15);
        assert!((iv[1][1] - 3.0 / std::f64::consts::SQRT_2).abs() < 1e-15);
    }

    #[test]
    fn a9b_seven_slabs_around_a_unit_sphere() {
        let k = Kdop::around_sphere(DVec3::ZERO, 1.0);
        let ray = Ray::new(DVec3::new(-5.0, 0.9, 0.9), DVec3::X);
        let mut iv = Vec::new();
        let h = k.test(&ray, |i| iv.push(i));
        let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12;
        assert!(close(iv[0], [4.0, 6.0]), "{:?}", iv[0]);
        let r3 = 3f64.sqrt();
        assert!(close(iv[3], [3.2 - r3, 3.2 + r3]), "{:?}", iv[3]);
        assert!(close(iv[4], [6.8 - r3, 6.8 + r3]), "{:?}", iv[4]);
        assert!(!h.hit, "0.9² + 0.9² > 1: the diagonal slabs separate it");
        // Through the centre it hits.
        assert!(k.test(&Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X), |_| {}).hit);
    }

    #[test]
    fn kdop_is_tighter_than_the_box_for_a_diagonal_segment_of_points() {
        let pts = [DVec2::ZERO, DVec2::ONE];
        let k = Kdop::around(&pts);
        // Crosses the box [0,1]² near its corner (1, 0) but runs beside the thin diagonal.
        let ray = Ray::new(DVec2::new(0.3, -0.3), DVec2::ONE.normalize());
        assert!(!k.test(&ray, |_| {}).hit);
        let b = crate::bounds::aabb::Aabb::around(pts);
        assert!(b.test(&ray, |_| {}).hit);
    }
}
