//! The local model (algorithm.md §5):
//! `I_local = Ia·Ka + Σ_i Isrc_i·fat_i·s_i·lum_i·[kd·(N·L_i) + ks·(N·H_i)^n]`, with the shadow
//! factor `s_i` the product of `kt` over the distinct objects on the segment from I to light i.

use super::{Shading, Tracer};
use crate::geom::offset::spawn_origin;
use crate::geom::ray::Ray;
use crate::record::event::{Event, LightTerm, Occluder};
use crate::record::Recorder;
use crate::scene::material::Rgb;
use crate::shape::Dim;

impl<V: Dim, R: Recorder<V>> Tracer<'_, V, R> {
    /// `I_local` at a hit, every light in scene order.
    pub(crate) fn local(&mut self, at: &Shading<'_, V>) -> Rgb {
        let scene = self.scene;
        let material = at.material;
        // The checker swaps kd (and ka) by the parity of I's cell.
        let (ka, kd) = material.colors_at(at.hit.point);
        let mut sum = scene.ambient.modulate(ka);
        let view = -at.ray.dir;
        for (index, light) in scene.lights.iter().enumerate() {
            let to_light = light.position - at.hit.point;
            let distance = to_light.length();
            let fat = light.fat(distance);
            // A light exactly at I has no direction: skipped with lum = 0 (§11 "Normalising").
            let Some(l) = to_light.try_unit() else {
                self.recorder.light(|| unlit(index, None, 0.0, fat));
                continue;
            };
            let n_dot_l = at.n_f.dot(l);
            // lum = 1 iff N·L > 0; no shadow ray otherwise (§6).
            if !(n_dot_l > 0.0) {
                self.recorder.light(|| unlit(index, Some(l), n_dot_l, fat));
                continue;
            }
            let s = self.shadow_factor(at, index, light.position);
            let weight = fat * s;
            let diffuse = light.intensity.modulate(kd) * (weight * n_dot_l);
            // H = normalize(L + V); undefined when L = −V, and then there is no highlight. With
            // ks = 0 the term is 0 whatever (N·H)^n ∈ [0, 1], so it is not computed.
            let highlight = match (material.ks > 0.0).then(|| (l + view).try_unit()).flatten() {
                Some(h) => material.highlight(at.n_f.dot(h)),
                None => 0.0,
            };
            let specular = light.intensity * (weight * material.ks * highlight);
            sum += diffuse + specular;
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
        }
        sum
    }

    /// `s`: the shadow ray is the segment from the offset origin to the light; an object counts for
    /// `0 < t < d_L`, each distinct one multiplying s by its kt once; an opaque one ends it (§11).
    fn shadow_factor(&mut self, at: &Shading<'_, V>, light: usize, position: V) -> f64 {
        self.stats.rays.shadow += 1;
        let origin = spawn_origin(at.hit.point, at.n_f, position - at.hit.point, at.delta);
        let to_light = position - origin;
        let distance = to_light.length();
        let Some(direction) = to_light.try_unit() else {
            // The offset origin sits on the light: nothing lies between.
            return 1.0;
        };
        let ray = Ray::new(origin, direction);
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
        self.recorder.event(|| Event::ShadowRay { light, origin, direction, distance, occluders, s });
        s
    }
}

/// The entry of a light with `lum = 0`: no shadow ray, no terms.
fn unlit<V>(light: usize, l: Option<V>, n_dot_l: f64, fat: f64) -> LightTerm<V> {
    LightTerm { light, l, n_dot_l, lum: 0.0, fat, shadow: None, diffuse: Rgb::BLACK, specular: Rgb::BLACK }
}
