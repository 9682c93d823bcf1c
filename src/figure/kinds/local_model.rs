//! `local-model` (lecture "Ray tracing – calculul culorii unui pixel (2), (3)", algorithm.md §5):
//! at one recorded hit I, the normal N, the direction V towards the observer, and for each light
//! the direction L towards it and the bisector H of L and V; beside them the terms of
//! `I_local = Ia·Ka + Σ Isrc·fat·s·lum·[kd·(N·L) + ks·(N·H)^n]` with the recorded numbers
//! (N·L, lum, fat, s, the diffuse and specular terms, I_local). In 3D the four vectors are not
//! coplanar: each is drawn at its true angle to N, on the side of N it leans to (the page's
//! x axis is the tangent part of L − V), so the angles the model uses (N·L, N·H) read true.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, LegendIcon, Pen};
use crate::figure::labels::Label;
use crate::figure::parts::{
    self, label_outward, legend_normal, object_name, rgb_text, sub, swatch, text_column, Names,
};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::first_hit;
use crate::figure::style::{self, RayRole, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::record::event::{LightTerm, ObjectRef};

/// At most this many lights are told term by term; the others are summed in I_local only.
const TOLD_LIGHTS: usize = 2;

// The schematic's coordinates, in units of the recorded unit vectors, the hit at the origin.
/// Half the drawn surface's length (and the object's body under it).
const SURFACE_HALF: f64 = 1.5;
/// The depth of the object's body drawn under the surface.
const BODY_DEPTH: f64 = 0.4;
/// The drawn length of N, V and L.
const VECTOR_LEN: f64 = 1.2;
/// H's length as a share of [`VECTOR_LEN`]: shorter, so its tip and name stay clear of L's and V's.
const H_SHARE: f64 = 0.85;
/// The box the view fits: the surface's width, the body below, the vectors above.
const VIEW_BOX: [DVec2; 2] = [DVec2::new(-SURFACE_HALF, -0.45), DVec2::new(SURFACE_HALF, SURFACE_HALF)];
/// The share of the canvas the numbers' column takes, right of the schematic.
const COLUMN_SHARE: f64 = 0.5;
/// The view's margin around [`VIEW_BOX`], as a share of its size.
const VIEW_MARGIN: f64 = 0.02;

/// Draws the figure.
///
/// # Errors
/// When the trace has no hit.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let log = &traced.log;
    let k = first_hit(log).ok_or_else(|| FigureError("the trace has no hit".into()))?;
    let node = &log.nodes[k];
    let (Some(end), Some(hit)) = (node.end.as_ref(), node.end.as_ref().and_then(|e| e.hit)) else {
        return Err(FigureError("the trace has no hit".into()));
    };
    let scene = input.scene;
    let names = Names::of(log);
    let hit_name = names.hit_name(k).unwrap_or_default();
    let n_f = if hit.entering { hit.normal } else { -hit.normal };
    let view_dir = -node.start.direction;
    let lit: Vec<&LightTerm<V>> = node.lights.iter().filter(|t| t.l.is_some()).collect();

    // The plane of N and L − V (for the first light), so L and V fall on either side of N.
    let tangent_of = |v: V| v - n_f * v.dot(n_f);
    let spread =
        lit.first().and_then(|t| t.l).map_or(-tangent_of(view_dir), |l| tangent_of(l) - tangent_of(view_dir));
    let fallback = (0..V::DIM).map(V::axis).map(tangent_of).find(|a| a.length() > 0.5);
    let x = if spread.length() > 1e-9 { Some(spread) } else { fallback };
    let plane = x
        .and_then(|x| PagePlane::spanned(hit.point, x, n_f))
        .ok_or_else(|| FigureError("no plane holds N".into()))?;

    let object = ObjectRef { index: hit.object.index, triangle: None };
    let title = format!(
        "{} {hit_name} ({})",
        input.t(Label::TitleLocalModel),
        object_name(scene, object, input.lang)
    );
    d.set_title(&title);
    let caption = format!(
        "{} · {}",
        input.traced(traced),
        if V::DIM == 3 { input.t(Label::TrueAnglesToN) } else { input.t(Label::PlaneOfIncidence) }
    );
    d.set_caption(&caption);
    let view_role = parts::role(node.start.kind);
    legend_normal(d, input.lang);
    d.legend_entry(input.t(Label::VectorV), view_role.style(), LegendIcon::Arrow);
    // L is drawn as its shadow ray is (clear, or through glass): the legend shows each style used.
    let mut l_roles: Vec<RayRole> = Vec::new();
    for role in lit.iter().map(|t| light_role(t)) {
        if !l_roles.contains(&role) {
            l_roles.push(role);
        }
    }
    for role in if l_roles.is_empty() { vec![RayRole::Shadow] } else { l_roles } {
        d.legend_entry(input.t(Label::VectorL), role.style(), LegendIcon::Arrow);
    }
    d.legend_entry(input.t(Label::VectorH), h_style(), LegendIcon::Arrow);
    if let Some(local) = end.local {
        d.legend_entry("I_{local}", style::outline(style::BLACK), LegendIcon::Swatch(swatch(local)));
    }
    let column = parts::fit_with_column(d, &VIEW_BOX, VIEW_MARGIN, COLUMN_SHARE);

    // The surface, the vectors, their names.
    let i = plane.point(hit.point);
    d.rect(
        "object",
        i + DVec2::new(-SURFACE_HALF, -BODY_DEPTH),
        i + DVec2::new(SURFACE_HALF, 0.0),
        Pen::NONE,
        Some(style::OBJECT_FILL),
    );
    d.segment(
        "surface",
        i + DVec2::new(-SURFACE_HALF, 0.0),
        i + DVec2::new(SURFACE_HALF, 0.0),
        style::object(),
    );
    // A vector at its true angle to N, on the side of N its tangent part leans to.
    let unit = |v: V| {
        let cos = v.dot(n_f).clamp(-1.0, 1.0);
        let side = if plane.dir(v).x < 0.0 { -1.0 } else { 1.0 };
        DVec2::new(side * (1.0 - cos * cos).sqrt(), cos)
    };
    let len = VECTOR_LEN;
    // The events drawn: N and the hit its `hit`, V the ray's events, L and H a light's shadow ray
    // (the hit when the light sends none).
    let hit_ev: Vec<usize> = log.ended_by(k).into_iter().collect();
    let view_ev = log.ray_events(k);
    let light_ev = |light: usize| {
        let shadow = log.shadow_events(k, light);
        if shadow.is_empty() {
            hit_ev.clone()
        } else {
            shadow
        }
    };
    d.with_events(hit_ev.clone(), |d| {
        d.arrow(style::NORMAL_TAG, i, i + DVec2::Y * len, style::normal());
    });
    d.with_events(view_ev.clone(), |d| {
        d.arrow(view_role.tag(), i, i + unit(view_dir) * len, view_role.style());
    });
    // Named by the light's number (`L₂` is lights[1]), as the narration names them, whichever are lit.
    let many = node.lights.len() > 1;
    let name = |letter: &str, light: usize| if many { sub(letter, light + 1) } else { letter.to_owned() };
    let mut tips =
        vec![(DVec2::Y, "N".to_owned(), hit_ev.clone()), (unit(view_dir), "V".to_owned(), view_ev)];
    for t in &lit {
        let Some(l) = t.l else { continue };
        let role = light_role(t);
        let events = light_ev(t.light);
        d.with_events(events.clone(), |d| {
            d.arrow(role.tag(), i, i + unit(l) * len, role.style());
        });
        tips.push((unit(l), name("L", t.light), events.clone()));
        if let Some(h) = (l + view_dir).try_unit() {
            d.with_events(events.clone(), |d| {
                d.arrow("vector:H", i, i + unit(h) * len * H_SHARE, h_style());
            });
            tips.push((unit(h) * H_SHARE, name("H", t.light), events));
        }
    }
    d.with_events(hit_ev.clone(), |d| {
        d.dot("hit", i, style::HIT);
    });
    for (dir, text, events) in &tips {
        d.with_events(events.iter().copied(), |d| label_outward(d, i + *dir * len, *dir, text));
    }
    d.with_events(hit_ev, |d| {
        d.text("label", i, &hit_name, crate::canvas::TextOpts::LABEL.avoid_overlap());
    });

    // The terms, with the recorded numbers.
    let material = scene.material_of(hit.object.index);
    let (ka, _) = material.colors_at(hit.point);
    // The light's intensity as the lecture writes it: Isrc, in Romanian Isursa.
    let src = input.t(Label::Isrc);
    let mut lines = vec![
        format!("I_{{local}} = Ia·Ka + Σ {src}·fat·s·lum·[kd·(N·L) + ks·(N·H)^n]"),
        format!(
            "Ia·Ka = {} · {} = {}",
            rgb_text(scene.ambient),
            rgb_text(ka),
            rgb_text(scene.ambient.modulate(ka))
        ),
    ];
    for t in node.lights.iter().take(TOLD_LIGHTS) {
        let l = name("L", t.light);
        if t.lum == 0.0 {
            lines.push(format!("{l}: N·L = {} ≤ 0 → lum = 0", slide_number(t.n_dot_l)));
            continue;
        }
        let s = t.shadow.map_or_else(|| "—".to_owned(), slide_number);
        lines.push(format!(
            "{l}: N·L = {}, lum = 1, fat = {}, s = {s}",
            slide_number(t.n_dot_l),
            slide_number(t.fat)
        ));
        if let Some(h) = t.l.and_then(|l| (l + view_dir).try_unit()) {
            let n_dot_h = n_f.dot(h);
            lines.push(format!(
                "{}: N·H = {}, (N·H)^n = {} (n = {})",
                name("H", t.light),
                slide_number(n_dot_h),
                slide_number(material.highlight(n_dot_h)),
                slide_number(material.n)
            ));
        }
        lines.push(format!("{src}·fat·s·kd·(N·L) = {}", rgb_text(t.diffuse)));
        lines.push(format!("{src}·fat·s·ks·(N·H)^n = {}", rgb_text(t.specular)));
    }
    if let Some(local) = end.local {
        lines.push(format!("I_{{local}} = {}", rgb_text(local)));
    }
    text_column(d, column + DVec2::new(0.1, -0.05), &lines, TextSize::Body, 50.0);
    Ok(())
}

/// How light `t`'s L is drawn: as its shadow ray (clear, or attenuated by glass).
fn light_role<V>(t: &LightTerm<V>) -> RayRole {
    t.shadow.map_or(RayRole::Shadow, |s| RayRole::shadow(s, s < 1.0))
}

/// The bisector H: black, a little thinner than a ray.
fn h_style() -> Pen {
    Pen::solid(style::BLACK, style::RAY_WIDTH * 0.8)
}
