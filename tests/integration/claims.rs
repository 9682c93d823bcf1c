//! Lesson claims (product.md "Lessons", `lesson::claim`): every figure of every lesson states what
//! it must show and shows it; the old scenes and pixels that did not show their point fail.

use std::path::Path;
use whitted::accel::AccelOptions;
use whitted::figure::source::Tracing;
use whitted::figure::{Lang, Options};
use whitted::lesson::claim::Verdict;
use whitted::lesson::{self, FigureSpec};
use whitted::request::figure::{figure_checked, Request};
use whitted::request::target::Target;
use whitted::sample::Sampling;
use whitted::scene::load::load_str;

/// The verdicts of one lesson figure's claims, drawn as `whitted lessons` draws it (no PNG).
fn verdicts(dir: &Path, spec: &FigureSpec, lang: Lang) -> Vec<Verdict> {
    let scene = load_str(&std::fs::read_to_string(dir.join(&spec.scene)).unwrap()).unwrap();
    let signed = |k: usize| i64::try_from(k).unwrap();
    let request = Request {
        kind: spec.kind,
        target: Target { pixel: spec.pixel.map(|(i, j)| (signed(i), j.map(signed))), ray: spec.ray.clone() },
        tracing: Tracing {
            depth: spec.depth,
            sampling: spec.sampling.unwrap_or(Sampling::Center),
            accel: AccelOptions { grid: spec.grid.clone(), ..Tracing::SCENE.accel },
        },
        opts: Options::slide(lang),
    };
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
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
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
