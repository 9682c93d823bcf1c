//! `rays` (lecture "Razele folosite în Ray tracing", algorithm.md §3–§4): every ray of one pixel's
//! trace, coloured by kind — the primary ray P, the reflected R_k and transmitted T_k spawned at
//! each hit I_k, the shadow rays L towards the lights (blocked ones dashed, with the point where
//! they meet an object) — over the scene's objects, the observer O, the view window and the lights.
//! A 3D trace is drawn on the camera's (u, w) plane through I₁.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, LegendIcon, Pen};
use crate::figure::labels::Label;
use crate::figure::parts::{
    self, camera_plane, draw_light, draw_objects, draw_observer, draw_ray, exit_point, label, label_objects,
    legend_normal, legend_points, legend_role, plane_note, shadow_block_t, Names,
};
use crate::figure::plane::Planar;
use crate::figure::source::{first_hit, Target};
use crate::figure::style::{self, RayRole};
use crate::figure::FigureError;
use crate::format::markup_escape;
use crate::record::event::Event;

/// The drawn length of a normal N, as a share of the view's smaller side: long enough that its
/// dashes read at slide size beside a ray that leaves along it.
const NORMAL_SHARE: f64 = 0.12;

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
    d.fit_view(&points, 0.06);
    let view = d.view;

    let anchors = draw_objects(d, scene, &plane, &view, &[]);
    for s in &segments {
        let role = parts::role(log.nodes[s.node].start.kind);
        let to = s.to.unwrap_or_else(|| exit_point(s.from, s.dir, &view));
        d.with_events(log.ray_events(s.node), |d| draw_ray(d, role, s.from, to));
    }
    for s in &shadows {
        let role = s.role;
        d.with_events([s.event], |d| {
            d.segment(role.tag(), s.from, s.to, role.style());
        });
    }
    // The facing normal N at every hit, dashed.
    let normal_len = NORMAL_SHARE * view.width().min(view.height());
    for (node, n) in log.nodes.iter().enumerate() {
        let Some(hit) = n.end.as_ref().and_then(|e| e.hit) else { continue };
        let facing = if hit.entering { hit.normal } else { -hit.normal };
        let at = plane.point(hit.point);
        if let Some(dir) = plane.dir(facing).try_normalize() {
            d.with_events(log.ended_by(node), |d| {
                d.segment("normal", at, at + dir * normal_len, style::normal());
            });
        }
    }
    if let Some((a, b)) = window {
        d.segment("window", a, b, style::view_window());
        draw_observer(d, plane.point(cam.eye));
    }
    for s in &shadows {
        if let Some(b) = s.block {
            d.with_events([s.event], |d| {
                d.marker("occluder-point", b, style::DOT_RADIUS, s.role.color(), Pen::NONE);
            });
        }
    }
    for (k, l) in scene.lights.iter().enumerate() {
        draw_light(d, k, plane.point(l.position));
    }
    for s in &segments {
        if let Some(to) = s.to {
            d.with_events(log.ended_by(s.node), |d| {
                d.dot("hit", to, style::HIT);
            });
        }
    }

    // Labels last, so they keep clear of every line.
    if window.is_some() {
        label(d, plane.point(cam.eye), "O");
    }
    for (k, l) in scene.lights.iter().enumerate() {
        let name = if scene.lights.len() == 1 { "S".to_owned() } else { parts::sub("S", k + 1) };
        label(d, plane.point(l.position), &name);
    }
    for s in &segments {
        if let (Some(to), Some(name)) = (s.to, names.hit_name(s.node)) {
            d.with_events(log.ended_by(s.node), |d| label(d, to, &name));
        }
        let to = s.to.unwrap_or_else(|| exit_point(s.from, s.dir, &view));
        d.with_events(log.ray_events(s.node), |d| {
            parts::ray_label(d, s.from + (to - s.from) * 0.3, &names.ray[s.node]);
        });
    }
    label_objects(d, scene, &anchors, input.lang);
    Ok(())
}
