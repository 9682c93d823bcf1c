//! `grid-dda` (lecture "Scena divizată în volume încadratoare (1), (2)", algorithm.md §9 "Regular
//! grid", §11 "The voxel DDA"): the regular grid over the scene's box and the cells one primary
//! ray's recorded walk visited, numbered in order, with the point where it leaves each (the
//! smallest tMax) and beside them each step's cell, tMax per axis and the objects tested there;
//! and the lecture's pitfall when the walk met it: a hit found while visiting a cell but lying
//! beyond that cell is not accepted until the walk reaches it. Traced with `--accel grid`.

use glam::DVec2;

use super::Input;
use crate::accel::Layout;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign, View};
use crate::figure::labels::{self, Label};
use crate::figure::parts::{self, draw_objects, draw_ray, label_objects, text_column};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::{first_hit, grid_pitfall, search_indexed, GridPitfall};
use crate::figure::style::{self, RayRole, TextSize};
use crate::figure::FigureError;
use crate::format::markup_escape;
use crate::format::slide_number;
use crate::record::event::Event;

/// The most cells drawn along one axis of the page: the heuristic's own cap per axis. Denser
/// lines would merge at slide size, and `--grid` can ask for 2^24 cells along one axis.
pub const MAX_DRAWN_CELLS: usize = crate::accel::grid::MAX_CELLS_PER_AXIS;

/// A step's number sits this far inside its cell's corner, in reference pixels (x, y).
const STEP_INSET: DVec2 = DVec2::new(5.0, 3.0);

/// At most this many steps are listed in the table.
const LISTED: usize = 7;

/// One recorded step of the walk.
struct Step<'a> {
    /// The index of its `voxel_step` event.
    event: usize,
    cell: &'a [i64],
    t_max: &'a [f64],
    objects: Vec<usize>,
}

/// Draws the figure.
///
/// # Errors
/// When the traces were not recorded with a grid.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let Layout::Grid { bounds, cells } = input.traces.accel.layout() else {
        return Err(FigureError("grid-dda: the traces were not recorded with a grid".into()));
    };
    if bounds.is_empty() {
        return Err(FigureError("grid-dda: the scene has no bounded object to build a grid over".into()));
    }
    let (scene, log) = (input.scene, &traced.log);
    let root = log.nodes.first().ok_or_else(|| FigureError("no ray was traced".into()))?;
    let steps: Vec<Step<'_>> = search_indexed(log, 0)
        .filter_map(|(event, e)| match e {
            Event::VoxelStep { cell, t_max, objects, .. } => {
                Some(Step { event, cell, t_max, objects: objects.iter().map(|o| o.index).collect() })
            }
            _ => None,
        })
        .collect();
    let hit = first_hit(log).filter(|k| *k == 0).and_then(|k| log.nodes[k].end.as_ref()?.hit);
    // Each visited cell's scene box, and the objects it lists that do not reach into it: the grid
    // inserts by bounding boxes (algorithm.md §9), so a box may put an object in a cell that the
    // object itself misses.
    let cell_box = |c: &[i64]| {
        let (mut lo, mut hi) = (V::ZERO, V::ZERO);
        for a in 0..V::DIM {
            let size = (bounds.max[a] - bounds.min[a]) / cells[a] as f64;
            lo[a] = bounds.min[a] + c[a] as f64 * size;
            hi[a] = lo[a] + size;
        }
        (lo, hi)
    };
    let box_only: Vec<Vec<usize>> = steps
        .iter()
        .map(|s| {
            let (lo, hi) = cell_box(s.cell);
            s.objects.iter().copied().filter(|o| !scene.objects[*o].shape.meets_box(lo, hi)).collect()
        })
        .collect();
    let pitfall = grid_pitfall(log);

    // 2D: the scene's plane; 3D: the plane of the two axes the ray moves most along.
    let dir = root.start.direction;
    let axes: [usize; 2] = if V::DIM == 2 {
        [0, 1]
    } else {
        let dropped = (0..3).fold(0, |m, a| if dir[a].abs() < dir[m].abs() { a } else { m });
        let kept: Vec<usize> = (0..3).filter(|a| *a != dropped).collect();
        [kept[0], kept[1]]
    };
    // In 3D the plane passes through the hit (or the ray's origin), so the objects the ray meets
    // are cut where it meets them.
    let through = hit.map_or(root.start.origin, |h| h.point);
    let plane =
        PagePlane::spanned(if V::DIM == 2 { V::ZERO } else { through }, V::axis(axes[0]), V::axis(axes[1]))
            .ok_or_else(|| FigureError("no plane for the grid".into()))?;
    let names = ["x", "y", "z"];

    d.set_title(input.t(Label::TitleGridDda));
    let resolution: Vec<String> = cells.iter().map(ToString::to_string).collect();
    let object_tests = search_indexed(log, 0).filter(|(_, e)| matches!(e, Event::ObjectTest { .. })).count();
    let mut caption = format!(
        "{} · {} {} · {}: {} · {}",
        input.traced(traced),
        input.t(Label::Grid),
        resolution.join(" × "),
        input.t(Label::CellsVisited),
        steps.len(),
        labels::objects_tested(object_tests, scene.objects.len(), input.lang)
    );
    if V::DIM == 3 {
        caption.push_str(&format!(" · {} {}{}", input.t(Label::AxisPlane), names[axes[0]], names[axes[1]]));
    }
    d.set_caption(&caption);
    parts::legend_role(d, RayRole::Primary, input.lang);
    d.legend_entry(input.t(Label::CellVisited), Pen::NONE, LegendIcon::Swatch(visited_fill()));
    d.legend_entry(input.t(Label::CellExit), Pen::NONE, LegendIcon::Dot(style::ORANGE));
    if pitfall.is_some() {
        d.legend_entry(input.t(Label::FoundBeyond), pitfall_ring(), LegendIcon::Dot(style::WHITE));
    }
    if box_only.iter().any(|b| !b.is_empty()) {
        d.legend_entry(input.t(Label::ListedByBox), box_only_pen(), LegendIcon::Line);
    }
    // Under the table, in the column kept free of the scene (the table is at most 13 lines).
    d.legend_place = crate::canvas::LegendPlace::Inside(crate::canvas::Corner::BottomRight);

    // The grid's rectangle on the page and the size of a cell.
    let (lo, hi) = (plane.point(bounds.min), plane.point(bounds.max));
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    let n = [cells[axes[0]], cells[axes[1]]];
    if n.iter().any(|k| *k > MAX_DRAWN_CELLS) {
        return Err(FigureError(format!(
            "a {}x{} grid on the page is more than the {MAX_DRAWN_CELLS} cells an axis may draw legibly; give a \
             smaller --grid",
            n[0], n[1]
        )));
    }
    let size = DVec2::new((hi.x - lo.x) / n[0] as f64, (hi.y - lo.y) / n[1] as f64);
    let cell_rect = |c: &[i64]| {
        let at = DVec2::new(c[axes[0]] as f64, c[axes[1]] as f64);
        (lo + at * size, lo + (at + DVec2::ONE) * size)
    };
    let ray_at = |t: f64| plane.point(root.start.origin + dir * t);
    let mut points = vec![lo, hi];
    let from = plane.point(root.start.origin);
    let span = parts::span(&points);
    points.push(from.clamp(lo - DVec2::splat(0.3 * span), hi + DVec2::splat(0.3 * span)));
    let column = parts::fit_with_column(d, &points, 0.05, 0.42);
    let view = d.view;
    let scene_part = View::new(view.xmin(), column.x, view.ymin(), view.ymax()).unwrap_or(view);

    // Visited cells, the grid, the objects.
    for s in &steps {
        let (a, b) = cell_rect(s.cell);
        d.with_events([s.event], |d| {
            d.rect("cell:visited", a, b, Pen::NONE, Some(visited_fill()));
        });
    }
    for k in 0..=n[0] {
        let x = lo.x + k as f64 * size.x;
        d.segment("grid", DVec2::new(x, lo.y), DVec2::new(x, hi.y), style::grid());
    }
    for k in 0..=n[1] {
        let y = lo.y + k as f64 * size.y;
        d.segment("grid", DVec2::new(lo.x, y), DVec2::new(hi.x, y), style::grid());
    }
    d.rect("grid-box", lo, hi, style::outline(style::DARK_GREY), None);
    let anchors = draw_objects(d, scene, &plane, &scene_part, &[]);
    // An object listed only through its box: that box, dashed, lit with the cells that list it.
    let mut outlined: Vec<usize> = Vec::new();
    for &o in box_only.iter().flatten() {
        if outlined.contains(&o) {
            continue;
        }
        outlined.push(o);
        let Some((lo, hi)) = scene.objects[o].shape.bounds() else { continue };
        let (a, b) = (plane.point(lo), plane.point(hi));
        let events: Vec<usize> =
            box_only.iter().zip(&steps).filter(|(b, _)| b.contains(&o)).map(|(_, s)| s.event).collect();
        d.with_events(events, |d| {
            d.rect(&format!("object-box-only:{o}"), a.min(b), a.max(b), box_only_pen(), None);
        });
    }

    // The ray, from where it enters the picture to its hit or the picture's edge.
    let start = parts::entry_point(from, plane.dir(dir), &scene_part);
    let end =
        hit.map_or_else(|| parts::exit_point(start, plane.dir(dir), &scene_part), |h| plane.point(h.point));
    d.with_events(log.ray_events(0), |d| draw_ray(d, RayRole::Primary, start, end));
    // Where the ray leaves each visited cell: its smallest tMax; none past the accepted hit
    // (the ray ends there: the hit's cell is left by no ray).
    for s in &steps {
        let exit = s.t_max.iter().copied().fold(f64::INFINITY, f64::min);
        if exit.is_finite() && hit.is_none_or(|h| exit <= h.t) {
            d.with_events([s.event], |d| {
                d.marker("cell-exit", ray_at(exit), style::DOT_RADIUS * 0.8, style::ORANGE, Pen::NONE);
            });
        }
    }
    if let Some(GridPitfall { t, .. }) = pitfall {
        d.marker("pitfall", ray_at(t), 22.0, style::WHITE.with_alpha(0.0), pitfall_ring());
    }
    if let Some(h) = hit {
        d.with_events(log.ended_by(0), |d| {
            d.dot("hit", plane.point(h.point), style::HIT);
        });
    }
    // Each step's number in its cell's top left corner, or in the first other corner, else
    // beside the middle of a side, where the ray's stroke does not run through it (else placed
    // clear near the cell's centre, with a leader): the ray never hides it.
    let tf = d.transform();
    let (ray_a, ray_b) = (tf.to_px(start), tf.to_px(end));
    let stroke = tf.ref_px(style::RAY_WIDTH) / 2.0;
    for (k, s) in steps.iter().enumerate() {
        let (a, b) = cell_rect(s.cell);
        let (number, mid) = ((k + 1).to_string(), (a + b) / 2.0);
        let in_corner = |(at, h, v): (DVec2, HAlign, VAlign)| {
            let sx = match h {
                HAlign::Left => 1.0,
                HAlign::Center => 0.0,
                HAlign::Right => -1.0,
            };
            let sy = match v {
                VAlign::Top => -1.0,
                VAlign::Bottom => 1.0,
                VAlign::Middle | VAlign::Baseline => 0.0,
            };
            let opts = TextOpts::NOTE
                .size(TextSize::Small)
                .align(Align { h, v })
                .offset(sx * STEP_INSET.x, sy * STEP_INSET.y)
                .bold();
            let label = opts.label(&number, at);
            // Neither the ray nor another object's outline may run through it (issue 32 item 1).
            let crossed = Drawing::ink_box(&label, &tf).inflate(stroke).length_inside(ray_a, ray_b)
                + d.outline_crossing("step", &label, style::OBJECT_TAG);
            (crossed, at, opts)
        };
        let corners = [
            (DVec2::new(a.x, b.y), HAlign::Left, VAlign::Top),
            (b, HAlign::Right, VAlign::Top),
            (a, HAlign::Left, VAlign::Bottom),
            (DVec2::new(b.x, a.y), HAlign::Right, VAlign::Bottom),
            (DVec2::new(a.x, mid.y), HAlign::Left, VAlign::Middle),
            (DVec2::new(b.x, mid.y), HAlign::Right, VAlign::Middle),
            (DVec2::new(mid.x, b.y), HAlign::Center, VAlign::Top),
            (DVec2::new(mid.x, a.y), HAlign::Center, VAlign::Bottom),
        ]
        .map(in_corner);
        let free = corners.iter().find(|c| c.0 <= 0.0);
        d.with_events([s.event], |d| match free {
            Some((_, at, opts)) => {
                d.text("step", *at, &number, *opts);
            }
            // A cell too small for a number beside the ray: near it, clear, with a leader.
            None => {
                let opts = TextOpts::NOTE.size(TextSize::Small).bold().avoid_overlap_with_leader();
                d.text("step", mid, &number, opts);
            }
        });
    }
    label_objects(d, scene, &anchors, input.lang);

    // The table of steps and the pitfall, in the column.
    let axis_names: Vec<&str> = (0..V::DIM).map(|a| names[a]).collect();
    let mut lines = vec![format!(
        "k: {} · tMax({}) · {}",
        input.t(Label::Cell),
        axis_names.join(", "),
        input.t(Label::ObjectsTested)
    )];
    for (k, s) in steps.iter().enumerate().take(LISTED) {
        let cell: Vec<String> = s.cell.iter().map(ToString::to_string).collect();
        let t_max: Vec<String> = s.t_max.iter().map(|t| slide_number(*t)).collect();
        let objects: Vec<String> = s
            .objects
            .iter()
            .map(|o| {
                let name = markup_escape(&scene.object_label(*o, input.lang));
                if box_only[k].contains(o) {
                    format!("{name} ({})", input.t(Label::BoxOnly))
                } else {
                    name
                }
            })
            .collect();
        let objects = if objects.is_empty() { "—".to_owned() } else { objects.join(", ") };
        lines.push(format!("{}: ({}) · ({}) · {objects}", k + 1, cell.join(", "), t_max.join(", ")));
    }
    if steps.len() > LISTED {
        lines.push("…".to_owned());
    }
    if let Some(GridPitfall { step, object, t, exit }) = pitfall {
        lines.push(String::new());
        lines.push(format!(
            "{} {}: {}",
            input.t(Label::PitfallIn),
            step + 1,
            markup_escape(&scene.object_label(object, input.lang))
        ));
        lines.push(format!(
            "   t = {} > {} = {}",
            slide_number(t),
            input.t(Label::CellExitT),
            slide_number(exit)
        ));
        lines.extend(input.t(Label::PitfallRule).split('\n').map(str::to_owned));
    }
    if let Some(h) = hit {
        lines.push(format!(
            "{}: {} (t = {})",
            input.t(Label::HitPoint),
            markup_escape(&scene.object_label(h.object.index, input.lang)),
            slide_number(h.t)
        ));
    }
    text_column(
        d,
        column + DVec2::new(0.02 * view.width(), -0.02 * view.height()),
        &lines,
        TextSize::Small,
        40.0,
    );
    Ok(())
}

/// Visited cells: a light fill of the entered-node green.
fn visited_fill() -> style::Rgba {
    style::BLUISH_GREEN.with_alpha(0.25)
}

/// The bounding box of an object listed only through it: thin, dashed, reddish purple.
fn box_only_pen() -> Pen {
    Pen::solid(style::REDDISH_PURPLE, style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH)
}

/// The ring around a hit found beyond its cell.
fn pitfall_ring() -> Pen {
    Pen::solid(style::VERMILLION, style::CONSTRUCTION_WIDTH * 1.4)
}
