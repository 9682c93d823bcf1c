//! `shadows` (lecture "Ray tracing – calculul culorii unui pixel (2)", algorithm.md §5, §11
//! "Shadow rays are segments"): at one recorded hit I, the shadow ray L towards every light — a
//! segment from the offset origin to the light — with the objects it meets outlined by kind (a
//! transparent one in the attenuated L's pink, an opaque one in the stopped L's black, both named
//! in the legend) and marked where it meets them, and the shadow factor s: 1 when nothing is in between, 0 behind an opaque object, the
//! product of the kt of the transparent ones otherwise. A 3D trace is drawn in the plane of N and
//! the first blocked L, turned so that the scene's up (the camera's v) is drawn upwards.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, Pen};
use crate::figure::labels::Label;
use crate::figure::parts::{
    self, camera_plane, draw_light, draw_objects, draw_ray, label, label_objects, legend_normal,
    legend_points, legend_role, object_name, plane_note, shadow_block_t, sub, text_column, Names,
};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::shadow_node;
use crate::figure::style::{self, RayRole, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::record::event::{Event, Occluder};

/// One recorded shadow ray of the node.
struct Shadow<'a, V> {
    /// The index of its `shadow_ray` event.
    event: usize,
    light: usize,
    origin: V,
    direction: V,
    occluders: &'a [Occluder],
    s: f64,
    /// The t where it first meets an occluder (from the recorded object tests).
    block: Option<f64>,
}

/// Draws the figure.
///
/// # Errors
/// When the trace has no shadow ray.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let log = &traced.log;
    let (node_index, _) =
        shadow_node(log).ok_or_else(|| FigureError("the trace has no shadow ray".into()))?;
    let node = &log.nodes[node_index];
    let hit = node.end.as_ref().and_then(|e| e.hit).ok_or_else(|| FigureError("no hit".into()))?;
    let (scene, lang) = (input.scene, input.lang);
    let names = Names::of(log);
    let hit_name = names.hit_name(node_index).unwrap_or_default();
    let n_f = if hit.entering { hit.normal } else { -hit.normal };
    let shadows: Vec<Shadow<'_, V>> = log
        .events
        .iter()
        .enumerate()
        .filter(|(_, l)| l.ray == Some(node_index))
        .filter_map(|(index, l)| match &l.event {
            Event::ShadowRay { light, origin, direction, occluders, s, .. } => Some(Shadow {
                event: index,
                light: *light,
                origin: *origin,
                direction: *direction,
                occluders,
                s: *s,
                block: shadow_block_t(log, index),
            }),
            _ => None,
        })
        .collect();

    // 2D: the scene's plane. 3D: the plane of N and the first blocked shadow ray through I.
    // The scene's up stays up: the camera's v, turned into the plane.
    let frame = &scene.camera.frame;
    let plane = if V::DIM == 2 {
        camera_plane(scene, hit.point, false)
    } else {
        let along = shadows.iter().find(|s| !s.occluders.is_empty()).or(shadows.first()).map(|s| s.direction);
        along
            .and_then(|l| PagePlane::upright(hit.point, l, n_f, frame.v, frame.u))
            .unwrap_or_else(|| camera_plane(scene, hit.point, false))
    };
    let i = plane.point(hit.point);

    d.set_title(input.t(Label::TitleShadows));
    d.set_caption(&format!(
        "{} · {hit_name} ({}){}",
        input.traced(traced),
        object_name(scene, hit.object, input.lang),
        plane_note(V::DIM, Label::PlaneOfNL, Some(&hit_name), lang)
    ));
    legend_role(d, parts::role(node.start.kind), lang);
    let role_of = |s: &Shadow<'_, V>| RayRole::shadow(s.s, !s.occluders.is_empty());
    for role in [RayRole::Shadow, RayRole::BlockedShadow, RayRole::OpaqueShadow] {
        if shadows.iter().any(|s| role_of(s) == role) {
            legend_role(d, role, lang);
        }
    }
    // Occluders outlined by kind, as their shadow rays are drawn: a transparent one (kt > 0) in
    // the attenuated L's pink, an opaque one in the stopped L's black; the legend says which.
    let occluder_kinds: Vec<(usize, bool)> =
        shadows.iter().flat_map(|s| s.occluders.iter().map(|o| (o.object.index, o.kt > 0.0))).collect();
    let kind_colour =
        |transparent: bool| if transparent { RayRole::BlockedShadow } else { RayRole::OpaqueShadow }.color();
    if shadows.iter().any(|s| !s.occluders.is_empty()) {
        d.legend_entry(
            input.t(Label::OccluderPoint),
            Pen::NONE,
            crate::canvas::LegendIcon::Dot(style::DARK_GREY),
        );
    }
    for (transparent, word) in [(true, Label::TransparentOccluder), (false, Label::OpaqueOccluder)] {
        if occluder_kinds.iter().any(|(_, t)| *t == transparent) {
            let outline = style::outline(kind_colour(transparent)).with_width(parts::EMPHASIS_WIDTH);
            d.legend_entry(input.t(word), outline, crate::canvas::LegendIcon::Swatch(style::OBJECT_FILL));
        }
    }
    // The view: I, the occluders, the near lights, and where the incoming ray came from
    // (clipped); a far light is left out, its L drawn leaving the picture towards it.
    let occluding: Vec<usize> =
        shadows.iter().flat_map(|s| s.occluders.iter().map(|o| o.object.index)).collect();
    let mut points = vec![i];
    points.extend(parts::object_extent(scene, &plane, &occluding));
    points.extend(parts::object_extent(scene, &plane, &[hit.object.index]));
    let lights: Vec<DVec2> = scene.lights.iter().map(|l| plane.point(l.position)).collect();
    let far = parts::far_lights(&points, &lights);
    points.extend(lights.iter().zip(&far).filter(|(_, far)| !**far).map(|(l, _)| *l));
    legend_points(d, lang, false, far.contains(&false), false);
    legend_normal(d, lang);
    let span = parts::span(&points);
    let from = plane.point(node.start.origin);
    let incoming =
        if (from - i).length() > 0.6 * span { i + (from - i).normalize() * 0.6 * span } else { from };
    points.push(incoming);
    let column = parts::fit_with_column(d, &points, 0.08, 0.4);
    let view = d.view;
    // Unbounded lines stop where the text column begins, leaving its lower part to the legend.
    let scene_part =
        crate::canvas::View::new(view.xmin(), column.x, view.ymin(), view.ymax()).unwrap_or(view);

    // An object both kinds of L meet (never: kt is the object's) takes the first.
    let emphasis: Vec<(usize, crate::canvas::style::Rgba)> =
        occluder_kinds.iter().map(|(k, transparent)| (*k, kind_colour(*transparent))).collect();
    let anchors = draw_objects(d, scene, &plane, &scene_part, &emphasis);
    let hit_ev: Vec<usize> = log.ended_by(node_index).into_iter().collect();
    d.with_events(log.ray_events(node_index), |d| draw_ray(d, parts::role(node.start.kind), incoming, i));
    let light_name = |k: usize| if scene.lights.len() == 1 { "S".to_owned() } else { sub("S", k + 1) };
    for s in &shadows {
        let role = role_of(s);
        let from = plane.point(s.origin);
        d.with_events([s.event], |d| {
            if far[s.light] {
                let name = format!("{} {}", input.t(Label::TowardsLight), light_name(s.light));
                parts::draw_towards_light(d, role, from, plane.dir(s.direction), &scene_part, &name);
            } else {
                d.segment(role.tag(), from, lights[s.light], role.style());
            }
        });
    }
    // Long enough to read beside an incoming ray that runs close to it.
    let normal_len = 0.2 * view.height();
    if let Some(dir) = plane.dir(n_f).try_normalize() {
        d.with_events(hit_ev.clone(), |d| {
            d.segment(style::NORMAL_TAG, i, i + dir * normal_len, style::normal());
            label(d, i + dir * normal_len, "N");
        });
    }
    for s in &shadows {
        if let Some(t) = s.block {
            let at = plane.point(s.origin + s.direction * t);
            d.with_events([s.event], |d| {
                // In its ray's colour: pink where every occluder lets light through, else black.
                let colour = kind_colour(s.occluders.iter().all(|o| o.kt > 0.0));
                d.marker("occluder-point", at, style::DOT_RADIUS, colour, Pen::NONE);
            });
        }
    }
    for (k, l) in lights.iter().enumerate().filter(|(k, _)| !far[*k]) {
        draw_light(d, k, *l);
    }
    d.with_events(hit_ev, |d| {
        d.dot("hit", i, style::HIT);
        label(d, i, &hit_name);
    });
    for (k, l) in lights.iter().enumerate().filter(|(k, _)| !far[*k]) {
        label(d, *l, &light_name(k));
    }
    label_objects(d, scene, &anchors, input.lang);

    // s for every light, with the recorded occluders.
    let mut lines = Vec::new();
    for term in &node.lights {
        let name = light_name(term.light);
        let Some(s) = shadows.iter().find(|s| s.light == term.light) else {
            lines.push(format!("{name}: N·L = {} ≤ 0 → lum = 0", slide_number(term.n_dot_l)));
            continue;
        };
        if s.occluders.is_empty() {
            lines.push(format!("{name}: {} → s = 1", input.t(Label::NothingBetween)));
            continue;
        }
        // The lecture's letter, as the legend and the ray tree write it (`kt`, Romanian `Kt`).
        let kt = input.t(Label::WeightKt);
        let list: Vec<String> = s
            .occluders
            .iter()
            .map(|o| {
                let what = object_name(scene, o.object, input.lang);
                if o.kt == 0.0 {
                    format!("{what} ({})", input.t(Label::Opaque))
                } else {
                    format!("{what} ({kt} = {})", slide_number(o.kt))
                }
            })
            .collect();
        lines.push(format!("{name}: {}", list.join(", ")));
        let product: Vec<String> = s.occluders.iter().map(|o| slide_number(o.kt)).collect();
        lines.push(if s.occluders.iter().any(|o| o.kt == 0.0) {
            "   → s = 0".to_owned()
        } else if product.len() == 1 {
            format!("   → s = {kt} = {}", slide_number(s.s))
        } else {
            format!("   → s = Π {kt} = {} = {}", product.join(" · "), slide_number(s.s))
        });
    }
    text_column(d, column + DVec2::new(0.02 * view.width(), 0.0), &lines, TextSize::Body, 50.0);
    Ok(())
}
