//! Diagrams drawn from traces (product.md "Diagrams"; every section of the lecture that has a
//! figure). A figure reads recorded traces (`source`, the only part that runs the tracer) and the
//! scene, and draws what the code *did* onto a [`crate::canvas::Drawing`] (the display list) in
//! the lecture's notation (`labels`, `parts`, `plane`), one file per diagram (`kinds`), each ray
//! kind in its colour (`style`); the canvas draws the list to PNG or SVG.
//!
//! `FigureKind` is the closed list of product.md "Diagrams", with a line each; `Options` and `draw`
//! make one; `Lang` is the narration's. The items of a `Drawing` carry the main trace's event
//! indices (`Drawing::with_events`), so a page can light up what a narration step explains.

pub mod clearance;
pub mod inset;
pub mod kinds;
pub mod labels;
pub mod lighting;
pub mod parts;
pub mod plane;
pub mod source;
pub mod style;
pub mod tradeoff;

use crate::canvas::Drawing;
use crate::scene::Scene;
use plane::Planar;
use source::FigureInput;

/// The language of a figure's labels: the narration's.
pub use crate::doc::narrate::Lang;

/// The diagrams of product.md, one per `whitted figure KIND`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FigureKind {
    /// Rays traced backwards: from the observer against the light's own path.
    BackwardRays,
    /// The camera frame lookAt builds: O, C, up → u, v, w, the window at distance p.
    CameraFrame,
    /// Pixel (i, j) → window point (u, v).
    UvMap,
    /// Orthographic vs perspective primary rays.
    Projections,
    /// All rays of one pixel's trace, by kind.
    Rays,
    /// R and T at one hit: N, θᵢ, θₜ, n₁, n₂, and total internal reflection.
    Refraction,
    /// N, L, H, V at a hit and the terms of I_local.
    LocalModel,
    /// The ray tree as a graph.
    RayTree,
    /// Shadow rays from a hit to every light and the factor s.
    Shadows,
    /// Jagged edges: one ray per pixel beside supersampling, the same crop.
    JaggedEdges,
    /// Tests per ray against the number of objects, brute force and each structure.
    Complexity,
    /// The ray–sphere discriminant: Δ < 0, Δ = 0, Δ > 0 and the roots.
    Discriminant,
    /// The slab test of an axis-aligned box.
    SlabTest,
    /// Kay–Kajiya slabs.
    KayKajiya,
    /// BVH traversal.
    Bvh,
    /// Regular grid and the voxel DDA.
    GridDda,
    /// Octree traversal.
    Octree,
    /// Adaptive subdivision of one pixel.
    Adaptive,
    /// Primary rays per pixel over the image.
    HeatMap,
}

impl FigureKind {
    /// Every kind, in the lecture's order.
    pub const ALL: [Self; 19] = [
        Self::BackwardRays,
        Self::CameraFrame,
        Self::UvMap,
        Self::Projections,
        Self::Rays,
        Self::Refraction,
        Self::LocalModel,
        Self::RayTree,
        Self::Shadows,
        Self::JaggedEdges,
        Self::Complexity,
        Self::Discriminant,
        Self::SlabTest,
        Self::KayKajiya,
        Self::Bvh,
        Self::GridDda,
        Self::Octree,
        Self::Adaptive,
        Self::HeatMap,
    ];

    /// The name `whitted figure` takes.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::BackwardRays => "backward",
            Self::CameraFrame => "camera-frame",
            Self::JaggedEdges => "jagged-edges",
            Self::Complexity => "complexity",
            Self::Discriminant => "discriminant",
            Self::UvMap => "uv-map",
            Self::Projections => "projections",
            Self::Rays => "rays",
            Self::Refraction => "refraction",
            Self::LocalModel => "local-model",
            Self::RayTree => "ray-tree",
            Self::Shadows => "shadows",
            Self::SlabTest => "slab-test",
            Self::KayKajiya => "kay-kajiya",
            Self::Bvh => "bvh",
            Self::GridDda => "grid-dda",
            Self::Octree => "octree",
            Self::Adaptive => "adaptive",
            Self::HeatMap => "heat-map",
        }
    }

    /// The kind called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// What the figure shows, in one line (`whitted figure --list`).
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self {
            Self::BackwardRays => "the light's path (S → I → O) beside the rays traced backwards (O → I, then L from I towards S)",
            Self::CameraFrame => "the camera frame lookAt builds: O, C, up → w, u, v with their numbers, the window at distance p",
            Self::JaggedEdges => "the same crop of the image with one ray per pixel and supersampled: the jagged edge and its smoothing",
            Self::Complexity => "tests per ray against n = 10 … 10 000 objects, measured: brute force O(n) and each structure",
            Self::Discriminant => "three rays and a sphere: Δ < 0 (miss), Δ = 0 (tangent), Δ > 0 (roots t₁, t₂)",
            Self::UvMap => "the pixel grid and the view window: pixel (i, j), rows from the bottom, its centre → (u, v) with the numbers",
            Self::Projections => "orthographic and perspective primary rays side by side for the same window (D = [0, 0, −1] vs S − O)",
            Self::Rays => "every ray of one pixel's trace by kind (primary, reflected, transmitted, shadow; blocked ones dashed), hits I₁, I₂ …",
            Self::Refraction => "R and T at one hit: N, θᵢ, θₜ with their values, n₁, n₂, Snell's law; the total internal reflection case",
            Self::LocalModel => "N, L, H, V at a hit with N·L, N·H and the terms of I_local with their numbers",
            Self::RayTree => "the ray tree as a graph (P, R₁, T₁, L₁ …): each node's level, object and colour, the depth limit",
            Self::Shadows => "the shadow rays from a hit to every light, the occluders and the factor s = Π kt",
            Self::SlabTest => "a box with a hitting and a missing ray, per-axis intervals [tᵢ, tₑ], max tᵢ and min tₑ",
            Self::KayKajiya => "Kay–Kajiya slab pairs at 0°, 45°, 90°, 135° around an object; a ray's per-slab intervals",
            Self::Bvh => "the hierarchy's volumes, the nodes a ray visits in order and those it skips, the tree beside it",
            Self::GridDda => "the regular grid and the cells the DDA visits in order, tMax per axis, the pitfall",
            Self::Octree => "the adaptive subdivision of space and the nodes a ray visits",
            Self::Adaptive => "one pixel's adaptive subdivision: squares by level, samples CA, CB …, reused ones, leaf colours",
            Self::HeatMap => "primary rays per pixel over the whole image, with a colour scale",
        }
    }
}

/// Why a figure could not be made (a message for the reader, naming what is missing).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FigureError(pub String);

impl std::fmt::Display for FigureError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for FigureError {}

/// The most pixels a figure's canvas may have (8192² = 2^26, a 256 MiB pixmap): a slide is 2 073 600.
pub const MAX_CANVAS_PIXELS: u64 = 1 << 26;

/// How a figure is drawn: its language and canvas size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// The labels' language.
    pub lang: Lang,
    /// Canvas width, pixels.
    pub width: u32,
    /// Canvas height, pixels.
    pub height: u32,
}

impl Options {
    /// A slide (1920 × 1080) in `lang`.
    #[must_use]
    pub const fn slide(lang: Lang) -> Self {
        Self { lang, width: style::REFERENCE_WIDTH, height: style::REFERENCE_HEIGHT }
    }
}

/// Draws figure `kind` from the recorded `traces` of `scene` (made by [`source::record`]).
///
/// # Errors
/// A zero canvas size, or traces that lack what the kind draws.
pub fn draw<V: Planar>(
    kind: FigureKind,
    traces: &FigureInput<V>,
    scene: &Scene<V>,
    opts: &Options,
) -> Result<Drawing, FigureError> {
    let mut d = Drawing::new(opts.width, opts.height)
        .ok_or_else(|| FigureError(format!("a {}×{} canvas is empty", opts.width, opts.height)))?;
    // No label may hide a ray it does not name (issue 23 item 9).
    d.guard_lines(style::RAY_TAG);
    // No label may sit on another object's outline (issue 32 item 1).
    d.guard_outlines(style::OBJECT_TAG);
    // No label may be touched by a mapping arrow's head (issue 32, pixel-uv 2), nor lie on a
    // normal, even its own point's (issue 32, shadows 1's "I₁").
    d.guard_strictly(style::MAPPING_TAG);
    d.guard_strictly(style::NORMAL_TAG);
    let input = kinds::Input { traces, scene, lang: opts.lang };
    let mut drawn = kinds::draw(kind, &input, d)?;
    // What each step lights beyond the kinds' own tags (issue 30 item 3); moves nothing.
    if let Some(main) = traces.traces.first() {
        lighting::complete(&mut drawn, &main.log);
    }
    Ok(drawn)
}
