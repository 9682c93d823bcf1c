//! `refraction` (lecture "Calculul razelor secundare", algorithm.md §3): at one recorded hit, the
//! incident ray, the normal N, the reflected ray R and the transmitted ray T with the angles θᵢ
//! and θₜ, the indices n₁ and n₂ and Snell's law `n₁·sin θᵢ = n₂·sin θₜ` with the recorded numbers;
//! and, when a trace has one, the total internal reflection (k < 0, no T). Each case is drawn in
//! its plane of incidence, the surface horizontal and N up; every direction is the one recorded.

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign};
use crate::figure::labels::{self, Label};
use crate::figure::parts::{
    self, deg, draw_arc, label_outward, legend_normal, legend_role, object_name, text_column, Names,
};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::{node_events, refraction_node, tir_node, FigureTrace};
use crate::figure::style::{self, RayRole, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::record::event::Event;

// The schematic's coordinates, in units of the recorded unit directions, the hit at the origin.
/// How far a panel reaches from its hit, each way: the view fits this box.
const PANEL_HALF: DVec2 = DVec2::new(1.6, 1.45);
/// The distance between two panels' hits, side by side.
const PANEL_GAP: f64 = 4.4;
/// The height kept under two panels for their numbers.
const NUMBERS_BELOW: f64 = 1.45;
/// Half the drawn surface's length, and the medium's width.
const SURFACE_HALF: f64 = 1.5;
/// The medium's depth beyond the surface.
const MEDIUM_DEPTH: f64 = 1.35;
/// Half the drawn normal's length.
const NORMAL_HALF: f64 = 1.3;
/// The drawn length of the incident, reflected and transmitted rays.
const RAY_LEN: f64 = 1.15;
/// The radius of θᵢ's arc.
const ARC_I: f64 = 0.42;
/// The radius of θₜ's arc: unlike [`ARC_I`], so the two arcs never merge.
const ARC_T: f64 = 0.52;
/// Where the labels n₁ and n₂ start: left, above and below the surface.
const INDEX_LABEL: DVec2 = DVec2::new(-1.45, 1.05);

/// What one panel shows: a hit and the recorded rays leaving it.
struct Case<V> {
    /// The node whose hit it is.
    node: usize,
    /// The incident direction D (unit).
    d: V,
    /// The facing normal N_f.
    n_f: V,
    /// The hit point.
    point: V,
    /// R, when the material reflects.
    r: Option<V>,
    /// T, unless totally reflected.
    t: Option<V>,
    /// n₁, n₂ from the `refract` or `total_internal_reflection` event.
    n1: f64,
    n2: f64,
    /// `k` of a total internal reflection.
    k: Option<f64>,
    entering: bool,
    object: usize,
}

/// The case of node `node` of `traced`, read from its recorded events.
fn case<V: Planar>(traced: &FigureTrace<V>, node: usize) -> Option<Case<V>> {
    let n = &traced.log.nodes[node];
    let hit = n.end.as_ref()?.hit?;
    let n_f = if hit.entering { hit.normal } else { -hit.normal };
    let mut c = Case {
        node,
        d: n.start.direction,
        n_f,
        point: hit.point,
        r: None,
        t: None,
        n1: 1.0,
        n2: 1.0,
        k: None,
        entering: hit.entering,
        object: hit.object.index,
    };
    for e in node_events(&traced.log, node) {
        match e {
            Event::Reflect { direction, .. } => c.r = Some(*direction),
            Event::Refract { direction, n1, n2, .. } => {
                c.t = Some(*direction);
                (c.n1, c.n2) = (*n1, *n2);
            }
            Event::TotalInternalReflection { k, n1, n2 } => {
                c.k = Some(*k);
                (c.n1, c.n2) = (*n1, *n2);
            }
            _ => {}
        }
    }
    Some(c)
}

/// Draws the figure.
///
/// # Errors
/// When the traces hold no refraction and no total internal reflection.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let main = input.main()?;
    let mut cases: Vec<(&FigureTrace<V>, Case<V>)> = Vec::new();
    if let Some(c) = refraction_node(&main.log).and_then(|(k, _)| case(main, k)) {
        cases.push((main, c));
    }
    // The total internal reflection: in the main trace, or in the second trace the source found.
    let tir = tir_node(&main.log)
        .map(|k| (main, k))
        .or_else(|| input.traces.traces.get(1).and_then(|t| tir_node(&t.log).map(|k| (t, k))));
    if let Some(c) = tir.and_then(|(t, k)| case(t, k).map(|c| (t, c))) {
        cases.push(c);
    }
    if cases.is_empty() {
        return Err(FigureError("the trace has no refraction and no total internal reflection".into()));
    }
    let lang = input.lang;

    d.set_title(input.t(Label::TitleRefraction));
    let mut caption = String::new();
    for (k, (traced, c)) in cases.iter().enumerate() {
        let names = Names::of(&traced.log);
        let hit = names.hit_name(c.node).unwrap_or_default();
        let what = if c.k.is_some() { format!("{}: ", input.t(Label::Tir)) } else { String::new() };
        // The trace is named once, unless the second case comes from another one.
        let same = k > 0 && std::ptr::eq(*traced, cases[0].0);
        let source = if same { String::new() } else { format!("{}: ", input.traced(traced)) };
        let sep = if k == 0 { "" } else { "; " };
        let object = object_name(
            input.scene,
            crate::record::event::ObjectRef { index: c.object, triangle: None },
            input.lang,
        );
        caption.push_str(&format!("{sep}{source}{what}{hit} ({object})"));
    }
    caption.push_str(&format!(" · {}", input.t(Label::PlaneOfIncidence)));
    d.set_caption(&caption);
    let incident_roles: Vec<RayRole> =
        cases.iter().map(|(t, c)| parts::role(t.log.nodes[c.node].start.kind)).collect();
    for role in [RayRole::Primary, RayRole::Reflected, RayRole::Transmitted] {
        let used = incident_roles.contains(&role)
            || (role == RayRole::Reflected && cases.iter().any(|(_, c)| c.r.is_some()))
            || (role == RayRole::Transmitted && cases.iter().any(|(_, c)| c.t.is_some()));
        if used {
            legend_role(d, role, lang);
        }
    }
    legend_normal(d, lang);
    d.legend_entry(
        input.t(Label::Inside),
        style::outline(style::BLACK),
        LegendIcon::Swatch(style::OBJECT_FILL),
    );

    // One case: its numbers in a column on the right. Two: side by side, [`PANEL_GAP`] apart,
    // each with its numbers below (in smaller type, [`NUMBERS_BELOW`] kept for them).
    if let [(traced, c)] = cases.as_slice() {
        let column = parts::fit_with_column(d, &[-PANEL_HALF, PANEL_HALF], 0.01, 0.48);
        let lines = panel(input, d, traced, c, DVec2::ZERO);
        text_column(d, column + DVec2::new(0.15, -0.1), &lines, TextSize::Body, 50.0);
    } else {
        let gap = PANEL_GAP;
        let (lo, hi) = (-PANEL_HALF - DVec2::new(0.0, NUMBERS_BELOW), PANEL_HALF + DVec2::new(gap, 0.0));
        d.fit_view(&[lo, hi], 0.01);
        for (k, (traced, c)) in cases.iter().enumerate() {
            let offset = DVec2::new(gap * k as f64, 0.0);
            let lines = panel(input, d, traced, c, offset);
            text_column(d, offset + DVec2::new(-1.55, -1.5), &lines, TextSize::Small, 38.0);
        }
    }
    Ok(())
}

/// The page plane of a case: the plane of incidence through I, the tangent part of D to the right
/// and N_f up.
fn incidence_plane<V: Planar>(c: &Case<V>) -> Option<PagePlane<V>> {
    let tangent = c.d - c.n_f * c.d.dot(c.n_f);
    let fallback = (0..V::DIM).map(V::axis).map(|a| a - c.n_f * a.dot(c.n_f)).find(|a| a.length() > 0.5);
    let tangent = if tangent.length() > 1e-9 { tangent } else { fallback? };
    PagePlane::spanned(c.point, tangent, c.n_f)
}

/// Draws one case at `offset` and returns its text lines.
fn panel<V: Planar>(
    input: &Input<'_, V>,
    d: &mut Drawing,
    traced: &FigureTrace<V>,
    c: &Case<V>,
    offset: DVec2,
) -> Vec<String> {
    let Some(plane) = incidence_plane(c) else { return Vec::new() };
    let plane = plane.shifted(offset);
    let i = plane.point(c.point);
    let len = RAY_LEN;
    let at = |v: DVec2| i + v;

    // The medium of index n₂ below the surface (or above, for a ray leaving the object: n₂ = 1
    // is outside, so the object is on the incoming side).
    let object_below = c.entering;
    let (lo, hi) = if object_below {
        (at(DVec2::new(-SURFACE_HALF, -MEDIUM_DEPTH)), at(DVec2::new(SURFACE_HALF, 0.0)))
    } else {
        (at(DVec2::new(-SURFACE_HALF, 0.0)), at(DVec2::new(SURFACE_HALF, MEDIUM_DEPTH)))
    };
    d.rect("medium", lo, hi, Pen::NONE, Some(style::OBJECT_FILL));
    let (surface, normal) = (DVec2::new(SURFACE_HALF, 0.0), DVec2::new(0.0, NORMAL_HALF));
    // Written out rather than negated, so that no −0 enters the coordinates.
    d.segment("surface", at(DVec2::new(-SURFACE_HALF, 0.0)), at(surface), style::object());
    d.segment(style::NORMAL_TAG, at(DVec2::new(0.0, -NORMAL_HALF)), at(normal), style::normal());

    let page = |v: V| plane.dir(v);
    let incident = page(c.d);
    let role = parts::role(traced.log.nodes[c.node].start.kind);
    // The events each item draws, when this panel shows the main trace (whose events are the
    // trace document's): the incident ray, its hit, R, T.
    let log = &traced.log;
    let own = input.main().is_ok_and(|m| std::ptr::eq(m, traced));
    let mine = |events: Vec<usize>| if own { events } else { Vec::new() };
    let ray_ev = mine(log.ray_events(c.node));
    let hit_ev = mine(log.ended_by(c.node).into_iter().collect());
    let r_ev = mine(log.indices_of(c.node, |e| matches!(e, Event::Reflect { .. })));
    let t_ev =
        mine(log.indices_of(c.node, |e| {
            matches!(e, Event::Refract { .. } | Event::TotalInternalReflection { .. })
        }));
    d.with_events(ray_ev.clone(), |d| parts::draw_ray(d, role, i - incident * len, i));
    if let Some(r) = c.r {
        d.with_events(r_ev.clone(), |d| {
            d.arrow(RayRole::Reflected.tag(), i, i + page(r) * len, RayRole::Reflected.style());
        });
    }
    if let Some(t) = c.t {
        d.with_events(t_ev.clone(), |d| {
            d.arrow(RayRole::Transmitted.tag(), i, i + page(t) * len, RayRole::Transmitted.style());
        });
    }
    d.with_events(hit_ev.clone(), |d| {
        d.dot("hit", i, style::HIT);
    });

    // θᵢ between N and −D; θₜ between −N and T.
    let arc = Pen::solid(style::BLACK, style::CONSTRUCTION_WIDTH);
    let cos_i = (-c.d.dot(c.n_f)).clamp(-1.0, 1.0);
    let theta_i = cos_i.acos();
    let mid_i = draw_arc(d, i, ARC_I, DVec2::Y, -incident, arc);
    let names = Names::of(&traced.log);
    let mut lines = Vec::new();
    // Short names in the wedge; the values head the text column.
    d.text("label", i + (mid_i - i) * 1.45, "θ_i", TextOpts::LABEL.avoid_overlap());
    let n_text = |x: f64, y: f64, text: &str, d: &mut Drawing| {
        let o = TextOpts::LABEL.align(Align { h: HAlign::Left, v: VAlign::Middle });
        d.text("label", at(DVec2::new(x, y)), text, o);
    };
    let (above, below) = (format!("n_1 = {}", slide_number(c.n1)), format!("n_2 = {}", slide_number(c.n2)));
    n_text(INDEX_LABEL.x, INDEX_LABEL.y, &above, d);
    n_text(INDEX_LABEL.x, -INDEX_LABEL.y, &below, d);
    d.text("label", at(normal), "N", TextOpts::LABEL.align(Align::ABOVE).offset(0.0, 4.0));
    if let Some(name) = names.hit_name(c.node) {
        d.with_events(hit_ev, |d| {
            d.text(
                "label",
                i,
                &name,
                TextOpts::LABEL
                    .align(Align { h: HAlign::Left, v: VAlign::Top })
                    .offset(14.0, -12.0)
                    .avoid_overlap(),
            );
        });
    }
    let surface_name = object_name(
        input.scene,
        crate::record::event::ObjectRef { index: c.object, triangle: None },
        input.lang,
    );
    d.text(
        "label",
        at(surface),
        &surface_name,
        TextOpts::NOTE.align(Align { h: HAlign::Right, v: VAlign::Bottom }).offset(0.0, 8.0),
    );
    d.with_events(ray_ev, |d| label_outward(d, i - incident * len, -incident, &names.ray[c.node]));
    if let Some(r) = c.r {
        d.with_events(r_ev, |d| label_outward(d, i + page(r) * len, page(r), "R"));
    }
    let eta = c.n1 / c.n2;
    let theta_t = c.t.map(|t| (-t.dot(c.n_f)).clamp(-1.0, 1.0).acos());
    lines.push(match theta_t {
        Some(tt) => format!("θ_i = {}, θ_t = {}", deg(theta_i), deg(tt)),
        None => format!("θ_i = {}", deg(theta_i)),
    });
    lines.push(format!(
        "η = n_1/n_2 = {}/{} = {}",
        slide_number(c.n1),
        slide_number(c.n2),
        slide_number(eta)
    ));
    lines.push(format!(
        "n_1·sin θ_i = {} · sin {} = {}",
        slide_number(c.n1),
        deg(theta_i),
        slide_number(c.n1 * theta_i.sin())
    ));
    if let Some(t) = c.t {
        let cos_t = (-t.dot(c.n_f)).clamp(-1.0, 1.0);
        let theta_t = cos_t.acos();
        d.with_events(t_ev, |d| {
            let mid_t = draw_arc(d, i, ARC_T, -DVec2::Y, page(t), arc);
            d.text("label", i + (mid_t - i) * 1.4, "θ_t", TextOpts::LABEL.avoid_overlap());
            label_outward(d, i + page(t) * len, page(t), "T");
        });
        lines.push(format!(
            "n_2·sin θ_t = {} · sin {} = {}",
            slide_number(c.n2),
            deg(theta_t),
            slide_number(c.n2 * theta_t.sin())
        ));
        lines.push("T = η·L − (cos θ_t + η·(L·N))·N, L = D".to_owned());
        lines.push(format!("L·N = {}, cos θ_t = {}", slide_number(c.d.dot(c.n_f)), slide_number(cos_t)));
    }
    if let Some(k) = c.k {
        let critical = (c.n2 / c.n1).clamp(-1.0, 1.0).asin();
        lines.push(format!("{} θ_c = asin(n_2/n_1) = {}", input.t(Label::CriticalAngle), deg(critical)));
        lines.push(format!("k = 1 − η^2·(1 − (L·N)^2) = {} < 0", slide_number(k)));
        lines.push(format!("{}: {}", labels::Label::Tir.text(input.lang), input.t(Label::NoT)));
    }
    if c.r.is_some() {
        lines.push("R = 2(N·V)·N − V, V = −L".to_owned());
    }
    lines
}
