//! The display list's entries: an [`Item`] (tag, stroke, the trace events it draws) holds a
//! [`Mark`] in world coordinates; a label is a [`Text`]; an arrow laid out in pixels for the
//! back ends is an [`ArrowPx`].

use glam::DVec2;

use super::label::Align;
use super::style::{Pen, Rgba, TextSize};
use super::text::Weight;

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
