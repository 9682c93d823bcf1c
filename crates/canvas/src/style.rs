//! The canvas's look: colours (the Okabe–Ito palette), strokes ([`Pen`], [`Dash`]) and the
//! sizes of text, margins, arrow heads and dots, all at slide scale.
//!
//! Every size here is in *reference pixels*: pixels of the [`REFERENCE_WIDTH`] ×
//! [`REFERENCE_HEIGHT`] (1920 × 1080) slide canvas. A drawing of another size scales them all by
//! one factor ([`px_scale`]), so a figure looks the same on a slide and in a thumbnail.
//!
//! The palette is Okabe and Ito's eight colours ("Color Universal Design", 2008), chosen so that
//! the lines of a figure stay apart for readers with any common colour-vision deficiency. What
//! each thing of a figure is drawn in is the figure's choice (`figure::style`), not the canvas's.

/// Width of the reference slide canvas, in pixels.
pub const REFERENCE_WIDTH: u32 = 1920;
/// Height of the reference slide canvas, in pixels.
pub const REFERENCE_HEIGHT: u32 = 1080;

/// The factor from reference pixels to the pixels of a `width` × `height` canvas:
/// `min(width / 1920, height / 1080)`, so the smaller side decides and nothing outgrows the canvas.
#[must_use]
pub fn px_scale(width: u32, height: u32) -> f64 {
    let sx = f64::from(width) / f64::from(REFERENCE_WIDTH);
    let sy = f64::from(height) / f64::from(REFERENCE_HEIGHT);
    sx.min(sy)
}

/// A colour in sRGB with straight (not premultiplied) alpha, 8 bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rgba {
    /// Red, 0–255.
    pub r: u8,
    /// Green, 0–255.
    pub g: u8,
    /// Blue, 0–255.
    pub b: u8,
    /// Opacity, 0 (transparent) – 255 (opaque).
    pub a: u8,
}

impl Rgba {
    /// An opaque colour.
    #[must_use]
    pub const fn rgb(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b, a: 255 }
    }

    /// The same colour with opacity `alpha` in [0, 1] (clamped; NaN counts as 0).
    #[must_use]
    pub fn with_alpha(self, alpha: f64) -> Self {
        let a = if alpha.is_nan() { 0.0 } else { alpha.clamp(0.0, 1.0) };
        Self { a: unit_to_u8(a), ..self }
    }

    /// The opacity as a fraction in [0, 1].
    #[must_use]
    pub fn opacity(self) -> f64 {
        f64::from(self.a) / 255.0
    }

    /// `#rrggbb`, the form SVG and CSS read (the alpha goes into a separate opacity attribute).
    #[must_use]
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }

    /// The contrast ratio of this colour, laid over a white page at its opacity, against the
    /// page: `(1 + 0.05) / (L + 0.05)` in WCAG 2.1's definition, where the relative luminance is
    /// `L = 0.2126·R + 0.7152·G + 0.0722·B` of the linear channels ([`Self::linear_on_white`]).
    /// 1 for white (or transparent), 21 for black.
    #[must_use]
    pub fn contrast_on_white(self) -> f64 {
        let [r, g, b] = self.linear_on_white();
        let luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        1.05 / (luminance + 0.05)
    }

    /// The linear channels of this colour laid over a white page at its opacity: each sRGB value
    /// `c` decoded to `c/12.92` when `c ≤ 0.04045` and `((c + 0.055)/1.055)^2.4` above.
    fn linear_on_white(self) -> [f64; 3] {
        let alpha = self.opacity();
        let linear = |byte: u8| {
            // Composited over white: the page shows through what the colour leaves.
            let c = alpha * f64::from(byte) / 255.0 + (1.0 - alpha);
            if c <= 0.040_45 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        [linear(self.r), linear(self.g), linear(self.b)]
    }

    /// CIE L\*a\*b\* of this colour laid over white (sRGB, white point D65): `XYZ` from the
    /// linear channels by sRGB's matrix, then `L* = 116·f(Y/Yn) − 16`,
    /// `a* = 500·(f(X/Xn) − f(Y/Yn))`, `b* = 200·(f(Y/Yn) − f(Z/Zn))`, where `f(t) = t^(1/3)`
    /// above `(6/29)³` and `t/(3·(6/29)²) + 4/29` below.
    #[must_use]
    pub fn lab(self) -> [f64; 3] {
        const WHITE: [f64; 3] = [0.950_47, 1.0, 1.088_83];
        const DELTA: f64 = 6.0 / 29.0;
        let [r, g, b] = self.linear_on_white();
        let xyz = [
            0.412_4 * r + 0.357_6 * g + 0.180_5 * b,
            0.212_6 * r + 0.715_2 * g + 0.072_2 * b,
            0.019_3 * r + 0.119_2 * g + 0.950_5 * b,
        ];
        let f = |k: usize| {
            let t = xyz[k] / WHITE[k];
            if t > DELTA.powi(3) {
                t.cbrt()
            } else {
                t / (3.0 * DELTA * DELTA) + 4.0 / 29.0
            }
        };
        [116.0 * f(1) - 16.0, 500.0 * (f(0) - f(1)), 200.0 * (f(1) - f(2))]
    }

    /// The CIE76 colour difference of two colours: `ΔE*ab = |Lab₁ − Lab₂|`, the distance of
    /// their [`Self::lab`] triples (about 2.3 is just noticeable side by side).
    #[must_use]
    pub fn delta_e76(self, other: Self) -> f64 {
        let (a, b) = (self.lab(), other.lab());
        a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
    }
}

/// `round(255·v)` for `v` in [0, 1], as a byte.
fn unit_to_u8(v: f64) -> u8 {
    // The clamp keeps the value in 0..=255, so the cast neither truncates nor loses a sign.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let byte = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    byte
}

/// Okabe–Ito black.
pub const BLACK: Rgba = Rgba::rgb(0x00, 0x00, 0x00);
/// Okabe–Ito orange.
pub const ORANGE: Rgba = Rgba::rgb(0xE6, 0x9F, 0x00);
/// Okabe–Ito sky blue.
pub const SKY_BLUE: Rgba = Rgba::rgb(0x56, 0xB4, 0xE9);
/// Okabe–Ito bluish green.
pub const BLUISH_GREEN: Rgba = Rgba::rgb(0x00, 0x9E, 0x73);
/// Okabe–Ito yellow.
pub const YELLOW: Rgba = Rgba::rgb(0xF0, 0xE4, 0x42);
/// Okabe–Ito blue.
pub const BLUE: Rgba = Rgba::rgb(0x00, 0x72, 0xB2);
/// Okabe–Ito vermillion.
pub const VERMILLION: Rgba = Rgba::rgb(0xD5, 0x5E, 0x00);
/// Okabe–Ito reddish purple.
pub const REDDISH_PURPLE: Rgba = Rgba::rgb(0xCC, 0x79, 0xA7);
/// White: the background, legend box and text halos.
pub const WHITE: Rgba = Rgba::rgb(0xFF, 0xFF, 0xFF);
/// Dark grey: construction lines (normals, the camera window, axes).
pub const DARK_GREY: Rgba = Rgba::rgb(0x4D, 0x4D, 0x4D);
/// Light grey: grids, cells and other background structure.
pub const LIGHT_GREY: Rgba = Rgba::rgb(0xBB, 0xBB, 0xBB);

/// Text colour: near-black, a little softer than the object outlines.
pub const TEXT: Rgba = Rgba::rgb(0x1A, 0x1A, 0x1A);

/// Width of a grid or cell line, in reference pixels.
pub const GRID_WIDTH: f64 = 2.0;
/// Length of an arrow head, tip to base, in reference pixels, for a thin stroke.
pub const ARROW_HEAD: f64 = 30.0;
/// A thick stroke's arrow head is at least this many stroke widths long, so the head stays wider
/// than the shaft.
pub const ARROW_HEAD_PER_WIDTH: f64 = 4.5;

/// The length of the arrow head of a stroke `width` reference pixels wide, in reference pixels:
/// [`ARROW_HEAD`], or [`ARROW_HEAD_PER_WIDTH`] widths when that is longer.
#[must_use]
pub fn arrow_head(width: f64) -> f64 {
    ARROW_HEAD.max(ARROW_HEAD_PER_WIDTH * width)
}
/// Radius of a dot ([`crate::Drawing::dot`]: a hit point's marker), in reference pixels.
pub const DOT_RADIUS: f64 = 10.0;
/// Width of the white halo around labels, in reference pixels (the full stroke width).
pub const HALO_WIDTH: f64 = 9.0;
/// Padding between the canvas edge and anything drawn, in reference pixels.
pub const MARGIN: f64 = 28.0;

/// The size class of a piece of text; [`TextSize::px`] gives its font size (the em size).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TextSize {
    /// Secondary annotations: tick values, cell indices, small numbers (30 px).
    Small,
    /// Legend entries and captions (36 px).
    Body,
    /// Labels on the diagram: N, L, θ_i, n_1 (40 px).
    Label,
    /// The figure's title (52 px, bold).
    Title,
}

impl TextSize {
    /// Font size in reference pixels (the em size, as CSS `font-size`). Body text is 36 px on the
    /// 1080-pixel-high slide, so its capitals are about 26 px and a whole line about 49 px tall.
    #[must_use]
    pub const fn px(self) -> f64 {
        match self {
            Self::Small => 30.0,
            Self::Body => 36.0,
            Self::Label => 40.0,
            Self::Title => 52.0,
        }
    }
}

/// A dash pattern, in reference pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dash {
    /// Length of each drawn stretch.
    pub on: f64,
    /// Length of each gap.
    pub off: f64,
}

/// How an item is stroked (and, for text, coloured).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pen {
    /// The stroke colour (the text colour for text, the fill for a dot without fill).
    pub color: Rgba,
    /// The stroke width in reference pixels; 0 draws no stroke.
    pub width: f64,
    /// The dash pattern, or `None` for a solid line.
    pub dash: Option<Dash>,
}

impl Pen {
    /// No stroke at all: for shapes drawn only by their fill.
    pub const NONE: Self = Self { color: Rgba { r: 0, g: 0, b: 0, a: 0 }, width: 0.0, dash: None };

    /// A solid stroke.
    #[must_use]
    pub const fn solid(color: Rgba, width: f64) -> Self {
        Self { color, width, dash: None }
    }

    /// The same stroke, dashed.
    #[must_use]
    pub const fn dashed(self, dash: Dash) -> Self {
        Self { dash: Some(dash), ..self }
    }

    /// The same stroke at another width.
    #[must_use]
    pub const fn with_width(self, width: f64) -> Self {
        Self { width, ..self }
    }

    /// The same stroke in another colour.
    #[must_use]
    pub const fn with_color(self, color: Rgba) -> Self {
        Self { color, ..self }
    }

    /// Whether this style draws a visible stroke.
    #[must_use]
    pub fn strokes(&self) -> bool {
        self.width > 0.0 && self.color.a > 0
    }
}

/// The stroke of a grid or cell boundary: thin light grey.
#[must_use]
pub const fn grid() -> Pen {
    Pen { color: LIGHT_GREY, width: GRID_WIDTH, dash: None }
}

/// The stroke of a label's leader (a label moved away from what it names): thin dark grey.
#[must_use]
pub const fn leader() -> Pen {
    Pen { color: DARK_GREY, width: GRID_WIDTH, dash: None }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn scale_is_one_on_the_reference_canvas_and_follows_the_smaller_side() {
        assert!((px_scale(1920, 1080) - 1.0).abs() < 1e-12);
        assert!((px_scale(960, 1080) - 0.5).abs() < 1e-12);
        assert!((px_scale(3840, 1080) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn body_text_is_slide_sized() {
        // "Body text at least 28 px tall" on the 1920×1080 canvas.
        for size in [TextSize::Small, TextSize::Body, TextSize::Label, TextSize::Title] {
            assert!(size.px() >= 28.0, "{size:?}");
        }
    }

    #[test]
    fn alpha_and_hex() {
        assert_eq!(BLUE.hex(), "#0072b2");
        assert_eq!(BLUE.with_alpha(0.5).a, 128);
        assert_eq!(BLUE.with_alpha(f64::NAN).a, 0);
        assert!((WHITE.opacity() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn contrast_on_white_follows_wcag() {
        assert!((BLACK.contrast_on_white() - 21.0).abs() < 1e-9);
        assert!((WHITE.contrast_on_white() - 1.0).abs() < 1e-12);
        assert!((BLACK.with_alpha(0.0).contrast_on_white() - 1.0).abs() < 1e-12);
        // #777777 is the usual example of a grey just under 4.5:1 (4.48).
        assert!((Rgba::rgb(0x77, 0x77, 0x77).contrast_on_white() - 4.48).abs() < 0.01);
        // Half-transparent black (alpha 128/255) is about #7F7F7F on white.
        let half = BLACK.with_alpha(0.5).contrast_on_white();
        assert!((half - Rgba::rgb(0x7F, 0x7F, 0x7F).contrast_on_white()).abs() < 0.01, "{half}");
        assert!(LIGHT_GREY.contrast_on_white() < 3.0 && DARK_GREY.contrast_on_white() > 3.0);
    }

    #[test]
    fn lab_and_delta_e_follow_cie() {
        let near = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 0.05);
        assert!(near(WHITE.lab(), [100.0, 0.0, 0.0]), "{:?}", WHITE.lab());
        assert!(near(BLACK.lab(), [0.0, 0.0, 0.0]), "{:?}", BLACK.lab());
        // sRGB's red and green in CIE L*a*b* (D65), as the usual converters print them.
        let red = Rgba::rgb(0xFF, 0, 0).lab();
        assert!(near(red, [53.24, 80.09, 67.20]), "{red:?}");
        let green = Rgba::rgb(0, 0xFF, 0).lab();
        assert!(near(green, [87.73, -86.18, 83.18]), "{green:?}");
        assert!((BLACK.delta_e76(WHITE) - 100.0).abs() < 0.05);
        assert_eq!(BLUE.delta_e76(BLUE), 0.0);
    }
}

/// The strokes the canvas's own tests draw with: colours and widths, nothing of rays.
#[cfg(test)]
pub(crate) mod test_strokes {
    use super::{Dash, Pen, Rgba, BLACK, BLUE, BLUISH_GREEN, DARK_GREY, SKY_BLUE, VERMILLION};

    pub(crate) const BLUE_LINE: Pen = Pen::solid(BLUE, 6.0);
    pub(crate) const RED_LINE: Pen = Pen::solid(VERMILLION, 6.0);
    pub(crate) const GREEN_LINE: Pen = Pen::solid(BLUISH_GREEN, 6.0);
    pub(crate) const OUTLINE: Pen = Pen::solid(BLACK, 4.0);
    pub(crate) const DASHED: Pen = Pen::solid(DARK_GREY, 3.5).dashed(Dash { on: 18.0, off: 12.0 });
    pub(crate) const FILL: Rgba = Rgba { a: 64, ..SKY_BLUE };
}
