//! `octree` (lecture "Scena divizată în volume încadratoare (3)", algorithm.md §9 "Adaptive
//! (octree)"): the adaptive subdivision of the scene's box (a quadtree in 2D), split while a cell
//! holds more than one object, and the nodes one primary ray's recorded walk entered in order,
//! missed, or never tested. Traced with `--accel octree`.

use super::{hierarchy, Input};
use crate::canvas::Drawing;
use crate::figure::labels::Label;
use crate::figure::plane::Planar;
use crate::figure::FigureError;

/// Draws the figure.
///
/// # Errors
/// When the traces were not recorded with an octree.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    hierarchy::draw(input, d, Label::TitleOctree, "octree")
}
