//! `projections` (lecture "Calculul razelor primare (2), (3)", algorithm.md §2): the primary rays of
//! the same pixels traced with an orthographic camera (left: parallel rays from the window points
//! S, D = [0, 0, −1] in camera space) and a perspective one (right: rays from the observer O
//! through S, D = S − O), for the same window at distance p. A 2D scene is drawn in its own axes,
//! x to the right and y up, as every 2D figure draws it (the camera's −w is then the direction
//! the rays run on the page, and the printed D is the scene's); a 3D scene has no 2D axes of its
//! own, so each panel is drawn on the plane that holds its row of rays: u to the right and the
//! row's viewing direction up. Far hits on unbounded planes are left beyond the panel's edge, so
//! the window stays large enough to read.

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

/// One primary ray in its row's plane: where it starts and where it ends (a hit, or the far edge).
struct Primary {
    from: DVec2,
    hit: Option<DVec2>,
    dir: DVec2,
}

/// A panel's two planes: `row`, the plane of its row of rays, in which the figure measures how
/// far a point lies along the viewing direction (its y); and `page`, the plane it is drawn on —
/// the scene's own axes in 2D, `row` itself in 3D.
#[derive(Clone, Copy)]
struct Panel<V> {
    row: PagePlane<V>,
    page: PagePlane<V>,
}

impl<V: Planar> Panel<V> {
    /// The panel of `row` (unshifted).
    fn new(row: PagePlane<V>) -> Self {
        let page = if V::DIM == 2 {
            PagePlane { origin: V::ZERO, x: V::axis(0), y: V::axis(1), offset: DVec2::ZERO }
        } else {
            row
        };
        Self { row, page }
    }

    /// The same panel drawn `offset` to the side.
    fn shifted(self, offset: DVec2) -> Self {
        Self { page: self.page.shifted(offset), ..self }
    }

    /// The page position of the point `q` of the row's plane: the scene point
    /// `row.origin + q.x·row.x + q.y·row.y` on the page.
    fn at(&self, q: DVec2) -> DVec2 {
        self.page.point(self.row.origin + self.row.x * q.x + self.row.y * q.y)
    }

    /// The page components of the row's direction `q`.
    fn along(&self, q: DVec2) -> DVec2 {
        self.page.dir(self.row.x * q.x + self.row.y * q.y)
    }
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

/// Where a ray reaches the far edge `y_far` of its row's plane.
fn far_end(p: &Primary, y_far: f64) -> DVec2 {
    if p.dir.y > 1e-12 {
        p.from + p.dir * ((y_far - p.from.y) / p.dir.y)
    } else {
        p.from + p.dir.normalize_or_zero() * y_far
    }
}

/// The printed direction of the orthographic rays: in 2D the scene's `−w` (the page's, since a 2D
/// scene is drawn in its own axes); in 3D the lecture's camera-space `[0, 0, −1]`.
fn orthographic_direction<V: Planar>(cam: &Camera<V>) -> String {
    if V::DIM == 2 {
        let d = -cam.frame.w;
        format!("D = [{}, {}]", slide_number(d[0]), slide_number(d[1]))
    } else {
        "D = [0, 0, −1]".to_owned()
    }
}

/// Where the second panel starts, in widths of the first.
const PANEL_STEP: f64 = 1.12;
/// The room above the panels for their headings, in paddings.
const HEADING_ROOM: f64 = 2.5;
/// The padding around a panel's content, as a share of its larger side.
const PAD_SHARE: f64 = 0.06;
/// How far past the farthest bounded object the rays are drawn: `y_far = 1.1 ·` its depth.
const FAR_MARGIN: f64 = 1.1;

/// The plane of a row of rays (`v_row`: the row's v on the window): the orthographic rays start on
/// the window row and run along −w; the perspective ones fan out from O through the row.
pub(crate) fn row_plane<V: Planar>(scene: &Scene<V>, projection: Projection, v_row: f64) -> PagePlane<V> {
    let cam = &scene.camera;
    let frame = &cam.frame;
    let plane = match projection {
        Projection::Orthographic => PagePlane::spanned(cam.eye + frame.v * v_row, frame.u, -frame.w),
        Projection::Perspective => PagePlane::spanned(cam.eye, frame.u, frame.v * v_row - frame.w * cam.p),
    };
    plane.unwrap_or_else(|| camera_plane(scene, cam.eye, true))
}

/// What the figure's panels hold: `y_far`, how far along the viewing direction (each row plane's
/// y) the rays are drawn, and the page box `lo`–`hi` (padded by `pad`) that holds either panel.
pub(crate) struct Extent {
    pub(crate) y_far: f64,
    pub(crate) lo: DVec2,
    pub(crate) hi: DVec2,
    pub(crate) pad: f64,
}

/// The [`Extent`] of the two traces' panels.
pub(crate) fn extent<V: Planar>(
    scene: &Scene<V>,
    ortho: &FigureTrace<V>,
    persp: &FigureTrace<V>,
    v_row: f64,
) -> Extent {
    let cam = &scene.camera;
    let window = |plane: &PagePlane<V>| {
        [
            plane.point(cam.window_point(cam.window.l, v_row)),
            plane.point(cam.window_point(cam.window.r, v_row)),
        ]
    };
    let panels = [
        Panel::new(row_plane(scene, Projection::Orthographic, v_row)),
        Panel::new(row_plane(scene, Projection::Perspective, v_row)),
    ];
    // How far the rays are drawn: past every bounded object (at least 3p), those the rays hit
    // and those they pass between; a ray that goes farther ends there.
    let bounded: Vec<usize> =
        (0..scene.objects.len()).filter(|k| scene.objects[*k].shape.bounds().is_some()).collect();
    let mut along = Vec::new();
    for (traced, panel) in [ortho, persp].into_iter().zip(&panels) {
        along.push(panel.row.point(cam.eye));
        along.extend(window(&panel.row));
        along.extend(object_extent(scene, &panel.row, &bounded));
        for n in &traced.log.nodes {
            if let Some(hit) = n.end.as_ref().and_then(|e| e.hit) {
                if scene.objects[hit.object.index].shape.bounds().is_some() {
                    along.push(panel.row.point(hit.point));
                }
            }
        }
    }
    let y_far = along.iter().map(|p| p.y).fold(3.0 * cam.p, f64::max) * FAR_MARGIN;
    // One box on the page that holds both panels' content, so that both are drawn at one scale.
    let mut points = Vec::new();
    for (traced, panel) in [ortho, persp].into_iter().zip(&panels) {
        points.push(panel.page.point(cam.eye));
        points.extend(window(&panel.page));
        for n in &traced.log.nodes {
            if let Some(hit) = n.end.as_ref().and_then(|e| e.hit) {
                let object = hit.object.index;
                if scene.objects[object].shape.bounds().is_some() {
                    points.extend(object_extent(scene, &panel.page, &[object]));
                }
            }
        }
        points.extend(primaries(traced, &panel.row).iter().map(|p| panel.at(drawn_end(p, y_far))));
    }
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let pad = PAD_SHARE * (hi - lo).max_element();
    Extent { y_far, lo: lo - DVec2::splat(pad), hi: hi + DVec2::splat(pad), pad }
}

/// The plot area of a slide the figure is fitted into, in reference pixels (the slide less its
/// title and caption): what [`slide_scale`] estimates the scale from before the figure is drawn.
const SLIDE_PLOT: DVec2 = DVec2::new(1840.0, 800.0);

/// The reference pixels per scene unit the figure of `extent` gets on a slide: its two panels
/// side by side and the headings' room fitted into [`SLIDE_PLOT`] (an estimate: the legend and
/// the caption's lines move the plot area a little).
pub(crate) fn slide_scale(extent: &Extent) -> f64 {
    let size = extent.hi - extent.lo;
    let (width, height) = (size.x * (1.0 + PANEL_STEP), size.y + HEADING_ROOM * extent.pad);
    (SLIDE_PLOT.x / width).min(SLIDE_PLOT.y / height)
}

/// How far root `root` of `traced`, drawn in its row's plane `plane` up to `y_far`, passes from
/// the outlines of the objects it does not end on, in scene units (in its row's plane; infinity
/// when it passes none). Outlines it crosses (a 3D silhouette it passes over) do not count.
pub(crate) fn ray_clearance<V: Planar>(
    scene: &Scene<V>,
    plane: &PagePlane<V>,
    traced: &FigureTrace<V>,
    root: usize,
    y_far: f64,
) -> f64 {
    let n = &traced.log.nodes[root];
    let hit = n.end.as_ref().and_then(|e| e.hit);
    let p = Primary {
        from: plane.point(n.start.origin),
        hit: hit.map(|h| plane.point(h.point)),
        dir: plane.dir(n.start.direction),
    };
    let to = drawn_end(&p, y_far);
    let touched = hit.filter(|h| plane.point(h.point).y <= y_far).map(|h| h.object.index);
    scene
        .objects
        .iter()
        .enumerate()
        .filter(|(k, _)| Some(*k) != touched)
        .flat_map(|(_, o)| V::outlines(&o.shape, plane))
        .map(|o| o.outline.gap(p.from, to))
        .filter(|gap| *gap > TOUCHING)
        .fold(f64::INFINITY, f64::min)
}

/// A gap at most this (scene units) is a touch, not a miss.
const TOUCHING: f64 = 1e-9;

/// The end drawn for a ray, in its row's plane: its hit when inside `y_far`, else where it reaches it.
fn drawn_end(p: &Primary, y_far: f64) -> DVec2 {
    match p.hit {
        Some(h) if h.y <= y_far => h,
        _ => far_end(p, y_far),
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
    let panels = [
        Panel::new(row_plane(scene, Projection::Orthographic, v_row)),
        Panel::new(row_plane(scene, Projection::Perspective, v_row)),
    ];
    let window = |plane: &PagePlane<V>| {
        (
            plane.point(cam.window_point(cam.window.l, v_row)),
            plane.point(cam.window_point(cam.window.r, v_row)),
        )
    };
    let Extent { y_far, lo, hi, pad } = extent(scene, ortho, persp, v_row);
    let end = |p: &Primary| drawn_end(p, y_far);
    let width = hi.x - lo.x;
    let shift = DVec2::new(width * PANEL_STEP, 0.0);

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
    d.fit_view(&[lo, hi + shift + DVec2::new(0.0, HEADING_ROOM * pad)], 0.0);

    let traces = [(ortho, DVec2::ZERO), (persp, shift)];
    let mut anchors = Vec::new();
    for ((traced, offset), panel) in traces.into_iter().zip(panels) {
        let panel = panel.shifted(offset);
        let clip = View::new(lo.x + offset.x, hi.x + offset.x, lo.y, hi.y).unwrap_or(d.view);
        anchors.push(draw_objects(d, scene, &panel.page, &clip, &[]));
        let (a, b) = window(&panel.page);
        d.segment("window", a, b, style::view_window());
        let rays = primaries(traced, &panel.row);
        for p in &rays {
            draw_ray(d, RayRole::Primary, panel.at(p.from), panel.at(end(p)));
        }
        draw_observer(d, panel.page.point(cam.eye));
        for h in rays.iter().filter_map(|p| p.hit).filter(|h| h.y <= y_far) {
            d.dot("hit", panel.at(h), style::HIT);
        }
        // The window points S the rays start at (orthographic) or pass through (perspective).
        for s in window_points(traced, &panel.page, cam) {
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
    for ((traced, offset), panel) in traces.into_iter().zip(panels) {
        let panel = panel.shifted(offset);
        let eye = panel.page.point(cam.eye);
        label(d, eye, "O");
        if let Some(s) = window_points(traced, &panel.page, cam).last() {
            // Right of the last window point, a little back from where its ray runs.
            let back = -6.0 * panel.along(DVec2::Y).y.signum();
            let opts = TextOpts::LABEL.align(Align::RIGHT_OF).offset(18.0, back);
            d.text("label", *s, "S", opts);
        }
        // D beside the leftmost ray, in the open space left of the bundle (not on the rays).
        if let Some(p) = primaries(traced, &panel.row).first() {
            let text = match traced.projection {
                Projection::Orthographic => orthographic_direction(cam),
                Projection::Perspective => "D = S − O".to_owned(),
            };
            let opts = TextOpts::LABEL.align(Align::LEFT_OF).offset(-12.0, 0.0).avoid_overlap();
            d.text("label", panel.at(p.from + (end(p) - p.from) * 0.45), &text, opts);
        }
        if traced.projection == Projection::Perspective {
            // The distance p, as a dimension line beside the window, from O's depth to the window's.
            let (left, _) = window(&panel.row);
            let x = left.x - 0.04 * width;
            let (a, b) =
                (panel.at(DVec2::new(x, panel.row.point(cam.eye).y)), panel.at(DVec2::new(x, left.y)));
            d.segment("p", a, b, style::normal());
            let opts = TextOpts::LABEL.align(Align::LEFT_OF).offset(-10.0, 0.0);
            d.text("label", (a + b) / 2.0, "p", opts);
        }
    }
    for list in &anchors {
        label_objects(d, scene, list, input.lang);
    }
    // The spacing of adjacent rays at each row of objects: what aliasing is about.
    for ((traced, offset), panel) in traces.into_iter().zip(panels) {
        let panel = panel.shifted(offset);
        for row in object_rows(scene, &panel.row) {
            mark_spacing(d, &primaries(traced, &panel.row), &row, &panel);
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
/// past its far side), joined to the crossings by extension lines, labelled `Δ = 3` on the side
/// away from the row. Only a pair whose two rays reach the line is marked (a ray stopped by an
/// object of the row does not). Computed in the row's plane, drawn through `panel`.
fn mark_spacing<V: Planar>(d: &mut Drawing, rays: &[Primary], row: &Row, panel: &Panel<V>) {
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
        d.segment("spacing", panel.at(DVec2::new(x, row.y)), panel.at(DVec2::new(x, y)), style::normal());
    }
    let line = Pen::solid(style::DARK_GREY, style::CONSTRUCTION_WIDTH);
    d.segment("spacing", panel.at(DVec2::new(a, y)), panel.at(DVec2::new(b, y)), line);
    // Beyond the line, away from the row: down the page when the rays run down it.
    let (align, gap) = if panel.along(DVec2::Y).y < 0.0 { (Align::BELOW, -4.0) } else { (Align::ABOVE, 4.0) };
    let opts = TextOpts::LABEL.align(align).offset(0.0, gap).avoid_overlap_with_leader().far();
    let at = panel.at(DVec2::new((a + b) / 2.0, y));
    d.text("spacing", at, &format!("Δ = {}", slide_number(b - a)), opts);
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
