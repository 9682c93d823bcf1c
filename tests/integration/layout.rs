//! Layout (issue 23 item 9): in every lesson figure, in both languages, at slide size, no label
//! is printed on top of another — checked on the display list's placed boxes; and a shadows
//! figure keeps its point large however far its light.

use crate::support::lesson_files;
use glam::DVec2;
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

/// The least share of the plot area's smaller side that the point of a shadows figure must
/// span: the hit, the points where L meets an occluder, and the occluders (drawn in those
/// points' colour). Whitted's scene with its light fitted gave 0.27; the 2D lesson scene, whose
/// light is near, 0.39.
const MIN_POINT_SHARE: f64 = 0.35;

/// The larger side of the pixel box of a shadows figure's point, per the plot's smaller side.
fn point_share(d: &Drawing) -> f64 {
    let frame = d.frame();
    let tf = frame.transform;
    let occluder_colour = d.tagged("occluder-point").find_map(|item| match item.mark {
        Mark::Dot { fill, .. } => Some(fill),
        _ => None,
    });
    let mut px: Vec<DVec2> = Vec::new();
    for item in &d.items {
        match &item.mark {
            Mark::Dot { center, .. } if item.tag == "hit" || item.tag == "occluder-point" => {
                px.push(tf.to_px(*center));
            }
            Mark::Circle { center, radius, .. }
                if item.tag.starts_with("object:") && Some(item.pen.color) == occluder_colour =>
            {
                px.push(tf.to_px(*center - DVec2::splat(*radius)));
                px.push(tf.to_px(*center + DVec2::splat(*radius)));
            }
            _ => {}
        }
    }
    let lo = px.iter().copied().reduce(DVec2::min).unwrap();
    let hi = px.iter().copied().reduce(DVec2::max).unwrap();
    (hi - lo).max_element() / frame.plot.width().min(frame.plot.height())
}

#[test]
fn a_shadows_figure_keeps_its_point_large_however_far_the_light() {
    let mut small = Vec::new();
    for lang in [Lang::En, Lang::Ro] {
        for (name, d) in lesson_figures(lang).into_iter().filter(|(name, _)| name.contains("-shadows (")) {
            let share = point_share(&d);
            if share < MIN_POINT_SHARE {
                small.push(format!("{name}: {share:.2}"));
            }
        }
    }
    assert!(
        small.is_empty(),
        "points squeezed below {MIN_POINT_SHARE} of the picture:\n{}",
        small.join("\n")
    );
}
