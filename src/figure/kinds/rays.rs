//! `rays` (lecture "Razele folosite în Ray tracing", algorithm.md §3–§4): every ray of one pixel's
//! trace, coloured by kind — the primary ray P, the reflected R_k and transmitted T_k spawned at
//! each hit I_k, the shadow rays L towards the lights (blocked ones dashed, with the point where
//! they meet an object) — over the scene's objects, the observer O, the view window and the lights.
//! A 3D trace is drawn on the camera's (u, w) plane through I₁.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, LegendIcon, Pen, View};
use crate::figure::inset::{self, Panel};
use crate::figure::labels::Label;
use crate::figure::parts::{
    self, camera_plane, draw_light, draw_objects_through, draw_observer, draw_ray, exit_point, label,
    label_objects, legend_normal, legend_points, legend_role, plane_note, shadow_block_t, Names,
};
use crate::figure::plane::{Outline, PagePlane, Planar};
use crate::figure::source::{first_hit, Target};
use crate::figure::style::{self, RayRole};
use crate::figure::FigureError;
use crate::format::{markup_escape, slide_number};
use crate::record::event::Event;
use crate::scene::Scene;

/// The drawn length of a normal N, as a share of the view's smaller side: long enough that its
/// dashes read at slide size beside a ray that leaves along it.
const NORMAL_SHARE: f64 = 0.12;

/// The margin around the points the view is fitted to, a share of their larger extent.
const FIT_MARGIN: f64 = 0.06;

/// Where a ray's name stands, as a share of the way from its origin to its end on the page.
const RAY_NAME_AT: f64 = 0.3;

/// Draws the figure.
///
/// # Errors
/// When no trace was recorded.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let (log, scene, lang) = (&traced.log, input.scene, input.lang);
    let names = Names::of(log);
    let first = first_hit(log);
    let cam = &scene.camera;
    let through = first.and_then(|k| log.nodes[k].end.as_ref()?.hit.map(|h| h.point)).unwrap_or(cam.eye);
    let plane = camera_plane(scene, through, false);

    // The rays: every node, from its origin to its hit (or out of the picture).
    struct Segment {
        node: usize,
        from: DVec2,
        to: Option<DVec2>,
        dir: DVec2,
    }
    let segments: Vec<Segment> = log
        .nodes
        .iter()
        .enumerate()
        .map(|(node, n)| Segment {
            node,
            from: plane.point(n.start.origin),
            to: n.end.as_ref().and_then(|e| e.hit).map(|h| plane.point(h.point)),
            dir: plane.dir(n.start.direction),
        })
        .collect();
    // The shadow rays: origin, light, and where an occluder stops them.
    struct Shadow {
        event: usize,
        from: DVec2,
        to: DVec2,
        block: Option<DVec2>,
        role: RayRole,
    }
    let shadows: Vec<Shadow> = log
        .events
        .iter()
        .enumerate()
        .filter_map(|(index, l)| match &l.event {
            Event::ShadowRay { light, origin, direction, occluders, s, .. } => Some(Shadow {
                event: index,
                from: plane.point(*origin),
                to: plane.point(scene.lights[*light].position),
                block: (!occluders.is_empty())
                    .then(|| shadow_block_t(log, index).map(|t| plane.point(*origin + *direction * t)))
                    .flatten(),
                role: RayRole::shadow(*s, !occluders.is_empty()),
            }),
            _ => None,
        })
        .collect();
    let pixel_uv = traced.targets.first().and_then(|t| match t {
        Target::Pixel { uv, .. } => Some(uv.clone()),
        Target::Ray => None,
    });
    let window = pixel_uv.map(|uv| {
        let v = uv.get(1).copied().unwrap_or(0.0);
        (plane.point(cam.window_point(cam.window.l, v)), plane.point(cam.window_point(cam.window.r, v)))
    });

    // Title, caption and legend first: they decide the plot area the view is fitted to.
    d.set_title(input.t(Label::TitleRays));
    let through_name = if first.is_some() { "I_1" } else { "O" };
    let depth = format!(" · {} = {}", markup_escape(input.t(Label::MaxDepth)), traced.max_depth);
    d.set_caption(&format!(
        "{}{depth}{}",
        input.traced(traced),
        plane_note(V::DIM, Label::PlaneUw, Some(through_name), lang)
    ));
    for role in [RayRole::Primary, RayRole::Reflected, RayRole::Transmitted] {
        if segments.iter().any(|s| parts::role(log.nodes[s.node].start.kind) == role) {
            legend_role(d, role, lang);
        }
    }
    for role in [RayRole::Shadow, RayRole::BlockedShadow, RayRole::OpaqueShadow] {
        if shadows.iter().any(|s| s.role == role) {
            legend_role(d, role, lang);
        }
    }
    // Hit points and the observer are named on the drawing (I_k, O); the lights need a word.
    legend_points(d, lang, false, !scene.lights.is_empty(), false);
    if first.is_some() {
        legend_normal(d, lang);
    }
    if window.is_some() {
        d.legend_entry(input.t(Label::ViewWindow), style::view_window(), LegendIcon::Line);
    }

    // The view: every origin, hit, light, the observer and the window; misses get some room.
    let mut points: Vec<DVec2> = segments.iter().flat_map(|s| [Some(s.from), s.to]).flatten().collect();
    points.extend(scene.lights.iter().map(|l| plane.point(l.position)));
    if let Some((a, b)) = window {
        points.extend([a, b, plane.point(cam.eye)]);
    }
    let hit_objects: Vec<usize> =
        log.nodes.iter().filter_map(|n| n.end.as_ref()?.hit.map(|h| h.object.index)).collect();
    points.extend(parts::object_extent(scene, &plane, &hit_objects));
    let span = parts::span(&points);
    for s in segments.iter().filter(|s| s.to.is_none()) {
        if let Some(unit) = s.dir.try_normalize() {
            points.push(s.from + unit * 0.35 * span);
        }
    }
    d.fit_view(&points, FIT_MARGIN);
    let view = d.view;

    // The names' anchors: where each hit's and each ray's name will stand. When they crowd one
    // spot at slide size, that spot is drawn again, magnified, beside the picture.
    let ray_anchor = |s: &Segment, clip: &View| {
        let to = s.to.unwrap_or_else(|| exit_point(s.from, s.dir, clip));
        s.from + (to - s.from) * RAY_NAME_AT
    };
    let mut anchors: Vec<DVec2> = segments.iter().filter_map(|s| s.to).collect();
    anchors.extend(segments.iter().map(|s| ray_anchor(s, &view)));
    // The caption says the inset and its factor: set with the longest factor while the inset
    // is planned (it may take a line from the plot), then with the one chosen.
    let caption = d.caption.clone().unwrap_or_default();
    let with_inset =
        |factor: f64| format!("{caption} · {} ×{}", input.t(Label::InsetNote), slide_number(factor));
    d.set_caption(&with_inset(inset::FACTORS[1]));
    let planned = inset::plan(d, &points, FIT_MARGIN, &anchors);
    d.set_caption(&planned.map_or(caption.clone(), |p| with_inset(p.inset.factor)));
    let main = Panel::Main { clip: planned.map_or(view, |p| p.main), inset: planned.map(|p| p.inset) };
    // Where the rays that leave the scene stop, in every panel: the main picture's border.
    let main_clip = planned.map_or(view, |p| p.main);
    let mut panels = vec![main];
    panels.extend(planned.map(|p| Panel::Detail(p.inset)));

    // Every panel's lines first, then every panel's names, so that each name keeps clear of
    // every line.
    let normal_len = NORMAL_SHARE * view.width().min(view.height());
    let mut object_anchors = Vec::new();
    for panel in &panels {
        let clip = panel.clip();
        let inset = match panel {
            Panel::Detail(i) => Some(i),
            Panel::Main { .. } => None,
        };
        object_anchors.push(draw_objects_through(d, scene, &plane, &clip, &[], inset));
        for s in &segments {
            let role = parts::role(log.nodes[s.node].start.kind);
            let to = s.to.unwrap_or_else(|| exit_point(s.from, s.dir, &main_clip));
            if let Some((a, b)) = panel.segment(s.from, to) {
                d.with_events(log.ray_events(s.node), |d| draw_ray(d, role, a, b));
            }
        }
        for s in &shadows {
            let role = s.role;
            if let Some((a, b)) = panel.segment(s.from, s.to) {
                d.with_events([s.event], |d| {
                    d.segment(role.tag(), a, b, role.style());
                });
            }
        }
        // The facing normal N at every hit, dashed.
        for (node, n) in log.nodes.iter().enumerate() {
            let Some(hit) = n.end.as_ref().and_then(|e| e.hit) else { continue };
            let facing = if hit.entering { hit.normal } else { -hit.normal };
            let at = plane.point(hit.point);
            if let Some(dir) = plane.dir(facing).try_normalize() {
                if let Some((a, b)) = panel.segment(at, at + dir * normal_len) {
                    d.with_events(log.ended_by(node), |d| {
                        d.segment(style::NORMAL_TAG, a, b, style::normal());
                    });
                }
            }
        }
        if let Some((a, b)) = window {
            if let Some((a, b)) = panel.segment(a, b) {
                d.segment("window", a, b, style::view_window());
            }
            let eye = plane.point(cam.eye);
            if panel.shows(eye) {
                draw_observer(d, panel.map(eye));
            }
        }
        for s in &shadows {
            if let Some(b) = s.block.filter(|b| panel.shows(*b)) {
                d.with_events([s.event], |d| {
                    d.marker("occluder-point", panel.map(b), style::DOT_RADIUS, s.role.color(), Pen::NONE);
                });
            }
        }
        for (k, l) in scene.lights.iter().enumerate() {
            let at = plane.point(l.position);
            if panel.shows(at) {
                draw_light(d, k, panel.map(at));
            }
        }
        for s in &segments {
            if let Some(to) = s.to.filter(|to| panel.shows(*to)) {
                d.with_events(log.ended_by(s.node), |d| {
                    d.dot("hit", panel.map(to), style::HIT);
                });
            }
        }
    }
    if let Some(p) = planned {
        inset::draw_frame(d, &p.inset, &format!("×{}", slide_number(p.inset.factor)));
    }

    // Labels last, so they keep clear of every line; each name once, in the panel where it
    // is legible (the inset's, for what its frame holds).
    for (panel, objects) in panels.iter().zip(&object_anchors) {
        let eye = plane.point(cam.eye);
        if window.is_some() && panel.shows(eye) && panel.names(eye) {
            label(d, panel.map(eye), "O");
        }
        for (k, l) in scene.lights.iter().enumerate() {
            let at = plane.point(l.position);
            if panel.shows(at) && panel.names(at) {
                let name = if scene.lights.len() == 1 { "S".to_owned() } else { parts::sub("S", k + 1) };
                label(d, panel.map(at), &name);
            }
        }
        for s in &segments {
            if let (Some(to), Some(name)) = (s.to, names.hit_name(s.node)) {
                if panel.shows(to) && panel.names(to) {
                    d.with_events(log.ended_by(s.node), |d| label(d, panel.map(to), &name));
                }
            }
            let at = ray_anchor(s, &main_clip);
            if panel.names(at) {
                d.with_events(log.ray_events(s.node), |d| {
                    parts::ray_label(d, panel.map(at), &names.ray[s.node]);
                });
            }
        }
        // An object's name once: in the main picture unless its spot lies in the frame; in the
        // inset, where rays crowd, at the first clear spot of its outline.
        match panel {
            Panel::Main { .. } => {
                let named: Vec<(usize, DVec2)> =
                    objects.iter().copied().filter(|(_, a)| panel.names(*a)).collect();
                label_objects(d, scene, &named, input.lang);
            }
            Panel::Detail(inset) => {
                let main = &object_anchors[0];
                let in_main = |o: usize| main.iter().any(|(k, a)| *k == o && panels[0].names(*a));
                let spots: Vec<(usize, Vec<DVec2>)> = objects
                    .iter()
                    .filter(|(o, _)| !in_main(*o))
                    .map(|(o, at)| {
                        let mut spots = vec![*at];
                        spots.extend(
                            compass_points(scene, &plane, *o)
                                .into_iter()
                                .filter(|p| inset.in_frame(*p))
                                .map(|p| inset.map(p)),
                        );
                        (*o, spots)
                    })
                    .collect();
                parts::label_objects_first_clear(d, scene, &spots, input.lang);
            }
        }
    }
    Ok(())
}

/// The eight compass points of object `index`'s circle outlines on `plane` (none for other
/// outlines), diagonals first: spots to name it by.
fn compass_points<V: Planar>(scene: &Scene<V>, plane: &PagePlane<V>, index: usize) -> Vec<DVec2> {
    const ANGLES_DEG: [f64; 8] = [45.0, -45.0, 135.0, -135.0, 0.0, 90.0, 180.0, -90.0];
    V::outlines(&scene.objects[index].shape, plane)
        .into_iter()
        .filter_map(|o| match o.outline {
            Outline::Circle { center, radius } => Some((center, radius)),
            _ => None,
        })
        .flat_map(|(c, r)| ANGLES_DEG.map(|a| c + DVec2::from_angle(a.to_radians()) * r))
        .collect()
}
