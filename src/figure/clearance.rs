//! A ray that passes close by what it misses (issue 32): drawn within
//! [`MIN_CLEARANCE_WIDTHS`] of its stroke widths of an object's outline, it reads as a hit, so
//! the figure says by how much it misses, in scene units, beside the spot ("misses block by
//! 0.12"; Romanian "trece la 0.12 de bloc"). Only where the drawing's units are the scene's (a 2D
//! scene drawn in its own axes, [`Drawing::scene_axes`]); the figures that pick their rays keep
//! clear of such spots in the first place (`source`'s `clear_columns` for `projections`).
//! Read on the display list after a kind has drawn, before the labels settle.

use glam::DVec2;

use super::labels::Label;
use super::plane::Outline;
use super::style::{self, OBJECT_TAG, RAY_TAG};
use super::Lang;
use crate::canvas::{Drawing, Mark, TextOpts};
use crate::format::{markup_escape, slide_number};
use crate::scene::Scene;
use crate::shape::Dim;

/// The least clearance between a drawn ray and an object's outline it passes, in the ray's
/// stroke widths, centre line to outline on the page; `layout.rs` holds every lesson figure to it.
pub const MIN_CLEARANCE_WIDTHS: f64 = 3.0;
/// How near, in pixels, an end of a ray lies to an outline to start or end on it (its hit, its
/// surface), and how near a ray passes to touch it (a tangent ray).
pub const TOUCH_PX: f64 = 1.0;
/// The tag of a near miss's note.
pub const NOTE_TAG: &str = "miss-note";
/// The spots tried along a ray for the one nearest an outline (where its note goes).
const SPOTS: u32 = 64;

/// A drawn ray: its points (its pieces joined end to start), its tag and events, its stroke width.
struct Ray {
    points: Vec<DVec2>,
    tag: String,
    events: Vec<usize>,
    width: f64,
}

/// The rays of `d`, in drawing units.
fn rays(d: &Drawing) -> Vec<Ray> {
    let mut rays: Vec<Ray> = Vec::new();
    for item in d.items.iter().filter(|i| i.tag.starts_with(RAY_TAG)) {
        let points = match &item.mark {
            Mark::Arrow { from, to, .. } => vec![*from, *to],
            Mark::Line { points } => points.clone(),
            _ => continue,
        };
        match rays.last_mut() {
            Some(ray) if ray.tag == item.tag && ray.points.last() == points.first() => {
                ray.points.extend(&points[1..]);
            }
            _ => rays.push(Ray {
                points,
                tag: item.tag.clone(),
                events: item.events.clone(),
                width: item.pen.width,
            }),
        }
    }
    rays
}

/// The objects' outlines of `d` with their object's index, in drawing units.
fn outlines(d: &Drawing) -> Vec<(usize, Outline)> {
    d.items
        .iter()
        .filter_map(|i| {
            let object = i.tag.strip_prefix(OBJECT_TAG)?.parse().ok()?;
            let outline = match &i.mark {
                Mark::Circle { center, radius, .. } => Outline::Circle { center: *center, radius: *radius },
                Mark::Polygon { points, .. } => Outline::Polygon(points.clone()),
                Mark::Line { points } => Outline::Path(points.clone()),
                Mark::Rect { min, max, .. } => {
                    Outline::Polygon(vec![*min, DVec2::new(max.x, min.y), *max, DVec2::new(min.x, max.y)])
                }
                _ => return None,
            };
            Some((object, outline))
        })
        .collect()
}

/// Whether every panel of `d` draws its scene in the scene's own units: a 2D scene in its axes
/// (an inset's panel in them magnified by its factor, [`crate::canvas::Inset`]).
fn in_scene_units(d: &Drawing) -> bool {
    let unit = |a: DVec2, b: DVec2| (a - b).length() < 1e-9;
    let scales: Vec<f64> = std::iter::once(1.0).chain(d.insets.iter().map(|i| i.factor)).collect();
    !d.scene_axes.is_empty()
        && d.scene_axes.iter().all(|p| {
            p.axes.len() == 2
                && scales.iter().any(|k| unit(p.axes[0], DVec2::X * *k) && unit(p.axes[1], DVec2::Y * *k))
        })
}

/// Whether `points` are drawn in an inset's panel (magnified: a gap there is not in scene
/// units, and the main picture notes the same miss).
fn in_inset(d: &Drawing, points: &[DVec2]) -> bool {
    points.first().is_some_and(|p| d.insets.iter().any(|i| i.in_panel(*p)))
}

/// Adds to `d` a note for each ray that passes an object's outline closer than
/// [`MIN_CLEARANCE_WIDTHS`] of its stroke widths without starting, ending or crossing there:
/// "misses NAME by X" at the ray's spot nearest the outline, X the gap in scene units.
pub fn note_near_misses<V: Dim>(d: &mut Drawing, scene: &Scene<V>, lang: Lang) {
    if !in_scene_units(d) {
        return;
    }
    let px = d.transform().len_px(1.0);
    let rays: Vec<Ray> = rays(d).into_iter().filter(|r| !in_inset(d, &r.points)).collect();
    let outlines: Vec<(usize, Outline)> = outlines(d)
        .into_iter()
        .filter(|(_, o)| {
            !in_inset(d, &super::parts::outline_edges(o).iter().map(|e| e.0).collect::<Vec<_>>())
        })
        .collect();
    let mut noted: Vec<(usize, DVec2)> = Vec::new();
    for ray in &rays {
        let ends = [ray.points[0], ray.points[ray.points.len() - 1]];
        let clear = MIN_CLEARANCE_WIDTHS * d.transform().ref_px(ray.width) / px;
        for (object, outline) in &outlines {
            if ends.iter().any(|p| outline.gap(*p, *p) * px <= TOUCH_PX) {
                continue;
            }
            let gap = ray.points.windows(2).map(|w| outline.gap(w[0], w[1])).fold(f64::INFINITY, f64::min);
            if !(gap * px > TOUCH_PX && gap < clear) {
                continue;
            }
            // The spot of the ray nearest the outline.
            let spot = ray
                .points
                .windows(2)
                .flat_map(|w| {
                    (0..=SPOTS).map(move |k| w[0] + (w[1] - w[0]) * (f64::from(k) / f64::from(SPOTS)))
                })
                .min_by(|a, b| outline.gap(*a, *a).total_cmp(&outline.gap(*b, *b)))
                .unwrap_or(ends[0]);
            if noted.iter().any(|(o, s)| o == object && s.distance(spot) * px < clear * px) {
                continue;
            }
            noted.push((*object, spot));
            let name = markup_escape(&scene.object_label(*object, lang));
            let gap = slide_number(gap);
            let text = match lang {
                Lang::En => {
                    format!("{} {name} {} {gap}", Label::Misses.text(lang), Label::MissesBy.text(lang))
                }
                Lang::Ro => {
                    format!("{} {gap} {} {name}", Label::Misses.text(lang), Label::MissesBy.text(lang))
                }
            };
            let opts = TextOpts::NOTE.color(style::DARK_GREY).avoid_overlap_with_leader();
            d.with_events(ray.events.iter().copied(), |d| {
                // Tagged without the object's index: the note keeps off its outline too.
                d.text(NOTE_TAG, spot, &text, opts);
            });
        }
    }
}
