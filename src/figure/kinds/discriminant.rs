//! `discriminant` (lecture "Utilizarea de volume încadratoare (2)", "Intersecția cu sfera";
//! algorithm.md §9 "Sphere", §11 "Roots"): a sphere of the scene and the three rays that
//! `source` traced along the camera's −w at 1.5, 1 and 0.5 radii from its centre, on one
//! drawing: Δ < 0 (no root, a miss), Δ = 0 (one root, the tangent), Δ > 0 (two roots t₁ < t₂).
//! Each ray's Δ is the one the tracer's own half-b form gives (`source::Quadratic`, `Δ = 4Δ'`);
//! its roots are those its `object_test` event recorded, each marked at r(t) on the ray. The
//! page is the plane of the rays, through the centre C: −w to the right, u up.

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign};
use crate::figure::labels::{scene_lead, Label};
use crate::figure::parts::{draw_objects, draw_ray, label, label_objects, legend_role};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::{node_events, DISCRIMINANT_OFFSETS, DISCRIMINANT_START};
use crate::figure::style::{self, RayRole, TextSize};
use crate::figure::FigureError;
use crate::format::{markup_escape, slide_number};
use crate::record::event::Event;
use crate::shape::Shape;

/// How far past the centre the rays are drawn, in radii (they start 3 radii before it): room
/// past the sphere for the longest Δ text (Romanian) above each ray's end.
const DRAWN_PAST: f64 = 3.5;
/// How far above its ray's end a Δ text sits, in reference pixels.
const DELTA_RISE: f64 = 10.0;
/// Where on the outline the sphere's name stands: low on the right (−45°), clear of the rays.
const NAME_ANGLE: f64 = -std::f64::consts::FRAC_PI_4;
/// How far outside the outline the sphere's name starts, in reference pixels.
const NAME_GAP: f64 = 10.0;

/// The subscripted name of root k of n: `t` alone, or `t_1`, `t_2` (the layout's subscripts).
fn root_name(k: usize, n: usize) -> String {
    if n == 1 {
        "t".to_owned()
    } else {
        format!("t_{}", k + 1)
    }
}

/// Draws the figure.
///
/// # Errors
/// When the sphere or its three rays were not recorded.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let (log, scene, lang) = (&traced.log, input.scene, input.lang);
    let focus = input.traces.focus.ok_or_else(|| FigureError("no sphere was chosen".into()))?;
    let Shape::Sphere(sphere) = &scene.objects[focus].shape else {
        return Err(FigureError("the chosen object is not a sphere".into()));
    };
    let (center, radius) = (sphere.center, sphere.radius);
    let frame = &scene.camera.frame;
    let plane = PagePlane::spanned(center, -frame.w, frame.u)
        .ok_or_else(|| FigureError("the camera's −w and u span no plane".into()))?;
    let roots: Vec<usize> = log.roots().collect();
    if roots.len() != DISCRIMINANT_OFFSETS.len() || input.traces.quadratics.len() != roots.len() {
        return Err(FigureError("the three rays of the discriminant were not recorded".into()));
    }

    d.set_title(input.t(Label::TitleDiscriminant));
    d.set_caption(&format!(
        "{}{} · {} · {}",
        scene_lead(&input.traces.scene_name, input.lang),
        input.t(Label::ThreeRays),
        input.t(Label::Quadratic),
        input.t(Label::NearestRoot),
    ));
    legend_role(d, RayRole::Primary, lang);
    d.legend_entry(input.t(Label::Root), Pen::NONE, LegendIcon::Dot(style::HIT));

    struct Drawn {
        node: usize,
        from: DVec2,
        to: DVec2,
        roots: Vec<f64>,
        delta: f64,
    }
    let drawn: Vec<Drawn> = roots
        .iter()
        .zip(&input.traces.quadratics)
        .map(|(&node, q)| {
            let ray = &log.nodes[node].start;
            let tested = node_events(log, node).find_map(|e| match e {
                Event::ObjectTest { object, roots, .. } if object.index == focus => Some(roots.clone()),
                _ => None,
            });
            let far = ray.origin + ray.direction * ((DISCRIMINANT_START + DRAWN_PAST) * radius);
            Drawn {
                node,
                from: plane.point(ray.origin),
                to: plane.point(far),
                roots: tested.unwrap_or_default(),
                delta: q.delta,
            }
        })
        .collect();

    let c = plane.point(center);
    let mut points: Vec<DVec2> = drawn.iter().flat_map(|r| [r.from, r.to]).collect();
    points.extend([c - DVec2::splat(radius), c + DVec2::splat(radius)]);
    // Room under the lowest ray for the roots' names.
    points.push(c - DVec2::new(0.0, 0.6 * radius));
    d.fit_view(&points, 0.1);
    let view = d.view;

    let anchors = draw_objects(d, scene, &plane, &view, &[(focus, style::BLACK)]);
    d.dot("center", c, style::DARK_GREY);
    let rim = c + DVec2::new(-radius, 0.0);
    d.segment("radius", c, rim, Pen::solid(style::DARK_GREY, style::CONSTRUCTION_WIDTH));
    for r in &drawn {
        d.with_events(log.ray_events(r.node), |d| draw_ray(d, RayRole::Primary, r.from, r.to));
    }
    let ray_of = |node: usize, t: f64| {
        let n = &log.nodes[node].start;
        plane.point(n.origin + n.direction * t)
    };
    for r in &drawn {
        for t in &r.roots {
            d.with_events(log.ray_events(r.node), |d| {
                d.dot("root", ray_of(r.node, *t), style::HIT);
            });
        }
    }

    // Words: each ray's Δ and what it means, above the ray's right end, past the sphere, ending
    // where the ray ends: read along its own ray, with no leader (each text lies over the part
    // of its ray that no other text or outline takes, and the next ray is half a radius away);
    // the roots' values at their points; C and r.
    for r in &drawn {
        let (relation, words) = if r.roots.is_empty() {
            (" < 0", Label::DeltaMiss)
        } else if r.roots.len() == 1 {
            ("", Label::DeltaTangent)
        } else {
            (" > 0", Label::DeltaTwo)
        };
        let text = format!("Δ = {}{relation}: {}", slide_number(r.delta), input.t(words));
        let above_end = Align { h: HAlign::Right, v: VAlign::Bottom };
        let opts = TextOpts::LABEL.size(TextSize::Body).align(above_end).offset(0.0, DELTA_RISE);
        d.with_events(log.ray_events(r.node), |d| {
            d.text("delta", r.to, &text, opts);
        });
        for (k, t) in r.roots.iter().enumerate() {
            let name = format!("{} = {}", root_name(k, r.roots.len()), slide_number(*t));
            d.with_events(log.ray_events(r.node), |d| label(d, ray_of(r.node, *t), &name));
        }
    }
    label(d, c, "C");
    label(d, (c + rim) / 2.0, &format!("r = {}", slide_number(radius)));
    // The sphere's name just outside its outline, low on the right, where no ray runs (every ray
    // passes above the centre); the other objects' names where every figure puts them.
    let name = markup_escape(&scene.object_label(focus, lang));
    let away = DVec2::from_angle(NAME_ANGLE);
    let opts = TextOpts::NOTE
        .color(style::DARK_GREY)
        .align(Align { h: HAlign::Left, v: VAlign::Top })
        .offset(away.x * NAME_GAP, away.y * NAME_GAP)
        .avoid_overlap();
    d.text(&format!("object-name:{focus}"), c + away * radius, &name, opts);
    let others: Vec<(usize, DVec2)> = anchors.into_iter().filter(|(k, _)| *k != focus).collect();
    label_objects(d, scene, &others, lang);
    Ok(())
}
