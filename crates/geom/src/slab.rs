//! The slab test (algorithm.md §9 "Axis-aligned box", "Kay–Kajiya slabs"; §11 policies): per slab
//! `[t_near, t_far]`, their intersection `[max t_near, min t_far]`, closed, NaN-proof.
//!
//! `RecipRay` with `slab_interval_recip` is the same slab by reciprocals, for the traversals that
//! test many boxes with one ray.

use super::ray::Ray;
use super::Vector;

/// One slab's interval along a ray, `t_near ≤ t_far` unless the slab is parallel and outside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlabInterval {
    /// Where the ray enters the slab (−∞ for a parallel slab that holds the origin).
    pub t_near: f64,
    /// Where the ray leaves the slab (+∞ for a parallel slab that holds the origin).
    pub t_far: f64,
}

/// The interval of the slab `lo ≤ n·x ≤ hi` along the ray, given `o = n·O` and `d = n·D`.
///
/// §9: `t1 = (lo − o)/d`, `t2 = (hi − o)/d`, `t_near = min(t1, t2)`, `t_far = max(t1, t2)`.
/// A slab parallel to the ray (`d = 0`, of either sign) is inside iff `lo ≤ o ≤ hi`, recorded as
/// `(−∞, +∞)`, else outside, recorded as `(+∞, −∞)`: never `0·∞ = NaN` (§11).
#[inline]
#[must_use]
pub fn slab_interval(o: f64, d: f64, lo: f64, hi: f64) -> SlabInterval {
    slab_by(o, d, lo, hi, |x| x / d)
}

/// [`slab_interval`] with `1/d` computed once per ray: `t = (lo − o)·(1/d)`. Each t then carries
/// three roundings, the `γ₃` of [`widen_exit`], so only culling volumes use it; objects divide.
#[inline]
#[must_use]
pub fn slab_interval_recip(o: f64, d: f64, inv_d: f64, lo: f64, hi: f64) -> SlabInterval {
    slab_by(o, d, lo, hi, |x| x * inv_d)
}

/// The one slab rule, with `t_of(x)` turning a distance along the slab normal into a t.
#[inline(always)]
fn slab_by(o: f64, d: f64, lo: f64, hi: f64, t_of: impl Fn(f64) -> f64) -> SlabInterval {
    if d == 0.0 {
        return if lo <= o && o <= hi {
            SlabInterval { t_near: f64::NEG_INFINITY, t_far: f64::INFINITY }
        } else {
            SlabInterval { t_near: f64::INFINITY, t_far: f64::NEG_INFINITY }
        };
    }
    let t1 = t_of(lo - o);
    let t2 = t_of(hi - o);
    if t1 <= t2 {
        SlabInterval { t_near: t1, t_far: t2 }
    } else {
        SlabInterval { t_near: t2, t_far: t1 }
    }
}

/// A ray prepared for many culling tests: its origin, direction and `1/D` per axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecipRay<V> {
    /// The origin O.
    pub origin: V,
    /// The unit direction D.
    pub dir: V,
    /// `1/D` per axis (±∞ where a component is ±0; never used there, see [`slab_interval`]).
    pub inv_dir: V,
    /// No component of D is zero: no slab is parallel, and [`RecipRay::box_interval`] takes
    /// the same formulas without the parallel branch.
    pub oblique: bool,
}

impl<V: Vector> RecipRay<V> {
    /// Prepares `ray`.
    #[must_use]
    pub fn new(ray: &Ray<V>) -> Self {
        let mut inv_dir = ray.dir;
        for axis in 0..V::DIM {
            inv_dir[axis] = 1.0 / ray.dir[axis];
        }
        // 1/±0 = ±∞ and a NaN stays NaN, so a finite 1/d alone says the component is usable.
        let oblique = (0..V::DIM).all(|a| inv_dir[a].is_finite());
        Self { origin: ray.origin, dir: ray.dir, inv_dir, oblique }
    }
    /// `[max t_near, min t_far]` of the box `[min, max]`, slab by slab, by reciprocals.
    #[inline(always)]
    #[must_use]
    pub fn box_interval(&self, min: V, max: V) -> (f64, f64) {
        let (mut t_in, mut t_out) = (f64::NEG_INFINITY, f64::INFINITY);
        if self.oblique {
            // slab_interval_recip without its parallel branch, written with plain comparisons
            // (no NaN can arise: every 1/d is finite and non-zero).
            for axis in 0..V::DIM {
                let t1 = (min[axis] - self.origin[axis]) * self.inv_dir[axis];
                let t2 = (max[axis] - self.origin[axis]) * self.inv_dir[axis];
                let (near, far) = if t1 <= t2 { (t1, t2) } else { (t2, t1) };
                t_in = if near > t_in { near } else { t_in };
                t_out = if far < t_out { far } else { t_out };
            }
            return (t_in, t_out);
        }
        for axis in 0..V::DIM {
            let s = slab_interval_recip(
                self.origin[axis],
                self.dir[axis],
                self.inv_dir[axis],
                min[axis],
                max[axis],
            );
            t_in = t_in.max(s.t_near);
            t_out = t_out.min(s.t_far);
        }
        (t_in, t_out)
    }
}

impl<V: Vector> RecipRay<V> {
    /// [`RecipRay::box_interval`] of two boxes at once (a BVH node's children). For an oblique
    /// ray the near plane of every slab is chosen once by the sign of `1/d` (rounding is
    /// monotonic, so `(lo − o)/d ≤ (hi − o)/d` keeps its order), which leaves two lanes of plain
    /// arithmetic; the results are those of two calls of `box_interval`, bit for bit.
    #[inline(always)]
    #[must_use]
    pub fn box_pair_interval(&self, min: [V; 2], max: [V; 2]) -> [(f64, f64); 2] {
        if !self.oblique {
            return [self.box_interval(min[0], max[0]), self.box_interval(min[1], max[1])];
        }
        let mut t_in = [f64::NEG_INFINITY; 2];
        let mut t_out = [f64::INFINITY; 2];
        for axis in 0..V::DIM {
            let (o, inv) = (self.origin[axis], self.inv_dir[axis]);
            let (near, far) = if inv >= 0.0 { (min, max) } else { (max, min) };
            for c in 0..2 {
                let tn = (near[c][axis] - o) * inv;
                let tf = (far[c][axis] - o) * inv;
                t_in[c] = if tn > t_in[c] { tn } else { t_in[c] };
                t_out[c] = if tf < t_out[c] { tf } else { t_out[c] };
            }
        }
        [(t_in[0], t_out[0]), (t_in[1], t_out[1])]
    }
}

/// Whether a culling volume's interval `[t_in, t_out]` admits the ray: closed, exit widened
/// (§11), `t_in ≤ t_out·(1 + 2γ₃)` and `t_out·(1 + 2γ₃) ≥ 0`.
#[inline]
#[must_use]
pub fn culling_hit(t_in: f64, t_out: f64) -> bool {
    admits(t_in, widen_exit(t_out))
}

/// [`culling_hit`] of an exit already widened: `t_in ≤ wide` and `wide ≥ 0`.
#[inline(always)]
#[must_use]
pub fn admits(t_in: f64, wide: f64) -> bool {
    t_in <= wide && wide >= 0.0
}

/// The intersection of a ray with an axis-aligned box, slab by slab.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxCrossing {
    /// `max` over axes of `t_near`: the entry `I = r(t_in)`.
    pub t_in: f64,
    /// `min` over axes of `t_far`: the exit `E = r(t_out)`.
    pub t_out: f64,
    /// The axis that set `t_in` (ties in the order x, y, z).
    pub axis_in: usize,
    /// The axis that set `t_out` (ties in the order x, y, z).
    pub axis_out: usize,
}

impl BoxCrossing {
    /// §9, closed: the line meets the box iff `t_in ≤ t_out`; the ray iff also `t_out ≥ 0`.
    #[must_use]
    pub fn hits_ray(&self) -> bool {
        self.t_in <= self.t_out && self.t_out >= 0.0
    }
}

/// The slab test of an axis-aligned box `[min, max]`, returning every axis's interval through
/// `each` (for the trace) and their intersection.
#[inline]
pub fn box_crossing<V: Vector>(
    ray: &Ray<V>,
    min: V,
    max: V,
    mut each: impl FnMut(usize, SlabInterval),
) -> BoxCrossing {
    let mut out = BoxCrossing { t_in: f64::NEG_INFINITY, t_out: f64::INFINITY, axis_in: 0, axis_out: 0 };
    for axis in 0..V::DIM {
        let s = slab_interval(ray.origin[axis], ray.dir[axis], min[axis], max[axis]);
        each(axis, s);
        // Strict comparisons keep the earlier axis on a tie (x before y before z).
        if s.t_near > out.t_in {
            out.t_in = s.t_near;
            out.axis_in = axis;
        }
        if s.t_far < out.t_out {
            out.t_out = s.t_far;
            out.axis_out = axis;
        }
    }
    out
}

/// `γ₃ = 3ε/(1 − 3ε)`, `ε = 2^-53` (pbrt's rounding bound; algorithm.md §11).
pub const GAMMA3: f64 = 3.0 * f64::EPSILON * 0.5 / (1.0 - 3.0 * f64::EPSILON * 0.5);

/// §11 "Bounding volumes cull conservatively": a culling volume widens its exit by
/// `t_out·(1 + 2γ₃)` so rounding never loses a hit.
#[inline]
#[must_use]
pub fn widen_exit(t_out: f64) -> f64 {
    t_out * (1.0 + 2.0 * GAMMA3)
}

/// The factor of [`far_recip`]: `(1 + 2γ₃)(1 + 8u)` (`u = 2^-53`, `f64::EPSILON = 2u`), above
/// `(1 + 2γ₃)(1 + u)²/(1 − u)² ≈ (1 + 2γ₃)(1 + 4u)`, the two roundings it must absorb.
pub const WIDEN_FAR: f64 = (1.0 + 2.0 * GAMMA3) * (1.0 + 4.0 * f64::EPSILON);
// Its margin over `1 + 2γ₃`, as rounded: at least 3 steps of `f64::EPSILON` (2 are needed).
const _: () = assert!(WIDEN_FAR - (1.0 + 2.0 * GAMMA3) >= 3.0 * f64::EPSILON);

/// `1/d` for the far planes of many boxes, the exit's widening folded into it:
/// `(x − o)·(1/d)·WIDEN_FAR`. For `x − o` of either sign and a non-negative result,
/// `fl(fl(x − o)·fl(inv·WIDEN_FAR)) ≥ fl(fl(fl(x − o)·inv)·(1 + 2γ₃))`: the product's two
/// roundings lose at most `(1 − u)²`, the reference's gain at most `(1 + u)²`, and
/// [`WIDEN_FAR`] covers both (outside the subnormal range, as [`widen_exit`] itself). So one
/// multiplication per plane gives an exit at least [`widen_exit`]'s, and a box the reference
/// admits is admitted.
#[inline]
#[must_use]
pub fn far_recip(inv: f64) -> f64 {
    inv * WIDEN_FAR
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    fn cross3(o: [f64; 3], d: [f64; 3], min: [f64; 3], max: [f64; 3]) -> BoxCrossing {
        let ray = Ray::new(DVec3::from(o), DVec3::from(d));
        box_crossing(&ray, DVec3::from(min), DVec3::from(max), |_, _| {})
    }

    const B: ([f64; 3], [f64; 3]) = ([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);

    #[test]
    fn a1_ray_along_a_box_edge_hits() {
        let c = cross3([0.0; 3], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(c.hits_ray());
        assert_eq!((c.t_in, c.t_out), (1.0, 2.0));
        let c = cross3([0.0, 1.5, 0.5], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(!c.hits_ray());
        assert!(!c.t_in.is_nan() && !c.t_out.is_nan());
    }

    #[test]
    fn a2_ray_in_a_face_plane() {
        assert!(!cross3([5.0, 1.0, 0.5], [1.0, 0.0, 0.0], B.0, B.1).hits_ray());
        let c = cross3([0.0, 1.0, 0.5], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(c.hits_ray());
        assert_eq!((c.t_in, c.t_out), (1.0, 2.0));
    }

    #[test]
    fn a3_negative_zero_changes_nothing() {
        for o in [[0.0, 0.5, 0.5], [0.0, 0.0, 0.5]] {
            let plus = cross3(o, [1.0, 0.0, 0.0], B.0, B.1);
            let minus = cross3(o, [1.0, -0.0, 0.0], B.0, B.1);
            assert_eq!(plus, minus);
            assert!(minus.hits_ray());
            assert_eq!((minus.t_in, minus.t_out), (1.0, 2.0));
        }
    }

    #[test]
    fn a4_corner_touch_is_a_hit() {
        let d = 0.707_106_781_186_547_5;
        let c = cross3([0.0; 3], [d, d, 0.0], [1.0, 0.0, -1.0], [2.0, 1.0, 1.0]);
        assert!(c.hits_ray());
        assert_eq!(c.t_in.to_bits(), c.t_out.to_bits());
        assert_eq!(c.t_in, std::f64::consts::SQRT_2);
    }

    #[test]
    fn a5_zero_thickness_box() {
        let c = cross3([0.5, 1.0, 0.5], [0.0, -1.0, 0.0], [0.0; 3], [1.0, 0.0, 1.0]);
        assert!(c.hits_ray());
        assert_eq!((c.t_in, c.t_out), (1.0, 1.0));
    }

    #[test]
    fn a6_origin_inside() {
        let c = cross3([1.5, 0.5, 0.5], [1.0, 0.0, 0.0], B.0, B.1);
        assert!(c.hits_ray());
        assert_eq!((c.t_in, c.t_out), (-0.5, 0.5));
        assert_eq!(c.axis_out, 0);
    }

    #[test]
    fn a7_edge_tie_picks_x() {
        let d = std::f64::consts::FRAC_1_SQRT_2;
        let c = cross3([-1.0, -1.0, 0.5], [d, d, 0.0], [0.0; 3], [1.0; 3]);
        assert_eq!(c.axis_in, 0);
    }

    #[test]
    fn a8_large_coordinates() {
        let c = cross3([0.0, 0.5, 0.5], [1.0, 0.0, 0.0], [1e8, 0.0, 0.0], [1e8 + 1.0, 1.0, 1.0]);
        assert_eq!((c.t_in, c.t_out), (1e8, 100_000_001.0));
    }

    #[test]
    fn parallel_slab_intervals_are_infinite_not_nan() {
        assert_eq!(
            slab_interval(0.5, 0.0, 0.0, 1.0),
            SlabInterval { t_near: f64::NEG_INFINITY, t_far: f64::INFINITY }
        );
        assert_eq!(
            slab_interval(1.5, -0.0, 0.0, 1.0),
            SlabInterval { t_near: f64::INFINITY, t_far: f64::NEG_INFINITY }
        );
    }

    #[test]
    fn rectangle_in_2d() {
        let ray = Ray::new(DVec2::new(-1.0, 0.5), DVec2::new(1.0, 0.0));
        let c = box_crossing(&ray, DVec2::ZERO, DVec2::ONE, |_, _| {});
        assert_eq!((c.t_in, c.t_out), (1.0, 2.0));
    }

    /// A small deterministic generator (xorshift64*), so the sweep is the same on every run.
    fn next(state: &mut u64) -> f64 {
        *state ^= *state >> 12;
        *state ^= *state << 25;
        *state ^= *state >> 27;
        let bits = state.wrapping_mul(0x2545_f491_4f6c_dd1d);
        // A mantissa and a sign from the bits, a magnitude from 1e-30 to 1e30.
        #[allow(clippy::cast_precision_loss)]
        let m = (bits >> 11) as f64 / (1u64 << 53) as f64;
        let sign = if bits & 1 == 0 { 1.0 } else { -1.0 };
        #[allow(clippy::cast_possible_truncation)]
        let exp = ((bits >> 1) % 61) as i32 - 30;
        sign * (0.5 + m) * 10f64.powi(exp)
    }

    #[test]
    fn the_far_reciprocal_exit_is_at_least_the_widened_exit() {
        let mut state = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            let (x, o, d) = (next(&mut state), next(&mut state), next(&mut state));
            // Near neighbours too: the exit close to the origin and x − o exact.
            for (x, o) in [(x, o), (o * (1.0 + f64::EPSILON), o), (x, x.next_down())] {
                let inv = 1.0 / d;
                let reference = widen_exit((x - o) * inv);
                if reference >= 0.0 {
                    assert!((x - o) * far_recip(inv) >= reference, "x {x:e} o {o:e} d {d:e}");
                }
            }
        }
    }
}
