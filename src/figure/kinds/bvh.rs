//! `bvh` (lecture "Scena reprezentată printr-o ierarhie de volume încadratoare", algorithm.md §9
//! "BVH"): the bounding volume hierarchy's boxes over the scene and the tree beside them; the
//! nodes one primary ray entered, in order, those whose box it missed (their subtrees skipped),
//! and those never tested — all from its recorded `node_visit` events. Traced with `--accel bvh`.

use super::{hierarchy, Input};
use crate::canvas::Drawing;
use crate::figure::labels::Label;
use crate::figure::plane::Planar;
use crate::figure::FigureError;

/// Draws the figure.
///
/// # Errors
/// When the traces were not recorded with a BVH.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    hierarchy::draw(input, d, Label::TitleBvh, "bvh")
}
