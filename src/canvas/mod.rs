//! The 2D drawing engine, which knows nothing of ray tracing: a back-end-free display list in
//! world coordinates (f64), before a back end turns it into pixels (`skia`) or SVG (`svg`).
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
//!
//! Modules: `drawing` (the [`Drawing`] and its builders), `items` (the display list's entries),
//! `view` (world rectangle, pixel rectangle, transform), `label` (text options and label
//! placement), `legend`, `listing` (the drawing as text, [`Drawing::to_text`]), `page` (the
//! layout of title, caption, plot area and legend), `style` (colours, strokes, sizes), `text`
//! (the embedded font, the label markup, text layout), and the back ends `skia` (PNG) and `svg`.
//! Nothing here imports from the rest of the crate.

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
