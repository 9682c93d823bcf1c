//! The recursion (algorithm.md §4, §6): `TraceRay` finds the nearest hit and `ShadePoint` sums
//! `I = I_local + ks·R + kt·T`, spawning R and T (in that order) while the level `n ≤ max_depth`.
//! Everything it does is reported to the recorder `R`, chosen at compile time.

#[cfg(target_arch = "x86_64")]
pub mod packet;
pub mod shade;
#[cfg(target_arch = "x86_64")]
mod surface;
#[cfg(target_arch = "x86_64")]
mod wave;

use crate::accel::Accel;
use crate::geom::offset::{offset_distance, spawn_origin};
use crate::geom::optics::{indices, reflect, refract, Refraction};
use crate::geom::ray::Ray;
use crate::record::event::{Event, NodeHit, RayKind};
use crate::record::stats::Stats;
use crate::record::{NoRecorder, RayEnd, RayStart, Recorder};
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
        self.stats.rays.count(kind);
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
        // The secondary rays made before the local shading, so that their chains (the
        // refraction's square root) overlap with it: the same rays, events in the same order.
        let spawned = self.spawn(&at, level);
        let local = self.local(&at);
        let color = local + self.secondary(&at, level, spawned);
        self.recorder.close_ray(|| RayEnd {
            hit: Some(NodeHit { object, t: hit.t, point: hit.point, normal: hit.normal, entering }),
            local: Some(local),
            color,
        });
        color
    }

    /// The rays a hit at level `n` spawns (§6): none past `max_depth`; R when the material
    /// reflects, T (or TIR's `k`) when it transmits, each from its offset origin (§3, §11).
    fn spawn(&self, at: &Shading<'_, V>, level: u32) -> Spawned<V> {
        let material = at.material;
        if level > self.max_depth {
            return Spawned { reflected: None, transmitted: None };
        }
        let d = at.ray.dir;
        let reflected = material.reflects().then(|| {
            let r = reflect(d, at.n_f);
            Ray::new(spawn_origin(at.hit.point, at.n_f, r, at.delta), r)
        });
        let transmitted = material.transmits().then(|| {
            // Swap n1, n2 for a leaving ray (§3).
            let (n1, n2) = indices(at.entering, material.ior);
            let ray = match refract(d, at.n_f, n1 / n2) {
                Refraction::TotalInternalReflection { k } => Err(k),
                Refraction::Transmitted { dir, .. } => {
                    Ok(Ray::new(spawn_origin(at.hit.point, at.n_f, dir, at.delta), dir))
                }
            };
            Transmission { n1, n2, ray }
        });
        Spawned { reflected, transmitted }
    }

    /// `ks·TraceRay(R, n + 1) + kt·TraceRay(T, n + 1)` when `n ≤ max_depth` (§6), children in the
    /// order R, then T; TIR drops the `kt·T` term and records it. `spawned`: [`Tracer::spawn`]'s.
    fn secondary(&mut self, at: &Shading<'_, V>, level: u32, spawned: Spawned<V>) -> Rgb {
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
        let (ks, kt) = (material.ks, material.kt);
        let mut sum = Rgb::BLACK;
        if let Some(ray) = spawned.reflected {
            let (origin, direction) = (ray.origin, ray.dir);
            self.recorder.event(|| Event::Reflect { origin, direction, offset: at.delta });
            sum += self.trace(&ray, RayKind::Reflected, level + 1, &[]) * ks;
        }
        if let Some(Transmission { n1, n2, ray }) = spawned.transmitted {
            match ray {
                Err(k) => {
                    self.recorder.event(|| Event::TotalInternalReflection { k, n1, n2 });
                }
                Ok(ray) => {
                    let (origin, direction) = (ray.origin, ray.dir);
                    self.recorder.event(|| Event::Refract { origin, direction, offset: at.delta, n1, n2 });
                    sum += self.trace(&ray, RayKind::Transmitted, level + 1, &[]) * kt;
                }
            }
        }
        sum
    }
}

impl<V: Dim> Tracer<'_, V, NoRecorder> {
    /// [`Tracer::trace_primary`] of the primary rays through `(u, v)` for each `u` of `us`
    /// (`Camera::primary_ray`) into the same place of `colors`, the same colours, rays and tests:
    /// in packets where the structure has a packet search and the CPU's SIMD serves it (x86-64,
    /// [`packet`]), else one at a time, made first into `rays` (their normalisations back to
    /// back, independent, so they overlap).
    pub fn trace_window_row(&mut self, us: &[f64], v: f64, rays: &mut Vec<Ray<V>>, colors: &mut [Rgb]) {
        if self.trace_packets(us, v, colors) {
            return;
        }
        let camera = &self.scene.camera;
        rays.clear();
        rays.extend(us.iter().map(|&u| camera.primary_ray(u, v)));
        for (color, ray) in colors.iter_mut().zip(rays.iter()) {
            *color = self.trace_primary(ray, &[]);
        }
    }

    /// [`Tracer::trace_primary`] of the primary ray through each window point `(us[i], vs[i])`
    /// into `colors[i]`, the same colours, rays and tests: in packets whose lanes each have their
    /// own point, where [`Tracer::trace_window_row`] would use packets, else one at a time.
    pub fn trace_window_points(&mut self, us: &[f64], vs: &[f64], colors: &mut [Rgb]) {
        debug_assert_eq!(us.len(), vs.len(), "a v for every u");
        if self.trace_packets(us, vs, colors) {
            return;
        }
        let camera = &self.scene.camera;
        for ((color, &u), &v) in colors.iter_mut().zip(us).zip(vs) {
            *color = self.trace_primary(&camera.primary_ray(u, v), &[]);
        }
    }

    /// The rays through `(us[i], v.at(i))` into `colors` in packets ([`packet`]), if this is
    /// x86-64 and the structure has a packet search: then true, else false and nothing traced.
    #[cfg_attr(not(target_arch = "x86_64"), allow(unused_variables, clippy::unused_self))]
    fn trace_packets(&mut self, us: &[f64], v: impl WindowV, colors: &mut [Rgb]) -> bool {
        #[cfg(target_arch = "x86_64")]
        if let Some(packets) = self.accel.packets(self.scene) {
            let camera = &self.scene.camera;
            packet::trace(self, packets, packet::Row { camera, us, v }, colors);
            return true;
        }
        false
    }
}

/// The `v` of a batch of window points: one `f64` for a row of the window, or a slice of one a
/// point. A type, not a value, so that a row's packets are made with its one `v` in a register.
/// Only the packets read it: elsewhere (the WebAssembly module) it is carried and never read.
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
pub(crate) trait WindowV: Copy {
    /// The `v` of point `i`.
    fn at(self, i: usize) -> f64;
}

impl WindowV for f64 {
    #[inline(always)]
    fn at(self, _i: usize) -> f64 {
        self
    }
}

impl WindowV for &[f64] {
    #[inline(always)]
    fn at(self, i: usize) -> f64 {
        self[i]
    }
}

/// The secondary rays of a hit ([`Tracer::spawn`]), made before they are traced.
pub(crate) struct Spawned<V> {
    /// R, when the material reflects.
    reflected: Option<Ray<V>>,
    /// T, or TIR, when the material transmits.
    transmitted: Option<Transmission<V>>,
}

/// A transmitting hit's refraction: the indices `n1 → n2`, and T, or TIR's negative `k`.
struct Transmission<V> {
    n1: f64,
    n2: f64,
    ray: Result<Ray<V>, f64>,
}

/// The invariants ARCHITECTURE.md states of the recursion, each on the smallest scene that shows
/// it: `kt = 0` spawns no T, a full recorder stops the secondary rays, the depth limit, and total
/// internal reflection spawns R only.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::record::EventLog;
    use crate::scene::load::load_str;
    use crate::scene::AnyScene;
    use glam::DVec3;

    /// A 3D scene of `objects` (JSON), one light, `max_depth` as given.
    fn scene(objects: &str, max_depth: u32) -> Scene<DVec3> {
        let text = format!(
            r#"{{ "camera": {{ "eye": [0, 0, 5], "center": [0, 0, 0], "window": {{ "l": -1, "r": 1, "b": -1, "t": 1 }},
                "resolution": [4, 4] }}, "max_depth": {max_depth}, "lights": [ {{ "position": [0, 5, 5] }} ],
                "objects": [ {objects} ] }}"#
        );
        match load_str(&text) {
            Ok(AnyScene::Space(s)) => s,
            other => panic!("not a 3D scene: {other:?}"),
        }
    }

    /// The log and the counts of one ray traced through `scene` into `recorder`.
    fn traced<R: Recorder<DVec3>>(scene: &Scene<DVec3>, ray: Ray<DVec3>, recorder: R) -> (R, Stats) {
        let accel = Accel::build(scene, AccelKind::None);
        let mut tracer = Tracer::new(scene, &accel, recorder);
        tracer.trace_primary(&ray, &[]);
        (tracer.recorder, tracer.stats)
    }

    fn kinds(log: &EventLog<DVec3>) -> Vec<RayKind> {
        log.nodes.iter().map(|n| n.start.kind).collect()
    }

    fn count(log: &EventLog<DVec3>, test: impl Fn(&Event<DVec3>) -> bool) -> usize {
        log.events.iter().filter(|l| test(&l.event)).count()
    }

    /// Two parallel mirrors, x = ±1, and a ray between them at 45°: every hit reflects.
    const MIRRORS: &str = r#"{ "type": "plane", "point": [-1, 0, 0], "normal": [1, 0, 0], "material": { "ks": 0.9 } },
        { "type": "plane", "point": [1, 0, 0], "normal": [-1, 0, 0], "material": { "ks": 0.9 } }"#;

    fn diagonal() -> Ray<DVec3> {
        Ray::new(DVec3::ZERO, DVec3::new(1.0, 0.0, -1.0).normalize())
    }

    #[test]
    fn a_material_with_kt_0_spawns_no_transmitted_ray() {
        let mirror =
            r#"{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": { "ks": 0.5, "kt": 0 } }"#;
        let s = scene(mirror, 5);
        let (log, stats) = traced(&s, Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z), EventLog::new());
        assert_eq!(kinds(&log), [RayKind::Primary, RayKind::Reflected]);
        assert_eq!(stats.rays.transmitted, 0);
        assert_eq!(
            count(&log, |e| matches!(e, Event::Refract { .. } | Event::TotalInternalReflection { .. })),
            0
        );
        // The same sphere with kt > 0 does spawn T: the test above can fail.
        let glass = mirror.replace("\"kt\": 0", "\"kt\": 0.5, \"ior\": 1.5");
        let (log, stats) =
            traced(&scene(&glass, 5), Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z), EventLog::new());
        assert!(stats.rays.transmitted > 0 && kinds(&log).contains(&RayKind::Transmitted));
    }

    #[test]
    fn the_depth_limit_stops_the_recursion_at_max_depth_plus_one() {
        for max_depth in [0, 1, 4] {
            let (log, stats) = traced(&scene(MIRRORS, max_depth), diagonal(), EventLog::new());
            // Levels 1 … max_depth + 1 are traced; the deepest node records the limit instead of a child.
            let deepest = log.nodes.iter().map(|n| n.start.level).max();
            assert_eq!(deepest, Some(max_depth + 1));
            assert_eq!(stats.rays.reflected, u64::from(max_depth));
            let limits: Vec<u32> = log
                .events
                .iter()
                .filter_map(|l| match l.event {
                    Event::DepthLimit { level } => Some(level),
                    _ => None,
                })
                .collect();
            assert_eq!(limits, [max_depth + 1]);
        }
    }

    /// A recorder that says it is full from the start, and counts the rays it is shown.
    #[derive(Default)]
    struct Full {
        opened: usize,
    }

    impl Recorder<DVec3> for Full {
        const ENABLED: bool = true;
        fn event(&mut self, _make: impl FnOnce() -> Event<DVec3>) {}
        fn open_ray(&mut self, _make: impl FnOnce() -> RayStart<DVec3>) {
            self.opened += 1;
        }
        fn light(&mut self, _make: impl FnOnce() -> crate::record::event::LightTerm<DVec3>) {}
        fn close_ray(&mut self, _make: impl FnOnce() -> RayEnd<DVec3>) {}
        fn full(&self) -> bool {
            true
        }
    }

    #[test]
    fn a_full_recorder_stops_the_secondary_rays() {
        let s = scene(MIRRORS, 8);
        let (full, stats) = traced(&s, diagonal(), Full::default());
        assert_eq!((full.opened, stats.rays.reflected), (1, 0), "the primary ray only");
        // A log that fills up part way: it stops spawning there and says it overflowed.
        let (log, stats) = traced(&s, diagonal(), EventLog::with_limit(10));
        assert!(log.overflowed() && stats.rays.reflected < 8, "{} reflected", stats.rays.reflected);
        assert!(log.events.len() + log.nodes.len() <= 10 + 1);
        // Not full: all eight generations.
        assert_eq!(traced(&s, diagonal(), EventLog::new()).1.rays.reflected, 8);
    }

    #[test]
    fn total_internal_reflection_spawns_the_reflected_ray_only() {
        // From inside a glass sphere (n = 1.5) at 64° to the normal, beyond the critical 41.8°.
        let glass = r#"{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": { "ks": 0.1, "kt": 0.9, "ior": 1.5 } }"#;
        let ray = Ray::new(DVec3::new(0.0, 0.9, 0.0), DVec3::X);
        let (log, stats) = traced(&scene(glass, 1), ray, EventLog::new());
        let root = &log.nodes[0];
        let children: Vec<RayKind> = root.children.iter().map(|c| log.nodes[*c].start.kind).collect();
        assert_eq!(children, [RayKind::Reflected]);
        let tir = log.events.iter().find(|l| matches!(l.event, Event::TotalInternalReflection { .. }));
        assert_eq!(tir.map(|l| l.ray), Some(Some(0)), "recorded on the root");
        assert_eq!(count(&log, |e| matches!(e, Event::Refract { .. })), 0);
        assert_eq!(stats.rays.transmitted, 0);
    }
}
