//! The 2D drawing engine, which knows nothing of ray tracing: a back-end-free display list in
//! world coordinates (f64), before a back end turns it into pixels (`skia`) or SVG (`svg`).
//! It is a crate of its own (`whitted-canvas`, re-exported as `whitted::canvas`): nothing here can
//! import from the rest of whitted, so the figures' geometry and their pixels stay apart.
//!
//! A [`Drawing`] maps a world rectangle ([`View`], y up) onto its canvas with one uniform scale, so
//! circles stay round. Geometry is in world units; what a reader sees at a fixed size (strokes,
//! dashes, arrow heads, dots, text) is in *reference pixels* of the 1920 × 1080 slide ([`style`]),
//! scaled by [`Drawing::px_scale`]. The page (title, caption, plot area, legend) is laid out once
//! for both back ends ([`Drawing::frame`]).
#![forbid(unsafe_code)]

pub mod drawing;
pub mod items;
pub mod label;
pub mod legend;
pub mod listing;
pub mod page;
pub mod skia;
pub mod style;
pub mod svg;
pub mod text;
pub mod view;

pub use drawing::Drawing;
pub use items::{ArrowPx, Item, Mark, Text};
pub use label::{Align, HAlign, PlacedText, Placement, TextOpts, VAlign};
pub use legend::{Corner, LegendBox, LegendEntry, LegendIcon, LegendPlace, LegendRow};
pub use page::{PageLayout, PlacedLine};
pub use style::{Dash, Pen, Rgba, TextSize};
pub use view::{PxRect, Transform, View};
