//! The 4 shared pixel corners (algorithm.md §8.1, "Uniform"): corner `(i, j)` sits at
//! `u = l + (r − l)·i/Nx`, `v = b + (t − b)·j/Ny`, an `m × n` image needs `(m + 1)(n + 1)` rays,
//! and a pixel is the mean of its 4 corners. Here also the integer lattice that refines the
//! corners for the adaptive method: point `(x, y) = (i·2^K + a, j·2^K + b)` is the corner
//! `(x/2^K, y/2^K)`, so the same corner gets the same bits at every K.
//!
//! `Lattice` maps lattice points to (u, v); `Axes` tabulates those u and v once per render;
//! `corner_mean` is a square's colour.

use crate::geom::Vector;
use crate::scene::camera::Camera;
use crate::scene::material::Rgb;

/// The sample lattice of an image: `2^K` lattice steps per pixel side, on 2 axes (a 3D scene's
/// image) or 1 (a 2D scene's image line, whose "squares" are intervals with 2 ends).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lattice {
    /// K, the deepest level.
    pub max_level: u32,
    /// `2^K`: lattice steps per pixel side.
    pub scale: u32,
    /// Columns `Nx`.
    pub nx: usize,
    /// Rows `Ny` (1 for a 2D scene).
    pub ny: usize,
    /// 2 for a 3D scene's image, 1 for a 2D scene's image line.
    dims: usize,
}

impl Lattice {
    /// The lattice of `camera`'s image with K = `max_level` (at most [`super::MAX_LEVEL`]).
    #[must_use]
    pub fn new<V: Vector>(camera: &Camera<V>, max_level: u32) -> Self {
        Self { max_level, scale: 1 << max_level, nx: camera.nx, ny: camera.ny, dims: V::DIM - 1 }
    }
    /// 2 (squares with 4 corners) or 1 (intervals with 2 ends).
    #[must_use]
    pub fn dims(self) -> usize {
        self.dims
    }
    /// Points on one lattice row: `Nx·2^K + 1`.
    #[must_use]
    pub fn row_len(self) -> usize {
        self.nx * self.scale as usize + 1
    }
    /// The global point of pixel `(i, j)`'s local point `(a, b)`: `(i·2^K + a, j·2^K + b)`
    /// (`b = 0` and `y = 0` on a 2D scene's line).
    #[must_use]
    pub fn global(self, i: usize, j: usize, a: u32, b: u32) -> (u64, u64) {
        let s = u64::from(self.scale);
        (i as u64 * s + u64::from(a), j as u64 * s + u64::from(b))
    }
    /// The window point of lattice point `(x, y)`: `u = l + (r − l)·(x/2^K)/Nx`,
    /// `v = b + (t − b)·(y/2^K)/Ny` (§8.1 with the fractional corner `x/2^K`, exact because
    /// `2^K` is a power of two; `v = 0` in 2D).
    #[must_use]
    pub fn uv<V: Vector>(self, camera: &Camera<V>, x: u64, y: u64) -> (f64, f64) {
        let s = f64::from(self.scale);
        (camera.u_at(x as f64 / s), camera.v_at(y as f64 / s))
    }
}

/// The window coordinates of every lattice column and row: `u(x)` for `x = 0 … Nx·2^K` and
/// `v(y)` for `y = 0 … Ny·2^K` (2D: `v = 0`), each [`Lattice::uv`] bit for bit, computed once per
/// render so that a sample reads two numbers instead of dividing four times (`x/2^K`, `/Nx`,
/// `y/2^K`, `/Ny`). Memory: 8 bytes a lattice column and row, where every shared edge row takes
/// 32 bytes a lattice column.
#[derive(Debug)]
pub struct Axes {
    u: Vec<f64>,
    v: Vec<f64>,
}

impl Axes {
    /// The coordinates of `lattice`'s columns and rows on `camera`'s window.
    #[must_use]
    pub fn new<V: Vector>(lattice: Lattice, camera: &Camera<V>) -> Self {
        let rows = lattice.ny as u64 * u64::from(lattice.scale) + 1;
        let u = (0..lattice.row_len() as u64).map(|x| lattice.uv(camera, x, 0).0).collect();
        let v = (0..rows).map(|y| lattice.uv(camera, 0, y).1).collect();
        Self { u, v }
    }
    /// The window point `(u, v)` of lattice point `(x, y)`.
    #[must_use]
    #[inline]
    pub fn uv(&self, x: u64, y: u64) -> (f64, f64) {
        // x ≤ Nx·2^K and y ≤ Ny·2^K index the tables, whose lengths are usize.
        #[allow(clippy::cast_possible_truncation)]
        (self.u[x as usize], self.v[y as usize])
    }
}

/// §8.1: the colour of a pixel (or of a leaf square, §8.2) is the mean of its corners,
/// `(C1 + C2 + C3 + C4)/4` (2D: `(C1 + C2)/2`), summed in the order given (no corners: black).
#[must_use]
#[inline]
pub fn corner_mean<'a, I>(corners: I) -> Rgb
where
    I: IntoIterator<Item = &'a Rgb>,
    I::IntoIter: ExactSizeIterator,
{
    let mut corners = corners.into_iter();
    let n = corners.len();
    let mut sum = corners.next().copied().unwrap_or_default();
    for c in corners {
        sum += *c;
    }
    // 1/2 and 1/4 are exact: this is the division by the number of corners.
    sum * (1.0 / n.max(1) as f64)
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::scene::load::load_str;
    use crate::scene::AnyScene;

    fn camera() -> Camera<glam::DVec3> {
        let text = r#"{"camera": {"eye": [0,0,5], "center": [0,0,0],
            "window": {"l": -0.6666666666666666, "r": 0.6666666666666666, "b": -0.5, "t": 0.5},
            "resolution": [7, 3]}}"#;
        match load_str(text) {
            Ok(AnyScene::Space(s)) => s.camera,
            _ => panic!("scene"),
        }
    }

    #[test]
    fn a_corner_has_the_same_bits_at_every_level() {
        let cam = camera();
        for k in 0..=8 {
            let lattice = Lattice::new(&cam, k);
            for (i, j) in [(0, 0), (3, 1), (7, 3)] {
                let (x, y) = lattice.global(i, j, 0, 0);
                let (u, v) = lattice.uv(&cam, x, y);
                assert_eq!(u, cam.u_at(i as f64));
                assert_eq!(v, cam.v_at(j as f64));
            }
        }
    }

    #[test]
    fn the_axes_hold_the_lattice_coordinates_bit_for_bit() {
        let cam = camera();
        for k in [0, 2, 5] {
            let lattice = Lattice::new(&cam, k);
            let axes = Axes::new(lattice, &cam);
            let (last_x, last_y) = lattice.global(lattice.nx, lattice.ny, 0, 0);
            assert_eq!(axes.u.len() as u64, last_x + 1);
            assert_eq!(axes.v.len() as u64, last_y + 1);
            for x in 0..=last_x {
                for y in 0..=last_y {
                    assert_eq!(axes.uv(x, y), lattice.uv(&cam, x, y));
                }
            }
        }
    }

    #[test]
    fn the_middle_point_is_the_pixel_centre() {
        let cam = camera();
        let lattice = Lattice::new(&cam, 1);
        let (x, y) = lattice.global(3, 1, 1, 1);
        assert_eq!(lattice.uv(&cam, x, y), cam.pixel_center(3, 1));
    }

    #[test]
    fn the_mean_of_corners() {
        let c = [Rgb([1.0, 0.0, 0.5]), Rgb([0.0, 1.0, 0.5]), Rgb([1.0, 1.0, 0.5]), Rgb([0.0, 0.0, 0.5])];
        assert_eq!(corner_mean(&c), Rgb([0.5, 0.5, 0.5]));
        assert_eq!(corner_mean(&c[..2]), Rgb([0.5, 0.5, 0.5]));
    }
}
