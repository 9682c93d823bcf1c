//! Text options and label placement: how a label sits on its anchor ([`Align`]), how it is drawn
//! ([`TextOpts`]), and where [`Drawing::text`] puts it ([`Placement`]): as given, clear of
//! earlier labels, lines, leaders and other points' markers (with a leader when set far from its
//! anchor), or stacked down inside a box. [`Drawing::place_text`] says where a label lands in
//! pixels, for placement and for both back ends.

use glam::DVec2;

use super::drawing::Drawing;
use super::items::{Mark, Text};
use super::legend::PlacedLegend;
use super::style::{self, Rgba, TextSize};
use super::text::{self, Weight};
use super::view::{PxRect, Transform};

/// Horizontal alignment of text to its anchor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HAlign {
    /// The text starts at the anchor.
    Left,
    /// The text is centred on the anchor.
    Center,
    /// The text ends at the anchor.
    Right,
}

/// Vertical alignment of text to its anchor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VAlign {
    /// The anchor is at the top of the text box.
    Top,
    /// The anchor is halfway up the capitals.
    Middle,
    /// The anchor is on the baseline.
    Baseline,
    /// The anchor is at the bottom of the text box.
    Bottom,
}

/// Where text sits relative to its anchor point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Align {
    /// Horizontally.
    pub h: HAlign,
    /// Vertically.
    pub v: VAlign,
}

impl Align {
    /// Centred on the anchor.
    pub const CENTER: Self = Self { h: HAlign::Center, v: VAlign::Middle };
    /// To the right of the anchor, centred vertically.
    pub const RIGHT_OF: Self = Self { h: HAlign::Left, v: VAlign::Middle };
    /// To the left of the anchor, centred vertically.
    pub const LEFT_OF: Self = Self { h: HAlign::Right, v: VAlign::Middle };
    /// Above the anchor, centred horizontally.
    pub const ABOVE: Self = Self { h: HAlign::Center, v: VAlign::Bottom };
    /// Below the anchor, centred horizontally.
    pub const BELOW: Self = Self { h: HAlign::Center, v: VAlign::Top };
}

/// A label placed farther than this many reference pixels from its anchor gets a leader
/// ([`TextOpts::avoid_overlap_with_leader`]).
pub const LEADER_FROM: f64 = 30.0;

/// How a label is drawn: built from a named baseline such as [`TextOpts::LABEL`], then adjusted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextOpts {
    /// Offset from the anchor in reference pixels, x right and y up.
    pub offset: DVec2,
    /// Alignment to the (offset) anchor.
    pub align: Align,
    /// Size class.
    pub size: TextSize,
    /// Text colour.
    pub color: Rgba,
    /// Weight.
    pub weight: Weight,
    /// White halo behind the glyphs.
    pub halo: bool,
    /// Where the label may move when it would overlap an earlier one (see [`Drawing::text`]).
    pub placement: Placement,
    /// A leader from the anchor when [`Placement::Clear`] moved the label far ([`Text::leader`]).
    pub leader: bool,
    /// How far [`Placement::Clear`] may move the label: [`NEAR_STEPS`] or, for a plot with room
    /// to spare, [`FAR_STEPS`] ([`TextOpts::far`]).
    pub far: bool,
}

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
/// What each ring farther from the anchor costs: a label far from its anchor loses its meaning.
pub const RING_COST: f64 = 1.5;

/// The distances, in gaps of [`RING_GAP`], at which [`Placement::Clear`] tries the eight
/// directions around the anchor: near, for a crowded diagram, where a name far from its object
/// would be lost among the others.
pub const NEAR_STEPS: [f64; 4] = [1.0, 2.5, 4.5, 7.0];
/// [`NEAR_STEPS`] and two more rings, for a plot whose points crowd one band of a mostly empty
/// area: a name may go to the empty part, with its leader.
pub const FAR_STEPS: [f64; 6] = [1.0, 2.5, 4.5, 7.0, 10.0, 14.0];

/// How [`Drawing::text`] places a label against the labels already drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Placement {
    /// Exactly as requested.
    AsGiven,
    /// Nudged to a free spot near its anchor when it would overlap an earlier label or cross a
    /// line ([`TextOpts::avoid_overlap`]).
    Clear,
    /// Moved down a line at a time, keeping its alignment, until it overlaps no earlier label,
    /// its bottom never below the world height `floor` ([`TextOpts::stack_down`]): the names of
    /// nested boxes that share a corner, each kept inside its box.
    StackDown {
        /// The lowest world y the label may reach.
        floor: f64,
    },
}

impl TextOpts {
    /// A diagram label: label size, centred on its anchor, dark, with a halo.
    pub const LABEL: Self = Self {
        offset: DVec2::ZERO,
        align: Align::CENTER,
        size: TextSize::Label,
        color: style::TEXT,
        weight: Weight::Regular,
        halo: true,
        placement: Placement::AsGiven,
        leader: false,
        far: false,
    };
    /// A secondary note: small, centred, with a halo.
    pub const NOTE: Self = Self { size: TextSize::Small, ..Self::LABEL };

    /// With an offset of (`dx`, `dy`) reference pixels, y up.
    #[must_use]
    pub const fn offset(self, dx: f64, dy: f64) -> Self {
        Self { offset: DVec2::new(dx, dy), ..self }
    }
    /// With another alignment.
    #[must_use]
    pub const fn align(self, align: Align) -> Self {
        Self { align, ..self }
    }
    /// With another size class.
    #[must_use]
    pub const fn size(self, size: TextSize) -> Self {
        Self { size, ..self }
    }
    /// In another colour.
    #[must_use]
    pub const fn color(self, color: Rgba) -> Self {
        Self { color, ..self }
    }
    /// In bold.
    #[must_use]
    pub const fn bold(self) -> Self {
        Self { weight: Weight::Bold, ..self }
    }
    /// Without the halo.
    #[must_use]
    pub const fn no_halo(self) -> Self {
        Self { halo: false, ..self }
    }
    /// Placed clear of earlier labels and lines where a free spot exists.
    #[must_use]
    pub const fn avoid_overlap(self) -> Self {
        Self { placement: Placement::Clear, ..self }
    }
    /// Placed clear as [`TextOpts::avoid_overlap`], and joined to its anchor by a leader when it
    /// lands farther than [`LEADER_FROM`] from it: for names of points in a plot and of objects,
    /// not for the symbols of a construction, where one more line would read as geometry.
    #[must_use]
    pub const fn avoid_overlap_with_leader(self) -> Self {
        Self { placement: Placement::Clear, leader: true, ..self }
    }
    /// Free to go as far as [`FAR_STEPS`] from its anchor when placed clear.
    #[must_use]
    pub const fn far(self) -> Self {
        Self { far: true, ..self }
    }
    /// Stacked below the earlier labels it would overlap, no lower than world height `floor`
    /// ([`Placement::StackDown`]).
    #[must_use]
    pub const fn stack_down(self, floor: f64) -> Self {
        Self { placement: Placement::StackDown { floor }, ..self }
    }
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

/// How many lines down [`TextOpts::stack_down`] moves a label at most (then it takes the least
/// covered of those lines).
pub const STACK_LINES: usize = 6;

impl Drawing {
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
        let chain = |pts: &[DVec2], closed: bool, out: &mut Vec<(DVec2, DVec2)>| {
            let px: Vec<DVec2> = pts.iter().map(|p| tf.to_px(*p)).collect();
            out.extend(px.windows(2).map(|w| (w[0], w[1])));
            if closed && px.len() > 2 {
                out.push((px[px.len() - 1], px[0]));
            }
        };
        for item in &self.items {
            match &item.mark {
                Mark::Line { points } => chain(points, false, &mut out),
                Mark::Arrow { from, to, .. } => chain(&[*from, *to], false, &mut out),
                Mark::Polygon { points, .. } => chain(points, true, &mut out),
                Mark::Rect { min, max, .. } => {
                    let corners = [*min, DVec2::new(max.x, min.y), *max, DVec2::new(min.x, max.y)];
                    chain(&corners, true, &mut out);
                }
                Mark::Circle { center, radius, .. } => {
                    let ring: Vec<DVec2> = (0..48)
                        .map(|i| {
                            let a = std::f64::consts::TAU * f64::from(i) / 48.0;
                            *center + *radius * DVec2::new(a.cos(), a.sin())
                        })
                        .collect();
                    chain(&ring, true, &mut out);
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
        out
    }

    /// The pairs of text items, as indices into `items`, whose ink overlaps where both back ends
    /// draw them (under [`Drawing::frame`]'s transform): one label printed on top of another.
    /// Each label is its advance width across and its glyphs' ink up and down
    /// ([`text::TextLayout::ink`]), so lines of a column, whose font boxes touch, pass. Empty
    /// for a legible layout: the check that proves it, not a look at the picture.
    #[must_use]
    pub fn overlapping_labels(&self) -> Vec<(usize, usize)> {
        let tf = self.frame().transform;
        let boxes: Vec<(usize, PxRect)> = self
            .items
            .iter()
            .enumerate()
            .filter_map(|(k, item)| match &item.mark {
                Mark::Text(label) => {
                    let placed = Self::place_text(label, &tf);
                    let (above, below) = text::layout(&label.text, placed.size, label.weight).ink();
                    let (x0, x1) = (placed.bbox.min.x, placed.bbox.max.x);
                    let y = placed.origin.y;
                    Some((k, PxRect { min: DVec2::new(x0, y - above), max: DVec2::new(x1, y + below) }))
                }
                _ => None,
            })
            .collect();
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

    /// Moves `label` down, a line at a time, off the earlier labels and no lower than world
    /// height `floor` (see [`Drawing::text`]).
    pub(super) fn place_stacked(&self, label: &mut Text, floor: f64) {
        let tf = self.placed_legend().transform;
        let boxes = self.text_boxes(&tf);
        // One line down: the label's own height and a gap of 2 reference pixels, so that
        // labels on neighbouring lines never touch.
        let line = Self::place_text(label, &tf).bbox.height() / tf.ref_px(1.0) + 2.0;
        let start = label.offset;
        let lowest = tf.to_px(DVec2::new(0.0, floor)).y;
        // The first line clear of every earlier label, else the least covered one.
        let mut best = (f64::INFINITY, start);
        for k in 0..=STACK_LINES {
            label.offset = start - DVec2::new(0.0, line * k as f64);
            let b = Self::place_text(label, &tf).bbox;
            if k > 0 && b.max.y > lowest {
                break;
            }
            let covered: f64 = boxes.iter().map(|o| b.overlap(o)).sum();
            if covered < best.0 {
                best = (covered, label.offset);
            }
            if covered <= 0.0 {
                break;
            }
        }
        label.offset = best.1;
    }

    /// Moves `label` to the clearest candidate spot `steps` gaps from its anchor (see
    /// [`Drawing::text`]), with a leader when `leader` and the spot is farther than
    /// [`LEADER_FROM`]. A spot costs [`COVER_COST`], [`LINE_COST`], [`OUTSIDE_COST`],
    /// [`LEADER_CROSSING_COST`] and [`RING_COST`] per what each counts; the cheapest wins.
    pub(super) fn place_clear(&self, label: &mut Text, leader: bool, steps: &[f64]) {
        let PlacedLegend { transform: tf, plot, .. } = self.placed_legend();
        let segments = self.segments(&tf);
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
        let area = self.label_area.map_or(plot, |(lo, hi)| {
            let (a, b) = (tf.to_px(lo), tf.to_px(hi));
            PxRect { min: a.min(b), max: a.max(b) }
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
            let outside = if area.contains_rect(&b) { 0.0 } else { 1.0 };
            // A box that holds the anchor meets every leader: only the others count.
            let leader_over_labels = placed.leader.map_or(0, |(a, c)| {
                boxes.iter().filter(|o| !o.contains_point(a) && o.meets_segment(a, c)).count()
            });
            COVER_COST * overlap
                + LINE_COST * crossings as f64
                + OUTSIDE_COST * outside
                + LEADER_CROSSING_COST * leader_over_labels as f64
        };
        let requested = with_leader(label.clone());
        let mut best = (cost(&requested), requested.offset, requested.align);
        if best.0 <= 0.0 {
            *label = requested;
            return;
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
    }
}
