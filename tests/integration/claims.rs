//! Lesson claims (product.md "Lessons", `lesson::claim`): every figure of every lesson states what
//! it must show and shows it; the old scenes and pixels that did not show their point fail.

use crate::support::lesson_files;
use std::path::Path;
use whitted::figure::{Lang, Options};
use whitted::lesson::claim::Verdict;
use whitted::lesson::{self, FigureSpec};
use whitted::request::figure::{figure_checked, Request};
use whitted::scene::load::load_str;

/// The verdicts of one lesson figure's claims, drawn as `whitted lessons` draws it (no PNG).
fn verdicts(dir: &Path, spec: &FigureSpec, lang: Lang) -> Vec<Verdict> {
    let scene = load_str(&std::fs::read_to_string(dir.join(&spec.scene)).unwrap()).unwrap();
    let request = Request::of_lesson(spec, Options::slide(lang));
    figure_checked(&scene, "scene", &request, &spec.claims).unwrap().1
}

/// The failed claims of a lesson's figures, as `whitted lessons` words them.
fn failures(dir: &Path, text: &str, lang: Lang) -> Vec<String> {
    let lesson = lesson::parse(text).unwrap_or_else(|e| panic!("{e:?}"));
    let mut failed = Vec::new();
    for (k, spec) in lesson.figures.iter().enumerate() {
        for v in verdicts(dir, spec, lang).iter().filter(|v| !v.holds()) {
            failed.push(v.message(&lesson.name, k + 1, spec.kind.name()));
        }
    }
    failed
}

#[test]
fn every_lesson_figure_states_its_point_and_shows_it_in_both_languages() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut failed = Vec::new();
    for (path, text) in lesson_files() {
        let lesson = lesson::parse(&text).unwrap();
        for (k, spec) in lesson.figures.iter().enumerate() {
            assert!(!spec.claims.is_empty(), "{} figure {}: no claim", path.display(), k + 1);
        }
        for lang in [Lang::En, Lang::Ro] {
            failed.extend(failures(&dir, &text, lang));
        }
    }
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}

/// Numbers keep the decimal point in both languages (docs/algorithm.md, the lecture's `i + 0.5`):
/// a Romanian caption that wrote 0,5 beside a figure that writes 0.5 would teach two notations.
#[test]
fn every_lesson_writes_numbers_with_the_decimal_point_in_both_languages() {
    let mut found = Vec::new();
    for (path, text) in lesson_files() {
        let lesson = lesson::parse(&text).unwrap();
        let captions = lesson.figures.iter().map(|f| &f.caption);
        for words in [&lesson.title, &lesson.text].into_iter().chain(captions) {
            for text in [&words.en, &words.ro] {
                let chars: Vec<char> = text.chars().collect();
                let comma =
                    chars.windows(3).any(|w| w[0].is_ascii_digit() && w[1] == ',' && w[2].is_ascii_digit());
                if comma {
                    found.push(format!("{}: {text}", path.display()));
                }
            }
        }
    }
    assert!(found.is_empty(), "a decimal comma:\n{}", found.join("\n"));
}

/// A lesson scene names its objects in both languages (`{ "en": "mirror", "ro": "oglindă" }`): a
/// Romanian figure that labels "ball" teaches in two languages at once. Letters and codes (`a`,
/// `A`, `o12`) are the same in both and may stay one string.
#[test]
fn every_lesson_scene_names_its_objects_in_both_languages() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/scenes");
    let mut english_only = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let scene: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        for object in scene["objects"].as_array().into_iter().flatten() {
            if let Some(name) = object["name"].as_str() {
                let code = name.chars().count() <= 1 || name.chars().skip(1).all(|c| c.is_ascii_digit());
                if !code {
                    english_only.push(format!("{}: {name}", path.display()));
                }
            }
        }
    }
    assert!(english_only.is_empty(), "named in one language only:\n{}", english_only.join("\n"));
}

/// The old scenes and pixels that did not show their point (issue "taught right", item 1), each
/// with the claim that now fails on it: the grid pitfall whose first voxel already held the
/// nearer sphere (its box leaked into it, the ray ran along a cell boundary), the 3D slab chart
/// of a near-axis ray, the flat heat map of corner sampling, the BVH of one node, and Whitted's
/// shadow figure whose primary ray was drawn through the glass sphere, and the 2D local model
/// whose L and N lay 3.25° apart — the same hit on the mirror that the ray-casting lesson drew,
/// its N hidden under L.
#[test]
fn the_old_scenes_and_pixels_fail_their_claims() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/claims");
    let old = r#"{ "name": "old", "title": { "en": "old", "ro": "vechi" }, "figures": [
        { "kind": "grid-dda", "scene": "pitfall-old.json", "grid": [4, 4, 4],
          "claims": [ { "kind": "grid-pitfall", "min": 1 } ],
          "caption": { "en": "", "ro": "" } },
        { "kind": "slab-test", "scene": "../../../scenes/whitted.json",
          "claims": [ { "kind": "intervals", "min": 5 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "heat-map", "scene": "../../../lessons/scenes/whitted_small.json", "aa": "corners",
          "claims": [ { "kind": "heat-values", "min": 3 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "bvh", "scene": "../../../scenes/whitted.json",
          "claims": [ { "kind": "nodes", "min": 5 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "shadows", "scene": "../../../scenes/whitted.json", "pixel": [292, 227],
          "claims": [ { "kind": "false-crossings", "max": 0 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "local-model", "scene": "../../../scenes/flat.json", "pixel": [20],
          "claims": [ { "kind": "apart", "min": 10 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "refraction", "scene": "prism-old.json",
          "claims": [ { "kind": "incidence", "min": 20, "max": 60 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "rays", "scene": "../../../scenes/flat.json", "pixel": [20], "depth": 0,
          "claims": [ { "kind": "apart", "min": 10 } ], "caption": { "en": "", "ro": "" } },
        { "kind": "bvh", "scene": "../../../lessons/scenes/crowd_2d.json", "pixel": [13],
          "claims": [ { "kind": "events", "event": "hit", "min": 1 } ], "caption": { "en": "", "ro": "" } } ] }"#;
    let failed = failures(&dir, old, Lang::En);
    let expected = [
        "old figure 1 (grid-dda): claim grid-pitfall (voxels from the early find to the accepted hit): wanted ≥ 1, measured 0",
        "old figure 2 (slab-test): claim intervals",
        "old figure 3 (heat-map): claim heat-values: wanted ≥ 3, measured 1",
        "old figure 4 (bvh): claim nodes: wanted ≥ 5, measured 1",
        "old figure 5 (shadows): claim false-crossings: wanted ≤ 0, measured 1",
        "old figure 6 (local-model): claim apart (least angle between N, V, L, H, °): wanted ≥ 10, measured 3.25",
        "old figure 7 (refraction): claim incidence",
        "old figure 8 (rays): claim apart (least angle between N, V, L, H, °): wanted ≥ 10, measured 3.25",
        "old figure 9 (bvh): claim events hit: wanted ≥ 1, measured 0",
    ];
    assert_eq!(failed.len(), expected.len(), "{}", failed.join("\n"));
    for (line, want) in failed.iter().zip(expected) {
        assert!(line.starts_with(want), "{line}\nwanted it to start with {want}");
    }
}

#[test]
fn lessons_writes_nothing_and_exits_1_when_a_claim_fails() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tmp = crate::support::Scratch::new();
    let lessons = tmp.join("lessons");
    std::fs::create_dir(&lessons).unwrap();
    let scene = root.join("scenes/whitted.json");
    let text = format!(
        r#"{{ "name": "one", "title": {{ "en": "t", "ro": "t" }}, "figures": [
            {{ "kind": "bvh", "scene": "{}", "claims": [ {{ "kind": "nodes", "min": 5 }} ],
               "caption": {{ "en": "", "ro": "" }} }} ] }}"#,
        scene.display()
    );
    std::fs::write(lessons.join("one.json"), text).unwrap();
    let out = tmp.join("out");
    let (code, _, err) = crate::support::whitted(&[
        "lessons",
        "--lessons",
        lessons.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--lang",
        "en",
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("one figure 1 (bvh): claim nodes: wanted ≥ 5, measured 1"), "{err}");
    assert!(!out.join("en/one-1-bvh.png").exists() && !out.join("index.html").exists());
}
