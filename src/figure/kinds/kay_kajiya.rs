//! `kay-kajiya` (lecture "Utilizarea de volume încadratoare (5)", algorithm.md §9 "Kay–Kajiya
//! slabs"): the Kay–Kajiya volume of one object — 4 pairs of parallel planes at 0°, 45°, 90°,
//! 135° in 2D (7 in 3D: the axes and the diagonals (±1, ±1, 1)), each placed tight around it —
//! with a ray that meets it and one that misses it, their per-slab intervals, entry
//! I = r(max t_i) and exit E = r(min t_e). Traced with `--accel bounds --bounds kdop`.

use super::slabs::{self, Slab};
use super::Input;
use crate::bounds::kdop::{normal, slab_count};
use crate::bounds::BoundingVolume;
use crate::canvas::Drawing;
use crate::figure::labels::Label;
use crate::figure::plane::Planar;
use crate::figure::FigureError;

/// The slab names: in 2D their angles (0°, 45°, 90°, 135°), in 3D their numbers.
fn name(dim: usize, k: usize) -> String {
    if dim == 2 {
        ["0°", "45°", "90°", "135°"][k % 4].to_owned()
    } else {
        (k + 1).to_string()
    }
}

/// Draws the figure.
///
/// # Errors
/// When the traces hold no k-DOP test of the object.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let Some(BoundingVolume::Kdop(k)) = slabs::focus_volume(input, "kay-kajiya")? else {
        return Err(FigureError("the object has no Kay–Kajiya volume (--bounds kdop)".into()));
    };
    let slabs: Vec<Slab<V>> = (0..slab_count::<V>())
        .map(|s| Slab { normal: normal::<V>(s), lo: k.lo[s], hi: k.hi[s], name: name(V::DIM, s) })
        .collect();
    slabs::draw(input, d, Label::TitleKayKajiya, &slabs)
}
