//! `slab-test` (lecture "Utilizarea de volume încadratoare (3), (4)", algorithm.md §9 "Axis-aligned
//! box (slab test)"): the box of one object, a ray that meets it (the lecture's red ray) and one
//! that misses it (the blue one), each crossing the planes x = xmin, x = xmax, y = ymin, … at
//! the recorded t, with the per-axis intervals [t_ix, t_ex] and the verdict
//! max(t_i) ≤ min(t_e). Traced with `--accel bounds --bounds aabb`.

use super::slabs::{self, axis_name, Slab};
use super::Input;
use crate::bounds::BoundingVolume;
use crate::canvas::Drawing;
use crate::figure::labels::Label;
use crate::figure::plane::Planar;
use crate::figure::FigureError;

/// Draws the figure.
///
/// # Errors
/// When the traces hold no box test of the object.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let Some(BoundingVolume::Aabb(b)) = slabs::focus_volume(input, "slab-test")? else {
        return Err(FigureError("the object has no box (--bounds aabb)".into()));
    };
    let slabs: Vec<Slab<V>> = (0..V::DIM)
        .map(|a| Slab {
            normal: V::axis(a),
            lo: b.min[a],
            hi: b.max[a],
            name: axis_name(a).to_owned(),
            row: a,
        })
        .collect();
    slabs::draw(input, d, Label::TitleSlabTest, &slabs)
}
