//! The classic mistakes of a student's tracer (docs/grading.md "The classic mistakes"): each has a
//! name, a sentence in English and Romanian, the lecture's rule, and a test on the first
//! divergence that recognises it. A test recomputes the quantity as the mistake would and asks
//! whether that gives what the student found, within the tolerance.

use crate::geom::optics::{refract, Refraction};
use crate::geom::Vector;
use crate::lang::Lang;
use crate::record::event::LightTerm;
use crate::scene::material::{Material, Rgb};
use crate::scene::Scene;
use crate::shape::Dim;

/// A classic mistake.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mistake {
    /// A ray's direction not of unit length.
    UnnormalizedDirection,
    /// N not of unit length.
    UnnormalizedNormal,
    /// N not turned toward the incoming ray inside an object.
    NormalNotFlipped,
    /// η = n₂/n₁.
    InvertedEta,
    /// Total internal reflection not handled.
    NoTir,
    /// R with the wrong sign of V (or with D).
    ReflectSign,
    /// The shadow ray leaves from the surface itself.
    NoShadowOffset,
    /// Occluders beyond the light counted.
    OccludersBeyondLight,
    /// The pixel's centre without the +0.5.
    NoHalfPixel,
    /// Rows counted from the top.
    RowsFromTop,
    /// Phong's (R·V)^n.
    PhongRv,
    /// f_at left out.
    NoAttenuation,
    /// f_at not clamped to 1.
    UnclampedAttenuation,
    /// The depth limit off by one.
    DepthOffByOne,
    /// A T ray for kt = 0.
    TransmitKt0,
    /// The local term counted twice.
    LocalTwice,
    /// Colours clamped before summing.
    ClampBeforeSum,
}

impl Mistake {
    /// Every mistake, in docs/grading.md's order.
    pub const ALL: [Mistake; 17] = [
        Self::UnnormalizedDirection,
        Self::UnnormalizedNormal,
        Self::NormalNotFlipped,
        Self::InvertedEta,
        Self::NoTir,
        Self::ReflectSign,
        Self::NoShadowOffset,
        Self::OccludersBeyondLight,
        Self::NoHalfPixel,
        Self::RowsFromTop,
        Self::PhongRv,
        Self::NoAttenuation,
        Self::UnclampedAttenuation,
        Self::DepthOffByOne,
        Self::TransmitKt0,
        Self::LocalTwice,
        Self::ClampBeforeSum,
    ];

    /// Its name (the `diagnosis` of `--json`, the Python tracer's `--mistake`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::UnnormalizedDirection => "unnormalized-direction",
            Self::UnnormalizedNormal => "unnormalized-normal",
            Self::NormalNotFlipped => "normal-not-flipped",
            Self::InvertedEta => "inverted-eta",
            Self::NoTir => "no-tir",
            Self::ReflectSign => "reflect-sign",
            Self::NoShadowOffset => "no-shadow-offset",
            Self::OccludersBeyondLight => "occluders-beyond-light",
            Self::NoHalfPixel => "no-half-pixel",
            Self::RowsFromTop => "rows-from-top",
            Self::PhongRv => "phong-rv",
            Self::NoAttenuation => "no-attenuation",
            Self::UnclampedAttenuation => "unclamped-attenuation",
            Self::DepthOffByOne => "depth-off-by-one",
            Self::TransmitKt0 => "transmit-kt0",
            Self::LocalTwice => "local-twice",
            Self::ClampBeforeSum => "clamp-before-sum",
        }
    }

    /// What went wrong, in a sentence.
    #[must_use]
    pub fn what(self, lang: Lang) -> &'static str {
        let (en, ro) = match self {
            Self::UnnormalizedDirection => {
                ("the direction is not of unit length", "direcția nu are lungimea 1")
            }
            Self::UnnormalizedNormal => ("the normal is not of unit length", "normala nu are lungimea 1"),
            Self::NormalNotFlipped => (
                "inside the object the normal was not turned toward the incoming ray",
                "în interiorul obiectului normala nu a fost întoarsă spre raza incidentă",
            ),
            Self::InvertedEta => ("η was taken as n₂/n₁, inverted", "η a fost luat n₂/n₁, inversat"),
            Self::NoTir => (
                "total internal reflection was not handled: a T ray was spawned where there is none",
                "reflexia totală internă nu a fost tratată: s-a generat o rază T acolo unde nu există",
            ),
            Self::ReflectSign => (
                "R was built with the wrong sign of V (or with D in place of V)",
                "R a fost construit cu semnul greșit al lui V (sau cu D în locul lui V)",
            ),
            Self::NoShadowOffset => (
                "the shadow ray leaves from the surface itself, without an offset: the object shadows itself",
                "raza de umbră pleacă chiar de pe suprafață, fără deplasare: obiectul se umbrește singur",
            ),
            Self::OccludersBeyondLight => (
                "objects beyond the light were counted as occluders",
                "obiectele aflate dincolo de sursă au fost numărate ca obstacole",
            ),
            Self::NoHalfPixel => (
                "the ray goes through the pixel's corner: the +0.5 of the centre is missing",
                "raza trece prin colțul pixelului: lipsește +0.5 al centrului",
            ),
            Self::RowsFromTop => ("the rows were counted from the top", "rândurile au fost numărate de sus"),
            Self::PhongRv => (
                "the highlight was computed with Phong's (R·V)^n",
                "reflexia speculară a fost calculată cu (R·V)^n al lui Phong",
            ),
            Self::NoAttenuation => ("the attenuation f_at was left out", "atenuarea f_at a fost omisă"),
            Self::UnclampedAttenuation => {
                ("the attenuation f_at was not clamped to 1", "atenuarea f_at nu a fost limitată la 1")
            }
            Self::DepthOffByOne => ("the depth limit is off by one", "limita de adâncime e greșită cu unu"),
            Self::TransmitKt0 => (
                "a transmitted ray was spawned for an object with kt = 0",
                "s-a generat o rază transmisă pentru un obiect cu kt = 0",
            ),
            Self::LocalTwice => {
                ("the local term was counted twice", "termenul local a fost numărat de două ori")
            }
            Self::ClampBeforeSum => (
                "the colours were clamped to [0, 1] before being summed",
                "culorile au fost limitate la [0, 1] înainte de însumare",
            ),
        };
        match lang {
            Lang::En => en,
            Lang::Ro => ro,
        }
    }

    /// The lecture's rule (algorithm.md).
    #[must_use]
    pub fn rule(self, lang: Lang) -> &'static str {
        let (en, ro) = match self {
            Self::UnnormalizedDirection => (
                "every ray direction is a unit vector before it is used, so t is a distance (§2)",
                "orice direcție de rază e un vector unitar înainte de folosire, deci t e o distanță (§2)",
            ),
            Self::UnnormalizedNormal => (
                "N is the outward unit normal, e.g. (I − C)/r on a sphere (§3)",
                "N este normala exterioară unitară, de ex. (I − C)/r pe sferă (§3)",
            ),
            Self::NormalNotFlipped => (
                "a ray with D·N > 0 is leaving: N_f = −N is the N of every formula, and n₁ = ior, n₂ = 1 (§3)",
                "o rază cu D·N > 0 iese: N_f = −N este N-ul tuturor formulelor, iar n₁ = ior, n₂ = 1 (§3)",
            ),
            Self::InvertedEta => (
                "η = n₁/n₂, n₁ on the side the ray comes from: entering, n₁ = 1 and n₂ = ior (§3, §11)",
                "η = n₁/n₂, cu n₁ de partea din care vine raza: la intrare n₁ = 1 și n₂ = ior (§3, §11)",
            ),
            Self::NoTir => (
                "k = 1 − η²(1 − c²) < 0 means total internal reflection: no T, the kt·T term is dropped (§3, §11)",
                "k = 1 − η²(1 − c²) < 0 înseamnă reflexie totală internă: nu există T, termenul kt·T dispare (§3, §11)",
            ),
            Self::ReflectSign => (
                "R = 2(N·V)·N − V with V = −D, that is R = D − 2(D·N)·N (§3)",
                "R = 2(N·V)·N − V cu V = −D, adică R = D − 2(D·N)·N (§3)",
            ),
            Self::NoShadowOffset => (
                "a secondary or shadow ray starts at I moved off the surface by an offset δ (§11)",
                "o rază secundară sau de umbră pleacă din I deplasat de pe suprafață cu δ (§11)",
            ),
            Self::OccludersBeyondLight => (
                "the shadow ray is a segment: an object occludes only for 0 < t < d_L (§11)",
                "raza de umbră e un segment: un obiect acoperă doar pentru 0 < t < d_L (§11)",
            ),
            Self::NoHalfPixel => (
                "u = l + (r − l)·(i + 0.5)/Nx, v = b + (t − b)·(j + 0.5)/Ny (§2)",
                "u = l + (r − l)·(i + 0.5)/Nx, v = b + (t − b)·(j + 0.5)/Ny (§2)",
            ),
            Self::RowsFromTop => (
                "j counts rows from the bottom, so that v grows with j (§2)",
                "j numără rândurile de jos, astfel încât v crește cu j (§2)",
            ),
            Self::PhongRv => (
                "the lecture's highlight is ks·(N·H)^n with H = normalize(L + V) (§5)",
                "reflexia speculară din curs este ks·(N·H)^n cu H = normalize(L + V) (§5)",
            ),
            Self::NoAttenuation => (
                "each light is weighted by fat = min(1, 1/(c0 + c1·d + c2·d²)) (§5)",
                "fiecare sursă e ponderată cu fat = min(1, 1/(c0 + c1·d + c2·d²)) (§5)",
            ),
            Self::UnclampedAttenuation => (
                "fat = min(1, 1/(c0 + c1·d + c2·d²)): never above 1 (§5)",
                "fat = min(1, 1/(c0 + c1·d + c2·d²)): niciodată peste 1 (§5)",
            ),
            Self::DepthOffByOne => (
                "P is at level 1 and a node at level n spawns children iff n ≤ max_depth (§6)",
                "P este pe nivelul 1, iar un nod de pe nivelul n generează copii dacă și numai dacă n ≤ max_depth (§6)",
            ),
            Self::TransmitKt0 => (
                "an object transmits (spawns T) iff kt > 0 (§6)",
                "un obiect transmite (generează T) dacă și numai dacă kt > 0 (§6)",
            ),
            Self::LocalTwice => (
                "I = I_local + ks·R + kt·T: the local term once (§1)",
                "I = I_local + ks·R + kt·T: termenul local o singură dată (§1)",
            ),
            Self::ClampBeforeSum => (
                "colours are linear and nothing is clamped until the pixel is written (§5)",
                "culorile sunt liniare și nimic nu se limitează până la scrierea pixelului (§5)",
            ),
        };
        match lang {
            Lang::En => en,
            Lang::Ro => ro,
        }
    }

    /// The mistake of this name.
    #[must_use]
    pub fn named(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// Agreement within the tolerance: `‖found − expected‖∞ ≤ tol·max(1, ‖expected‖∞) + slack`.
#[must_use]
pub fn close(found: &[f64], expected: &[f64], tol: f64, slack: f64) -> bool {
    if found.len() != expected.len() {
        return false;
    }
    let scale = expected.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    let diff = found.iter().zip(expected).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    diff <= tol * scale + slack
}

fn close_v<V: Vector>(found: V, expected: V, tol: f64) -> bool {
    close(&found.to_vec(), &expected.to_vec(), tol, 0.0)
}

/// `found` is `expected` scaled by a length other than 1.
#[must_use]
pub fn unnormalized<V: Vector>(found: V, expected: V, tol: f64) -> bool {
    let len = found.length();
    (len - 1.0).abs() > tol && found.try_unit().is_some_and(|u| close_v(u, expected, tol))
}

/// What the parent of a secondary ray tells about it: the incoming D, the facing normal, the
/// indices, whether the parent ray was entering.
#[derive(Clone, Copy, Debug)]
pub struct Spawn<V> {
    /// The parent's direction D (the student's).
    pub d: V,
    /// The facing normal N_f at the parent's hit.
    pub n_f: V,
    /// The indices on either side.
    pub n1: f64,
    /// See `n1`.
    pub n2: f64,
    /// `D·N ≤ 0` at the parent's hit.
    pub entering: bool,
}

/// The mistake that explains a secondary ray's wrong direction, if one does.
#[must_use]
pub fn direction<V: Vector>(
    found: V,
    expected: V,
    transmitted: Option<Spawn<V>>,
    tol: f64,
) -> Option<Mistake> {
    if unnormalized(found, expected, tol) {
        return Some(Mistake::UnnormalizedDirection);
    }
    let Some(s) = transmitted else {
        return close_v(found, -expected, tol).then_some(Mistake::ReflectSign);
    };
    let refracted = |n: V, eta: f64| match refract(s.d, n, eta) {
        Refraction::Transmitted { dir, .. } => Some(dir),
        Refraction::TotalInternalReflection { .. } => None,
    };
    let matches = |dir: Option<V>| dir.is_some_and(|t| close_v(found, t, tol));
    if matches(refracted(s.n_f, s.n2 / s.n1)) {
        return Some(Mistake::InvertedEta);
    }
    if !s.entering && (matches(refracted(-s.n_f, s.n1 / s.n2)) || matches(refracted(-s.n_f, s.n2 / s.n1))) {
        return Some(Mistake::NormalNotFlipped);
    }
    None
}

/// The channels of a colour clamped to [0, 1].
#[must_use]
pub fn clamped(c: Rgb) -> Rgb {
    Rgb(c.0.map(|x| x.clamp(0.0, 1.0)))
}

/// What the local model is at one hit, for recomputing it as a mistake would.
pub struct LocalInputs<'a, V: Dim> {
    /// The scene.
    pub scene: &'a Scene<V>,
    /// The hit object's material.
    pub material: &'a Material,
    /// I.
    pub point: V,
    /// N_f.
    pub n_f: V,
    /// V = −D.
    pub view: V,
    /// whitted's terms per light (L, N·L, s, fat).
    pub lights: &'a [LightTerm<V>],
}

/// How the local model is computed: the lecture's, or as a mistake would.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Variant {
    PhongRv,
    NoFat,
    UnclampedFat,
}

impl<V: Dim> LocalInputs<'_, V> {
    /// `I_local = Ia·Ka + Σ Isrc·fat·s·lum·[kd·(N·L) + ks·h]` with the variant's highlight h and fat.
    fn local(&self, variant: Variant) -> Rgb {
        let (ka, kd) = self.material.colors_at(self.point);
        let mut sum = self.scene.ambient.modulate(ka);
        for term in self.lights {
            let (Some(l), Some(s)) = (term.l, term.shadow) else { continue };
            let light = &self.scene.lights[term.light];
            let d = (light.position - self.point).length();
            let fat = match variant {
                Variant::NoFat => 1.0,
                Variant::UnclampedFat => {
                    let [c0, c1, c2] = light.attenuation;
                    1.0 / (c0 + c1 * d + c2 * d * d)
                }
                Variant::PhongRv => term.fat,
            };
            let highlight = if self.material.ks > 0.0 {
                if variant == Variant::PhongRv {
                    // Phong: R = 2(N·L)·N − L against V.
                    let r = self.n_f * (2.0 * term.n_dot_l) - l;
                    self.material.highlight(r.dot(self.view))
                } else {
                    (l + self.view).try_unit().map_or(0.0, |h| self.material.highlight(self.n_f.dot(h)))
                }
            } else {
                0.0
            };
            let weight = fat * s;
            sum += light.intensity.modulate(kd) * (weight * term.n_dot_l)
                + light.intensity * (weight * self.material.ks * highlight);
        }
        sum
    }

    /// The mistake that explains a wrong `I_local` (`expected` is whitted's), if one does.
    #[must_use]
    pub fn diagnose(&self, found: Rgb, expected: Rgb, tol: f64) -> Option<Mistake> {
        let same = |c: Rgb| close(&found.0, &c.0, tol, 0.0) && !close(&c.0, &expected.0, tol, 0.0);
        if same(clamped(expected)) {
            return Some(Mistake::ClampBeforeSum);
        }
        [
            (Variant::PhongRv, Mistake::PhongRv),
            (Variant::NoFat, Mistake::NoAttenuation),
            (Variant::UnclampedFat, Mistake::UnclampedAttenuation),
        ]
        .into_iter()
        .find(|(v, _)| same(self.local(*v)))
        .map(|(_, m)| m)
    }
}

/// The mistake that explains a wrong node colour, if one does: `local` and the children's
/// weighted colours are the student's own.
#[must_use]
pub fn colour(found: Rgb, expected: Rgb, local: Rgb, children: &[(f64, Rgb)], tol: f64) -> Option<Mistake> {
    if close(&found.0, &(expected + local).0, tol, 0.0) {
        return Some(Mistake::LocalTwice);
    }
    let clamped_sum = children.iter().fold(clamped(local), |sum, (k, c)| sum + clamped(*c) * *k);
    (close(&found.0, &clamped_sum.0, tol, 0.0) && !close(&clamped_sum.0, &expected.0, tol, 0.0))
        .then_some(Mistake::ClampBeforeSum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn names_are_unique_and_found_again() {
        for m in Mistake::ALL {
            assert_eq!(Mistake::named(m.name()), Some(m));
            assert!(!m.what(Lang::Ro).is_empty() && m.rule(Lang::Ro).contains('§'));
        }
        let mut names: Vec<&str> = Mistake::ALL.iter().map(|m| m.name()).collect();
        names.dedup();
        assert_eq!(names.len(), 17);
    }

    #[test]
    fn closeness_is_relative_above_1_and_absolute_below() {
        assert!(close(&[1000.05], &[1000.0], 1e-4, 0.0));
        assert!(!close(&[1000.2], &[1000.0], 1e-4, 0.0));
        assert!(close(&[0.00005], &[0.0], 1e-4, 0.0));
        assert!(!close(&[0.0002], &[0.0], 1e-4, 0.0));
        assert!(close(&[0.0002], &[0.0], 1e-4, 1e-3));
    }

    #[test]
    fn a_wrong_reflection_and_refraction_are_named() {
        let r = DVec3::new(0.6, 0.8, 0.0);
        assert_eq!(direction(-r, r, None, 1e-4), Some(Mistake::ReflectSign));
        assert_eq!(direction(r * 2.0, r, None, 1e-4), Some(Mistake::UnnormalizedDirection));
        assert_eq!(direction(DVec3::Z, r, None, 1e-4), None);
        // Entering glass at 45°: T with η = 1/1.5 is expected; the inverted η gives another T.
        let d = DVec3::new(1.0, -1.0, 0.0).normalize();
        let spawn = Spawn { d, n_f: DVec3::Y, n1: 1.0, n2: 1.5, entering: true };
        let Refraction::Transmitted { dir: t, .. } = refract(d, DVec3::Y, 1.0 / 1.5) else { panic!() };
        let Refraction::Transmitted { dir: wrong, .. } = refract(d, DVec3::Y, 1.5 / 1.0 * 0.9) else {
            panic!()
        };
        assert_eq!(direction(wrong, t, Some(spawn), 1e-4), None);
        let d = DVec3::new(0.3, -1.0, 0.0).normalize();
        let spawn = Spawn { d, ..spawn };
        let Refraction::Transmitted { dir: t, .. } = refract(d, DVec3::Y, 1.0 / 1.5) else { panic!() };
        let Refraction::Transmitted { dir: inv, .. } = refract(d, DVec3::Y, 1.5) else { panic!() };
        assert_eq!(direction(inv, t, Some(spawn), 1e-4), Some(Mistake::InvertedEta));
    }

    #[test]
    fn a_colour_with_the_local_term_twice_or_clamped_terms_is_named() {
        let local = Rgb([0.3, 0.2, 0.1]);
        let r = Rgb([1.5, 0.5, 0.5]);
        let expected = local + r * 0.5;
        assert_eq!(colour(expected + local, expected, local, &[(0.5, r)], 1e-4), Some(Mistake::LocalTwice));
        let clamped_sum = local + clamped(r) * 0.5;
        assert_eq!(colour(clamped_sum, expected, local, &[(0.5, r)], 1e-4), Some(Mistake::ClampBeforeSum));
        assert_eq!(colour(Rgb([9.0; 3]), expected, local, &[(0.5, r)], 1e-4), None);
    }
}
