//! The image (algorithm.md §2, §5): a linear RGB buffer indexed by pixel `(i, j)` with row `j`
//! counted from the bottom; written as 8 bits per channel `round(255·clamp(c, 0, 1))`, no gamma,
//! with file row `Ny − 1 − j` (image files store the top row first).

use crate::scene::material::Rgb;
use rayon::iter::ParallelExtend;

/// Linear colours, `width × height`, row 0 at the bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `pixels[j·width + i]`, j from the bottom.
    pub pixels: Vec<Rgb>,
}

/// §5: `round(255·clamp(c, 0, 1))`; round half away from zero (0.5 → 128). A NaN would be a bug
/// upstream; it is written as 0 rather than panicking.
#[must_use]
pub fn to_byte(c: f64) -> u8 {
    let scaled = (255.0 * c.clamp(0.0, 1.0)).round();
    // The clamp keeps the value in [0, 255].
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let byte = scaled as u8;
    byte
}

impl Image {
    /// A black image, written by every thread of the current rayon pool at once: a large image's
    /// first-touch page faults are most of its allocation time, which a serial `vec!` would add
    /// to the serial part of every render.
    #[must_use]
    pub fn new(width: usize, height: usize) -> Self {
        let mut pixels = Vec::with_capacity(width * height);
        pixels.par_extend(rayon::iter::repeat_n(Rgb::BLACK, width * height));
        Self { width, height, pixels }
    }
    /// The colour of pixel `(i, j)`, j from the bottom.
    #[must_use]
    pub fn get(&self, i: usize, j: usize) -> Rgb {
        self.pixels[j * self.width + i]
    }
    /// 8-bit RGB bytes in file order: file row `Ny − 1 − j` holds image row j.
    #[must_use]
    pub fn to_rgb8(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.width * self.height * 3);
        for file_row in 0..self.height {
            let j = self.height - 1 - file_row;
            for i in 0..self.width {
                out.extend(self.get(i, j).0.map(to_byte));
            }
        }
        out
    }
    /// 8-bit RGBA bytes in file order (top row first), alpha 255: the pixels of the command line's
    /// PNG as a browser's `ImageData` takes them.
    #[must_use]
    pub fn to_rgba8(&self) -> Vec<u8> {
        self.to_rgb8().chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], u8::MAX]).collect()
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn bytes_round_half_away_and_clamp() {
        assert_eq!(to_byte(0.5), 128);
        assert_eq!(to_byte(0.0), 0);
        assert_eq!(to_byte(128.0 / 255.0 - 0.5 / 255.0), 128);
        assert_eq!(to_byte(-1.0), 0);
        assert_eq!(to_byte(2.0), 255);
        assert_eq!(to_byte(f64::NAN), 0);
    }

    #[test]
    fn file_rows_are_flipped() {
        let mut img = Image::new(1, 2);
        img.pixels[0] = Rgb::grey(1.0);
        assert_eq!(img.to_rgb8(), vec![0, 0, 0, 255, 255, 255]);
    }
}
