//! Arithmetic on [`LANES`] rays at once: a lane is one ray's `f64`, a packet is `[f64; LANES]`,
//! and every operation here is the scalar operation done in each lane, in the scalar order (no
//! fused multiply-add, no reassociation). So each lane's result is the scalar result bit for
//! bit, and the compiler turns the loops over lanes into SIMD instructions as wide as the code
//! it compiles for allows.
//!
//! A condition is a mask per lane, all ones (true) or all zeros ([`M`]), as SIMD comparisons give
//! it: kept in the vector registers, where `bool`s would be taken out lane by lane. Where scalar
//! code branches, the lanes compute both sides and [`select`] keeps the side the scalar code
//! takes; a lane's value on the side not taken (a NaN, an infinity) is never read.

use crate::Vector;

/// Rays in a packet: 4 lanes of `f64` fill one AVX2 register (two SSE2 ones).
pub const LANES: usize = 4;

/// One `f64` per lane.
pub type F = [f64; LANES];
/// One condition per lane: `u64::MAX` where it holds, else 0.
pub type M = [u64; LANES];
/// A vector per lane, axis by axis; a 2D vector leaves its third axis 0.
pub type Vs = [F; 3];

/// The mask where nothing holds.
pub const NONE: M = [0; LANES];
/// The mask where everything holds.
pub const ALL: M = [u64::MAX; LANES];

/// The lanes `f(0) … f(LANES − 1)`.
#[inline(always)]
pub fn lanes(f: impl Fn(usize) -> f64) -> F {
    std::array::from_fn(f)
}

/// The condition `f` in each lane.
#[inline(always)]
pub fn test(f: impl Fn(usize) -> bool) -> M {
    std::array::from_fn(|k| if f(k) { u64::MAX } else { 0 })
}

/// Whether `x` is finite in each lane, as `f64::is_finite`: `x − x` is 0 for a finite `x` and
/// NaN for ±∞ and NaN. Written so, the test stays one subtraction and one comparison per
/// packet; `is_finite` itself is taken apart lane by lane, through the integer bits.
#[inline(always)]
#[must_use]
#[allow(clippy::float_cmp, clippy::eq_op)] // x − x == 0 is the test.
pub fn finite(x: F) -> M {
    test(|k| x[k] - x[k] == 0.0)
}

/// `a ∧ b` in each lane.
#[inline(always)]
#[must_use]
pub fn and(a: M, b: M) -> M {
    std::array::from_fn(|k| a[k] & b[k])
}

/// `a ∨ b` in each lane.
#[inline(always)]
#[must_use]
pub fn or(a: M, b: M) -> M {
    std::array::from_fn(|k| a[k] | b[k])
}

/// `a ∧ ¬b` in each lane.
#[inline(always)]
#[must_use]
pub fn and_not(a: M, b: M) -> M {
    std::array::from_fn(|k| a[k] & !b[k])
}

/// Whether the condition holds in lane `k`.
#[inline(always)]
#[must_use]
pub fn holds(m: M, k: usize) -> bool {
    m[k] != 0
}

/// Whether the condition holds in some lane.
#[inline(always)]
#[must_use]
pub fn any(m: M) -> bool {
    m.iter().fold(0, |acc, x| acc | x) != 0
}

/// Whether the condition holds in every lane.
#[inline(always)]
#[must_use]
pub fn all(m: M) -> bool {
    m.iter().fold(u64::MAX, |acc, x| acc & x) != 0
}

/// How many lanes hold the condition, one count per lane (0 or 1), to add to per-lane counters.
#[inline(always)]
#[must_use]
pub fn ones(m: M) -> [u64; LANES] {
    m.map(|x| x & 1)
}

/// `a` where `m` holds, else `b`, bit for bit.
#[inline(always)]
#[must_use]
pub fn select(m: M, a: F, b: F) -> F {
    std::array::from_fn(|k| f64::from_bits((a[k].to_bits() & m[k]) | (b[k].to_bits() & !m[k])))
}

/// [`select`] of lane vectors.
#[inline(always)]
#[must_use]
pub fn select_v(m: M, a: &Vs, b: &Vs) -> Vs {
    std::array::from_fn(|axis| select(m, a[axis], b[axis]))
}

/// The same scalar in every lane.
#[inline(always)]
#[must_use]
pub fn splat(x: f64) -> F {
    [x; LANES]
}

/// A scalar vector's axes (unused axes 0), to combine with lane vectors.
#[inline(always)]
#[must_use]
pub fn axes<V: Vector>(v: V) -> [f64; 3] {
    std::array::from_fn(|a| if a < V::DIM { v[a] } else { 0.0 })
}

/// The lane vectors of `LANES` scalar vectors: lane `k` of axis `a` is `of(k)[a]`.
#[inline(always)]
#[must_use]
pub fn gather<V: Vector>(of: impl Fn(usize) -> V) -> Vs {
    let vs: [V; LANES] = std::array::from_fn(of);
    std::array::from_fn(|a| lanes(|k| if a < V::DIM { vs[k][a] } else { 0.0 }))
}

/// `a·b` of lane vectors, summed as [`Vector::dot`] sums, left to right: `(x·x' + y·y') + z·z'`.
#[inline(always)]
#[must_use]
pub fn dot<V: Vector>(a: &Vs, b: &Vs) -> F {
    let mut sum = lanes(|k| a[0][k] * b[0][k]);
    for axis in 1..V::DIM {
        sum = lanes(|k| sum[k] + a[axis][k] * b[axis][k]);
    }
    sum
}

/// `a·s` of lane vectors with a scalar vector `s` ([`axes`]), summed as [`dot`].
#[inline(always)]
#[must_use]
pub fn dot_axes<V: Vector>(a: &Vs, s: &[f64; 3]) -> F {
    let mut sum = lanes(|k| a[0][k] * s[0]);
    for axis in 1..V::DIM {
        sum = lanes(|k| sum[k] + a[axis][k] * s[axis]);
    }
    sum
}

/// `f(a, k)` for every used axis `a` and lane `k`: a lane vector made axis by axis.
#[inline(always)]
#[must_use]
pub fn vector<V: Vector>(f: impl Fn(usize, usize) -> f64) -> Vs {
    std::array::from_fn(|a| if a < V::DIM { lanes(|k| f(a, k)) } else { [0.0; LANES] })
}

/// [`Vector::max_abs`] in each lane: the largest `|x_a|`, folded from 0 as the scalar folds it.
#[inline(always)]
#[must_use]
pub fn max_abs<V: Vector>(v: &Vs) -> F {
    let mut m = [0.0; LANES];
    for axis in v.iter().take(V::DIM) {
        m = lanes(|k| f64::max(m[k], axis[k].abs()));
    }
    m
}

/// [`Vector::try_unit`]'s common case in each lane: `v / √(v·v)` where `1e-200 < v·v < 1e200`;
/// the mask says where that holds (elsewhere the scalar code scales `v` first, and the caller
/// must take that lane the scalar way). Also `v·v`, whose root is `|v|`.
#[inline(always)]
#[must_use]
pub fn unit<V: Vector>(v: &Vs) -> (Vs, M, F) {
    let d = dot::<V>(v, v);
    let ok = and(test(|k| d[k] > 1e-200), test(|k| d[k] < 1e200));
    let len = lanes(|k| d[k].sqrt());
    (vector::<V>(|a, k| v[a][k] / len[k]), ok, d)
}

#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    /// Lane `k` of lane vectors, as a scalar vector.
    fn lane<V: Vector>(v: &Vs, k: usize) -> V {
        let mut out = V::ZERO;
        for a in 0..V::DIM {
            out[a] = v[a][k];
        }
        out
    }

    fn sample() -> [DVec3; LANES] {
        [
            DVec3::new(0.1, -2.5, 3.0),
            DVec3::new(1e-120, 3e-101, -2e-110),
            DVec3::new(-7.0, 0.0, 1e150),
            DVec3::new(0.3, 0.7, -0.2),
        ]
    }

    #[test]
    fn every_lane_is_the_scalar_operation_bit_for_bit() {
        let v = sample();
        let w = v.map(|x| DVec3::new(x.z, x.x, x.y) * 1.5 + DVec3::ONE);
        let (lv, lw) = (gather(|k| v[k]), gather(|k| w[k]));
        let (dots, maxes) = (dot::<DVec3>(&lv, &lw), max_abs::<DVec3>(&lv));
        let (units, ok, _) = unit::<DVec3>(&lv);
        for k in 0..LANES {
            assert_eq!(dots[k].to_bits(), v[k].dot(w[k]).to_bits(), "lane {k}");
            assert_eq!(maxes[k], v[k].max_abs());
            assert_eq!(lane::<DVec3>(&lv, k), v[k]);
            // try_unit's first branch where the mask holds; elsewhere the scalar code scales first.
            assert_eq!(holds(ok, k), k != 1 && k != 2, "lane {k}");
            if holds(ok, k) {
                assert_eq!(Some(lane::<DVec3>(&units, k)), v[k].try_unit());
            }
        }
    }

    #[test]
    fn a_2d_vector_leaves_its_third_axis_zero_and_dots_two_terms() {
        let v = [DVec2::new(1.0, 2.0), DVec2::new(-3.0, 0.5), DVec2::ZERO, DVec2::new(1e-3, 7.0)];
        let lv = gather(|k| v[k]);
        assert_eq!(lv[2], [0.0; LANES]);
        let d = dot::<DVec2>(&lv, &lv);
        for k in 0..LANES {
            assert_eq!(d[k], v[k].dot(v[k]));
        }
    }

    #[test]
    fn finite_is_is_finite_for_every_kind_of_value() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -2.5e300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for x in values {
            assert_eq!(holds(finite(splat(x)), 0), x.is_finite(), "{x}");
        }
    }

    #[test]
    fn masks_select_and_count_lane_by_lane() {
        let m = test(|k| k % 2 == 0);
        assert_eq!(select(m, splat(1.0), splat(2.0)), [1.0, 2.0, 1.0, 2.0]);
        assert_eq!(ones(m), [1, 0, 1, 0]);
        assert_eq!(and_not(ALL, m), test(|k| k % 2 == 1));
        assert!(any(m) && !any(NONE) && holds(or(m, NONE), 2) && !holds(and(m, NONE), 0));
        assert!(all(ALL) && !all(m) && !all(NONE));
    }
}
