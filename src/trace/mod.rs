//! The recursion (algorithm.md §4, §6): `TraceRay` finds the nearest hit and `ShadePoint` sums
//! `I = I_local + ks·R + kt·T`, spawning R and T (in that order) while the level `n ≤ max_depth`.
//! Everything it does is reported to the recorder `R`, chosen at compile time.

pub mod shade;

use crate::accel::Accel;
use crate::geom::offset::{offset_distance, spawn_origin};
use crate::geom::optics::{indices, reflect, refract, Refraction};
use crate::geom::ray::Ray;
use crate::record::event::{Event, NodeHit, RayKind};
use crate::record::stats::Stats;
use crate::record::{RayEnd, RayStart, Recorder};
use crate::scene::material::{Material, Rgb};
use crate::scene::Scene;
use crate::shape::{Dim, SurfaceHit};

/// Traces rays through one scene, counting always and recording through `R`.
pub struct Tracer<'s, V: Dim, R: Recorder<V>> {
    /// The scene.
    pub scene: &'s Scene<V>,
    /// The structure that finds hits.
    pub accel: &'s Accel<V>,
    /// Children are spawned by a node at level n iff `n ≤ max_depth` (the scene's, or `--depth`).
    pub max_depth: u32,
    /// Where events go.
    pub recorder: R,
    /// Rays and tests so far.
    pub stats: Stats,
}

/// What a hit carries into shading.
pub(crate) struct Shading<'a, V> {
    pub ray: &'a Ray<V>,
    pub hit: SurfaceHit<V>,
    /// `D·N ≤ 0` (§3).
    pub entering: bool,
    /// The facing normal N_f: N when entering, −N when leaving.
    pub n_f: V,
    /// The spawn offset δ for every ray leaving this hit.
    pub delta: f64,
    /// The hit object's material.
    pub material: &'a Material,
}

impl<'s, V: Dim, R: Recorder<V>> Tracer<'s, V, R> {
    /// A tracer with the scene's own `max_depth`.
    pub fn new(scene: &'s Scene<V>, accel: &'s Accel<V>, recorder: R) -> Self {
        Self { scene, accel, max_depth: scene.max_depth, recorder, stats: Stats::default() }
    }

    /// Traces a primary ray (level 1) through the window point `uv` (empty for a ray given by hand).
    pub fn trace_primary(&mut self, ray: &Ray<V>, uv: &[f64]) -> Rgb {
        self.trace(ray, RayKind::Primary, 1, uv)
    }

    /// `TraceRay(R, n)`: the nearest hit (none → the background), then `ShadePoint`.
    fn trace(&mut self, ray: &Ray<V>, kind: RayKind, level: u32, uv: &[f64]) -> Rgb {
        match kind {
            RayKind::Primary => self.stats.rays.primary += 1,
            RayKind::Reflected => self.stats.rays.reflected += 1,
            RayKind::Transmitted => self.stats.rays.transmitted += 1,
        }
        self.recorder.open_ray(|| RayStart { kind, level, origin: ray.origin, direction: ray.dir });
        if kind == RayKind::Primary {
            self.recorder.event(|| Event::PrimaryRay {
                origin: ray.origin,
                direction: ray.dir,
                uv: uv.to_vec(),
            });
        }
        let Some((object, hit)) = self.accel.nearest(self.scene, ray, &mut self.stats, &mut self.recorder)
        else {
            let color = self.scene.background;
            self.recorder.event(|| Event::Miss { color });
            self.recorder.close_ray(|| RayEnd { hit: None, local: None, color });
            return color;
        };
        // §3: entering iff D·N ≤ 0 (a tangent counts as entering); N_f faces the incoming ray.
        let entering = ray.dir.dot(hit.normal) <= 0.0;
        let n_f = if entering { hit.normal } else { -hit.normal };
        self.recorder.event(|| Event::Hit {
            object,
            t: hit.t,
            point: hit.point,
            normal: hit.normal,
            entering,
        });
        let scene = self.scene;
        let hit_object = &scene.objects[object.index];
        let delta = offset_distance(hit.point, ray.origin, hit.t, hit_object.scale);
        let material = &scene.materials[hit_object.material];
        let at = Shading { ray, hit, entering, n_f, delta, material };
        let local = self.local(&at);
        let color = local + self.secondary(&at, level);
        self.recorder.close_ray(|| RayEnd {
            hit: Some(NodeHit { object, t: hit.t, point: hit.point, normal: hit.normal, entering }),
            local: Some(local),
            color,
        });
        color
    }

    /// `ks·TraceRay(R, n + 1) + kt·TraceRay(T, n + 1)` when `n ≤ max_depth` (§6), children in the
    /// order R, then T; TIR drops the `kt·T` term and records it.
    fn secondary(&mut self, at: &Shading<'_, V>, level: u32) -> Rgb {
        let material = at.material;
        let (reflects, transmits) = (material.reflects(), material.transmits());
        if !(reflects || transmits) {
            return Rgb::BLACK;
        }
        if level > self.max_depth {
            self.recorder.event(|| Event::DepthLimit { level });
            return Rgb::BLACK;
        }
        // A full log ends the recursion (its trace is then refused); compiled away when not recording.
        if R::ENABLED && self.recorder.full() {
            return Rgb::BLACK;
        }
        let (ks, kt, ior) = (material.ks, material.kt, material.ior);
        let mut sum = Rgb::BLACK;
        let d = at.ray.dir;
        if reflects {
            let r = reflect(d, at.n_f);
            let origin = spawn_origin(at.hit.point, at.n_f, r, at.delta);
            self.recorder.event(|| Event::Reflect { origin, direction: r, offset: at.delta });
            sum += self.trace(&Ray::new(origin, r), RayKind::Reflected, level + 1, &[]) * ks;
        }
        if transmits {
            // Swap n1, n2 for a leaving ray (§3).
            let (n1, n2) = indices(at.entering, ior);
            match refract(d, at.n_f, n1 / n2) {
                Refraction::TotalInternalReflection { k } => {
                    self.recorder.event(|| Event::TotalInternalReflection { k, n1, n2 });
                }
                Refraction::Transmitted { dir, .. } => {
                    let origin = spawn_origin(at.hit.point, at.n_f, dir, at.delta);
                    self.recorder.event(|| Event::Refract {
                        origin,
                        direction: dir,
                        offset: at.delta,
                        n1,
                        n2,
                    });
                    sum += self.trace(&Ray::new(origin, dir), RayKind::Transmitted, level + 1, &[]) * kt;
                }
            }
        }
        sum
    }
}
