//! whitted: recursive (Whitted) ray tracing, taught in the open.
//!
//! A scene file is read and validated once (`scene`), the camera turns pixels into primary rays
//! (`scene::camera`), the tracer follows each ray through the lecture's recursion
//! `I = I_local + ks·R + kt·T` (`trace`) while reporting every step to a recorder chosen at compile
//! time (`record`), and what was recorded becomes the trace document (`doc`), a narration, an image
//! (`render`, `image`) or a diagram (`figure`), and the lessons (`lesson`) gather the diagrams of
//! the lecture, with the interactive pages of the course (`site`); `tradeoff` measures what
//! accuracy costs. `request` is what a command does between
//! its arguments and its answer, shared by the command line and the WebAssembly binding; `clock`
//! times where the platform has a clock; `memory` is the budget every estimate is checked against. The mathematics is written once for 2D
//! and 3D (`geom`, `shape`).
//! See `ARCHITECTURE.md` for the codemap and the invariants.
#![forbid(unsafe_code)]

pub mod accel;
pub mod bounds;
pub use whitted_canvas as canvas;
pub mod clock;
pub mod complexity;
pub mod doc;
pub mod figure;
pub mod format;
pub use whitted_geom as geom;
pub mod grade;
pub mod image;
pub mod json;
pub mod lang;
pub mod lesson;
pub mod memory;
pub mod record;
pub mod render;
pub mod request;
pub mod sample;
pub mod scene;
pub mod shape;
pub mod site;
pub mod trace;
pub mod tradeoff;
