//! Primary rays in packets of [`LANES`] (`accel::packet`): each packet's nearest hits found at
//! once, and the rays whose ray tree ends at that hit — a miss (the background), or a plane of
//! a material that neither reflects nor transmits (the lecture's floor) — shaded at once too:
//! the local model of §5 with its shadow segments ([`shade`], [`super::surface`]), lane by lane the operations of
//! [`Tracer::local`] in its order. Every other ray (a sphere, a mirror, a lane the packet
//! cannot answer) waits, from the start, for the batch's ray trees, traced a level at a time in
//! packets too ([`super::wave`]). The colours, the rays and the tests counted are those of one
//! ray at a time, bit for bit: a packet's counts for a lane are added only when its answer is
//! kept.
//!
//! The width is chosen when the program runs: `pulp::Arch` asks the CPU once, and the packets'
//! loop runs in code built for AVX2 where the CPU has it, else in the baseline build (SSE2).
//! Everything the loop calls in the packet is inlined into that code (`#[inline(always)]` all
//! the way down); the rays traced one at a time take the tracer's ordinary code.

use super::surface::{colors_at, facing, keep, offset, plane_point, shade, Colors, Surface};
use super::wave::{Searched, Trees};
use super::{Tracer, WindowV};
use crate::accel::packet::{key, LaneCounts, Packets, NO_KEY};
use crate::geom::lanes::{
    all, and_not, any, axes, gather, holds, lanes, or, select, splat, test, unit, vector, Vs, F, LANES, M,
};
use crate::geom::ray::Ray;
use crate::record::event::RayKind;
use crate::record::NoRecorder;
use crate::scene::camera::{Camera, Projection};
use crate::scene::material::{Material, Rgb};
use crate::shape::plane::Plane;
use crate::shape::Dim;
use std::sync::OnceLock;

/// The instruction sets this CPU has, asked once.
fn arch() -> pulp::Arch {
    static ARCH: OnceLock<pulp::Arch> = OnceLock::new();
    *ARCH.get_or_init(pulp::Arch::new)
}

/// The primary rays of a batch of window points: `Camera::primary_ray(u, v)` of each `u` of `us`
/// with its `v` (one for a row of the window), made 4 at a time as they are traced.
#[derive(Clone, Copy)]
pub(super) struct Row<'a, V, W> {
    pub camera: &'a Camera<V>,
    pub us: &'a [f64],
    pub v: W,
}

impl<V: Dim, W: WindowV> Row<'_, V, W> {
    /// Ray `i`, as the scalar code makes it.
    #[inline(always)]
    fn ray(&self, i: usize) -> Ray<V> {
        self.camera.primary_ray(self.us[i], self.v.at(i))
    }
    /// Rays `first … first + LANES − 1` as lane vectors: origins and directions.
    #[inline(always)]
    fn lanes(&self, first: usize) -> (Vs, Vs) {
        if let Some(rays) =
            window_rays(self.camera, lanes(|k| self.us[first + k]), lanes(|k| self.v.at(first + k)))
        {
            return rays;
        }
        let rays: [Ray<V>; LANES] = std::array::from_fn(|k| self.ray(first + k));
        (gather(|k| rays[k].origin), gather(|k| rays[k].dir))
    }
}

/// `Camera::primary_ray(u, v)` in each lane: the window point `S = O + u·u + v·v − p·w`, then
/// from S along `−w` (orthographic) or from O along `S − O` normalised (perspective). `None`
/// when some lane's `S − O` is off `try_unit`'s usual branch: the scalar code makes those rays.
#[inline(always)]
fn window_rays<V: Dim>(camera: &Camera<V>, u: F, v: F) -> Option<(Vs, Vs)> {
    let frame = &camera.frame;
    let (eye, fu, fv, fw) = (axes(camera.eye), axes(frame.u), axes(frame.v), axes(frame.w));
    let s = vector::<V>(|a, k| eye[a] + fu[a] * u[k] + fv[a] * v[k] - fw[a] * camera.p);
    match camera.projection {
        Projection::Orthographic => Some((s, vector::<V>(|a, _| -fw[a]))),
        Projection::Perspective => {
            let (d, usual, _) = unit::<V>(&vector::<V>(|a, k| s[a][k] - eye[a]));
            all(usual).then(|| (vector::<V>(|a, _| eye[a]), d))
        }
    }
}

/// [`Tracer::trace_primary`] of each ray of `row` into the same place of `colors`, in
/// packets searched by `packets`, in the widest code this CPU runs.
pub(super) fn trace<'s, V: Dim, W: WindowV>(
    tracer: &mut Tracer<'s, V, NoRecorder>,
    packets: Packets<'s, V>,
    row: Row<'_, V, W>,
    colors: &mut [Rgb],
) {
    debug_assert_eq!(row.us.len(), colors.len(), "a colour for every ray");
    arch().dispatch(Batch { tracer, packets, row, colors });
}

/// The packets' loop, run by `pulp` in the code it chose.
struct Batch<'b, 's, V: Dim, W> {
    tracer: &'b mut Tracer<'s, V, NoRecorder>,
    packets: Packets<'s, V>,
    row: Row<'b, V, W>,
    colors: &'b mut [Rgb],
}

impl<V: Dim, W: WindowV> pulp::WithSimd for Batch<'_, '_, V, W> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Batch { tracer, packets, row, colors } = self;
        let mut trees = Trees::take();
        let whole = row.us.len() - row.us.len() % LANES;
        for (first, part) in (0..whole).step_by(LANES).zip(colors[..whole].chunks_exact_mut(LANES)) {
            packet(tracer, &packets, &row, first, part, &mut trees);
        }
        // The last rays, fewer than a packet, and the rays the packets left: their trees in waves.
        for i in whole..row.us.len() {
            trees.root(&row.ray(i), i, None);
        }
        trees.trace(tracer, &packets, colors);
        trees.keep();
    }
}

/// The packet of rays `first …` of `row` into their colours, or into `trees` (a sphere, a
/// mirror, a lane the packet cannot answer), which write them later.
#[inline(always)]
fn packet<V: Dim, W: WindowV>(
    tracer: &mut Tracer<'_, V, NoRecorder>,
    packets: &Packets<'_, V>,
    row: &Row<'_, V, W>,
    first: usize,
    colors: &mut [Rgb],
    trees: &mut Trees,
) {
    let scene = tracer.scene;
    let (o, d) = row.lanes(first);
    let mut counts = LaneCounts::default();
    let mut shadows = [0; LANES];
    let (best, scalar) = packets.nearest(&o, &d, &mut counts);
    // The search's tests alone, for the lanes left to the ray trees.
    let search = counts;
    let background = scene.background.0;
    let mut color: Colors = std::array::from_fn(|c| splat(background[c]));
    // Misses end here; so do the lanes a plane below shades.
    let mut done = test(|k| best.key[k] == NO_KEY);
    for (prim, plane) in packets.planes() {
        let on = and_not(test(|k| best.key[k] == key(*prim)), scalar);
        let object = &scene.objects[prim.object()];
        let material = &scene.materials[object.material];
        if !any(on) || material.reflects() || material.transmits() {
            continue;
        }
        let hit = PlaneHit { plane, scale: object.scale, material, t: best.t };
        let (shaded, ok) = local(tracer, packets, &hit, (&o, &d), on, (&mut counts, &mut shadows));
        // `local + secondary` with no secondary ray: `+ (0, 0, 0)`, as the recursion adds it.
        color = std::array::from_fn(|c| select(ok, lanes(|k| shaded[c][k] + Rgb::BLACK.0[c]), color[c]));
        done = or(done, ok);
    }
    let done = and_not(done, scalar);
    for k in 0..LANES {
        if holds(done, k) {
            keep(&mut tracer.stats, RayKind::Primary, (&counts, &shadows), k);
            colors[k] = Rgb(std::array::from_fn(|c| color[c][k]));
        } else {
            let searched = Searched {
                t: best.t[k],
                key: best.key[k],
                flagged: holds(scalar, k),
                object_tests: search.object[k],
                node_tests: search.node[k],
            };
            trees.root(&row.ray(first + k), first + k, Some(searched));
        }
    }
}

/// A plane met by the lanes of a packet.
struct PlaneHit<'a, V> {
    plane: &'a Plane<V>,
    /// The object's scale, for the spawn offset.
    scale: f64,
    material: &'a Material,
    /// Each lane's t.
    t: F,
}

/// `I_local` of [`Tracer::local`] in the lanes `on`, each lane's hit on `hit`'s plane by the ray
/// `o + t·d`, then [`shade`]: [`Hit::new`]'s surface for one plane and one material, which the
/// lecture's floor, most of an image, takes without a lane's object chosen. The material
/// reflects nothing, so `ks = 0` and there is no highlight.
#[inline(always)]
fn local<V: Dim>(
    tracer: &Tracer<'_, V, NoRecorder>,
    packets: &Packets<'_, V>,
    hit: &PlaneHit<'_, V>,
    (o, d): (&Vs, &Vs),
    on: M,
    tally: (&mut LaneCounts, &mut [u64; LANES]),
) -> (Colors, M) {
    let (material, t) = (hit.material, &hit.t);
    let n = axes(hit.plane.normal);
    let raw = vector::<V>(|a, k| o[a][k] + d[a][k] * t[k]);
    let point = plane_point::<V>(axes(hit.plane.point), n, &raw);
    let (_, n_f) = facing::<V>(d, &vector::<V>(|a, _| n[a]));
    let delta = offset::<V>(&point, o, t, &splat(hit.scale));
    let (ka, kd) = colors_at::<V>(material, &point);
    let view = vector::<V>(|a, k| -d[a][k]);
    let surface =
        Surface { point, n_f, delta, view, ka, kd, ks: splat(material.ks), materials: [material; LANES] };
    shade(tracer, packets, &surface, on, tally)
}

/// The packets against one ray at a time, on the scenes that take each branch: the colours bit
/// for bit and every count, over every pixel centre (so whole packets and a last partial one).
#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{Accel, AccelKind, AccelOptions};
    use crate::record::stats::Stats;
    use crate::scene::load::load_str;
    use crate::scene::{fixtures, AnyScene, Scene};
    use proptest::prelude::*;

    /// The colours and counts of every pixel centre of `scene`, traced by `trace`.
    fn traced<V: Dim>(
        scene: &Scene<V>,
        accel: &Accel<V>,
        trace: impl Fn(&mut Tracer<'_, V, NoRecorder>, &[Ray<V>], &mut [Rgb]),
    ) -> (Vec<[u64; 3]>, Stats) {
        let cam = &scene.camera;
        let rays: Vec<Ray<V>> = (0..cam.ny)
            .flat_map(|j| (0..cam.nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let (u, v) = cam.pixel_center(i, j);
                cam.primary_ray(u, v)
            })
            .collect();
        let mut tracer = Tracer::new(scene, accel, NoRecorder);
        let mut colors = vec![Rgb::BLACK; rays.len()];
        trace(&mut tracer, &rays, &mut colors);
        (colors.iter().map(|c| c.0.map(f64::to_bits)).collect(), tracer.stats)
    }

    /// Packets and single rays agree on `scene`; `packed`: whether the scene has a packet search
    /// (`None`: either).
    fn agree<V: Dim>(scene: &Scene<V>, packed: impl Into<Option<bool>>) {
        let accel = Accel::build_for_render(scene, &AccelOptions::of(AccelKind::Bvh));
        if let Some(packed) = packed.into() {
            assert_eq!(accel.packets(scene).is_some(), packed, "a packet search");
        }
        let single = traced(scene, &accel, |t, rays, colors| {
            for (color, ray) in colors.iter_mut().zip(rays) {
                *color = t.trace_primary(ray, &[]);
            }
        });
        // The same rays made in the packets, a row of the window at a time.
        let cam = &scene.camera;
        let us: Vec<f64> = (0..cam.nx).map(|i| cam.pixel_center(i, 0).0).collect();
        let rows = traced(scene, &accel, |t, _, colors| {
            for (j, row) in colors.chunks_exact_mut(cam.nx).enumerate() {
                t.trace_window_row(&us, cam.pixel_center(0, j).1, &mut Vec::new(), row);
            }
        });
        let differ = rows.0.iter().zip(&single.0).position(|(a, b)| a != b);
        assert_eq!(differ, None, "the first pixel that differs");
        assert_eq!(rows.1, single.1);
        assert!(single.1.rays.primary > 0);
    }

    fn space(text: &str) -> Scene<glam::DVec3> {
        match load_str(text) {
            Ok(AnyScene::Space(s)) => s,
            other => panic!("not a 3D scene: {other:?}"),
        }
    }

    fn flat(text: &str) -> Scene<glam::DVec2> {
        match load_str(text) {
            Ok(AnyScene::Flat(s)) => s,
            other => panic!("not a 2D scene: {other:?}"),
        }
    }

    /// A 3D scene: a camera at `eye` looking at the origin, `objects` and `lights` (JSON).
    fn scene_3d(eye: &str, projection: &str, lights: &str, objects: &str) -> String {
        format!(
            r#"{{ "camera": {{ "eye": {eye}, "center": [0, 0, 0], "up": [0, 1, 0], "projection": "{projection}",
                "window": {{ "l": -2, "r": 2, "b": -1.5, "t": 1.5 }}, "resolution": [37, 23] }},
                "background": [0.2, 0.3, 0.9], "ambient": [0.5, 0.4, 0.3], "max_depth": 3,
                "lights": [ {lights} ], "objects": [ {objects} ] }}"#
        )
    }

    /// A checkered floor, a glass sphere, a mirror sphere and a matte one.
    const ROOM: &str = r#"
        { "type": "plane", "point": [0, -1, 0], "normal": [0, 1, 0],
          "material": { "ka": [0.1, 0.02, 0.01], "kd": [0.7, 0.1, 0.1],
                        "checker": { "size": 0.5, "kd2": [0.8, 0.7, 0.1], "ka2": [0.1, 0.1, 0.02] } } },
        { "type": "sphere", "center": [-0.8, 0, -0.5], "radius": 0.7, "material": { "ks": 0.7, "kd": 0.2 } },
        { "type": "sphere", "center": [0.6, -0.2, 0.6], "radius": 0.6,
          "material": { "ks": 0.2, "kt": 0.8, "ior": 1.5, "kd": 0.05 } },
        { "type": "sphere", "center": [1.5, -0.5, -1], "radius": 0.5, "material": { "kd": [0.2, 0.6, 0.2] } }"#;

    #[test]
    fn the_lecture_scene_is_the_same_in_packets() {
        agree(&space(include_str!("../../scenes/whitted.json")), true);
    }

    #[test]
    fn checkers_lights_shadows_and_attenuation_are_the_same_in_packets() {
        let lights = r#"{ "position": [3, 5, 4] }, { "position": [-4, 2, 1], "intensity": [0.5, 0.4, 0.3],
            "attenuation": [1, 0.1, 0.02] }, { "position": [0, -3, 0] }"#;
        agree(&space(&scene_3d("[0, 2, 6]", "perspective", lights, ROOM)), true);
        // A light on the floor's plane (N·L = 0) and one right at a floor point's height.
        let grazing = r#"{ "position": [5, -1, 0] }, { "position": [0.3, -0.99, 0.2] }"#;
        agree(&space(&scene_3d("[0, 2, 6]", "perspective", grazing, ROOM)), true);
    }

    #[test]
    fn planes_of_every_kind_and_a_camera_inside_the_box_are_the_same_in_packets() {
        // A transparent plane and a mirror one beside the floor; a floor seen from below.
        let planes = format!(
            r#"{ROOM},
            {{ "type": "plane", "point": [0, 0, -3], "normal": [0, 0, 1], "material": {{ "kt": 0.5, "ior": 1.0, "kd": 0.3 }} }},
            {{ "type": "plane", "point": [-3, 0, 0], "normal": [1, 0, 0], "material": {{ "ks": 0.5 }} }},
            {{ "type": "plane", "point": [0, 3, 0], "normal": [0, 1, 0], "material": {{ "kd": [0.3, 0.3, 0.3] }} }}"#
        );
        let light = r#"{ "position": [1, 2, 2] }"#;
        agree(&space(&scene_3d("[0, 2, 6]", "perspective", light, &planes)), true);
        // The eye inside the spheres' box: the root box holds every primary ray's origin.
        agree(&space(&scene_3d("[0.1, -0.3, 0.05]", "perspective", light, ROOM)), true);
    }

    #[test]
    fn rays_parallel_to_a_slab_and_scenes_without_a_packet_search_are_the_same() {
        // Orthographic along −z: every D has zero x and y, so 1/D is infinite (the scalar branch).
        let light = r#"{ "position": [1, 4, 5] }"#;
        agree(&space(&scene_3d("[0, 0, 6]", "orthographic", light, ROOM)), true);
        // Only planes: no box, no node test.
        let floor = ROOM.split("},\n        { \"type\": \"sphere\"").next().expect("the floor");
        agree(&space(&scene_3d("[0, 2, 6]", "perspective", light, &format!("{floor}}}"))), true);
        // A box among the objects: no packet search.
        let boxed = format!(r#"{ROOM}, {{ "type": "box", "min": [-2, -1, -2], "max": [-1.5, 0, -1.5] }}"#);
        agree(&space(&scene_3d("[0, 2, 6]", "perspective", light, &boxed)), false);
    }

    #[test]
    fn a_2d_scene_is_the_same_in_packets() {
        agree(&flat(&fixtures::line(203)), true);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// Random spheres over a random plane, random lights and eye.
        #[test]
        fn random_scenes_are_the_same_in_packets(
            spheres in fixtures::random_spheres(),
            normal in (-0.3..0.3f64, 0.5..1.0f64, -0.3..0.3f64),
            lights in fixtures::random_lights(),
            eye in fixtures::random_eye(),
        ) {
            let eye = format!("[{}, {}, {}]", eye.0, eye.1, eye.2);
            // A BVH of several spheres may split, and then has no packet search.
            let (objects, lights) = (fixtures::objects(normal, &spheres), fixtures::lights(&lights));
            agree(&space(&scene_3d(&eye, "perspective", &lights, &objects)), None);
        }
    }
}
