//! What `slab-test` and `kay-kajiya` share (lecture "Utilizarea de volume încadratoare (3)–(5)",
//! algorithm.md §9 "Axis-aligned box (slab test)", "Kay–Kajiya slabs"): a volume as pairs of
//! parallel planes `lo_k ≤ n_k·x ≤ hi_k` (the axes for a box, the lecture's 0°, 45°, 90°, 135° for
//! Kay–Kajiya), drawn with its planes dashed; a ray that meets it and one that misses it by the
//! least, each with the points where it crosses every plane (I_k, E_k at the recorded `t`); and
//! beside them each ray's recorded per-slab intervals [t_i, t_e] on a t axis (from 0, ticked and
//! numbered), with the lines max t_i and min t_e named where they stand — the test itself, as
//! the trace recorded it.

use glam::DVec2;

use super::Input;
use crate::accel::Layout;
use crate::bounds::BoundingVolume;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign, View};
use crate::figure::labels::Label;
use crate::figure::parts::{self, clip_line, object_name};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::{bound_test_index, bound_test_of, BoundTestOf, FigureTrace, Target};
use crate::figure::style::{self, RayRole, Rgba, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::record::event::ObjectRef;

/// The bounding volume of the object the figure `kind` is about, from the per-object volumes the
/// traces were recorded with (`--accel bounds`); `None` when that object has none.
///
/// # Errors
/// When no object was tested or the traces hold no per-object volumes.
pub fn focus_volume<V: Planar>(
    input: &Input<'_, V>,
    kind: &str,
) -> Result<Option<BoundingVolume<V>>, FigureError> {
    let focus = input.traces.focus.ok_or_else(|| FigureError("no object was tested".into()))?;
    let Layout::Volumes(entries) = input.traces.accel.layout() else {
        return Err(FigureError(format!("{kind} reads per-object volumes (--accel bounds)")));
    };
    Ok(entries.iter().find(|(p, _)| p.object() == focus).map(|(_, v)| *v))
}

/// One pair of parallel planes: `lo ≤ n·x ≤ hi`, and its name (`x`, `45°`, `3`).
pub struct Slab<V> {
    /// The normal n (not necessarily unit).
    pub normal: V,
    /// Lower extent of `n·x`.
    pub lo: f64,
    /// Upper extent.
    pub hi: f64,
    /// Its name in labels (`x` → I_x, t_{ix}).
    pub name: String,
    /// Its place in the legend and among the interval rows (the lecture's order).
    pub row: usize,
}

/// The colour of slab `k`.
fn slab_colour(k: usize) -> Rgba {
    const COLOURS: [Rgba; 7] = [
        style::BLUISH_GREEN,
        style::REDDISH_PURPLE,
        style::ORANGE,
        style::SKY_BLUE,
        style::DARK_GREY,
        style::YELLOW,
        style::BLACK,
    ];
    COLOURS[k % COLOURS.len()]
}

/// The two rays' colours: the lecture draws the ray that meets the box red, the one that misses
/// it blue.
const HIT_RAY: Rgba = style::VERMILLION;
const MISS_RAY: Rgba = style::BLUE;

/// A traced ray's test of the volume, read from its `bound_test` event.
struct Tested<'a, V> {
    traced: &'a FigureTrace<V>,
    /// The events it draws, when it is the main trace: its primary ray and its `bound_test`.
    events: Vec<usize>,
    origin: V,
    direction: V,
    intervals: Vec<[f64; 2]>,
    t_in: f64,
    t_out: f64,
    hit: bool,
}

/// The page plane: in 2D the scene's; in 3D the plane of the two axes along which the first ray
/// moves most, through `centre` (the axis it moves least along is dropped).
fn page<V: Planar>(centre: V, direction: V) -> (PagePlane<V>, Option<[usize; 2]>) {
    let fallback = PagePlane { origin: centre, x: V::axis(0), y: V::axis(1), offset: DVec2::ZERO };
    if V::DIM == 2 {
        return (PagePlane { origin: V::ZERO, ..fallback }, None);
    }
    let dropped = (0..3).fold(0, |m, a| if direction[a].abs() < direction[m].abs() { a } else { m });
    let axes: Vec<usize> = (0..3).filter(|a| *a != dropped).collect();
    let plane = PagePlane::spanned(centre, V::axis(axes[0]), V::axis(axes[1])).unwrap_or(fallback);
    (plane, Some([axes[0], axes[1]]))
}

/// The convex polygon `{p : lo_k ≤ n_k·p ≤ hi_k}` on the page, cut from `start` (Sutherland–Hodgman).
fn section<V: Planar>(plane: &PagePlane<V>, slabs: &[Slab<V>], start: Vec<DVec2>) -> Vec<DVec2> {
    let mut poly = start;
    for s in slabs {
        // n·(O + a·x + b·y) = n·O + (n·x, n·y)·(a, b), with (a, b) the page point less the offset.
        let m = plane.dir(s.normal);
        if m.length() < 1e-12 {
            continue;
        }
        let base = s.normal.dot(plane.origin) - m.dot(plane.offset);
        for (sign, c) in [(1.0, s.hi - base), (-1.0, base - s.lo)] {
            poly = clip(&poly, m * sign, c);
        }
    }
    poly
}

/// Keeps the part of `poly` with `m·p ≤ c`.
fn clip(poly: &[DVec2], m: DVec2, c: f64) -> Vec<DVec2> {
    let mut out = Vec::new();
    for (k, a) in poly.iter().enumerate() {
        let b = poly[(k + 1) % poly.len()];
        let (fa, fb) = (m.dot(*a) - c, m.dot(b) - c);
        if fa <= 0.0 {
            out.push(*a);
        }
        if (fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0) {
            out.push(*a + (b - *a) * (fa / (fa - fb)));
        }
    }
    out
}

/// Draws a slab figure: `slabs` describe the volume around object `input.traces.focus`.
///
/// # Errors
/// When the traces hold no test of that object's volume.
pub fn draw<V: Planar>(
    input: &Input<'_, V>,
    d: &mut Drawing,
    title: Label,
    slabs: &[Slab<V>],
) -> Result<(), FigureError> {
    let focus = input.traces.focus.ok_or_else(|| FigureError("no object to draw the volume of".into()))?;
    let tested: Vec<Tested<'_, V>> = input
        .traces
        .traces
        .iter()
        .filter_map(|traced| {
            let BoundTestOf { intervals, t_in, t_out, hit } = bound_test_of(&traced.log, focus)?;
            let root = traced.log.nodes.first()?;
            let main = std::ptr::eq(traced, &input.traces.traces[0]);
            let events = if main {
                traced.log.spawned_by(0).into_iter().chain(bound_test_index(&traced.log, focus)).collect()
            } else {
                Vec::new()
            };
            Some(Tested {
                traced,
                events,
                origin: root.start.origin,
                direction: root.start.direction,
                intervals: intervals.to_vec(),
                t_in,
                t_out,
                hit,
            })
        })
        .collect();
    let first = tested.first().ok_or_else(|| FigureError("no ray was tested against the volume".into()))?;
    let lang = input.lang;
    let scene = input.scene;
    // The volume's centre, from its slabs along the axes when it has them.
    let mut centre = V::ZERO;
    for (a, s) in slabs.iter().take(V::DIM).enumerate() {
        centre[a] = (s.lo + s.hi) / 2.0;
    }
    let (plane, axes) = page(centre, first.direction);

    d.set_title(input.t(title));
    let object = object_name(scene, ObjectRef { index: focus, triangle: None }, input.lang);
    // The object named as the one whose volume the rays test: a bare name ("d") says nothing.
    let mut caption = format!(
        "{}{} {object}",
        crate::figure::labels::scene_lead(&input.traces.scene_name, lang),
        input.t(Label::VolumeOf)
    );
    for t in &tested {
        let target = t.traced.targets.first().cloned().unwrap_or(Target::Ray);
        let verdict = if t.hit { Label::MeetsVolume } else { Label::MissesVolume };
        caption.push_str(&format!(
            " · {} {}",
            crate::figure::labels::target(&target, V::DIM, lang),
            input.t(verdict)
        ));
    }
    if let Some([a, b]) = axes {
        caption.push_str(&format!(" · {} {}{}", input.t(Label::AxisPlane), axis_name(a), axis_name(b)));
    }
    d.set_caption(&caption);
    for t in &tested {
        let (colour, label) = if t.hit { (HIT_RAY, Label::RayMeets) } else { (MISS_RAY, Label::RayMisses) };
        d.legend_entry(input.t(label), Pen::solid(colour, style::RAY_WIDTH), LegendIcon::Arrow);
    }
    let mut in_rows: Vec<(usize, &Slab<V>)> = slabs.iter().enumerate().collect();
    in_rows.sort_by_key(|(_, s)| s.row);
    for (k, s) in in_rows {
        let text = format!("{} {}", input.t(Label::SlabPlanes), s.name);
        d.legend_entry(
            &text,
            Pen::solid(slab_colour(k), style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH),
            LegendIcon::Line,
        );
    }
    d.legend_place = crate::canvas::LegendPlace::Outside;

    // Where each ray is drawn: around its max t_i and min t_e, a volume's width either side.
    let size = slabs.iter().map(|s| (s.hi - s.lo) / s.normal.length()).fold(0.0, f64::max).max(1e-9);
    let finite = |t: &Tested<'_, V>| -> Vec<f64> {
        t.intervals.iter().flatten().copied().filter(|x| x.is_finite()).collect()
    };
    let span_of = |t: &Tested<'_, V>| {
        let (a, b) = (t.t_in.min(t.t_out), t.t_in.max(t.t_out));
        ((a - 1.2 * size).max(0.0), b + 1.2 * size)
    };
    let at = |t: &Tested<'_, V>, s: f64| plane.point(t.origin + t.direction * s);
    let mut points: Vec<DVec2> = Vec::new();
    for t in &tested {
        let (a, b) = span_of(t);
        points.extend([at(t, a), at(t, b)]);
    }
    let big = 1e3 * parts::span(&points).max(1.0);
    let square = [DVec2::new(-big, -big), DVec2::new(big, -big), DVec2::new(big, big), DVec2::new(-big, big)];
    let polygon = section(&plane, slabs, square.iter().map(|p| *p + plane.offset).collect());
    points.extend(polygon.iter().copied());
    let column = parts::fit_with_column(d, &points, 0.08, 0.42);
    let view = d.view;
    let scene_part = View::new(view.xmin(), column.x, view.ymin(), view.ymax()).unwrap_or(view);

    // The volume, its planes, the object.
    d.polygon("volume", polygon.clone(), style::object(), Some(style::OBJECT_FILL));
    for (k, s) in slabs.iter().enumerate() {
        let m = plane.dir(s.normal);
        if m.length() < 1e-12 {
            continue;
        }
        let base = s.normal.dot(plane.origin) - m.dot(plane.offset);
        let dash = Pen::solid(slab_colour(k), style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH);
        for c in [s.lo, s.hi] {
            let point = m * ((c - base) / m.length_squared());
            if let Some((a, b)) = clip_line(point, m.perp().normalize(), &scene_part) {
                d.segment("slab-plane", a, b, dash);
            }
        }
    }
    let one = only(scene, focus);
    let first_item = d.items.len();
    let anchors = parts::draw_objects(d, &one, &plane, &scene_part, &[]);
    // The object keeps its scene index in its tag (`object:K`), as in every other figure.
    for item in &mut d.items[first_item..] {
        item.tag = format!("object:{focus}");
    }

    // The rays, their crossings, the entry and exit.
    for t in &tested {
        let (a, b) = span_of(t);
        let colour = if t.hit { HIT_RAY } else { MISS_RAY };
        let role = Pen::solid(colour, style::RAY_WIDTH);
        let (pa, pb) = (at(t, a), at(t, b));
        let mid = pa + (pb - pa) * 0.5;
        d.with_events(t.events.iter().copied(), |d| {
            d.arrow(RayRole::Primary.tag(), pa, mid, role);
            d.segment(RayRole::Primary.tag(), mid, pb, role);
        });
    }
    for t in &tested {
        let (from, to) = span_of(t);
        d.with_events(t.events.iter().copied(), |d| {
            for (k, iv) in t.intervals.iter().enumerate().take(slabs.len()) {
                for (end, letter) in iv.iter().zip(["I", "E"]) {
                    if end.is_finite() && (from..=to).contains(end) {
                        let p = at(t, *end);
                        d.marker("crossing", p, style::DOT_RADIUS * 0.8, slab_colour(k), Pen::NONE);
                        let opts = TextOpts::NOTE.size(TextSize::Small).color(slab_colour(k)).avoid_overlap();
                        d.text("crossing-name", p, &sub_text(letter, &slabs[k].name), opts);
                    }
                }
            }
            if t.hit {
                for (s, name) in [(t.t_in, "I"), (t.t_out, "E")] {
                    let p = at(t, s);
                    d.marker("entry-exit", p, style::DOT_RADIUS * 1.2, style::BLACK, Pen::NONE);
                    d.text("label", p, name, TextOpts::LABEL.bold().avoid_overlap());
                }
            }
        });
    }
    let first_name = d.items.len();
    parts::label_objects(d, &one, &anchors, input.lang);
    // Its name too: `object-name:K` names `object:K`.
    for item in &mut d.items[first_name..] {
        item.tag = format!("object-name:{focus}");
    }

    // The per-slab intervals on a t axis, one block per ray, in the column on the right.
    let width = view.xmax() - column.x;
    let left = column.x + 0.1 * width;
    let right = view.xmax() - 0.04 * width;
    // The axis starts at t = 0, the ray's origin, or before it when an interval does.
    let t_lo = tested.iter().flat_map(finite).fold(0.0, f64::min);
    let t_hi = tested.iter().flat_map(finite).fold(f64::NEG_INFINITY, f64::max);
    let (t_lo, t_hi) = if t_lo < t_hi {
        (t_lo - 0.08 * (t_hi - t_lo), t_hi + 0.08 * (t_hi - t_lo))
    } else {
        (t_lo - 1.0, t_hi + 1.0)
    };
    let x_of = |t: f64| left + (t.clamp(t_lo, t_hi) - t_lo) / (t_hi - t_lo) * (right - left);
    // A block: its title, a row per slab, the t axis under them (two rows: ticks and numbers),
    // the verdict.
    let rows = slabs.len() as f64 + 5.0;
    let step = tick_step(t_hi - t_lo);
    let row_h = view.height() / (rows * tested.len() as f64 + 0.5);
    for (k, t) in tested.iter().enumerate() {
        d.with_events(t.events.iter().copied(), |d| {
            let top = view.ymax() - row_h * (0.6 + rows * k as f64);
            let colour = if t.hit { HIT_RAY } else { MISS_RAY };
            let target = t.traced.targets.first().cloned().unwrap_or(Target::Ray);
            let head = TextOpts::LABEL
                .size(TextSize::Body)
                .align(Align { h: HAlign::Left, v: VAlign::Middle })
                .color(colour)
                .no_halo();
            d.text(
                "interval-title",
                DVec2::new(column.x + 0.02 * width, top),
                &crate::figure::labels::target(&target, V::DIM, lang),
                head,
            );
            for (s, iv) in t.intervals.iter().enumerate().take(slabs.len()) {
                let y = top - row_h * (slabs[s].row as f64 + 1.0);
                let name =
                    TextOpts::NOTE.align(Align::LEFT_OF).offset(-10.0, 0.0).color(slab_colour(s)).no_halo();
                d.text("interval-name", DVec2::new(left, y), &slabs[s].name, name);
                d.segment("t-axis", DVec2::new(left, y), DVec2::new(right, y), style::grid());
                let (a, b) = (iv[0], iv[1]);
                if a <= b {
                    let bar = Pen::solid(slab_colour(s), style::RAY_WIDTH * 1.6);
                    d.segment("interval", DVec2::new(x_of(a), y), DVec2::new(x_of(b), y), bar);
                }
            }
            // max t_i and min t_e: the verdict.
            let y_top = top - row_h * 0.5;
            let y_bot = top - row_h * (slabs.len() as f64 + 0.5);
            for (value, tag) in [(t.t_in, "t-in"), (t.t_out, "t-out")] {
                if value.is_finite() {
                    let line = Pen::solid(colour, style::CONSTRUCTION_WIDTH);
                    d.segment(tag, DVec2::new(x_of(value), y_top), DVec2::new(x_of(value), y_bot), line);
                }
            }
            // The two lines named at their feet, under the rows: the left one's name to its left,
            // the right one's to its right, so that close lines keep their names apart.
            let names = [(t.t_in, "max t_i"), (t.t_out, "min t_e")];
            let (first, second) = if t.t_in <= t.t_out { (names[0], names[1]) } else { (names[1], names[0]) };
            for ((value, name), h) in [(first, HAlign::Right), (second, HAlign::Left)] {
                if value.is_finite() {
                    let opts = TextOpts::NOTE.align(Align { h, v: VAlign::Top }).color(colour).no_halo();
                    let dx = if h == HAlign::Right { -4.0 } else { 4.0 };
                    d.text("line-name", DVec2::new(x_of(value), y_bot), name, opts.offset(dx, -2.0));
                }
            }
            // The t axis: ticks every `step`, zero among them, numbered, and its name.
            let y_axis = y_bot - row_h * 1.1;
            d.segment("t-scale", DVec2::new(left, y_axis), DVec2::new(right, y_axis), style::object());
            let tick = row_h * 0.15;
            // Whole numbers of steps, counted in f64 (exact at these sizes).
            let (mut k, last_tick) = ((t_lo / step).ceil(), (t_hi / step).floor());
            while k <= last_tick {
                let value = k * step;
                k += 1.0;
                let x = x_of(value);
                d.segment(
                    "t-tick",
                    DVec2::new(x, y_axis + tick),
                    DVec2::new(x, y_axis - tick),
                    style::object(),
                );
                let opts = TextOpts::NOTE.align(Align::BELOW).offset(0.0, -4.0).no_halo();
                d.text("t-tick-value", DVec2::new(x, y_axis - tick), &slide_number(value), opts);
            }
            let opts = TextOpts::LABEL.align(Align::RIGHT_OF).offset(8.0, 0.0).no_halo();
            d.text("t-axis-name", DVec2::new(right, y_axis), "t", opts);
            let y_bot = y_axis - row_h * 1.4;
            let relation = if t.t_in <= t.t_out { "≤" } else { ">" };
            let verdict = if t.hit { Label::MeetsVolume } else { Label::MissesVolume };
            let text = format!(
                "max t_i = {} {relation} min t_e = {} → {}",
                slide_number(t.t_in),
                slide_number(t.t_out),
                input.t(verdict)
            );
            let opts = TextOpts::NOTE.align(Align { h: HAlign::Left, v: VAlign::Top }).no_halo();
            d.text("verdict", DVec2::new(column.x + 0.02 * width, y_bot - row_h * 0.2), &text, opts);
        });
    }
    Ok(())
}

/// The most ticks a t axis carries.
const MAX_TICKS: f64 = 8.0;

/// The step between the ticks of a t axis `span` long: the least of 1, 2 or 5 × 10^k that puts
/// at most [`MAX_TICKS`] ticks on it.
fn tick_step(span: f64) -> f64 {
    let raw = (span / MAX_TICKS).max(1e-9);
    let unit = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * unit).find(|s| *s >= raw).unwrap_or(10.0 * unit)
}

/// A scene with only object `index` (for drawing the object the volume bounds).
fn only<V: Planar>(scene: &crate::scene::Scene<V>, index: usize) -> crate::scene::Scene<V> {
    let mut one = scene.clone();
    one.objects = vec![scene.objects[index].clone()];
    one
}

/// `I_x`, `E_{45°}`: a crossing's name.
fn sub_text(letter: &str, name: &str) -> String {
    if name.chars().count() == 1 {
        format!("{letter}_{name}")
    } else {
        format!("{letter}_{{{name}}}")
    }
}

/// `x`, `y`, `z`.
#[must_use]
pub fn axis_name(axis: usize) -> &'static str {
    ["x", "y", "z"][axis.min(2)]
}
