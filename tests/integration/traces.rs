//! The recursion's conventions, checked on traces (algorithm.md §3–§6, §11; numerics.md E, F, L).

use crate::support::{
    assert_finite, events, f, fixture, fixture_with, scene2, scene3, trace_pixel, trace_ray, SceneText,
};
use glam::{DVec2, DVec3};
use serde_json::{json, Value};
use whitted::accel::{Accel, AccelKind};
use whitted::geom::ray::Ray;
use whitted::record::NoRecorder;
use whitted::render::render_centers;
use whitted::trace::Tracer;

#[test]
fn l2_mirror_corridor_sums_the_geometric_series() {
    for (k, expected) in [(0u32, 0.1), (1, 0.15), (2, 0.175), (10, 0.199_902_343_75)] {
        let scene = scene3(&fixture_with("corridor.json", &[("/max_depth", json!(k))]));
        let doc = trace_pixel(&scene, 0, 0);
        let c = f(&doc["color"][0]);
        assert!((c - expected).abs() < 1e-15, "k = {k}: {c}");
        assert_eq!(doc["stats"]["rays"]["reflected"], k, "one reflected ray per bounce");
        // The last node may not spawn: one depth_limit event.
        assert_eq!(events(&doc, "depth_limit").len(), 1);
        assert_eq!(events(&doc, "depth_limit")[0]["level"], k + 1);
    }
}

#[test]
fn l1_max_depth_zero_is_ray_casting() {
    let scene = scene3(&fixture_with("glass.json", &[("/max_depth", json!(0))]));
    let accel = Accel::build(&scene, AccelKind::None);
    let r = render_centers(&scene, &accel, 0, None);
    assert_eq!(r.stats.rays.reflected + r.stats.rays.transmitted, 0);
    assert_eq!(r.stats.rays.primary, 48);
}

#[test]
fn levels_count_from_one_and_children_come_r_then_t() {
    let scene = scene3(&fixture("glass.json"));
    // A ray straight at the glass sphere's centre.
    let eye = DVec3::new(0.45, 0.2, 5.0);
    let doc = trace_ray(&scene, &Ray::new(eye, DVec3::NEG_Z));
    let tree = &doc["tree"];
    assert_eq!(tree["level"], 1);
    assert_eq!(tree["kind"], "primary");
    assert_eq!(tree["hit"]["object"], "glass");
    assert_eq!(tree["hit"]["entering"], true);
    let kids = tree["children"].as_array().unwrap();
    assert_eq!(kids.len(), 2);
    assert_eq!(kids[0]["kind"], "reflected");
    assert_eq!(kids[1]["kind"], "transmitted");
    assert_eq!(kids[1]["level"], 2);
    // E2 / F3: normal incidence passes straight; the T ray starts inside and leaves at the far side.
    assert_eq!(kids[1]["direction"], serde_json::json!([0.0, 0.0, -1.0]));
    let inside = &kids[1];
    assert_eq!(inside["hit"]["entering"], false);
    assert!((f(&inside["hit"]["t"]) - 1.5).abs() < 1e-12);
    let refract = events(&doc, "refract");
    assert_eq!((f(&refract[0]["n1"]), f(&refract[0]["n2"])), (1.0, 1.5));
    assert_eq!((f(&refract[1]["n1"]), f(&refract[1]["n2"])), (1.5, 1.0));
    assert_finite(&doc);
}

#[test]
fn e3_tir_inside_a_2d_slab_keeps_its_side() {
    let scene = scene2(&fixture("tir_slab_2d.json"));
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    let doc = trace_ray(&scene, &Ray::new(DVec2::ZERO, DVec2::new(c, s)));
    let hits = events(&doc, "hit");
    assert!(hits.len() >= 10);
    for (k, h) in hits.iter().enumerate() {
        let x = f(&h["point"][0]);
        let expected = 0.173_205_080_756_887_7 + 0.346_410_161_513_775_5 * k as f64;
        // Each bounce starts δ = 2^-44·M inside the wall (§11), shifting the next hit by ~δ·√3.
        let tolerance = 2e-12 * (k + 1) as f64;
        assert!((x - expected).abs() < tolerance, "bounce {k}: x = {x}, expected {expected}");
        let y = f(&h["point"][1]);
        assert_eq!(y.abs(), 0.1);
        assert_eq!(h["entering"], false, "every hit is from inside");
    }
    assert_eq!(
        events(&doc, "total_internal_reflection").len(),
        hits.len() - 1,
        "every wall but the last, cut by the depth"
    );
    assert!(events(&doc, "refract").is_empty());
}

#[test]
fn e4_shadow_segments_end_at_the_light() {
    let with = |occluders: &[Value]| {
        let base = SceneText::space3(1, 1)
            .set("/camera/eye", json!([0, 1, 5]))
            .light(json!({"position": [0, 2, 0]}))
            .object(json!({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]}));
        occluders.iter().fold(base, |s, o| s.object(o.clone())).space()
    };
    let down = Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::NEG_Y);
    let s_of = |occluders: &[Value]| {
        let doc = trace_ray(&with(occluders), &down);
        f(&doc["tree"]["lights"][0]["shadow"])
    };
    // (a) planes through the light and beyond it do not shadow.
    assert_eq!(
        s_of(&[
            json!({"type": "plane", "point": [0, 2, 0], "normal": [0, -1, 0]}),
            json!({"type": "plane", "point": [0, 3, 0], "normal": [0, 1, 0]})
        ]),
        1.0
    );
    assert_eq!(s_of(&[json!({"type": "plane", "point": [0, 1.999_999, 0], "normal": [0, 1, 0]})]), 0.0);
    // (b) a thin box 0.0007 above the point shadows it: the offset is ~1e-13, not 1e-3.
    let scene = with(&[json!({"type": "box", "min": [-0.01, 0.0007, -0.003], "max": [0.01, 0.0008, 0.003]})]);
    let doc =
        trace_ray(&scene, &Ray::new(DVec3::new(0.0, 1.0, 5.0), DVec3::new(0.0, -1.0, -5.0).normalize()));
    assert_eq!(doc["tree"]["hit"]["object"], 0);
    assert_eq!(f(&doc["tree"]["lights"][0]["shadow"]), 0.0);
    assert!(f(&events(&doc, "shadow_ray")[0]["distance"]) < 2.0);
}

#[test]
fn transparent_occluders_multiply_kt_once_each() {
    let scene = SceneText::space3(1, 1)
        .set("/camera/eye", json!([0, 1, 5]))
        .set("/max_depth", json!(0))
        .light(json!({"position": [0, 10, 0]}))
        .object(json!({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]}))
        .object(json!({"type": "sphere", "center": [0, 3, 0], "radius": 1, "material": {"kt": 0.5}}))
        .object(json!({"type": "box", "min": [-1, 5, -1], "max": [1, 6, 1], "material": {"kt": 0.8}}));
    let doc = trace_ray(&scene.space(), &Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::NEG_Y));
    let shadow = events(&doc, "shadow_ray")[0];
    assert_eq!(shadow["occluders"].as_array().unwrap().len(), 2);
    assert!((f(&shadow["s"]) - 0.4).abs() < 1e-15);
    assert!((f(&doc["tree"]["lights"][0]["shadow"]) - 0.4).abs() < 1e-15);
}

#[test]
fn equal_t_goes_to_the_smaller_index() {
    // Three objects whose nearest hits share t = 4 (the box's face, the plane, the sphere's pole).
    let objects = [
        json!({"type": "box", "name": "box", "min": [-1, -1, -1], "max": [1, 1, 1]}),
        json!({"type": "plane", "name": "plane", "point": [0, 0, 1], "normal": [0, 0, 1]}),
        json!({"type": "sphere", "name": "sphere", "center": [0, 0, 0], "radius": 1}),
    ];
    let first_hit = |order: [usize; 3]| {
        let scene = order.iter().fold(SceneText::space3(1, 1), |s, &k| s.object(objects[k].clone()));
        let doc = trace_pixel(&scene.space(), 0, 0);
        assert_eq!(doc["tree"]["hit"]["t"], 4.0);
        doc["tree"]["hit"]["object"].clone()
    };
    assert_eq!(first_hit([0, 1, 2]), "box");
    // Listing the sphere first makes it win the same t.
    assert_eq!(first_hit([2, 1, 0]), "sphere");
}

#[test]
fn a_scene_with_nothing_transparent_spawns_no_t_ray() {
    let scene = scene3(&fixture_with("glass.json", &[("/materials/glass/kt", json!(0))]));
    assert!(!scene.has_transparent());
    let accel = Accel::build(&scene, AccelKind::None);
    let r = render_centers(&scene, &accel, scene.max_depth, None);
    assert_eq!(r.stats.rays.transmitted, 0);
    assert!(r.stats.rays.reflected > 0);
}

#[test]
fn g5_one_pixel_image_looks_down_minus_w() {
    let scene =
        SceneText::space3(1, 1).set("/camera/window", json!({"l": -0.8, "r": 0.8, "b": -0.6, "t": 0.6}));
    let doc = trace_pixel(&scene.space(), 0, 0);
    assert_eq!(doc["uv"], serde_json::json!([0.0, 0.0]));
    assert_eq!(doc["tree"]["direction"], serde_json::json!([0.0, 0.0, -1.0]));
    assert_eq!(events(&doc, "miss").len(), 1);
}

#[test]
fn rows_count_from_the_bottom() {
    let scene = SceneText::space3(2, 2).space();
    assert_eq!(scene.camera.pixel_center(0, 0), (-0.5, -0.5));
    assert_eq!(scene.camera.pixel_center(1, 1), (0.5, 0.5));
    let ray = scene.camera.primary_ray(-0.5, -0.5);
    assert!(ray.dir.y < 0.0 && ray.dir.x < 0.0, "row 0 looks down-left");
}

#[test]
fn two_d_frame_and_strip() {
    let scene = scene2(&fixture("lens_2d.json"));
    assert_eq!(scene.camera.frame.u, DVec2::new(1.0, 0.0));
    let accel = Accel::build(&scene, AccelKind::None);
    let r = render_centers(&scene, &accel, scene.max_depth, None);
    assert_eq!((r.image.width, r.image.height), (8, 1));
    let r = render_centers(&scene, &accel, scene.max_depth, Some(3));
    assert_eq!(r.image.height, 3);
    assert_eq!(r.image.get(5, 0), r.image.get(5, 2));
}

#[test]
fn recording_does_not_change_the_colour() {
    let scene = scene3(&fixture("glass.json"));
    let accel = Accel::build(&scene, AccelKind::None);
    for j in 0..scene.camera.ny {
        for i in 0..scene.camera.nx {
            let (u, v) = scene.camera.pixel_center(i, j);
            let ray = scene.camera.primary_ray(u, v);
            let plain = Tracer::new(&scene, &accel, NoRecorder).trace_primary(&ray, &[]);
            let doc = trace_pixel(&scene, i, j);
            let traced: Vec<f64> = doc["color"].as_array().unwrap().iter().map(f).collect();
            assert_eq!(plain.0.to_vec(), traced);
            assert_finite(&doc);
        }
    }
}

#[test]
fn snapshots_of_every_fixture_centre_pixel() {
    insta::glob!("../data/scenes", "*.json", |path| {
        let text = std::fs::read_to_string(path).unwrap();
        let doc = match whitted::scene::load::load_str(&text).unwrap() {
            whitted::scene::AnyScene::Flat(s) => trace_pixel(&s, s.camera.nx / 2, 0),
            whitted::scene::AnyScene::Space(s) => trace_pixel(&s, s.camera.nx / 2, s.camera.ny / 2),
        };
        assert_finite(&doc);
        insta::assert_json_snapshot!(whitted::doc::round::round_floats(&doc, 9));
    });
}
