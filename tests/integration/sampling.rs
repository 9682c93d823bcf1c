//! Anti-aliasing (algorithm.md §8; numerics.md H1): exact sample counts of corners and adaptive
//! sampling, sharing across rows, jobs of rows and threads, the area-weighted mean by hand, the trace
//! document of a sampled pixel, and the options' validation.

use crate::support::{
    assert_finite, events, f, fixture, fixture_path, scene2, scene3, whitted, SceneText, Scratch,
};
use serde_json::{json, Value};
use whitted::accel::{Accel, AccelKind};
use whitted::doc::round::round_floats;
use whitted::doc::samples::sampled_document;
use whitted::doc::TraceTarget;
use whitted::record::EventLog;
use whitted::render::{render, RenderConfig, Rendered};
use whitted::sample::{trace_pixel, PixelTrace, Sampling};
use whitted::scene::material::Rgb;
use whitted::scene::Scene;
use whitted::shape::Dim;
use whitted::trace::Tracer;

/// Renders in a pool of `threads` threads, with the per-pixel counts.
fn render_in<V: Dim>(scene: &Scene<V>, sampling: Sampling, threads: usize) -> Rendered {
    let accel = Accel::build(scene, AccelKind::None);
    let config = RenderConfig { sampling, rays_per_pixel: true, ..RenderConfig::centers(scene.max_depth) };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| render(scene, &accel, &config))
}

fn adaptive(threshold: f64, max_level: u32) -> Sampling {
    Sampling::adaptive(threshold, max_level).unwrap()
}

/// Traces one pixel with samples: the pixel's record and its trace document.
fn trace_sampled<V: Dim>(scene: &Scene<V>, sampling: Sampling, i: usize, j: usize) -> (PixelTrace, Value) {
    let accel = Accel::build(scene, AccelKind::None);
    let mut tracer = Tracer::new(scene, &accel, EventLog::new());
    let traced = trace_pixel(&mut tracer, sampling, i, j);
    let (u, v) = scene.camera.pixel_center(i, j);
    let target = if V::DIM == 2 {
        TraceTarget { pixel: Some(vec![i]), uv: Some(vec![u]) }
    } else {
        TraceTarget { pixel: Some(vec![i, j]), uv: Some(vec![u, v]) }
    };
    let doc = sampled_document(scene, &tracer.recorder, &tracer.stats, &target, sampling, &traced);
    (traced, doc)
}

/// (Nx·2^K + 1)(Ny·2^K + 1).
fn lattice_points(nx: usize, ny: usize, k: u32) -> u64 {
    let s = 1 << k;
    ((nx * s + 1) * (ny * s + 1)) as u64
}

#[test]
fn corners_trace_each_shared_corner_once() {
    let scene = scene3(&fixture("glass.json"));
    let r = render_in(&scene, Sampling::Corners, 2);
    assert_eq!(r.stats.rays.primary, (8 + 1) * (6 + 1));
    assert!(r.rays_per_pixel.unwrap().iter().all(|n| *n == 4));
    // §8.1: only m + n + 1 more than one a pixel.
    assert_eq!(r.stats.rays.primary, 8 * 6 + 8 + 6 + 1);
}

#[test]
fn h1_threshold_zero_traces_the_whole_lattice() {
    let scene = scene3(&fixture("glass.json"));
    for k in 0..=3 {
        let r = render_in(&scene, adaptive(0.0, k), 2);
        assert_eq!(r.stats.rays.primary, lattice_points(8, 6, k), "K = {k}");
        let side = (1 << k) + 1;
        assert!(r.rays_per_pixel.unwrap().iter().all(|n| *n == side * side), "K = {k}");
    }
}

#[test]
fn sharing_holds_across_jobs_of_rows() {
    // An unbounded edge-row budget lets rayon split the rows into jobs of one row, so nearly every
    // edge row is made by one job and read by another; a budget of one byte gives the largest
    // jobs. The image, the statistics and the counts are the same either way, on 1 or 2 threads.
    let mut scene = scene3(&fixture("glass.json"));
    let accel = Accel::build(&scene, AccelKind::None);
    // 8x6 as written, and 32x24, where a budget of one byte gives jobs of several rows.
    for (nx, ny, sampling) in [
        (8, 6, Sampling::Corners),
        (8, 6, adaptive(0.0, 2)),
        (8, 6, adaptive(0.05, 3)),
        (32, 24, Sampling::Corners),
        (32, 24, adaptive(0.05, 2)),
    ] {
        (scene.camera.nx, scene.camera.ny) = (nx, ny);
        let reference = render_in(&scene, sampling, 2);
        for (threads, edge_memory) in [(2, usize::MAX), (2, 1), (1, usize::MAX), (3, usize::MAX)] {
            let config = RenderConfig {
                sampling,
                edge_memory,
                rays_per_pixel: true,
                ..RenderConfig::centers(scene.max_depth)
            };
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let r = pool.install(|| render(&scene, &accel, &config));
            let case = format!("{nx}x{ny}, {sampling:?}, {threads} threads, budget {edge_memory}");
            assert_eq!(r.image, reference.image, "{case}");
            assert_eq!(r.stats, reference.stats, "{case}");
            assert_eq!(r.rays_per_pixel, reference.rays_per_pixel, "{case}");
        }
    }
    let config = RenderConfig { sampling: adaptive(0.0, 2), edge_memory: 1, ..RenderConfig::centers(4) };
    assert_eq!(render(&scene, &accel, &config).stats.rays.primary, lattice_points(32, 24, 2));
}

#[test]
fn infinite_threshold_and_level_zero_equal_corners_bit_for_bit() {
    let scene = scene3(&fixture("glass.json"));
    let corners = render_in(&scene, Sampling::Corners, 2);
    for sampling in
        [adaptive(f64::INFINITY, 0), adaptive(f64::INFINITY, 3), adaptive(0.0, 0), adaptive(0.1, 0)]
    {
        let r = render_in(&scene, sampling, 2);
        assert_eq!(r.image, corners.image, "{sampling:?}");
        assert_eq!(r.stats, corners.stats, "{sampling:?}");
    }
}

#[test]
fn h1_a_uniform_image_never_splits() {
    let scene = SceneText::space3(7, 5)
        .window(json!({"l": -1, "r": 1, "b": -0.5, "t": 0.5}))
        .set("/background", json!([0.2, 0.4, 0.6]))
        .space();
    let r = render_in(&scene, adaptive(0.1, 3), 2);
    assert_eq!(r.stats.rays.primary, 8 * 6);
    assert!(r.image.pixels.iter().all(|c| *c == Rgb([0.2, 0.4, 0.6])));
    // Threshold 0 splits even equal corners: spread 0 ≥ 0.
    let r = render_in(&scene, adaptive(0.0, 2), 2);
    assert_eq!(r.stats.rays.primary, lattice_points(7, 5, 2));
}

#[test]
fn h1_bad_threshold_or_level_is_refused() {
    for bad in [f64::NAN, -0.1, f64::NEG_INFINITY] {
        let e = Sampling::adaptive(bad, 2).unwrap_err();
        assert!(e.to_string().starts_with("--threshold"), "{e}");
    }
    assert!(Sampling::adaptive(f64::INFINITY, 8).is_ok());
    assert!(Sampling::adaptive(0.0, 0).is_ok());
    assert!(Sampling::adaptive(0.1, 9).unwrap_err().to_string().starts_with("--max-level"));
    let glass = fixture_path("glass.json");
    for (args, expected) in [
        (vec!["--threshold", "nan"], "--threshold"),
        (vec!["--threshold", "-1"], "--threshold"),
        (vec!["--threshold", "-inf"], "--threshold"),
        (vec!["--max-level", "9"], "--max-level"),
        (vec!["--max-level", "-1"], "--max-level"),
    ] {
        for cmd in ["render", "trace"] {
            let mut all = vec![cmd, glass.as_str(), "--aa", "adaptive", "-o", "/dev/null", "--pixel", "1,1"];
            all.drain(if cmd == "render" { 6..8 } else { 4..6 });
            all.extend(&args);
            let (code, _, err) = whitted(&all);
            assert_eq!(code, 2, "{all:?}: {err}");
            assert!(err.contains(expected), "{all:?}: {err}");
        }
    }
}

/// An orthographic camera looking down −z at the window [−1, 1]²: u = x. A box fills x ≤ 0.3 with
/// the ambient colour ka (no lights, black background), so pixel (1, j), u ∈ [0, 1], has one
/// sharp vertical edge at u = 0.3.
fn edge() -> Scene<glam::DVec3> {
    SceneText::space3(2, 2)
        .set("/camera/projection", json!("orthographic"))
        .object(json!({"type": "box", "min": [-10, -10, -1], "max": [0.3, 10, 0],
            "material": {"ka": [0.8, 0.4, 0.2], "kd": 0}}))
        .space()
}

#[test]
fn one_pixel_is_the_area_weighted_mean_of_its_leaves_by_hand() {
    let scene = edge();
    let ka = Rgb([0.8, 0.4, 0.2]);
    // The spread across the edge is 0.8 (red) ≥ 0.5: squares whose corners straddle u = 0.3
    // split; the others are uniform leaves.
    // K = 2: columns of level-2 squares (width 1/4): [0, 1/4] both corners inside → ka,
    // area 1/4; [1/4, 1/2] corners 0.25 (inside) and 0.5 (outside), level 2 = K → leaf of colour
    // ka/2, area 1/4; the right half of the pixel: level-1 leaves, black.
    let by_hand = ka * (0.25 * 1.0) + ka * (0.25 * 0.5);
    // K = 3: [1/4, 1/2] splits again into [1/4, 3/8] (0.25 in, 0.375 out: ka/2, area 1/8) and
    // [3/8, 1/2] (black).
    let by_hand_3 = ka * (0.25 * 1.0) + ka * (0.125 * 0.5);
    for (k, expected) in [(2, by_hand), (3, by_hand_3)] {
        let sampling = adaptive(0.5, k);
        let (traced, doc) = trace_sampled(&scene, sampling, 1, 0);
        for c in 0..3 {
            assert!((traced.color.0[c] - expected.0[c]).abs() < 1e-15, "K = {k}: {:?}", traced.color);
        }
        // The document's leaves give the same mean, weight by weight.
        let mut sum = [0.0; 3];
        let mut area = 0.0;
        for q in doc["squares"].as_array().unwrap().iter().filter(|q| q["split"] == false) {
            let w = f(&q["weight"]);
            area += w;
            for (c, s) in sum.iter_mut().enumerate() {
                *s += w * f(&q["color"][c]);
            }
        }
        assert_eq!(area, 1.0);
        for (s, e) in sum.iter().zip(expected.0) {
            assert!((s - e).abs() < 1e-15, "K = {k}");
        }
        // The render gives the pixel the same bits.
        let r = render_in(&scene, sampling, 2);
        assert_eq!(r.image.get(1, 0), traced.color, "K = {k}");
        assert_eq!(r.image.get(0, 0), ka, "the box fills pixel 0");
    }
}

#[test]
fn rendered_and_traced_pixels_agree_everywhere() {
    let scene = scene3(&fixture("glass.json"));
    let sampling = adaptive(0.05, 2);
    let r = render_in(&scene, sampling, 2);
    let counts = r.rays_per_pixel.as_ref().unwrap();
    for j in 0..scene.camera.ny {
        for i in 0..scene.camera.nx {
            let (traced, _) = trace_sampled(&scene, sampling, i, j);
            assert_eq!(r.image.get(i, j), traced.color, "pixel ({i}, {j})");
            assert_eq!(counts[j * scene.camera.nx + i] as usize, traced.samples.len(), "pixel ({i}, {j})");
        }
    }
}

#[test]
fn threads_do_not_change_the_image_or_the_counts() {
    let scene = scene3(&fixture("glass.json"));
    for sampling in [Sampling::Center, Sampling::Corners, adaptive(0.05, 3)] {
        let one = render_in(&scene, sampling, 1);
        for threads in [2, 3] {
            let many = render_in(&scene, sampling, threads);
            assert_eq!(many.image, one.image, "{sampling:?}");
            assert_eq!(many.stats, one.stats, "{sampling:?}");
            assert_eq!(many.rays_per_pixel, one.rays_per_pixel, "{sampling:?}");
        }
    }
}

#[test]
fn one_and_two_threads_write_the_same_png() {
    let dir = Scratch::new();
    let glass = fixture_path("glass.json");
    let mut bytes = Vec::new();
    for threads in ["1", "2"] {
        let out = dir.join(format!("aa-{threads}.png"));
        let out_s = out.display().to_string();
        let args = [
            "render",
            &glass,
            "-o",
            &out_s,
            "--aa",
            "adaptive",
            "--threshold",
            "0.05",
            "--max-level",
            "2",
            "--size",
            "48x36",
            "--threads",
            threads,
            "--json",
        ];
        let (code, stdout, err) = whitted(&args);
        assert_eq!(code, 0, "{err}");
        let doc: Value = serde_json::from_str(&stdout).unwrap();
        assert_eq!(doc["aa"], "adaptive");
        assert_eq!(doc["max_level"], 2);
        assert!(err.contains("samples (adaptive"), "{err}");
        assert!(!err.contains('\r'), "no progress bar when stderr is not a terminal");
        bytes.push(std::fs::read(&out).unwrap());
    }
    assert_eq!(bytes[0], bytes[1]);
}

#[test]
fn two_d_scenes_sample_intervals() {
    let scene = scene2(&fixture("lens_2d.json"));
    let nx = scene.camera.nx;
    let corners = render_in(&scene, Sampling::Corners, 2);
    assert_eq!(corners.stats.rays.primary, nx as u64 + 1);
    assert!(corners.rays_per_pixel.as_ref().unwrap().iter().all(|n| *n == 2));
    for k in 0..=3 {
        let r = render_in(&scene, adaptive(0.0, k), 2);
        assert_eq!(r.stats.rays.primary, (nx * (1 << k) + 1) as u64, "K = {k}");
    }
    let r = render_in(&scene, adaptive(f64::INFINITY, 2), 2);
    assert_eq!(r.image, corners.image);
    // Every row of the strip is the sampled row.
    assert_eq!(r.image.get(3, 0), r.image.get(3, r.image.height - 1));
    // A pixel traced alone: 2 ends, u only, the mean of its leaves.
    let sampling = adaptive(0.05, 2);
    let (traced, doc) = trace_sampled(&scene, sampling, 3, 0);
    let r = render_in(&scene, sampling, 1);
    assert_eq!(r.image.get(3, 0), traced.color);
    for s in doc["samples"].as_array().unwrap() {
        assert!(s.get("v").is_none());
        assert_eq!(s["lattice"].as_array().unwrap().len(), 1);
    }
    for q in doc["squares"].as_array().unwrap() {
        assert_eq!(q["corners"].as_array().unwrap().len(), 2);
    }
    assert_finite(&doc);
}

#[test]
fn the_sampled_trace_document() {
    let scene = scene3(&fixture("glass.json"));
    let (traced, doc) = trace_sampled(&scene, adaptive(0.05, 2), 3, 2);
    assert_eq!(doc["tree"], Value::Null);
    assert_eq!(doc["pixel"], serde_json::json!([3, 2]));
    let samples = doc["samples"].as_array().unwrap();
    assert_eq!(samples.len(), traced.samples.len());
    assert_eq!(doc["stats"]["rays"]["primary"], samples.len());
    assert_eq!(samples[0]["label"], "CA");
    assert_eq!(samples[1]["label"], "CB");
    // The first 4 are the pixel's corners, at level 0, at u = l + (r − l)·i/Nx.
    let cam = &scene.camera;
    for (k, (i, j)) in [(3, 2), (4, 2), (3, 3), (4, 3)].into_iter().enumerate() {
        assert_eq!(samples[k]["level"], 0);
        assert_eq!(f(&samples[k]["u"]), cam.u_at(f64::from(i)));
        assert_eq!(f(&samples[k]["v"]), cam.v_at(f64::from(j)));
        assert_eq!(samples[k]["tree"]["kind"], "primary");
    }
    // Every event carries its sample; each sample's rays come before its first sample event.
    for e in doc["events"].as_array().unwrap() {
        assert!(e["sample"].as_u64().is_some(), "{e}");
    }
    let sample_events = events(&doc, "sample");
    let squares = doc["squares"].as_array().unwrap();
    let corners_read: usize = squares.iter().map(|q| q["corners"].as_array().unwrap().len()).sum();
    assert_eq!(sample_events.len(), corners_read, "one sample event per corner a square reads");
    assert_eq!(sample_events.iter().filter(|e| e["reused"] == false).count(), samples.len());
    assert_eq!(squares[0]["level"], 0);
    assert_eq!(squares[0]["split"], true, "the pixel straddles an edge");
    // A split square's colour is the mean of its children; the pixel's is the root square's.
    assert_eq!(doc["color"], squares[0]["color"]);
    assert_finite(&doc);
}

#[test]
fn snapshot_of_one_adaptive_pixel() {
    // The edge scene: 9 samples, 1 level-0 square split into 4, two of them across the edge.
    let (_, doc) = trace_sampled(&edge(), adaptive(0.5, 1), 1, 0);
    assert_finite(&doc);
    insta::assert_json_snapshot!("adaptive_edge_pixel", round_floats(&doc, 9));
}

#[test]
fn trace_cli_with_samples() {
    let glass = fixture_path("glass.json");
    let (code, out, err) = whitted(&["trace", &glass, "--pixel", "3,2", "--aa", "corners", "--json"]);
    assert_eq!(code, 0, "{err}");
    let doc: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["samples"].as_array().unwrap().len(), 4);
    assert_eq!(doc["squares"].as_array().unwrap().len(), 1);
    assert_eq!(doc["sampling"]["aa"], "corners");
    let (code, out, _) =
        whitted(&["trace", &glass, "--pixel", "3,2", "--aa", "adaptive", "--threshold", "0.05"]);
    assert_eq!(code, 0);
    assert!(out.contains("CA ("), "{out}");
    assert!(out.contains("area-weighted mean"), "{out}");
    let (code, _, err) = whitted(&["trace", &glass, "--ray", "0,0,5:0,0,-1", "--aa", "corners"]);
    assert_eq!(code, 2);
    assert!(err.contains("--pixel"), "{err}");
}
