//! What `bvh` and `octree` share (lecture "Scena reprezentată printr-o ierarhie de volume
//! încadratoare", "Scena divizată în volume încadratoare (3)", algorithm.md §9): the hierarchy's
//! boxes over the scene, each drawn by what the recorded walk of one primary ray did with it and
//! why — opened (numbered in the order opened), met but skipped because it starts beyond
//! the nearest hit found (`node_skip`, the lecture's rule), missed (its whole subtree skipped), or
//! never tested because an ancestor was missed or skipped — and the tree beside it with the same
//! marks. Nodes are named N₀, N₁, … by the structure's own numbering, the number the narration
//! gives them ("visit node bvh 3" is N₃): never a letter, which the scene's objects may carry.

use glam::DVec2;

use super::Input;
use crate::accel::{Layout, TreeNode};
use crate::bounds::aabb::Aabb;
use crate::canvas::label::{Leader, NEAR_STEPS, OWNER_COST};
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Mark, Pen, PxRect, TextOpts, VAlign, View};
use crate::figure::labels::{self, Label};
use crate::figure::parts::{self, draw_objects, draw_ray, label_objects};
use crate::figure::plane::{Outline, PagePlane, Planar};
use crate::figure::source::{first_hit, met, search_events, search_indexed};
use crate::figure::style::{self, RayRole, Rgba, TextSize};
use crate::figure::FigureError;
use crate::format::markup_escape;
use crate::record::event::Event;
use crate::scene::Scene;

/// What the walk did with a node, and why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Fate {
    /// Its box was met and opened: the k-th node opened (from 1), in the order of the tests.
    Entered(usize),
    /// Its box was met, but it starts beyond the nearest hit already found (`node_skip`,
    /// `t_in > t_best`): left unopened.
    Skipped,
    /// Its box was tested and missed: its subtree was skipped.
    Missed,
    /// Never tested, because an ancestor's box was missed.
    UnderMissed,
    /// Never tested, because an ancestor was skipped beyond the nearest hit.
    UnderSkipped,
    /// Never tested, for no recorded reason (the walk ended first).
    Untested,
}

impl Fate {
    /// Every fate, in the legend's order.
    const ALL: [Fate; 6] = [
        Fate::Entered(1),
        Fate::Skipped,
        Fate::Missed,
        Fate::UnderSkipped,
        Fate::UnderMissed,
        Fate::Untested,
    ];

    /// The name a drawn node's tag carries (`node-skipped:6`, by its number), for pages and tests.
    fn class(self) -> &'static str {
        match self {
            Fate::Entered(_) => "entered",
            Fate::Skipped => "skipped",
            Fate::Missed => "missed",
            Fate::UnderMissed => "under-missed",
            Fate::UnderSkipped => "under-skipped",
            Fate::Untested => "untested",
        }
    }

    /// The legend's words for it.
    fn label(self) -> Label {
        match self {
            Fate::Entered(_) => Label::NodeEntered,
            Fate::Skipped => Label::NodeSkipped,
            Fate::Missed => Label::NodeMissed,
            Fate::UnderMissed => Label::NodeUnderMissed,
            Fate::UnderSkipped => Label::NodeUnderSkipped,
            Fate::Untested => Label::NodeUntested,
        }
    }

    /// Whether the walk never tested the node.
    fn untested(self) -> bool {
        matches!(self, Fate::UnderMissed | Fate::UnderSkipped | Fate::Untested)
    }

    /// The same fate, its order forgotten (to compare kinds).
    fn kind(self) -> Fate {
        match self {
            Fate::Entered(_) => Fate::Entered(1),
            f => f,
        }
    }
}

/// Above this many nodes a hierarchy is dense: its picture names only the nodes at the walk's
/// frontier (the cost lesson's 31 boxes would otherwise bury the walk under names at slide size).
const DENSE_NODES: usize = 15;

/// Above this many objects a scene is crowded: its picture names only the objects of the leaves
/// the walk reached (the rule that every object a figure shows is named stops here).
pub const DENSE_OBJECTS: usize = 15;

/// A sphere drawn at least this wide (its radius, in shares of the view's width) carries its name
/// inside, at its centre: beside a circle, in a group of circles, a name reads as its neighbour's.
const NAME_INSIDE_RADIUS: f64 = 0.012;

/// The corners of a box where its name may stand, in the order tried (a tie goes to the
/// first): the label aligned into the box from each.
const CORNERS: [(HAlign, VAlign); 4] = [
    (HAlign::Left, VAlign::Top),
    (HAlign::Right, VAlign::Top),
    (HAlign::Left, VAlign::Bottom),
    (HAlign::Right, VAlign::Bottom),
];
/// How far inside its corner a box's name stands, in reference pixels across and down: more
/// than the 4 px a placed label keeps clear of lines, so that its own box's edges do not count.
const NAME_INSET: DVec2 = DVec2::new(8.0, 6.0);

/// The ring a box's name may move out to from a corner of its box without a leader: one
/// [`RING_GAP`](crate::canvas::label::RING_GAP) (a tab just outside the box's edge, well within `LEADER_FROM`).
const TAB_RING: [f64; 1] = [1.0];

/// Where in its box a box name's leader may start, as shares of the box across and up, in the
/// order tried (a tie goes to the first): its middle, then, for a name that finds no spot from
/// there clear of the ray and the objects, the middles of the box's outer ninths, so that a
/// leader can leave a small cell on either side of the ray through it.
const LEADER_FROM_SHARES: [DVec2; 9] = [
    DVec2::new(0.5, 0.5),
    DVec2::new(1.0 / 6.0, 0.5),
    DVec2::new(5.0 / 6.0, 0.5),
    DVec2::new(0.5, 1.0 / 6.0),
    DVec2::new(0.5, 5.0 / 6.0),
    DVec2::new(1.0 / 6.0, 1.0 / 6.0),
    DVec2::new(5.0 / 6.0, 1.0 / 6.0),
    DVec2::new(1.0 / 6.0, 5.0 / 6.0),
    DVec2::new(5.0 / 6.0, 5.0 / 6.0),
];
/// What a box name's leader costs per ray or object outline it meets: more than a name that
/// reads as another box's ([`OWNER_COST`]) and lies on a ray
/// ([`GUARDED_LINE_COST`](crate::canvas::label::GUARDED_LINE_COST)) at once, since a leader
/// across a line reads as pointing at that line, and the reader follows it.
const LEADER_ACROSS_COST: f64 = OWNER_COST + crate::canvas::label::GUARDED_LINE_COST;
/// How far, in reference pixels, a box name's leader keeps from the strokes it must not cross,
/// beyond their half widths.
const LEADER_CLEARANCE: f64 = 2.0;

/// How far, in reference pixels, an object's name keeps from where a box name's leader starts:
/// a ring of label spots ([`RING_GAP`](crate::canvas::label::RING_GAP)), so that the leader
/// does not read as pointing at the name.
const LEADER_END_CLEARANCE: f64 = crate::canvas::label::RING_GAP;

/// The entered nodes' colour.
const ENTERED: Rgba = style::BLUISH_GREEN;
/// The missed nodes' colour.
const MISSED: Rgba = style::REDDISH_PURPLE;
/// The colour of nodes skipped beyond the nearest hit.
const SKIPPED: Rgba = style::VERMILLION;
/// The dash of skipped nodes: dots, apart from the missed nodes' dashes.
const SKIPPED_DASH: crate::canvas::Dash = crate::canvas::Dash { on: 5.0, off: 9.0 };

/// The radius of a tree node's disc, in reference pixels.
const TREE_NODE: f64 = 25.0;

/// The tree's top, as a fraction of the view's height below its top, under a legend of up to
/// [`LEGEND_LINES_FREE`] lines.
const TREE_TOP: f64 = 0.36;
/// The legend's lines that fit above [`TREE_TOP`].
const LEGEND_LINES_FREE: usize = 4;
/// A legend line's height, as a fraction of the view's height (slide-size text).
const LEGEND_LINE: f64 = 0.06;

/// Each node's fate from the primary ray's search events: a `node_visit` that meets the box
/// opens the node, unless a `node_skip` names it; a missed box is missed; a node never tested
/// takes its reason from its nearest tested ancestor.
fn fates<V>(nodes: &[TreeNode<V>], search: &[&Event<V>]) -> Vec<Fate> {
    let mut fate: Vec<Option<Fate>> = vec![None; nodes.len()];
    for e in search {
        match **e {
            Event::NodeVisit { node, t_in, t_out, .. } if node < fate.len() && fate[node].is_none() => {
                fate[node] = Some(if met(t_in, t_out) { Fate::Entered(0) } else { Fate::Missed });
            }
            Event::NodeSkip { node, .. } if node < fate.len() => fate[node] = Some(Fate::Skipped),
            _ => {}
        }
    }
    // Number the opened nodes in the order of their tests.
    let mut order = 0;
    for e in search {
        if let Event::NodeVisit { node, .. } = **e {
            if let Some(Some(Fate::Entered(k @ 0))) = fate.get_mut(node) {
                order += 1;
                *k = order;
            }
        }
    }
    // A node never tested inherits its reason from its nearest tested ancestor.
    let mut out: Vec<Fate> = vec![Fate::Untested; nodes.len()];
    fn down<V>(k: usize, inherited: Fate, nodes: &[TreeNode<V>], fate: &[Option<Fate>], out: &mut [Fate]) {
        out[k] = fate[k].unwrap_or(inherited);
        let pass = match out[k] {
            Fate::Missed | Fate::UnderMissed => Fate::UnderMissed,
            Fate::Skipped | Fate::UnderSkipped => Fate::UnderSkipped,
            _ => Fate::Untested,
        };
        for &c in &nodes[k].children {
            down(c, pass, nodes, fate, out);
        }
    }
    down(0, Fate::Untested, nodes, &fate, &mut out);
    out
}

/// The name of node `k`, `N_{k}` (N with k as subscript): the structure's own number, as the
/// narration and the trace's `node_visit` events give it, so that a node's name never reuses
/// the letter of an object (`a` … `h`) or of the lecture's points (I, E).
fn node_name(k: usize) -> String {
    format!("N_{{{k}}}")
}

/// How much of the ray's length a 3D page plane must keep: a plane the ray crosses more steeply
/// than this (|D on the page| < 0.5, over 60° out of it) is chosen only when no other is left.
const MIN_RAY_ON_PAGE: f64 = 0.5;

/// Two sibling overlaps closer than this (in shares of the smaller box) count as equal.
const OVERLAP_TIE: f64 = 1e-6;

/// The page plane: 2D the scene's. In 3D one of the three axis planes (boxes project to
/// rectangles exactly), through the root box's centre: y (the scenes' up) up the page when it is
/// one of its axes and the ray running left to right, else the view from above. Of the three, the figure takes the one that tells the walk most truly:
/// first, the ray keeps at least [`MIN_RAY_ON_PAGE`] of its length on the page; then, fewest
/// boxes the drawn ray would seem to cross while it misses them in space; then, least overlap
/// between sibling boxes (the groups a ray skips drawn apart); last, the plane the ray moves
/// most in. The axes are returned in index order, for the caption.
fn page<V: Planar>(
    nodes: &[TreeNode<V>],
    origin: V,
    direction: V,
    reach: f64,
) -> (PagePlane<V>, Option<[usize; 2]>) {
    let fallback = PagePlane { origin: V::ZERO, x: V::axis(0), y: V::axis(1), offset: DVec2::ZERO };
    if V::DIM == 2 {
        return (fallback, None);
    }
    let score = |dropped: usize| {
        let kept = [(dropped + 1) % 3, (dropped + 2) % 3];
        let steep = (1.0 - direction[dropped].powi(2)).max(0.0).sqrt() < MIN_RAY_ON_PAGE;
        let lies = nodes
            .iter()
            .filter(|n| {
                segment_meets(&n.bounds, origin, direction, reach, &kept)
                    && !segment_meets(&n.bounds, origin, direction, reach, &[0, 1, 2])
            })
            .count();
        (steep, lies, sibling_overlap(nodes, &kept), direction[dropped].abs())
    };
    let better = |a: &(bool, usize, f64, f64), b: &(bool, usize, f64, f64)| {
        (a.0, a.1).cmp(&(b.0, b.1)).then_with(|| {
            if (a.2 - b.2).abs() > OVERLAP_TIE {
                a.2.total_cmp(&b.2)
            } else {
                a.3.total_cmp(&b.3)
            }
        })
    };
    let dropped = (0..3).map(|a| (a, score(a))).min_by(|(_, a), (_, b)| better(a, b)).map_or(2, |(a, _)| a);
    let centre = (nodes[0].bounds.min + nodes[0].bounds.max) * 0.5;
    let axes: Vec<usize> = (0..3).filter(|a| *a != dropped).collect();
    let (across, up) = if dropped == 1 {
        // Seen from above (+y toward the viewer): x across, −z up, since x × (−z) = y.
        (V::axis(0), -V::axis(2))
    } else {
        // y up; across the other axis, signed so the ray runs left to right.
        let other = axes[0] + axes[1] - 1;
        let sign = if direction[other] < 0.0 { -1.0 } else { 1.0 };
        (V::axis(other) * sign, V::axis(1))
    };
    let plane = PagePlane::spanned(centre, across, up).unwrap_or(fallback);
    (plane, Some([axes[0], axes[1]]))
}

/// Whether the segment `O + t·D`, `0 ≤ t ≤ reach`, meets box `b` in the coordinates `axes`
/// (the slab test `max t_near ≤ min t_far` over those axes only). Over all three it is the box in
/// space; over two it is the box's rectangle on that axis plane, for projecting onto an axis plane
/// drops one coordinate and keeps every point's t.
fn segment_meets<V: Planar>(b: &Aabb<V>, origin: V, direction: V, reach: f64, axes: &[usize]) -> bool {
    let (mut near, mut far) = (0.0_f64, reach);
    for &a in axes {
        if direction[a] == 0.0 {
            if origin[a] < b.min[a] || origin[a] > b.max[a] {
                return false;
            }
            continue;
        }
        let (t0, t1) = ((b.min[a] - origin[a]) / direction[a], (b.max[a] - origin[a]) / direction[a]);
        near = near.max(t0.min(t1));
        far = far.min(t0.max(t1));
    }
    near <= far
}

/// How much sibling boxes overlap on the axis plane of `axes`: over every pair of children of a
/// node, the area they share as a share of the smaller one's area, summed.
fn sibling_overlap<V: Planar>(nodes: &[TreeNode<V>], axes: &[usize; 2]) -> f64 {
    let side = |b: &Aabb<V>, a: usize| (b.min[a], b.max[a]);
    let area = |b: &Aabb<V>| axes.iter().map(|&a| (b.max[a] - b.min[a]).max(0.0)).product::<f64>();
    let mut total = 0.0;
    for n in nodes {
        for (i, &p) in n.children.iter().enumerate() {
            for &q in &n.children[i + 1..] {
                let (bp, bq) = (&nodes[p].bounds, &nodes[q].bounds);
                let shared: f64 = axes
                    .iter()
                    .map(|&a| {
                        let ((p0, p1), (q0, q1)) = (side(bp, a), side(bq, a));
                        (p1.min(q1) - p0.max(q0)).max(0.0)
                    })
                    .product();
                let smaller = area(bp).min(area(bq));
                if smaller > 0.0 {
                    total += shared / smaller;
                }
            }
        }
    }
    total
}

/// A box on the page: its projection's bounding rectangle (exact on an axis plane).
fn rect<V: Planar>(plane: &PagePlane<V>, b: &Aabb<V>) -> (DVec2, DVec2) {
    let corners: Vec<DVec2> = (0..1usize << V::DIM)
        .map(|k| {
            let mut p = b.min;
            for a in 0..V::DIM {
                if k & (1 << a) != 0 {
                    p[a] = b.max[a];
                }
            }
            plane.point(p)
        })
        .collect();
    let lo = corners.iter().copied().fold(DVec2::splat(f64::INFINITY), DVec2::min);
    let hi = corners.iter().copied().fold(DVec2::splat(f64::NEG_INFINITY), DVec2::max);
    (lo, hi)
}

/// The world distance between the outlines of a BVH box and its child in a tree `depth` levels
/// deep: 0.8 % of the picture's span a level, and no more than 4 % from the root to the deepest
/// leaf.
fn nesting_gap(depth: u32, span: f64) -> f64 {
    (0.008 * span).min(0.04 * span / f64::from(depth.max(1)))
}

/// Draws a hierarchy figure for `structure` (`bvh` or `octree`) under `title`.
///
/// # Errors
/// When the traces hold no hierarchy or no walk through it.
pub fn draw<V: Planar>(
    input: &Input<'_, V>,
    d: &mut Drawing,
    title: Label,
    structure: &str,
) -> Result<(), FigureError> {
    let traced = input.main()?;
    let Layout::Tree(nodes) = input.traces.accel.layout() else {
        return Err(FigureError(format!("{structure}: the traces were not recorded with a hierarchy")));
    };
    if nodes.is_empty() {
        return Err(FigureError(format!("{structure}: the scene has no bounded object to build it over")));
    }
    let (scene, log) = (input.scene, &traced.log);
    // The walk of the primary ray: every node tested, in order, and every node skipped.
    let search: Vec<&Event<V>> = search_events(log, 0).collect();
    let fate = fates(&nodes, &search);
    let tested = search.iter().filter(|e| matches!(e, Event::NodeVisit { .. })).count();
    let entered = fate.iter().filter(|f| matches!(f, Fate::Entered(_))).count();
    let skipped = fate.iter().filter(|f| **f == Fate::Skipped).count();
    let object_tests = search_events(log, 0).filter(|e| matches!(e, Event::ObjectTest { .. })).count();
    // The `node_visit` events of each node in the primary ray's search: what its box draws.
    let mut visits: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
    for (index, e) in search_indexed(log, 0) {
        if let Event::NodeVisit { node, .. } = *e {
            if let Some(v) = visits.get_mut(node) {
                v.push(index);
            }
        }
    }
    let root = log.nodes.first().ok_or_else(|| FigureError("no ray was traced".into()))?;
    let hit = first_hit(log).filter(|k| *k == 0).and_then(|k| log.nodes[k].end.as_ref()?.hit);
    let reach = hit.map_or(f64::INFINITY, |h| (h.point - root.start.origin).length());
    let (plane, axes) = page(&nodes, root.start.origin, root.start.direction, reach);

    d.set_title(input.t(title));
    let mut caption = format!(
        "{} · {}: {tested}, {}: {entered}, ",
        input.traced(traced),
        input.t(Label::NodesTested),
        input.t(Label::NodesEntered),
    );
    if skipped > 0 {
        caption.push_str(&format!("{}: {skipped}, ", input.t(Label::NodesSkipped)));
    }
    caption.push_str(&labels::objects_tested(object_tests, scene.objects.len(), input.lang));
    if let Some([a, b]) = axes {
        let names = ["x", "y", "z"];
        caption.push_str(&format!(" · {} {}{}", input.t(Label::AxisPlane), names[a], names[b]));
    }
    d.set_caption(&caption);
    legend_role_and_fates(d, input, &fate);
    // The legend over the tree's column, whose top is kept free for it.
    d.legend_place = crate::canvas::LegendPlace::Inside(crate::canvas::Corner::TopRight);
    // The geometry on the left, the tree in the column on the right.
    let mut points: Vec<DVec2> = nodes
        .iter()
        .flat_map(|n| {
            let (lo, hi) = rect(&plane, &n.bounds);
            [lo, hi]
        })
        .collect();
    let from = plane.point(root.start.origin);
    let to = hit.map(|h| plane.point(h.point));
    let span = parts::span(&points);
    let (lo, hi) = rect(&plane, &nodes[0].bounds);
    let near = |p: DVec2| p.clamp(lo - DVec2::splat(0.6 * span), hi + DVec2::splat(0.6 * span));
    points.push(near(from));
    let column = parts::fit_with_column(d, &points, 0.05, 0.5);
    let view = d.view;
    let scene_part = View::new(view.xmin(), column.x, view.ymin(), view.ymax()).unwrap_or(view);

    // A BVH's boxes nest and share edges (a child often spans its parent on some side): each is
    // drawn a little outside its true box, the more the nearer the root, so that every outline
    // stays visible. An octree's cells tile their parent: those are drawn as they are.
    let deepest = nodes.iter().map(|n| n.depth).max().unwrap_or(0);
    let outset = if structure == "bvh" { nesting_gap(deepest, span) } else { 0.0 };
    let drawn = |n: &TreeNode<V>| {
        let (lo, hi) = rect(&plane, &n.bounds);
        let o = outset * f64::from(deepest - n.depth);
        (lo - DVec2::splat(o), hi + DVec2::splat(o))
    };
    // Boxes: untested first (faint), then missed, skipped, then entered, so the walk reads on top.
    let anchors = draw_objects(d, scene, &plane, &scene_part, &[]);
    let passes = [
        Fate::UnderMissed,
        Fate::UnderSkipped,
        Fate::Untested,
        Fate::Missed,
        Fate::Skipped,
        Fate::Entered(1),
    ];
    for pass in passes {
        for (k, n) in nodes.iter().enumerate() {
            let f = fate[k];
            if f.kind() != pass {
                continue;
            }
            let (lo, hi) = drawn(n);
            d.with_events(visits[k].iter().copied(), |d| {
                d.rect(&format!("node-{}:{k}", f.class()), lo, hi, fate_style(f), None);
            });
        }
    }
    // The ray: from where it enters the picture to its hit (or out of the picture).
    let start = parts::entry_point(from, plane.dir(root.start.direction), &scene_part);
    let end = to.unwrap_or_else(|| parts::exit_point(start, plane.dir(root.start.direction), &scene_part));
    d.with_events(log.ray_events(0), |d| draw_ray(d, RayRole::Primary, start, end));
    if let Some(p) = to {
        d.with_events(log.ended_by(0), |d| {
            d.dot("hit", p, style::HIT);
        });
    }
    // Where the names would pile up (a dense tree, or an octree whose cells share their
    // parent's corners), the picture names only the walk's frontier: the nodes it tested whose
    // children it did not; the tree beside names the opened ones above them.
    let crowded = structure == "octree" || nodes.len() > DENSE_NODES;
    let was_tested = |k: usize| !fate[k].untested();
    let named = |k: usize| !crowded || (was_tested(k) && !nodes[k].children.iter().any(|c| was_tested(*c)));
    // A crowded scene's objects are named where the walk reached their leaf (and the hit's): the
    // others are not part of its point.
    let reached: Vec<usize> = nodes
        .iter()
        .enumerate()
        .filter(|(k, n)| was_tested(*k) && n.children.is_empty())
        .flat_map(|(_, n)| n.prims.iter().map(|p| p.object()))
        .chain(hit.map(|h| h.object.index))
        .collect();
    let anchors: Vec<(usize, DVec2)> = anchors
        .into_iter()
        .filter(|(o, _)| scene.objects.len() <= DENSE_OBJECTS || reached.contains(o))
        .collect();
    // A name inside its circle unless another name is already there (overlapping circles);
    // then beside it.
    let mut beside = Vec::new();
    for (o, anchor) in anchors {
        let centre = circle_of(scene, &plane, o).filter(|(_, r)| *r >= NAME_INSIDE_RADIUS * view.width());
        let Some((centre, _)) = centre else {
            beside.push((o, anchor));
            continue;
        };
        let opts =
            TextOpts::NOTE.color(style::DARK_GREY).align(Align { h: HAlign::Center, v: VAlign::Middle });
        d.text(&format!("object-name:{o}"), centre, &markup_escape(&scene.object_label(o, input.lang)), opts);
        let last = d.items.len() - 1;
        if d.overlapping_labels().iter().any(|(a, b)| *a == last || *b == last) {
            d.items.pop();
            beside.push((o, anchor));
        }
    }
    let named: Vec<bool> = (0..nodes.len()).map(named).collect();
    let rects: Vec<(DVec2, DVec2)> = nodes.iter().map(drawn).collect();
    // What a box name's leader must not cross, with its stroke's width: the ray and the objects.
    let ray = Outline::Path(vec![start, end]);
    let mut strokes = vec![Stroke { outline: ray, width: RayRole::Primary.style().width, object: None }];
    for (k, o) in scene.objects.iter().enumerate() {
        let outlines = V::outlines(&o.shape, &plane).into_iter();
        strokes.extend(outlines.map(|ol| Stroke {
            outline: ol.outline,
            width: style::OBJECT_WIDTH,
            object: Some(k),
        }));
    }
    name_boxes(d, &nodes, &named, &rects, &fate, &visits, &strokes);
    // The other objects' names around the boxes' names, their leaders across no ray nor other
    // object where a spot allows (triangle d's name beside the hit, not across the ray); one
    // that finds no spot clear of the other labels and lines is placed clear as any object's
    // name, and settled with them.
    let tf = d.transform();
    // The boxes' names' leaders, which an object's name must not cover (it would read as the
    // box's name, at the end of its leader).
    let leaders: Vec<(DVec2, DVec2)> = d
        .tagged("node-name")
        .filter_map(|i| match &i.mark {
            Mark::Text(t) => Drawing::place_text(t, &tf).leader,
            _ => None,
        })
        .collect();
    let (clear, beside_end) = (tf.ref_px(LEADER_CLEARANCE), tf.ref_px(LEADER_END_CLEARANCE));
    for &(o, anchor) in &beside {
        let others: Vec<&Stroke> = strokes.iter().filter(|s| s.object != Some(o)).collect();
        let name = markup_escape(&scene.object_label(o, input.lang));
        let opts = TextOpts::NOTE.color(style::DARK_GREY).avoid_overlap_with_leader();
        let tag = format!("object-name:{o}");
        d.text_at_cheapest(&tag, &[(anchor, opts, &NEAR_STEPS)], &name, |ink, leader| {
            let covered = leaders
                .iter()
                .filter(|(a, b)| {
                    ink.inflate(clear).meets_segment(*a, *b) || ink.inflate(beside_end).contains_point(*a)
                })
                .count();
            leader_across(others.iter().copied(), leader, &tf) + LEADER_ACROSS_COST * covered as f64
        });
        let last = d.items.len() - 1;
        let on_another = d.overlapping_labels().iter().any(|(a, b)| *a == last || *b == last);
        let on_a_line = d.labels_on_lines(style::RAY_TAG).iter().any(|(a, _)| *a == last)
            || d.labels_on_outlines(style::OBJECT_TAG).iter().any(|(a, _)| *a == last);
        if on_another || on_a_line {
            d.items.pop();
            label_objects(d, scene, &[(o, anchor)], input.lang);
        }
    }
    tree(d, &nodes, &fate, &visits, input, column, &view);
    Ok(())
}

/// Names each named node's box (`named`, drawn at `rects`): inside its box at a corner (or at
/// its middle) where the name keeps clear of the other names, the ray and the objects' outlines,
/// anchored there; where its box has no room, just outside a corner (a tab, in the box of its
/// nearest named ancestor), or out from its middle joined by a leader. A spot that reads as
/// another box's name costs as much as one nearer another anchor: across a named box's
/// outline, or, without a leader, with the innermost named box around it neither its own nor
/// that ancestor's. A leader that meets one of `strokes` (world outlines, with their stroke
/// widths in reference pixels: the ray, the objects) reads as pointing at what it crosses: it
/// costs [`LEADER_ACROSS_COST`] per stroke, and the leader may start at any of its box's
/// [`LEADER_FROM_SHARES`] (beside the ray that runs through a small cell) rather than only at
/// its middle.
fn name_boxes<V>(
    d: &mut Drawing,
    nodes: &[TreeNode<V>],
    named: &[bool],
    rects: &[(DVec2, DVec2)],
    fate: &[Fate],
    visits: &[Vec<usize>],
    strokes: &[Stroke],
) {
    let tf = d.transform();
    let boxes: Vec<PxRect> = rects
        .iter()
        .map(|(lo, hi)| {
            let (a, b) = (tf.to_px(*lo), tf.to_px(*hi));
            PxRect { min: a.min(b), max: a.max(b) }
        })
        .collect();
    let mut parent: Vec<Option<usize>> = vec![None; nodes.len()];
    for (k, n) in nodes.iter().enumerate() {
        for &c in &n.children {
            parent[c] = Some(k);
        }
    }
    let named_ancestor = |k: usize| std::iter::successors(parent[k], |p| parent[*p]).find(|p| named[*p]);
    let tab: &[f64] = &TAB_RING;
    for k in (0..nodes.len()).filter(|k| named[*k]) {
        let (lo, hi) = rects[k];
        let opts = TextOpts::NOTE.size(TextSize::Small).color(fate_colour(fate[k])).avoid_overlap();
        let mut candidates: Vec<(DVec2, TextOpts, &[f64])> = CORNERS
            .iter()
            .map(|&(h, v)| {
                let (left, top) = (h == HAlign::Left, v == VAlign::Top);
                let corner = DVec2::new(if left { lo.x } else { hi.x }, if top { hi.y } else { lo.y });
                let inward = DVec2::new(if left { 1.0 } else { -1.0 }, if top { -1.0 } else { 1.0 });
                let inset = NAME_INSET * inward;
                (corner, opts.align(Align { h, v }).offset(inset.x, inset.y), tab)
            })
            .collect();
        // Its middle and the other points a leader may start from, unless a smaller named box
        // holds them (a leader from there is that one's).
        let leader_from: Vec<(DVec2, TextOpts, &[f64])> = LEADER_FROM_SHARES
            .iter()
            .map(|share| lo + (hi - lo) * *share)
            .filter(|from| {
                let at = tf.to_px(*from);
                !(0..nodes.len()).any(|j| {
                    j != k && named[j] && area(&boxes[j]) < area(&boxes[k]) && boxes[j].contains_point(at)
                })
            })
            .map(|from| (from, opts.align(Align::CENTER).avoid_overlap_with_leader(), &NEAR_STEPS[..]))
            .collect();
        let ancestor = named_ancestor(k);
        let reads_as_another = |ink: &PxRect, leader: Option<Leader>| {
            let across_a_stroke = leader_across(strokes, leader, &tf);
            let leader = leader.is_some();
            let around = (0..nodes.len()).filter(|j| named[*j] && boxes[*j].contains_rect(ink));
            let innermost = around.min_by(|a, b| area(&boxes[*a]).total_cmp(&area(&boxes[*b])));
            let across = (0..nodes.len())
                .any(|j| named[j] && boxes[j].overlap(ink) > 0.0 && !boxes[j].contains_rect(ink));
            let own = leader || innermost == Some(k) || innermost == ancestor;
            across_a_stroke + if own && !across { 0.0 } else { OWNER_COST }
        };
        // The middle first; the other points only for a name that finds no spot there clear of
        // the ray and the objects (a leader across one, or its ink on one).
        let middle = usize::from(
            leader_from.first().is_some_and(|(from, _, _)| *from == lo + (hi - lo) * LEADER_FROM_SHARES[0]),
        );
        candidates.extend(leader_from.iter().take(middle).cloned());
        d.with_events(visits[k].iter().copied(), |d| {
            d.text_at_cheapest("node-name", &candidates, &node_name(k), reads_as_another);
            let last = d.items.len() - 1;
            let Mark::Text(t) = &d.items[last].mark else { return };
            let leader = Drawing::place_text(t, &tf).leader;
            let on_a_line = d.labels_on_lines(style::RAY_TAG).iter().any(|(a, _)| *a == last)
                || d.labels_on_outlines(style::OBJECT_TAG).iter().any(|(a, _)| *a == last);
            if on_a_line || leader_across(strokes, leader, &tf) > 0.0 {
                d.items.pop();
                candidates.extend(leader_from.iter().skip(middle).cloned());
                d.text_at_cheapest("node-name", &candidates, &node_name(k), reads_as_another);
            }
        });
    }
}

/// A line on the page a box name's leader must not cross: the ray, or an object's outline.
struct Stroke {
    /// Where it runs, in world units on the page.
    outline: Outline,
    /// Its stroke's width, in reference pixels.
    width: f64,
    /// The object it outlines, if any.
    object: Option<usize>,
}

/// What a label's `leader` (pixels under `tf`, if it has one) costs for the `strokes` it meets
/// (its centre line within their half widths and [`LEADER_CLEARANCE`]): [`LEADER_ACROSS_COST`]
/// each.
fn leader_across<'a>(
    strokes: impl IntoIterator<Item = &'a Stroke>,
    leader: Option<Leader>,
    tf: &crate::canvas::Transform,
) -> f64 {
    let Some((a, b)) = leader else { return 0.0 };
    let (a, b) = (tf.to_world(a), tf.to_world(b));
    let per_world = tf.len_px(1.0);
    let met = strokes
        .into_iter()
        .filter(|s| s.outline.gap(a, b) * per_world <= tf.ref_px(s.width / 2.0 + LEADER_CLEARANCE))
        .count();
    LEADER_ACROSS_COST * met as f64
}

/// A pixel box's area.
fn area(b: &PxRect) -> f64 {
    b.width() * b.height()
}

/// Object `o`'s section on `plane` when it is a circle: its centre and radius.
fn circle_of<V: Planar>(scene: &Scene<V>, plane: &PagePlane<V>, o: usize) -> Option<(DVec2, f64)> {
    V::outlines(&scene.objects[o].shape, plane).into_iter().find_map(|ol| match ol.outline {
        Outline::Circle { center, radius } if ol.section => Some((center, radius)),
        _ => None,
    })
}

/// The legend: the ray and the fates that occur (the opened boxes always).
fn legend_role_and_fates<V: Planar>(d: &mut Drawing, input: &Input<'_, V>, fate: &[Fate]) {
    parts::legend_role(d, RayRole::Primary, input.lang);
    for f in Fate::ALL {
        if matches!(f, Fate::Entered(_)) || fate.iter().any(|g| g.kind() == f) {
            d.legend_entry(input.t(f.label()), fate_style(f), LegendIcon::Line);
        }
    }
}

fn fate_colour(f: Fate) -> Rgba {
    match f {
        Fate::Entered(_) => ENTERED,
        Fate::Skipped => SKIPPED,
        Fate::Missed => MISSED,
        Fate::UnderMissed | Fate::UnderSkipped | Fate::Untested => style::DARK_GREY,
    }
}

fn fate_style(f: Fate) -> Pen {
    match f {
        Fate::Entered(_) => Pen::solid(ENTERED, style::OBJECT_WIDTH * 1.2),
        Fate::Skipped => Pen::solid(SKIPPED, style::CONSTRUCTION_WIDTH).dashed(SKIPPED_DASH),
        Fate::Missed => Pen::solid(MISSED, style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH),
        Fate::UnderMissed | Fate::Untested => Pen::solid(style::LIGHT_GREY, style::GRID_WIDTH),
        Fate::UnderSkipped => Pen::solid(SKIPPED.with_alpha(0.45), style::GRID_WIDTH).dashed(SKIPPED_DASH),
    }
}

/// Where each shown node of the subtree under `k` goes across the page, in units, its root at 0:
/// the children's subtrees side by side, each as close to the ones before as keeps every two
/// nodes of one level at least a unit apart, and the parent over the middle of its first and last
/// child (a tidy layout after Reingold and Tilford, without their centring of the small subtrees
/// between two large ones). Packing by levels, rather than giving every leaf its own column, keeps
/// a parent near its leaf children: beside a wide sibling they no longer sit so far off that
/// their edges leave the parent almost along one line.
fn tidy<V>(k: usize, nodes: &[TreeNode<V>], shown: &[bool]) -> Tidy {
    let mut placed: Vec<(usize, f64)> = Vec::new();
    let mut extent: Vec<(f64, f64)> = Vec::new();
    let mut roots: Vec<f64> = Vec::new();
    for &c in nodes[k].children.iter().filter(|c| shown[**c]) {
        let Tidy { placed: sub, levels: sub_extent } = tidy(c, nodes, shown);
        // The least shift that keeps this subtree a unit clear of the ones before, level by level.
        let shift = extent
            .iter()
            .zip(&sub_extent)
            .map(|(before, next)| before.1 + 1.0 - next.0)
            .fold(f64::NEG_INFINITY, f64::max);
        let shift = if extent.is_empty() { 0.0 } else { shift };
        placed.extend(sub.into_iter().map(|(n, x)| (n, x + shift)));
        for (level, (lo, hi)) in sub_extent.into_iter().enumerate() {
            match extent.get_mut(level) {
                Some(e) => *e = (e.0.min(lo + shift), e.1.max(hi + shift)),
                None => extent.push((lo + shift, hi + shift)),
            }
        }
        roots.push(shift);
    }
    // The parent over the middle of its first and last child; everything shifted to put it at 0.
    let middle = match (roots.first(), roots.last()) {
        (Some(first), Some(last)) => (first + last) / 2.0,
        _ => 0.0,
    };
    let mut out = vec![(k, 0.0)];
    out.extend(placed.into_iter().map(|(n, x)| (n, x - middle)));
    let mut levels = vec![(0.0, 0.0)];
    levels.extend(extent.into_iter().map(|(lo, hi)| (lo - middle, hi - middle)));
    Tidy { placed: out, levels }
}

/// A subtree laid out by [`tidy`], its root at x = 0.
struct Tidy {
    /// Every shown node of it with its x, in units.
    placed: Vec<(usize, f64)>,
    /// Its extent `(least, greatest x)` on each level, its root's first.
    levels: Vec<(f64, f64)>,
}

/// The tree in the column whose top-left is `column`, laid out by [`tidy`], each node a disc of
/// its fate's colour with its name, the entry order beside it and a leaf's objects under it.
fn tree<V: Planar>(
    d: &mut Drawing,
    nodes: &[TreeNode<V>],
    fate: &[Fate],
    visits: &[Vec<usize>],
    input: &Input<'_, V>,
    column: DVec2,
    view: &View,
) {
    // Only the part of the tree the walk reached, plus the children of what it entered.
    let shown: Vec<bool> = (0..nodes.len())
        .map(|k| {
            !fate[k].untested()
                || nodes
                    .iter()
                    .enumerate()
                    .any(|(p, n)| matches!(fate[p], Fate::Entered(_)) && n.children.contains(&k))
        })
        .collect();
    let Tidy { placed, levels } = tidy(0, nodes, &shown);
    let least = levels.iter().map(|l| l.0).fold(f64::INFINITY, f64::min);
    let units = levels.iter().map(|l| l.1).fold(f64::NEG_INFINITY, f64::max) - least;
    let mut x = vec![0.0; nodes.len()];
    for (k, at) in placed {
        x[k] = at - least;
    }
    let depth = nodes.iter().zip(&shown).filter(|(_, s)| **s).map(|(n, _)| n.depth).max().unwrap_or(0);
    let width = view.xmax() - column.x;
    let (left, right) = (column.x + 0.08 * width, view.xmax() - 0.06 * width);
    // The tree starts under the legend, which grows by one line per fate that occurs.
    let extra = d.legend.len().saturating_sub(LEGEND_LINES_FREE);
    let below_legend = TREE_TOP + LEGEND_LINE * f64::from(u32::try_from(extra).unwrap_or(u32::MAX));
    let (top, bottom) = (view.ymax() - below_legend * view.height(), view.ymin() + 0.1 * view.height());
    let at = |k: usize| {
        let fx = if units > 0.0 { x[k] / units } else { 0.5 };
        let fy = if depth > 0 { f64::from(nodes[k].depth) / f64::from(depth) } else { 0.0 };
        DVec2::new(left + fx * (right - left), top - fy * (top - bottom))
    };
    for (k, n) in nodes.iter().enumerate() {
        if !shown[k] {
            continue;
        }
        for &c in n.children.iter().filter(|c| shown[**c]) {
            d.segment("tree-edge", at(k), at(c), Pen::solid(style::DARK_GREY, style::GRID_WIDTH));
        }
    }
    for (k, n) in nodes.iter().enumerate() {
        if !shown[k] {
            continue;
        }
        let f = fate[k];
        let fill = if matches!(f, Fate::Entered(_)) { ENTERED } else { style::WHITE };
        d.with_events(visits[k].iter().copied(), |d| {
            let ring = fate_style(f).with_width(style::CONSTRUCTION_WIDTH);
            parts::node_disc(d, &format!("tree-node-{}", f.class()), at(k), TREE_NODE, fill, ring);
            let name = TextOpts::NOTE.size(TextSize::Small).align(Align::CENTER).no_halo();
            d.text("tree-name", at(k), &node_name(k), name);
            if let Fate::Entered(order) = f {
                let o = TextOpts::NOTE
                    .size(TextSize::Small)
                    .align(Align { h: HAlign::Left, v: VAlign::Bottom })
                    .offset(20.0, 16.0)
                    .color(ENTERED)
                    .bold();
                d.text("tree-order", at(k), &order.to_string(), o);
            }
            if n.children.is_empty() && !n.prims.is_empty() {
                let names: Vec<String> = n
                    .prims
                    .iter()
                    .map(|p| markup_escape(&input.scene.object_label(p.object(), input.lang)))
                    .collect();
                let o = TextOpts::NOTE
                    .size(TextSize::Small)
                    .align(Align::BELOW)
                    .offset(0.0, -30.0)
                    .color(style::DARK_GREY);
                d.text("tree-objects", at(k), &names.join(", "), o);
            }
        });
    }
}
