//! What each thing of a ray-tracing figure is drawn in: one colour per ray kind ([`RayRole`]),
//! and the strokes and sizes of objects, normals, lights, hit points and highlights, chosen from
//! the canvas's palette. Colour is never the only cue: blocked shadow rays are also dashed, and
//! normals are dashed construction lines.
//!
//! The canvas's own palette, strokes and sizes ([`crate::canvas::style`]) are re-exported here, so
//! that a figure names every colour and size through this one module.

pub use crate::canvas::style::*;

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
/// Radius of a light's marker, in reference pixels.
pub const LIGHT_RADIUS: f64 = 18.0;
/// The dash of construction lines: 18 px on, 12 px off.
pub const CONSTRUCTION_DASH: Dash = Dash { on: 18.0, off: 12.0 };
/// The dash of blocked shadow rays: 22 px on, 12 px off.
pub const BLOCKED_DASH: Dash = Dash { on: 22.0, off: 12.0 };
/// The dash of shadow rays stopped by an opaque object: 8 px on, 8 px off.
pub const OPAQUE_DASH: Dash = Dash { on: 8.0, off: 8.0 };

/// The prefix of every ray's tag ([`RayRole::tag`]): the lines a label keeps off unless it names
/// them ([`crate::canvas::Drawing::guard_lines`]).
pub const RAY_TAG: &str = "ray:";
/// The tag prefix of every object's outline (`object:2`): labels keep off the outlines of the
/// objects they do not name ([`crate::canvas::Drawing::guard_outlines`]).
pub const OBJECT_TAG: &str = "object:";
/// The tag of the arrow that maps one panel's point onto another's (pixel-uv's pixel centre →
/// window point): labels keep off its shaft and its head
/// ([`crate::canvas::Drawing::guard_strictly`]).
pub const MAPPING_TAG: &str = "mapping";
/// The tag of a surface normal drawn from a point: labels keep off it, even the point's own
/// name ([`crate::canvas::Drawing::guard_strictly`]).
pub const NORMAL_TAG: &str = "normal";

/// The least contrast against the white page ([`Rgba::contrast_on_white`]) that a tree node's
/// ring or fill must reach to be seen: 3:1, what WCAG 2.1 (success criterion 1.4.11, "Non-text
/// Contrast") asks of the graphical objects a reader needs. A node whose colours fall short
/// (a light grey ring, an orange one, a fill that clamps to white) gets a [`node_outline`].
pub const MIN_NODE_CONTRAST: f64 = 3.0;
/// The outline of a node whose own colours fall short of [`MIN_NODE_CONTRAST`]: thin, dark grey.
pub const NODE_OUTLINE: Pen = Pen { color: DARK_GREY, width: GRID_WIDTH, dash: None };

/// The outline a tree node of `fill` ringed with `ring` needs to stay visible on the white page:
/// [`NODE_OUTLINE`] when neither its fill nor its ring (if it strokes at all) reaches
/// [`MIN_NODE_CONTRAST`], else none (its own colours already stand out).
#[must_use]
pub fn node_outline(fill: Rgba, ring: Pen) -> Option<Pen> {
    let seen = |c: Rgba| c.contrast_on_white() >= MIN_NODE_CONTRAST;
    let ring_seen = ring.strokes() && seen(ring.color);
    (!ring_seen && !seen(fill)).then_some(NODE_OUTLINE)
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
    pub const fn style(self) -> Pen {
        let dash = match self {
            Self::BlockedShadow => Some(BLOCKED_DASH),
            Self::OpaqueShadow => Some(OPAQUE_DASH),
            _ => None,
        };
        Pen { color: self.color(), width: RAY_WIDTH, dash }
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
pub const fn object() -> Pen {
    Pen { color: OBJECT_STROKE, width: OBJECT_WIDTH, dash: None }
}

/// The stroke of a surface normal or other construction line: dark grey, dashed.
#[must_use]
pub const fn normal() -> Pen {
    Pen { color: NORMAL, width: CONSTRUCTION_WIDTH, dash: Some(CONSTRUCTION_DASH) }
}

/// The stroke of the view window (the lecture's "fereastra vizuală"): dark grey, half again as
/// wide as an object's outline, so it never reads as an object.
#[must_use]
pub const fn view_window() -> Pen {
    Pen { color: DARK_GREY, width: OBJECT_WIDTH * 1.5, dash: None }
}

/// A solid stroke of `color` at [`CONSTRUCTION_WIDTH`], for outlines of highlights and markers.
#[must_use]
pub const fn outline(color: Rgba) -> Pen {
    Pen { color, width: CONSTRUCTION_WIDTH, dash: None }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_node_gets_an_outline_only_when_its_colours_fade_into_the_page() {
        // White or light fills ringed in light grey, orange or yellow: outlined.
        for ring in [LIGHT_GREY, ORANGE, YELLOW] {
            assert_eq!(node_outline(WHITE, outline(ring)), Some(NODE_OUTLINE), "{ring:?}");
        }
        assert_eq!(node_outline(Rgba::rgb(0xE3, 0xE3, 0xE3), Pen::NONE), Some(NODE_OUTLINE));
        // A ring or a fill of enough contrast is seen on its own.
        assert_eq!(node_outline(WHITE, outline(BLUE)), None);
        assert_eq!(node_outline(BLUISH_GREEN, outline(LIGHT_GREY)), None);
        assert_eq!(node_outline(WHITE, outline(REDDISH_PURPLE)), None);
        // The outline itself is seen.
        assert!(NODE_OUTLINE.color.contrast_on_white() >= MIN_NODE_CONTRAST);
    }

    #[test]
    fn ray_roles_have_distinct_colours() {
        for (i, a) in RayRole::ALL.iter().enumerate() {
            for b in &RayRole::ALL[i + 1..] {
                assert_ne!(a.color(), b.color(), "{a:?} and {b:?}");
            }
            assert!(a.tag().starts_with(RAY_TAG), "{a:?}: labels keep off it");
        }
    }
}
