//! The back-end-free display list: what a figure shows, in world coordinates (f64), before any
//! back end turns it into pixels (`skia`) or SVG (`svg`).
//!
//! A [`Drawing`] maps a world rectangle ([`View`], y up) onto its canvas with one uniform scale, so
//! circles stay round. Geometry (points, circle radii) is in world units; everything a reader sees
//! at a fixed size — stroke widths, dashes, arrow heads, dot radii, text sizes and text offsets —
//! is in *reference pixels* (pixels of the 1920 × 1080 slide, see [`style`]), scaled
//! by [`Drawing::px_scale`] for other canvas sizes.
//!
//! The canvas is laid out once, by [`Drawing::frame`], for both back ends: a title band at the
//! top, a caption band at the bottom, the plot area between them, and the legend box in a clear
//! corner of the plot area, in a column to its right or in a band under it ([`LegendPlace`]). Set
//! the title, caption and legend (and [`LegendPlace::Outside`] or [`LegendPlace::Below`] if the
//! legend will not fit inside), then the view,
//! then add items and labels: a label placed with [`TextOpts::avoid_overlap`] is placed against
//! the transform in force when it is added.

use glam::DVec2;

use super::style::{self, Rgba, TextSize};
use super::text::{self, Weight};

/// A dash pattern, in reference pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dash {
    /// Length of each drawn stretch.
    pub on: f64,
    /// Length of each gap.
    pub off: f64,
}

/// How an item is stroked (and, for text, coloured).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Style {
    /// The stroke colour (the text colour for text, the fill for a dot without fill).
    pub color: Rgba,
    /// The stroke width in reference pixels; 0 draws no stroke.
    pub width: f64,
    /// The dash pattern, or `None` for a solid line.
    pub dash: Option<Dash>,
}

impl Style {
    /// No stroke at all: for shapes drawn only by their fill.
    pub const NONE: Self = Self { color: Rgba { r: 0, g: 0, b: 0, a: 0 }, width: 0.0, dash: None };

    /// A solid stroke.
    #[must_use]
    pub const fn solid(color: Rgba, width: f64) -> Self {
        Self { color, width, dash: None }
    }

    /// The same stroke, dashed.
    #[must_use]
    pub const fn dashed(self, dash: Dash) -> Self {
        Self { dash: Some(dash), ..self }
    }

    /// The same stroke at another width.
    #[must_use]
    pub const fn with_width(self, width: f64) -> Self {
        Self { width, ..self }
    }

    /// The same stroke in another colour.
    #[must_use]
    pub const fn with_color(self, color: Rgba) -> Self {
        Self { color, ..self }
    }

    /// Whether this style draws a visible stroke.
    #[must_use]
    pub fn strokes(&self) -> bool {
        self.width > 0.0 && self.color.a > 0
    }
}

/// A rectangle of the world, `[xmin, xmax] × [ymin, ymax]`, y up.
///
/// Guarantees: all four bounds are finite, `xmin < xmax` and `ymin < ymax`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    xmin: f64,
    xmax: f64,
    ymin: f64,
    ymax: f64,
}

impl View {
    /// The rectangle `[xmin, xmax] × [ymin, ymax]`, or `None` unless the bounds are finite and
    /// each minimum is below its maximum.
    #[must_use]
    pub fn new(xmin: f64, xmax: f64, ymin: f64, ymax: f64) -> Option<Self> {
        let finite = [xmin, xmax, ymin, ymax].iter().all(|v| v.is_finite());
        (finite && xmin < xmax && ymin < ymax).then_some(Self { xmin, xmax, ymin, ymax })
    }

    /// The smallest rectangle of aspect `aspect` (width / height) that holds every finite point
    /// of `points` with a margin of `margin` times the larger extent on each side, centred on
    /// the points. A single point (or a flat set) gets an extent of 1 along its flat axes.
    /// `None` if no point is finite, or if `margin` or `aspect` is not finite and positive
    /// (`margin` may be 0).
    #[must_use]
    pub fn fit(points: &[DVec2], margin: f64, aspect: f64) -> Option<Self> {
        if !(margin.is_finite() && margin >= 0.0 && aspect.is_finite() && aspect > 0.0) {
            return None;
        }
        let mut finite = points.iter().filter(|p| p.is_finite());
        let first = *finite.next()?;
        let (lo, hi) = finite.fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let center = (lo + hi) / 2.0;
        let mut extent = hi - lo;
        let largest = extent.max_element();
        let fallback = if largest > 0.0 { largest } else { 1.0 };
        if extent.x <= 0.0 {
            extent.x = fallback;
        }
        if extent.y <= 0.0 {
            extent.y = fallback;
        }
        let pad = margin * extent.max_element();
        let mut w = extent.x + 2.0 * pad;
        let mut h = extent.y + 2.0 * pad;
        if w / h < aspect {
            w = h * aspect;
        } else {
            h = w / aspect;
        }
        Self::new(center.x - w / 2.0, center.x + w / 2.0, center.y - h / 2.0, center.y + h / 2.0)
    }

    /// The left edge.
    #[must_use]
    pub fn xmin(&self) -> f64 {
        self.xmin
    }
    /// The right edge.
    #[must_use]
    pub fn xmax(&self) -> f64 {
        self.xmax
    }
    /// The bottom edge.
    #[must_use]
    pub fn ymin(&self) -> f64 {
        self.ymin
    }
    /// The top edge.
    #[must_use]
    pub fn ymax(&self) -> f64 {
        self.ymax
    }
    /// The width, `xmax − xmin` (> 0).
    #[must_use]
    pub fn width(&self) -> f64 {
        self.xmax - self.xmin
    }
    /// The height, `ymax − ymin` (> 0).
    #[must_use]
    pub fn height(&self) -> f64 {
        self.ymax - self.ymin
    }
    /// The centre.
    #[must_use]
    pub fn center(&self) -> DVec2 {
        DVec2::new(self.xmin + self.xmax, self.ymin + self.ymax) / 2.0
    }
}

/// A rectangle in canvas pixels, y down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PxRect {
    /// Top-left corner.
    pub min: DVec2,
    /// Bottom-right corner.
    pub max: DVec2,
}

impl PxRect {
    /// The width.
    #[must_use]
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }
    /// The height.
    #[must_use]
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }
    /// The rectangle grown by `d` on every side.
    #[must_use]
    pub fn inflate(&self, d: f64) -> Self {
        Self { min: self.min - DVec2::splat(d), max: self.max + DVec2::splat(d) }
    }
    /// The area shared with `other` (0 when they are apart).
    #[must_use]
    pub fn overlap(&self, other: &Self) -> f64 {
        let lo = self.min.max(other.min);
        let hi = self.max.min(other.max);
        let d = (hi - lo).max(DVec2::ZERO);
        d.x * d.y
    }
    /// Whether `p` lies inside (edges included).
    #[must_use]
    pub fn contains_point(&self, p: DVec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
    /// Whether `other` lies wholly inside.
    #[must_use]
    pub fn contains_rect(&self, other: &Self) -> bool {
        other.min.cmpge(self.min).all() && other.max.cmple(self.max).all()
    }
    /// Whether the segment `a`–`b` meets the rectangle (Liang–Barsky clipping).
    #[must_use]
    pub fn meets_segment(&self, a: DVec2, b: DVec2) -> bool {
        let d = b - a;
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-d.x, a.x - self.min.x),
            (d.x, self.max.x - a.x),
            (-d.y, a.y - self.min.y),
            (d.y, self.max.y - a.y),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        t0 <= t1
    }
}

/// The world → pixel map of a drawing: `px = (tx + s·x, ty − s·y)`, one uniform scale `s` and a
/// y flip. Back ends narrow its f64 results to f32 at the last moment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    scale: f64,
    tx: f64,
    ty: f64,
    px_scale: f64,
}

impl Transform {
    /// The pixel position of world point `p`.
    #[must_use]
    pub fn to_px(&self, p: DVec2) -> DVec2 {
        DVec2::new(self.tx + self.scale * p.x, self.ty - self.scale * p.y)
    }
    /// The world point at pixel `q` (the inverse of [`Transform::to_px`]).
    #[must_use]
    pub fn to_world(&self, q: DVec2) -> DVec2 {
        DVec2::new((q.x - self.tx) / self.scale, (self.ty - q.y) / self.scale)
    }
    /// A world length in pixels.
    #[must_use]
    pub fn len_px(&self, world: f64) -> f64 {
        world * self.scale
    }
    /// A length in reference pixels, in this canvas's pixels.
    #[must_use]
    pub fn ref_px(&self, reference: f64) -> f64 {
        reference * self.px_scale
    }
    /// A reference-pixel offset with y up (as items give them) → a canvas pixel offset, y down.
    #[must_use]
    pub fn offset_px(&self, offset: DVec2) -> DVec2 {
        DVec2::new(offset.x, -offset.y) * self.px_scale
    }
}

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

/// A text item: markup (see [`text`]) placed at a world anchor.
#[derive(Clone, Debug, PartialEq)]
pub struct Text {
    /// The label, in the markup of [`text`] (`θ_i`, `t_{ex}`).
    pub text: String,
    /// The world point the label belongs to.
    pub anchor: DVec2,
    /// An offset from the anchor in reference pixels, x right and y up.
    pub offset: DVec2,
    /// How the text box sits on the offset anchor.
    pub align: Align,
    /// The size class.
    pub size: TextSize,
    /// The weight.
    pub weight: Weight,
    /// Whether a thin line joins the anchor to the box: set when a label placed with
    /// [`TextOpts::avoid_overlap_with_leader`] lands farther than [`LEADER_FROM`] from its
    /// anchor, so that it still points at what it names.
    pub leader: bool,
    /// Whether a white halo outlines the glyphs so the text reads over lines.
    pub halo: bool,
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

/// The distances, in gaps of 14 reference pixels, at which [`Placement::Clear`] tries the eight
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

/// The geometry of one display-list item.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// An open polyline through world points.
    Line {
        /// The vertices, in order.
        points: Vec<DVec2>,
    },
    /// A segment with a filled arrow head at `to`.
    Arrow {
        /// Tail, in world coordinates.
        from: DVec2,
        /// Tip, in world coordinates.
        to: DVec2,
        /// Head length, tip to base, in reference pixels (shortened on short arrows).
        head: f64,
    },
    /// A circle of world radius.
    Circle {
        /// Centre, world.
        center: DVec2,
        /// Radius, world units.
        radius: f64,
        /// Interior fill, if any.
        fill: Option<Rgba>,
    },
    /// A round marker of fixed pixel size (hit points, lights, sample points).
    Dot {
        /// Centre, world.
        center: DVec2,
        /// Radius in reference pixels.
        radius: f64,
        /// Interior fill.
        fill: Rgba,
    },
    /// A closed polygon.
    Polygon {
        /// The vertices, in order (the last joins the first).
        points: Vec<DVec2>,
        /// Interior fill, if any (its alpha is the fill opacity).
        fill: Option<Rgba>,
    },
    /// An axis-aligned rectangle of the world.
    Rect {
        /// The corner with the smaller coordinates.
        min: DVec2,
        /// The corner with the larger coordinates.
        max: DVec2,
        /// Interior fill, if any.
        fill: Option<Rgba>,
    },
    /// A label.
    Text(Text),
}

/// One entry of the display list.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// A short tag naming what the item shows (`ray:primary`, `object:2`, `label`); the SVG groups
    /// items by it and tests count by it.
    pub tag: String,
    /// Stroke (and text colour).
    pub style: Style,
    /// Geometry.
    pub shape: Shape,
    /// The indices of the trace events it draws (into the main trace's events, which are the
    /// trace document's): a ray its spawning event and its hit, a test its test… Empty for what
    /// no event drew (objects, lights, axes). The SVG writes them as `data-events`.
    pub events: Vec<usize>,
}

/// What a legend entry's sample looks like.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sample {
    /// A short line in the entry's style.
    Line,
    /// A short arrow in the entry's style.
    Arrow,
    /// A dot of this fill, outlined in the entry's style.
    Dot(Rgba),
    /// A filled square of this colour, outlined in the entry's style.
    Swatch(Rgba),
}

/// One row of the legend.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendEntry {
    /// The text (markup).
    pub label: String,
    /// The sample's stroke.
    pub style: Style,
    /// The sample's kind.
    pub sample: Sample,
}

/// A corner of the plot area, for the legend.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Corner {
    /// Top right.
    TopRight,
    /// Top left.
    TopLeft,
    /// Bottom right.
    BottomRight,
    /// Bottom left.
    BottomLeft,
}

impl Corner {
    /// The corners in the order the automatic placement prefers them.
    pub const ALL: [Self; 4] = [Self::TopRight, Self::TopLeft, Self::BottomRight, Self::BottomLeft];
}

/// Where the legend box goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LegendPlace {
    /// The first corner of the plot area (in [`Corner::ALL`] order) that no line crosses and no
    /// label overlaps; if none is clear, [`LegendPlace::Outside`]. The view is fitted to the whole
    /// plot area first, so going outside only shrinks the picture, uniformly.
    Auto,
    /// In this corner of the plot area, whatever it covers.
    Inside(Corner),
    /// In a column to the right of the plot area, which is narrowed to make room.
    Outside,
    /// In a band under the plot area (above the caption), at its right end; the plot area is
    /// shortened to make room. A wide picture (two panels side by side) keeps more of its size
    /// this way than beside a column.
    Below,
}

/// A figure: the display list, the world rectangle it shows, its canvas size, and its legend,
/// title and caption.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    width: u32,
    height: u32,
    /// The world rectangle shown (uniformly scaled and centred in the plot area).
    pub view: View,
    /// The display list, drawn in order (later items on top).
    pub items: Vec<Item>,
    /// The legend's rows; no box is drawn when empty.
    pub legend: Vec<LegendEntry>,
    /// Where the legend box goes.
    pub legend_place: LegendPlace,
    /// The caption under the plot (markup), wrapped to the canvas width.
    pub caption: Option<String>,
    /// The title above the plot (markup), in bold.
    pub title: Option<String>,
    /// Where labels placed clear ([`TextOpts::avoid_overlap`]) may go: a world rectangle, or the
    /// whole plot area when `None` ([`Drawing::keep_labels_within`]).
    pub label_area: Option<(DVec2, DVec2)>,
    /// The events of the items added now ([`Drawing::with_events`]).
    events: Vec<usize>,
}

/// A text line placed in canvas pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedLine {
    /// The markup.
    pub text: String,
    /// The start of the baseline, in pixels.
    pub origin: DVec2,
    /// Font size in pixels.
    pub size: f64,
}

/// One legend row laid out in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendRow {
    /// Where the sample starts (left end, vertical middle of the row).
    pub sample_from: DVec2,
    /// Where the sample ends.
    pub sample_to: DVec2,
    /// The row's text.
    pub label: PlacedLine,
}

/// The legend box laid out in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendBox {
    /// The box.
    pub rect: PxRect,
    /// Its rows, top to bottom, in the order of [`Drawing::legend`].
    pub rows: Vec<LegendRow>,
}

/// The canvas layout shared by the back ends (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The world → pixel map.
    pub transform: Transform,
    /// The plot area in pixels.
    pub plot: PxRect,
    /// The title line, centred at the top.
    pub title: Option<PlacedLine>,
    /// The caption lines, centred at the bottom.
    pub caption: Vec<PlacedLine>,
    /// The legend box, if there are legend entries.
    pub legend: Option<LegendBox>,
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

/// An arrow laid out in pixels: the shaft to draw and the head to fill.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArrowPx {
    /// The shaft's start (the arrow's tail).
    pub shaft_from: DVec2,
    /// The shaft's end, a little inside the head so no gap shows.
    pub shaft_to: DVec2,
    /// The head as a closed quadrilateral: tip, one barb, the notch, the other barb.
    pub head: [DVec2; 4],
}

impl ArrowPx {
    /// The arrow from pixel `from` to pixel `to` with a head `head` pixels long (at most 0.6 of
    /// the arrow, so a short arrow keeps a shaft), or `None` for a zero-length arrow.
    #[must_use]
    pub fn new(from: DVec2, to: DVec2, head: f64) -> Option<Self> {
        let along = to - from;
        let len = along.length();
        if len.is_nan() || len <= f64::EPSILON {
            return None;
        }
        let dir = along / len;
        let head = head.min(0.6 * len);
        let base = to - dir * head;
        let side = dir.perp() * head * 0.42;
        Some(Self {
            shaft_from: from,
            shaft_to: to - dir * head * 0.7,
            head: [to, base + side, to - dir * head * 0.85, base - side],
        })
    }
}

/// Line spacing of stacked text lines, in em.
const LINE_SPACING: f64 = 1.3;

/// How many lines down [`TextOpts::stack_down`] moves a label at most (then it takes the least
/// covered of those lines).
pub const STACK_LINES: usize = 6;

impl Drawing {
    /// An empty drawing for a `width` × `height` pixel canvas showing the world square
    /// [−1, 1]², or `None` if either size is 0.
    #[must_use]
    pub fn new(width: u32, height: u32) -> Option<Self> {
        let view = View::new(-1.0, 1.0, -1.0, 1.0)?;
        (width > 0 && height > 0).then_some(Self {
            width,
            height,
            view,
            items: Vec::new(),
            legend: Vec::new(),
            legend_place: LegendPlace::Auto,
            caption: None,
            title: None,
            label_area: None,
            events: Vec::new(),
        })
    }

    /// An empty drawing on the reference slide canvas, 1920 × 1080.
    #[must_use]
    pub fn slide() -> Self {
        Self {
            width: style::REFERENCE_WIDTH,
            height: style::REFERENCE_HEIGHT,
            view: View { xmin: -1.0, xmax: 1.0, ymin: -1.0, ymax: 1.0 },
            items: Vec::new(),
            legend: Vec::new(),
            legend_place: LegendPlace::Auto,
            caption: None,
            title: None,
            label_area: None,
            events: Vec::new(),
        }
    }

    /// Canvas width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Canvas height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Reference pixels → canvas pixels (see [`style::px_scale`]).
    #[must_use]
    pub fn px_scale(&self) -> f64 {
        style::px_scale(self.width, self.height)
    }

    /// Sets the title (markup).
    pub fn set_title(&mut self, title: &str) -> &mut Self {
        self.title = Some(title.to_owned());
        self
    }

    /// Sets the caption (markup).
    pub fn set_caption(&mut self, caption: &str) -> &mut Self {
        self.caption = Some(caption.to_owned());
        self
    }

    /// Keeps the labels placed from now on with [`TextOpts::avoid_overlap`] inside the world
    /// rectangle spanned by `a` and `b` where they can be (a plot's data area, so that no name
    /// lands among the tick names).
    pub fn keep_labels_within(&mut self, a: DVec2, b: DVec2) -> &mut Self {
        self.label_area = Some((a.min(b), a.max(b)));
        self
    }

    /// Sets the world rectangle shown.
    pub fn set_view(&mut self, view: View) -> &mut Self {
        self.view = view;
        self
    }

    /// Shows every finite point of `points` with a margin of `margin` times their larger extent,
    /// at the plot area's aspect ratio. Leaves the view unchanged when no point is finite.
    pub fn fit_view(&mut self, points: &[DVec2], margin: f64) -> &mut Self {
        let plot = self.plot_area();
        if let Some(view) = View::fit(points, margin, plot.width() / plot.height()) {
            self.view = view;
        }
        self
    }

    /// The aspect ratio (width / height) of the plot area, for [`View::fit`].
    #[must_use]
    pub fn plot_aspect(&self) -> f64 {
        let plot = self.plot_area();
        plot.width() / plot.height()
    }

    /// Adds an item (drawing the events of the enclosing [`Drawing::with_events`], if any).
    pub fn push(&mut self, tag: &str, style: Style, shape: Shape) -> &mut Self {
        self.items.push(Item { tag: tag.to_owned(), style, shape, events: self.events.clone() });
        self
    }

    /// Runs `draw`, every item it adds drawing `events` (indices into the main trace's events,
    /// sorted and deduplicated here); the events in force before are restored after.
    pub fn with_events<R>(
        &mut self,
        events: impl IntoIterator<Item = usize>,
        draw: impl FnOnce(&mut Self) -> R,
    ) -> R {
        let mut now: Vec<usize> = events.into_iter().collect();
        now.sort_unstable();
        now.dedup();
        let before = std::mem::replace(&mut self.events, now);
        let out = draw(self);
        self.events = before;
        out
    }

    /// Adds a polyline.
    pub fn line(&mut self, tag: &str, points: impl IntoIterator<Item = DVec2>, style: Style) -> &mut Self {
        let points = points.into_iter().collect();
        self.push(tag, style, Shape::Line { points })
    }

    /// Adds the segment `a`–`b`.
    pub fn segment(&mut self, tag: &str, a: DVec2, b: DVec2, style: Style) -> &mut Self {
        self.push(tag, style, Shape::Line { points: vec![a, b] })
    }

    /// Adds an arrow from `from` to `to`, its head sized for the stroke
    /// (`max(ARROW_HEAD, 4.5 × width)` reference pixels).
    pub fn arrow(&mut self, tag: &str, from: DVec2, to: DVec2, style: Style) -> &mut Self {
        let head = style::ARROW_HEAD.max(4.5 * style.width);
        self.push(tag, style, Shape::Arrow { from, to, head })
    }

    /// Adds a circle of world radius `radius`, stroked with `style` and filled with `fill`.
    pub fn circle(
        &mut self,
        tag: &str,
        center: DVec2,
        radius: f64,
        style: Style,
        fill: Option<Rgba>,
    ) -> &mut Self {
        self.push(tag, style, Shape::Circle { center, radius, fill })
    }

    /// Adds a dot of the standard radius ([`style::DOT_RADIUS`]) filled with `fill`, no outline.
    pub fn dot(&mut self, tag: &str, center: DVec2, fill: Rgba) -> &mut Self {
        self.marker(tag, center, style::DOT_RADIUS, fill, Style::NONE)
    }

    /// Adds a dot of `radius` reference pixels, filled with `fill` and outlined with `outline`.
    pub fn marker(&mut self, tag: &str, center: DVec2, radius: f64, fill: Rgba, outline: Style) -> &mut Self {
        self.push(tag, outline, Shape::Dot { center, radius, fill })
    }

    /// Adds a closed polygon.
    pub fn polygon(
        &mut self,
        tag: &str,
        points: impl IntoIterator<Item = DVec2>,
        style: Style,
        fill: Option<Rgba>,
    ) -> &mut Self {
        let points = points.into_iter().collect();
        self.push(tag, style, Shape::Polygon { points, fill })
    }

    /// Adds the world rectangle spanned by corners `a` and `b` (in any order).
    pub fn rect(&mut self, tag: &str, a: DVec2, b: DVec2, style: Style, fill: Option<Rgba>) -> &mut Self {
        self.push(tag, style, Shape::Rect { min: a.min(b), max: a.max(b), fill })
    }

    /// Adds a label at `anchor`. With [`TextOpts::avoid_overlap`], the label keeps the requested
    /// placement if its box is clear of earlier labels and lines and inside the plot area;
    /// otherwise it takes the first clear spot among candidates around the anchor (eight
    /// directions, at growing distances), or the least bad one if none is clear. With
    /// [`TextOpts::stack_down`] it moves down by its own height until no earlier label overlaps
    /// it (at most [`STACK_LINES`] lines, never below its floor; if none is clear, to the least
    /// covered).
    pub fn text(&mut self, tag: &str, anchor: DVec2, markup: &str, opts: TextOpts) -> &mut Self {
        let mut label = Text {
            text: markup.to_owned(),
            anchor,
            offset: opts.offset,
            align: opts.align,
            size: opts.size,
            weight: opts.weight,
            leader: false,
            halo: opts.halo,
        };
        match opts.placement {
            Placement::AsGiven => {}
            Placement::Clear => {
                let steps: &[f64] = if opts.far { &FAR_STEPS } else { &NEAR_STEPS };
                self.place_clear(&mut label, opts.leader, steps);
            }
            Placement::StackDown { floor } => self.place_stacked(&mut label, floor),
        }
        let style = Style { color: opts.color, width: 0.0, dash: None };
        self.push(tag, style, Shape::Text(label))
    }

    /// Adds a legend row.
    pub fn legend_entry(&mut self, label: &str, style: Style, sample: Sample) -> &mut Self {
        self.legend.push(LegendEntry { label: label.to_owned(), style, sample });
        self
    }

    /// The items whose tag is `tag`.
    pub fn tagged<'a>(&'a self, tag: &'a str) -> impl Iterator<Item = &'a Item> + 'a {
        self.items.iter().filter(move |item| item.tag == tag)
    }

    /// The plot area before the legend is placed: the canvas less its margin, the title and
    /// caption bands and, for [`LegendPlace::Outside`], the legend column (for
    /// [`LegendPlace::Below`], the legend band). [`View::fit`] and
    /// [`Drawing::fit_view`] fit to this area.
    fn plot_area(&self) -> PxRect {
        match (self.legend_place, self.legend_size()) {
            (LegendPlace::Outside, Some(size)) => self.plot_area_beside(size.x),
            (LegendPlace::Below, Some(size)) => self.plot_area_above(size.y),
            _ => self.plot_area_beside(0.0),
        }
    }

    /// The plot area with a legend band `band` pixels tall under it, and a margin between them.
    fn plot_area_above(&self, band: f64) -> PxRect {
        let mut plot = self.plot_area_beside(0.0);
        plot.max.y = (plot.max.y - band - style::MARGIN * self.px_scale()).max(plot.min.y + 1.0);
        plot
    }

    /// The world → pixel scale of the picture: how large the figure draws its view.
    #[must_use]
    pub fn picture_scale(&self) -> f64 {
        self.placed_legend().0.scale
    }

    /// The plot area with a legend column `column` pixels wide (0 for none) on the right.
    fn plot_area_beside(&self, column: f64) -> PxRect {
        let k = self.px_scale();
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let margin = style::MARGIN * k;
        let mut top = margin;
        let mut bottom = h - margin;
        if self.title.is_some() {
            top += TextSize::Title.px() * k * LINE_SPACING;
        }
        let lines = self.caption_lines().len();
        if lines > 0 {
            bottom -= TextSize::Body.px() * k * LINE_SPACING * lines as f64 + margin * 0.5;
        }
        // A canvas too small for its bands still gets a plot area of one pixel.
        let bottom = bottom.max(top + 1.0);
        let left = margin.min(w / 2.0);
        let right = if column > 0.0 { w - margin - column - margin } else { w - margin };
        let right = right.max(left + 1.0);
        PxRect { min: DVec2::new(left, top), max: DVec2::new(right, bottom) }
    }

    /// The caption, wrapped to the canvas width.
    fn caption_lines(&self) -> Vec<String> {
        let Some(caption) = &self.caption else {
            return Vec::new();
        };
        let k = self.px_scale();
        let max_width = f64::from(self.width) - 2.0 * style::MARGIN * k;
        text::wrap(caption, TextSize::Body.px() * k, Weight::Regular, max_width)
    }

    /// The world → pixel map: the view scaled uniformly to fit the plot area, centred (the plot
    /// area after the legend is placed, as in [`Drawing::frame`]).
    #[must_use]
    pub fn transform(&self) -> Transform {
        self.placed_legend().0
    }

    /// The view scaled uniformly to fit `plot`, centred.
    fn transform_in(&self, plot: &PxRect) -> Transform {
        let scale = (plot.width() / self.view.width()).min(plot.height() / self.view.height());
        let c = self.view.center();
        let mid = (plot.min + plot.max) / 2.0;
        Transform { scale, tx: mid.x - scale * c.x, ty: mid.y + scale * c.y, px_scale: self.px_scale() }
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
    fn segments(&self, tf: &Transform) -> Vec<(DVec2, DVec2)> {
        let mut out = Vec::new();
        let chain = |pts: &[DVec2], closed: bool, out: &mut Vec<(DVec2, DVec2)>| {
            let px: Vec<DVec2> = pts.iter().map(|p| tf.to_px(*p)).collect();
            out.extend(px.windows(2).map(|w| (w[0], w[1])));
            if closed && px.len() > 2 {
                out.push((px[px.len() - 1], px[0]));
            }
        };
        for item in &self.items {
            match &item.shape {
                Shape::Line { points } => chain(points, false, &mut out),
                Shape::Arrow { from, to, .. } => chain(&[*from, *to], false, &mut out),
                Shape::Polygon { points, .. } => chain(points, true, &mut out),
                Shape::Rect { min, max, .. } => {
                    let corners = [*min, DVec2::new(max.x, min.y), *max, DVec2::new(min.x, max.y)];
                    chain(&corners, true, &mut out);
                }
                Shape::Circle { center, radius, .. } => {
                    let ring: Vec<DVec2> = (0..48)
                        .map(|i| {
                            let a = std::f64::consts::TAU * f64::from(i) / 48.0;
                            *center + *radius * DVec2::new(a.cos(), a.sin())
                        })
                        .collect();
                    chain(&ring, true, &mut out);
                }
                // A leader is a line like any other: a later label keeps off it.
                Shape::Text(label) => out.extend(Self::place_text(label, tf).leader),
                Shape::Dot { center, radius, .. } => {
                    let c = tf.to_px(*center);
                    let r = tf.ref_px(*radius);
                    out.push((c - DVec2::splat(r), c + DVec2::splat(r)));
                    out.push((c + DVec2::new(-r, r), c + DVec2::new(r, -r)));
                }
            }
        }
        out
    }

    /// The pixel boxes of every text item.
    fn text_boxes(&self, tf: &Transform) -> Vec<PxRect> {
        self.items
            .iter()
            .filter_map(|item| match &item.shape {
                Shape::Text(label) => Some(Self::place_text(label, tf).bbox),
                _ => None,
            })
            .collect()
    }

    /// Moves `label` down, a line at a time, off the earlier labels and no lower than world
    /// height `floor` (see [`Drawing::text`]).
    fn place_stacked(&self, label: &mut Text, floor: f64) {
        let (tf, _, _) = self.placed_legend();
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
    /// [`LEADER_FROM`]. A spot costs the share of it that covers earlier labels and other points'
    /// markers (×100), one per line it crosses, 100 outside the label area, 20 per label its
    /// leader would cross, and 1.5 per ring away from the anchor.
    fn place_clear(&self, label: &mut Text, leader: bool, steps: &[f64]) {
        let (tf, plot, _) = self.placed_legend();
        let segments = self.segments(&tf);
        let mut boxes = self.text_boxes(&tf);
        // Other points' markers are data: a name must not hide one (its own point is the anchor).
        boxes.extend(self.items.iter().filter_map(|item| match item.shape {
            Shape::Dot { center, radius, .. } if center != label.anchor => {
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
            100.0 * overlap + crossings as f64 + 100.0 * outside + 20.0 * leader_over_labels as f64
        };
        let requested = with_leader(label.clone());
        let mut best = (cost(&requested), requested.offset, requested.align);
        if best.0 <= 0.0 {
            *label = requested;
            return;
        }
        let gap = 14.0;
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
        // A label far from its anchor loses its meaning: each step away costs as much as crossing
        // one and a half lines (the halo keeps a label readable over a line).
        for (step, &distance) in steps.iter().enumerate() {
            for (dir, align) in directions {
                let candidate =
                    with_leader(Text { offset: dir * gap * distance, align, ..requested.clone() });
                let c = cost(&candidate) + 1.5 * step as f64;
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

    /// Lays out the canvas for the back ends: transform, plot area, title, caption and legend.
    #[must_use]
    pub fn frame(&self) -> Frame {
        let (tf, plot, legend_rect) = self.placed_legend();
        let k = self.px_scale();
        let w = f64::from(self.width);
        let h = f64::from(self.height);
        let margin = style::MARGIN * k;

        let title = self.title.as_ref().map(|t| {
            let size = TextSize::Title.px() * k;
            let laid = text::layout(t, size, Weight::Bold);
            let origin = DVec2::new((w - laid.width) / 2.0, margin + text::cap_height(size));
            PlacedLine { text: t.clone(), origin, size }
        });

        let caption_size = TextSize::Body.px() * k;
        let lines = self.caption_lines();
        let step = caption_size * LINE_SPACING;
        let first = h
            - margin
            - step * (lines.len().saturating_sub(1)) as f64
            - text::layout("g", caption_size, Weight::Regular).descent;
        let caption = lines
            .into_iter()
            .enumerate()
            .map(|(i, line)| {
                let width = text::layout(&line, caption_size, Weight::Regular).width;
                let origin = DVec2::new((w - width) / 2.0, first + step * i as f64);
                PlacedLine { text: line, origin, size: caption_size }
            })
            .collect();

        let legend = legend_rect.map(|rect| self.legend_rows(rect));
        Frame { transform: tf, plot, title, caption, legend }
    }

    /// The legend's padding, sample length, gap before the text, and row height, in pixels.
    fn legend_metrics(&self) -> (f64, f64, f64, f64) {
        let k = self.px_scale();
        (18.0 * k, 64.0 * k, 16.0 * k, TextSize::Body.px() * k * LINE_SPACING)
    }

    /// The legend box's size in pixels, or `None` without legend entries.
    fn legend_size(&self) -> Option<DVec2> {
        if self.legend.is_empty() {
            return None;
        }
        let size = TextSize::Body.px() * self.px_scale();
        let (pad, sample_len, gap, row) = self.legend_metrics();
        let text_width = self
            .legend
            .iter()
            .map(|e| text::layout(&e.label, size, Weight::Regular).width)
            .fold(0.0, f64::max);
        Some(DVec2::new(
            pad * 2.0 + sample_len + gap + text_width,
            pad * 2.0 + row * self.legend.len() as f64,
        ))
    }

    /// The transform, the plot area and the legend box, with [`LegendPlace::Auto`] resolved.
    fn placed_legend(&self) -> (Transform, PxRect, Option<PxRect>) {
        let Some(size) = self.legend_size() else {
            let plot = self.plot_area_beside(0.0);
            return (self.transform_in(&plot), plot, None);
        };
        let inset = style::MARGIN * self.px_scale() * 0.3;
        let in_corner = |plot: &PxRect, corner: Corner| {
            let x = match corner {
                Corner::TopLeft | Corner::BottomLeft => plot.min.x + inset,
                Corner::TopRight | Corner::BottomRight => plot.max.x - inset - size.x,
            };
            let y = match corner {
                Corner::TopLeft | Corner::TopRight => plot.min.y + inset,
                Corner::BottomLeft | Corner::BottomRight => plot.max.y - inset - size.y,
            };
            PxRect { min: DVec2::new(x, y), max: DVec2::new(x, y) + size }
        };
        let outside = || {
            let plot = self.plot_area_beside(size.x);
            let margin = style::MARGIN * self.px_scale();
            let min = DVec2::new(plot.max.x + margin, plot.min.y);
            (self.transform_in(&plot), plot, Some(PxRect { min, max: min + size }))
        };
        let below = || {
            let plot = self.plot_area_above(size.y);
            let margin = style::MARGIN * self.px_scale();
            let min = DVec2::new(plot.max.x - size.x, plot.max.y + margin);
            (self.transform_in(&plot), plot, Some(PxRect { min, max: min + size }))
        };
        match self.legend_place {
            LegendPlace::Below => below(),
            LegendPlace::Inside(corner) => {
                let plot = self.plot_area_beside(0.0);
                (self.transform_in(&plot), plot, Some(in_corner(&plot, corner)))
            }
            LegendPlace::Outside => outside(),
            LegendPlace::Auto => {
                let plot = self.plot_area_beside(0.0);
                let tf = self.transform_in(&plot);
                let segments = self.segments(&tf);
                let boxes = self.text_boxes(&tf);
                let clear = |r: &PxRect| {
                    let r = r.inflate(inset);
                    !segments.iter().any(|(a, b)| r.meets_segment(*a, *b))
                        && boxes.iter().all(|b| r.overlap(b) <= 0.0)
                };
                Corner::ALL
                    .iter()
                    .map(|c| in_corner(&plot, *c))
                    .find(|r| clear(r))
                    .map_or_else(outside, |r| (tf, plot, Some(r)))
            }
        }
    }

    /// The legend's rows inside its box.
    fn legend_rows(&self, rect: PxRect) -> LegendBox {
        let size = TextSize::Body.px() * self.px_scale();
        let (pad, sample_len, gap, row) = self.legend_metrics();
        let cap = text::cap_height(size);
        let rows = self
            .legend
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let mid_y = rect.min.y + pad + row * (i as f64 + 0.5);
                let sample_from = DVec2::new(rect.min.x + pad, mid_y);
                let sample_to = sample_from + DVec2::new(sample_len, 0.0);
                let origin = DVec2::new(sample_to.x + gap, mid_y + cap / 2.0);
                let label = PlacedLine { text: e.label.clone(), origin, size };
                LegendRow { sample_from, sample_to, label }
            })
            .collect();
        LegendBox { rect, rows }
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    #[test]
    fn views_validate() {
        assert!(View::new(0.0, 1.0, 0.0, 1.0).is_some());
        assert!(View::new(1.0, 1.0, 0.0, 1.0).is_none());
        assert!(View::new(0.0, f64::NAN, 0.0, 1.0).is_none());
        assert!(Drawing::new(0, 10).is_none());
    }

    #[test]
    fn fit_holds_the_points_at_the_requested_aspect() {
        let pts = [v(-2.0, 0.0), v(3.0, 1.0), v(0.0, -1.0)];
        let view = View::fit(&pts, 0.1, 16.0 / 9.0).unwrap();
        assert!((view.width() / view.height() - 16.0 / 9.0).abs() < 1e-9);
        for p in pts {
            assert!(p.x > view.xmin() && p.x < view.xmax() && p.y > view.ymin() && p.y < view.ymax());
        }
        // One point still gives a view; no finite point gives none.
        assert!(View::fit(&[v(1.0, 1.0)], 0.1, 1.0).is_some());
        assert!(View::fit(&[v(f64::NAN, 0.0)], 0.1, 1.0).is_none());
        assert!(View::fit(&pts, 0.1, 0.0).is_none());
    }

    #[test]
    fn transform_is_uniform_with_y_up() {
        let mut d = Drawing::slide();
        d.set_view(View::new(0.0, 2.0, 0.0, 1.0).unwrap());
        let tf = d.transform();
        let a = tf.to_px(v(0.0, 0.0));
        let b = tf.to_px(v(1.0, 1.0));
        assert!(b.y < a.y, "y goes up in the world, down in pixels");
        assert!(((b.x - a.x) - (a.y - b.y)).abs() < 1e-9, "one scale for both axes");
        let back = tf.to_world(tf.to_px(v(0.3, 0.7)));
        assert!((back - v(0.3, 0.7)).length() < 1e-12);
        // The view's centre lands in the middle of the plot area.
        let frame = d.frame();
        let mid = (frame.plot.min + frame.plot.max) / 2.0;
        assert!((tf.to_px(v(1.0, 0.5)) - mid).length() < 1e-9);
    }

    #[test]
    fn fitted_view_keeps_circles_round_on_any_canvas() {
        let mut d = Drawing::new(800, 1200).unwrap();
        d.set_title("t").set_caption("c");
        d.fit_view(&[v(0.0, 0.0), v(10.0, 1.0)], 0.05);
        let tf = d.transform();
        let plot = d.frame().plot;
        let corner_lo = tf.to_px(v(d.view.xmin(), d.view.ymin()));
        let corner_hi = tf.to_px(v(d.view.xmax(), d.view.ymax()));
        // The fitted view fills the plot area exactly.
        assert!((corner_lo.x - plot.min.x).abs() < 1e-6 && (corner_hi.x - plot.max.x).abs() < 1e-6);
        assert!((corner_hi.y - plot.min.y).abs() < 1e-6 && (corner_lo.y - plot.max.y).abs() < 1e-6);
    }

    #[test]
    fn builders_add_one_tagged_item_each() {
        let mut d = Drawing::slide();
        d.segment("ray:primary", v(0.0, 0.0), v(1.0, 0.0), style::RayRole::Primary.style())
            .arrow("ray:reflected", v(0.0, 0.0), v(0.0, 1.0), style::RayRole::Reflected.style())
            .circle("object:0", v(0.0, 0.0), 0.5, style::object(), Some(style::OBJECT_FILL))
            .dot("hit", v(0.5, 0.0), style::HIT)
            .polygon("object:1", [v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)], style::object(), None)
            .rect("cell", v(1.0, 1.0), v(0.0, 0.0), style::grid(), None)
            .text("label", v(0.0, 0.0), "θ_i", TextOpts::LABEL);
        assert_eq!(d.items.len(), 7);
        assert_eq!(d.tagged("object:1").count(), 1);
        let Shape::Rect { min, max, .. } = d.tagged("cell").next().unwrap().shape else {
            panic!("not a rect");
        };
        assert!(min.cmple(max).all());
    }

    #[test]
    fn segment_rectangle_meeting() {
        let r = PxRect { min: v(0.0, 0.0), max: v(10.0, 10.0) };
        assert!(r.meets_segment(v(-5.0, 5.0), v(15.0, 5.0)));
        assert!(r.meets_segment(v(2.0, 2.0), v(3.0, 3.0)));
        assert!(!r.meets_segment(v(-5.0, -1.0), v(15.0, -1.0)));
        assert!(!r.meets_segment(v(11.0, 0.0), v(20.0, 10.0)));
        assert!(r.meets_segment(v(-1.0, 5.0), v(5.0, -1.0)));
    }

    #[test]
    fn avoid_overlap_moves_a_label_off_an_earlier_one_and_off_lines() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        d.segment("ray:primary", v(-2.0, 0.0), v(2.0, 0.0), style::RayRole::Primary.style());
        d.text("label", v(0.0, 0.0), "first", TextOpts::LABEL.avoid_overlap());
        d.text("label", v(0.0, 0.0), "second", TextOpts::LABEL.avoid_overlap());
        let tf = d.transform();
        let boxes = d.text_boxes(&tf);
        assert_eq!(boxes.len(), 2);
        assert!(boxes[0].overlap(&boxes[1]) <= 0.0, "{boxes:?}");
        let y = tf.to_px(v(0.0, 0.0)).y;
        for b in &boxes {
            assert!(b.min.y > y || b.max.y < y, "label crosses the ray: {b:?}");
        }
    }

    fn text_items(d: &Drawing) -> Vec<&Text> {
        d.items
            .iter()
            .filter_map(|item| if let Shape::Text(t) = &item.shape { Some(t) } else { None })
            .collect()
    }

    #[test]
    fn a_plot_keeps_its_names_inside_the_axes() {
        // A point on the x axis, the area above it: the name must not go below the axis.
        let mut d = Drawing::slide();
        d.set_view(View::new(-1.0, 3.0, -1.0, 1.0).unwrap());
        d.keep_labels_within(v(0.0, 0.0), v(3.0, 1.0));
        d.marker("point", v(1.0, 0.0), 6.0, style::BLUE, Style::NONE);
        d.text(
            "name",
            v(1.0, 0.0),
            "a name",
            TextOpts::NOTE.align(Align::BELOW).offset(0.0, -14.0).avoid_overlap(),
        );
        let tf = d.transform();
        let placed = Drawing::place_text(text_items(&d)[0], &tf);
        assert!(placed.bbox.max.y <= tf.to_px(v(0.0, 0.0)).y, "above the axis: {:?}", placed.bbox);
    }

    #[test]
    fn a_name_keeps_off_other_points_and_its_leader_off_other_names() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        // A marker just right of the anchor, where the name is asked to go.
        d.marker("other", v(0.12, 0.0), 6.0, style::BLUE, Style::NONE);
        let right = TextOpts::NOTE.align(Align::RIGHT_OF).offset(14.0, 0.0);
        d.text("name", v(0.0, 0.0), "a name", right.avoid_overlap());
        let tf = d.transform();
        let dot = tf.to_px(v(0.12, 0.0));
        let b = Drawing::place_text(text_items(&d)[0], &tf).bbox;
        assert!(!b.contains_point(dot), "the name left the other point visible: {b:?} {dot:?}");

        // Hatching around the anchor makes every near spot cost more than the third ring; of the
        // third ring's spots, the first tried (right) has a leader through the label "b": the
        // name goes to the next clear one (above) instead.
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        let tf = d.transform();
        // World units per reference pixel.
        let world = tf.ref_px(1.0) / (tf.to_px(v(1.0, 0.0)).x - tf.to_px(v(0.0, 0.0)).x);
        let at = |x: f64, y: f64| v(x * world, y * world);
        for k in -5..=5 {
            let x = 10.0 * f64::from(k);
            d.segment("hatch", at(x, -50.0), at(x, 50.0), Style::solid(style::BLACK, 1.0));
        }
        d.text("b", at(40.0, 0.0), "b", TextOpts::NOTE);
        d.text("name", v(0.0, 0.0), "a name", right.avoid_overlap_with_leader());
        let tf = d.transform();
        let texts = text_items(&d);
        let name = Drawing::place_text(texts[1], &tf);
        let b = Drawing::place_text(texts[0], &tf).bbox;
        let (from, to) = name.leader.expect("set apart, with a leader");
        assert!(!b.meets_segment(from, to), "the leader crosses b: {name:?} {b:?}");
        assert!(name.bbox.min.y < tf.to_px(v(0.0, 0.0)).y, "above the anchor: {name:?}");
    }

    #[test]
    fn a_name_set_far_from_its_anchor_gets_a_leader_to_its_box() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        // Three names of one point: the later ones must move away, the last farther than
        // LEADER_FROM; only labels that ask for a leader get one.
        for _ in 0..3 {
            d.text("name", v(0.0, 0.0), "a long name", TextOpts::LABEL.avoid_overlap_with_leader());
        }
        d.text("symbol", v(0.0, 0.0), "a long name", TextOpts::LABEL.avoid_overlap());
        let tf = d.transform();
        let texts = text_items(&d);
        assert!(!texts[0].leader, "the first name sits where asked");
        let far = texts[2];
        assert!(far.leader && far.offset.length() > LEADER_FROM, "{far:?}");
        let placed = Drawing::place_text(far, &tf);
        let (from, to) = placed.leader.expect("a leader in pixels");
        assert_eq!(from, tf.to_px(far.anchor));
        // It stops just short of the box, on the side facing the anchor.
        let near = placed.bbox.inflate(tf.ref_px(4.5));
        assert!(near.contains_point(to) && !placed.bbox.contains_point(to), "{to:?} {:?}", placed.bbox);
        assert!(!texts[3].leader, "a symbol never gets a leader");
        assert!(Drawing::place_text(texts[3], &tf).leader.is_none());
    }

    #[test]
    fn stacked_names_of_boxes_sharing_a_corner_go_down_a_line_each_and_stay_in_their_box() {
        let mut d = Drawing::slide();
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        let corner = v(-1.0, 0.5);
        let opts = TextOpts::NOTE.align(Align { h: HAlign::Left, v: VAlign::Top });
        for name in ["A", "B", "C"] {
            d.text("node-name", corner, name, opts.stack_down(-1.0));
        }
        // A box too short for a second line: its name stays at the corner, over A's.
        d.text("node-name", corner, "D", opts.stack_down(0.49));
        let tf = d.transform();
        let boxes = d.text_boxes(&tf);
        for k in 1..3 {
            assert!(boxes[k].min.y >= boxes[k - 1].max.y, "{k}: {boxes:?}");
            assert!(boxes[k].min.x == boxes[0].min.x, "{k}: alignment kept");
        }
        assert_eq!(boxes[3].min, boxes[0].min);
    }

    #[test]
    fn a_clear_label_stays_where_asked() {
        let mut d = Drawing::slide();
        let opts = TextOpts::LABEL.offset(10.0, 20.0).align(Align::ABOVE).avoid_overlap();
        d.text("label", v(0.0, 0.0), "N", opts);
        let Shape::Text(t) = &d.items[0].shape else { panic!() };
        assert_eq!(t.offset, v(10.0, 20.0));
        assert_eq!(t.align, Align::ABOVE);
    }

    #[test]
    fn legend_goes_to_the_emptiest_corner() {
        let mut d = Drawing::slide();
        d.set_view(View::new(0.0, 16.0, 0.0, 9.0).unwrap());
        // Clutter the top right corner.
        for i in 0..10 {
            let y = 9.0 - f64::from(i) * 0.2;
            d.segment("clutter", v(10.0, y), v(16.0, y), style::grid());
        }
        d.legend_entry("primary", style::RayRole::Primary.style(), Sample::Line);
        let legend = d.frame().legend.unwrap();
        let plot = d.frame().plot;
        assert!(legend.rect.min.x < (plot.min.x + plot.max.x) / 2.0, "{legend:?}");
        assert_eq!(legend.rows.len(), 1);
    }

    #[test]
    fn legend_goes_outside_when_no_corner_is_clear_and_stays_where_fixed() {
        let mut d = Drawing::slide();
        d.set_view(View::new(0.0, 16.0, 0.0, 9.0).unwrap());
        for i in 0..=16 {
            let x = f64::from(i);
            d.segment("grid", v(x, 0.0), v(x, 9.0), style::grid());
        }
        d.legend_entry("primary", style::RayRole::Primary.style(), Sample::Line);
        let full = Drawing::slide().frame().plot;
        let frame = d.frame();
        let legend = frame.legend.unwrap();
        assert!(frame.plot.width() < full.width());
        assert!(legend.rect.min.x > frame.plot.max.x);
        assert!(legend.rect.max.x <= 1920.0);
        // The transform follows the narrowed plot area.
        assert!(d.transform().to_px(v(16.0, 0.0)).x <= frame.plot.max.x + 1e-9);

        d.legend_place = LegendPlace::Inside(Corner::BottomLeft);
        let frame = d.frame();
        let legend = frame.legend.unwrap();
        assert!((frame.plot.width() - full.width()).abs() < 1e-9);
        assert!(legend.rect.max.y > frame.plot.max.y - 20.0 && legend.rect.min.x < 100.0);
    }

    #[test]
    fn a_legend_below_shortens_the_plot_and_keeps_a_wide_picture_larger_than_a_column() {
        // A picture three times as wide as tall, which the slide's plot area fits by its width.
        let wide = |place: LegendPlace| {
            let mut d = Drawing::slide();
            d.set_view(View::new(0.0, 30.0, 0.0, 10.0).unwrap());
            d.legend_entry("a legend entry with a long label", style::RayRole::Primary.style(), Sample::Line);
            d.legend_place = place;
            d
        };
        let (column, band) = (wide(LegendPlace::Outside), wide(LegendPlace::Below));
        let (full, frame) = (Drawing::slide().frame().plot, band.frame());
        let legend = frame.legend.unwrap();
        // The band: the plot keeps its width, loses the legend's height and a margin, and the
        // legend sits under it at its right end, above the caption band and inside the canvas.
        assert!((frame.plot.width() - full.width()).abs() < 1e-9);
        assert!(frame.plot.max.y < full.max.y - legend.rect.height());
        assert!(legend.rect.min.y > frame.plot.max.y);
        assert!((legend.rect.max.x - frame.plot.max.x).abs() < 1e-9);
        assert!(legend.rect.max.y <= full.max.y + 1e-9);
        // The picture is drawn larger under a band than beside a column.
        assert!(
            band.picture_scale() > column.picture_scale(),
            "{} {}",
            band.picture_scale(),
            column.picture_scale()
        );
        // A tall picture is the other way round.
        let tall = |place: LegendPlace| {
            let mut d = wide(place);
            d.set_view(View::new(0.0, 10.0, 0.0, 10.0).unwrap());
            d
        };
        assert!(tall(LegendPlace::Outside).picture_scale() >= tall(LegendPlace::Below).picture_scale());
    }

    #[test]
    fn title_and_caption_bands_shrink_the_plot() {
        let mut d = Drawing::slide();
        let full = d.frame().plot;
        d.set_title("Title").set_caption("A caption");
        let frame = d.frame();
        assert!(frame.plot.height() < full.height());
        let title = frame.title.unwrap();
        assert!(title.origin.y < frame.plot.min.y);
        assert!(frame.caption[0].origin.y > frame.plot.max.y);
        assert!(frame.caption[0].origin.y < 1080.0);
    }
}
