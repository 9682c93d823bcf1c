//! `projections` (lecture "Calculul razelor primare (2), (3)", algorithm.md §2): the primary rays of
//! the same pixels traced with an orthographic camera (left: parallel rays from the window points
//! S, D = [0, 0, −1] in camera space, [0, −1] in 2D's (u, w)) and a perspective one (right: rays
//! from the observer O through S, D = S − O), for the same window at distance p. Each panel is
//! drawn on the plane that holds its row of rays: u to the right and the row's viewing direction
//! up (in 2D, the camera's u and −w). Far hits on unbounded planes are left beyond the panel's
//! edge, so the window stays large enough to read.

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, LegendIcon, Pen, TextOpts, View};
use crate::figure::labels::Label;
use crate::figure::parts::{
    camera_plane, draw_objects, draw_observer, draw_ray, label, label_objects, legend_points, legend_role,
    object_extent, plane_note,
};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::{FigureTrace, Target};
use crate::figure::style::{self, RayRole, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::scene::camera::{Camera, Projection};
use crate::scene::Scene;

/// One primary ray on the page: where it starts and where it ends (a hit, or the far edge).
struct Primary {
    from: DVec2,
    hit: Option<DVec2>,
    dir: DVec2,
}

/// The primary rays of one trace (its roots), on `plane`.
fn primaries<V: Planar>(traced: &FigureTrace<V>, plane: &PagePlane<V>) -> Vec<Primary> {
    traced
        .log
        .roots()
        .map(|k| {
            let n = &traced.log.nodes[k];
            Primary {
                from: plane.point(n.start.origin),
                hit: n.end.as_ref().and_then(|e| e.hit).map(|h| plane.point(h.point)),
                dir: plane.dir(n.start.direction),
            }
        })
        .collect()
}

/// Where a ray reaches the far edge `y_far` of a panel shifted by `offset`.
fn far_end(p: &Primary, y_far: f64, offset: DVec2) -> DVec2 {
    if p.dir.y > 1e-12 {
        p.from + p.dir * ((y_far - (p.from.y - offset.y)) / p.dir.y)
    } else {
        p.from + p.dir.normalize_or_zero() * y_far
    }
}

/// Draws the figure.
///
/// # Errors
/// When the two traces (orthographic, perspective) are not there.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let [ortho, persp] = input.traces.traces.as_slice() else {
        return Err(FigureError("projections needs an orthographic and a perspective trace".into()));
    };
    let (scene, lang) = (input.scene, input.lang);
    let cam = &scene.camera;
    let v_row = match ortho.targets.first() {
        Some(Target::Pixel { uv, .. }) => uv.get(1).copied().unwrap_or(0.0),
        _ => 0.0,
    };
    // The plane of each panel's row of rays: the orthographic rays start on the window row and
    // run along −w; the perspective ones fan out from O through the row.
    let frame = &cam.frame;
    let row_plane = |projection: Projection| {
        let plane = match projection {
            Projection::Orthographic => PagePlane::spanned(cam.eye + frame.v * v_row, frame.u, -frame.w),
            Projection::Perspective => {
                PagePlane::spanned(cam.eye, frame.u, frame.v * v_row - frame.w * cam.p)
            }
        };
        plane.unwrap_or_else(|| camera_plane(scene, cam.eye, true))
    };
    let planes = [row_plane(Projection::Orthographic), row_plane(Projection::Perspective)];
    let window = |plane: &PagePlane<V>| {
        (
            plane.point(cam.window_point(cam.window.l, v_row)),
            plane.point(cam.window_point(cam.window.r, v_row)),
        )
    };

    // One box that holds both panels' content, so that both are drawn at the same scale. It
    // reaches as far as the bounded objects hit (at least 3p); a ray that goes farther leaves it.
    let mut points = Vec::new();
    let mut bounded = Vec::new();
    for (traced, plane) in [ortho, persp].into_iter().zip(&planes) {
        let (wl, wr) = window(plane);
        points.extend([plane.point(cam.eye), wl, wr]);
        for n in &traced.log.nodes {
            if let Some(hit) = n.end.as_ref().and_then(|e| e.hit) {
                if scene.objects[hit.object.index].shape.bounds().is_some() {
                    bounded.push(plane.point(hit.point));
                    points.extend(object_extent(scene, plane, &[hit.object.index]));
                }
            }
        }
    }
    let y_near = points.iter().chain(&bounded).map(|p| p.y).fold(3.0 * cam.p, f64::max);
    let y_far = y_near * 1.1;
    // The end drawn for a ray: its hit when inside the box, else where it reaches y_far.
    let end = |p: &Primary, offset: DVec2| match p.hit {
        Some(h) if h.y <= y_far => h,
        _ => far_end(p, y_far, offset),
    };
    for (traced, plane) in [ortho, persp].into_iter().zip(&planes) {
        points.extend(primaries(traced, plane).iter().map(|p| end(p, DVec2::ZERO)));
    }
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let pad = 0.06 * (hi - lo).max_element();
    let (lo, hi) = (lo - DVec2::splat(pad), hi + DVec2::splat(pad));
    let width = hi.x - lo.x;
    let shift = DVec2::new(width * 1.12, 0.0);

    d.set_title(input.t(Label::TitleProjections));
    let row = match ortho.targets.first() {
        Some(Target::Pixel { j, .. }) if V::DIM == 3 => format!("{} j = {j} · ", input.t(Label::Row)),
        _ => String::new(),
    };
    let columns: Vec<String> = ortho
        .targets
        .iter()
        .filter_map(|t| match t {
            Target::Pixel { i, .. } => Some(i.to_string()),
            Target::Ray => None,
        })
        .collect();
    d.set_caption(&format!(
        "{}{row}{} i = {} · {}{}",
        crate::figure::labels::scene_lead(&input.traces.scene_name, lang),
        input.t(Label::Columns),
        columns.join(", "),
        input.t(Label::PrimaryOnly),
        plane_note(V::DIM, Label::PlaneOfRow, None, lang),
    ));
    legend_role(d, RayRole::Primary, lang);
    legend_points(d, lang, true, false, false);
    d.legend_entry(input.t(Label::ViewWindow), style::view_window(), LegendIcon::Line);
    // Room above the panels for their headings.
    d.fit_view(&[lo, hi + shift + DVec2::new(0.0, 2.5 * pad)], 0.0);

    let mut anchors = Vec::new();
    for ((traced, offset), plane) in [(ortho, DVec2::ZERO), (persp, shift)].into_iter().zip(&planes) {
        let panel = plane.shifted(offset);
        let clip = View::new(lo.x + offset.x, hi.x + offset.x, lo.y, hi.y).unwrap_or(d.view);
        anchors.push((draw_objects(d, scene, &panel, &clip, &[]), offset));
        let (a, b) = window(&panel);
        d.segment("window", a, b, style::view_window());
        for p in primaries(traced, &panel) {
            draw_ray(d, RayRole::Primary, p.from, end(&p, offset));
        }
        let eye = panel.point(cam.eye);
        draw_observer(d, eye);
        for p in primaries(traced, &panel) {
            if let Some(h) = p.hit.filter(|h| h.y <= y_far) {
                d.dot("hit", h, style::HIT);
            }
        }
        // The window points S the rays start at (orthographic) or pass through (perspective).
        for s in window_points(traced, &panel, cam) {
            d.marker(
                "window-point",
                s,
                style::DOT_RADIUS * 0.7,
                style::WHITE,
                style::outline(style::DARK_GREY),
            );
        }
        let heading = if traced.projection == Projection::Orthographic {
            Label::Orthographic
        } else {
            Label::Perspective
        };
        let title_at = DVec2::new((lo.x + hi.x) / 2.0 + offset.x, hi.y);
        let opts = TextOpts::LABEL.align(Align::ABOVE).size(TextSize::Body).bold().offset(0.0, 12.0);
        d.text("panel-title", title_at, input.t(heading), opts);
    }
    // Labels: O, S, D and p in each panel.
    for ((traced, offset), plane) in [(ortho, DVec2::ZERO), (persp, shift)].into_iter().zip(&planes) {
        let panel = plane.shifted(offset);
        let eye = panel.point(cam.eye);
        label(d, eye, "O");
        if let Some(s) = window_points(traced, &panel, cam).last() {
            let opts = TextOpts::LABEL.align(Align::RIGHT_OF).offset(18.0, -6.0);
            d.text("label", *s, "S", opts);
        }
        // D beside the leftmost ray, in the open space left of the bundle (not on the rays).
        if let Some(p) = primaries(traced, &panel).first() {
            let to = end(p, offset);
            // In camera coordinates: (u, v, w) in 3D, (u, w) in 2D, which has no v (§2).
            let text = match (traced.projection, V::DIM) {
                (Projection::Orthographic, 2) => "D = [0, −1]",
                (Projection::Orthographic, _) => "D = [0, 0, −1]",
                (Projection::Perspective, _) => "D = S − O",
            };
            let opts = TextOpts::LABEL.align(Align::LEFT_OF).offset(-12.0, 0.0).avoid_overlap();
            d.text("label", p.from + (to - p.from) * 0.45, text, opts);
        }
        if traced.projection == Projection::Perspective {
            // The distance p, as a dimension line left of the window.
            let (left, _) = window(&panel);
            let x = left.x - 0.04 * width;
            let (a, b) = (DVec2::new(x, eye.y), DVec2::new(x, left.y));
            d.segment("p", a, b, style::normal());
            let opts = TextOpts::LABEL.align(Align::LEFT_OF).offset(-10.0, 0.0);
            d.text("label", (a + b) / 2.0, "p", opts);
        }
    }
    for (list, _) in &anchors {
        label_objects(d, scene, list, input.lang);
    }
    // The spacing of adjacent rays at each row of objects: what aliasing is about.
    for ((traced, offset), plane) in [(ortho, DVec2::ZERO), (persp, shift)].into_iter().zip(&planes) {
        let panel = plane.shifted(offset);
        for row in object_rows(scene, &panel) {
            mark_spacing(d, &primaries(traced, &panel), &row);
        }
    }
    Ok(())
}

/// A row of bounded objects on the page: their centres' common height and their mean x.
struct Row {
    y: f64,
    x: f64,
    /// Half the tallest object's extent along the page's y, to keep the mark clear of the row.
    half_height: f64,
}

/// The rows of objects in a panel: two or more bounded objects whose centres lie at one height
/// (one distance along the viewing direction), the depths at which the ray spacing is marked.
fn object_rows<V: Planar>(scene: &Scene<V>, plane: &PagePlane<V>) -> Vec<Row> {
    let mut centres: Vec<(DVec2, f64)> = scene
        .objects
        .iter()
        .filter_map(|o| {
            let (lo, hi) = o.shape.bounds()?;
            let (a, b) = (plane.point(lo), plane.point(hi));
            Some((plane.point((lo + hi) * 0.5), (a.y - b.y).abs() / 2.0))
        })
        .collect();
    centres.sort_by(|a, b| a.0.y.total_cmp(&b.0.y));
    let mut rows = Vec::new();
    for group in centres.chunk_by(|a, b| (a.0.y - b.0.y).abs() <= ROW_TOLERANCE * (1.0 + a.0.y.abs())) {
        if group.len() >= 2 {
            let x = group.iter().map(|c| c.0.x).sum::<f64>() / group.len() as f64;
            let half_height = group.iter().map(|c| c.1).fold(0.0, f64::max);
            rows.push(Row { y: group[0].0.y, x, half_height });
        }
    }
    rows
}

/// Centres whose heights differ by less than this (relative) are one row.
const ROW_TOLERANCE: f64 = 1e-9;

/// Marks the distance between two adjacent primary rays near the middle of `row`, measured where
/// they cross the row's height: a dimension line just beyond the row (one object's half-height
/// past its far side), joined to the crossings by extension lines, labelled `Δ = 3`. Only a pair
/// whose two rays reach the line is marked (a ray stopped by an object of the row does not).
fn mark_spacing(d: &mut Drawing, rays: &[Primary], row: &Row) {
    let y = row.y + 2.0 * row.half_height;
    let mut crossings: Vec<(f64, bool)> = rays
        .iter()
        .filter(|p| p.dir.y > 1e-12)
        .map(|p| (p.from.x + p.dir.x * (row.y - p.from.y) / p.dir.y, p.hit.is_none_or(|h| h.y >= y)))
        .collect();
    crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
    let middle = |(a, b): (f64, f64)| ((a + b) / 2.0 - row.x).abs();
    let Some((a, b)) = crossings
        .windows(2)
        .filter(|w| w[0].1 && w[1].1)
        .map(|w| (w[0].0, w[1].0))
        .min_by(|p, q| middle(*p).total_cmp(&middle(*q)))
    else {
        return;
    };
    for x in [a, b] {
        d.segment("spacing", DVec2::new(x, row.y), DVec2::new(x, y), style::normal());
    }
    let line = Pen::solid(style::DARK_GREY, style::CONSTRUCTION_WIDTH);
    d.segment("spacing", DVec2::new(a, y), DVec2::new(b, y), line);
    let opts = TextOpts::LABEL.align(Align::ABOVE).offset(0.0, 4.0).avoid_overlap();
    d.text("spacing", DVec2::new((a + b) / 2.0, y), &format!("Δ = {}", slide_number(b - a)), opts);
}

/// The window points S of a trace's pixels, on `plane`.
fn window_points<V: Planar>(traced: &FigureTrace<V>, plane: &PagePlane<V>, cam: &Camera<V>) -> Vec<DVec2> {
    traced
        .targets
        .iter()
        .filter_map(|t| match t {
            Target::Pixel { uv, .. } => {
                let cam_v = uv.get(1).copied().unwrap_or(0.0);
                Some((uv[0], cam_v))
            }
            Target::Ray => None,
        })
        .map(|(u, v)| plane.point(cam.window_point(u, v)))
        .collect()
}
