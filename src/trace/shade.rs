//! The local model (algorithm.md §5):
//! `I_local = Ia·Ka + Σ_i Isrc_i·fat_i·s_i·lum_i·[kd·(N·L_i) + ks·(N·H_i)^n]`, with the shadow
//! factor `s_i` the product of `kt` over the distinct objects on the segment from I to light i.

use super::{Shading, Tracer};
use crate::geom::offset::spawn_origin;
use crate::geom::ray::Ray;
use crate::record::event::{Event, LightTerm, Occluder};
use crate::record::Recorder;
use crate::scene::light::Light;
use crate::scene::material::Rgb;
use crate::shape::Dim;

/// A light that may light a hit, before its shadow ray: `L`, `N_f·L > 0` and `fat`.
pub(crate) struct Lit<V> {
    l: V,
    n_dot_l: f64,
    fat: f64,
}

impl<V: Dim, R: Recorder<V>> Tracer<'_, V, R> {
    /// `I_local` at a hit, every light in scene order.
    pub(crate) fn local(&mut self, at: &Shading<'_, V>) -> Rgb {
        let scene = self.scene;
        // The checker swaps kd (and ka) by the parity of I's cell.
        let (ka, kd) = at.material.colors_at(at.hit.point);
        let mut sum = scene.ambient.modulate(ka);
        for (index, light) in scene.lights.iter().enumerate() {
            let Some(lit) = self.lit(at, index, light) else {
                continue;
            };
            let s = self.shadow_factor(at, index, light.position);
            sum += self.light_term(at, kd, (index, light), &lit, s);
        }
        sum
    }

    /// [`Tracer::local`] of two hits, light by light, the shadow rays of a light that may light
    /// both walked at once ([`Accel::occluders_pair`](crate::accel::Accel::occluders_pair)):
    /// the colours and counts of two calls of [`Tracer::local`]. With a recorder, those calls.
    pub(crate) fn local_pair(&mut self, a: &Shading<'_, V>, b: &Shading<'_, V>) -> [Rgb; 2] {
        if R::ENABLED {
            return [self.local(a), self.local(b)];
        }
        let scene = self.scene;
        let ((ka_a, kd_a), (ka_b, kd_b)) =
            (a.material.colors_at(a.hit.point), b.material.colors_at(b.hit.point));
        let mut sum = [scene.ambient.modulate(ka_a), scene.ambient.modulate(ka_b)];
        for (index, light) in scene.lights.iter().enumerate() {
            match (self.lit(a, index, light), self.lit(b, index, light)) {
                (Some(lit_a), Some(lit_b)) => {
                    let [s_a, s_b] = self.shadow_factor_pair((a, b), (index, light.position));
                    sum[0] += self.light_term(a, kd_a, (index, light), &lit_a, s_a);
                    sum[1] += self.light_term(b, kd_b, (index, light), &lit_b, s_b);
                }
                (Some(lit_a), None) => {
                    let s = self.shadow_factor(a, index, light.position);
                    sum[0] += self.light_term(a, kd_a, (index, light), &lit_a, s);
                }
                (None, Some(lit_b)) => {
                    let s = self.shadow_factor(b, index, light.position);
                    sum[1] += self.light_term(b, kd_b, (index, light), &lit_b, s);
                }
                (None, None) => {}
            }
        }
        sum
    }

    /// Light `index` at a hit before its shadow ray: `None` (recorded with `lum = 0`) when it
    /// cannot light it.
    #[inline(always)]
    fn lit(&mut self, at: &Shading<'_, V>, index: usize, light: &Light<V>) -> Option<Lit<V>> {
        let to_light = light.position - at.hit.point;
        let distance = to_light.length();
        let fat = light.fat(distance);
        // A light exactly at I has no direction: skipped with lum = 0 (§11 "Normalising").
        let Some(l) = to_light.try_unit() else {
            self.recorder.light(|| unlit(index, None, 0.0, fat));
            return None;
        };
        let n_dot_l = at.n_f.dot(l);
        // lum = 1 iff N·L > 0; no shadow ray otherwise (§6).
        if !(n_dot_l > 0.0) {
            self.recorder.light(|| unlit(index, Some(l), n_dot_l, fat));
            return None;
        }
        Some(Lit { l, n_dot_l, fat })
    }

    /// Light `index`'s term at a hit it may light, with shadow factor `s` (`kd` the hit's).
    #[inline(always)]
    fn light_term(
        &mut self,
        at: &Shading<'_, V>,
        kd: Rgb,
        (index, light): (usize, &Light<V>),
        &Lit { l, n_dot_l, fat }: &Lit<V>,
        s: f64,
    ) -> Rgb {
        let material = at.material;
        let view = -at.ray.dir;
        let weight = fat * s;
        let diffuse = light.intensity.modulate(kd) * (weight * n_dot_l);
        // H = normalize(L + V); undefined when L = −V, and then there is no highlight. With
        // ks = 0 the term is 0 whatever (N·H)^n ∈ [0, 1], so it is not computed.
        let highlight = match (material.ks > 0.0).then(|| (l + view).try_unit()).flatten() {
            Some(h) => material.highlight(at.n_f.dot(h)),
            None => 0.0,
        };
        let specular = light.intensity * (weight * material.ks * highlight);
        self.recorder.light(|| LightTerm {
            light: index,
            l: Some(l),
            n_dot_l,
            lum: 1.0,
            fat,
            shadow: Some(s),
            diffuse,
            specular,
        });
        diffuse + specular
    }

    /// The shadow ray from a hit toward the light at `position`, counted: the segment from the
    /// offset origin, and its length `d_L`; `None` when the offset origin sits on the light.
    #[inline(always)]
    fn shadow_ray(&mut self, at: &Shading<'_, V>, position: V) -> Option<(Ray<V>, f64)> {
        self.stats.rays.shadow += 1;
        let origin = spawn_origin(at.hit.point, at.n_f, position - at.hit.point, at.delta);
        let to_light = position - origin;
        let distance = to_light.length();
        let direction = to_light.try_unit()?;
        Some((Ray::new(origin, direction), distance))
    }

    /// `s`: the shadow ray is the segment from the offset origin to the light; an object counts for
    /// `0 < t < d_L`, each distinct one multiplying s by its kt once; an opaque one ends it (§11).
    fn shadow_factor(&mut self, at: &Shading<'_, V>, light: usize, position: V) -> f64 {
        let segment = self.shadow_ray(at, position);
        self.shadow_of(segment, light)
    }

    /// [`Tracer::shadow_factor`] of the segment [`Tracer::shadow_ray`] gave.
    fn shadow_of(&mut self, segment: Option<(Ray<V>, f64)>, light: usize) -> f64 {
        // The offset origin sits on the light: nothing lies between.
        let Some((ray, distance)) = segment else {
            return 1.0;
        };
        let scene = self.scene;
        let mut s = 1.0;
        let mut occluders: Vec<Occluder> = Vec::new();
        self.accel.occluders(scene, &ray, distance, &mut self.stats, &mut self.recorder, |object| {
            let kt = scene.material_of(object.index).kt;
            if R::ENABLED {
                occluders.push(Occluder { object, kt });
            }
            s *= kt;
            kt > 0.0
        });
        let (origin, direction) = (ray.origin, ray.dir);
        self.recorder.event(|| Event::ShadowRay { light, origin, direction, distance, occluders, s });
        s
    }

    /// [`Tracer::shadow_factor`] of two hits toward light `light` at `position`, their segments
    /// walked at once ([`Tracer::local_pair`] calls it when no recorder listens).
    fn shadow_factor_pair(
        &mut self,
        (a, b): (&Shading<'_, V>, &Shading<'_, V>),
        (light, position): (usize, V),
    ) -> [f64; 2] {
        match (self.shadow_ray(a, position), self.shadow_ray(b, position)) {
            (Some((ra, d_a)), Some((rb, d_b))) => {
                let scene = self.scene;
                let mut s = [1.0, 1.0];
                let segments = ((&ra, d_a), (&rb, d_b));
                self.accel.occluders_pair(
                    scene,
                    segments,
                    &mut self.stats,
                    &mut self.recorder,
                    |k, object| {
                        let kt = scene.material_of(object.index).kt;
                        s[k] *= kt;
                        kt > 0.0
                    },
                );
                s
            }
            (sa, sb) => [self.shadow_of(sa, light), self.shadow_of(sb, light)],
        }
    }
}

/// The entry of a light with `lum = 0`: no shadow ray, no terms.
fn unlit<V>(light: usize, l: Option<V>, n_dot_l: f64, fat: f64) -> LightTerm<V> {
    LightTerm { light, l, n_dot_l, lum: 0.0, fat, shadow: None, diffuse: Rgb::BLACK, specular: Rgb::BLACK }
}
