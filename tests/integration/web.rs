//! The WebAssembly binding (`web/`), called natively: its answers equal the command line's output
//! byte for byte (trace documents, narrations, figure SVGs, render pixels, error messages) for
//! many pixels of the lesson scenes, and the events its steps name lie in the trace document.
//! (`web/test/identical.mjs` holds the compiled module to the same outputs.)

use crate::support::{edited, whitted, SceneText, Scratch};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// Calls the binding with a request; returns its code and JSON text.
fn call(request: &Value) -> (u8, String) {
    let answer = whitted_web::call(request.to_string().as_bytes());
    (answer.code, answer.json)
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The lesson scenes and the example scenes (not those with meshes: the OBJ text is tested apart).
fn scenes() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root().join("lessons/scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    paths.push(root().join("scenes/whitted.json"));
    paths.push(root().join("scenes/flat.json"));
    paths
}

fn text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap()
}

/// The image's size, from the binding's `info`.
fn size(scene: &str) -> (usize, usize, usize) {
    let (code, info) = call(&json!({"op": "info", "scene": scene}));
    assert_eq!(code, 0, "{info}");
    let info: Value = serde_json::from_str(&info).unwrap();
    let n = |k: &str| usize::try_from(info[k].as_u64().unwrap()).unwrap();
    (n("dimension"), n("width"), n("height"))
}

/// Pixels spread over the image: the corners, the centre and points at thirds (deduplicated);
/// `[i]` in 2D.
fn pixels(dim: usize, w: usize, h: usize) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = Vec::new();
    for (a, b) in [(1, 2), (0, 0), (3, 3), (1, 3), (2, 3)] {
        let i = (w * a / b.max(1)).min(w - 1);
        let j = (h * (b - a) / b.max(1)).min(h - 1);
        let p = if dim == 2 { vec![i] } else { vec![i, j] };
        if !out.contains(&p) {
            out.push(p);
        }
    }
    out
}

fn pixel_arg(p: &[usize]) -> String {
    p.iter().map(ToString::to_string).collect::<Vec<_>>().join(",")
}

#[test]
fn trace_documents_and_narrations_equal_the_command_line() {
    for path in scenes() {
        let scene = text(&path);
        let (dim, w, h) = size(&scene);
        let file = path.to_str().unwrap();
        for p in pixels(dim, w, h) {
            let arg = pixel_arg(&p);
            let target = json!({"pixel": p});
            let (code, doc) = call(&json!({"op": "trace", "scene": scene, "target": target}));
            let (status, cli, err) = whitted(&["trace", file, "--pixel", &arg, "--json"]);
            assert_eq!((code, status), (0, 0), "{file} {arg}: {doc} {err}");
            assert_eq!(doc, cli, "{file} --pixel {arg}");
            let events = serde_json::from_str::<Value>(&doc).unwrap()["events"].as_array().unwrap().len();
            for (lang, flag) in [("en", "en"), ("ro", "ro")] {
                let request =
                    json!({"op": "narrate", "scene": scene, "target": target, "lang": lang, "name": file});
                let (code, answer) = call(&request);
                assert_eq!(code, 0, "{answer}");
                let answer: Value = serde_json::from_str(&answer).unwrap();
                let (_, told, _) = whitted(&["trace", file, "--pixel", &arg, "--lang", flag]);
                let steps = answer["steps"].as_array().unwrap();
                let joined: Vec<&str> = steps.iter().map(|s| s["text"].as_str().unwrap()).collect();
                assert_eq!(joined.join("\n") + "\n", told, "{file} --pixel {arg} --lang {lang}");
                for (k, step) in steps.iter().enumerate() {
                    assert_eq!(step["step"], k + 1);
                    let named = step["events"].as_array().unwrap();
                    assert!(!named.is_empty(), "{file} {arg}: step {} names no event", k + 1);
                    assert!(named.iter().all(|e| e.as_u64().unwrap() < events as u64), "{step}");
                    // Where `whitted step` says it stands: the pixel, or a path from P.
                    let place = step["place"].as_str().unwrap();
                    assert!(place.starts_with("pix") || place.starts_with("P"), "{file} {arg}: {place}");
                }
                let expected = format!(
                    "whitted trace {file} --pixel {arg}{}",
                    if lang == "ro" { " --lang ro" } else { "" }
                );
                assert_eq!(answer["command"], expected);
                assert_eq!(answer["pixel"], json!(p));
            }
        }
    }
}

#[test]
fn options_reach_the_trace_as_the_command_line_gives_them() {
    let path = root().join("scenes/whitted.json");
    let (scene, file) = (text(&path), path.to_str().unwrap().to_owned());
    let cases: [(Value, &[&str]); 4] = [
        (
            json!({"depth": 1, "accel": "grid", "grid": [4, 4, 4]}),
            &["--depth", "1", "--accel", "grid", "--grid", "4,4,4"],
        ),
        (
            json!({"aa": "adaptive", "threshold": 0.05, "max_level": 3}),
            &["--aa", "adaptive", "--threshold", "0.05", "--max-level", "3"],
        ),
        (
            json!({"aa": "corners", "accel": "bounds", "bounds": "kdop"}),
            &["--aa", "corners", "--accel", "bounds", "--bounds", "kdop"],
        ),
        (json!({"accel": "octree", "depth": 0}), &["--accel", "octree", "--depth", "0"]),
    ];
    for (options, flags) in cases {
        let (code, doc) = call(
            &json!({"op": "trace", "scene": scene, "target": {"pixel": [400, 200]}, "options": options}),
        );
        let mut args = vec!["trace", file.as_str(), "--pixel", "400,200", "--json"];
        args.extend(flags);
        let (status, cli, err) = whitted(&args);
        assert_eq!((code, status), (0, 0), "{doc} {err}");
        assert_eq!(doc, cli, "{options}");
    }
    let ray = json!({"op": "trace", "scene": scene, "target": {"ray": [[0, 0.5, 5], [0.1, 0, -1]]}});
    let (_, doc) = call(&ray);
    assert_eq!(doc, whitted(&["trace", &file, "--ray=0,0.5,5:0.1,0,-1", "--json"]).1);
}

#[test]
fn figure_svgs_equal_the_command_line() {
    let dir = Scratch::new();
    for path in scenes() {
        let scene = text(&path);
        let (dim, w, h) = size(&scene);
        let file = path.to_str().unwrap();
        for p in pixels(dim, w, h).into_iter().take(2) {
            let arg = pixel_arg(&p);
            for kind in ["ray-tree", "rays", "uv-map", "bvh"] {
                for lang in ["en", "ro"] {
                    let request = json!({"op": "figure", "kind": kind, "scene": scene, "name": file,
                        "target": {"pixel": p}, "lang": lang});
                    let (code, answer) = call(&request);
                    let out = dir.join(format!("{kind}.svg"));
                    let out = out.to_str().unwrap();
                    let (status, _, err) =
                        whitted(&["figure", kind, file, "--pixel", &arg, "--lang", lang, "-o", out]);
                    assert_eq!((code, status), (0, 0), "{file} {kind} {arg}: {answer} {err}");
                    let answer: Value = serde_json::from_str(&answer).unwrap();
                    assert_eq!(
                        answer["svg"].as_str().unwrap(),
                        std::fs::read_to_string(out).unwrap(),
                        "{file} {kind} {arg} {lang}"
                    );
                    assert_eq!(answer["pick"], Value::Null);
                    assert_eq!(answer["pixel"], json!(p));
                }
            }
        }
    }
    // Without a pixel the figure picks one and says which, as its caption does.
    let path = root().join("scenes/whitted.json");
    let (code, answer) = call(
        &json!({"op": "figure", "kind": "refraction", "scene": text(&path), "name": "scenes/whitted.json"}),
    );
    assert_eq!(code, 0, "{answer}");
    let answer: Value = serde_json::from_str(&answer).unwrap();
    let pick = answer["pick"].as_str().unwrap();
    assert!(
        pick.starts_with("pixel (") && pick.contains("(picked: its first refraction is the clearest)"),
        "{pick}"
    );
    let out = dir.join("refraction.svg");
    whitted(&["figure", "refraction", path.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let svg = answer["svg"].as_str().unwrap();
    assert_eq!(
        svg,
        std::fs::read_to_string(&out).unwrap().replace(path.to_str().unwrap(), "scenes/whitted.json")
    );
}

#[test]
fn a_render_gives_the_pixels_of_the_png() {
    let dir = Scratch::new();
    for (scene, options, flags) in [
        ("scenes/whitted.json", json!({"size": [64]}), vec!["--size", "64"]),
        (
            "lessons/scenes/shiny.json",
            json!({"size": [40, 30], "aa": "adaptive"}),
            vec!["--size", "40x30", "--aa", "adaptive"],
        ),
        ("scenes/flat.json", json!({}), vec![]),
    ] {
        let path = root().join(scene);
        let answer = whitted_web::call(
            json!({"op": "render", "scene": text(&path), "options": options}).to_string().as_bytes(),
        );
        assert_eq!(answer.code, 0, "{}", answer.json);
        let png = dir.join("x.png");
        let mut args =
            vec!["render", path.to_str().unwrap(), "-o", png.to_str().unwrap(), "--json", "--threads", "1"];
        args.extend(flags.iter().copied());
        let (status, stats, err) = whitted(&args);
        assert_eq!(status, 0, "{err}");
        let image = image::load_from_memory(&std::fs::read(&png).unwrap()).unwrap().to_rgba8();
        assert_eq!(answer.bytes, image.into_raw(), "{scene}");
        // The statistics but the times, the threads and the file equal the command line's.
        let mut ours: Value = serde_json::from_str(&answer.json).unwrap();
        let mut theirs: Value = serde_json::from_str(&stats).unwrap();
        for doc in [&mut ours, &mut theirs] {
            let map = doc.as_object_mut().unwrap();
            for key in ["load_seconds", "build_seconds", "seconds", "threads", "output", "notes"] {
                map.remove(key);
            }
        }
        assert_eq!(ours, theirs, "{scene}");
    }
}

#[test]
fn bad_input_is_refused_with_the_command_line_words() {
    let dir = Scratch::new();
    let bad = SceneText::space3(2, 2)
        .set("/max_depth", json!(-1))
        .object(json!({"type": "sphere", "center": [0, 0, 0], "radius": -1}))
        .text();
    let file = dir.join("bad.json");
    std::fs::write(&file, &bad).unwrap();
    let (code, answer) = call(&json!({"op": "check", "scene": bad}));
    let (status, _, err) = whitted(&["check", file.to_str().unwrap()]);
    assert_eq!((code, status), (2, 2));
    let answer: Value = serde_json::from_str(&answer).unwrap();
    assert_eq!(answer["ok"], false);
    let prefix = format!("error: {}: ", file.display());
    let cli: Vec<&str> = err.lines().map(|l| l.strip_prefix(&prefix).unwrap()).collect();
    assert_eq!(answer["errors"], json!(cli));
    assert!(cli.len() >= 2, "{err}");

    let good = root().join("scenes/whitted.json");
    let (code, answer) = call(&json!({"op": "check", "scene": text(&good), "name": "scenes/whitted.json"}));
    assert_eq!(code, 0);
    let answer: Value = serde_json::from_str(&answer).unwrap();
    assert_eq!(answer["text"], whitted(&["check", "scenes/whitted.json"]).1.as_str().replace("\r", ""));

    let scene = text(&good);
    let svg_out = dir.join("x.svg");
    let svg_out = svg_out.to_str().unwrap();
    for (request, args) in [
        (
            json!({"op": "trace", "scene": scene, "target": {"pixel": [9999, 0]}}),
            vec!["trace", "--pixel", "9999,0"],
        ),
        (json!({"op": "trace", "scene": scene, "target": {"pixel": [3]}}), vec!["trace", "--pixel", "3"]),
        (
            json!({"op": "trace", "scene": scene, "target": {"pixel": [3, 3]}, "options": {"grid": [2, 2]}}),
            vec!["trace", "--pixel", "3,3", "--grid", "2,2"],
        ),
        (
            json!({"op": "narrate", "scene": scene, "target": {"ray": [[0, 0, 5], [0, 0, -1]]}, "options": {"aa": "corners"}}),
            vec!["trace", "--ray=0,0,5:0,0,-1", "--aa", "corners"],
        ),
        (
            json!({"op": "figure", "kind": "refraction", "scene": scene, "target": {"pixel": [0, 0]}}),
            vec!["figure", "refraction", "--pixel", "0,0"],
        ),
        (
            json!({"op": "render", "scene": scene, "options": {"grid": [2, 2]}, "name": "x"}),
            vec!["render", "--grid", "2,2"],
        ),
    ] {
        let (code, answer) = call(&request);
        let mut full = args.clone();
        full.insert(if args[0] == "figure" { 2 } else { 1 }, good.to_str().unwrap());
        if args[0] == "figure" {
            full.extend(["-o", svg_out]);
        }
        let (status, _, err) = whitted(&full);
        assert_eq!((code, status), (2, 2), "{request}: {answer} / {err}");
        let answer: Value = serde_json::from_str(&answer).unwrap();
        // Notes on ignored options (`whitted: …`) may precede the error on stderr.
        let errors: Vec<&str> = err.lines().filter_map(|l| l.strip_prefix("error: ")).collect();
        assert_eq!(answer["errors"], json!(errors), "{request}");
    }
    // A value the command line's parser refuses gets that parser's words.
    let (code, answer) = call(
        &json!({"op": "trace", "scene": scene, "target": {"pixel": [1, 2]}, "options": {"threshold": "nan"}}),
    );
    let (_, _, err) = whitted(&["trace", good.to_str().unwrap(), "--pixel", "1,2", "--threshold", "nan"]);
    assert_eq!(code, 2);
    let message = serde_json::from_str::<Value>(&answer).unwrap()["errors"][0].as_str().unwrap().to_owned();
    assert!(err.contains(&message), "{message} / {err}");
    // Broken requests are bad input, never a panic.
    for broken in ["", "{", "[]", r#"{"op": 3}"#, r#"{"op": "nope"}"#, r#"{"op": "trace"}"#, "\u{0}\u{ff}"] {
        let answer = whitted_web::call(broken.as_bytes());
        assert_eq!(answer.code, 2, "{broken}: {}", answer.json);
        assert!(answer.json.starts_with(r#"{"errors":["#), "{}", answer.json);
    }
}

#[test]
fn a_mesh_is_read_from_the_request_objs() {
    let scene = SceneText::space3(4, 4)
        .object(json!({"type": "mesh", "obj": "tri.obj"}))
        .light(json!({"position": [0, 0, 5]}))
        .text();
    let obj = "v -10 -10 0\nv 10 -10 0\nv 0 10 0\nf 1 2 3\n";
    let (code, answer) =
        call(&json!({"op": "trace", "scene": scene, "objs": {"tri.obj": obj}, "target": {"pixel": [2, 2]}}));
    assert_eq!(code, 0, "{answer}");
    assert!(answer.contains("\"triangle\": 0"), "{answer}");
    let (code, answer) = call(&json!({"op": "check", "scene": scene}));
    assert_eq!(code, 2);
    assert!(
        answer.contains("objects[0].obj: cannot read `tri.obj`: not among the request's objs"),
        "{answer}"
    );
}

/// The `data-events` of every item of an SVG, as index lists.
fn svg_events(svg: &str) -> Vec<Vec<u64>> {
    svg.split("data-events=\"")
        .skip(1)
        .map(|rest| {
            let list = &rest[..rest.find('"').unwrap()];
            list.split_whitespace().map(|n| n.parse().unwrap()).collect()
        })
        .collect()
}

#[test]
fn figure_items_name_the_events_they_draw() {
    // Per kind: its options, and the events of the trace document it must draw (all of those
    // kinds; `search` = only those of the primary ray's search, before its hit or miss).
    let cases: [(&str, Value, &[&str], bool); 4] = [
        ("rays", json!({}), &["primary_ray", "reflect", "refract", "shadow_ray", "hit", "miss"], false),
        ("ray-tree", json!({}), &["primary_ray", "reflect", "refract"], false),
        ("bvh", json!({}), &["node_visit"], true),
        ("grid-dda", json!({"accel": "grid"}), &["voxel_step"], true),
    ];
    let mut checked = 0;
    for path in scenes() {
        let scene = text(&path);
        let (dim, w, h) = size(&scene);
        for p in pixels(dim, w, h).into_iter().take(3) {
            for (kind, options, drawn, search) in &cases {
                let target = json!({"pixel": p});
                let (_, doc) =
                    call(&json!({"op": "trace", "scene": scene, "target": target, "options": options}));
                let doc: Value = serde_json::from_str(&doc).unwrap();
                let events = doc["events"].as_array().unwrap();
                let (code, answer) = call(
                    &json!({"op": "figure", "kind": kind, "scene": scene, "target": target, "options": options}),
                );
                if code == 2 {
                    continue; // the kind has nothing to draw here (no bounded object, say)
                }
                assert_eq!(code, 0, "{answer}");
                let svg = serde_json::from_str::<Value>(&answer).unwrap()["svg"].as_str().unwrap().to_owned();
                let items = svg_events(&svg);
                assert_eq!(items.len(), svg.matches("<g data-tag=").count());
                let named: std::collections::BTreeSet<u64> = items.into_iter().flatten().collect();
                assert!(named.iter().all(|k| *k < events.len() as u64), "{kind} {p:?}: {named:?}");
                let mut expected = Vec::new();
                for (k, e) in events.iter().enumerate() {
                    let what = e["kind"].as_str().unwrap();
                    if *search {
                        if e["ray"] != 0 {
                            continue;
                        }
                        if matches!(what, "hit" | "miss") {
                            break;
                        }
                    }
                    if drawn.contains(&what) {
                        expected.push(k as u64);
                    }
                }
                let missing: Vec<&u64> = expected.iter().filter(|k| !named.contains(k)).collect();
                assert!(
                    missing.is_empty(),
                    "{} {kind} {p:?}: events {missing:?} are drawn by no item",
                    path.display()
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 40, "{checked}");
}

#[test]
fn figure_items_of_the_other_kinds_name_their_events() {
    // One telling pixel each (picked by the figure), the events named in range and non-empty.
    let path = root().join("scenes/whitted.json");
    let scene = text(&path);
    for (kind, options) in [
        ("uv-map", json!({})),
        ("refraction", json!({})),
        ("local-model", json!({})),
        ("shadows", json!({})),
        ("slab-test", json!({})),
        ("kay-kajiya", json!({})),
        ("octree", json!({})),
        ("adaptive", json!({})),
    ] {
        let (code, answer) = call(&json!({"op": "figure", "kind": kind, "scene": scene, "options": options}));
        assert_eq!(code, 0, "{kind}: {answer}");
        let answer: Value = serde_json::from_str(&answer).unwrap();
        let pixel = answer["pixel"].clone();
        let mut trace_options = options.clone();
        match kind {
            "slab-test" | "kay-kajiya" => {
                trace_options =
                    json!({"accel": "bounds", "bounds": if kind == "slab-test" { "aabb" } else { "kdop" }});
            }
            "octree" => trace_options = json!({"accel": "octree"}),
            "adaptive" => trace_options = json!({"aa": "adaptive"}),
            _ => {}
        }
        let (_, doc) = call(
            &json!({"op": "trace", "scene": scene, "target": {"pixel": pixel}, "options": trace_options}),
        );
        let doc: Value = serde_json::from_str(&doc).unwrap();
        let count = doc["events"].as_array().unwrap().len() as u64;
        let named: Vec<u64> = svg_events(answer["svg"].as_str().unwrap()).into_iter().flatten().collect();
        assert!(!named.is_empty(), "{kind}: no item names an event");
        assert!(named.iter().all(|k| *k < count), "{kind}: {named:?} beyond {count}");
    }
}

#[test]
fn a_render_too_large_for_the_page_is_refused() {
    let scene = text(&root().join("scenes/whitted.json"));
    let answer = whitted_web::call(
        json!({"op": "render", "scene": scene, "options": {"size": [65536, 65536]}}).to_string().as_bytes(),
    );
    assert_eq!(answer.code, 2);
    assert!(
        answer.json.contains("render: the page renders at most 8388608 pixels (4096x2048), got 65536x65536"),
        "{}",
        answer.json
    );
    assert!(answer.bytes.is_empty());
    let big = edited(&scene, &[("/camera/resolution", json!([65536, 65536]))]);
    let (code, answer) = call(&json!({"op": "figure", "kind": "heat-map", "scene": big}));
    assert_eq!(code, 2, "{answer}");
    assert!(answer.contains("heat-map: the page renders at most"), "{answer}");
}

#[test]
fn max_events_reaches_the_trace_as_the_command_line_gives_it() {
    let path = root().join("scenes/whitted.json");
    let (scene, file) = (text(&path), path.to_str().unwrap().to_owned());
    let request =
        json!({"op": "trace", "scene": scene, "target": {"pixel": [400, 200]}, "options": {"max_events": 5}});
    let (code, answer) = call(&request);
    let (status, _, err) = whitted(&["trace", &file, "--pixel", "400,200", "--max-events", "5"]);
    assert_eq!((code, status), (2, 2), "{answer} / {err}");
    let message = serde_json::from_str::<Value>(&answer).unwrap()["errors"][0].as_str().unwrap().to_owned();
    assert_eq!(format!("error: {message}\n"), err);
    let request = json!({"op": "narrate", "scene": scene, "target": {"pixel": [1, 2]}, "options": {"max_events": 100000}});
    let (code, answer) = call(&request);
    assert_eq!(code, 0, "{answer}");
    let command = serde_json::from_str::<Value>(&answer).unwrap()["command"].as_str().unwrap().to_owned();
    assert_eq!(command, "whitted trace scene.json --pixel 1,2 --max-events 100000");
}
