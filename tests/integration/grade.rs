//! `whitted grade` (docs/grading.md) against the student's tracer of `examples/student/`: its
//! correct documents pass on 2D and 3D lesson scenes, with glass and without; each classic
//! mistake is found at the ray where it first shows, with its diagnosis, in both languages; a
//! bad document is refused with every error's JSON path.

use crate::support::{whitted, Scratch};
use serde_json::Value;
use std::path::Path;
use std::process::Command;

const TRACER: &str = "examples/student/tracer.py";
const SPHERES: &str = "lessons/scenes/spheres.json";
const WHITTED: &str = "lessons/scenes/whitted_small.json";
const SHADOWS: &str = "lessons/scenes/shadows_2d.json";
const PRISM: &str = "lessons/scenes/prism_2d.json";
const MIRRORS: &str = "lessons/scenes/mirrors_2d.json";
/// The grid lesson's scene.
const GROUPS: &str = "lessons/scenes/groups_2d.json";
/// Attenuated lights and an I_local above 1: what no lesson scene shows.
const LAMP: &str = "tests/data/grade/lamp.json";

/// The student's document of one pixel, with a mistake or none, written in `scratch`.
fn student(scratch: &Scratch, scene: &str, pixel: &str, mistake: Option<&str>) -> String {
    let mut cmd = Command::new("python3");
    cmd.current_dir(env!("CARGO_MANIFEST_DIR")).args([TRACER, scene, "--pixel", pixel]);
    if let Some(m) = mistake {
        cmd.args(["--mistake", m]);
    }
    let out = cmd.output().expect("python3 runs the student's tracer");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let name = format!("{}-{}-{}.json", scene.replace('/', "_"), pixel, mistake.unwrap_or("correct"));
    scratch.write(&name, out.stdout)
}

fn scene_path(scene: &str) -> String {
    format!("{}/{scene}", env!("CARGO_MANIFEST_DIR"))
}

fn grade_json(scene: &str, doc: &str) -> (i32, Value) {
    let (code, out, err) = whitted(&["grade", &scene_path(scene), doc, "--json"]);
    assert!(err.is_empty(), "{err}");
    (code, serde_json::from_str(&out).expect("grade --json prints JSON"))
}

#[test]
fn the_students_correct_tracer_agrees_in_2d_and_3d_with_glass_and_mirrors() {
    let scratch = Scratch::new();
    for (scene, pixel, at_least) in [
        (SPHERES, "7,5", 20),
        (WHITTED, "93,66", 70),
        (SHADOWS, "10", 60),
        (PRISM, "4", 60),
        (MIRRORS, "0", 40),
        (LAMP, "8,7", 18),
    ] {
        let doc = student(&scratch, scene, pixel, None);
        let (code, report) = grade_json(scene, &doc);
        assert_eq!(code, 0, "{scene} {pixel}: {report:#}");
        assert_eq!(report["ok"], true);
        assert!(report["first"].is_null());
        assert!(report["checked"].as_u64().unwrap() >= at_least, "{scene}: {report}");
        assert_eq!(report["not_checked"], serde_json::json!([]), "the tracer writes every field");
    }
}

/// Each classic mistake, where it first shows: (mistake, scene, pixel, ray, quantity). Every
/// mistake appears at least once; most on the three scenes of the acceptance table.
const CASES: &[(&str, &str, &str, &str, &str)] = &[
    ("unnormalized-direction", SPHERES, "7,5", "P", "direction"),
    ("unnormalized-direction", WHITTED, "93,66", "P", "direction"),
    ("unnormalized-direction", SHADOWS, "10", "P", "direction"),
    ("unnormalized-normal", SPHERES, "7,5", "P", "normal"),
    ("unnormalized-normal", WHITTED, "93,66", "P", "normal"),
    ("unnormalized-normal", SHADOWS, "10", "P", "normal"),
    ("normal-not-flipped", WHITTED, "93,66", "T₁", "n_dot_l"),
    ("normal-not-flipped", SHADOWS, "10", "T₁", "n_dot_l"),
    ("inverted-eta", WHITTED, "93,66", "T₁", "direction"),
    ("inverted-eta", SHADOWS, "10", "T₁", "direction"),
    ("no-tir", PRISM, "4", "T₄", "extra"),
    ("reflect-sign", SPHERES, "7,5", "R₁", "direction"),
    ("reflect-sign", WHITTED, "93,66", "R₁", "direction"),
    ("reflect-sign", SHADOWS, "10", "R₁", "direction"),
    ("no-shadow-offset", SPHERES, "8,6", "P", "shadow"),
    ("no-shadow-offset", SHADOWS, "12", "P", "shadow"),
    ("occluders-beyond-light", MIRRORS, "1", "P", "shadow"),
    ("no-half-pixel", SPHERES, "7,5", "P", "window_point"),
    ("no-half-pixel", WHITTED, "93,66", "P", "window_point"),
    ("no-half-pixel", SHADOWS, "10", "P", "window_point"),
    ("rows-from-top", SPHERES, "7,5", "P", "window_point"),
    ("rows-from-top", WHITTED, "93,66", "P", "window_point"),
    ("phong-rv", SPHERES, "7,5", "P", "local"),
    ("phong-rv", SHADOWS, "10", "P", "local"),
    ("phong-rv", LAMP, "8,7", "P", "local"),
    ("no-attenuation", LAMP, "8,7", "P", "local"),
    ("unclamped-attenuation", LAMP, "8,7", "P", "local"),
    ("depth-off-by-one", WHITTED, "93,66", "R₄", "missing"),
    ("depth-off-by-one", SHADOWS, "10", "R₃", "missing"),
    ("transmit-kt0", SPHERES, "7,5", "T₂", "extra"),
    ("transmit-kt0", WHITTED, "93,66", "T₇", "extra"),
    ("transmit-kt0", SHADOWS, "10", "T₅", "extra"),
    ("local-twice", SPHERES, "7,5", "R₁", "colour"),
    ("local-twice", WHITTED, "93,66", "R₄", "colour"),
    ("local-twice", SHADOWS, "10", "R₃", "colour"),
    ("clamp-before-sum", SHADOWS, "10", "T₂", "colour"),
    ("clamp-before-sum", LAMP, "8,7", "P", "colour"),
];

#[test]
fn each_classic_mistake_is_named_at_the_ray_where_it_first_shows() {
    let scratch = Scratch::new();
    let mut failures = Vec::new();
    for &(mistake, scene, pixel, ray, quantity) in CASES {
        let doc = student(&scratch, scene, pixel, Some(mistake));
        let (code, report) = grade_json(scene, &doc);
        let first = &report["first"];
        let got = (code, first["diagnosis"].as_str(), first["ray"].as_str(), first["quantity"].as_str());
        if got != (1, Some(mistake), Some(ray), Some(quantity)) {
            failures.push(format!("{mistake} on {scene} {pixel}: got {got:?}"));
        }
        assert!(first["step"].as_u64().is_some_and(|k| k > 0), "{mistake}: a step of the narration");
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn every_mistake_has_a_case_and_a_switch_in_the_students_tracer() {
    let out = Command::new("python3")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([TRACER, "--list-mistakes"])
        .output()
        .expect("python3 runs");
    let listed = String::from_utf8_lossy(&out.stdout);
    for m in whitted::grade::Mistake::ALL {
        assert!(CASES.iter().any(|c| c.0 == m.name()), "{} has no case", m.name());
        assert!(listed.lines().any(|l| l.split_whitespace().next() == Some(m.name())), "{}", m.name());
    }
}

#[test]
fn the_report_says_the_divergence_in_english_and_in_romanian() {
    let scratch = Scratch::new();
    let doc = student(&scratch, WHITTED, "93,66", Some("inverted-eta"));
    let (code, en, _) = whitted(&["grade", &scene_path(WHITTED), &doc]);
    assert_eq!(code, 1);
    for needle in
        ["First divergence, step 18 (P → T₁, level 2): T₁ — direction", "η was taken as n₂/n₁", "n2 = 1.5"]
    {
        assert!(en.contains(needle), "{needle} in\n{en}");
    }
    let (code, ro, _) = whitted(&["grade", &scene_path(WHITTED), &doc, "--lang", "ro"]);
    assert_eq!(code, 1);
    for needle in
        ["Prima divergență, pasul 18 (P → T₁, nivelul 2): T₁ — direcția", "η a fost luat n₂/n₁", "regula"]
    {
        assert!(ro.contains(needle), "{needle} in\n{ro}");
    }
    let (code, ok, _) =
        whitted(&["grade", &scene_path(WHITTED), &student(&scratch, WHITTED, "93,66", None), "--lang", "ro"]);
    assert_eq!(code, 0);
    assert!(ok.contains("Totul coincide: 78 de mărimi verificate."), "{ok}");
}

#[test]
fn a_bad_document_is_refused_with_every_error_and_its_path() {
    let scratch = Scratch::new();
    let doc = scratch.write(
        "bad.json",
        r#"{"pixel": [99, 0], "ray": {"origin": [0, 0, 6], "direction": [0, 0],
            "hit": {"object": "middle", "t": "far"}, "reflected": {"colour": [1, 2]}}, "color": [0, 0, 0]}"#,
    );
    let (code, out, err) = whitted(&["grade", &scene_path(SPHERES), &doc]);
    assert_eq!(code, 2, "{out}");
    assert!(out.is_empty());
    for needle in [
        "bad.json: pixel[0]: 99 is outside the image: must be below 16",
        "bad.json: color: unknown field `color`; did you mean `colour`?",
        "bad.json: ray.hit.t: must be a number, got a string",
        "bad.json: ray.reflected.colour: must have 3 numbers, got 2",
        "bad.json: ray.direction: must have 3 numbers, got 2",
        "bad.json: colour: missing (required)",
    ] {
        assert!(err.contains(needle), "{needle} in\n{err}");
    }
    let (code, _, err) = whitted(&["grade", &scene_path(SPHERES), &doc, "--tolerance", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--tolerance must be in (0, 1), got 0"), "{err}");
}

#[test]
fn exercise_sheets_ask_six_to_ten_questions_and_answer_them_with_the_narrations_steps() {
    let scratch = Scratch::new();
    for (scene, pixel, lang, step) in
        [(WHITTED, "93,66", "en", "Step 1 —"), (SHADOWS, "10", "ro", "Pasul 1 —")]
    {
        let out = scratch.arg(lang);
        let (code, said, err) =
            whitted(&["exercises", &scene_path(scene), "--pixel", pixel, "--lang", lang, "--out", &out]);
        assert_eq!(code, 0, "{err}");
        let exercises = std::fs::read_to_string(scratch.join(lang).join("exercises.html")).unwrap();
        let answers = std::fs::read_to_string(scratch.join(lang).join("answers.html")).unwrap();
        let count = exercises.matches("<li>").count();
        assert!((6..=10).contains(&count), "{count} questions");
        assert_eq!(answers.matches("<li>").count(), count);
        assert!(said.starts_with(&format!("{count} questions")), "{said}");
        assert!(exercises.contains("<svg") && answers.contains("<svg"), "figures inline");
        assert!(answers.contains(step), "each answer is a step of the narration");
        assert!(!exercises.contains(step), "the sheet holds no answer");
        // The same seed gives the same sheets.
        let again = scratch.arg(&format!("{lang}-again"));
        whitted(&["exercises", &scene_path(scene), "--pixel", pixel, "--lang", lang, "--out", &again]);
        assert_eq!(
            std::fs::read_to_string(scratch.join(format!("{lang}-again")).join("answers.html")).unwrap(),
            answers
        );
    }
    let ro = std::fs::read_to_string(scratch.join("ro").join("exercises.html")).unwrap();
    assert!(ro.contains("calculați") && ro.contains("lang=\"ro\""));
}

#[test]
fn a_lessons_exercise_sheets_are_written_beside_its_pages_and_linked() {
    let scratch = Scratch::new();
    let out = scratch.arg("course");
    let (code, _, err) = whitted(&["lessons", "--only", "ray-tree", "--out", &out, "--size", "640x360"]);
    assert_eq!(code, 0, "{err}");
    for (lang, words) in [("en", "sheet 1"), ("ro", "fișa 1")] {
        let dir = scratch.join("course").join(lang);
        let page = std::fs::read_to_string(dir.join("ray-tree.html")).unwrap();
        assert!(page.contains("href=\"ray-tree-exercises-1.html\"") && page.contains(words), "{lang}");
        let sheet = std::fs::read_to_string(dir.join("ray-tree-exercises-1.html")).unwrap();
        assert!(sheet.contains(&format!("lang=\"{lang}\"")) && sheet.contains("(100, 60)"));
        assert!(dir.join("ray-tree-answers-1.html").exists());
    }
}

/// The page's `grade` op (web/, called natively) answers `whitted grade --json` and prints its
/// report, both languages, for a correct document and a mistaken one; the stored documents the
/// page's tests paste are the student tracer's output.
#[test]
fn the_page_grades_with_the_same_library_code_as_the_command_line() {
    let scratch = Scratch::new();
    let scene = std::fs::read_to_string(scene_path(WHITTED)).unwrap();
    for mistake in [None, Some("inverted-eta")] {
        let doc = student(&scratch, WHITTED, "93,66", mistake);
        let text = std::fs::read_to_string(&doc).unwrap();
        for lang in ["en", "ro"] {
            let request = serde_json::json!({"op": "grade", "scene": scene, "student": text, "lang": lang});
            let answer = whitted_web::call(request.to_string().as_bytes());
            assert_eq!(answer.code, 0, "{}", answer.json);
            let mut page: Value = serde_json::from_str(&answer.json).unwrap();
            let page = page.as_object_mut().unwrap();
            let report = page.remove("text").unwrap();
            page.remove("words");
            page.remove("page_step");
            let (code, cli, _) = whitted(&["grade", &scene_path(WHITTED), &doc, "--lang", lang]);
            assert_eq!(code, i32::from(mistake.is_some()));
            assert_eq!(report.as_str(), Some(cli.as_str()), "{lang}");
            let (_, cli_json, _) = whitted(&["grade", &scene_path(WHITTED), &doc, "--lang", lang, "--json"]);
            let cli_json: Value = serde_json::from_str(&cli_json).unwrap();
            assert_eq!(Value::Object(page.clone()), cli_json, "{lang}");
        }
    }
    for (stored, mistake) in [
        ("tests/data/grade/whitted-422-292.json", None),
        ("tests/data/grade/whitted-422-292-reflect-sign.json", Some("reflect-sign")),
    ] {
        let made = student(&scratch, "scenes/whitted.json", "422,292", mistake);
        let stored = std::fs::read_to_string(scene_path(stored)).unwrap();
        assert_eq!(
            std::fs::read_to_string(made).unwrap(),
            stored,
            "regenerate it with examples/student/tracer.py"
        );
    }
}

/// The numbers inside the first `(…)` or `[…]` after `key` in `text`.
fn numbers_after(text: &str, key: &str, open: char, close: char) -> Vec<f64> {
    let at = text.find(key).unwrap_or_else(|| panic!("`{key}` in {text}")) + key.len();
    let from = at + text[at..].find(open).unwrap() + open.len_utf8();
    let to = from + text[from..].find(close).unwrap();
    text[from..to].split(", ").map(|x| x.replace('−', "-").parse().unwrap()).collect()
}

/// Issue 31 item 6's grid question: with `--accel grid` a sheet asks which voxel the ray enters
/// next, with the cell, D, tMax and tDelta; its answer is the cell's step (exit at min tMax) and
/// the next cell's, which is the DDA's step along the axis of the least tMax by the sign of D.
#[test]
fn a_grid_sheet_asks_which_voxel_the_ray_enters_next_and_answers_with_the_walk() {
    let scratch = Scratch::new();
    for (scene, pixel, seed) in
        [(GROUPS, "10", "1"), (GROUPS, "10", "2"), (GROUPS, "10", "5"), (WHITTED, "93,66", "1")]
    {
        let out = scratch.arg(&format!("{seed}-{}", pixel.replace(',', "-")));
        let (code, _, err) = whitted(&[
            "exercises",
            &scene_path(scene),
            "--pixel",
            pixel,
            "--accel",
            "grid",
            "--seed",
            seed,
            "--out",
            &out,
        ]);
        assert_eq!(code, 0, "{err}");
        let exercises = std::fs::read_to_string(Path::new(&out).join("exercises.html")).unwrap();
        assert_eq!(exercises.matches("which voxel does it enter next").count(), 1, "{scene} {seed}");
        let answers = std::fs::read_to_string(Path::new(&out).join("answers.html")).unwrap();
        let item = answers.split("<li>").find(|li| li.contains("which voxel does it enter next")).unwrap();
        let cell = numbers_after(item, "is in voxel", '[', ']');
        let d = numbers_after(item, "D = ", '(', ')');
        let t_max = numbers_after(item, "tMax = ", '(', ')');
        let axis = (0..t_max.len()).min_by(|&a, &b| t_max[a].total_cmp(&t_max[b])).unwrap();
        let mut next = cell.clone();
        next[axis] += d[axis].signum();
        let text = |v: &[f64]| v.iter().map(|x| format!("{x}")).collect::<Vec<_>>().join(", ");
        let steps: Vec<&str> = item.split("<pre>").skip(1).collect();
        assert_eq!(steps.len(), 2, "the cell's step and the next cell's: {item}");
        assert!(steps[0].contains(&format!("Voxel [{}]", text(&cell))), "{}", steps[0]);
        let exit = whitted::format::narration_number(t_max[axis]);
        assert!(steps[0].contains(&format!("leaves the voxel at t = {exit}")), "{}", steps[0]);
        assert!(steps[1].contains(&format!("Voxel [{}]", text(&next))), "{} → {}", text(&cell), steps[1]);
    }
    // Without the grid, no such question.
    let out = scratch.arg("bvh");
    whitted(&["exercises", &scene_path(GROUPS), "--pixel", "10", "--out", &out]);
    let exercises = std::fs::read_to_string(Path::new(&out).join("exercises.html")).unwrap();
    assert!(!exercises.contains("voxel"));
}
