//! `ray-tree` (lecture "Ray tracing – arborele de raze", algorithm.md §4, §6): the recorded ray
//! tree of one pixel as a graph. Each node is the ray that reached a hit — P, then R_k and T_k
//! spawned at hit I_k — filled with the colour it returned and ringed in its kind's colour, with
//! the object it hit (or the background) below it; the shadow rays L_k of each hit are leaves with
//! their factor s: free, through
//! transparent objects (0 < s < 1), stopped by an opaque one (s = 0), or not cast at all because
//! the light is behind the surface (lum = 0). Each R and T edge carries its weight as the lecture
//! writes it (`ks = 0.8`, `kt = 0.9`: I = I_local + ks·R + kt·T), and a node whose colour
//! saturates its disc's fill has the colour printed as computed (`I = 1.37`). Rows are the levels
//! n (P is level 1); the depth limit is a line between level `max_depth`, the last whose nodes
//! spawn R and T (§6: a node at level n spawns iff n ≤ max_depth), and the level under it, which
//! it says spawns nothing; nodes it stopped are marked. Every word takes the first of its
//! candidate spots clear of the edges it does not name, the discs and the words before it.

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Mark, Pen, PxRect, TextOpts, Transform, VAlign};
use crate::figure::labels::Label;
use crate::figure::parts::{self, legend_role, swatch, Names};
use crate::figure::plane::Planar;
use crate::figure::style::{self, RayRole};
use crate::figure::FigureError;
use crate::format::markup_escape;
use crate::format::slide_number;
use crate::record::event::{Event, RayKind};
use crate::record::EventLog;
use crate::scene::material::Rgb;

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

/// Where the rows of a tree lie: row r (level r + 1) at y = −r·h, and the rows from `gap_at` down
/// lowered by `extra` more, to make room for the depth-limit line and its words between level
/// `max_depth` (row `gap_at` − 1) and the level under it.
#[derive(Clone, Copy, Debug)]
struct Rows {
    /// The distance between two rows, in world units.
    h: f64,
    /// The first row lowered.
    gap_at: f64,
    /// How much it is lowered, in world units.
    extra: f64,
}

impl Rows {
    /// Evenly spaced rows `h` apart.
    fn even(h: f64) -> Self {
        Self { h, gap_at: f64::INFINITY, extra: 0.0 }
    }

    /// The y of row `row` (0 for the primary ray's).
    fn y(self, row: f64) -> f64 {
        -row * self.h - if row >= self.gap_at { self.extra } else { 0.0 }
    }
}

/// Lays the tree out: leaves one unit apart in order (ray leaves [`RAY_LEAF_GAP`]), each parent over the middle of its
/// children, one row per level (at `rows`). Returns every vertex with its position and parent position.
fn layout<V>(
    log: &EventLog<V>,
    root: usize,
    shadows: bool,
    rows: Rows,
) -> Vec<(Vertex, DVec2, Option<DVec2>)> {
    fn walk<V>(
        log: &EventLog<V>,
        v: Vertex,
        row: f64,
        (shadows, rows): (bool, Rows),
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
            DVec2::new(next.0, rows.y(row))
        } else {
            let xs: Vec<f64> =
                kids.into_iter().map(|c| walk(log, c, row + 1.0, (shadows, rows), next, out).x).collect();
            DVec2::new((xs[0] + xs[xs.len() - 1]) / 2.0, rows.y(row))
        };
        out[slot].1 = at;
        at
    }
    let mut out = Vec::new();
    // The last leaf's x, whether it was a ray's and its row.
    let mut next = (0.0, None);
    walk(log, Vertex::Ray(root), 0.0, (shadows, rows), &mut next, &mut out);
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
    let full = layout(log, root, true, Rows::even(1.0));
    let leaves = full
        .iter()
        .filter(|(v, _, _)| match v {
            Vertex::Ray(k) => children(log, *k, true).is_empty(),
            Vertex::Shadow { .. } => true,
        })
        .count();
    let shadows = leaves <= MAX_LEAVES;
    // Rows as tall as make the graph about as wide as the plot (within reason).
    let probe = if shadows { full } else { layout(log, root, false, Rows::even(1.0)) };
    let width = probe.iter().map(|(_, p, _)| p.x).fold(0.0, f64::max) + 1.7;
    let rows = probe.iter().map(|(_, p, _)| -p.y).fold(0.0, f64::max) + 1.5;
    let natural = width / ASPECT / rows;
    let row_h = natural.clamp(0.55, 1.3);
    // A deep, narrow tree: rows too close for a word under each node.
    let deep = natural < 0.55;
    let graph = layout(log, root, shadows, Rows::even(row_h));
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
    if log.nodes.iter().any(|n| n.start.kind == RayKind::Reflected) {
        roles.push(RayRole::Reflected);
    }
    if log.nodes.iter().any(|n| n.start.kind == RayKind::Transmitted) {
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
    // How far below its centre a vertex's words reach, in reference pixels.
    let reach = |v: &Vertex| match (v, deep) {
        (Vertex::Ray(_), true) => STOP_RADIUS + STOP_CLEAR,
        (Vertex::Ray(_), false) => UNDER_WORD,
        (Vertex::Shadow { .. }, true) => SHADOW_NODE + STOP_CLEAR,
        (Vertex::Shadow { .. }, false) => SHADOW_WORD_BELOW + WORD_BOX + STOP_CLEAR,
    };
    // The limit line lies between level max_depth, the last whose nodes spawn R and T, and level
    // max_depth + 1, whose nodes spawn nothing (§6: a node at level n spawns iff
    // n ≤ max_depth): under the words of the upper level's vertices (its ray nodes, and the
    // shadow leaves of the level above, drawn on its row), with room under it for its words
    // over the lower level's rings. Where the rows are too close for that, the rows from level
    // max_depth + 1 down are lowered by what is missing, and the view fitted again (the scale
    // shrinks a little with the taller tree: a few rounds settle it).
    let gap_at = f64::from(traced.max_depth);
    let mut rows = Rows { h: row_h, gap_at, extra: 0.0 };
    let (mut graph, mut left, mut right, mut limit_y) = (graph, 0.0, 0.0, 0.0);
    for round in 0..LIMIT_ROUNDS {
        graph = layout(log, root, shadows, rows);
        // The view: the graph, a column for the level names on the left, the limit line below.
        let mut points: Vec<DVec2> = graph.iter().map(|(_, p, _)| *p).collect();
        left = points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min) - 1.5;
        right = points.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max) + 0.6;
        let bottom = points.iter().map(|p| p.y).fold(0.0, f64::min) - 0.5 * row_h;
        points.extend([DVec2::new(left, 0.4 * row_h), DVec2::new(right, bottom)]);
        d.fit_view(&points, 0.03);
        // The lowest words must fit too; where they reach depends on the view's scale and the
        // view on where they reach: refit until they agree (three fits move it by well under a
        // pixel).
        for _ in 0..3 {
            let px = d.px_scale() / d.picture_scale();
            let lowest = graph.iter().map(|(v, p, _)| p.y - reach(v) * px).fold(bottom, f64::min);
            let mut with_words = points.clone();
            with_words.push(DVec2::new(left, lowest));
            d.fit_view(&with_words, 0.03);
        }
        if stopped.is_empty() || traced.max_depth == 0 {
            break;
        }
        let px = d.px_scale() / d.picture_scale();
        let upper_y = rows.y(gap_at - 1.0);
        #[allow(clippy::float_cmp)] // a row's y is computed alike for each of its vertices
        let under_upper = graph
            .iter()
            .filter(|(_, p, _)| p.y == upper_y)
            .map(|(v, p, _)| p.y - reach(v) * px)
            .fold(upper_y, f64::min);
        let over_lower = rows.y(gap_at) + (STOP_RADIUS + STOP_CLEAR) * px;
        limit_y = under_upper;
        let missing = LIMIT_ROOM * px - (under_upper - over_lower);
        if missing <= 0.0 || round + 1 == LIMIT_ROUNDS {
            break;
        }
        rows.extra += missing + px;
    }
    let px = d.px_scale() / d.picture_scale();
    if traced.max_depth == 0 {
        // Ray casting: the primary ray itself spawns nothing; the line runs under its words.
        limit_y = graph.iter().map(|(v, p, _)| p.y - reach(v) * px).fold(0.0, f64::min);
    }
    for level in 1..=deepest {
        let y = rows.y(f64::from(level - 1));
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
        d.with_events(limits.iter().copied(), |d| {
            d.segment("depth-limit", DVec2::new(left, limit_y), DVec2::new(right, limit_y), line);
        });
    }
    // Edges first, then the nodes over them, then the words. An edge straight down from a node
    // with its word under it starts below the word, not through it.
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
        let start = edge_start(v, *from, *p, deep, px);
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
    // The words, each at the first of its candidate spots that is clear of the edges it does
    // not name, of the discs and of the words already placed: the shadow leaves' first (short,
    // under their leaf), then the ray nodes' names, object words, colours and edge weights.
    let tf = d.transform();
    let edges: Vec<(usize, DVec2, DVec2)> = graph
        .iter()
        .enumerate()
        .filter_map(|(j, (v, p, parent))| {
            let from = (*parent)?;
            let start = edge_start(v, from, *p, deep, px);
            Some((j, tf.to_px(start), tf.to_px(*p)))
        })
        .collect();
    let discs: Vec<PxRect> = graph
        .iter()
        .map(|(v, p, _)| {
            let r = match v {
                Vertex::Ray(k) if stopped.contains(k) => STOP_RADIUS,
                Vertex::Ray(_) => RAY_NODE,
                Vertex::Shadow { .. } => SHADOW_NODE,
            };
            let (c, r) = (tf.to_px(*p), tf.ref_px(r + 2.0));
            PxRect { min: c - DVec2::splat(r), max: c + DVec2::splat(r) }
        })
        .collect();
    let below_at = |dy: f64| {
        if deep {
            TextOpts::NOTE.align(Align::RIGHT_OF).offset(38.0, 0.0)
        } else {
            TextOpts::NOTE.align(Align::BELOW).offset(0.0, -dy)
        }
    };
    let anchors = graph.iter().map(|(_, p, _)| tf.to_px(*p)).collect();
    let mut spot = Spots { tf, plot: d.frame().plot, edges, discs, anchors };
    if !stopped.is_empty() {
        // The words keep off the depth-limit line.
        let (a, b) = (DVec2::new(left, limit_y), DVec2::new(right, limit_y));
        spot.edges.push((usize::MAX, tf.to_px(a), tf.to_px(b)));
    }
    for (v, p, _) in &graph {
        let Vertex::Shadow { parent, light, s, .. } = v else { continue };
        d.with_events(events_of(v), |d| {
            let beside = TextOpts::LABEL.align(Align::LEFT_OF).offset(-22.0, 0.0);
            d.text("name", *p, &names.shadow_name(*parent, *light), beside);
            let s_text = match s {
                Some(s) => format!("s = {}", slide_number(*s)),
                None => "lum = 0".to_owned(),
            };
            d.text("object", *p, &s_text, below_at(SHADOW_WORD_BELOW));
        });
    }
    for (j, (v, p, parent)) in graph.iter().enumerate() {
        let Vertex::Ray(k) = v else { continue };
        // A stopped node's words stand outside its ring.
        let ring = if stopped.contains(k) { STOP_RADIUS + STOP_CLEAR } else { RAY_NODE };
        let side = ring + 8.0;
        let slant = ring * 0.8;
        d.with_events(events_of(v), |d| {
            let name = [
                TextOpts::LABEL.align(Align::LEFT_OF).offset(-side, 0.0),
                TextOpts::LABEL.align(Align { h: HAlign::Right, v: VAlign::Bottom }).offset(-slant, slant),
                TextOpts::LABEL.align(Align { h: HAlign::Left, v: VAlign::Bottom }).offset(slant, slant),
                TextOpts::LABEL.align(Align::RIGHT_OF).offset(side, 0.0),
            ];
            spot.place(d, j, "name", *p, &names.ray[*k], &name);
            let what = match log.nodes[*k].end.as_ref().and_then(|e| e.hit) {
                Some(h) => markup_escape(&scene.object_label(h.object.index, input.lang)),
                None => input.t(Label::Background).to_owned(),
            };
            let under = WORD_BELOW;
            let word = [
                below_at(under),
                TextOpts::NOTE.align(Align { h: HAlign::Left, v: VAlign::Top }).offset(slant, -slant),
                TextOpts::NOTE.align(Align { h: HAlign::Right, v: VAlign::Top }).offset(-slant, -slant),
                TextOpts::NOTE.align(Align::RIGHT_OF).offset(side, 0.0),
                TextOpts::NOTE.align(Align::LEFT_OF).offset(-side, 0.0),
                TextOpts::NOTE.align(Align { h: HAlign::Left, v: VAlign::Bottom }).offset(slant, slant),
                TextOpts::NOTE.align(Align { h: HAlign::Right, v: VAlign::Bottom }).offset(-slant, slant),
                below_at(under + 30.0),
            ];
            spot.place(d, j, "object", *p, &what, &word);
            if let Some(colour) = log.nodes[*k].end.as_ref().map(|e| e.color).filter(|c| beyond_white(*c)) {
                // A colour above 1 fills the disc white: its value is printed as computed.
                let text = format!("I = {}", parts::rgb_text(colour));
                let far = side + 24.0;
                let mut spots = word.to_vec();
                // One line farther out than the word's spots above and below the node, then
                // beside it farther.
                let line = slant + COLOUR_LINE;
                spots.extend([
                    TextOpts::NOTE.align(Align { h: HAlign::Left, v: VAlign::Bottom }).offset(slant, line),
                    TextOpts::NOTE.align(Align { h: HAlign::Right, v: VAlign::Bottom }).offset(-slant, line),
                    TextOpts::NOTE.align(Align { h: HAlign::Left, v: VAlign::Top }).offset(slant, -line),
                    TextOpts::NOTE.align(Align { h: HAlign::Right, v: VAlign::Top }).offset(-slant, -line),
                    TextOpts::NOTE.align(Align { h: HAlign::Left, v: VAlign::Bottom }).offset(far, slant),
                    TextOpts::NOTE.align(Align { h: HAlign::Right, v: VAlign::Bottom }).offset(-far, slant),
                    TextOpts::NOTE.align(Align::ABOVE).offset(0.0, side),
                    below_at(under + 60.0),
                ]);
                spot.place(d, j, "colour", *p, &text, &spots);
            }
        });
        if let (Some(from), Some((weight, role))) = (parent, edge_weight(input, log, *k)) {
            // The weight the child's colour is multiplied by (I = I_local + ks·R + kt·T), beside
            // the edge it weighs, in its colour.
            let a = tf.to_px(edge_start(v, *from, *p, deep, px));
            let b = tf.to_px(*p);
            let along = (b - a).normalize_or_zero();
            // The two normals of the edge in reference pixels, y up (the page's y runs down); a
            // label whose corner stands on a normal, its box on the normal's side, keeps clear
            // of the edge's whole line.
            let normal = DVec2::new(-along.y, -along.x);
            let weight_opts = TextOpts::NOTE.color(role.color());
            let mut spots = Vec::new();
            // The near spots first; then, where the wedges beside the edge are taken (another
            // edge leaves the node close by), spots farther out and nearer the edge's ends.
            let near = [normal * WEIGHT_GAP, -normal * WEIGHT_GAP, normal * WEIGHT_FAR, -normal * WEIGHT_FAR];
            let far = [
                normal * WEIGHT_FARTHER,
                -normal * WEIGHT_FARTHER,
                normal * WEIGHT_GAP,
                -normal * WEIGHT_GAP,
            ];
            let tries = WEIGHT_AT.iter().map(|s| (*s, &near)).chain(WEIGHT_ENDS.iter().map(|s| (*s, &far)));
            for (share, offsets) in tries {
                let at = tf.to_world(a + (b - a) * share);
                let corners: Vec<TextOpts> = offsets
                    .iter()
                    .copied()
                    .map(|n| {
                        let h = if n.x >= 0.0 { HAlign::Left } else { HAlign::Right };
                        let v = if n.y >= 0.0 { VAlign::Bottom } else { VAlign::Top };
                        weight_opts.align(Align { h, v }).offset(n.x, n.y)
                    })
                    .collect();
                spots.push((at, corners));
            }
            let spots: Vec<(DVec2, &[TextOpts])> = spots.iter().map(|(at, c)| (*at, &c[..])).collect();
            d.with_events(events_of(v), |d| spot.place_any(d, j, "weight", &spots, &weight));
        }
    }
    if !stopped.is_empty() {
        // The limit's words, last, where the others left room: under or over the line.
        let (a, b) = (DVec2::new(left, limit_y), DVec2::new(right, limit_y));
        // In full where there is room, else only what the level below does.
        let full = format!(
            "{} = {}: n = {} {}",
            markup_escape(input.t(Label::MaxDepth)),
            traced.max_depth,
            traced.max_depth + 1,
            input.t(Label::SpawnsNoRt)
        );
        let short = format!("n = {} {}", traced.max_depth + 1, input.t(Label::SpawnsNoRt));
        let opts = TextOpts::NOTE.color(style::VERMILLION);
        let gap = LIMIT_GAP;
        let under = opts.align(Align { h: HAlign::Left, v: VAlign::Top }).offset(0.0, -gap);
        let over = opts.align(Align { h: HAlign::Left, v: VAlign::Bottom }).offset(0.0, gap);
        let sides = [under, over];
        // Along the line from its left end, under it first.
        let anchors: Vec<(DVec2, &[TextOpts])> = (0..LIMIT_SPOTS)
            .map(|k| (a.lerp(b, f64::from(k) / f64::from(LIMIT_SPOTS)), &sides[..]))
            .collect();
        d.with_events(limits.iter().copied(), |d| {
            let clear = |text: &str| {
                spot.best(d, usize::MAX, "label", &anchors, text).is_some_and(|(c, _, _)| c <= 0.0)
            };
            let text = if clear(&full) { full } else { short };
            spot.place_any(d, usize::MAX, "label", &anchors, &text);
            // Words that end past the line's right end: the line runs on under them.
            let words_end = match d.items.last().map(|i| &i.mark) {
                Some(Mark::Text(t)) => tf.to_world(Drawing::ink_box(t, &tf).max).x,
                _ => right,
            };
            if let Some(Mark::Line { points }) =
                d.items.iter_mut().find(|i| i.tag == "depth-limit").map(|i| &mut i.mark)
            {
                if let Some(end) = points.last_mut() {
                    end.x = end.x.max(words_end);
                }
            }
        });
    }
    Ok(())
}

/// Where the edge from `from` down to a vertex at `p` starts: an edge straight down from a node
/// with its word under it starts below the word, not through it.
fn edge_start(v: &Vertex, from: DVec2, p: DVec2, deep: bool, px: f64) -> DVec2 {
    let _ = v;
    let under_word = from.y - UNDER_WORD * px;
    #[allow(clippy::float_cmp)] // a child straight below has its parent's very x
    if !deep && p.x == from.x && under_word > p.y + (RAY_NODE + 6.0) * px {
        DVec2::new(from.x, under_word)
    } else {
        from
    }
}

/// What a tree's words keep clear of, in pixels: the edges (with the index of the vertex each
/// leads to) and the discs of the vertices; and the plot area they keep within.
struct Spots {
    tf: Transform,
    plot: PxRect,
    /// The vertices, in pixels: a node's words must lie nearer their own than any other.
    anchors: Vec<DVec2>,
    edges: Vec<(usize, DVec2, DVec2)>,
    discs: Vec<PxRect>,
}

/// Reference pixels between an edge and its weight.
const WEIGHT_GAP: f64 = 6.0;
/// The farther gap a weight takes where the near one is taken.
const WEIGHT_FAR: f64 = 20.0;
/// Where along its edge a weight may stand, tried in this order (shares of the edge).
const WEIGHT_AT: [f64; 9] = [0.5, 0.4, 0.6, 0.3, 0.7, 0.2, 0.8, 0.15, 0.85];
/// The second round of spots along an edge (shares), with the farthest gap first.
const WEIGHT_ENDS: [f64; 11] = [0.5, 0.6, 0.4, 0.7, 0.3, 0.8, 0.2, 0.85, 0.15, 0.9, 0.1];
/// The farthest gap a weight takes from its edge, in reference pixels.
const WEIGHT_FARTHER: f64 = 36.0;
/// How many spots along the depth-limit line its words may start at.
const LIMIT_SPOTS: u32 = 8;
/// Reference pixels between the depth-limit line and its words.
const LIMIT_GAP: f64 = 8.0;
/// The room, in reference pixels, between the depth-limit line (under the words of level
/// max_depth) and the rings of the level under it: its words under it, a gap either side.
const LIMIT_ROOM: f64 = LIMIT_GAP + WORD_BOX + LIMIT_GAP;
/// How many times the rows under the depth limit may be lowered and the view fitted again.
const LIMIT_ROUNDS: usize = 5;

/// Reference pixels a node's colour may stand one line farther out than its word's spots.
const COLOUR_LINE: f64 = 36.0;

/// How much a word may cross before it is not clear: nothing, in pixels.
const WORD_GAP: f64 = 3.0;

impl Spots {
    /// Draws `markup` for vertex `owner` at `anchor` in the first of `candidates` whose ink is
    /// clear (by [`WORD_GAP`]) of the edges but the one into `owner`, of the other vertices'
    /// discs and of the words already drawn; when none is, in the least covered.
    fn place(
        &mut self,
        d: &mut Drawing,
        owner: usize,
        tag: &str,
        anchor: DVec2,
        markup: &str,
        candidates: &[TextOpts],
    ) {
        self.place_any(d, owner, tag, &[(anchor, candidates)], markup);
    }

    /// As [`Spots::place`], with candidates around several anchors, tried in order.
    fn place_any(
        &mut self,
        d: &mut Drawing,
        owner: usize,
        tag: &str,
        anchors: &[(DVec2, &[TextOpts])],
        markup: &str,
    ) {
        if let Some((_, anchor, opts)) = self.best(d, owner, tag, anchors, markup) {
            d.text(tag, anchor, markup, opts);
        }
    }

    /// The first spot among `anchors`' candidates that is clear, else the least bad: its cost
    /// (0 when clear), anchor and options.
    fn best(
        &self,
        d: &Drawing,
        owner: usize,
        tag: &str,
        anchors: &[(DVec2, &[TextOpts])],
        markup: &str,
    ) -> Option<(f64, DVec2, TextOpts)> {
        let words: Vec<PxRect> = d
            .items
            .iter()
            .filter_map(|i| match &i.mark {
                Mark::Text(t) => Some(Drawing::ink_box(t, &self.tf)),
                _ => None,
            })
            .collect();
        let mut best: Option<(f64, DVec2, TextOpts)> = None;
        for (anchor, candidates) in anchors {
            for opts in *candidates {
                let ink = Drawing::ink_box(&opts.label(markup, *anchor), &self.tf).inflate(WORD_GAP);
                let crossed: f64 = self
                    .edges
                    .iter()
                    // The depth-limit line too: a weight on an edge across it keeps to one side.
                    .filter(|(to, _, _)| *to != owner)
                    .map(|(_, a, b)| ink.length_inside(*a, *b))
                    .sum();
                // Its own disc too, but for the words beside it, which stand clear of it by their
                // offsets (a stopped node's ring reaches past the word under it).
                let discs = self.discs.iter().enumerate().filter(|(j, _)| *j != owner || tag == "weight");
                let covered: f64 = words.iter().chain(discs.map(|(_, r)| r)).map(|r| ink.overlap(r)).sum();
                let outside = ink.width() * ink.height() - ink.overlap(&self.plot);
                // A node's word as near another vertex as its own reads as that one's.
                let own = self.tf.to_px(*anchor);
                let own_gap = gap_to(&ink, own);
                let rival = tag != "weight"
                    && self.anchors.iter().any(|at| at.distance(own) > 1.0 && gap_to(&ink, *at) <= own_gap);
                let cost = crossed * CROSSING_COST
                    + covered
                    + outside * OUTSIDE_COST
                    + if rival { RIVAL_COST } else { 0.0 };
                if best.as_ref().is_none_or(|(c, _, _)| cost < *c) {
                    best = Some((cost, *anchor, *opts));
                }
                if cost <= 0.0 {
                    return best;
                }
            }
        }
        best
    }
}

/// What a word nearer another vertex than its own costs: more than any overlap.
const RIVAL_COST: f64 = 1e6;

/// The distance from `p` to the rectangle `r` (0 inside).
fn gap_to(r: &PxRect, p: DVec2) -> f64 {
    p.distance(p.clamp(r.min, r.max))
}

/// What a square pixel of word outside the plot area costs (against one over another word).
const OUTSIDE_COST: f64 = 10.0;

/// What a pixel of edge inside a word costs against a square pixel of word over a word or a
/// disc: a word across a line is harder to read than one touching another's corner.
const CROSSING_COST: f64 = 10.0;

/// Whether a node's colour has a channel above 1: its swatch clips to white.
fn beyond_white(c: Rgb) -> bool {
    c.0.iter().any(|x| *x > 1.0)
}

/// The weight on the edge into ray node `k` from its parent, as the lecture writes it
/// (`ks = 0.8` on an R edge, `kt = 0.9` on a T edge: `I = I_local + ks·R + kt·T`), with the
/// edge's colour role; none for the primary ray.
fn edge_weight<V: Planar>(input: &Input<'_, V>, log: &EventLog<V>, k: usize) -> Option<(String, RayRole)> {
    let parent = log.nodes[k].parent?;
    let object = log.nodes[parent].end.as_ref()?.hit?.object.index;
    let material = input.scene.material_of(object);
    let kind = log.nodes[k].start.kind;
    let (symbol, weight) = match kind {
        RayKind::Reflected => (Label::WeightKs, material.ks),
        RayKind::Transmitted => (Label::WeightKt, material.kt),
        RayKind::Primary => return None,
    };
    Some((format!("{} = {}", input.t(symbol), slide_number(weight)), parts::role(kind)))
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
