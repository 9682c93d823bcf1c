//! The display list's entries: an [`Item`] (tag, stroke, the trace events it draws) holds a
//! [`Mark`] in world coordinates; a label is a [`Text`]; an arrow laid out in pixels for the
//! back ends is an [`ArrowPx`]. Beside them, what a [`Drawing`](crate::Drawing) stores or is
//! asked for and its parts read: a label's options ([`TextOpts`], [`Align`], [`Placement`]) and the
//! legend's rows and place ([`LegendEntry`], [`LegendIcon`], [`LegendPlace`], [`Corner`]), and a
//! magnified detail ([`Inset`]: a frame of the world drawn larger in a panel, whose border
//! label placement keeps each label on its side of). So this
//! file imports no part of `Drawing`, and every part can import it.

use glam::DVec2;

use super::style::{self, Pen, Rgba, TextSize};
use super::text::Weight;
use super::view::{PxRect, Transform};

/// A text item: markup (see [`text`](crate::text)) placed at a world anchor.
#[derive(Clone, Debug, PartialEq)]
pub struct Text {
    /// The label, in the markup of [`text`](crate::text) (`θ_i`, `t_{ex}`).
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
    /// [`TextOpts::avoid_overlap_with_leader`] lands farther than [`LEADER_FROM`](crate::label::LEADER_FROM) from its
    /// anchor, so that it still points at what it names.
    pub leader: bool,
    /// Whether a white halo outlines the glyphs so the text reads over lines.
    pub halo: bool,
}

/// The geometry of one display-list item.
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
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
    pub pen: Pen,
    /// Geometry.
    pub mark: Mark,
    /// The indices of the trace events it draws (into the main trace's events, which are the
    /// trace document's): a ray its spawning event and its hit, a test its test… Empty for what
    /// no event drew (objects, lights, axes). The SVG writes them as `data-events`.
    pub events: Vec<usize>,
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

/// The largest share of an arrow its head may take, so that a short arrow keeps a shaft.
pub const HEAD_MAX_SHARE: f64 = 0.6;
/// Half the head's width at its base, per head length: a barb's distance from the shaft's line.
pub const HEAD_HALF_WIDTH: f64 = 0.42;
/// Where the shaft stops, in head lengths back from the tip: inside the head, so no gap shows.
pub const SHAFT_END: f64 = 0.7;
/// Where the head's notch lies, in head lengths back from the tip: short of the base, so the
/// head's back is swept between the barbs.
pub const HEAD_NOTCH: f64 = 0.85;

impl ArrowPx {
    /// The arrow from pixel `from` to pixel `to` with a head `head` pixels long (at most
    /// [`HEAD_MAX_SHARE`] of the arrow), or `None` for a zero-length arrow.
    #[must_use]
    pub fn new(from: DVec2, to: DVec2, head: f64) -> Option<Self> {
        let along = to - from;
        let len = along.length();
        if len.is_nan() || len <= f64::EPSILON {
            return None;
        }
        let dir = along / len;
        let head = head.min(HEAD_MAX_SHARE * len);
        let base = to - dir * head;
        let side = dir.perp() * head * HEAD_HALF_WIDTH;
        Some(Self {
            shaft_from: from,
            shaft_to: to - dir * head * SHAFT_END,
            head: [to, base + side, to - dir * head * HEAD_NOTCH, base - side],
        })
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
    /// Where the label may move when it would overlap an earlier one (see [`Drawing::text`](crate::Drawing::text)).
    pub placement: Placement,
    /// A leader from the anchor when [`Placement::Clear`] moved the label far ([`Text::leader`]).
    pub leader: bool,
    /// How far [`Placement::Clear`] may move the label: [`NEAR_STEPS`](crate::label::NEAR_STEPS) or, for a plot with room
    /// to spare, [`FAR_STEPS`](crate::label::FAR_STEPS) ([`TextOpts::far`]).
    pub far: bool,
}

/// How [`Drawing::text`](crate::Drawing::text) places a label against the labels already drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Placement {
    /// Exactly as requested.
    AsGiven,
    /// Nudged to a free spot near its anchor when it would overlap an earlier label or cross a
    /// line ([`TextOpts::avoid_overlap`]).
    Clear,
}

impl TextOpts {
    /// The label `markup` at `anchor` as these options lay it out, before any placement moves it.
    #[must_use]
    pub fn label(&self, markup: &str, anchor: DVec2) -> Text {
        Text {
            text: markup.to_owned(),
            anchor,
            offset: self.offset,
            align: self.align,
            size: self.size,
            weight: self.weight,
            leader: false,
            halo: self.halo,
        }
    }

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
    /// lands farther than [`LEADER_FROM`](crate::label::LEADER_FROM) from it: for names of points in a plot and of objects,
    /// not for the symbols of a construction, where one more line would read as geometry.
    #[must_use]
    pub const fn avoid_overlap_with_leader(self) -> Self {
        Self { placement: Placement::Clear, leader: true, ..self }
    }
    /// Free to go as far as [`FAR_STEPS`](crate::label::FAR_STEPS) from its anchor when placed clear.
    #[must_use]
    pub const fn far(self) -> Self {
        Self { far: true, ..self }
    }
}

/// What a legend entry's sample looks like.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LegendIcon {
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
    pub style: Pen,
    /// The sample's kind.
    pub sample: LegendIcon,
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

/// A magnified detail: the world rectangle `frame` drawn `factor` times larger in `panel`
/// (`panel`'s sides are `factor` times `frame`'s, centre on centre).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inset {
    /// The region magnified: lower-left and upper-right world corners.
    pub frame: (DVec2, DVec2),
    /// Where it is drawn magnified: lower-left and upper-right world corners.
    pub panel: (DVec2, DVec2),
    /// The magnification, `panel`'s width over `frame`'s.
    pub factor: f64,
}

impl Inset {
    /// The inset magnifying `frame` (any two opposite corners) `factor` times, its panel
    /// centred on `panel_centre`.
    #[must_use]
    pub fn new(frame: (DVec2, DVec2), factor: f64, panel_centre: DVec2) -> Self {
        let (lo, hi) = (frame.0.min(frame.1), frame.0.max(frame.1));
        let half = (hi - lo) * factor / 2.0;
        Self { frame: (lo, hi), panel: (panel_centre - half, panel_centre + half), factor }
    }

    /// Where world point `p` of the frame is drawn in the panel:
    /// `q = c_panel + factor · (p − c_frame)`, `c` each rectangle's centre.
    #[must_use]
    pub fn map(&self, p: DVec2) -> DVec2 {
        let frame_centre = (self.frame.0 + self.frame.1) / 2.0;
        let panel_centre = (self.panel.0 + self.panel.1) / 2.0;
        panel_centre + (p - frame_centre) * self.factor
    }

    /// Whether world point `p` lies in the frame (edges included).
    #[must_use]
    pub fn in_frame(&self, p: DVec2) -> bool {
        p.cmpge(self.frame.0).all() && p.cmple(self.frame.1).all()
    }

    /// Whether world point `p` lies in the panel (edges included).
    #[must_use]
    pub fn in_panel(&self, p: DVec2) -> bool {
        p.cmpge(self.panel.0).all() && p.cmple(self.panel.1).all()
    }

    /// The panel in pixels under `tf`.
    #[must_use]
    pub fn panel_px(&self, tf: &Transform) -> PxRect {
        let (a, b) = (tf.to_px(self.panel.0), tf.to_px(self.panel.1));
        PxRect { min: a.min(b), max: a.max(b) }
    }
}
