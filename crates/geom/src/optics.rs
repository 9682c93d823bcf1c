//! Reflection and refraction at a hit (algorithm.md §3, §11 "Refraction"), with the facing normal
//! `N_f` (the N of every formula) and the n1/n2 swap of a leaving ray.

use super::Vector;

/// Mirror direction of an incident direction `D`: with `V = −D` (towards the viewer),
/// §3: `R = 2(N·V)·N − V`, i.e. `R = D − 2(D·N)·N`, for the facing normal `N = N_f`.
#[inline]
#[must_use]
pub fn reflect<V: Vector>(d: V, n_f: V) -> V {
    let v = -d;
    n_f * (2.0 * n_f.dot(v)) - v
}

/// The outcome of Snell's law at a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Refraction<V> {
    /// The transmitted direction T, with `k = cos²θt` that produced it.
    Transmitted {
        /// The transmitted unit direction T.
        dir: V,
        /// `k = 1 − η²(1 − c²)`, computed as `(1 − η²) + (η·c)²`.
        k: f64,
    },
    /// `k < 0`: no T ray (total internal reflection).
    TotalInternalReflection {
        /// The negative `k` that decided it.
        k: f64,
    },
}

/// Refraction of the incident unit direction `D` at facing normal `N_f` with `η = n1/n2`.
///
/// §3 (Snell, `n1·sin θi = n2·sin θt`): `T = η·D + (η·c − √k)·N_f` with `c = −D·N_f` clamped to
/// [−1, 1] and, as §11 fixes, `k = (1 − η²) + (η·c)²` (exact when η = 1, so `T = D` exactly);
/// total internal reflection iff `k < 0` (`k = 0` refracts, grazing). glam's `refract` is not used:
/// it hides TIR as a zero vector.
#[inline]
#[must_use]
pub fn refract<V: Vector>(d: V, n_f: V, eta: f64) -> Refraction<V> {
    let c = (-d.dot(n_f)).clamp(-1.0, 1.0);
    let k = (1.0 - eta * eta) + (eta * c) * (eta * c);
    if k < 0.0 {
        return Refraction::TotalInternalReflection { k };
    }
    Refraction::Transmitted { dir: d * eta + n_f * (eta * c - k.sqrt()), k }
}

/// The indices on either side of a surface, §3: entering, `n1 = 1`, `n2 = ior`; leaving, swapped.
#[inline]
#[must_use]
pub fn indices(entering: bool, ior: f64) -> (f64, f64) {
    if entering {
        (1.0, ior)
    } else {
        (ior, 1.0)
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    #[test]
    fn reflect_is_the_lecture_formula() {
        let d = DVec3::new(1.0, -1.0, 0.0).normalize();
        let r = reflect(d, DVec3::Y);
        assert!((r - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
    }

    #[test]
    fn f1_critical_angle_refracts_grazing() {
        let d = DVec3::new(0.666_666_666_666_666_6, -0.745_355_992_499_929_9, 0.0);
        match refract(d, DVec3::Y, 1.5) {
            Refraction::Transmitted { dir, k } => {
                assert!(k.abs() < 1e-15, "k = {k}");
                assert!((dir - DVec3::X).length() < 1e-7, "{dir}");
            }
            Refraction::TotalInternalReflection { k } => {
                // k may round to a hair below 0; the policy is still k < 0 ⇔ TIR.
                assert!(k > -1e-15);
            }
        }
        let theta_c = (2.0f64 / 3.0).asin();
        for delta in [1e-6, 1e-9] {
            let past = theta_c + delta;
            let d = DVec3::new(past.sin(), -past.cos(), 0.0);
            assert!(matches!(refract(d, DVec3::Y, 1.5), Refraction::TotalInternalReflection { .. }));
            let before = theta_c - delta;
            let d = DVec3::new(before.sin(), -before.cos(), 0.0);
            assert!(matches!(refract(d, DVec3::Y, 1.5), Refraction::Transmitted { .. }));
        }
    }

    #[test]
    fn f2_equal_indices_give_d_exactly_even_grazing() {
        let c: f64 = -1e-9;
        let d = DVec3::new((1.0 - c * c).sqrt(), c, 0.0);
        match refract(d, DVec3::Y, 1.0) {
            Refraction::Transmitted { dir, .. } => assert_eq!(dir, d),
            Refraction::TotalInternalReflection { .. } => panic!("η = 1 never reflects totally"),
        }
    }

    #[test]
    fn f3_normal_incidence_passes_straight() {
        for eta in [1.0 / 1.5, 1.5, 1e6] {
            match refract(DVec3::NEG_Y, DVec3::Y, eta) {
                Refraction::Transmitted { dir, .. } => assert_eq!(dir, DVec3::NEG_Y),
                Refraction::TotalInternalReflection { .. } => panic!(),
            }
        }
    }

    #[test]
    fn e2_refraction_at_45_degrees() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        match refract(DVec2::new(h, -h), DVec2::Y, 1.0 / 1.5) {
            Refraction::Transmitted { dir, k } => {
                assert!((k - 0.777_777_777_777_777_9).abs() < 1e-15);
                assert!((dir - DVec2::new(0.471_404_520_791_031_7, -0.881_917_103_688_197)).length() < 1e-15);
            }
            Refraction::TotalInternalReflection { .. } => panic!(),
        }
    }
}
