//! Every edge of issue 21 (items 1, 2 and 4): negative numbers as arguments, memory refused up
//! front with the number and the option, inputs said exactly. Resource limits are tested with a
//! lowered limit (`--max-events`) or with requests that are refused before any work, so each case
//! is fast.

use crate::support::{whitted, SceneText, Scratch};
use serde_json::json;
use std::path::{Path, PathBuf};

const MIRRORS: &str = "tests/data/limits/mirrors_glass_2d.json";

/// Exit code 2 and the message on stderr: the shape of every refusal.
#[track_caller]
fn refused(args: &[&str], says: &str) {
    let (code, _, err) = whitted(args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert!(err.contains(says), "{args:?}: expected `{says}` in: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
}

#[test]
fn a_ray_whose_first_number_is_negative_is_a_ray_not_a_flag() {
    for ray in [["--ray", "-2,0,0:1,0,0"].as_slice(), ["--ray=-2,0,0:1,0,0"].as_slice()] {
        let args: Vec<&str> = ["trace", "scenes/whitted.json", "--json"].iter().chain(ray).copied().collect();
        let (code, out, err) = whitted(&args);
        assert_eq!(code, 0, "{err}");
        let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(doc["tree"]["origin"], serde_json::json!([-2.0, 0.0, 0.0]));
    }
    let dir = Scratch::new();
    let svg = dir.arg("rays.svg");
    let (code, _, err) =
        whitted(&["figure", "rays", "scenes/flat.json", "--ray", "-0.5,3:0.2,-1", "-o", &svg]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn negative_numbers_reach_their_checks() {
    refused(&["trace", "scenes/whitted.json", "--pixel", "-1,2"], "(-1, 2) is outside the image");
    refused(&["figure", "rays", "scenes/whitted.json", "--pixel", "3,-4"], "(3, -4) is outside the image");
    refused(
        &["render", "scenes/whitted.json", "--depth", "-1"],
        "--depth: expected a whole number in [0, 64]",
    );
    refused(&["render", "scenes/whitted.json", "--size", "-5"], "--size: expected WxH");
    refused(
        &["render", "scenes/whitted.json", "--threads", "-2"],
        "--threads: expected a whole number in [1, 1024]",
    );
    refused(&["trace", "scenes/whitted.json", "--pixel", "1,1", "--max-level", "-1"], "--max-level");
    refused(
        &["trace", "scenes/whitted.json", "--pixel", "1,1", "--accel", "grid", "--grid", "-2,2,2"],
        "--grid",
    );
}

#[test]
fn an_exponential_ray_tree_is_refused_at_its_limit() {
    // 2^51 − 1 rays at depth 50: the log stops at its limit and the trace is refused, with the
    // worst case and both options; a limit of 5 000 keeps the test small.
    let says =
        "outgrew its limit of 5000 recorded events and ray nodes: at depth 50 one ray's tree may hold up \
                to 2.252e15 rays; lower --depth or raise --max-events";
    refused(&["trace", MIRRORS, "--pixel", "4", "--max-events", "5000"], says);
    refused(&["trace", MIRRORS, "--pixel", "4", "--max-events", "5000", "--json"], says);
    refused(
        &["trace", MIRRORS, "--pixel", "4", "--max-events", "5000", "--aa", "corners"],
        "outgrew its limit",
    );
    // Within the limit the same pixel is traced: depth 6 holds 2^7 − 1 = 127 rays at most.
    let (code, out, err) = whitted(&["trace", MIRRORS, "--pixel", "4", "--depth", "6", "--json"]);
    assert_eq!(code, 0, "{err}");
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rays = &doc["stats"]["rays"];
    assert!(rays["reflected"].as_u64().unwrap() + rays["transmitted"].as_u64().unwrap() > 20, "{rays}");
    refused(&["trace", MIRRORS, "--pixel", "4", "--max-events", "0"], "--max-events");
}

#[test]
fn a_figure_of_an_exponential_tree_is_refused_too() {
    let dir = Scratch::new();
    let svg = dir.arg("t.svg");
    refused(&["figure", "ray-tree", MIRRORS, "--pixel", "4", "-o", &svg], "rays; lower --depth");
    assert!(!Path::new(&svg).exists());
}

#[test]
fn what_cannot_fit_in_memory_is_refused_before_the_work() {
    let dir = Scratch::new();
    let png = dir.arg("x.png");
    refused(
        &["render", "scenes/whitted.json", "--size", "65536x65536", "-o", &png],
        "65536x65536 is 4294967296 pixels, more than the limit of 268435456: choose a smaller --size",
    );
    refused(
        &[
            "render",
            "scenes/whitted.json",
            "--size",
            "16384x16384",
            "--aa",
            "adaptive",
            "--max-level",
            "8",
            "-o",
            &png,
        ],
        // More than the 8 GiB cap, or than a smaller machine's memory (`memory::budget`).
        "with adaptive sampling needs about 8.3 GiB, more than the ",
    );
    refused(&["render", "scenes/flat.json", "--size", "65536", "-o", &png], "65536x8192 is 536870912 pixels");
    refused(
        &["tradeoff", "scenes/whitted.json", "--size", "65536x65536"],
        "tradeoff: 65536x65536 is 4294967296 pixels",
    );
    refused(
        &["figure", "rays", "scenes/whitted.json", "--size", "20000", "-o", &png],
        "canvas is more than the",
    );
    let scene = dir.write("huge.json", SceneText::space3(65536, 65536).text());
    refused(&["figure", "heat-map", &scene, "-o", &png], "heat-map: 65536x65536 is 4294967296 pixels");
    refused(&["render", &scene, "-o", &png], "render: 65536x65536");
    assert!(!Path::new(&png).exists());
}

#[test]
fn a_huge_grid_is_not_drawn() {
    let dir = Scratch::new();
    let svg = dir.arg("g.svg");
    refused(
        &["figure", "grid-dda", "lessons/scenes/pitfall.json", "--grid", "4096,4096,1", "-o", &svg],
        "more than the 256 cells an axis may draw legibly; give a smaller --grid",
    );
}

#[test]
fn the_runs_and_threads_are_bounded() {
    refused(
        &["tradeoff", "scenes/whitted.json", "--runs", "101"],
        "--runs: expected a whole number in [1, 100]",
    );
    refused(
        &["tradeoff", "scenes/whitted.json", "--threads", "5000"],
        "--threads: expected a whole number in [1, 1024]",
    );
}

#[test]
fn files_that_are_not_regular_files_are_refused() {
    refused(&["check", "/dev/zero"], "/dev/zero: cannot read the scene: not a regular file");
    refused(&["check", "/tmp"], "not a regular file");
    let dir = Scratch::new();
    let fifo = dir.join("pipe.json");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success());
    if made {
        // Opening a pipe for reading blocks until someone writes: it must be refused before.
        refused(&["check", &fifo.display().to_string()], "not a regular file");
    } else {
        eprintln!("mkfifo unavailable: the named-pipe case is skipped");
    }
    let mesh = dir.write(
        "mesh.json",
        SceneText::space3(4, 4).object(json!({"type": "mesh", "obj": "/dev/zero"})).text(),
    );
    refused(&["check", &mesh], "objects[0].obj");
}

#[test]
fn a_key_written_twice_is_an_error_naming_its_path() {
    let dir = Scratch::new();
    // A key written twice has no JSON value: the fields are written as text.
    let text = SceneText::space3(4, 4).set("/max_depth", json!(2)).text_with(&[
        ("objects", r#"[{"type": "sphere", "center": [0,0,0], "radius": 1, "radius": 2}]"#),
        ("max_depth", "3"),
    ]);
    let scene = dir.write("twice.json", text);
    let (code, _, err) = whitted(&["check", &scene]);
    assert_eq!(code, 2);
    assert!(err.contains("max_depth: written more than once in this object; keep one"), "{err}");
    assert!(err.contains("objects[0].radius: written more than once in this object; keep one"), "{err}");
}

#[test]
fn a_byte_order_mark_is_skipped() {
    let dir = Scratch::new();
    let text = std::fs::read_to_string("scenes/whitted.json").unwrap();
    let scene = dir.write("bom.json", format!("\u{feff}{text}"));
    let (code, out, err) = whitted(&["check", &scene]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("valid"), "{out}");
}

#[test]
fn two_lessons_with_one_name_are_an_error_naming_both_files() {
    let dir = Scratch::new();
    let lessons = dir.join("lessons");
    std::fs::create_dir(&lessons).unwrap();
    let text = std::fs::read_to_string("lessons/01-ray-casting.json").unwrap();
    std::fs::write(lessons.join("01-a.json"), &text).unwrap();
    std::fs::write(lessons.join("02-b.json"), &text).unwrap();
    let out = dir.arg("out");
    let (code, _, err) = whitted(&["lessons", "--lessons", &lessons.display().to_string(), "--out", &out]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("02-b.json: name: `ray-casting` is already the name of"), "{err}");
    assert!(err.contains("01-a.json"), "{err}");
}

#[test]
fn options_another_option_makes_meaningless_are_said_ignored() {
    let (code, _, err) = whitted(&["trace", "scenes/whitted.json", "--pixel", "1,1", "--bounds", "kdop"]);
    assert_eq!(code, 0);
    assert!(err.contains("--bounds applies to --accel bounds only; ignored with --accel bvh"), "{err}");
    let (code, _, err) = whitted(&["trace", "scenes/whitted.json", "--pixel", "1,1", "--grid", "2,2,2"]);
    assert_eq!(code, 0);
    assert!(err.contains("--grid applies to --accel grid only; ignored with --accel bvh"), "{err}");
    let (_, _, err) =
        whitted(&["trace", "scenes/whitted.json", "--pixel", "1,1", "--accel", "grid", "--grid", "2,2,2"]);
    assert!(!err.contains("ignored"), "{err}");
}

/// The lines of ```sh blocks in the README and in docs/ that run `whitted`.
fn documented_examples(root: &Path) -> Vec<(String, String)> {
    let mut files = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    let mut examples = Vec::new();
    for file in files {
        let name = file.strip_prefix(root).unwrap().display().to_string();
        let mut in_sh = false;
        for line in std::fs::read_to_string(&file).unwrap().lines() {
            if line.trim_start().starts_with("```") {
                in_sh = !in_sh && line.trim() == "```sh";
            } else if in_sh && line.contains("whitted ") {
                examples.push((name.clone(), line.trim().to_owned()));
            }
        }
    }
    examples
}

#[test]
fn every_documented_example_runs_as_written() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let examples = documented_examples(root);
    assert!(examples.len() >= 10, "the README's examples were not found: {examples:?}");
    // A folder of its own, with the repository's inputs linked in, so outputs land there.
    let dir = Scratch::new();
    for input in ["scenes", "lessons", "tests"] {
        std::os::unix::fs::symlink(root.join(input), dir.join(input)).unwrap();
    }
    let bin = Path::new(env!("CARGO_BIN_EXE_whitted")).parent().unwrap().display().to_string();
    let path = format!("{bin}:{}", std::env::var("PATH").unwrap_or_default());
    for (file, line) in &examples {
        let out = std::process::Command::new("sh")
            .args(["-c", &format!("set -e; {line}")])
            .current_dir(dir.path())
            .env("PATH", &path)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{file}: `{line}` failed ({}): {err}", out.status);
        assert!(!err.contains("panicked"), "{file}: `{line}`: {err}");
    }
    for written in
        ["whitted.png", "flat.png", "tree.svg", "grid.png", "course/index.html", "tradeoff/sampling.png"]
    {
        assert!(dir.join(written).is_file(), "{written} was not written");
    }
}

/// Arguments a careless or hostile user might add, good and bad.
const EXTRA_ARGS: &[&[&str]] = &[
    &[],
    &["--depth", "-1"],
    &["--depth", "3"],
    &["--depth", "64"],
    &["--pixel", "-1,2"],
    &["--pixel", "1,1"],
    &["--pixel", "1"],
    &["--ray", "-2,0,0:1,0,0"],
    &["--ray", "0,0:0,0"],
    &["--aa", "adaptive", "--max-level", "3"],
    &["--aa", "corners"],
    &["--threshold", "nan"],
    &["--max-level", "9"],
    &["--accel", "grid", "--grid", "2,2,2"],
    &["--accel", "octree"],
    &["--size", "0"],
    &["--size", "4x3"],
    &["--max-events", "10"],
    &["--threads", "0"],
    &["--bogus"],
    &["--lang", "ro"],
];

/// True iff every number in `v` is finite (JSON has no NaN; a bug would have to write a string).
fn json_is_finite(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Number(n) => n.as_f64().is_some_and(f64::is_finite),
        serde_json::Value::String(s) => !s.eq_ignore_ascii_case("nan"),
        serde_json::Value::Array(a) => a.iter().all(json_is_finite),
        serde_json::Value::Object(m) => m.values().all(json_is_finite),
        _ => true,
    }
}

/// The output file after a run: the old bytes, or a whole new PNG or SVG.
fn whole_or_old(path: &Path, old: &[u8]) -> Result<(), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes == old {
        return Ok(());
    }
    match path.extension().and_then(|e| e.to_str()) {
        Some("png") => image::load_from_memory(&bytes).map(|_| ()).map_err(|e| format!("a torn PNG: {e}")),
        _ => {
            let text = String::from_utf8(bytes).map_err(|e| e.to_string())?;
            roxmltree::Document::parse(&text).map(|_| ()).map_err(|e| format!("a torn SVG: {e}"))
        }
    }
}

mod mutated {
    use super::*;
    use crate::properties::{at_mut, paths, wild_value};
    use crate::support::fixture;
    use proptest::prelude::*;
    use serde_json::Value;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

        /// A mutated scene under a command with added arguments: exit 0 or 2 and never a panic, no
        /// NaN in what is printed, and the output file that was there before is either untouched
        /// or replaced by a whole new one.
        #[test]
        fn mutated_scenes_and_arguments_exit_0_or_2_and_keep_outputs_whole(
            which in 0usize..4,
            pick in any::<prop::sample::Index>(),
            value in wild_value(),
            mutate in any::<bool>(),
            command in 0usize..4,
            extra in 0..EXTRA_ARGS.len(),
            extra2 in 0..EXTRA_ARGS.len(),
        ) {
            let name = ["glass.json", "lens_2d.json", "ortho_box.json", "tir_slab_2d.json"][which];
            let mut doc: Value = serde_json::from_str(&fixture(name)).unwrap();
            if mutate {
                let mut all = Vec::new();
                paths(&doc, vec![], &mut all);
                let path = pick.get(&all).clone();
                *at_mut(&mut doc, &path) = value;
            }
            let dir = Scratch::new();
            let scene = dir.write("scene.json", doc.to_string());
            let (png, svg) = (dir.join("out.png"), dir.join("out.svg"));
            let (png_s, svg_s) = (png.display().to_string(), svg.display().to_string());
            let mut args: Vec<&str> = match command {
                0 => vec!["render", &scene, "--size", "8x6", "-o", &png_s, "--json"],
                1 => vec!["trace", &scene, "--json"],
                2 => vec!["figure", "rays", &scene, "--size", "320", "-o", &svg_s],
                _ => vec!["check", &scene],
            };
            args.extend(EXTRA_ARGS[extra]);
            args.extend(EXTRA_ARGS[extra2]);
            // A good file from an earlier run, which the run must keep or replace whole.
            let old_png = std::fs::read("docs/whitted.png").unwrap();
            std::fs::write(&png, &old_png).unwrap();
            let old_svg = b"<svg xmlns=\"http://www.w3.org/2000/svg\"/>".to_vec();
            std::fs::write(&svg, &old_svg).unwrap();

            let (code, out, err) = whitted(&args);
            prop_assert!(code == 0 || code == 2, "{args:?} exited {code}: {err}");
            prop_assert!(!err.contains("panicked"), "{args:?}: {err}");
            if code == 0 && args.contains(&"--json") {
                let printed: Value = serde_json::from_str(&out).map_err(|e| TestCaseError::fail(e.to_string()))?;
                prop_assert!(json_is_finite(&printed), "{args:?}: a NaN in {out}");
            }
            prop_assert!(!out.contains("NaN"), "{args:?}: {out}");
            prop_assert_eq!(whole_or_old(&png, &old_png), Ok(()));
            prop_assert_eq!(whole_or_old(&svg, &old_svg), Ok(()));
        }
    }
}

/// The address space a scene may use, as a multiple of its file's size (on top of the program's
/// own): a 100 MB scene once took 1.6 GB; the compact, deferred tree takes about 3.3 times.
const SCENE_MEMORY_MULTIPLE: u64 = 6;

#[test]
fn a_scene_takes_a_small_multiple_of_its_size() {
    use std::fmt::Write;
    let dir = Scratch::new();
    // 400 000 spheres written as text: the file's size is what the limit is measured against.
    let mut objects = String::from("[");
    for k in 0..400_000u32 {
        let x = f64::from(k % 1000) / 100.0 - 5.0;
        let y = f64::from(k / 1000) / 40.0 - 5.0;
        let sep = if k == 0 { "" } else { "," };
        write!(objects, r#"{sep}{{"type":"sphere","center":[{x:.6},{y:.6},-1.000000],"radius":0.012345}}"#)
            .unwrap();
    }
    objects.push(']');
    let text = SceneText::space3(8, 8).eye(json!([0, 0, 10])).text_with(&[("objects", &objects)]);
    let scene = dir.write("many.json", &text);
    let size = text.len() as u64;
    // ulimit -v counts the program's mapped code and libraries too: 64 MiB for those.
    let limit_kib = (SCENE_MEMORY_MULTIPLE * size + (64 << 20)) >> 10;
    let bin = env!("CARGO_BIN_EXE_whitted");
    let out = std::process::Command::new("sh")
        .args(["-c", &format!("ulimit -v {limit_kib} && exec \"$0\" check \"$1\""), bin, &scene])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{size} bytes of scene in {limit_kib} KiB: {} {err}", out.status);
    assert!(String::from_utf8_lossy(&out.stdout).contains("objects: 400000 (400000 sphere)"));
}

/// Runs the binary with its stdout sent to `stdout`: (exit code, stderr).
fn whitted_into(args: &[&str], stdout: std::process::Stdio) -> (i32, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .stdout(stdout)
        .output()
        .expect("run whitted");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// Every command that prints, with what it needs (issue 33, item 1).
fn printing_commands(dir: &Scratch) -> Vec<Vec<String>> {
    let png = dir.arg("out.png");
    let course = dir.arg("course");
    let none = dir.arg("no.wasm");
    let glass = crate::support::fixture_path("glass.json");
    let lines: [&[&str]; 10] = [
        &["check", "scenes/flat.json"],
        &["trace", &glass, "--pixel", "4,3"],
        &["trace", &glass, "--pixel", "4,3", "--json"],
        &["step", &glass, "--pixel", "4,3"],
        &["render", "scenes/flat.json", "--size", "16", "--json", "-o", &png],
        &["figure", "--list"],
        &["tradeoff", "scenes/flat.json", "--runs", "1", "--size", "8"],
        &["tradeoff", "scenes/flat.json", "--runs", "1", "--size", "8", "--json"],
        &[
            "lessons", "--only", "pixel-uv", "--lang", "en", "--size", "320x180", "--out", &course, "--wasm",
            &none,
        ],
        &["trace", "scenes/flat.json", "--pixel", "30", "--aa", "corners"],
    ];
    lines.iter().map(|l| l.iter().map(|a| (*a).to_owned()).collect()).collect()
}

#[test]
fn a_failed_write_to_stdout_is_an_error_and_a_closed_pipe_is_not() {
    let dir = Scratch::new();
    let full = Path::new("/dev/full");
    for args in printing_commands(&dir) {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        if full.exists() {
            let device = std::fs::OpenOptions::new().write(true).open(full).expect("open /dev/full");
            let (code, err) = whitted_into(&args, device.into());
            assert_eq!(code, 1, "{args:?} > /dev/full: {err}");
            let last = err.lines().last().unwrap_or_default();
            assert!(last.starts_with("error: standard output: cannot write: "), "{args:?}: {err}");
            assert!(!err.contains("panicked"), "{args:?}: {err}");
        }
        // A reader that stops reading (`| head -0`): the answer was not wanted, which is no error.
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_whitted"))
            .args(&args)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("run whitted");
        drop(child.stdout.take());
        let out = child.wait_with_output().expect("run whitted");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?} | head -0: {err}");
        assert!(!err.contains("error: "), "{args:?}: {err}");
    }
    if !full.exists() {
        eprintln!("/dev/full unavailable: only the closed pipe was checked");
    }
}

#[test]
fn names_that_a_terminal_would_execute_are_refused_and_shown_escaped() {
    let dir = Scratch::new();
    let sphere = |name: serde_json::Value| json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "name": name, "material": "m\u{7}"});
    let scene = SceneText::space3(4, 4)
        .material("m\u{7}", json!({"kd": 0.5}))
        .object(sphere(json!("\u{1b}]0;owned\u{7}\u{1b}[2J")))
        .object(sphere(json!({"en": "ok", "ro": "a\u{202e}b"})))
        .light(json!({"position": [0, 5, 5], "name": "key\r"}));
    let path = dir.write("names.json", scene.text());
    for args in
        [vec!["check", &path], vec!["trace", &path, "--pixel", "1,1"], vec!["step", &path, "--pixel", "1,1"]]
    {
        let (code, out, err) = whitted(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{out}");
        let raw = err.chars().find(|c| whitted::format::is_hidden_control(*c) && *c != '\n');
        assert_eq!(raw, None, "a raw control character on stderr: {err:?}");
        for said in [
            "materials.m\\u{7}: a name must not hold a control or bidirectional character, found U+0007",
            "objects[0].name: a name must not hold a control or bidirectional character, found U+001B",
            "objects[1].name.ro: a name must not hold a control or bidirectional character, found U+202E",
            "lights[0].name: a name must not hold a control or bidirectional character, found U+000D",
        ] {
            assert!(err.contains(said), "{args:?}: expected `{said}` in {err}");
        }
    }
    // What is not a scene name (here a file name) is escaped where it is printed: `--json` as
    // `\u202e`, which reads back as the character.
    let flat = dir.write("flat.json", SceneText::flat2(4).text());
    let png = dir.arg("a\u{202e}gnp.png");
    let (code, out, err) = whitted(&["render", &flat, "--json", "-o", &png]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("a\\u202egnp.png") && !out.contains('\u{202e}'), "{out}");
    assert!(err.contains("a\\u{202e}gnp.png") && !err.contains('\u{202e}'), "{err}");
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["output"], png.as_str());
}

/// A lessons folder in `dir` holding the one lesson `text`, for `--lessons`.
fn lesson_folder(dir: &Scratch, text: &str) -> String {
    std::fs::create_dir_all(dir.join("lessons")).unwrap();
    dir.write("lessons/01-a.json", text)
}

#[test]
fn small_holes_in_lessons_check_and_step_are_closed() {
    let dir = Scratch::new();
    // No lesson files: said, exit 2.
    std::fs::create_dir_all(dir.join("empty")).unwrap();
    let out = dir.arg("out");
    refused(
        &["lessons", "--lessons", &dir.arg("empty"), "--out", &out],
        "no lesson files (NAME.json) in the lessons folder",
    );
    // A ray the command shown beside the figure would refuse is refused when the lesson loads.
    let flat = std::fs::canonicalize("scenes/flat.json").unwrap();
    lesson_folder(
        &dir,
        &json!({ "name": "a", "title": { "en": "x", "ro": "y" }, "figures": [ { "kind": "rays",
            "scene": flat, "ray": { "origin": [0, 0], "direction": [0, 0] },
            "caption": { "en": "a", "ro": "b" } } ] })
        .to_string(),
    );
    refused(
        &["lessons", "--lessons", &dir.arg("lessons"), "--out", &out],
        "01-a.json: figures[0].ray: must be { \"origin\": [..], \"direction\": [..] } with a non-zero direction",
    );
    // `check` says when `render` would refuse the scene's own resolution; the scene stays valid.
    let huge = dir.write("huge.json", SceneText::space3(65536, 65536).text());
    let (code, said, err) = whitted(&["check", &huge]);
    assert_eq!(code, 0, "{err}");
    assert!(said.contains("render: refused at this resolution: 65536x65536 is 4294967296 pixels"), "{said}");
    let (_, said, _) = whitted(&["check", "scenes/flat.json"]);
    assert!(!said.contains("refused"), "{said}");
}

#[test]
fn lessons_write_through_a_symbolic_link_inside_their_folder() {
    let dir = Scratch::new();
    std::fs::create_dir_all(dir.join("out/en")).unwrap();
    std::fs::create_dir_all(dir.join("kept")).unwrap();
    std::fs::write(dir.join("kept/uv.png"), b"old").unwrap();
    let link = dir.join("out/en/pixel-uv-1-uv-map.png");
    std::os::unix::fs::symlink("../../kept/uv.png", &link).unwrap();
    let none = dir.arg("no.wasm");
    let (code, _, err) = whitted(&[
        "lessons",
        "--only",
        "pixel-uv",
        "--lang",
        "en",
        "--size",
        "320x180",
        "--out",
        &dir.arg("out"),
        "--wasm",
        &none,
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "the link was replaced");
    assert!(std::fs::read(dir.join("kept/uv.png")).unwrap().starts_with(b"\x89PNG"), "not written through");
}

/// Runs the binary under an address-space limit of `kib` KiB (`ulimit -v`): (exit code, stderr).
fn whitted_limited(kib: u64, args: &[&str]) -> (i32, String) {
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .output()
        .expect("run sh");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The address-space limit these tests run under: room for the binary (it runs `check` in well
/// under 150 MiB), not for what they ask.
const LIMITED_KIB: u64 = 400 << 10;

#[test]
fn meshes_figures_and_traces_are_estimated_against_the_memory_the_process_has() {
    let dir = Scratch::new();
    // 3 000 001 triangles in 6 MB: a face fanned over two vertices named again and again. The counts
    // alone (480 MB) are more than the address space left, so nothing is parsed.
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3");
    obj.push_str(&" 2 3".repeat(1_500_000));
    obj.push('\n');
    dir.write("big.obj", &obj);
    let scene = dir
        .write("mesh.json", SceneText::space3(8, 8).object(json!({"type": "mesh", "obj": "big.obj"})).text());
    let (code, err) = whitted_limited(LIMITED_KIB, &["check", &scene]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("objects[0].obj: big.obj: 3 vertices and 3000001 triangles needs about 458 MiB")
            && err.contains("of address space left under the process's limit (ulimit -v): use a mesh with fewer triangles"),
        "{err}"
    );
    // A figure of 200 000 spheres (600 MB by the count): refused before its structure is built.
    let spheres: Vec<serde_json::Value> = (0..200_000)
        .map(|k| json!({"type": "sphere", "center": [f64::from(k % 500) * 0.01, f64::from(k / 500) * 0.01, -1], "radius": 0.004}))
        .collect();
    let many = dir.write("many.json", SceneText::space3(8, 8).objects(spheres).text());
    let svg = dir.arg("bvh.svg");
    let (code, err) = whitted_limited(LIMITED_KIB, &["figure", "bvh", &many, "-o", &svg]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("a bvh figure of 200000 objects and triangles needs about"), "{err}");
    assert!(err.contains("draw a scene with fewer objects"), "{err}");
    assert!(!Path::new(&svg).exists());
    // `--max-events` at its maximum: its memory is said before the trace.
    refused(
        &["trace", "scenes/flat.json", "--pixel", "30", "--max-events", "100000000"],
        "a trace of up to 100000000 events (--max-events, about 4096 bytes each) needs about 381.5 GiB",
    );
}

#[test]
fn a_trace_that_outgrows_its_limit_is_told_what_filled_it() {
    // 2 000 spheres tested one by one (`--accel none`): the object tests fill the log, not the tree.
    let spheres: Vec<serde_json::Value> = (0..2000)
        .map(|k| json!({"type": "sphere", "center": [f64::from(k) * 0.001, 50, -5], "radius": 0.0001}))
        .collect();
    let dir = Scratch::new();
    let scene = dir.write("tests.json", SceneText::space3(4, 4).objects(spheres).text());
    refused(
        &["trace", &scene, "--pixel", "1,1", "--accel", "none", "--max-events", "1000"],
        "of them are object tests: a ray tests the objects its structure gives it; trace with a structure \
         that tests fewer (--accel bvh) or raise --max-events",
    );
    let (_, _, err) =
        whitted(&["trace", &scene, "--pixel", "1,1", "--accel", "none", "--max-events", "1000"]);
    assert!(!err.contains("--depth"), "{err}");
}
