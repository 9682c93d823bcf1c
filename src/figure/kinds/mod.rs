//! One file per diagram of product.md "Diagrams". Each reads the recorded traces and the scene
//! through [`Input`] and adds its items to a [`Drawing`]; none traces, intersects or refracts.

pub mod adaptive;
pub mod backward;
pub mod bvh;
pub mod camera_frame;
pub mod complexity;
pub mod discriminant;
pub mod grid_dda;
pub mod heat_map;
pub mod hierarchy;
pub mod jagged;
pub mod kay_kajiya;
pub mod local_model;
pub mod octree;
pub mod projections;
pub mod ray_tree;
pub mod rays;
pub mod refraction;
pub mod shadows;
pub mod slab_test;
pub mod slabs;
pub mod uv_map;

use super::labels::{self, Label};
use super::plane::Planar;
use super::source::{FigureInput, FigureTrace};
use super::{FigureError, FigureKind, Lang};
use crate::canvas::{Drawing, LegendPlace};
use crate::scene::Scene;

/// What a kind reads.
pub struct Input<'a, V: Planar> {
    /// The recorded traces (the main one first).
    pub traces: &'a FigureInput<V>,
    /// The scene they were recorded in.
    pub scene: &'a Scene<V>,
    /// The labels' language.
    pub lang: Lang,
}

impl<V: Planar> Input<'_, V> {
    /// The main trace.
    ///
    /// # Errors
    /// When there is none.
    pub fn main(&self) -> Result<&FigureTrace<V>, FigureError> {
        self.traces.traces.first().ok_or_else(|| FigureError("no trace was recorded".into()))
    }
    /// A fixed label in the figure's language.
    #[must_use]
    pub fn t(&self, label: Label) -> &'static str {
        label.text(self.lang)
    }
    /// The caption's start: the scene and the traced pixel (and why it was picked).
    #[must_use]
    pub fn traced(&self, traced: &FigureTrace<V>) -> String {
        let target = traced.targets.first().cloned().unwrap_or(super::source::Target::Ray);
        labels::traced(&self.traces.scene_name, &target, traced.pick, V::DIM, self.lang)
    }
}

/// Draws `kind` into `d`. A legend that finds no free corner goes beside the picture or under
/// it, which then has a narrower or a shorter plot area: the kind is drawn again with the legend
/// placed either way from the start, so that its view is fitted to that area (and not merely
/// shrunk), and the larger picture is kept.
///
/// # Errors
/// Traces that lack what the kind draws, or a kind whose events this build does not record.
pub fn draw<V: Planar>(kind: FigureKind, input: &Input<'_, V>, d: Drawing) -> Result<Drawing, FigureError> {
    let mut first = d.clone();
    draw_once(kind, input, &mut first)?;
    let frame = first.frame();
    let beside = frame.legend.is_some_and(|l| l.rect.min.x >= frame.plot.max.x);
    if first.legend_place == LegendPlace::Auto && beside {
        // Beside the picture in a column, or under it in a band: whichever draws it larger (a
        // band only when clearly so, 2 %, so that a near tie keeps the column).
        let mut column = d.clone();
        column.legend_place = LegendPlace::Outside;
        draw_once(kind, input, &mut column)?;
        let mut band = d;
        band.legend_place = LegendPlace::Below;
        draw_once(kind, input, &mut band)?;
        return Ok(if band.picture_scale() > 1.02 * column.picture_scale() { band } else { column });
    }
    Ok(first)
}

/// Draws `kind` into `d` once.
fn draw_once<V: Planar>(kind: FigureKind, input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    draw_kind(kind, input, d)?;
    // A ray that passes close by what it misses says by how much (issue 32 item 3).
    super::clearance::note_near_misses(d, input.scene, input.lang);
    // With every label drawn, each placed clear goes back to its own point if a later one took it.
    d.settle_labels();
    Ok(())
}

/// Draws `kind`'s items into `d`.
fn draw_kind<V: Planar>(kind: FigureKind, input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    match kind {
        FigureKind::BackwardRays => backward::draw(input, d),
        FigureKind::CameraFrame => camera_frame::draw(input, d),
        FigureKind::Discriminant => discriminant::draw(input, d),
        FigureKind::JaggedEdges => jagged::draw(input, d),
        FigureKind::Complexity => complexity::draw(input, d),
        FigureKind::UvMap => uv_map::draw(input, d),
        FigureKind::Projections => projections::draw(input, d),
        FigureKind::Rays => rays::draw(input, d),
        FigureKind::Refraction => refraction::draw(input, d),
        FigureKind::LocalModel => local_model::draw(input, d),
        FigureKind::RayTree => ray_tree::draw(input, d),
        FigureKind::Shadows => shadows::draw(input, d),
        FigureKind::Adaptive => adaptive::draw(input, d),
        FigureKind::HeatMap => heat_map::draw(input, d),
        FigureKind::SlabTest => slab_test::draw(input, d),
        FigureKind::KayKajiya => kay_kajiya::draw(input, d),
        FigureKind::Bvh => bvh::draw(input, d),
        FigureKind::Octree => octree::draw(input, d),
        FigureKind::GridDda => grid_dda::draw(input, d),
    }
}
