//! The command line: exit codes and one-line errors naming the field or argument (issue 3, item 8).

use crate::support::{fixture_path as fixture, whitted, whitted_with_input, SceneText, Scratch};
use serde_json::json;

#[test]
fn bad_input_exits_2_with_the_field_named() {
    let scene = SceneText::space3(2, 2);
    let sphere = |center: serde_json::Value, radius: serde_json::Value| {
        scene.clone().object(json!({"type": "sphere", "center": center, "radius": radius})).text()
    };
    let cases: &[(String, &str)] = &[
        ("{\"camera\": [}".into(), "invalid JSON at line 1, column"),
        (
            scene.clone().set("/objets", json!([])).text(),
            "objets: unknown field `objets`; did you mean `objects`?",
        ),
        (sphere(json!([0, 0, 0]), json!(-1)), "objects[0].radius: must be > 0, got -1"),
        (
            scene.clone().set("/max_depth", json!(-1)).text(),
            "max_depth: must be an integer in [0, 64], got -1",
        ),
        (
            // A number past f64: JSON values cannot hold it, so it is written as text.
            scene.text_with(&[("objects", r#"[{"type":"sphere","center":[0,0,0],"radius":1e400}]"#)]),
            "invalid JSON",
        ),
        (sphere(json!("x"), json!(1)), "objects[0].center: must be an array of 3 numbers, got a string"),
    ];
    let dir = Scratch::new();
    for (i, (text, expected)) in cases.iter().enumerate() {
        let path = dir.write(&format!("bad{i}.json"), text);
        for cmd in ["check", "render", "tradeoff"] {
            let (code, _, err) =
                whitted(&[cmd, &path, "-o", "/dev/null"][..if cmd == "render" { 4 } else { 2 }]);
            assert_eq!(code, 2, "{cmd} {text}: {err}");
            assert!(err.contains(expected), "{cmd}: expected `{expected}` in {err}");
            assert!(!err.contains("panicked"));
        }
    }
}

#[test]
fn missing_file_and_bad_arguments_exit_2() {
    let (code, _, err) = whitted(&["check", "/nonexistent/scene.json"]);
    assert_eq!(code, 2);
    assert!(err.contains("cannot read the scene"));
    let glass = fixture("glass.json");
    for (args, expected) in [
        (vec!["trace", &glass, "--pixel", "8,0"], "outside the image"),
        (vec!["trace", &glass, "--pixel", "1;2"], "--pixel"),
        (vec!["trace", &glass, "--ray", "0,0,5"], "--ray"),
        (vec!["trace", &glass, "--ray", "0,0:0,1"], "--ray: the origin must have 3 numbers"),
        (vec!["render", &glass, "--size", "0x3"], "--size"),
        (vec!["tradeoff", &glass, "--runs", "0"], "--runs"),
    ] {
        let (code, _, err) = whitted(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(expected), "{args:?}: {err}");
    }
}

#[test]
fn trace_json_and_narration() {
    let glass = fixture("glass.json");
    let (code, out, err) = whitted(&["trace", &glass, "--pixel", "4,3", "--json"]);
    assert_eq!(code, 0, "{err}");
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in ["pixel", "uv", "color", "stats", "tree", "events"] {
        assert!(doc.get(key).is_some(), "missing {key}");
    }
    assert_eq!(doc["pixel"], serde_json::json!([4, 3]));
    let (code, out, _) = whitted(&["trace", &glass, "--pixel", "4,3"]);
    assert_eq!(code, 0);
    assert!(out.contains("u = l + (r − l)·(i + 0.5)/Nx"));
    assert!(out.contains("1. Pixel (i, j) = (4, 3)"));
    let (code, out, _) = whitted(&["trace", &glass, "--pixel", "4,3", "--lang", "ro"]);
    assert_eq!(code, 0);
    assert!(out.contains("Raza primară"), "{out}");
    assert!(out.contains("rândul de jos"));
    let (code, out, _) = whitted(&["trace", &fixture("lens_2d.json"), "--pixel", "3", "--json"]);
    assert_eq!(code, 0);
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["pixel"], serde_json::json!([3]));
    assert_eq!(doc["uv"].as_array().unwrap().len(), 1);
}

#[test]
fn object_names_follow_the_language_and_the_document_keeps_the_english() {
    // scenes/flat.json names its segment {"en": "mirror", "ro": "oglindă"}; pixel 15's primary ray
    // meets it (narration steps 8 and 9).
    let scene = format!("{}/scenes/flat.json", env!("CARGO_MANIFEST_DIR"));
    let (code, out, err) = whitted(&["trace", &scene, "--pixel", "15", "--lang", "ro"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains(": I₁ pe „oglindă” (segmentul 2)"), "{out}");
    assert!(!out.contains("mirror"), "{out}");
    let (_, out, _) = whitted(&["trace", &scene, "--pixel", "15", "--lang", "en"]);
    assert!(out.contains("“mirror” (segment 2)"), "{out}");
    // The trace document is the same in every language: the English name.
    let (_, out, _) = whitted(&["trace", &scene, "--pixel", "15", "--json"]);
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    let objects: Vec<&serde_json::Value> =
        doc["events"].as_array().unwrap().iter().filter_map(|e| e.get("object")).collect();
    assert!(objects.contains(&&serde_json::json!("mirror")), "{objects:?}");
    assert!(!out.contains("oglindă"));
    // The figure's labels: the Romanian name in a Romanian figure, the English one otherwise.
    let dir = tempfile::tempdir().unwrap();
    for (lang, name, other) in [("ro", "oglindă", "mirror"), ("en", "mirror", "oglindă")] {
        let svg = dir.path().join(format!("rays-{lang}.svg"));
        let svg_arg = svg.to_str().unwrap();
        let (code, _, err) =
            whitted(&["figure", "rays", &scene, "--pixel", "15", "--lang", lang, "-o", svg_arg]);
        assert_eq!(code, 0, "{err}");
        let svg = std::fs::read_to_string(&svg).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let texts: Vec<String> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .map(|n| n.descendants().filter(roxmltree::Node::is_text).filter_map(|t| t.text()).collect())
            .collect();
        assert!(texts.iter().any(|t| t == name), "{lang}: {texts:?}");
        assert!(!texts.iter().any(|t| t.contains(other)), "{lang}: {texts:?}");
    }
}

#[test]
fn render_json_lists_the_statistics() {
    let dir = Scratch::new();
    let out_png = dir.join("glass.png");
    let (code, out, err) = whitted(&[
        "render",
        &fixture("glass.json"),
        "-o",
        &out_png.display().to_string(),
        "--json",
        "--threads",
        "1",
    ]);
    assert_eq!(code, 0, "{err}");
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in
        ["pixels", "samples", "rays", "tests", "load_seconds", "build_seconds", "seconds", "threads", "accel"]
    {
        assert!(doc.get(key).is_some(), "missing {key}");
    }
    assert_eq!(doc["pixels"], 48);
    assert_eq!(doc["threads"], 1);
    assert!(err.contains("48 pixels"));
    let png = std::fs::read(&out_png).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn sampling_options_a_mode_does_not_use_are_reported() {
    let dir = Scratch::new();
    let out_png = dir.arg("options.png");
    let glass = fixture("glass.json");
    let (code, _, err) = whitted(&["render", &glass, "-o", &out_png, "--threshold", "0.2"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("--threshold applies to --aa adaptive only; ignored with --aa center"), "{err}");
    assert!(err.contains("48 samples (center)"), "{err}");
    let (code, _, err) = whitted(&["render", &glass, "-o", &out_png, "--aa", "corners", "--max-level", "3"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("--max-level applies to --aa adaptive only; ignored with --aa corners"), "{err}");
    // Adaptive uses both: nothing to report.
    let (code, _, err) = whitted(&[
        "render",
        &glass,
        "-o",
        &out_png,
        "--aa",
        "adaptive",
        "--threshold",
        "0.2",
        "--max-level",
        "3",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("applies to"), "{err}");
}

#[test]
fn the_adaptive_figure_takes_the_threshold_it_is_given() {
    // `figure adaptive` samples adaptively without --aa, with --threshold and --max-level as given:
    // threshold 0 splits the pixel to level 2, inf never splits it.
    let dir = Scratch::new();
    let draw = |threshold: &str| {
        let svg = dir.arg(&format!("adaptive-{threshold}.svg"));
        let args = [
            "figure",
            "adaptive",
            &fixture("glass.json"),
            "--pixel",
            "4,3",
            "--threshold",
            threshold,
            "-o",
            &svg,
        ];
        let (code, _, err) = whitted(&args);
        assert_eq!(code, 0, "{err}");
        assert!(!err.contains("applies to"), "{err}");
        std::fs::read_to_string(&svg).unwrap()
    };
    let (all, none) = (draw("0"), draw("inf"));
    assert!(all.contains("25 / 25"), "threshold 0: every point of the 5×5 lattice");
    assert!(none.contains("4 / 25"), "threshold inf: the 4 corners");
    // The legend explains the ring of a sample read again only where one is.
    assert!(all.contains("read again by another subregion"));
    assert!(!none.contains("read again by another subregion"), "no square split, nothing read again");
}

#[test]
fn check_says_what_the_scene_models() {
    let (code, out, _) = whitted(&["check", &fixture("glass.json")]);
    assert_eq!(code, 0);
    assert!(out.contains("3D"));
    assert!(out.contains("transmitted: yes, from glass"));
    let (code, out, _) = whitted(&["check", &fixture("corridor.json")]);
    assert_eq!(code, 0);
    assert!(out.contains("transmitted: no: no object has kt > 0"), "{out}");
}

/// The `tradeoff --json` rows of one sweep, and its reference.
fn sweep<'a>(doc: &'a serde_json::Value, name: &str) -> (&'a serde_json::Value, &'a Vec<serde_json::Value>) {
    let sweep = doc["sweeps"].as_array().unwrap().iter().find(|s| s["sweep"] == name).unwrap();
    (&sweep["reference"], sweep["rows"].as_array().unwrap())
}

#[test]
fn tradeoff_measures_each_sweep_against_a_reference_that_differs_in_it_only() {
    let scratch = Scratch::new();
    let dir = scratch.join("plots");
    let glass = fixture("glass.json");
    let (code, out, err) = whitted(&[
        "tradeoff",
        &glass,
        "--runs",
        "2",
        "--threads",
        "2",
        "--json",
        "--out",
        &dir.display().to_string(),
    ]);
    assert_eq!(code, 0, "{err}");
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["runs"], 2);
    let fields = ["sampling", "max_depth", "accel"];
    // Each row differs from its sweep's reference in the sweep's field, and in nothing else.
    for (name, field) in [("sampling", "sampling"), ("depth", "max_depth"), ("structure", "accel")] {
        let (reference, rows) = sweep(&doc, name);
        assert_eq!(reference["rmse"], 0.0);
        for row in rows {
            for f in fields {
                assert_eq!(row[f] != reference[f], f == field, "{name}: {f} of {row}");
            }
            // The spread of the times holds the median; a line says why.
            let t = &row["seconds"];
            assert!(t["min"].as_f64() <= t["median"].as_f64() && t["median"].as_f64() <= t["max"].as_f64());
            assert!(!row["why"].as_str().unwrap().is_empty());
        }
    }
    // max_depth 4: centre, corners, 9 adaptive; depths 0 … 8; 4 structures but brute force.
    let (reference, sampling) = sweep(&doc, "sampling");
    assert_eq!(sampling.len(), 11);
    assert_eq!(
        (reference["max_depth"].as_u64(), reference["sampling"]["max_level"].as_u64()),
        (Some(4), Some(3))
    );
    // (8·8 + 1)(6·8 + 1) lattice points over 48 pixels.
    assert_eq!(reference["rays"]["primary"], 65 * 49);
    assert_eq!(sampling[0]["rays_per_pixel"]["primary"], 1.0);
    assert_eq!(sampling[1]["rays_per_pixel"]["primary"], 9.0 * 7.0 / 48.0);
    let (reference, depths) = sweep(&doc, "depth");
    assert_eq!(depths.len(), 9);
    assert_eq!(
        (reference["max_depth"].as_u64(), reference["sampling"]["aa"].as_str()),
        (Some(16), Some("center"))
    );
    let depth_error = |d: usize| depths[d]["rmse"].as_f64().unwrap();
    assert!(depth_error(0) > depth_error(4), "ray casting lacks every reflection the reference has");
    // A structure changes no pixel: every structure's image is brute force's, exactly.
    let (reference, structures) = sweep(&doc, "structure");
    assert_eq!(reference["accel"], "none");
    assert_eq!(structures.len(), 4);
    for row in structures {
        assert_eq!((row["rmse"].as_f64(), row["max_error"].as_f64()), (Some(0.0), Some(0.0)), "{row}");
        assert_eq!(row["rays"], reference["rays"], "the same rays, other tests");
    }
    // Every cost is the render's own count: `render --json` of the same setting says the same.
    let out_png = dir.join("render.png").display().to_string();
    for (name, row, extra) in [
        ("sampling", &sampling[5], vec!["--aa", "adaptive", "--threshold", "0.3", "--max-level", "2"]),
        ("depth", &depths[2], vec!["--depth", "2"]),
        ("structure", &structures[2], vec!["--accel", "grid"]),
    ] {
        let mut args = vec!["render", glass.as_str(), "--json", "-o", out_png.as_str()];
        args.extend(extra);
        let (code, out, err) = whitted(&args);
        assert_eq!(code, 0, "{err}");
        let render: serde_json::Value = serde_json::from_str(&out).unwrap();
        for kind in ["primary", "reflected", "transmitted", "shadow"] {
            assert_eq!(row["rays"][kind], render["rays"][kind], "{name} {kind}");
        }
        for kind in ["object", "bound", "node", "voxel"] {
            assert_eq!(row["tests"][kind], render["tests"][kind], "{name} {kind}");
        }
    }
    // The front is decided on rays: of two rows, the one with fewer rays and less error wins.
    for name in ["sampling", "depth"] {
        let s = doc["sweeps"].as_array().unwrap().iter().find(|s| s["sweep"] == name).unwrap();
        let rows = s["rows"].as_array().unwrap();
        let front: Vec<usize> = s["pareto"]
            .as_array()
            .unwrap()
            .iter()
            .map(|i| usize::try_from(i.as_u64().unwrap()).unwrap())
            .collect();
        let cost =
            |r: &serde_json::Value| (r["rays"]["total"].as_u64().unwrap(), r["rmse"].as_f64().unwrap());
        for (i, row) in rows.iter().enumerate() {
            let (rays, rmse) = cost(row);
            let beaten = rows.iter().any(|o| {
                let (r, e) = cost(o);
                r <= rays && e <= rmse && (r < rays || e < rmse)
            });
            assert_eq!(front.contains(&i), !beaten, "{name} row {i}");
        }
    }
    // The plots: one per sweep with an error, every point named.
    for file in ["sampling.png", "sampling.svg", "depth.png", "depth.svg", "heat-map.png", "heat-map.svg"] {
        let bytes = std::fs::read(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert!(bytes.len() > 1000, "{file}");
    }
    let svg = std::fs::read_to_string(dir.join("sampling.svg")).unwrap();
    for name in ["centre", "corners", "0.3, K = 1", "0.03, K = 3"] {
        assert!(svg.contains(&format!(">{name}<")), "{name} is not in sampling.svg");
    }
    let svg = std::fs::read_to_string(dir.join("depth.svg")).unwrap();
    assert!(svg.contains("rays traced per pixel"));
    for d in 0..=8 {
        assert!(svg.contains(&format!(">{d}<")) || svg.contains(&format!("… {d}<")), "depth {d}");
    }
    // A scene of nothing but background: every image equals its reference, every point sits on
    // the plot's 0 row; the tables still come.
    let empty = scratch.write("empty.json", SceneText::space3(4, 3).text());
    let empty_dir = dir.join("empty");
    let (code, out, err) =
        whitted(&["tradeoff", &empty, "--runs", "1", "--out", &empty_dir.display().to_string()]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches("| reference |").count(), 3, "{out}");
    assert!(out.contains("no ray goes past level 0"), "{out}");
    assert!(empty_dir.join("sampling.png").exists() && empty_dir.join("heat-map.png").exists());
    // Without --json: a Markdown table per sweep, a row per setting and the reference, and a
    // line per row saying why.
    let (code, out, err) = whitted(&["tradeoff", &glass, "--runs", "1"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().filter(|l| l.starts_with("| ")).count(), 3 + (11 + 1) + (9 + 1) + (4 + 1));
    assert_eq!(out.lines().filter(|l| l.starts_with("- ")).count(), 11 + 9 + 4);
    assert!(out.contains("- grid: error 0"), "{out}");
}

#[test]
fn step_shows_the_trace_narration_a_step_at_a_time() {
    let glass = fixture("glass.json");
    let (_, narration, _) = whitted(&["trace", &glass, "--pixel", "4,3"]);
    let run = |input: &str| {
        let (code, out, _) = whitted_with_input(&["step", &glass, "--pixel", "4,3"], input);
        (code, out)
    };
    // Enter twice: steps 1, 2 and 3, no more; then the end of input ends the session.
    let (code, out) = run("\n\n");
    assert_eq!(code, 0);
    assert!(out.contains("1. Pixel (i, j) = (4, 3)") && out.contains("\n3. P — primary ray"), "{out}");
    assert!(!out.contains("\n   4. "), "{out}");
    // `a`: the first step, then all the rest: the whole narration, every line of it.
    let (_, all) = run("a\n");
    for line in narration.lines() {
        assert!(all.contains(line), "missing {line}");
    }
    let (code, _, err) = whitted(&["step", &glass, "--pixel", "9,9"]);
    assert_eq!(code, 2, "{err}");
}
