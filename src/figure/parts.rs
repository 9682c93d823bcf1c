//! Pieces every diagram shares (product.md "Diagrams"): the names of a trace's rays and hits in the
//! lecture's notation (P, R₁, T₁, I₁ …, from `record::names`, which the narration uses too), numbers as a slide shows them, the scene's objects on a
//! page plane, rays clipped to the view, the observer, the lights, the legend rows of the ray kinds,
//! and a view that leaves a column free for text. Drawing only: nothing here traces.

use glam::DVec2;

use super::labels::Label;
use super::plane::{ObjectOutline, Outline, PagePlane, Planar};
use super::style::{self, RayRole, Rgba, TextSize};
use super::Lang;
use crate::canvas::{Align, Drawing, HAlign, Inset, LegendIcon, Pen, TextOpts, VAlign, View};
use crate::format::markup_escape;
use crate::format::slide_number;
use crate::image::to_byte;
use crate::record::event::{Event, ObjectRef, RayKind};
pub use crate::record::names::{sub, Names};
use crate::record::EventLog;
use crate::scene::material::Rgb;
use crate::scene::Scene;

/// An angle in degrees, one decimal: `30.0°`.
#[must_use]
pub fn deg(radians: f64) -> String {
    format!("{:.1}°", radians.to_degrees()).replace('-', "−")
}

/// `(0.1, 0.2, 0.3)`; a grey as one number.
#[must_use]
pub fn rgb_text(c: Rgb) -> String {
    let [r, g, b] = c.0;
    if slide_number(r) == slide_number(g) && slide_number(g) == slide_number(b) {
        slide_number(r)
    } else {
        format!("({}, {}, {})", slide_number(r), slide_number(g), slide_number(b))
    }
}

/// A linear colour as the image file would show it: `round(255·clamp(c, 0, 1))` per channel.
#[must_use]
pub fn swatch(c: Rgb) -> Rgba {
    Rgba::rgb(to_byte(c.0[0]), to_byte(c.0[1]), to_byte(c.0[2]))
}

/// The colour role of a ray node's kind.
#[must_use]
pub fn role(kind: RayKind) -> RayRole {
    match kind {
        RayKind::Primary => RayRole::Primary,
        RayKind::Reflected => RayRole::Reflected,
        RayKind::Transmitted => RayRole::Transmitted,
    }
}

/// An object's name as the trace calls it, safe for the markup.
#[must_use]
pub fn object_name<V: Planar>(scene: &Scene<V>, object: ObjectRef, lang: Lang) -> String {
    markup_escape(&scene.object_label(object.index, lang))
}

/// Where a shadow ray first meets an occluder: the least accepted t below `d_L` among the object
/// tests recorded just before the `shadow_ray` event at `index` in `log.events`.
#[must_use]
pub fn shadow_block_t<V>(log: &EventLog<V>, index: usize) -> Option<f64> {
    let Event::ShadowRay { distance, .. } = log.events[index].event else {
        return None;
    };
    log.events[..index]
        .iter()
        .rev()
        .map_while(|l| match l.event {
            Event::ObjectTest { accepted, .. } => Some(accepted),
            _ => None,
        })
        .flatten()
        .filter(|t| *t < distance)
        .reduce(f64::min)
}

/// Where a ray from `from` along `dir` enters the picture `view`: `from` itself when it lies inside,
/// else the first crossing of the view's border (or `from` when the ray never crosses it).
#[must_use]
pub fn entry_point(from: DVec2, dir: DVec2, view: &View) -> DVec2 {
    let inside =
        view.xmin() <= from.x && from.x <= view.xmax() && view.ymin() <= from.y && from.y <= view.ymax();
    if inside {
        return from;
    }
    clip_line(from, dir.normalize_or_zero(), view).map_or(from, |(a, _)| a)
}

/// The part of the line through `point` along `dir` inside `view`, or `None`.
#[must_use]
pub fn clip_line(point: DVec2, dir: DVec2, view: &View) -> Option<(DVec2, DVec2)> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for (axis, lo, hi) in [(0, view.xmin(), view.xmax()), (1, view.ymin(), view.ymax())] {
        let (p, d) = (point[axis], dir[axis]);
        if d.abs() < 1e-15 {
            if p < lo || p > hi {
                return None;
            }
        } else {
            let (a, b) = ((lo - p) / d, (hi - p) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
    }
    (t0 < t1).then(|| (point + dir * t0, point + dir * t1))
}

/// Where a ray from `from` along `dir` leaves `view` (`from` itself if it never enters or the
/// direction is zero on the page).
#[must_use]
pub fn exit_point(from: DVec2, dir: DVec2, view: &View) -> DVec2 {
    if dir.length() < 1e-12 {
        return from;
    }
    match clip_line(from, dir, view) {
        Some((_, b)) if (b - from).dot(dir) > 0.0 => b,
        _ => from,
    }
}

/// The stroke of an emphasised object's outline (an occluder, the sphere a figure is about).
pub const EMPHASIS_WIDTH: f64 = style::OBJECT_WIDTH * 1.6;

/// Draws every object of `scene` on `plane` (sections solid and filled, projection outlines faint
/// and dashed), unbounded lines clipped to `clip`; objects in `emphasis` get a thick outline in
/// the colour given with them. Records on the drawing how `plane` maps the scene's axes
/// ([`Drawing::record_axes`]: a 2D scene keeps its own, x right and y up). Returns where each
/// visible object's name goes, for [`label_objects`] once the rays are drawn.
pub fn draw_objects<V: Planar>(
    d: &mut Drawing,
    scene: &Scene<V>,
    plane: &PagePlane<V>,
    clip: &View,
    emphasis: &[(usize, Rgba)],
) -> Vec<(usize, DVec2)> {
    draw_objects_through(d, scene, plane, clip, emphasis, None)
}

/// [`draw_objects`], or with `inset` the part of them inside its frame (`clip`, the frame),
/// magnified into its panel ([`Inset::map`]): outlines clipped to the frame, then mapped; the
/// names' anchors those of the frame's objects, mapped. The panel records its scene axes too.
pub fn draw_objects_through<V: Planar>(
    d: &mut Drawing,
    scene: &Scene<V>,
    plane: &PagePlane<V>,
    clip: &View,
    emphasis: &[(usize, Rgba)],
    inset: Option<&Inset>,
) -> Vec<(usize, DVec2)> {
    let scale = inset.map_or(1.0, |i| i.factor);
    let place = |p: DVec2| inset.map_or(p, |i| i.map(p));
    d.record_axes(place(plane.point(V::ZERO)), (0..V::DIM).map(|k| plane.dir(V::axis(k)) * scale));
    let mut anchors = Vec::new();
    for (index, object) in scene.objects.iter().enumerate() {
        let tag = format!("object:{index}");
        let strong = emphasis.iter().find(|(k, _)| *k == index);
        let section_style = match strong {
            Some((_, colour)) => style::outline(*colour).with_width(EMPHASIS_WIDTH),
            None => style::object(),
        };
        let faint =
            Pen::solid(style::DARK_GREY.with_alpha(0.7), style::GRID_WIDTH).dashed(style::CONSTRUCTION_DASH);
        let mut anchor = None;
        let outlines = V::outlines(&object.shape, plane);
        for ObjectOutline { outline, section } in outlines.iter().cloned() {
            let (st, fill) = if section { (section_style, Some(style::OBJECT_FILL)) } else { (faint, None) };
            match &outline {
                Outline::Circle { center, radius } => {
                    anchor.get_or_insert(*center + DVec2::new(radius * 0.72, radius * 0.72));
                }
                Outline::Polygon(pts) => {
                    anchor.get_or_insert(top_point(pts));
                }
                Outline::Path(pts) => {
                    anchor.get_or_insert(pts.iter().copied().sum::<DVec2>() / pts.len().max(1) as f64);
                }
                Outline::Line { point, dir } => {
                    if let Some((a, b)) = clip_line(*point, *dir, clip) {
                        anchor.get_or_insert(a + (b - a) * 0.12);
                    }
                }
            }
            let drawn = match inset {
                None => vec![outline],
                Some(i) => detail_outlines(&outline, clip, i),
            };
            for outline in drawn {
                match outline {
                    Outline::Circle { center, radius } => {
                        d.circle(&tag, center, radius, st, fill);
                    }
                    Outline::Polygon(pts) => {
                        d.polygon(&tag, pts, st, fill);
                    }
                    Outline::Path(pts) => {
                        d.line(&tag, pts, st);
                    }
                    Outline::Line { point, dir } => {
                        if let Some((a, b)) = clip_line(point, dir, clip) {
                            d.segment(&tag, a, b, st);
                        }
                    }
                }
            }
        }
        let inside =
            |a: &DVec2| clip.xmin() <= a.x && a.x <= clip.xmax() && clip.ymin() <= a.y && a.y <= clip.ymax();
        // An anchor the view cuts off moves onto the longest visible piece of the outline, so
        // that an object the view shows in part (the mirror cut by the border) is still named.
        let anchor = anchor.filter(inside).or_else(|| {
            outlines
                .iter()
                .filter_map(|o| longest_visible_piece(&o.outline, clip))
                .reduce(|a, b| if a.0.distance(a.1) >= b.0.distance(b.1) { a } else { b })
                .map(|(a, b)| (a + b) / 2.0)
        });
        if let Some(a) = anchor {
            anchors.push((index, place(a)));
        }
    }
    anchors
}

/// An outline's part inside the frame `clip` of `inset`, magnified into its panel: a circle
/// the frame holds whole stays a circle; a circle or polygon it cuts is cut to it (as a
/// polygon of [`CIRCLE_CHORDS`] chords, clipped edge by edge against the frame, Sutherland–
/// Hodgman); a path keeps its pieces inside; a line its chord across the frame.
fn detail_outlines(outline: &Outline, clip: &View, inset: &Inset) -> Vec<Outline> {
    let inside =
        |p: DVec2| clip.xmin() <= p.x && p.x <= clip.xmax() && clip.ymin() <= p.y && p.y <= clip.ymax();
    let polygon = |points: Vec<DVec2>| {
        let cut = clip_polygon(&points, clip);
        if cut.len() >= 3 {
            vec![Outline::Polygon(cut.into_iter().map(|p| inset.map(p)).collect())]
        } else {
            Vec::new()
        }
    };
    match outline {
        Outline::Circle { center, radius } => {
            let r = DVec2::splat(*radius);
            if inside(*center - r) && inside(*center + r) {
                vec![Outline::Circle { center: inset.map(*center), radius: radius * inset.factor }]
            } else {
                polygon(outline_edges(outline).into_iter().map(|(a, _)| a).collect())
            }
        }
        Outline::Polygon(points) => polygon(points.clone()),
        Outline::Path(_) => outline_edges(outline)
            .into_iter()
            .filter_map(|(a, b)| clip_segment(a, b, clip))
            .map(|(a, b)| Outline::Path(vec![inset.map(a), inset.map(b)]))
            .collect(),
        Outline::Line { point, dir } => clip_line(*point, *dir, clip)
            .map(|(a, b)| Outline::Path(vec![inset.map(a), inset.map(b)]))
            .into_iter()
            .collect(),
    }
}

/// A polygon cut to `view` (Sutherland–Hodgman: against each of the view's four sides in
/// turn, keeping the vertices inside and adding where an edge crosses the side).
#[must_use]
pub fn clip_polygon(points: &[DVec2], view: &View) -> Vec<DVec2> {
    let sides: [(DVec2, f64); 4] = [
        (DVec2::X, view.xmin()),
        (DVec2::NEG_X, -view.xmax()),
        (DVec2::Y, view.ymin()),
        (DVec2::NEG_Y, -view.ymax()),
    ];
    let mut out = points.to_vec();
    for (n, c) in sides {
        // Inside where n·p ≥ c.
        let input = std::mem::take(&mut out);
        for (k, &p) in input.iter().enumerate() {
            let q = input[(k + 1) % input.len()];
            let (dp, dq) = (n.dot(p) - c, n.dot(q) - c);
            if dp >= 0.0 {
                out.push(p);
            }
            if (dp >= 0.0) != (dq >= 0.0) {
                out.push(p + (q - p) * (dp / (dp - dq)));
            }
        }
    }
    out
}

/// How many chords a circle's outline is cut into when its visible part is measured.
const CIRCLE_CHORDS: usize = 64;

/// The straight pieces of an outline on the page: its edges (a closed polygon's last one back
/// to the first), a circle as [`CIRCLE_CHORDS`] chords; none for an unbounded line.
#[must_use]
pub fn outline_edges(outline: &Outline) -> Vec<(DVec2, DVec2)> {
    let chain = |points: &[DVec2], closed: bool| {
        let mut edges: Vec<(DVec2, DVec2)> = points.windows(2).map(|w| (w[0], w[1])).collect();
        if closed && points.len() > 2 {
            edges.push((points[points.len() - 1], points[0]));
        }
        edges
    };
    match outline {
        Outline::Circle { center, radius } => {
            let at = |k: usize| {
                *center + DVec2::from_angle(std::f64::consts::TAU * k as f64 / CIRCLE_CHORDS as f64) * *radius
            };
            (0..CIRCLE_CHORDS).map(|k| (at(k), at(k + 1))).collect()
        }
        Outline::Polygon(points) => chain(points, true),
        Outline::Path(points) => chain(points, false),
        Outline::Line { .. } => Vec::new(),
    }
}

/// The part of segment `a`–`b` inside `view`, or `None`.
#[must_use]
pub fn clip_segment(a: DVec2, b: DVec2, view: &View) -> Option<(DVec2, DVec2)> {
    let (p, q) = clip_line(a, b - a, view)?;
    let d = b - a;
    let len2 = d.length_squared();
    if len2 <= 0.0 {
        return None;
    }
    let (tp, tq) = ((p - a).dot(d) / len2, (q - a).dot(d) / len2);
    let (t0, t1) = (tp.min(tq).max(0.0), tp.max(tq).min(1.0));
    (t0 < t1).then(|| (a + d * t0, a + d * t1))
}

/// The longest piece of `outline`'s edges ([`outline_edges`]) inside `view`; an unbounded
/// line's piece is the line clipped to the view.
fn longest_visible_piece(outline: &Outline, view: &View) -> Option<(DVec2, DVec2)> {
    if let Outline::Line { point, dir } = outline {
        return clip_line(*point, *dir, view);
    }
    outline_edges(outline)
        .into_iter()
        .filter_map(|(a, b)| clip_segment(a, b, view))
        .max_by(|x, y| x.0.distance(x.1).total_cmp(&y.0.distance(y.1)))
}

/// The objects' names at the anchors of [`draw_objects`], clear of lines and labels.
pub fn label_objects<V: Planar>(d: &mut Drawing, scene: &Scene<V>, anchors: &[(usize, DVec2)], lang: Lang) {
    for &(index, a) in anchors {
        let name = markup_escape(&scene.object_label(index, lang));
        let opts = TextOpts::NOTE.color(style::DARK_GREY).avoid_overlap_with_leader();
        d.text(&format!("object-name:{index}"), a, &name, opts);
    }
}

/// Each object's name at the first of its candidate spots where, once placed, it lies on no
/// ray or outline it does not name, on no other label, and reads as no other anchor's; at the
/// first spot when none is so. For a picture where the one spot [`draw_objects`] picks may lie
/// among many rays (an inset's magnified lens: the name tries the circle's compass points).
pub fn label_objects_first_clear<V: Planar>(
    d: &mut Drawing,
    scene: &Scene<V>,
    candidates: &[(usize, Vec<DVec2>)],
    lang: Lang,
) {
    for (index, spots) in candidates {
        let name = markup_escape(&scene.object_label(*index, lang));
        let opts = TextOpts::NOTE.color(style::DARK_GREY).avoid_overlap_with_leader();
        let tag = format!("object-name:{index}");
        for (k, at) in spots.iter().enumerate() {
            d.text(&tag, *at, &name, opts);
            let last = d.items.len() - 1;
            let involved = |pairs: Vec<(usize, usize)>| pairs.iter().any(|(a, b)| *a == last || *b == last);
            let clear = !involved(d.labels_on_lines(style::RAY_TAG))
                && !involved(d.labels_on_outlines(style::OBJECT_TAG))
                && !involved(d.overlapping_labels())
                && !involved(d.labels_nearer_another_anchor());
            if clear || k + 1 == spots.len() {
                break;
            }
            d.pop_item();
        }
    }
}

/// The highest vertex (for a label).
fn top_point(points: &[DVec2]) -> DVec2 {
    points.iter().copied().fold(DVec2::new(0.0, f64::NEG_INFINITY), |a, b| if b.y > a.y { b } else { a })
}

/// The page points that bound the objects in `indices` on `plane` (unbounded lines add none).
#[must_use]
pub fn object_extent<V: Planar>(scene: &Scene<V>, plane: &PagePlane<V>, indices: &[usize]) -> Vec<DVec2> {
    indices
        .iter()
        .flat_map(|i| V::outlines(&scene.objects[*i].shape, plane))
        .filter(|o| o.section)
        .flat_map(|o| o.outline.extent())
        .collect()
}

/// The page plane of a scene's traces: the plane of the camera's u and w axes through `through`,
/// u to the right and the viewing direction −w upwards; a 2D scene keeps its own axes unless
/// `camera_space` asks for the camera's in 2D too.
#[must_use]
pub fn camera_plane<V: Planar>(scene: &Scene<V>, through: V, camera_space: bool) -> PagePlane<V> {
    let world = PagePlane::spanned(V::ZERO, V::axis(0), V::axis(1));
    let frame = &scene.camera.frame;
    let camera = PagePlane::spanned(through, frame.u, -frame.w);
    let plane = if V::DIM == 2 && !camera_space { world } else { camera };
    // Both are built from orthonormal axes, so neither is ever refused.
    plane.unwrap_or(PagePlane { origin: through, x: V::axis(0), y: V::axis(1), offset: DVec2::ZERO })
}

/// A ray on the page: a line from `from` to `to` in the role's style with its arrow head halfway.
pub fn draw_ray(d: &mut Drawing, role: RayRole, from: DVec2, to: DVec2) {
    let mid = from + (to - from) * 0.55;
    d.arrow(role.tag(), from, mid, role.style());
    d.segment(role.tag(), mid, to, role.style());
}

/// An angle's arc at `centre` of `radius`, from direction `a` to direction `b` (the shorter way),
/// as a polyline; returns the point halfway along it, for the angle's label.
pub fn draw_arc(d: &mut Drawing, centre: DVec2, radius: f64, a: DVec2, b: DVec2, style: Pen) -> DVec2 {
    let (start, mut sweep) = (a.y.atan2(a.x), b.y.atan2(b.x) - a.y.atan2(a.x));
    if sweep > std::f64::consts::PI {
        sweep -= std::f64::consts::TAU;
    } else if sweep < -std::f64::consts::PI {
        sweep += std::f64::consts::TAU;
    }
    let at = |f: f64| centre + DVec2::from_angle(start + sweep * f) * radius;
    d.line("angle", (0..=24).map(|k| at(f64::from(k) / 24.0)), style);
    at(0.5)
}

/// A label just outside `at`, on the side that `away` points to (from a centre: an angle's arc,
/// a vector's tip), aligned so that it grows away from the centre.
pub fn label_outward(d: &mut Drawing, at: DVec2, away: DVec2, markup: &str) {
    let dir = away.try_normalize().unwrap_or(DVec2::Y);
    let h = if dir.x > 0.3 {
        HAlign::Left
    } else if dir.x < -0.3 {
        HAlign::Right
    } else {
        HAlign::Center
    };
    let v = if dir.y > 0.3 {
        VAlign::Bottom
    } else if dir.y < -0.3 {
        VAlign::Top
    } else {
        VAlign::Middle
    };
    let opts = TextOpts::LABEL.align(Align { h, v }).offset(dir.x * 12.0, dir.y * 12.0).avoid_overlap();
    d.text("label", at, markup, opts);
}

/// The observer O: a black dot and its label.
pub fn draw_observer(d: &mut Drawing, at: DVec2) {
    d.marker("observer", at, style::DOT_RADIUS * 1.3, style::BLACK, Pen::NONE);
}

/// Light `index` of the scene: a yellow dot outlined in black, tagged `light:index`
/// ([`lighting::LIGHT_TAG`](super::lighting::LIGHT_TAG)).
pub fn draw_light(d: &mut Drawing, index: usize, at: DVec2) {
    d.marker(
        &format!("{}{index}", super::lighting::LIGHT_TAG),
        at,
        style::LIGHT_RADIUS,
        style::LIGHT,
        style::outline(style::BLACK),
    );
}

/// A tree's node: a disc of `radius` reference pixels filled with `fill` and ringed with `ring`,
/// tagged `tag`; when those colours would fade into the white page ([`style::node_outline`]), a
/// thin dark outline just outside the ring, tagged `outline:` + `tag`, keeps it visible.
pub fn node_disc(d: &mut Drawing, tag: &str, at: DVec2, radius: f64, fill: Rgba, ring: Pen) {
    if let Some(outline) = style::node_outline(fill, ring) {
        let ring_width = if ring.strokes() { ring.width } else { 0.0 };
        let around = radius + 0.5 * (ring_width + outline.width);
        d.marker(&format!("outline:{tag}"), at, around, style::WHITE.with_alpha(0.0), outline);
    }
    d.marker(tag, at, radius, fill, ring);
}

/// A label placed clear of lines and other labels near `at`.
pub fn label(d: &mut Drawing, at: DVec2, markup: &str) {
    d.text("label", at, markup, TextOpts::LABEL.avoid_overlap());
}

/// The kind of label ([`crate::canvas::label::label_kind`]) of a ray's name: a ray's name is read
/// against the other rays' names, a point's name against the other points' (issue 32 item 1),
/// so "R₃" beside the point I₁ is no rival of "I₁", the letters tell them apart.
pub const RAY_NAME_TAG: &str = "ray-name";

/// A ray's name placed clear of lines and other labels near `at`, a point of the ray, tagged
/// [`RAY_NAME_TAG`].
pub fn ray_label(d: &mut Drawing, at: DVec2, markup: &str) {
    d.text(RAY_NAME_TAG, at, markup, TextOpts::LABEL.avoid_overlap());
}

/// The legend row of a ray role.
pub fn legend_role(d: &mut Drawing, role: RayRole, lang: Lang) {
    let text = match role {
        RayRole::Primary => Label::PrimaryRay,
        RayRole::Reflected => Label::ReflectedRay,
        RayRole::Transmitted => Label::TransmittedRay,
        RayRole::Shadow => Label::ShadowRay,
        RayRole::BlockedShadow => Label::BlockedShadowRay,
        RayRole::OpaqueShadow => Label::OpaqueShadowRay,
    };
    d.legend_entry(text.text(lang), role.style(), LegendIcon::Arrow);
}

/// The legend rows of the points: hit points, lights, the observer (those asked for).
pub fn legend_points(d: &mut Drawing, lang: Lang, hits: bool, lights: bool, observer: bool) {
    if hits {
        d.legend_entry(Label::HitPoint.text(lang), Pen::NONE, LegendIcon::Dot(style::HIT));
    }
    if lights {
        d.legend_entry(
            Label::LightSource.text(lang),
            style::outline(style::BLACK),
            LegendIcon::Dot(style::LIGHT),
        );
    }
    if observer {
        d.legend_entry(Label::Observer.text(lang), Pen::NONE, LegendIcon::Dot(style::BLACK));
    }
}

/// The legend row of normals.
pub fn legend_normal(d: &mut Drawing, lang: Lang) {
    d.legend_entry(Label::Normal.text(lang), style::normal(), LegendIcon::Line);
}

/// The larger side of the points' bounding box (1 when there are none or they are one point).
#[must_use]
pub fn span(points: &[DVec2]) -> f64 {
    let Some(first) = points.first() else { return 1.0 };
    let (lo, hi) = points.iter().fold((*first, *first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let e = (hi - lo).max_element();
    if e > 0.0 {
        e
    } else {
        1.0
    }
}

/// A light lies far when fitting it would leave what the figure is about (the hit, the objects
/// and rays near it) less than this share of the picture's span: the lecturer then draws L
/// leaving the picture towards it ([`far_lights`], [`draw_towards_light`]) instead of shrinking
/// the point into a corner.
pub const FAR_LIGHT_SHARE: f64 = 0.5;

/// Which of `lights` (page points) are far from the points `core` a figure is about: those that
/// would make `core`'s span less than [`FAR_LIGHT_SHARE`] of the span of `core` and that light.
#[must_use]
pub fn far_lights(core: &[DVec2], lights: &[DVec2]) -> Vec<bool> {
    let own = span(core);
    lights
        .iter()
        .map(|l| {
            let mut with = core.to_vec();
            with.push(*l);
            own < FAR_LIGHT_SHARE * span(&with)
        })
        .collect()
}

/// A shadow ray towards a far light: from `from` along `dir` to where it leaves `view`, in
/// `role`'s stroke with its arrow head there, and `name` (e.g. "to the light S") at that end.
pub fn draw_towards_light(d: &mut Drawing, role: RayRole, from: DVec2, dir: DVec2, view: &View, name: &str) {
    // Stop short of the border, so the head and the name stay inside the picture.
    let exit = exit_point(from, dir, view);
    let to = from + (exit - from) * TOWARDS_LIGHT_REACH;
    d.arrow(role.tag(), from, to, role.style());
    label_outward(d, to, dir, name);
}

/// How far towards the picture's border [`draw_towards_light`] draws L, as a share of the way.
pub const TOWARDS_LIGHT_REACH: f64 = 0.92;

/// Fits the view so that `points` fill the left `1 − column` of the plot area, leaving a free
/// column on the right for text; returns the world point at the top left of that column.
pub fn fit_with_column(d: &mut Drawing, points: &[DVec2], margin: f64, column: f64) -> DVec2 {
    let aspect = d.plot_aspect();
    let Some(left) = View::fit(points, margin, aspect * (1.0 - column)) else {
        return DVec2::ZERO;
    };
    let width = left.width() / (1.0 - column);
    if let Some(view) = View::new(left.xmin(), left.xmin() + width, left.ymin(), left.ymax()) {
        d.set_view(view);
    }
    DVec2::new(left.xmax(), left.ymax())
}

/// Stacked lines of text from `top_left` downwards (one line every `step` reference pixels).
pub fn text_column(d: &mut Drawing, top_left: DVec2, lines: &[String], size: TextSize, step: f64) {
    for (k, line) in lines.iter().enumerate() {
        let opts = TextOpts::LABEL
            .size(size)
            .align(Align { h: HAlign::Left, v: VAlign::Top })
            .offset(0.0, -step * k as f64)
            .no_halo();
        d.text("text", top_left, line, opts);
    }
}

/// The caption's tail for a 3D trace drawn on a plane: which plane, and what the outlines mean.
#[must_use]
pub fn plane_note(dim: usize, plane: Label, through: Option<&str>, lang: Lang) -> String {
    if dim == 2 {
        return String::new();
    }
    let through = through.map(|t| format!(" ({} {t})", if lang == Lang::Ro { "prin" } else { "through" }));
    format!(" · {}{}; {}", plane.text(lang), through.unwrap_or_default(), Label::SectionsNote.text(lang))
}

/// A panel's heading above `at`: its first line bold, the rest under it.
pub fn panel_heading(d: &mut Drawing, at: DVec2, text: &str) {
    /// The step between lines, in reference pixels.
    const LINE: f64 = 44.0;
    let lines: Vec<&str> = text.lines().collect();
    for (k, line) in lines.iter().enumerate() {
        let up = 12.0 + LINE * (lines.len() - 1 - k) as f64;
        let opts = TextOpts::LABEL.align(Align::ABOVE).size(TextSize::Body).offset(0.0, up);
        d.text("panel-title", at, line, if k == 0 { opts.bold() } else { opts });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_colours_and_subscripts_for_slides() {
        assert_eq!(deg(std::f64::consts::FRAC_PI_6), "30.0°");
        assert_eq!(rgb_text(Rgb([0.5, 0.5, 0.5])), "0.5");
        assert_eq!(sub("R", 12), "R_{12}");
    }

    #[test]
    fn lines_clip_to_the_view() {
        let view = View::new(-1.0, 1.0, -1.0, 1.0).unwrap();
        let (a, b) = clip_line(DVec2::ZERO, DVec2::X, &view).unwrap();
        assert_eq!((a.x, b.x), (-1.0, 1.0));
        assert!(clip_line(DVec2::new(0.0, 2.0), DVec2::X, &view).is_none());
        assert_eq!(exit_point(DVec2::ZERO, DVec2::new(0.0, 2.0), &view), DVec2::new(0.0, 1.0));
    }
}
