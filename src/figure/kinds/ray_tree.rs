//! `ray-tree` (lecture "Ray tracing – arborele de raze", algorithm.md §4, §6): the recorded ray
//! tree of one pixel as a graph. Each node is the ray that reached a hit — P, then R_k and T_k
//! spawned at hit I_k — filled with the colour it returned and ringed in its kind's colour, with
//! the object it hit (or the background) below it; the shadow rays L_k of each hit are leaves with
//! their factor s: free, through
//! transparent objects (0 < s < 1), stopped by an opaque one (s = 0), or not cast at all because
//! the light is behind the surface (lum = 0). Rows are the levels n (P is level 1); the depth
//! limit `max_depth` is drawn under the last level's nodes and their shadow leaves (shadow rays
//! are cast at every level), and nodes it stopped are marked.

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign};
use crate::figure::labels::Label;
use crate::figure::parts::{self, legend_role, swatch, Names};
use crate::figure::plane::Planar;
use crate::figure::style::{self, RayRole, TextSize};
use crate::figure::FigureError;
use crate::format::markup_escape;
use crate::format::slide_number;
use crate::record::event::Event;
use crate::record::EventLog;

/// Above this many leaves the shadow-ray leaves are left out.
const MAX_LEAVES: usize = 18;
/// The aspect (width / height) the graph is laid out for: that of a slide's plot area beside
/// the legend.
const ASPECT: f64 = 1.25;

/// A node of the drawn graph: a ray node of the log, or a shadow ray of one.
#[derive(Clone, Debug)]
enum Vertex {
    /// A ray node (index into `log.nodes`).
    Ray(usize),
    /// The shadow ray of ray node `parent` towards `light`: its factor s and its role (free,
    /// through transparent objects, stopped by an opaque one); `s` is None when it was not cast
    /// because the light is behind the surface (`lum = 0`).
    Shadow { parent: usize, light: usize, s: Option<f64>, role: RayRole },
}

impl Vertex {
    /// A shadow leaf never cast (`lum = 0`).
    fn uncast(&self) -> bool {
        matches!(self, Vertex::Shadow { s: None, .. })
    }
}

/// The children of ray node `k`: one shadow leaf per light (when shown; cast or not), then R,
/// then T.
fn children<V>(log: &EventLog<V>, k: usize, shadows: bool) -> Vec<Vertex> {
    let mut out = Vec::new();
    if shadows {
        for term in &log.nodes[k].lights {
            let cast = log.events.iter().filter(|l| l.ray == Some(k)).find_map(|l| match &l.event {
                Event::ShadowRay { light, occluders, s, .. } if *light == term.light => {
                    Some(RayRole::shadow(*s, !occluders.is_empty()))
                }
                _ => None,
            });
            let role = cast.unwrap_or(RayRole::Shadow);
            let s = cast.and(term.shadow);
            out.push(Vertex::Shadow { parent: k, light: term.light, s, role });
        }
    }
    out.extend(log.nodes[k].children.iter().map(|c| Vertex::Ray(*c)));
    out
}

/// The distance, in leaf units, between two neighbouring leaves when either is a ray's (a shadow
/// leaf's words are short: its neighbours stay one unit away).
const RAY_LEAF_GAP: f64 = 1.5;

/// The distance, in leaf units, between two neighbouring shadow leaves on one row: their words
/// (`lum = 0`, `s = 0.9`) side by side touched at one unit.
const SHADOW_ROW_GAP: f64 = 1.25;

/// Lays the tree out: leaves one unit apart in order (ray leaves [`RAY_LEAF_GAP`]), each parent over the middle of its
/// children, one row per level. Returns every vertex with its position and parent position.
fn layout<V>(
    log: &EventLog<V>,
    root: usize,
    shadows: bool,
    row_h: f64,
) -> Vec<(Vertex, DVec2, Option<DVec2>)> {
    fn walk<V>(
        log: &EventLog<V>,
        v: Vertex,
        row: f64,
        (shadows, row_h): (bool, f64),
        next: &mut (f64, Option<(bool, f64)>),
        out: &mut Vec<(Vertex, DVec2, Option<DVec2>)>,
    ) -> DVec2 {
        let kids = match v {
            Vertex::Ray(k) => children(log, k, shadows),
            Vertex::Shadow { .. } => Vec::new(),
        };
        let slot = out.len();
        out.push((v.clone(), DVec2::ZERO, None));
        let at = if kids.is_empty() {
            // A ray leaf has a word under it (its object, or "background") and its name beside
            // it: it keeps a wider gap to the leaf before it, so that neither touches.
            let ray = matches!(v, Vertex::Ray(_));
            if let Some((last_ray, last_row)) = next.1 {
                #[allow(clippy::float_cmp)] // rows are whole numbers
                let same_row = last_row == row;
                next.0 += match (ray || last_ray, same_row) {
                    (true, _) => RAY_LEAF_GAP,
                    (false, true) => SHADOW_ROW_GAP,
                    (false, false) => 1.0,
                };
            }
            next.1 = Some((ray, row));
            DVec2::new(next.0, -row * row_h)
        } else {
            let xs: Vec<f64> =
                kids.into_iter().map(|c| walk(log, c, row + 1.0, (shadows, row_h), next, out).x).collect();
            DVec2::new((xs[0] + xs[xs.len() - 1]) / 2.0, -row * row_h)
        };
        out[slot].1 = at;
        at
    }
    let mut out = Vec::new();
    // The last leaf's x, whether it was a ray's and its row.
    let mut next = (0.0, None);
    walk(log, Vertex::Ray(root), 0.0, (shadows, row_h), &mut next, &mut out);
    // Each vertex's parent position, from the tree's own structure.
    let positions: Vec<(Vertex, DVec2)> = out.iter().map(|(v, p, _)| (v.clone(), *p)).collect();
    let of_ray =
        |k: usize| positions.iter().find(|(v, _)| matches!(v, Vertex::Ray(j) if *j == k)).map(|(_, p)| *p);
    out.into_iter()
        .map(|(v, p, _)| {
            let parent = match &v {
                Vertex::Ray(k) => log.nodes[*k].parent.and_then(of_ray),
                Vertex::Shadow { parent, .. } => of_ray(*parent),
            };
            (v, p, parent)
        })
        .collect()
}

/// Draws the figure.
///
/// # Errors
/// When the trace has no ray.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let log = &traced.log;
    let root = log.roots().next().ok_or_else(|| FigureError("the trace has no ray".into()))?;
    let scene = input.scene;
    let names = Names::of(log);
    let full = layout(log, root, true, 1.0);
    let leaves = full
        .iter()
        .filter(|(v, _, _)| match v {
            Vertex::Ray(k) => children(log, *k, true).is_empty(),
            Vertex::Shadow { .. } => true,
        })
        .count();
    let shadows = leaves <= MAX_LEAVES;
    // Rows as tall as make the graph about as wide as the plot (within reason).
    let probe = if shadows { full } else { layout(log, root, false, 1.0) };
    let width = probe.iter().map(|(_, p, _)| p.x).fold(0.0, f64::max) + 1.7;
    let rows = probe.iter().map(|(_, p, _)| -p.y).fold(0.0, f64::max) + 1.5;
    let natural = width / ASPECT / rows;
    let row_h = natural.clamp(0.55, 1.3);
    // A deep, narrow tree: rows too close for a word under each node.
    let deep = natural < 0.55;
    let graph = layout(log, root, shadows, row_h);
    let deepest = log.nodes.iter().map(|n| n.start.level).max().unwrap_or(1);
    let stopped: Vec<usize> = log
        .events
        .iter()
        .filter(|l| matches!(l.event, Event::DepthLimit { .. }))
        .filter_map(|l| l.ray)
        .collect();

    d.set_title(input.t(Label::TitleRayTree));
    let limit = if stopped.is_empty() { format!(" ({})", input.t(Label::NotReached)) } else { String::new() };
    let omitted =
        if shadows { String::new() } else { format!(" · {}", input.t(Label::ShadowLeavesOmitted)) };
    d.set_caption(&format!(
        "{} · {}: {} = {}{limit}{omitted}",
        input.traced(traced),
        input.t(Label::DepthLimit),
        markup_escape(input.t(Label::MaxDepth)),
        traced.max_depth
    ));
    d.legend_entry(
        input.t(Label::NodeColour),
        Pen::solid(style::BLACK, 3.0),
        LegendIcon::Swatch(style::LIGHT_GREY),
    );
    let mut roles = vec![RayRole::Primary];
    if log.nodes.iter().any(|n| n.start.kind == crate::record::event::RayKind::Reflected) {
        roles.push(RayRole::Reflected);
    }
    if log.nodes.iter().any(|n| n.start.kind == crate::record::event::RayKind::Transmitted) {
        roles.push(RayRole::Transmitted);
    }
    if shadows {
        for role in [RayRole::Shadow, RayRole::BlockedShadow, RayRole::OpaqueShadow] {
            if graph
                .iter()
                .any(|(v, _, _)| matches!(v, Vertex::Shadow { s: Some(_), role: r, .. } if *r == role))
            {
                roles.push(role);
            }
        }
    }
    for role in roles {
        legend_role(d, role, input.lang);
    }
    if graph.iter().any(|(v, _, _)| v.uncast()) {
        d.legend_entry(input.t(Label::ShadowNotCast), uncast_style(), LegendIcon::Dot(style::WHITE));
    }
    if !stopped.is_empty() {
        d.legend_entry(input.t(Label::StoppedByDepth), stop_style(), LegendIcon::Dot(style::WHITE));
    }

    // The legend beside the graph, which fills the rest: its corners are rarely free.
    d.legend_place = crate::canvas::LegendPlace::Outside;
    // The view: the graph, a column for the level names on the left, the limit line below.
    let mut points: Vec<DVec2> = graph.iter().map(|(_, p, _)| *p).collect();
    let left = points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min) - 1.5;
    let right = points.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max) + 0.6;
    let bottom = points.iter().map(|p| p.y).fold(0.0, f64::min) - 0.5 * row_h;
    points.extend([DVec2::new(left, 0.4 * row_h), DVec2::new(right, bottom)]);
    d.fit_view(&points, 0.03);
    // The limit line lies below level max_depth + 1, the deepest that a ray may reach: under the
    // words of that level's nodes (which are px below them) and over the next level's nodes.
    // Where it lies depends on the view's scale and the view on where it lies: refit until they
    // agree (three fits move it by well under a pixel).
    let mut limit_y = -(f64::from(traced.max_depth) + 0.5) * row_h;
    if !stopped.is_empty() {
        for _ in 0..3 {
            let px = d.px_scale() / d.picture_scale();
            // Every vertex lies above the line, the last level's shadow leaves too (a shadow ray
            // is cast at every level, the limit stops only R and T): the line
            // runs under the lowest one's word. A deep tree writes its words beside the nodes:
            // then only a stopped node's ring (or a leaf's disc) reaches down.
            let reach = |v: &Vertex| match (v, deep) {
                (Vertex::Ray(_), true) => STOP_RADIUS + STOP_CLEAR,
                (Vertex::Ray(_), false) => UNDER_WORD,
                (Vertex::Shadow { .. }, true) => SHADOW_NODE + STOP_CLEAR,
                (Vertex::Shadow { .. }, false) => SHADOW_WORD_BELOW + WORD_BOX + STOP_CLEAR,
            };
            limit_y = graph.iter().map(|(v, p, _)| p.y - reach(v) * px).fold(f64::INFINITY, f64::min);
            let mut with_limit = points.clone();
            with_limit.push(DVec2::new(left, limit_y - LIMIT_TEXT * px));
            d.fit_view(&with_limit, 0.03);
        }
    }

    for level in 1..=deepest {
        let y = -f64::from(level - 1) * row_h;
        let opts = TextOpts::NOTE.align(Align::RIGHT_OF).color(style::DARK_GREY);
        d.text("level", DVec2::new(left, y), &format!("n = {level}"), opts);
    }
    // What each vertex draws: a ray its spawning event and its hit (and, stopped, its depth
    // limit), a shadow leaf its shadow ray.
    let events_of = |v: &Vertex| match v {
        Vertex::Ray(k) => log.ray_events(*k),
        Vertex::Shadow { parent, light, .. } => log.shadow_events(*parent, *light),
    };
    let limits =
        (0..log.nodes.len()).flat_map(|k| log.indices_of(k, |e| matches!(e, Event::DepthLimit { .. })));
    let limits: Vec<usize> = limits.collect();
    if !stopped.is_empty() {
        let line = Pen::solid(style::VERMILLION, style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH);
        let opts = TextOpts::NOTE
            .align(Align { h: HAlign::Left, v: VAlign::Top })
            .offset(0.0, -8.0)
            .color(style::VERMILLION);
        let text = format!(
            "{}: {} = {}",
            input.t(Label::DepthLimit),
            markup_escape(input.t(Label::MaxDepth)),
            traced.max_depth
        );
        d.with_events(limits.iter().copied(), |d| {
            d.segment("depth-limit", DVec2::new(left, limit_y), DVec2::new(right, limit_y), line);
            d.text("label", DVec2::new(left, limit_y), &text, opts);
        });
    }
    // Edges first, then the nodes over them, then the words. An edge straight down from a node
    // with its word under it starts below the word, not through it.
    let px = d.px_scale() / d.picture_scale();
    for (v, p, parent) in &graph {
        let Some(from) = parent else { continue };
        let (role, stroke) = match v {
            Vertex::Ray(k) => {
                let role = parts::role(log.nodes[*k].start.kind);
                (role, role.style())
            }
            Vertex::Shadow { s: None, .. } => (RayRole::Shadow, uncast_style()),
            Vertex::Shadow { role, .. } => (*role, role.style()),
        };
        let under_word = from.y - UNDER_WORD * px;
        #[allow(clippy::float_cmp)] // a child straight below has its parent's very x
        let start = if !deep && p.x == from.x && under_word > p.y + (RAY_NODE + 6.0) * px {
            DVec2::new(from.x, under_word)
        } else {
            *from
        };
        d.with_events(events_of(v), |d| {
            let tag = if v.uncast() { "ray:shadow-not-cast" } else { role.tag() };
            d.segment(tag, start, *p, stroke);
        });
    }
    for (v, p, _) in &graph {
        d.with_events(events_of(v), |d| match v {
            Vertex::Ray(k) => {
                let node = &log.nodes[*k];
                let role = parts::role(node.start.kind);
                let fill = node.end.as_ref().map_or(style::WHITE, |e| swatch(e.color));
                let ring = Pen::solid(role.color(), style::RAY_WIDTH);
                parts::node_disc(d, "node", *p, RAY_NODE, fill, ring);
                if stopped.contains(k) {
                    let limit = log.indices_of(*k, |e| matches!(e, Event::DepthLimit { .. }));
                    d.with_events(events_of(v).into_iter().chain(limit), |d| {
                        d.marker("stopped", *p, STOP_RADIUS, style::WHITE.with_alpha(0.0), stop_style());
                    });
                }
            }
            Vertex::Shadow { s: None, .. } => {
                parts::node_disc(d, "node:shadow", *p, SHADOW_NODE, style::WHITE, uncast_style());
            }
            Vertex::Shadow { role, .. } => {
                let ring = Pen { width: style::RAY_WIDTH * 0.8, ..role.style() };
                parts::node_disc(d, "node:shadow", *p, SHADOW_NODE, style::WHITE, ring);
            }
        });
    }
    for (v, p, _) in &graph {
        let beside = TextOpts::LABEL.align(Align::LEFT_OF).offset(-36.0, 0.0);
        // Under the node, or beside it when the rows are too close (a deep, narrow tree).
        let below = if deep {
            TextOpts::NOTE.align(Align::RIGHT_OF).offset(38.0, 0.0).size(TextSize::Small)
        } else {
            TextOpts::NOTE.align(Align::BELOW).offset(0.0, -WORD_BELOW).size(TextSize::Small)
        };
        d.with_events(events_of(v), |d| match v {
            Vertex::Ray(k) => {
                // A stopped node's name stands outside its ring.
                let beside = if stopped.contains(k) {
                    beside.offset(-(STOP_RADIUS + STOP_CLEAR), 0.0)
                } else {
                    beside
                };
                d.text("name", *p, &names.ray[*k], beside);
                let what = match log.nodes[*k].end.as_ref().and_then(|e| e.hit) {
                    Some(h) => markup_escape(&scene.object_label(h.object.index, input.lang)),
                    None => input.t(Label::Background).to_owned(),
                };
                // Fixed under the node: the halo keeps it readable over an edge.
                d.text("object", *p, &what, below);
            }
            Vertex::Shadow { parent, light, s, .. } => {
                let name = names.shadow_name(*parent, *light);
                d.text("name", *p, &name, beside.offset(-22.0, 0.0));
                let s_text = match s {
                    Some(s) => format!("s = {}", slide_number(*s)),
                    None => "lum = 0".to_owned(),
                };
                d.text(
                    "object",
                    *p,
                    &s_text,
                    if below.align == Align::BELOW { below.offset(0.0, -SHADOW_WORD_BELOW) } else { below },
                );
            }
        });
    }
    Ok(())
}

/// The radii, in reference pixels, of a ray's node and of a shadow leaf.
const RAY_NODE: f64 = 28.0;
const SHADOW_NODE: f64 = 14.0;
/// Reference pixels from a ray node's centre down to the top of the word under it (its object),
/// and from a shadow leaf's centre to its `s = …`.
const WORD_BELOW: f64 = 34.0;
const SHADOW_WORD_BELOW: f64 = 20.0;
/// The height of the box of a word under a node (small text), in reference pixels.
const WORD_BOX: f64 = 41.0;
/// The reference pixels that the limit's words take under its line.
const LIMIT_TEXT: f64 = 52.0;

/// Reference pixels from a ray node's centre down to below the word under it, with a gap: where
/// an edge straight down starts, and the least depth of the limit line under the last row.
const UNDER_WORD: f64 = WORD_BELOW + WORD_BOX + 5.0;

/// The radius, in reference pixels, of the ring around a node stopped by the depth limit, and the
/// gap kept outside it (by the node's name, by the limit line).
const STOP_RADIUS: f64 = 40.0;
const STOP_CLEAR: f64 = 6.0;

/// A shadow leaf that was not cast (`lum = 0`, the light behind the surface): thin, grey,
/// dotted.
fn uncast_style() -> Pen {
    Pen::solid(style::DARK_GREY, style::CONSTRUCTION_WIDTH).dashed(crate::canvas::Dash { on: 4.0, off: 8.0 })
}

/// The mark of a node stopped by the depth limit: a dashed vermillion ring.
fn stop_style() -> Pen {
    Pen::solid(style::VERMILLION, style::CONSTRUCTION_WIDTH)
        .dashed(crate::canvas::Dash { on: 10.0, off: 7.0 })
}
