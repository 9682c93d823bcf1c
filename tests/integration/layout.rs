//! Layout (issue 23 item 9): in every lesson figure, in both languages, at slide size, no label
//! is printed on top of another — checked on the display list's placed boxes.

use crate::support::lesson_files;
use std::path::Path;
use whitted::canvas::{Drawing, Mark};
use whitted::figure::{Lang, Options};
use whitted::lesson;
use whitted::request::figure::{figure, Request};
use whitted::scene::load::load_str;

/// Every lesson figure as `whitted lessons` draws it at slide size: `(name, drawing)`.
fn lesson_figures(lang: Lang) -> Vec<(String, Drawing)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut out = Vec::new();
    for (_, text) in lesson_files() {
        let lesson = lesson::parse(&text).unwrap();
        for (k, spec) in lesson.figures.iter().enumerate() {
            let scene = load_str(&std::fs::read_to_string(dir.join(&spec.scene)).unwrap()).unwrap();
            let request = Request::of_lesson(spec, Options::slide(lang));
            let made = figure(&scene, "scene", &request).unwrap();
            out.push((
                format!("{}-{}-{} ({})", lesson.name, k + 1, spec.kind.name(), lang.code()),
                made.drawing,
            ));
        }
    }
    out
}

/// The text of item `k`.
fn text_of(d: &Drawing, k: usize) -> String {
    match &d.items[k].mark {
        Mark::Text(t) => format!("{:?} [{}]", t.text, d.items[k].tag),
        _ => String::new(),
    }
}

#[test]
fn no_label_of_any_lesson_figure_lies_on_another() {
    let mut found = Vec::new();
    for lang in [Lang::En, Lang::Ro] {
        for (name, d) in lesson_figures(lang) {
            for (a, b) in d.overlapping_labels() {
                found.push(format!("{name}: {} over {}", text_of(&d, a), text_of(&d, b)));
            }
        }
    }
    assert!(found.is_empty(), "{} overlaps:\n{}", found.len(), found.join("\n"));
}

/// A view window drawn on a figure is named, in its legend or on the drawing (the rays figures
/// drew it unnamed).
#[test]
fn every_drawn_view_window_is_named_in_the_legend() {
    for (lang, word) in [(Lang::En, "view window"), (Lang::Ro, "fereastra vizuală")] {
        for (name, d) in lesson_figures(lang) {
            if d.tagged("window").next().is_some() {
                let labelled = d.items.iter().any(|i| matches!(&i.mark, Mark::Text(t) if t.text == word));
                let in_legend = d.legend.iter().any(|e| e.label == word);
                assert!(labelled || in_legend, "{name}: the window is not named");
            }
        }
    }
}
