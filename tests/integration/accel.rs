//! Acceleration structures agree with brute force (issue 5; algorithm.md §6, §9, §11;
//! numerics.md §I): property tests over random 2D and 3D scenes, exact-arithmetic scenes with
//! axis-parallel rays through edges and corners, meshes, and every case of numerics.md §I by name.

use crate::support::{fixture, scene2, scene3, trace_pixel, whitted, SceneText, Scratch};
use glam::{DVec2, DVec3};
use proptest::prelude::*;
use serde_json::{json, Value};
use whitted::accel::binned::LARGE;
use whitted::accel::grid::Grid;
use whitted::accel::{Accel, AccelKind, AccelOptions, Nearest, Prim, Visitor};
use whitted::bounds::aabb::Aabb;
use whitted::bounds::VolumeKind;
use whitted::doc::{trace_document, TraceTarget};
use whitted::geom::ray::Ray;
use whitted::record::event::Event;
use whitted::record::stats::Stats;
use whitted::record::{EventLog, NoRecorder, Recorder};
use whitted::render::render_centers;
use whitted::scene::load::load_str_with;
use whitted::scene::{AnyScene, Scene};
use whitted::shape::Dim;
use whitted::trace::Tracer;

/// Every structure and every bounding volume, brute force first.
fn every_structure() -> Vec<AccelOptions> {
    let mut all: Vec<AccelOptions> = AccelKind::ALL.iter().map(|k| AccelOptions::of(*k)).collect();
    for volume in [VolumeKind::Sphere, VolumeKind::Kdop] {
        all.push(AccelOptions { kind: AccelKind::Bounds, volume, grid: None });
    }
    all.push(AccelOptions { kind: AccelKind::Grid, volume: VolumeKind::Aabb, grid: Some(vec![1; 3]) });
    all.push(AccelOptions { kind: AccelKind::Grid, volume: VolumeKind::Aabb, grid: Some(vec![7, 3, 5]) });
    all
}

fn options_for<V: Dim>() -> Vec<AccelOptions> {
    every_structure()
        .into_iter()
        .map(|mut o| {
            if let Some(g) = &mut o.grid {
                g.truncate(V::DIM);
            }
            o
        })
        .collect()
}

/// The nearest hit as `(object, triangle, t bits)` and the shadow factor's bits for a segment of
/// length 7, by one structure.
fn answers<V: Dim>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    ray: &Ray<V>,
) -> (Option<(usize, Option<usize>, u64)>, u64) {
    let mut stats = Stats::default();
    let hit = accel
        .nearest(scene, ray, &mut stats, &mut NoRecorder)
        .map(|(o, h)| (o.index, o.triangle, h.t.to_bits()));
    let mut s = 1.0f64;
    accel.occluders(scene, ray, 7.0, &mut stats, &mut NoRecorder, |o| {
        let kt = scene.material_of(o.index).kt;
        s *= kt;
        kt > 0.0
    });
    (hit, s.to_bits())
}

/// Asserts that every structure answers every ray as brute force does, and renders its image.
fn assert_agree<V: Dim>(scene: &Scene<V>, rays: &[Ray<V>]) {
    let oracle = Accel::build(scene, AccelKind::None);
    let expected: Vec<_> = rays.iter().map(|r| answers(scene, &oracle, r)).collect();
    let image = render_centers(scene, &oracle, scene.max_depth, None).image;
    for options in options_for::<V>() {
        let accel = Accel::build_with(scene, &options);
        for (ray, want) in rays.iter().zip(&expected) {
            let got = answers(scene, &accel, ray);
            assert_eq!(&got, want, "{options:?} on {ray:?}");
        }
        let other = render_centers(scene, &accel, scene.max_depth, None).image;
        assert!(other.pixels == image.pixels, "{options:?}: the image differs");
    }
    // The render's wide BVH, walked when no recorder listens: collapsed from the binary tree,
    // and built straight into wide nodes (for large scenes; the collapse for the others).
    let collapsed = Accel::build(scene, AccelKind::Bvh).for_render();
    let direct = Accel::build_for_render(scene, &AccelOptions::of(AccelKind::Bvh));
    assert_eq!(direct.wide_nodes(), collapsed.wide_nodes(), "the same wide tree");
    for (ray, want) in rays.iter().zip(&expected) {
        // A recorder walking the direct build (no binary nodes) takes the wide walk.
        let found = direct.nearest(scene, ray, &mut Stats::default(), &mut EventLog::new());
        let found = found.map(|(o, h)| (o.index, o.triangle, h.t.to_bits()));
        assert_eq!(found, want.0, "the direct wide BVH with a recorder on {ray:?}");
    }
    for wide in [collapsed, direct] {
        for (ray, want) in rays.iter().zip(&expected) {
            assert_eq!(&answers(scene, &wide, ray), want, "the wide BVH on {ray:?}");
        }
        let other = render_centers(scene, &wide, scene.max_depth, None).image;
        assert!(other.pixels == image.pixels, "the wide BVH: the image differs");
    }
}

// ---------------------------------------------------------------------------------------------
// Random scenes

/// A number: an integer, a half, or a float with many digits.
fn coord(exact: bool) -> BoxedStrategy<f64> {
    if exact {
        (-6i32..=6).prop_map(|k| f64::from(k) * 0.5).boxed()
    } else {
        (-3.0f64..3.0).boxed()
    }
}

fn point(exact: bool, dim: usize) -> BoxedStrategy<Vec<f64>> {
    proptest::collection::vec(coord(exact), dim).boxed()
}

/// An object's JSON, of a type the dimension has.
fn object(exact: bool, dim: usize) -> BoxedStrategy<Value> {
    let material = prop_oneof![
        Just(None),
        Just(Some(json!({"kt": 0.5}))),
        Just(Some(json!({"ks": 0.5}))),
        Just(Some(json!({"kt": 0.25, "ior": 1.5}))),
    ];
    let radius =
        if exact { (1i32..=3).prop_map(|r| f64::from(r) * 0.5).boxed() } else { (0.2f64..1.5).boxed() };
    let size =
        if exact { (1i32..=4).prop_map(|r| f64::from(r) * 0.5).boxed() } else { (0.1f64..2.0).boxed() };
    let sphere =
        (point(exact, dim), radius).prop_map(|(c, r)| json!({"type": "sphere", "center": c, "radius": r}));
    let boxed = (point(exact, dim), proptest::collection::vec(size, dim)).prop_map(|(lo, e)| {
        let hi: Vec<f64> = lo.iter().zip(&e).map(|(a, b)| a + b).collect();
        json!({"type": "box", "min": lo, "max": hi})
    });
    let triangle = proptest::collection::vec(point(exact, dim), 3)
        .prop_filter("non-degenerate", move |vs| area(vs) > 1e-6)
        .prop_map(|vs| json!({"type": "triangle", "vertices": vs}));
    let shape = if dim == 2 {
        let segment = (point(exact, 2), point(exact, 2))
            .prop_filter("non-zero", |(a, b)| a != b)
            .prop_map(|(a, b)| json!({"type": "segment", "a": a, "b": b}));
        prop_oneof![sphere, boxed, triangle, segment].boxed()
    } else {
        prop_oneof![sphere, boxed, triangle].boxed()
    };
    (shape, material)
        .prop_map(|(mut s, m)| {
            if let Some(m) = m {
                s["material"] = m;
            }
            s
        })
        .boxed()
}

fn area(vs: &[Vec<f64>]) -> f64 {
    let d = |a: &Vec<f64>, b: &Vec<f64>| -> Vec<f64> { a.iter().zip(b).map(|(x, y)| x - y).collect() };
    let (u, v) = (d(&vs[1], &vs[0]), d(&vs[2], &vs[0]));
    if vs[0].len() == 2 {
        (u[0] * v[1] - u[1] * v[0]).abs()
    } else {
        let c = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        c.iter().map(|x| x * x).sum::<f64>().sqrt()
    }
}

/// The random scenes' frame: a camera off the axis looking at the origin, depth 2, one light,
/// the objects and, with `plane`, a reflecting floor at y = −4.
fn scene_text(objects: &[Value], dim: usize, plane: bool) -> String {
    let (camera, light, point, normal) = if dim == 2 {
        let camera = SceneText::flat2(24).eye(json!([0.3, 9])).window(json!({"l": -0.6, "r": 0.6}));
        (camera, json!([4, 7]), json!([0, -4]), json!([0, 1]))
    } else {
        let camera = SceneText::space3(10, 8)
            .eye(json!([1.5, 2, 9]))
            .window(json!({"l": -0.5, "r": 0.5, "b": -0.4, "t": 0.4}));
        (camera, json!([4, 7, 5]), json!([0, -4, 0]), json!([0, 1, 0]))
    };
    let floor = json!({"type": "plane", "point": point, "normal": normal, "material": {"ks": 0.3}});
    let scene = camera.set("/max_depth", json!(2)).light(json!({"position": light}));
    scene.objects(objects.iter().cloned()).objects(plane.then_some(floor)).text()
}

/// A ray direction: an axis (with ±0 elsewhere), a diagonal, or a general unit vector.
fn direction(dim: usize) -> BoxedStrategy<Vec<f64>> {
    let axis = (0..dim, any::<bool>(), proptest::collection::vec(any::<bool>(), dim)).prop_map(
        move |(a, neg, zeros)| {
            (0..dim)
                .map(|i| {
                    if i == a {
                        if neg {
                            -1.0
                        } else {
                            1.0
                        }
                    } else if zeros[i] {
                        -0.0
                    } else {
                        0.0
                    }
                })
                .collect::<Vec<f64>>()
        },
    );
    let diagonal = proptest::collection::vec(prop_oneof![Just(-1.0), Just(0.0), Just(1.0)], dim)
        .prop_filter("non-zero", |v| v.iter().any(|x| *x != 0.0));
    let general = proptest::collection::vec(-1.0f64..1.0, dim)
        .prop_filter("non-zero", |v| v.iter().any(|x| x.abs() > 1e-3));
    prop_oneof![axis, diagonal, general].boxed()
}

fn rays<V: Dim>(exact: bool) -> BoxedStrategy<Vec<Ray<V>>> {
    let dim = V::DIM;
    proptest::collection::vec((point(exact, dim), direction(dim)), 12)
        .prop_map(move |pairs| {
            pairs
                .into_iter()
                .filter_map(|(o, d)| {
                    let mut o = V::from_slice(&o)?;
                    // Start outside the scene's middle, on a lattice plane when exact.
                    o[dim - 1] += 5.0;
                    Some(Ray::new(o, V::from_slice(&d)?.try_unit()?))
                })
                .collect()
        })
        .boxed()
}

fn load<V: Dim>(text: &str) -> Scene<V> {
    match whitted::scene::load::load_str(text) {
        Ok(AnyScene::Flat(s)) if V::DIM == 2 => {
            *(Box::new(s) as Box<dyn std::any::Any>).downcast::<Scene<V>>().unwrap()
        }
        Ok(AnyScene::Space(s)) if V::DIM == 3 => {
            *(Box::new(s) as Box<dyn std::any::Any>).downcast::<Scene<V>>().unwrap()
        }
        other => panic!("{text}: {other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn i9_every_structure_equals_brute_force_in_3d(
        exact in any::<bool>(),
        objects in proptest::collection::vec(object(false, 3), 1..14),
        exact_objects in proptest::collection::vec(object(true, 3), 1..14),
        plane in any::<bool>(),
        float_rays in rays::<DVec3>(false),
        exact_rays in rays::<DVec3>(true),
    ) {
        let objects = if exact { exact_objects } else { objects };
        let scene: Scene<DVec3> = load(&scene_text(&objects, 3, plane));
        let mut all = float_rays;
        all.extend(exact_rays);
        assert_agree(&scene, &all);
    }

    #[test]
    fn i9_every_structure_equals_brute_force_in_2d(
        exact in any::<bool>(),
        objects in proptest::collection::vec(object(false, 2), 1..14),
        exact_objects in proptest::collection::vec(object(true, 2), 1..14),
        plane in any::<bool>(),
        float_rays in rays::<DVec2>(false),
        exact_rays in rays::<DVec2>(true),
    ) {
        let objects = if exact { exact_objects } else { objects };
        let scene: Scene<DVec2> = load(&scene_text(&objects, 2, plane));
        let mut all = float_rays;
        all.extend(exact_rays);
        assert_agree(&scene, &all);
    }
}

/// A crowd of `n` small objects (triangles, spheres, boxes; some glass) in `[-3, 3]³`, from
/// `seeds`: enough primitives for a wide BVH of several levels.
fn crowd(seeds: &[(u8, [f64; 3], f64, bool)]) -> Vec<Value> {
    seeds
        .iter()
        .map(|&(kind, [x, y, z], size, glass)| {
            let mut o = match kind % 3 {
                0 => json!({"type": "triangle", "vertices": [[x, y, z], [x + size, y, z - size], [x, y + size, z + size]]}),
                1 => json!({"type": "sphere", "center": [x, y, z], "radius": size}),
                _ => json!({"type": "box", "min": [x, y, z], "max": [x + size, y + size, z + size]}),
            };
            if glass {
                o["material"] = json!({"kt": 0.5});
            }
            o
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, failure_persistence: None, ..ProptestConfig::default() })]

    /// The render's wide BVH (4 children, boxes in f32 rounded outward) gives brute force's
    /// nearest hit bit for bit (object, triangle, t) and the same occluders, on crowds large
    /// enough for many wide nodes, and the same image.
    #[test]
    fn the_wide_bvh_equals_brute_force_bit_for_bit(
        seeds in proptest::collection::vec(
            (any::<u8>(), [-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0], 0.05f64..0.6, any::<bool>()),
            40..200,
        ),
        float_rays in rays::<DVec3>(false),
        exact_rays in rays::<DVec3>(true),
    ) {
        let scene: Scene<DVec3> = load(&scene_text(&crowd(&seeds), 3, true));
        let wide = Accel::build(&scene, AccelKind::Bvh).for_render();
        prop_assert!(wide.wide_nodes().is_some_and(|n| n > 1), "a wide tree of several nodes");
        let mut all = float_rays;
        all.extend(exact_rays);
        // Rays from inside the crowd too, as secondary and shadow rays start.
        all.extend(seeds.iter().take(12).map(|(_, c, _, _)| {
            Ray::new(DVec3::from(*c) * 0.5, DVec3::new(c[1], -c[2], c[0] + 0.1).normalize())
        }));
        assert_agree(&scene, &all);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3, failure_persistence: None, ..ProptestConfig::default() })]

    /// Scenes of more than `binned::LARGE` primitives take the BVH's compact build (boxes in f32
    /// rounded outward, every axis binned): brute force's answers bit for bit and the same image,
    /// in 3D (a crowd of small objects) and in 2D (exact coordinates: ties everywhere), for the
    /// binary tree and the render's wide one.
    #[test]
    fn the_binned_build_equals_brute_force_bit_for_bit(
        seeds in proptest::collection::vec(
            (any::<u8>(), [-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0], 0.05f64..0.6, any::<bool>()),
            LARGE + 1..LARGE + 40,
        ),
        flat in proptest::collection::vec(object(true, 2), LARGE + 1..LARGE + 40),
        rays3 in rays::<DVec3>(false),
        exact_rays3 in rays::<DVec3>(true),
        rays2 in rays::<DVec2>(true),
    ) {
        let space: Scene<DVec3> = load(&scene_text(&crowd(&seeds), 3, true));
        let mut all = rays3;
        all.extend(exact_rays3);
        all.extend(seeds.iter().take(12).map(|(_, c, _, _)| {
            Ray::new(DVec3::from(*c) * 0.5, DVec3::new(c[1], -c[2], c[0] + 0.1).normalize())
        }));
        assert_agree(&space, &all);
        let plane: Scene<DVec2> = load(&scene_text(&flat, 2, true));
        assert_agree(&plane, &rays2);
    }
}

// ---------------------------------------------------------------------------------------------
// Exact-arithmetic scenes, by hand

/// Unit cubes on an integer lattice, touching face to face, and rays along their edges, faces
/// and corners in every axis direction: every hit is an exact tie somewhere.
#[test]
fn exact_lattice_rays_through_edges_and_corners_agree_bit_for_bit() {
    let mut objects = Vec::new();
    for x in 0..3 {
        for y in 0..3 {
            for z in 0..2 {
                if (x + y + z) % 2 == 0 {
                    objects.push(json!({"type": "box", "min": [x, y, z], "max": [x + 1, y + 1, z + 1]}));
                }
            }
        }
    }
    objects.push(json!({"type": "sphere", "center": [1, 1, 1], "radius": 1}));
    objects.push(
        json!({"type": "triangle", "vertices": [[0, 0, 2], [3, 0, 2], [0, 3, 2]], "material": {"kt": 0.5}}),
    );
    let scene: Scene<DVec3> = load(&scene_text(&objects, 3, false));
    let mut rays = Vec::new();
    for a in 0..=6 {
        for b in 0..=6 {
            let (p, q) = (f64::from(a) * 0.5, f64::from(b) * 0.5);
            for (o, d) in [
                (DVec3::new(-2.0, p, q), DVec3::X),
                (DVec3::new(5.0, p, q), DVec3::new(-1.0, -0.0, 0.0)),
                (DVec3::new(p, -2.0, q), DVec3::Y),
                (DVec3::new(p, q, 6.0), DVec3::new(0.0, -0.0, -1.0)),
                (DVec3::new(p - 3.0, q - 3.0, 0.5), DVec3::new(1.0, 1.0, 0.0).normalize()),
            ] {
                rays.push(Ray::new(o, d));
            }
        }
    }
    assert_agree(&scene, &rays);
}

#[test]
fn flat_scene_rays_in_slab_planes_agree() {
    // Everything in the plane z = 0 (zero z-extent: numerics I8) and rays lying in it.
    let objects = vec![
        json!({"type": "triangle", "vertices": [[0, 0, 0], [2, 0, 0], [0, 2, 0]]}),
        json!({"type": "triangle", "vertices": [[2, 0, 0], [2, 2, 0], [0, 2, 0]], "material": {"kt": 0.5}}),
    ];
    let scene: Scene<DVec3> = load(&scene_text(&objects, 3, true));
    let mut rays = Vec::new();
    for k in 0..=8 {
        let p = f64::from(k) * 0.25;
        rays.push(Ray::new(DVec3::new(p, p, 3.0), DVec3::NEG_Z));
        rays.push(Ray::new(DVec3::new(-1.0, p, 0.0), DVec3::X));
        rays.push(Ray::new(DVec3::new(p, 2.0 - p, 1.0), DVec3::new(0.0, -0.0, -1.0)));
    }
    assert_agree(&scene, &rays);
}

// ---------------------------------------------------------------------------------------------
// Meshes

/// A height field of `n × n` cells, two triangles each, with exact (quarter) coordinates.
fn grid_obj(n: usize) -> String {
    let mut s = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let y = ((i * 7 + j * 3) % 5) as f64 * 0.25;
            s += &format!("v {} {} {}\n", i as f64 * 0.5 - 2.0, y, j as f64 * 0.5 - 2.0);
        }
    }
    let row = n + 1;
    for j in 0..n {
        for i in 0..n {
            let v = j * row + i + 1;
            s += &format!("f {} {} {}\nf {} {} {}\n", v, v + row, v + row + 1, v, v + row + 1, v + 1);
        }
    }
    s
}

/// The meshes' scenes: a camera above and in front of the origin, one light, and `objects`.
fn above_mesh(nx: usize, ny: usize, eye: Value, objects: impl IntoIterator<Item = Value>) -> SceneText {
    let window = json!({"l": -0.6, "r": 0.6, "b": -0.5, "t": 0.5});
    SceneText::space3(nx, ny).eye(eye).window(window).light(json!({"position": [-3, 5, 2]})).objects(objects)
}

fn mesh_scene(extra: Option<Value>) -> Scene<DVec3> {
    let obj = grid_obj(8);
    let terrain = json!({"type": "mesh", "name": "terrain", "obj": "t.obj", "material": {"kt": 0.5}});
    let text = above_mesh(12, 10, json!([0.1, 4, 5]), std::iter::once(terrain).chain(extra)).text();
    match load_str_with(&text, &|_| Ok(obj.clone())) {
        Ok(AnyScene::Space(s)) => s,
        other => panic!("{other:?}"),
    }
}

#[test]
fn meshes_agree_triangle_by_triangle_with_ties_to_the_smaller_triangle() {
    let scene = mesh_scene(Some(json!({"type": "sphere", "center": [0, 0.5, 0], "radius": 0.6})));
    let mut rays = Vec::new();
    // Straight down through every vertex and edge midpoint: shared edges, exact ties.
    for a in 0..=16 {
        for b in 0..=16 {
            let (x, z) = (f64::from(a) * 0.25 - 2.0, f64::from(b) * 0.25 - 2.0);
            rays.push(Ray::new(DVec3::new(x, 3.0, z), DVec3::new(0.0, -1.0, -0.0)));
            rays.push(Ray::new(DVec3::new(x - 3.0, 0.5, z), DVec3::X));
        }
    }
    assert_agree(&scene, &rays);
    // Through a shared vertex the brute force picks the smaller triangle index.
    let oracle = Accel::build(&scene, AccelKind::None);
    let down = Ray::new(DVec3::new(-1.0, 3.0, -1.0), DVec3::NEG_Y);
    let (o, _) = oracle.nearest(&scene, &down, &mut Stats::default(), &mut NoRecorder).unwrap();
    let mut all = Vec::new();
    for k in 0..128 {
        let r = whitted::accel::object_ref(&scene, Prim { object: 0, part: k });
        all.push(r);
    }
    assert_eq!(o.index, 0);
    assert!(o.triangle.is_some());
    assert!(all.iter().all(|r| r.triangle.is_some()));
}

#[test]
fn a_mesh_multiplies_the_shadow_factor_once() {
    let scene = mesh_scene(None);
    // A ray from below crosses the wavy surface several times: kt = 0.5 once, whatever crosses.
    let up = Ray::new(DVec3::new(0.3, -3.0, 0.2), DVec3::new(0.05, 1.0, 0.03).normalize());
    for options in every_structure() {
        let accel = Accel::build_with(&scene, &options);
        let mut found = Vec::new();
        accel.occluders(&scene, &up, 10.0, &mut Stats::default(), &mut NoRecorder, |o| {
            found.push(o.index);
            true
        });
        assert_eq!(found, vec![0], "{options:?}");
    }
}

#[test]
fn mesh_events_carry_the_triangle() {
    let scene = mesh_scene(None);
    let accel = Accel::build(&scene, AccelKind::Bvh);
    let mut tracer = Tracer::new(&scene, &accel, EventLog::new());
    let ray = Ray::new(DVec3::new(0.3, 3.0, 0.2), DVec3::NEG_Y);
    let color = tracer.trace_primary(&ray, &[]);
    let doc = trace_document(
        &scene,
        &tracer.recorder,
        &tracer.stats,
        &TraceTarget { pixel: None, uv: None },
        color,
    );
    assert_eq!(doc["tree"]["hit"]["object"], "terrain");
    assert!(doc["tree"]["hit"]["triangle"].is_u64());
    let tests: Vec<&Value> =
        doc["events"].as_array().unwrap().iter().filter(|e| e["kind"] == "object_test").collect();
    assert!(tests.iter().all(|e| e["triangle"].is_u64()));
    assert!(doc["events"].as_array().unwrap().iter().any(|e| e["kind"] == "node_visit"));
}

// ---------------------------------------------------------------------------------------------
// Cost

#[test]
fn the_bvh_does_under_a_quarter_of_brute_force_tests_on_300_spheres() {
    let mut objects = Vec::new();
    for i in 0..300 {
        let (x, y, z) = (f64::from(i % 10), f64::from(i / 10 % 10), f64::from(i / 100));
        let center = [x * 0.6 - 3.0, y * 0.6 - 3.0, z * 0.6 - 1.0];
        objects.push(json!({"type": "sphere", "center": center, "radius": 0.2}));
    }
    let scene: Scene<DVec3> = load(&scene_text(&objects, 3, true));
    let cost = |kind| {
        let accel = Accel::build(&scene, kind);
        let t = render_centers(&scene, &accel, scene.max_depth, None).stats.tests;
        t.object + t.bound + t.node + t.voxel
    };
    let (brute, bvh) = (cost(AccelKind::None), cost(AccelKind::Bvh));
    assert!(bvh * 4 < brute, "bvh {bvh} tests, brute force {brute}");
}

// ---------------------------------------------------------------------------------------------
// numerics.md §I, by name: the grid [0,4]³ of 4×4×4 unit cells

/// A visitor that tests nothing and never stops: the walk visits every cell the ray crosses.
struct Walk;

impl<V: Dim> Visitor<V> for Walk {
    fn bound(&self) -> f64 {
        f64::INFINITY
    }
    fn visit<R: Recorder<V>>(&mut self, _: Prim, _: &mut Stats, _: &mut R) -> bool {
        false
    }
}

fn cube_scene() -> Scene<DVec3> {
    scene3(&scene_text(&[json!({"type": "box", "min": [0, 0, 0], "max": [4, 4, 4]})], 3, false))
}

fn grid4() -> Grid<DVec3> {
    let b = Aabb::new(DVec3::ZERO, DVec3::splat(4.0));
    Grid::from_boxes(vec![Prim { object: 0, part: 0 }], &[b], b, &[4, 4, 4])
}

/// `(cell, t_enter, t_exit)` of every cell the walk visits.
fn cells(o: [f64; 3], d: [f64; 3]) -> Vec<([i64; 3], f64, f64)> {
    let scene = cube_scene();
    let ray = Ray::new(DVec3::from(o), DVec3::from(d));
    let mut log = EventLog::new();
    grid4().walk(&scene, &ray, &mut Walk, &mut Stats::default(), &mut log);
    let b = whitted::geom::slab::box_crossing(&ray, DVec3::ZERO, DVec3::splat(4.0), |_, _| {});
    let mut enter = b.t_in.max(0.0);
    log.events
        .iter()
        .filter_map(|e| match &e.event {
            Event::VoxelStep { cell, t_max, .. } => {
                let exit = t_max.iter().copied().fold(f64::INFINITY, f64::min).min(b.t_out);
                let out = ([cell[0], cell[1], cell[2]], enter, exit);
                enter = exit;
                Some(out)
            }
            _ => None,
        })
        .collect()
}

fn assert_cells(got: &[([i64; 3], f64, f64)], want: &[([i64; 3], f64, f64)]) {
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert_eq!(g.0, w.0, "{got:?}");
        assert!((g.1 - w.1).abs() < 1e-12 && (g.2 - w.2).abs() < 1e-12, "{g:?} vs {w:?}");
    }
}

#[test]
fn i1_axis_parallel_ray_never_steps_y_or_z() {
    let want = [([0, 2, 0], 0.0, 0.5), ([1, 2, 0], 0.5, 1.5), ([2, 2, 0], 1.5, 2.5), ([3, 2, 0], 2.5, 3.5)];
    assert_cells(&cells([0.5, 2.5, 0.5], [1.0, 0.0, 0.0]), &want);
}

#[test]
fn i2_negative_zero_on_a_cell_boundary_walks_like_plus_zero() {
    let want = [([0, 2, 0], 0.0, 0.5), ([1, 2, 0], 0.5, 1.5), ([2, 2, 0], 1.5, 2.5), ([3, 2, 0], 2.5, 3.5)];
    assert_cells(&cells([0.5, 2.0, 0.5], [1.0, -0.0, 0.0]), &want);
    assert_cells(&cells([0.5, 2.0, 0.5], [1.0, 0.0, -0.0]), &want);
}

#[test]
fn i3_ties_through_a_grid_vertex_step_x_then_y() {
    // algorithm.md §11: ties step in the order x, y, z (pbrt would step y first).
    let (a, b, c) = (std::f64::consts::FRAC_1_SQRT_2, 2.121_320_343_559_643, 3.535_533_905_932_738);
    let want = [
        ([0, 0, 0], 0.0, a),
        ([1, 0, 0], a, a),
        ([1, 1, 0], a, b),
        ([2, 1, 0], b, b),
        ([2, 2, 0], b, c),
        ([3, 2, 0], c, c),
        ([3, 3, 0], c, 4.949_747_468_305_833),
    ];
    let d = std::f64::consts::FRAC_1_SQRT_2;
    assert_cells(&cells([0.5, 0.5, 0.5], [d, d, 0.0]), &want);
    // An object through the vertex (1, 1, ·) is still found.
    let scene = scene3(&scene_text(
        &[
            json!({"type": "box", "min": [0, 0, 0], "max": [4, 4, 4], "material": {"kt": 0.5}}),
            json!({"type": "sphere", "center": [1, 1, 0.5], "radius": 0.01}),
        ],
        3,
        false,
    ));
    let ray = Ray::new(DVec3::splat(0.5), DVec3::new(d, d, 0.0));
    let want =
        Accel::build(&scene, AccelKind::None).nearest(&scene, &ray, &mut Stats::default(), &mut NoRecorder);
    let grid = Accel::build_with(
        &scene,
        &AccelOptions { kind: AccelKind::Grid, volume: VolumeKind::Aabb, grid: Some(vec![4, 4, 4]) },
    );
    let got = grid.nearest(&scene, &ray, &mut Stats::default(), &mut NoRecorder);
    assert_eq!(got.map(|(o, h)| (o, h.t.to_bits())), want.map(|(o, h)| (o, h.t.to_bits())));
}

#[test]
fn i4_start_outside_or_on_the_far_face_is_clipped_and_clamped() {
    let want =
        [([0, 0, 0], 10.0, 11.0), ([1, 0, 0], 11.0, 12.0), ([2, 0, 0], 12.0, 13.0), ([3, 0, 0], 13.0, 14.0)];
    assert_cells(&cells([-10.0, 0.5, 0.5], [1.0, 0.0, 0.0]), &want);
    assert_cells(&cells([4.0, 0.5, 0.5], [1.0, 0.0, 0.0]), &[([3, 0, 0], 0.0, 0.0)]);
    let back = [([3, 0, 0], 0.0, 1.0), ([2, 0, 0], 1.0, 2.0), ([1, 0, 0], 2.0, 3.0), ([0, 0, 0], 3.0, 4.0)];
    assert_cells(&cells([4.0, 0.5, 0.5], [-1.0, 0.0, 0.0]), &back);
}

#[test]
fn i5_a_generic_segment_crosses_exactly_ten_cells() {
    let (o, e) = (DVec3::new(0.1, 0.2, 0.3), DVec3::new(3.7, 3.9, 3.3));
    let d = (e - o).normalize();
    let got = cells(o.to_array(), d.to_array());
    let want_cells = [
        [0, 0, 0],
        [0, 1, 0],
        [0, 1, 1],
        [1, 1, 1],
        [1, 2, 1],
        [2, 2, 1],
        [2, 2, 2],
        [2, 3, 2],
        [3, 3, 2],
        [3, 3, 3],
    ];
    let crossings =
        [1.290_976, 1.393_178, 1.492_691, 2.904_695, 3.151_236, 3.383_432, 4.518_415, 4.809_781, 5.373_686];
    assert_eq!(got.iter().map(|c| c.0).collect::<Vec<_>>(), want_cells);
    for (c, t) in got.iter().zip(crossings) {
        assert!((c.2 - t).abs() < 1e-6, "{c:?} vs {t}");
    }
    for w in got.windows(2) {
        let steps: i64 = (0..3).map(|a| (w[1].0[a] - w[0].0[a]).abs()).sum();
        assert_eq!(steps, 1, "consecutive cells differ by ±1 in one axis");
    }
}

#[test]
fn i6_the_lecture_pitfall_a_hit_beyond_the_current_cell_is_not_accepted() {
    let scene = scene3(&fixture("grid_pitfall.json"));
    let ray = Ray::new(DVec3::splat(0.5), DVec3::X);
    let boxes: Vec<Aabb<DVec3>> =
        (0..2).map(|k| whitted::accel::prim_bounds(&scene, Prim { object: k, part: 0 })).collect();
    let prims = vec![Prim { object: 0, part: 0 }, Prim { object: 1, part: 0 }];
    let grid = Grid::from_boxes(prims, &boxes, Aabb::new(DVec3::ZERO, DVec3::splat(4.0)), &[4, 4, 4]);
    let mut log = EventLog::new();
    let mut stats = Stats::default();
    let mut near = Nearest::new(&scene, &ray);
    grid.walk(&scene, &ray, &mut near, &mut stats, &mut log);
    let (object, hit) = near.found().unwrap();
    // Sphere A (object 0) is tested in the first cell and hit at 1.4975, beyond that cell;
    // sphere B (object 1), in the next cell, is the nearest, at 0.7.
    assert_eq!(object.index, 1);
    assert!((hit.t - 0.7).abs() < 1e-12);
    assert_eq!(stats.tests.object, 2, "A is tested once: the mailbox");
    let steps: Vec<&Event<DVec3>> =
        log.events.iter().map(|e| &e.event).filter(|e| matches!(e, Event::VoxelStep { .. })).collect();
    assert!(
        matches!(steps[0], Event::VoxelStep { objects, .. } if objects.len() == 1 && objects[0].index == 0)
    );
    assert_eq!(steps.len(), 2, "the walk stops in the cell that holds the hit");
    // Every structure agrees, and the fixture's centre pixel is that ray.
    assert_agree(&scene, &[ray]);
    let doc = trace_pixel(&scene, 0, 0);
    assert_eq!(doc["tree"]["hit"]["object"], "B");
}

#[test]
fn i7_a_hit_exactly_on_a_cell_boundary_is_kept_with_the_mailbox() {
    let scene = scene3(&scene_text(&[json!({"type": "box", "min": [1, 0, 0], "max": [2, 1, 1]})], 3, false));
    let b = Aabb::new(DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 1.0, 1.0));
    let grid = Grid::from_boxes(
        vec![Prim { object: 0, part: 0 }],
        &[b],
        Aabb::new(DVec3::ZERO, DVec3::splat(4.0)),
        &[4, 4, 4],
    );
    let ray = Ray::new(DVec3::splat(0.5), DVec3::X);
    let mut near = Nearest::new(&scene, &ray);
    let mut log = EventLog::new();
    grid.walk(&scene, &ray, &mut near, &mut Stats::default(), &mut log);
    let (_, hit) = near.found().unwrap();
    assert!((hit.t - 0.5).abs() < 1e-15);
    assert_eq!(hit.normal, DVec3::NEG_X);
    let first = log.events.iter().find_map(|e| match &e.event {
        Event::VoxelStep { objects, .. } => Some(objects.len()),
        _ => None,
    });
    assert_eq!(first, Some(1), "the box touching x = 1 is listed in cell 0 too (closed overlap)");
}

#[test]
fn i8_degenerate_bounds_render_without_panic() {
    for objects in [
        vec![],
        vec![json!({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]})],
        vec![
            json!({"type": "sphere", "center": [0, 0, 0], "radius": 1}),
            json!({"type": "sphere", "center": [0, 0, 0], "radius": 1}),
        ],
    ] {
        for plane in [false, true] {
            let scene: Scene<DVec3> = load(&scene_text(&objects, 3, plane));
            let rays: Vec<Ray<DVec3>> =
                (0..5).map(|k| Ray::new(DVec3::new(0.25 * f64::from(k), 0.25, 5.0), DVec3::NEG_Z)).collect();
            assert_agree(&scene, &rays);
        }
    }
}

#[test]
fn i9_a_nan_ray_ends_every_walk() {
    let scene: Scene<DVec3> =
        load(&scene_text(&[json!({"type": "sphere", "center": [0, 0, 0], "radius": 1})], 3, false));
    let nan = Ray::new(DVec3::new(f64::NAN, 0.0, 5.0), DVec3::new(0.0, f64::NAN, -1.0));
    for options in every_structure() {
        let accel = Accel::build_with(&scene, &options);
        let mut stats = Stats::default();
        assert!(accel.nearest(&scene, &nan, &mut stats, &mut NoRecorder).is_none(), "{options:?}");
        assert!(stats.tests.voxel <= 3 * 256 + 3);
    }
}

#[test]
fn traces_are_the_same_tree_whatever_the_structure() {
    let scene = scene3(&fixture("glass.json"));
    let oracle = Accel::build(&scene, AccelKind::None);
    for options in every_structure() {
        let accel = Accel::build_with(&scene, &options);
        for (i, j) in [(0, 0), (3, 2), (4, 3)] {
            let ray = {
                let (u, v) = scene.camera.pixel_center(i, j);
                scene.camera.primary_ray(u, v)
            };
            let tree = |a: &Accel<DVec3>| {
                let mut t = Tracer::new(&scene, a, EventLog::new());
                let c = t.trace_primary(&ray, &[]);
                trace_document(&scene, &t.recorder, &t.stats, &TraceTarget { pixel: None, uv: None }, c)
                    ["tree"]
                    .clone()
            };
            assert_eq!(tree(&accel), tree(&oracle), "{options:?} at ({i}, {j})");
        }
    }
    let _ = scene2;
}

/// A walk without a recorder may take shortcuts (the BVH counts the root test of a ray that
/// starts inside its box without computing the interval), never a different answer or count:
/// every pixel of a 3D and a 2D fixture, every structure, traced with and without the log.
#[test]
fn recording_changes_neither_colours_nor_counts() {
    fn check<V: Dim>(scene: &Scene<V>) {
        for options in options_for::<V>() {
            let accel = Accel::build_with(scene, &options);
            for j in 0..scene.camera.ny {
                for i in 0..scene.camera.nx {
                    let (u, v) = scene.camera.pixel_center(i, j);
                    let ray = scene.camera.primary_ray(u, v);
                    let mut plain = Tracer::new(scene, &accel, NoRecorder);
                    let mut logged = Tracer::new(scene, &accel, EventLog::new());
                    let (a, b) = (plain.trace_primary(&ray, &[]), logged.trace_primary(&ray, &[]));
                    let bits = |c: whitted::scene::material::Rgb| c.0.map(f64::to_bits);
                    assert_eq!(bits(a), bits(b), "{options:?} at ({i}, {j})");
                    assert_eq!(plain.stats, logged.stats, "{options:?} at ({i}, {j})");
                }
            }
        }
    }
    check(&scene3(&fixture("glass.json")));
    check(&scene2(&fixture("groups_2d.json")));
}

// ---------------------------------------------------------------------------------------------
// The command line

#[test]
fn accel_options_on_the_command_line() {
    let scene = format!("{}/tests/data/scenes/grid_pitfall.json", env!("CARGO_MANIFEST_DIR"));
    let (code, out, err) =
        whitted(&["trace", &scene, "--pixel", "0,0", "--accel", "grid", "--grid", "4,4,4", "--json"]);
    assert_eq!(code, 0, "{err}");
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["tree"]["hit"]["object"], "B");
    assert!(doc["stats"]["tests"]["voxel"].as_u64().unwrap() >= 2);
    let (code, _, err) = whitted(&["trace", &scene, "--pixel", "0,0", "--accel", "grid", "--grid", "4,4"]);
    assert_eq!(code, 2);
    assert!(err.contains("--grid: a 3D scene needs 3 cell counts, got 2"), "{err}");
    for (accel, field) in [("bounds", "bound"), ("bvh", "node"), ("octree", "node"), ("none", "object")] {
        let (code, out, err) =
            whitted(&["render", &scene, "-o", "/dev/null", "--accel", accel, "--bounds", "kdop", "--json"]);
        assert_eq!(code, 0, "{err}");
        let stats: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(stats["accel"], accel);
        assert!(stats["tests"][field].as_u64().unwrap() > 0, "{accel}: {stats}");
        assert!(stats["build_seconds"].is_f64() && stats["load_seconds"].is_f64());
    }
}

#[test]
fn a_mesh_scene_loads_its_obj_relative_to_the_scene_file() {
    let dir = Scratch::new();
    std::fs::create_dir(dir.join("sub")).unwrap();
    dir.write("sub/t.obj", grid_obj(4));
    let mesh = json!({"type": "mesh", "obj": "sub/t.obj", "name": "m"});
    let path = dir.write("m.json", above_mesh(8, 6, json!([0, 4, 5]), [mesh]).text());
    let (code, out, err) = whitted(&["check", &path]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("mesh m: 32 triangles, 0 degenerate skipped"), "{out}");
    std::fs::write(dir.join("sub/t.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 3\n").unwrap();
    let (code, _, err) = whitted(&["render", &path, "-o", "/dev/null"]);
    assert_eq!(code, 2);
    assert!(err.contains("objects[0].obj: sub/t.obj line 3:"), "{err}");
}
