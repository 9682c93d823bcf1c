//! The figures' look: a colour-blind-safe palette (Okabe–Ito), one colour per ray kind, and stroke
//! widths and text sizes at slide scale.
//!
//! Every size here is in *reference pixels*: pixels of the [`REFERENCE_WIDTH`] ×
//! [`REFERENCE_HEIGHT`] (1920 × 1080) slide canvas. A drawing of another size scales them all by
//! one factor ([`px_scale`]), so a figure looks the same on a slide and in a thumbnail.
//!
//! The palette is Okabe and Ito's eight colours ("Color Universal Design", 2008), chosen so that
//! the ray kinds stay apart for readers with any common colour-vision deficiency. Colour is never
//! the only cue: blocked shadow rays are also dashed, and normals are dashed construction lines.

use super::drawing::{Dash, Style};

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
/// Object outlines (circles, boxes, polygons of the scene).
pub const OBJECT_STROKE: Rgba = BLACK;
/// Object interiors: sky blue, mostly transparent, so rays inside an object stay visible.
pub const OBJECT_FILL: Rgba = Rgba { a: 64, ..SKY_BLUE };
/// Surface normals and other construction lines (drawn dashed, see [`normal`]).
pub const NORMAL: Rgba = DARK_GREY;
/// Highlights: the current cell or node, the pixel under study (a fill with a black outline).
pub const HIGHLIGHT: Rgba = YELLOW;
/// Lights (drawn as a yellow dot with a black outline).
pub const LIGHT: Rgba = YELLOW;
/// Hit points.
pub const HIT: Rgba = BLACK;

/// Width of a ray, in reference pixels.
pub const RAY_WIDTH: f64 = 6.0;
/// Width of an object outline, in reference pixels.
pub const OBJECT_WIDTH: f64 = 4.0;
/// Width of a construction line (normals, window edges), in reference pixels.
pub const CONSTRUCTION_WIDTH: f64 = 3.5;
/// Width of a grid or cell line, in reference pixels.
pub const GRID_WIDTH: f64 = 2.0;
/// Length of an arrow head, tip to base, in reference pixels.
pub const ARROW_HEAD: f64 = 30.0;
/// Radius of a hit-point marker, in reference pixels.
pub const DOT_RADIUS: f64 = 10.0;
/// Radius of a light's marker, in reference pixels.
pub const LIGHT_RADIUS: f64 = 18.0;
/// The dash of construction lines: 18 px on, 12 px off.
pub const CONSTRUCTION_DASH: Dash = Dash { on: 18.0, off: 12.0 };
/// The dash of blocked shadow rays: 22 px on, 12 px off.
pub const BLOCKED_DASH: Dash = Dash { on: 22.0, off: 12.0 };
/// The dash of shadow rays stopped by an opaque object: 8 px on, 8 px off.
pub const OPAQUE_DASH: Dash = Dash { on: 8.0, off: 8.0 };
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

/// Which ray of the recursion a line shows; each has its own colour (and blocked shadows a dash).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RayRole {
    /// A primary ray, from the eye through a pixel: blue.
    Primary,
    /// A reflected ray R: vermillion.
    Reflected,
    /// A transmitted (refracted) ray T: bluish green.
    Transmitted,
    /// A shadow ray that reaches its light: orange.
    Shadow,
    /// A shadow ray attenuated by transparent occluders (0 < s < 1): reddish purple, dashed.
    BlockedShadow,
    /// A shadow ray stopped by an opaque occluder (s = 0): black, short dashes.
    OpaqueShadow,
}

impl RayRole {
    /// Every role, in the order a legend lists them.
    pub const ALL: [Self; 6] = [
        Self::Primary,
        Self::Reflected,
        Self::Transmitted,
        Self::Shadow,
        Self::BlockedShadow,
        Self::OpaqueShadow,
    ];

    /// A shadow ray's role by its factor s = Π kt of what it met: free (nothing met), attenuated
    /// by transparent objects (0 < s < 1), or stopped by an opaque one (s = 0).
    #[must_use]
    pub fn shadow(s: f64, met_something: bool) -> Self {
        if !met_something {
            Self::Shadow
        } else if s > 0.0 {
            Self::BlockedShadow
        } else {
            Self::OpaqueShadow
        }
    }

    /// The role's colour.
    #[must_use]
    pub const fn color(self) -> Rgba {
        match self {
            Self::Primary => BLUE,
            Self::Reflected => VERMILLION,
            Self::Transmitted => BLUISH_GREEN,
            Self::Shadow => ORANGE,
            Self::BlockedShadow => REDDISH_PURPLE,
            Self::OpaqueShadow => BLACK,
        }
    }

    /// The role's stroke: its colour at [`RAY_WIDTH`], dashed for a blocked shadow ray.
    #[must_use]
    pub const fn style(self) -> Style {
        let dash = match self {
            Self::BlockedShadow => Some(BLOCKED_DASH),
            Self::OpaqueShadow => Some(OPAQUE_DASH),
            _ => None,
        };
        Style { color: self.color(), width: RAY_WIDTH, dash }
    }

    /// A short tag for display-list items of this role: `ray:primary`, `ray:reflected`, …
    #[must_use]
    pub const fn tag(self) -> &'static str {
        match self {
            Self::Primary => "ray:primary",
            Self::Reflected => "ray:reflected",
            Self::Transmitted => "ray:transmitted",
            Self::Shadow => "ray:shadow",
            Self::BlockedShadow => "ray:shadow-blocked",
            Self::OpaqueShadow => "ray:shadow-opaque",
        }
    }
}

/// The stroke of a scene object's outline.
#[must_use]
pub const fn object() -> Style {
    Style { color: OBJECT_STROKE, width: OBJECT_WIDTH, dash: None }
}

/// The stroke of a surface normal or other construction line: dark grey, dashed.
#[must_use]
pub const fn normal() -> Style {
    Style { color: NORMAL, width: CONSTRUCTION_WIDTH, dash: Some(CONSTRUCTION_DASH) }
}

/// The stroke of a grid or cell boundary: thin light grey.
#[must_use]
pub const fn grid() -> Style {
    Style { color: LIGHT_GREY, width: GRID_WIDTH, dash: None }
}

/// The stroke of a label's leader (a label moved away from what it names): thin dark grey.
#[must_use]
pub const fn leader() -> Style {
    Style { color: DARK_GREY, width: GRID_WIDTH, dash: None }
}

/// A solid stroke of `color` at [`CONSTRUCTION_WIDTH`], for outlines of highlights and markers.
#[must_use]
pub const fn outline(color: Rgba) -> Style {
    Style { color, width: CONSTRUCTION_WIDTH, dash: None }
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
    fn ray_roles_have_distinct_colours() {
        for (i, a) in RayRole::ALL.iter().enumerate() {
            for b in &RayRole::ALL[i + 1..] {
                assert_ne!(a.color(), b.color(), "{a:?} and {b:?}");
            }
        }
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
}
