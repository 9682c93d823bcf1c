//! `backward` (lecture "Razele folosite în Ray tracing (3)", algorithm.md §1: "the rays run
//! backwards, from the observer into the scene, the reverse of the light's own path"): one
//! recorded pixel drawn twice, side by side at one scale. Left, the light as it travels: from the
//! source S to the hit I, then from I to the observer O. Right, the same two segments as the
//! tracer made them: the primary ray P from O through the pixel to I, then the shadow ray L from
//! I towards S. Each segment keeps its ray kind's colour in both panels; only the arrows turn. A
//! 3D trace is drawn on the camera's (u, w) plane through I.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, LegendIcon, Pen, View};
use crate::figure::labels::Label;
use crate::figure::parts::{
    camera_plane, draw_light, draw_objects, draw_observer, draw_ray, label, label_objects, legend_points,
    legend_role, object_extent, panel_heading, plane_note,
};
use crate::figure::plane::Planar;
use crate::figure::source::Target;
use crate::figure::style::{self, RayRole};
use crate::figure::FigureError;
use crate::record::event::Event;

/// The gap between the two panels, as a share of one panel's width.
const PANEL_GAP: f64 = 0.12;

/// Draws the figure.
///
/// # Errors
/// When the traced primary ray hits nothing, or no light reaches its hit.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let (log, scene, lang) = (&traced.log, input.scene, input.lang);
    let cam = &scene.camera;
    let root = log.nodes.first().ok_or_else(|| FigureError("no primary ray was recorded".into()))?;
    let hit = root
        .end
        .as_ref()
        .and_then(|e| e.hit)
        .ok_or_else(|| FigureError("the primary ray hits nothing".into()))?;
    // The shadow ray of the primary hit that reaches its light (s = 1).
    let Some((shadow_event, light)) = log.events.iter().enumerate().find_map(|(k, l)| match &l.event {
        Event::ShadowRay { light, occluders, .. } if l.ray == Some(0) && occluders.is_empty() => {
            Some((k, *light))
        }
        _ => None,
    }) else {
        return Err(FigureError("no light reaches the primary hit with nothing in between".into()));
    };
    let plane = camera_plane(scene, hit.point, false);
    let (start, at, source) =
        (plane.point(root.start.origin), plane.point(hit.point), plane.point(scene.lights[light].position));
    let window = traced.targets.first().and_then(|t| match t {
        Target::Pixel { uv, .. } => {
            let v = uv.get(1).copied().unwrap_or(0.0);
            Some((
                plane.point(cam.window_point(cam.window.l, v)),
                plane.point(cam.window_point(cam.window.r, v)),
            ))
        }
        Target::Ray => None,
    });

    d.set_title(input.t(Label::TitleBackward));
    d.set_caption(&format!(
        "{} · {}{}",
        input.traced(traced),
        input.t(Label::PixelTakesI),
        plane_note(V::DIM, Label::PlaneUw, Some("I"), lang)
    ));
    legend_role(d, RayRole::Primary, lang);
    legend_role(d, RayRole::Shadow, lang);
    d.legend_entry(
        input.t(Label::ArrowsTravel),
        Pen::solid(style::DARK_GREY, style::RAY_WIDTH),
        LegendIcon::Arrow,
    );
    legend_points(d, lang, true, true, true);
    if window.is_some() {
        d.legend_entry(input.t(Label::ViewWindow), style::view_window(), LegendIcon::Line);
    }

    // One box for a panel: the three points, the window and the objects.
    let mut points = vec![start, at, source, plane.point(cam.eye)];
    if let Some((a, b)) = window {
        points.extend([a, b]);
    }
    // Every bounded object, so that none reaches into the other panel.
    let bounded: Vec<usize> = (0..scene.objects.len()).collect();
    points.extend(object_extent(scene, &plane, &bounded));
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
    let pad = 0.08 * (hi - lo).max_element();
    let (lo, hi) = (lo - DVec2::splat(pad), hi + DVec2::splat(pad));
    let shift = DVec2::new((hi.x - lo.x) * (1.0 + PANEL_GAP), 0.0);
    // Room above the panels for their headings.
    d.fit_view(&[lo, hi + shift + DVec2::new(0.0, 2.5 * pad)], 0.0);

    let shadow_events = [shadow_event];
    let primary_events = log.ray_events(0);
    let mut anchors = Vec::new();
    for (panel, heading) in [(0.0, Label::InReality), (1.0, Label::InRayTracing)] {
        let offset = shift * panel;
        let on = plane.shifted(offset);
        let clip = View::new(lo.x + offset.x, hi.x + offset.x, lo.y, hi.y).unwrap_or(d.view);
        anchors.extend(draw_objects(d, scene, &on, &clip, &[]));
        if let Some((a, b)) = window {
            d.segment("window", a + offset, b + offset, style::view_window());
        }
        let (o, i, s) = (start + offset, at + offset, source + offset);
        if panel == 0.0 {
            // The light's own path: from the source to I, then from I to the observer.
            d.with_events(shadow_events, |d| draw_ray(d, RayRole::Shadow, s, i));
            d.with_events(primary_events.clone(), |d| draw_ray(d, RayRole::Primary, i, o));
        } else {
            d.with_events(primary_events.clone(), |d| draw_ray(d, RayRole::Primary, o, i));
            d.with_events(shadow_events, |d| draw_ray(d, RayRole::Shadow, i, s));
        }
        draw_observer(d, plane.point(cam.eye) + offset);
        draw_light(d, light, s);
        d.dot("hit", i, style::HIT);
        panel_heading(d, DVec2::new((lo.x + hi.x) / 2.0 + offset.x, hi.y), input.t(heading));
    }
    for panel in [0.0, 1.0] {
        let offset = shift * panel;
        let (o, i, s) = (start + offset, at + offset, source + offset);
        label(d, plane.point(cam.eye) + offset, "O");
        label(d, s, "S");
        label(d, i, "I");
        d.with_events(primary_events.clone(), |d| label(d, o + (i - o) * 0.3, "P"));
        d.with_events(shadow_events, |d| label(d, i + (s - i) * 0.5, "L"));
    }
    label_objects(d, scene, &anchors, lang);
    Ok(())
}
