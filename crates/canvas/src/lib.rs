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
//!
//! # Where each part of `Drawing` lives
//!
//! [`Drawing`] is one type whose methods are written beside what they do, each file adding its own
//! `impl Drawing` block; the parts import `drawing` and `items`, never each other in a circle:
//!
//! - `items`: what the display list holds (`Item`, `Mark`, `Text`) and the options and legend rows
//!   a `Drawing` stores (`TextOpts`, `Align`, `Placement`, `LegendEntry`, `LegendPlace`).
//! - `drawing`: the struct, its view and scale, and the builders of shapes (`line`, `arrow`,
//!   `circle`, `dot`, `rect`, `polygon` …), `guard_lines`, `with_events`.
//! - `label`: `text` and the placement of labels (`place_clear`, `text_at_cheapest`, `place_text`),
//!   with the layout checks.
//! - `legend`: `legend_entry` and the legend's box (`placed_legend`).
//! - `page`: `frame`, the page laid out once for both back ends (reads `legend`).
//! - `listing`: `to_text`; `skia` and `svg`: the two back ends (read everything above); `subset`:
//!   the fonts cut to what an SVG prints, which `svg` embeds (reads nothing of `Drawing`).
#![forbid(unsafe_code)]

pub mod drawing;
pub mod items;
pub mod label;
pub mod legend;
pub mod listing;
pub mod page;
pub mod skia;
pub mod style;
pub mod subset;
pub mod svg;
pub mod text;
pub mod view;

pub use drawing::{Drawing, SceneAxes};
pub use items::{
    Align, ArrowPx, Corner, HAlign, Inset, Item, LegendEntry, LegendIcon, LegendPlace, Mark, Placement, Text,
    TextOpts, VAlign,
};
pub use label::PlacedText;
pub use legend::{LegendBox, LegendRow};
pub use page::PageLayout;
pub use style::{Dash, Pen, Rgba, TextSize};
pub use text::PlacedLine;
pub use view::{PxRect, Transform, View};
