//! numerics.md cases that concern the scene and the shading (F4, G1, G4, K1, K2, M1, M2), each a
//! named test; the geometric cases sit beside their code in crates/geom and src/shape.

use crate::support::{assert_finite, events, f, trace_ray, SceneText};
use glam::DVec3;
use serde_json::{json, Value};
use whitted::geom::ray::Ray;
use whitted::scene::load::load_str;

/// A 2 × 2 scene seen from (0, 1, 5), lit by `lights`, holding one `object`.
fn scene_of(lights: &[Value], object: Value) -> SceneText {
    let scene = SceneText::space3(2, 2).set("/camera/eye", json!([0, 1, 5])).object(object);
    lights.iter().fold(scene, |s, l| s.light(l.clone()))
}

fn errors(text: &str) -> Vec<String> {
    load_str(text).err().map(|e| e.iter().map(ToString::to_string).collect()).unwrap_or_default()
}

#[test]
fn g1_light_at_the_hit_point_is_skipped_without_nan() {
    let scene = scene_of(
        &[json!({"position": [0, 0, 0]}), json!({"position": [0, 3, 0]})],
        json!({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"ks": 0.5}}),
    );
    let doc = trace_ray(&scene.space(), &Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::NEG_Y));
    let lights = doc["tree"]["lights"].as_array().unwrap();
    assert_eq!(lights[0]["lum"], 0.0);
    assert!(lights[0]["L"].is_null());
    assert!(lights[0]["shadow"].is_null());
    // The second light is straight above: N·H = 1, the highlight is ks.
    assert_eq!(lights[1]["lum"], 1.0);
    assert_eq!(lights[1]["specular"], serde_json::json!([0.5, 0.5, 0.5]));
    assert_eq!(events(&doc, "shadow_ray").len(), 1, "no shadow ray where lum = 0");
    assert_finite(&doc);
}

#[test]
fn k2_highlight_uses_max_zero_and_fractional_exponents() {
    // N·H < 0 with n = 2.5 would be powf(negative, 2.5) = NaN without the max(0, ·).
    let with_n = |n: f64| {
        scene_of(
            &[json!({"position": [5, 0.001, 0]})],
            json!({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": {"ks": 0.5, "n": n}}),
        )
        .space()
    };
    let grazing = Ray::new(DVec3::new(5.0, 1.0, 0.0), DVec3::new(-5.0, -1.0, 0.0).normalize());
    let doc = trace_ray(&with_n(2.5), &grazing);
    assert_finite(&doc);
    let doc = trace_ray(&with_n(0.0), &grazing);
    // 0^0 = 1: with n = 0 the highlight is ks·Isrc·fat·s whatever N·H.
    let spec = f(&doc["tree"]["lights"][0]["specular"][0]);
    assert!((spec - 0.5).abs() < 1e-15, "{spec}");
}

#[test]
fn k1_overflow_underflow_and_magnitude() {
    // The radius as written, numbers a JSON value cannot hold (1e400, NaN) included.
    let radius = |r: &str| {
        let text = scene_of(&[], json!({"type": "sphere", "center": [0, 0, 0], "radius": "R"})).text();
        errors(&text.replace(r#""R""#, r))
    };
    assert!(radius("1e400")[0].starts_with("invalid JSON at line 1"), "{:?}", radius("1e400"));
    assert_eq!(radius("1e-400"), vec!["objects[0].radius: must be > 0, got 0"]);
    assert_eq!(radius("-1"), vec!["objects[0].radius: must be > 0, got -1"]);
    assert_eq!(radius("1e200"), vec!["objects[0].radius: must be at most 1e100 in magnitude, got 1e200"]);
    assert!(radius("NaN")[0].starts_with("invalid JSON"));
}

#[test]
fn f4_index_extremes() {
    let ior = |v: f64| errors(&SceneText::space3(2, 2).material("glass", json!({"ior": v})).text());
    assert_eq!(ior(0.0), vec!["materials.glass.ior: must be > 0, got 0"]);
    assert_eq!(ior(-1.5), vec!["materials.glass.ior: must be > 0, got -1.5"]);
    // ior = 1e6 is valid: entering, T ≈ −N.
    let scene = scene_of(
        &[],
        json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": {"kt": 0.5, "ior": 1e6}}),
    )
    .set("/max_depth", json!(2));
    let doc = trace_ray(&scene.space(), &Ray::new(DVec3::new(0.3, 0.3, 5.0), DVec3::NEG_Z));
    assert_finite(&doc);
    let t = &doc["tree"]["children"][0];
    assert_eq!(t["kind"], "transmitted");
    let n: Vec<f64> = doc["tree"]["hit"]["normal"].as_array().unwrap().iter().map(f).collect();
    let dir: Vec<f64> = t["direction"].as_array().unwrap().iter().map(f).collect();
    let cos: f64 = n.iter().zip(&dir).map(|(a, b)| a * b).sum();
    assert!(cos < -0.999_999, "T ≈ −N, got cos = {cos}");
    // Inside a sphere the exit angle equals the refracted entry angle, so it leaves again (numerics.md F3).
    assert!(events(&doc, "total_internal_reflection").is_empty());
}

#[test]
fn g4_window_and_image_plane_extremes() {
    let cam = |w: Value, p: f64| {
        errors(&SceneText::space3(2, 2).set("/camera/window", w).set("/camera/p", json!(p)).text())
    };
    assert_eq!(
        cam(json!({"l": 0.5, "r": 0.5, "b": -1, "t": 1}), 1.0),
        vec!["camera.window: r must be > l, got l = 0.5, r = 0.5"]
    );
    assert_eq!(
        cam(json!({"l": -1, "r": 1, "b": 1, "t": -1}), 1.0),
        vec!["camera.window: t must be > b, got b = 1, t = -1"]
    );
    assert_eq!(cam(json!({"l": -1, "r": 1, "b": -1, "t": 1}), -2.0), vec!["camera.p: must be > 0, got -2"]);
    assert!(cam(json!({"l": -1, "r": 1}), 1.0).contains(&"camera.window.b: missing (required)".to_string()));
}

#[test]
fn m2_infinities_are_strings_and_nan_is_never_written() {
    use whitted::doc::float;
    assert_eq!(float(f64::INFINITY), serde_json::json!("inf"));
    assert_eq!(float(f64::NEG_INFINITY), serde_json::json!("-inf"));
    assert_eq!(float(0.5), serde_json::json!(0.5));
}

#[test]
fn mixed_dimensions_and_unknown_types_are_errors() {
    let e = errors(
        &SceneText::flat2(4)
            .light(json!({"position": [1, 2, 3]}))
            .object(json!({"type": "mesh", "obj": "x.obj"}))
            .object(json!({"type": "sphere", "center": [0, 0, 0], "radius": 1}))
            .text(),
    );
    assert!(
        e.contains(&"lights[0].position: must have 2 numbers (a 2D scene, as the camera says), got 3".into()),
        "{e:?}"
    );
    assert!(e.contains(&"objects[0].type: `mesh` exists only in 3D scenes".into()), "{e:?}");
    assert!(
        e.contains(&"objects[1].center: must have 2 numbers (a 2D scene, as the camera says), got 3".into()),
        "{e:?}"
    );
}
