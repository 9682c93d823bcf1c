//! Materials (algorithm.md §5, product.md "Defaults"): `ka`, `kd` (RGB), `ks`, `n`, `kt`, `ior`,
//! and the checker that swaps `kd` (and `ka`) by the parity of the hit point's cell; and [`Rgb`].

use crate::geom::Vector;
use std::ops::{Add, AddAssign, Mul};

/// A linear RGB colour (no gamma; clamped only when a pixel is written, §5).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb(pub [f64; 3]);

impl Rgb {
    /// Black.
    pub const BLACK: Rgb = Rgb([0.0; 3]);
    /// Grey of the given level.
    #[must_use]
    pub const fn grey(level: f64) -> Rgb {
        Rgb([level; 3])
    }
    /// Channel-wise product (light times reflectance).
    #[must_use]
    pub fn modulate(self, other: Rgb) -> Rgb {
        Rgb([self.0[0] * other.0[0], self.0[1] * other.0[1], self.0[2] * other.0[2]])
    }
    /// The largest over channels of the spread `max − min` of several colours (§8.2's criterion),
    /// in one pass over the colours.
    #[must_use]
    #[inline]
    pub fn spread<'a>(colors: impl IntoIterator<Item = &'a Rgb>) -> f64 {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for x in colors {
            for c in 0..3 {
                lo[c] = lo[c].min(x.0[c]);
                hi[c] = hi[c].max(x.0[c]);
            }
        }
        (0..3).map(|c| hi[c] - lo[c]).fold(0.0, f64::max)
    }
}

impl Add for Rgb {
    type Output = Rgb;
    fn add(self, o: Rgb) -> Rgb {
        Rgb([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}

impl AddAssign for Rgb {
    fn add_assign(&mut self, o: Rgb) {
        *self = *self + o;
    }
}

impl Mul<f64> for Rgb {
    type Output = Rgb;
    fn mul(self, k: f64) -> Rgb {
        Rgb([self.0[0] * k, self.0[1] * k, self.0[2] * k])
    }
}

/// A checker pattern: the second colours where the cell parity is odd.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checker {
    /// Side of a cell, > 0.
    pub size: f64,
    /// The diffuse colour of the odd cells.
    pub kd2: Rgb,
    /// The ambient colour of the odd cells (default: the material's `ka`).
    pub ka2: Rgb,
}

impl Checker {
    /// product.md: odd iff `Σ floor(x_i/size + 1e-10)` is odd (`rem_euclid(2) == 1`), at the hit
    /// point; the 1e-10 keeps a boundary such as y = −1 (size 1) from speckling.
    #[must_use]
    pub fn is_odd<V: Vector>(&self, point: V) -> bool {
        // Below 2^50 a floor is exact through the truncating integer conversion (no libm call, which
        // the renderer would otherwise pay at every checker hit) and the sum of the floors is exact
        // in f64 too, so both paths give the same parity; larger cells take the float path.
        let mut parity = 0_i64;
        let mut small = true;
        for i in 0..V::DIM {
            let x = point[i] / self.size + 1e-10;
            if x.abs() < 1_125_899_906_842_624.0 {
                // |x| < 2^50: the conversion truncates exactly.
                #[allow(clippy::cast_possible_truncation)]
                let t = x as i64;
                parity += t - i64::from((t as f64) > x);
            } else {
                small = false;
            }
        }
        if small {
            return parity.rem_euclid(2) == 1;
        }
        let sum: f64 = (0..V::DIM).map(|i| (point[i] / self.size + 1e-10).floor()).sum();
        // The sum is an integer-valued float, so its remainder is exactly 0 or 1.
        #[allow(clippy::float_cmp)]
        let odd = sum.rem_euclid(2.0) == 1.0;
        odd
    }
}

/// A material with every field given or defaulted (product.md's table).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Ambient coefficient Ka (RGB, each in [0, 1]); default 0.1.
    pub ka: Rgb,
    /// Diffuse coefficient kd (RGB, each in [0, 1]); default 0.7.
    pub kd: Rgb,
    /// Specular coefficient ks in [0, 1], also the weight of the reflected ray; default 0.
    pub ks: f64,
    /// Specular exponent n ≥ 0; default 32.
    pub n: f64,
    /// Transmission coefficient kt in [0, 1], the weight of T and the shadow factor; default 0.
    pub kt: f64,
    /// Index of refraction of the inside, > 0; default 1.
    pub ior: f64,
    /// An optional checker pattern.
    pub checker: Option<Checker>,
}

impl Material {
    /// product.md's defaults: `ka 0.1, kd 0.7, ks 0, n 32, kt 0, ior 1`, no checker.
    pub const DEFAULT: Material = Material {
        ka: Rgb::grey(0.1),
        kd: Rgb::grey(0.7),
        ks: 0.0,
        n: 32.0,
        kt: 0.0,
        ior: 1.0,
        checker: None,
    };
    /// The object spawns R iff `ks > 0` (§6).
    #[must_use]
    pub fn reflects(&self) -> bool {
        self.ks > 0.0
    }
    /// The object spawns T iff `kt > 0` (§6).
    #[must_use]
    pub fn transmits(&self) -> bool {
        self.kt > 0.0
    }
    /// The highlight `(N·H)^n` of §5, with `N·H` clamped at 0. An integral `n` up to 1024 (the
    /// usual 8, 64, 128 …) is raised by repeated squaring, within about `n` ulps of the correctly
    /// rounded power (below 3·10⁻¹³ relative, far under a colour's 1/255): 48 instructions a call
    /// against glibc `pow`'s 125 (callgrind, Whitted's scene) and a much shorter chain of dependent
    /// operations, once per lit point with `ks > 0`. Any other `n` uses `powf`.
    #[must_use]
    pub fn highlight(&self, n_dot_h: f64) -> f64 {
        let x = n_dot_h.max(0.0);
        #[allow(clippy::cast_possible_truncation)] // a truncation is caught by the comparison
        let k = self.n as i32;
        #[allow(clippy::float_cmp)] // exactly integral is the question
        if f64::from(k) == self.n && k <= 1024 {
            x.powi(k)
        } else {
            x.powf(self.n)
        }
    }
    /// `(ka, kd)` at a point, after the checker.
    #[must_use]
    pub fn colors_at<V: Vector>(&self, point: V) -> (Rgb, Rgb) {
        match &self.checker {
            Some(c) if c.is_odd(point) => (c.ka2, c.kd2),
            _ => (self.ka, self.kd),
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
    fn highlight_squares_integral_exponents_and_keeps_pow_for_the_rest() {
        let with_n = |n: f64| Material { n, ..Material::DEFAULT };
        for n in [0.0, 1.0, 8.0, 64.0, 128.0, 1024.0] {
            let m = with_n(n);
            for x in [1.0, 0.999_999, 0.99, 0.9, 0.5, 0.123_456_789, 1e-3] {
                let (fast, exact) = (m.highlight(x), f64::powf(x, n));
                // Within about n ulps, relative (and exactly 0 where pow underflows too).
                assert!(
                    (fast - exact).abs() <= exact * (n + 1.0) * f64::EPSILON,
                    "{x}^{n}: {fast} vs {exact}"
                );
            }
            // N·H is clamped at 0 first: 0^0 = 1, 0^n = 0.
            assert_eq!(m.highlight(-0.5), if n == 0.0 { 1.0 } else { 0.0 });
        }
        for n in [2.5, 1025.0, 1e6] {
            assert_eq!(with_n(n).highlight(0.75), f64::powf(0.75, n));
        }
    }

    #[test]
    fn checker_boundary_does_not_speckle() {
        let c = Checker { size: 1.0, kd2: Rgb::BLACK, ka2: Rgb::BLACK };
        // y = −1 exactly (a floor at a tile boundary) stays in one parity class along x.
        let a = c.is_odd(DVec3::new(0.5, -1.0, 0.5));
        let b = c.is_odd(DVec3::new(0.5, -1.0 + 1e-14, 0.5));
        assert_eq!(a, b);
        assert_ne!(c.is_odd(DVec3::new(0.5, 0.5, 0.5)), c.is_odd(DVec3::new(1.5, 0.5, 0.5)));
        assert!(!c.is_odd(DVec3::new(-0.5, 0.5, -0.5)));
    }

    #[test]
    fn the_integer_and_float_parities_agree() {
        let c = Checker { size: 0.75, kd2: Rgb::BLACK, ka2: Rgb::BLACK };
        let float = |p: DVec3| {
            let sum: f64 = (0..3).map(|i| (p[i] / c.size + 1e-10).floor()).sum();
            sum.rem_euclid(2.0) == 1.0
        };
        let mut x = 1e-3_f64;
        while x < 1e20 {
            for p in [DVec3::new(x, -x, 0.3 * x), DVec3::new(-x, -1.0, x * 1.7), DVec3::new(x, x, x)] {
                assert_eq!(c.is_odd(p), float(p), "{p}");
            }
            x *= 1.37;
        }
    }
}
