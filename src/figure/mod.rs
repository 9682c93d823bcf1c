//! Diagrams drawn from traces: a back-end-free display list (`drawing`) in world coordinates,
//! drawn to PNG through tiny-skia (`skia`) or to SVG (`svg`), with the lecture's colours and
//! slide-scale sizes (`style`) and labels in an embedded font (`text`).

pub mod drawing;
pub mod skia;
pub mod style;
pub mod svg;
pub mod text;
