//! `kay-kajiya` (lecture "Utilizarea de volume încadratoare (5)", algorithm.md §9 "Kay–Kajiya
//! slabs"): the Kay–Kajiya volume of one object — 4 pairs of parallel planes inclined at 0°, 45°,
//! 90°, 135° to the horizontal in 2D, named so as the lecture does (not by their normals) (7 in 3D: the axes and the diagonals (±1, ±1, 1)), each placed tight around it —
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

/// A 2D slab's planes' inclination to the horizontal, in whole degrees in [0°, 180°): the lecture
/// names the pairs so ("înclinate la 0, 45, 90, 135 grade față de planul orizontal"), while the
/// volume stores each pair by its normal n, which is perpendicular to them: the inclination is
/// `atan2(n_y, n_x) − 90°`, taken mod 180°.
fn inclination(n: glam::DVec2) -> u32 {
    let degrees = (n.y.atan2(n.x).to_degrees() - 90.0).rem_euclid(180.0);
    // The normals are the 4 of the convention, so this is 0, 45, 90 or 135 up to rounding.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let whole = degrees.round() as u32;
    whole % 180
}

/// The slab names and rows: in 2D the planes' inclinations (0°, 45°, 90°, 135°) in that order,
/// in 3D their numbers.
fn name_and_row<V: Planar>(k: usize) -> (String, usize) {
    if V::DIM == 2 {
        let n = normal::<V>(k);
        let degrees = inclination(glam::DVec2::new(n[0], n[1]));
        (format!("{degrees}°"), (degrees / 45) as usize)
    } else {
        ((k + 1).to_string(), k)
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
        .map(|s| {
            let (name, row) = name_and_row::<V>(s);
            Slab { normal: normal::<V>(s), lo: k.lo[s], hi: k.hi[s], name, row }
        })
        .collect();
    slabs::draw(input, d, Label::TitleKayKajiya, &slabs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn pairs_are_named_by_the_planes_inclination_not_the_normals() {
        // Normal along x: vertical planes, 90°; along y: horizontal, 0°.
        assert_eq!(inclination(DVec2::new(1.0, 0.0)), 90);
        assert_eq!(inclination(DVec2::new(0.0, 1.0)), 0);
        assert_eq!(inclination(DVec2::new(1.0, 1.0)), 135);
        assert_eq!(inclination(DVec2::new(-1.0, 1.0)), 45);
        let names: Vec<String> = (0..4).map(|k| name_and_row::<DVec2>(k).0).collect();
        assert_eq!(names, ["90°", "135°", "0°", "45°"]);
    }
}
