//! The image (algorithm.md §2, §5): a linear RGB buffer indexed by pixel `(i, j)` with row `j`
//! counted from the bottom; written as 8 bits per channel `round(255·clamp(c, 0, 1))`, no gamma,
//! with file row `Ny − 1 − j` (image files store the top row first).

use crate::scene::material::Rgb;
use rayon::iter::ParallelExtend;

/// An image, `width × height`, row 0 at the bottom, of pixels `P`: linear colours ([`Rgb`], the
/// default), or the 8-bit bytes a file stores (`[u8; 3]`), when nothing else will read them.
#[derive(Clone, Debug, PartialEq)]
pub struct Image<P = Rgb> {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `pixels[j·width + i]`, j from the bottom.
    pub pixels: Vec<P>,
}

/// What an image stores of a pixel's colour, and where a renderer traces a row of it.
pub trait Pixel: Copy + Send + Sync + 'static {
    /// Black.
    const BLACK: Self;
    /// The pixel of a linear colour.
    fn from_linear(c: Rgb) -> Self;
    /// Its 8-bit channels, §5's [`to_byte`] of each.
    fn bytes(self) -> [u8; 3];
    /// Where a row's colours are traced: `scratch` (as long as the row), whose colours
    /// [`Pixel::keep`] then converts into `row`.
    fn colours<'a>(_row: &'a mut [Self], scratch: &'a mut [Rgb]) -> &'a mut [Rgb] {
        scratch
    }
    /// The colours traced into `scratch` kept as the row's pixels.
    fn keep(row: &mut [Self], scratch: &[Rgb]) {
        for (pixel, colour) in row.iter_mut().zip(scratch) {
            *pixel = Self::from_linear(*colour);
        }
    }
}

impl Pixel for Rgb {
    const BLACK: Self = Rgb::BLACK;
    #[inline]
    fn from_linear(c: Rgb) -> Self {
        c
    }
    #[inline]
    fn bytes(self) -> [u8; 3] {
        self.0.map(to_byte)
    }
    /// The row itself: colours are traced in place, nothing copied.
    fn colours<'a>(row: &'a mut [Self], _scratch: &'a mut [Rgb]) -> &'a mut [Rgb] {
        row
    }
    /// Nothing to do: the row holds its colours already.
    fn keep(_row: &mut [Self], _scratch: &[Rgb]) {}
}

/// The 8-bit bytes alone: 3 bytes a pixel instead of 24, what a render that only writes a file
/// keeps (a 640x480 image's 7.4 MB of fresh pages cost its trace about 6 % in page faults).
impl Pixel for [u8; 3] {
    const BLACK: Self = [0; 3];
    #[inline]
    fn from_linear(c: Rgb) -> Self {
        c.bytes()
    }
    #[inline]
    fn bytes(self) -> [u8; 3] {
        self
    }
}

/// Half a step of the 8-bit scale.
const HALF: f64 = 0.5;

/// §5: `round(255·clamp(c, 0, 1))`; round half away from zero (0.5 → 128). A NaN would be a bug
/// upstream; it is written as 0 rather than panicking.
///
/// Computed without the clamp and the library's `round` (not an instruction of baseline x86-64),
/// with `x = 255·c`, as `⌊x + 0.5⌋` by Rust's saturating cast (which truncates, and gives 255 from
/// 255 up, every c ≥ 1 among them, and 0 for a negative sum or a NaN), and 0 whenever `x < 0.5`.
/// For 0.5 ≤ x ≤ 255 the sum `x + 0.5` is exact or rounds to a neighbour that is not an integer,
/// so its floor is `round(x)`; below 0.5 the sum could round up to 1.0 (at x = 0.5 − 2⁻⁵⁴),
/// which the comparison keeps from the byte. A render of bytes converts every pixel here:
/// converting inside the trace loop, Whitted's scene at 640x480 took 506.3 M instructions with
/// `clamp` and `round`, 503.3 M with this form (callgrind).
#[must_use]
#[inline]
pub fn to_byte(c: f64) -> u8 {
    let x = 255.0 * c;
    // x + 0.5 truncated by the saturating cast: ⌊·⌋ for a positive value, 255 from 255 up, 0 for
    // a NaN or a negative sum.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let byte = (x + HALF) as u8;
    if x < HALF {
        0
    } else {
        byte
    }
}

impl<P: Pixel> Image<P> {
    /// A black image, written by every thread of the current rayon pool at once: a large image's
    /// first-touch page faults are most of its allocation time, which a serial `vec!` would add
    /// to the serial part of every render.
    #[must_use]
    pub fn new(width: usize, height: usize) -> Self {
        let mut pixels = Vec::with_capacity(width * height);
        pixels.par_extend(rayon::iter::repeat_n(P::BLACK, width * height));
        Self { width, height, pixels }
    }
    /// The pixel `(i, j)`, j from the bottom.
    #[must_use]
    pub fn get(&self, i: usize, j: usize) -> P {
        self.pixels[j * self.width + i]
    }
    /// 8-bit RGB bytes in file order: file row `Ny − 1 − j` holds image row j.
    #[must_use]
    pub fn to_rgb8(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.width * self.height * 3);
        for file_row in 0..self.height {
            let j = self.height - 1 - file_row;
            for i in 0..self.width {
                out.extend(self.get(i, j).bytes());
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

    /// The definition, `round` of the library, half away from zero.
    fn by_definition(c: f64) -> u8 {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let byte = (255.0 * c.clamp(0.0, 1.0)).round() as u8;
        byte
    }

    #[test]
    fn bytes_equal_the_rounding_of_the_definition_at_every_half_and_its_neighbours() {
        // Each c whose 255·c lies at or near a half k + 0.5 (c = (k + 0.5)/255 and its four
        // neighbours either side), c = k and k + 0.5 themselves (past 1: the saturation), and the
        // two c just below 0.5/255.
        let below_half = 0.5_f64.next_down() / 255.0;
        let mut cases = vec![below_half, below_half.next_down()];
        for k in 0..=255 {
            let half = f64::from(k) + 0.5;
            cases.extend([half, f64::from(k), half / 255.0]);
            let (mut up, mut down) = (half / 255.0, half / 255.0);
            for _ in 0..4 {
                up = up.next_up();
                down = down.next_down();
                cases.extend([up, down]);
            }
        }
        assert_eq!(cases.len(), 2 + 256 * 11);
        for c in cases {
            assert_eq!(to_byte(c), by_definition(c), "c = {c:e}");
        }
    }

    proptest::proptest! {
        #[test]
        fn bytes_equal_the_rounding_of_the_definition(c in -0.5_f64..1.5) {
            proptest::prop_assert_eq!(to_byte(c), by_definition(c));
        }
    }

    #[test]
    fn a_byte_image_holds_the_bytes_of_the_colour_image() {
        let colours =
            Image { width: 2, height: 1, pixels: vec![Rgb([0.2, 0.5, 1.5]), Rgb([0.0, 0.9, -1.0])] };
        let bytes: Image<[u8; 3]> = Image {
            width: 2,
            height: 1,
            pixels: colours.pixels.iter().map(|c| Pixel::from_linear(*c)).collect(),
        };
        assert_eq!(bytes.to_rgb8(), colours.to_rgb8());
        assert_eq!(bytes.pixels, [[51, 128, 255], [0, 230, 0]]);
    }

    #[test]
    fn file_rows_are_flipped() {
        let mut img: Image = Image::new(1, 2);
        img.pixels[0] = Rgb::grey(1.0);
        assert_eq!(img.to_rgb8(), vec![0, 0, 0, 255, 255, 255]);
    }
}
