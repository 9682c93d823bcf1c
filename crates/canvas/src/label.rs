//! Label placement, `Drawing`'s label methods: [`Drawing::text`] puts a label where its
//! [`TextOpts`] ask ([`Placement`], both beside the items): as given, clear of earlier labels,
//! lines, leaders and other points' markers (with a leader when set far from its anchor), at
//! the cheapest of several anchors (a box's corners). [`Drawing::place_text`] says where a label lands in pixels, for
//! placement and for both back ends; the layout checks (`overlapping_labels`, `labels_on_lines`)
//! read the labels placed.

use glam::DVec2;

use super::drawing::Drawing;
/// The text options, beside the items since the display list stores them; here too for the paths
/// that name them through `label`.
pub use super::items::{Align, HAlign, VAlign};
use super::items::{ArrowPx, Item, Mark, Placement, Text, TextOpts};
use super::legend::PlacedLegend;
use super::style::Pen;
use super::text;
use super::view::{PxRect, Transform};

/// A label placed farther than this many reference pixels from its anchor gets a leader
/// ([`TextOpts::avoid_overlap_with_leader`]).
pub const LEADER_FROM: f64 = 30.0;

/// The gap between two rings of candidate spots around a label's anchor, in reference pixels.
pub const RING_GAP: f64 = 14.0;

/// What a candidate spot costs per share of its padded box that covers earlier labels and other
/// points' markers: covering all of one weighs as much as [`OUTSIDE_COST`].
pub const COVER_COST: f64 = 100.0;
/// What a candidate spot costs per line it crosses: the unit of the other costs, since the halo
/// keeps a label readable over a line.
pub const LINE_COST: f64 = 1.0;
/// What a candidate spot partly outside the label area costs.
pub const OUTSIDE_COST: f64 = 100.0;
/// What a candidate spot's leader costs per label it would cross.
pub const LEADER_CROSSING_COST: f64 = 20.0;
/// A label's ink box lies on a line when the line's stroke crosses it over more than this many
/// reference pixels ([`Drawing::labels_on_lines`]): a stroke that only grazes a corner leaves
/// every glyph readable, one that runs through the box hides part of a glyph.
pub const MIN_CROSSING: f64 = 4.0;
/// How near a guarded arrow's head may come to a label's ink box, in reference pixels
/// ([`Drawing::labels_on_strict_lines`]): the spacing a label placed clear keeps from what it avoids.
pub const HEAD_CLEARANCE: f64 = 4.0;
/// What a candidate spot costs per guarded line ([`Drawing::guard_lines`], a figure's rays) it
/// crosses and does not name: more than moving to the farthest ring and crossing a few plain
/// lines, less than covering most of another label, so a name leaves a ray it would hide a part
/// of whenever a spot allows.
pub const GUARDED_LINE_COST: f64 = 30.0;
/// What each ring farther from the anchor costs: a label far from its anchor loses its meaning.
pub const RING_COST: f64 = 1.5;
/// What a candidate spot costs when it reads as the name of another anchor of the label's
/// kind ([`Drawing::labels_nearer_another_anchor`], with or without a leader): the reader takes
/// a name for the nearest point's, so it weighs more than crossing one guarded line or outline
/// (a name across a ray stays readable, a name at the wrong point teaches the wrong thing),
/// less than covering most of another label.
pub const OWNER_COST: f64 = 45.0;
/// What a candidate spot costs per object outline ([`Drawing::guard_outlines`]) it crosses
/// that is not its own: as much as a guarded line, a name on an outline reads as that object's.
pub const OUTLINE_COST: f64 = GUARDED_LINE_COST;
/// Two anchors closer than this many reference pixels are one point
/// ([`Drawing::labels_nearer_another_anchor`]): labels that share a point share its anchor.
pub const SAME_ANCHOR: f64 = 1.0;
/// A label with a leader still reads as the name of another anchor of its kind that lies
/// within this many reference pixels of its ink ([`LEADER_MARGIN`]): beside that point, the
/// short line to its own is missed (ray-casting 2's "I₃" beside I₅, issue 32 item 1).
pub const LEADER_RIVAL: f64 = 2.0 * LEADER_FROM;
/// A label with a leader reads as its own anchor's only when every other anchor of its kind
/// within [`LEADER_RIVAL`] lies more than this many times as far from its ink as its own: two
/// labels mid-way between their points, each a little nearer its own (Kay–Kajiya's bold "I" and
/// "E"), are read by where they stand, not by their leaders.
pub const LEADER_MARGIN: f64 = 1.25;
/// A leader that passes this close to another anchor of its label's kind, in reference pixels,
/// reads as pointing at that anchor.
pub const LEADER_PASS: f64 = 4.0;
/// An outline that passes this close to a label's anchor, in reference pixels, is the outline
/// of the object the label's point lies on: its own ([`Drawing::labels_on_outlines`]).
pub const OWN_OUTLINE: f64 = 3.0;

/// The kind of a label, by its tag: the part before the first `:` (`object-name:2` →
/// `object-name`). A label names its anchor among the anchors of the labels of its kind.
#[must_use]
pub fn label_kind(tag: &str) -> &str {
    tag.split(':').next().unwrap_or(tag)
}

/// The part of a tag after its first `:` (`object-name:2` → `2`, `object:2` → `2`), if any: a
/// label and an outline with the same one name the same object.
fn tag_id(tag: &str) -> Option<&str> {
    tag.split_once(':').map(|(_, id)| id)
}

/// The distance in pixels from `p` to the segment `a`–`b`.
fn to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t =
        if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
    p.distance(a + ab * t)
}

/// Whether a label of ink box `ink`, anchored at `own` (pixels) and joined to it by `leader`,
/// reads as the name of the anchor `rival` (pixels) of its kind (issue 32 item 1). Without a
/// leader when `rival` lies as near the ink as `own`:
/// `gap(ink, rival) ≤ gap(ink, own)`. With one when `rival` lies within [`LEADER_RIVAL`] of the
/// ink and `gap(ink, rival) ≤ LEADER_MARGIN · gap(ink, own)`, or when the leader passes within
/// [`LEADER_PASS`] of `rival` away from its own end (an anchor beside its own, as overlapping
/// circles' centres, is told apart by the label's side, not by the line).
fn reads_as(ink: &PxRect, own: DVec2, leader: Option<(DVec2, DVec2)>, rival: DVec2, tf: &Transform) -> bool {
    let (gap, own_gap) = (gap_to(ink, rival), gap_to(ink, own));
    match leader {
        None => gap <= own_gap,
        Some((a, c)) => {
            (gap <= LEADER_MARGIN * own_gap && gap <= tf.ref_px(LEADER_RIVAL))
                || (to_segment(rival, a, c) <= tf.ref_px(LEADER_PASS)
                    && rival.distance(a) > 2.0 * tf.ref_px(LEADER_PASS))
        }
    }
}

/// The distance in pixels from `p` to the nearest point of `b` (0 inside).
fn gap_to(b: &PxRect, p: DVec2) -> f64 {
    (p.clamp(b.min, b.max) - p).length()
}

/// The distances, in gaps of [`RING_GAP`], at which [`Placement::Clear`] tries the eight
/// directions around the anchor: near, for a crowded diagram, where a name far from its object
/// would be lost among the others.
pub const NEAR_STEPS: [f64; 4] = [1.0, 2.5, 4.5, 7.0];
/// [`NEAR_STEPS`] and two more rings, for a plot whose points crowd one band of a mostly empty
/// area: a name may go to the empty part, with its leader.
pub const FAR_STEPS: [f64; 6] = [1.0, 2.5, 4.5, 7.0, 10.0, 14.0];

/// A label's leader in pixels: from its anchor to the point just short of its box.
pub type Leader = (DVec2, DVec2);

/// No cost of the caller's own for any spot (see [`Drawing::place_clear`]).
fn no_fit(_: &PxRect, _: Option<Leader>) -> f64 {
    0.0
}

/// A text item placed in canvas pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedText {
    /// The start of the baseline.
    pub origin: DVec2,
    /// The text box.
    pub bbox: PxRect,
    /// Font size in pixels.
    pub size: f64,
    /// The leader from the anchor to the nearest point of the box (pixels), when the label has
    /// one ([`Text::leader`]) and the anchor lies outside the box.
    pub leader: Option<(DVec2, DVec2)>,
}

impl Drawing {
    /// Adds a label at `anchor`. With [`TextOpts::avoid_overlap`], the label keeps the requested
    /// placement if its box is clear of earlier labels and lines and inside the plot area;
    /// otherwise it takes the first clear spot among candidates around the anchor (eight
    /// directions, at growing distances), or the least bad one if none is clear.
    pub fn text(&mut self, tag: &str, anchor: DVec2, markup: &str, opts: TextOpts) -> &mut Self {
        let mut label = opts.label(markup, anchor);
        match opts.placement {
            Placement::AsGiven => {}
            Placement::Clear => {
                let steps: &[f64] = if opts.far { &FAR_STEPS } else { &NEAR_STEPS };
                self.place_clear(tag, &mut label, opts.leader, steps, &no_fit);
                self.placed_clear.push((self.items.len(), opts.far));
            }
        }
        let style = Pen { color: opts.color, width: 0.0, dash: None };
        self.push(tag, style, Mark::Text(label))
    }

    /// Adds a label placed clear ([`TextOpts::avoid_overlap`]) at whichever of `candidates` (an
    /// anchor, the options asked there and the rings, in [`RING_GAP`]s, it may move out to)
    /// gives it the cheapest spot: a box's name may stand at any of its corners or at its
    /// middle, the one that leaves it clear of the other labels, the rays and the objects'
    /// outlines. `fit` adds the caller's own cost of a spot, from its ink box and the leader
    /// that joins it to its anchor, if any (pixels): a box's name read as another box's, a
    /// leader across a ray. The spots asked come
    /// first: the first of them that costs nothing wins; when none does, the cheapest spot of
    /// any candidate's rings (the first on a tie). The label keeps the anchor it was placed at,
    /// which the layout checks measure it against; [`Drawing::settle_labels`] leaves it where
    /// it is, as it cannot weigh `fit`.
    pub fn text_at_cheapest(
        &mut self,
        tag: &str,
        candidates: &[(DVec2, TextOpts, &[f64])],
        markup: &str,
        fit: impl Fn(&PxRect, Option<Leader>) -> f64,
    ) -> &mut Self {
        let mut best: Option<(f64, Text, TextOpts)> = None;
        // The spots asked, then each candidate's rings.
        for rings in [false, true] {
            for &(anchor, opts, steps) in candidates {
                let mut label = opts.label(markup, anchor);
                let steps = if rings { steps } else { &[] };
                let cost = self.place_clear(tag, &mut label, opts.leader, steps, &fit);
                if best.as_ref().is_none_or(|(least, _, _)| cost < *least) {
                    best = Some((cost, label, opts));
                }
                if !rings && cost <= 0.0 {
                    break;
                }
            }
            if best.as_ref().is_some_and(|(least, _, _)| *least <= 0.0) {
                break;
            }
        }
        let Some((_, label, opts)) = best else { return self };
        let style = Pen { color: opts.color, width: 0.0, dash: None };
        self.push(tag, style, Mark::Text(label))
    }

    /// Removes the last item (a label tried and refused) and its record as placed clear, so
    /// that [`Drawing::settle_labels`] does not move another in its place.
    pub fn pop_item(&mut self) -> Option<Item> {
        let item = self.items.pop()?;
        let index = self.items.len();
        self.placed_clear.retain(|(k, _)| *k != index);
        Some(item)
    }

    /// Where a text item lands in pixels under `tf`: its baseline origin, box and size.
    #[must_use]
    pub fn place_text(label: &Text, tf: &Transform) -> PlacedText {
        let size = tf.ref_px(label.size.px());
        let laid = text::layout(&label.text, size, label.weight);
        let p = tf.to_px(label.anchor) + tf.offset_px(label.offset);
        let x = match label.align.h {
            HAlign::Left => p.x,
            HAlign::Center => p.x - laid.width / 2.0,
            HAlign::Right => p.x - laid.width,
        };
        let baseline = match label.align.v {
            VAlign::Top => p.y + laid.ascent,
            VAlign::Middle => p.y + text::cap_height(size) / 2.0,
            VAlign::Baseline => p.y,
            VAlign::Bottom => p.y - laid.descent,
        };
        let origin = DVec2::new(x, baseline);
        let bbox = PxRect {
            min: DVec2::new(x, baseline - laid.ascent),
            max: DVec2::new(x + laid.width, baseline + laid.descent),
        };
        let leader = label.leader.then(|| tf.to_px(label.anchor)).and_then(|a| {
            // The nearest point of the box, a few pixels off it so the line stops short of the glyphs.
            let on_box = a.clamp(bbox.min, bbox.max);
            let gap = tf.ref_px(4.0);
            let length = (on_box - a).length();
            (length > 2.0 * gap).then(|| (a, a + (on_box - a) * ((length - gap) / length)))
        });
        PlacedText { origin, bbox, size, leader }
    }

    /// The pixel segments of every stroked item (circles as 48-gons, dots as their boxes'
    /// diagonals, labels' leaders), for the overlap tests of label and legend placement.
    pub(super) fn segments(&self, tf: &Transform) -> Vec<(DVec2, DVec2)> {
        let mut out = Vec::new();
        for item in &self.items {
            Self::item_segments(item, tf, &mut out);
        }
        out
    }

    /// The pixel segments of one item's stroke, appended to `out` (see [`Drawing::segments`]).
    fn item_segments(item: &Item, tf: &Transform, out: &mut Vec<(DVec2, DVec2)>) {
        let chain = |pts: &[DVec2], closed: bool, out: &mut Vec<(DVec2, DVec2)>| {
            let px: Vec<DVec2> = pts.iter().map(|p| tf.to_px(*p)).collect();
            out.extend(px.windows(2).map(|w| (w[0], w[1])));
            if closed && px.len() > 2 {
                out.push((px[px.len() - 1], px[0]));
            }
        };
        match &item.mark {
            Mark::Line { points } => chain(points, false, out),
            Mark::Arrow { from, to, .. } => chain(&[*from, *to], false, out),
            Mark::Polygon { points, .. } => chain(points, true, out),
            Mark::Rect { min, max, .. } => {
                let corners = [*min, DVec2::new(max.x, min.y), *max, DVec2::new(min.x, max.y)];
                chain(&corners, true, out);
            }
            Mark::Circle { center, radius, .. } => {
                let ring: Vec<DVec2> = (0..48)
                    .map(|i| {
                        let a = std::f64::consts::TAU * f64::from(i) / 48.0;
                        *center + *radius * DVec2::new(a.cos(), a.sin())
                    })
                    .collect();
                chain(&ring, true, out);
            }
            // A leader is a line like any other: a later label keeps off it.
            Mark::Text(label) => out.extend(Self::place_text(label, tf).leader),
            Mark::Dot { center, radius, .. } => {
                let c = tf.to_px(*center);
                let r = tf.ref_px(*radius);
                out.push((c - DVec2::splat(r), c + DVec2::splat(r)));
                out.push((c + DVec2::new(-r, r), c + DVec2::new(r, -r)));
            }
        }
    }

    /// The ink box of every text item, with its index into `items`: its advance width across
    /// and its glyphs' ink up and down ([`text::TextLayout::ink`]), where both back ends draw it.
    fn ink_boxes(&self, tf: &Transform) -> Vec<(usize, PxRect)> {
        self.ink_boxes_of(tf, None)
    }

    /// [`Drawing::ink_boxes`] of text item `only` alone (none when it is not text), or of every
    /// text item when `only` is `None`: a check of one label runs in the items' count, not its
    /// square (a 2D lens figure at depth 64, 1 379 labels, took over two minutes to settle them).
    fn ink_boxes_of(&self, tf: &Transform, only: Option<usize>) -> Vec<(usize, PxRect)> {
        let text = |(k, item): (usize, &Item)| match &item.mark {
            Mark::Text(label) => Some((k, Self::ink_box(label, tf))),
            _ => None,
        };
        match only {
            Some(k) => self.items.get(k).and_then(|item| text((k, item))).into_iter().collect(),
            None => self.items.iter().enumerate().filter_map(text).collect(),
        }
    }

    /// Where a text item's ink lands in pixels under `tf`: its advance width across and its
    /// glyphs' ink up and down ([`text::TextLayout::ink`]), the box the layout checks use.
    #[must_use]
    pub fn ink_box(label: &Text, tf: &Transform) -> PxRect {
        let placed = Self::place_text(label, tf);
        let (above, below) = text::layout(&label.text, placed.size, label.weight).ink();
        let (x0, x1) = (placed.bbox.min.x, placed.bbox.max.x);
        let y = placed.origin.y;
        PxRect { min: DVec2::new(x0, y - above), max: DVec2::new(x1, y + below) }
    }

    /// The pairs of text items, as indices into `items`, whose ink overlaps where both back ends
    /// draw them (under [`Drawing::frame`]'s transform): one label printed on top of another.
    /// Each label is its advance width across and its glyphs' ink up and down
    /// ([`text::TextLayout::ink`]), so lines of a column, whose font boxes touch, pass. Empty
    /// for a legible layout: the check that proves it, not a look at the picture.
    #[must_use]
    pub fn overlapping_labels(&self) -> Vec<(usize, usize)> {
        let boxes = self.ink_boxes(&self.frame().transform);
        let mut out = Vec::new();
        for (n, (i, a)) in boxes.iter().enumerate() {
            for (j, b) in &boxes[n + 1..] {
                if a.overlap(b) > 0.0 {
                    out.push((*i, *j));
                }
            }
        }
        out
    }

    /// Whether text item `index`'s ink overlaps another label's ([`Drawing::overlapping_labels`]
    /// of that one item).
    fn overlaps_another_label(&self, index: usize) -> bool {
        let tf = self.frame().transform;
        let Some((_, own)) = self.ink_boxes_of(&tf, Some(index)).pop() else { return false };
        self.ink_boxes(&tf).iter().any(|(k, b)| *k != index && own.overlap(b) > 0.0)
    }

    /// The pairs `(label, line)`, as indices into `items`, of a text item whose ink box (see
    /// [`Drawing::overlapping_labels`]) lies on a guarded line it does not name: a stroked item
    /// whose tag starts with `guard` (a figure's rays) sharing none of the label's events
    /// ([`Item::events`]; a label with no events names no line). "Lies on" means the line's
    /// stroke, its half width around its centre line, crosses the box over more than
    /// [`MIN_CROSSING`] reference pixels of the centre line: a corner grazed is not a crossing.
    /// Empty for a legible layout.
    #[must_use]
    pub fn labels_on_lines(&self, guard: &str) -> Vec<(usize, usize)> {
        self.labels_on(guard, false, None)
    }

    /// The pairs `(label, line)`, as indices into `items`, of a text item whose ink box (see
    /// [`Drawing::overlapping_labels`]) lies on a line or arrow tagged `prefix…` (strictly
    /// guarded, [`Drawing::guard_strictly`]), even one whose events it draws: on its shaft as in [`Drawing::labels_on_lines`], or on
    /// its head anywhere or within [`HEAD_CLEARANCE`] (a head touching a label reads as
    /// pointing at the label, not at the point it maps). Empty for a legible layout.
    #[must_use]
    pub fn labels_on_strict_lines(&self, prefix: &str) -> Vec<(usize, usize)> {
        self.labels_on(prefix, true, None)
    }

    /// The pairs `(label, line)` of a text item whose ink box lies on a line tagged `prefix…`:
    /// its stroke crosses the box over more than [`MIN_CROSSING`]; with `strict`, also a label
    /// that names the line, and one its arrow head meets within [`HEAD_CLEARANCE`]. Of text
    /// item `only` alone when given ([`Drawing::ink_boxes_of`]).
    fn labels_on(&self, prefix: &str, strict: bool, only: Option<usize>) -> Vec<(usize, usize)> {
        let tf = self.frame().transform;
        let boxes = self.ink_boxes_of(&tf, only);
        let mut out = Vec::new();
        for (j, line) in self.items.iter().enumerate() {
            if !Self::guarded(line, prefix) {
                continue;
            }
            let (mut shaft, mut head) = (Vec::new(), Vec::new());
            Self::item_segments(line, &tf, &mut shaft);
            if strict {
                Self::head_segments(line, &tf, &mut head);
            }
            let half = tf.ref_px(line.pen.width) / 2.0;
            for (i, b) in &boxes {
                if !strict && Self::names(&self.items[*i].events, line) {
                    continue;
                }
                let stroke = b.inflate(half);
                let along: f64 = shaft.iter().map(|(p, q)| stroke.length_inside(*p, *q)).sum();
                let near = b.inflate(tf.ref_px(HEAD_CLEARANCE));
                let on_head = head.iter().any(|(p, q)| near.meets_segment(*p, *q));
                if along > tf.ref_px(MIN_CROSSING) || on_head {
                    out.push((*i, j));
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// The pixel edges of the head of `item` when it is an arrow (its closed quadrilateral,
    /// [`ArrowPx`]); nothing for any other mark.
    fn head_segments(item: &Item, tf: &Transform, out: &mut Vec<(DVec2, DVec2)>) {
        if let Mark::Arrow { from, to, head } = &item.mark {
            if let Some(arrow) = ArrowPx::new(tf.to_px(*from), tf.to_px(*to), tf.ref_px(*head)) {
                let h = arrow.head;
                out.extend((0..h.len()).map(|k| (h[k], h[(k + 1) % h.len()])));
            }
        }
    }

    /// The pairs `(label, rival)`, as indices into `items`, of a text item whose ink box (see
    /// [`Drawing::overlapping_labels`]) reads as the name of the anchor of `rival` — another
    /// text item of its kind ([`label_kind`]) anchored elsewhere (farther than [`SAME_ANCHOR`]):
    /// without a leader, lies as near it as its own anchor; with one, as in `reads_as` (a
    /// leader does not excuse a name beside another point). Issue 32 item 1; empty when every
    /// label belongs to its point.
    #[must_use]
    pub fn labels_nearer_another_anchor(&self) -> Vec<(usize, usize)> {
        let tf = self.frame().transform;
        let mut out = Vec::new();
        for (i, item) in self.items.iter().enumerate() {
            if let Mark::Text(label) = &item.mark {
                if let Some(j) = self.rival(&item.tag, label, i, &tf) {
                    out.push((i, j));
                }
            }
        }
        out
    }

    /// The first text item of `tag`'s kind, other than item `skip`, anchored elsewhere, whose
    /// anchor `label` reads as the name of (`reads_as`); `None` when there is none (see
    /// [`Drawing::labels_nearer_another_anchor`]).
    fn rival(&self, tag: &str, label: &Text, skip: usize, tf: &Transform) -> Option<usize> {
        let leader = Self::place_text(label, tf).leader;
        let ink = Self::ink_box(label, tf);
        let own = tf.to_px(label.anchor);
        let kind = label_kind(tag);
        self.items.iter().enumerate().find_map(|(k, item)| match &item.mark {
            Mark::Text(other) if k != skip && label_kind(&item.tag) == kind => {
                let at = tf.to_px(other.anchor);
                let elsewhere = at.distance(own) > tf.ref_px(SAME_ANCHOR);
                (elsewhere && reads_as(&ink, own, leader, at, tf)).then_some(k)
            }
            _ => None,
        })
    }

    /// The pairs `(label, outline)`, as indices into `items`, of a text item whose ink box lies
    /// on the outline of an object it does not name (issue 32 item 1): a stroked item whose tag
    /// starts with `prefix` (`object:`), neither named by the label's tag (`object-name:2` names
    /// `object:2`). "Lies on" as in [`Drawing::labels_on_lines`]. The outline passing within
    /// [`OWN_OUTLINE`] of the label's anchor (the object a hit point lies on) may touch it but
    /// not run through its ink box itself over [`MIN_CROSSING`] (shadows 1's "I₁" struck
    /// through by the floor). Empty for a legible layout.
    #[must_use]
    pub fn labels_on_outlines(&self, prefix: &str) -> Vec<(usize, usize)> {
        self.labels_on_outlines_of(prefix, None)
    }

    /// [`Drawing::labels_on_outlines`] of text item `only` alone when given.
    fn labels_on_outlines_of(&self, prefix: &str, only: Option<usize>) -> Vec<(usize, usize)> {
        let tf = self.frame().transform;
        let boxes = self.ink_boxes_of(&tf, only);
        let mut out = Vec::new();
        for (j, line) in self.items.iter().enumerate() {
            if !Self::guarded(line, prefix) {
                continue;
            }
            let mut segments = Vec::new();
            Self::item_segments(line, &tf, &mut segments);
            let half = tf.ref_px(line.pen.width) / 2.0;
            for (i, b) in &boxes {
                let Mark::Text(label) = &self.items[*i].mark else { continue };
                let tag = &self.items[*i].tag;
                // The outline its point lies on may touch a point's name, not strike it through.
                let stroke = if Self::own_outline(tag, label, line, &segments, &tf) {
                    if Self::named_by_tag(tag, line) {
                        continue;
                    }
                    *b
                } else {
                    b.inflate(half)
                };
                let inside: f64 = segments.iter().map(|(p, q)| stroke.length_inside(*p, *q)).sum();
                if inside > tf.ref_px(MIN_CROSSING) {
                    out.push((*i, j));
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// How long, in pixels, the outlines tagged `prefix…` that are not its own (see
    /// [`Drawing::labels_on_outlines`]) run inside the ink box of `label`, tagged `tag`: 0 for
    /// a spot clear of every other object's outline.
    #[must_use]
    pub fn outline_crossing(&self, tag: &str, label: &Text, prefix: &str) -> f64 {
        let tf = self.frame().transform;
        let ink = Self::ink_box(label, &tf);
        let mut crossed = 0.0;
        for line in self.items.iter().filter(|item| Self::guarded(item, prefix)) {
            let mut segments = Vec::new();
            Self::item_segments(line, &tf, &mut segments);
            if Self::own_outline(tag, label, line, &segments, &tf) {
                continue;
            }
            let stroke = ink.inflate(tf.ref_px(line.pen.width) / 2.0);
            crossed += segments.iter().map(|(p, q)| stroke.length_inside(*p, *q)).sum::<f64>();
        }
        crossed
    }

    /// Whether a label tagged `tag` names `outline` by its tag id (`object-name:2` names
    /// `object:2`).
    fn named_by_tag(tag: &str, outline: &Item) -> bool {
        tag_id(tag).is_some() && tag_id(tag) == tag_id(&outline.tag)
    }

    /// Whether `outline` (its pixel `segments`) is the outline of what a label tagged `tag`
    /// names: the same tag id, or an outline through the label's anchor.
    fn own_outline(
        tag: &str,
        label: &Text,
        outline: &Item,
        segments: &[(DVec2, DVec2)],
        tf: &Transform,
    ) -> bool {
        if Self::named_by_tag(tag, outline) {
            return true;
        }
        let at = tf.to_px(label.anchor);
        let near = tf.ref_px(OWN_OUTLINE) + tf.ref_px(outline.pen.width) / 2.0;
        segments.iter().any(|(p, q)| to_segment(at, *p, *q) <= near)
    }

    /// Whether a label drawing `events` names `line`: they draw a trace event in common.
    fn names(events: &[usize], line: &Item) -> bool {
        events.iter().any(|e| line.events.contains(e))
    }

    /// Whether `item` is a line labels keep off unless they name it: a stroke (not a label or a
    /// dot) whose tag starts with `guard`.
    fn guarded(item: &Item, guard: &str) -> bool {
        item.tag.starts_with(guard) && !matches!(item.mark, Mark::Text(_) | Mark::Dot { .. })
    }

    /// The pixel boxes of every text item.
    pub(super) fn text_boxes(&self, tf: &Transform) -> Vec<PxRect> {
        self.items
            .iter()
            .filter_map(|item| match &item.mark {
                Mark::Text(label) => Some(Self::place_text(label, tf).bbox),
                _ => None,
            })
            .collect()
    }

    /// Whether text item `index` lies as near another anchor of its kind as its own
    /// ([`Drawing::labels_nearer_another_anchor`]), on a guarded line it does not name
    /// ([`Drawing::labels_on_lines`]) or on an outline it does not name
    /// ([`Drawing::labels_on_outlines`]).
    fn misplaced(&self, index: usize, tf: &Transform) -> bool {
        let Mark::Text(label) = &self.items[index].mark else { return false };
        let only = Some(index);
        let on_outline = self
            .outline_guard
            .as_ref()
            .is_some_and(|prefix| !self.labels_on_outlines_of(prefix, only).is_empty());
        let on_line = self.guard.as_ref().is_some_and(|guard| !self.labels_on(guard, false, only).is_empty());
        let on_arrow = self.strict_guards.iter().any(|prefix| !self.labels_on(prefix, true, only).is_empty());
        on_outline || on_line || on_arrow || self.rival(&self.items[index].tag, label, index, tf).is_some()
    }

    /// Places again every label placed clear ([`TextOpts::avoid_overlap`]) that, now that every
    /// label is drawn, reads as another anchor's name or lies on a line or outline it does not
    /// name (`misplaced`, issue 32 item 1): a label is placed against the labels
    /// before it, so a later point's name could not be foreseen. It goes to the clearest spot
    /// against all the others among its rings, then among the far rings ([`FAR_STEPS`]) if
    /// still misplaced, with a leader when that spot is far or still another anchor's.
    pub fn settle_labels(&mut self) {
        let tf = self.placed_legend().transform;
        for (index, far) in self.placed_clear.clone() {
            let Mark::Text(label) = &self.items[index].mark else { continue };
            let tag = self.items[index].tag.clone();
            // Far from its point with nothing to join them: the reader cannot tell whose it is.
            let far_alone = !label.leader && label.offset.length() > LEADER_FROM;
            if !self.misplaced(index, &tf) && !far_alone {
                continue;
            }
            let old = self.items[index].clone();
            let mut item = self.items.remove(index);
            let before = std::mem::replace(&mut self.events, item.events.clone());
            if let Mark::Text(label) = &mut item.mark {
                let steps: &[f64] = if far { &FAR_STEPS } else { &NEAR_STEPS };
                self.place_clear(&tag, label, true, steps, &no_fit);
                self.items.insert(index, item);
                // Still misplaced within the near rings: out to the far ones, joined.
                if !far && self.misplaced(index, &tf) {
                    let mut item = self.items.remove(index);
                    if let Mark::Text(label) = &mut item.mark {
                        self.place_clear(&tag, label, true, &FAR_STEPS, &no_fit);
                    }
                    self.items.insert(index, item);
                }
                let Mark::Text(label) = &self.items[index].mark else { unreachable!() };
                if self.rival(&tag, label, index, &tf).is_some() {
                    if let Mark::Text(label) = &mut self.items[index].mark {
                        label.leader = true;
                    }
                }
                // A new spot on another label is worse than the old one: keep that, joined.
                if self.overlaps_another_label(index) {
                    self.items[index] = old;
                    if let Mark::Text(label) = &mut self.items[index].mark {
                        label.leader = true;
                    }
                }
            } else {
                self.items.insert(index, item);
            }
            self.events = before;
        }
    }

    /// Moves `label` to the clearest candidate spot `steps` gaps from its anchor (see
    /// [`Drawing::text`]), with a leader when `leader` and the spot is farther than
    /// [`LEADER_FROM`]. A spot costs [`COVER_COST`], [`LINE_COST`], [`OUTSIDE_COST`],
    /// [`LEADER_CROSSING_COST`] and [`RING_COST`] per what each counts; the cheapest wins.
    /// `fit` adds a caller's cost of a spot (see [`Drawing::text_at_cheapest`]). Returns its
    /// cost (0 for a spot clear of everything).
    pub(super) fn place_clear(
        &self,
        tag: &str,
        label: &mut Text,
        leader: bool,
        steps: &[f64],
        fit: &dyn Fn(&PxRect, Option<Leader>) -> f64,
    ) -> f64 {
        let PlacedLegend { transform: tf, plot, .. } = self.placed_legend();
        let segments = self.segments(&tf);
        // The anchors of the other labels of its kind, elsewhere: a spot as near one of them as
        // its own reads as that one's name.
        let own = tf.to_px(label.anchor);
        let kind = label_kind(tag);
        let rivals: Vec<DVec2> = self
            .items
            .iter()
            .filter_map(|item| match &item.mark {
                Mark::Text(other) if label_kind(&item.tag) == kind => Some(tf.to_px(other.anchor)),
                _ => None,
            })
            .filter(|at| at.distance(own) > tf.ref_px(SAME_ANCHOR))
            .collect();
        // The outlines of the objects it does not name, and those its point lies on (which
        // its ink may touch but not cross).
        let (mut foreign, mut under) = (Vec::new(), Vec::new());
        if let Some(prefix) = &self.outline_guard {
            for item in self.items.iter().filter(|item| Self::guarded(item, prefix)) {
                let mut outline = Vec::new();
                Self::item_segments(item, &tf, &mut outline);
                if !Self::own_outline(tag, label, item, &outline, &tf) {
                    foreign.push(outline);
                } else if !Self::named_by_tag(tag, item) {
                    under.push(outline);
                }
            }
        }
        // The guarded lines this label does not name (it draws none of their events).
        let mut guarded = Vec::new();
        if let Some(guard) = &self.guard {
            let unnamed = |item: &&Item| Self::guarded(item, guard) && !Self::names(&self.events, item);
            for item in self.items.iter().filter(unnamed) {
                Self::item_segments(item, &tf, &mut guarded);
            }
        }
        // The strictly guarded lines, arrows' heads too: even those a label names.
        for prefix in &self.strict_guards {
            for item in self.items.iter().filter(|item| Self::guarded(item, prefix)) {
                Self::item_segments(item, &tf, &mut guarded);
                Self::head_segments(item, &tf, &mut guarded);
            }
        }
        let mut boxes = self.text_boxes(&tf);
        // Other points' markers are data: a name must not hide one (its own point is the anchor).
        boxes.extend(self.items.iter().filter_map(|item| match item.mark {
            Mark::Dot { center, radius, .. } if center != label.anchor => {
                let (c, r) = (tf.to_px(center), tf.ref_px(radius));
                Some(PxRect { min: c - DVec2::splat(r), max: c + DVec2::splat(r) })
            }
            _ => None,
        }));
        let pad = tf.ref_px(4.0);
        // An inset's panel holds the labels anchored in it, and no other ([`Inset`]).
        let (mut home, mut elsewhere) = (None, Vec::new());
        for inset in &self.insets {
            if inset.in_panel(label.anchor) {
                home = Some(inset.panel_px(&tf));
            } else {
                elsewhere.push(inset.panel_px(&tf));
            }
        }
        let area = home.unwrap_or_else(|| {
            self.label_area.map_or(plot, |(lo, hi)| {
                let (a, b) = (tf.to_px(lo), tf.to_px(hi));
                PxRect { min: a.min(b), max: a.max(b) }
            })
        });
        let with_leader = |mut candidate: Text| {
            candidate.leader = leader && candidate.offset.length() > LEADER_FROM;
            candidate
        };
        let cost = |candidate: &Text| {
            let placed = Self::place_text(candidate, &tf);
            let b = placed.bbox.inflate(pad);
            let area_px = (b.width() * b.height()).max(1.0);
            let overlap: f64 = boxes.iter().map(|o| b.overlap(o)).sum::<f64>() / area_px;
            let crossings = segments.iter().filter(|(a, c)| b.meets_segment(*a, *c)).count();
            let guarded_crossings = guarded.iter().filter(|(a, c)| b.meets_segment(*a, *c)).count();
            let outside = if area.contains_rect(&b) && elsewhere.iter().all(|p| p.overlap(&b) <= 0.0) {
                0.0
            } else {
                1.0
            };
            let ink = Self::ink_box(candidate, &tf);
            let not_its_own = rivals.iter().any(|r| reads_as(&ink, own, placed.leader, *r, &tf));
            let outlines = foreign.iter().filter(|o| o.iter().any(|(a, c)| b.meets_segment(*a, *c))).count()
                + under
                    .iter()
                    .filter(|o| {
                        o.iter().map(|(a, c)| ink.length_inside(*a, *c)).sum::<f64>()
                            > tf.ref_px(MIN_CROSSING)
                    })
                    .count();
            // A box that holds the anchor meets every leader: only the others count.
            let leader_over_labels = placed.leader.map_or(0, |(a, c)| {
                boxes.iter().filter(|o| !o.contains_point(a) && o.meets_segment(a, c)).count()
            });
            COVER_COST * overlap
                + LINE_COST * crossings as f64
                + GUARDED_LINE_COST * guarded_crossings as f64
                + OUTSIDE_COST * outside
                + LEADER_CROSSING_COST * leader_over_labels as f64
                + if not_its_own { OWNER_COST } else { 0.0 }
                + OUTLINE_COST * outlines as f64
                + fit(&ink, placed.leader)
        };
        let requested = with_leader(label.clone());
        let mut best = (cost(&requested), requested.offset, requested.align);
        if best.0 <= 0.0 {
            *label = requested;
            return best.0;
        }
        let diag = std::f64::consts::FRAC_1_SQRT_2;
        let directions = [
            (DVec2::new(1.0, 0.0), Align::RIGHT_OF),
            (DVec2::new(0.0, 1.0), Align::ABOVE),
            (DVec2::new(-1.0, 0.0), Align::LEFT_OF),
            (DVec2::new(0.0, -1.0), Align::BELOW),
            (DVec2::new(diag, diag), Align { h: HAlign::Left, v: VAlign::Bottom }),
            (DVec2::new(-diag, diag), Align { h: HAlign::Right, v: VAlign::Bottom }),
            (DVec2::new(-diag, -diag), Align { h: HAlign::Right, v: VAlign::Top }),
            (DVec2::new(diag, -diag), Align { h: HAlign::Left, v: VAlign::Top }),
        ];
        for (step, &distance) in steps.iter().enumerate() {
            for (dir, align) in directions {
                let candidate =
                    with_leader(Text { offset: dir * RING_GAP * distance, align, ..requested.clone() });
                let c = cost(&candidate) + RING_COST * step as f64;
                if c < best.0 {
                    best = (c, candidate.offset, candidate.align);
                    if c <= 0.0 {
                        break;
                    }
                }
            }
            if best.0 <= 0.0 {
                break;
            }
        }
        *label = with_leader(Text { offset: best.1, align: best.2, ..requested });
        best.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::style::test_strokes::BLUE_LINE;
    use crate::View;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    /// A drawing of 1 world unit per 100 canvas pixels, with the horizontal ray y = 0 drawing
    /// event 1.
    fn with_ray() -> Drawing {
        let mut d = Drawing::slide();
        d.set_view(View::new(-9.6, 9.6, -5.4, 5.4).unwrap());
        d.with_events([1], |d| {
            d.segment("ray:primary", v(-5.0, 0.0), v(5.0, 0.0), BLUE_LINE);
        });
        d
    }

    #[test]
    fn a_label_on_a_ray_it_does_not_name_is_found_its_own_is_not() {
        let mut d = with_ray();
        // The ray's own name, centred on it; an object's name on it; a name well above it.
        d.with_events([1], |d| {
            d.text("label", v(-3.0, 0.0), "P", TextOpts::LABEL);
        });
        d.text("object-name", v(0.0, 0.0), "glass", TextOpts::NOTE);
        d.text("object-name", v(3.0, 1.0), "mirror", TextOpts::NOTE);
        // Another ray's label, drawing event 2, on it.
        d.with_events([2], |d| {
            d.text("label", v(2.0, 0.0), "R_1", TextOpts::LABEL);
        });
        assert_eq!(d.labels_on_lines("ray:"), vec![(2, 0), (4, 0)]);
        // Only lines tagged with the guard count.
        assert!(d.labels_on_lines("axis").is_empty());
    }

    #[test]
    fn a_stroke_that_grazes_a_corner_of_the_ink_is_no_crossing() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-9.6, 9.6, -5.4, 5.4).unwrap());
        d.text("object-name", v(0.0, 0.0), "glass", TextOpts::NOTE.align(Align::RIGHT_OF));
        let tf = d.frame().transform;
        let ink = d.ink_boxes(&tf)[0].1;
        let (half, crossing) = (tf.ref_px(BLUE_LINE.width) / 2.0, tf.ref_px(MIN_CROSSING));
        // A diagonal through the stroke-widened box's top-left corner, cutting it over less
        // than MIN_CROSSING, then one moved in along the box's diagonal, cutting it over more.
        let corner = ink.min - DVec2::splat(half);
        let graze = tf.to_world(corner + DVec2::new(crossing / 3.0, 0.0));
        let dir = v(1.0, 1.0);
        d.segment("ray:shadow", graze - dir, graze + dir, BLUE_LINE);
        assert!(d.labels_on_lines("ray:").is_empty());
        let through = tf.to_world(corner + DVec2::new(2.0 * crossing, 0.0));
        d.segment("ray:shadow", through - dir, through + dir, BLUE_LINE);
        assert_eq!(d.labels_on_lines("ray:"), vec![(0, 2)]);
    }
}
