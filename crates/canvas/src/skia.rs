//! The raster back end: a [`Drawing`] → a tiny-skia `Pixmap` → PNG bytes.
//!
//! White background, anti-aliased. World points go through the drawing's one [`Transform`]
//! (uniform scale, y flipped) and are narrowed from f64 to f32 in one function, `px`; widths,
//! dashes, arrow heads, dot radii and text sizes are reference pixels times the drawing's
//! `px_scale`. Shapes are clipped to the plot area;
//! labels are not, and each gets a white halo (a stroke of its glyph outlines under the fill).

use std::fmt;

use glam::DVec2;
use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Mask, Paint, Path, PathBuilder, Pixmap, Rect, Stroke, StrokeDash,
    Transform as SkTransform,
};

use super::style::{self, Pen, Rgba};
use super::text::{self, PathSink, Weight};
use super::{ArrowPx, Drawing, LegendBox, LegendIcon, Mark, PageLayout, PlacedLine, Transform};

/// Why a drawing could not become a PNG.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SkiaError {
    /// tiny-skia could not allocate a canvas of this size (too large).
    Canvas {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// The PNG encoder failed (its message).
    Encode(String),
}

impl fmt::Display for SkiaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Canvas { width, height } => {
                write!(f, "cannot allocate a {width}×{height} canvas")
            }
            Self::Encode(message) => write!(f, "PNG encoding failed: {message}"),
        }
    }
}

impl std::error::Error for SkiaError {}

/// Draws `drawing` into a new pixmap of its size.
///
/// # Errors
/// [`SkiaError::Canvas`] when the canvas is too large to allocate.
pub fn render(drawing: &Drawing) -> Result<Pixmap, SkiaError> {
    let (width, height) = (drawing.width(), drawing.height());
    let mut pixmap = Pixmap::new(width, height).ok_or(SkiaError::Canvas { width, height })?;
    pixmap.fill(Color::WHITE);
    let frame = drawing.frame();
    let mut canvas = Canvas { pixmap: &mut pixmap, tf: frame.transform, clip: None };
    canvas.clip = plot_mask(&frame, width, height);
    for item in &drawing.items {
        canvas.item(&item.pen, &item.mark);
    }
    canvas.chrome(drawing, &frame);
    Ok(pixmap)
}

/// Draws `drawing` and encodes it as PNG.
///
/// # Errors
/// [`SkiaError::Canvas`] for a canvas too large, [`SkiaError::Encode`] if encoding fails.
pub fn to_png(drawing: &Drawing) -> Result<Vec<u8>, SkiaError> {
    render(drawing)?.encode_png().map_err(|e| SkiaError::Encode(e.to_string()))
}

/// The f64 → f32 narrowing of a pixel position: the single place where it happens.
fn px(p: DVec2) -> (f32, f32) {
    (narrow(p.x), narrow(p.y))
}

/// A pixel quantity as tiny-skia's f32. Canvas coordinates are far below f32's range, so the
/// narrowing loses only sub-pixel digits.
#[allow(clippy::cast_possible_truncation)]
fn narrow(v: f64) -> f32 {
    v as f32
}

/// A mask that is opaque over the plot area, so shapes stay out of the title and caption bands.
fn plot_mask(frame: &PageLayout, width: u32, height: u32) -> Option<Mask> {
    let mut mask = Mask::new(width, height)?;
    let (l, t) = px(frame.plot.min);
    let (r, b) = px(frame.plot.max);
    let path = PathBuilder::from_rect(Rect::from_ltrb(l, t, r, b)?);
    mask.fill_path(&path, FillRule::Winding, false, SkTransform::identity());
    Some(mask)
}

/// The paint of a colour, anti-aliased.
fn paint(color: Rgba) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(color.r, color.g, color.b, color.a);
    paint.anti_alias = true;
    paint
}

/// Builds tiny-skia paths from glyph outlines.
struct GlyphPath(PathBuilder);

impl PathSink for GlyphPath {
    fn move_to(&mut self, p: DVec2) {
        let (x, y) = px(p);
        self.0.move_to(x, y);
    }
    fn line_to(&mut self, p: DVec2) {
        let (x, y) = px(p);
        self.0.line_to(x, y);
    }
    fn quad_to(&mut self, c: DVec2, p: DVec2) {
        let ((cx, cy), (x, y)) = (px(c), px(p));
        self.0.quad_to(cx, cy, x, y);
    }
    fn cubic_to(&mut self, c1: DVec2, c2: DVec2, p: DVec2) {
        let ((ax, ay), (bx, by), (x, y)) = (px(c1), px(c2), px(p));
        self.0.cubic_to(ax, ay, bx, by, x, y);
    }
    fn close(&mut self) {
        self.0.close();
    }
}

/// A pixmap being drawn on, with the drawing's transform and the plot clip.
struct Canvas<'a> {
    pixmap: &'a mut Pixmap,
    tf: Transform,
    clip: Option<Mask>,
}

impl Canvas<'_> {
    /// The tiny-skia stroke of a style, or `None` when it draws nothing.
    fn stroke(&self, style: &Pen) -> Option<Stroke> {
        if !style.strokes() {
            return None;
        }
        let dash = style.dash.and_then(|d| {
            StrokeDash::new(vec![narrow(self.tf.ref_px(d.on)), narrow(self.tf.ref_px(d.off))], 0.0)
        });
        Some(Stroke {
            width: narrow(self.tf.ref_px(style.width)),
            line_cap: if dash.is_some() { LineCap::Butt } else { LineCap::Round },
            line_join: LineJoin::Round,
            dash,
            ..Stroke::default()
        })
    }

    /// Fills `path` with `color` (clipped to the plot when `clipped`).
    fn fill(&mut self, path: &Path, color: Rgba, clipped: bool) {
        let mask = if clipped { self.clip.as_ref() } else { None };
        self.pixmap.fill_path(path, &paint(color), FillRule::Winding, SkTransform::identity(), mask);
    }

    /// Strokes `path` with `style` (clipped to the plot when `clipped`).
    fn draw_stroke(&mut self, path: &Path, style: &Pen, clipped: bool) {
        let Some(stroke) = self.stroke(style) else {
            return;
        };
        let mask = if clipped { self.clip.as_ref() } else { None };
        self.pixmap.stroke_path(path, &paint(style.color), &stroke, SkTransform::identity(), mask);
    }

    /// A path through pixel points, optionally closed.
    fn polyline(points: impl IntoIterator<Item = DVec2>, closed: bool) -> Option<Path> {
        let mut pb = PathBuilder::new();
        for (i, p) in points.into_iter().enumerate() {
            let (x, y) = px(p);
            if i == 0 {
                pb.move_to(x, y);
            } else {
                pb.line_to(x, y);
            }
        }
        if closed {
            pb.close();
        }
        pb.finish()
    }

    /// Draws one display-list item.
    fn item(&mut self, style: &Pen, shape: &Mark) {
        let tf = self.tf;
        match shape {
            Mark::Line { points } => {
                if let Some(path) = Self::polyline(points.iter().map(|p| tf.to_px(*p)), false) {
                    self.draw_stroke(&path, style, true);
                }
            }
            Mark::Arrow { from, to, head } => {
                self.arrow(tf.to_px(*from), tf.to_px(*to), tf.ref_px(*head), style, true);
            }
            Mark::Circle { center, radius, fill } => {
                let (x, y) = px(tf.to_px(*center));
                if let Some(path) = PathBuilder::from_circle(x, y, narrow(tf.len_px(*radius))) {
                    self.shape(&path, style, *fill);
                }
            }
            Mark::Dot { center, radius, fill } => {
                self.dot(tf.to_px(*center), tf.ref_px(*radius), *fill, style, true);
            }
            Mark::Polygon { points, fill } => {
                if let Some(path) = Self::polyline(points.iter().map(|p| tf.to_px(*p)), true) {
                    self.shape(&path, style, *fill);
                }
            }
            Mark::Rect { min, max, fill } => {
                let (l, b) = px(tf.to_px(*min));
                let (r, t) = px(tf.to_px(*max));
                if let Some(rect) = Rect::from_ltrb(l, t, r, b) {
                    self.shape(&PathBuilder::from_rect(rect), style, *fill);
                }
            }
            Mark::Text(label) => {
                let placed = Drawing::place_text(label, &tf);
                if let Some((a, b)) = placed.leader {
                    if let Some(path) = Self::polyline([a, b], false) {
                        self.draw_stroke(&path, &style::leader(), true);
                    }
                }
                let halo = label.halo.then(|| tf.ref_px(style::HALO_WIDTH));
                self.text(&label.text, placed.origin, placed.size, label.weight, style.color, halo);
            }
        }
    }

    /// Fills then strokes a closed path (clipped to the plot).
    fn shape(&mut self, path: &Path, style: &Pen, fill: Option<Rgba>) {
        if let Some(fill) = fill {
            self.fill(path, fill, true);
        }
        self.draw_stroke(path, style, true);
    }

    /// A round marker of pixel radius `r`.
    fn dot(&mut self, center: DVec2, r: f64, fill: Rgba, outline: &Pen, clipped: bool) {
        let (x, y) = px(center);
        if let Some(path) = PathBuilder::from_circle(x, y, narrow(r)) {
            self.fill(&path, fill, clipped);
            self.draw_stroke(&path, outline, clipped);
        }
    }

    /// An arrow from pixel `a` to pixel `b` (see [`ArrowPx`]): stroked shaft, filled head.
    fn arrow(&mut self, a: DVec2, b: DVec2, head: f64, style: &Pen, clipped: bool) {
        let Some(arrow) = ArrowPx::new(a, b, head) else {
            return;
        };
        if let Some(path) = Self::polyline([arrow.shaft_from, arrow.shaft_to], false) {
            self.draw_stroke(&path, style, clipped);
        }
        if let Some(path) = Self::polyline(arrow.head, true) {
            self.fill(&path, style.color, clipped);
        }
    }

    /// One line of markup with its baseline at `origin`, with an optional white halo of
    /// `halo` pixels' stroke width.
    fn text(
        &mut self,
        markup: &str,
        origin: DVec2,
        size: f64,
        weight: Weight,
        color: Rgba,
        halo: Option<f64>,
    ) {
        let laid = text::layout(markup, size, weight);
        let mut sink = GlyphPath(PathBuilder::new());
        text::outline(&laid, origin, &mut sink);
        let Some(path) = sink.0.finish() else {
            return;
        };
        if let Some(width) = halo {
            let halo_style = Pen::solid(style::WHITE, width);
            if let Some(mut stroke) = self.stroke(&halo_style) {
                // The halo is already in pixels.
                stroke.width = narrow(width);
                self.pixmap.stroke_path(&path, &paint(style::WHITE), &stroke, SkTransform::identity(), None);
            }
        }
        self.fill(&path, color, false);
    }

    /// A placed line of chrome text (title, caption, legend).
    fn line_of_text(&mut self, line: &PlacedLine, weight: Weight) {
        self.text(&line.text, line.origin, line.size, weight, style::TEXT, None);
    }

    /// The title, caption and legend.
    fn chrome(&mut self, drawing: &Drawing, frame: &PageLayout) {
        if let Some(title) = &frame.title {
            self.line_of_text(title, Weight::Bold);
        }
        for line in &frame.caption {
            self.line_of_text(line, Weight::Regular);
        }
        if let Some(legend) = &frame.legend {
            self.legend(drawing, legend);
        }
    }

    /// The legend box: a white panel with a thin border, one sample and label per row.
    fn legend(&mut self, drawing: &Drawing, legend: &LegendBox) {
        let (l, t) = px(legend.rect.min);
        let (r, b) = px(legend.rect.max);
        let Some(rect) = Rect::from_ltrb(l, t, r, b) else {
            return;
        };
        let path = PathBuilder::from_rect(rect);
        self.fill(&path, style::WHITE.with_alpha(0.92), false);
        self.draw_stroke(&path, &Pen::solid(style::LIGHT_GREY, style::GRID_WIDTH), false);
        for (entry, row) in drawing.legend.iter().zip(&legend.rows) {
            let (a, z) = (row.sample_from, row.sample_to);
            let mid = (a + z) / 2.0;
            match entry.sample {
                LegendIcon::Line => {
                    if let Some(p) = Self::polyline([a, z], false) {
                        self.draw_stroke(&p, &entry.style, false);
                    }
                }
                LegendIcon::Arrow => {
                    let head = self.tf.ref_px(style::arrow_head(entry.style.width));
                    self.arrow(a, z, head, &entry.style, false);
                }
                LegendIcon::Dot(fill) => {
                    let r = self.tf.ref_px(style::DOT_RADIUS * 1.2);
                    self.dot(mid, r, fill, &entry.style, false);
                }
                LegendIcon::Swatch(fill) => {
                    let half = row.label.size * 0.4;
                    let (sl, st) = px(mid - DVec2::splat(half));
                    let (sr, sb) = px(mid + DVec2::splat(half));
                    if let Some(square) = Rect::from_ltrb(sl, st, sr, sb) {
                        self.shape_unclipped(&PathBuilder::from_rect(square), &entry.style, fill);
                    }
                }
            }
            self.line_of_text(&row.label, Weight::Regular);
        }
    }

    /// Fills then strokes a closed path, without the plot clip.
    fn shape_unclipped(&mut self, path: &Path, style: &Pen, fill: Rgba) {
        self.fill(path, fill, false);
        self.draw_stroke(path, style, false);
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::{TextOpts, View};

    use crate::style::test_strokes::{BLUE_LINE, FILL, OUTLINE, RED_LINE};

    fn demo() -> Drawing {
        let mut d = Drawing::new(640, 360).unwrap();
        d.set_title("Reflexie").set_caption("n_1 < n_2");
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        d.segment("ray:reflected", DVec2::new(-2.0, 0.5), DVec2::new(2.0, 0.5), RED_LINE)
            .circle("object:0", DVec2::ZERO, 0.4, OUTLINE, Some(FILL))
            .arrow("ray:primary", DVec2::new(-1.5, -0.5), DVec2::new(-0.4, 0.0), BLUE_LINE)
            .text("label", DVec2::new(1.0, -0.5), "ă â î ș ț θ n_1", TextOpts::LABEL);
        d.legend_entry("reflected", RED_LINE, LegendIcon::Line);
        d
    }

    #[test]
    fn png_has_the_requested_size_and_is_not_blank() {
        let d = demo();
        let pixmap = render(&d).unwrap();
        assert_eq!((pixmap.width(), pixmap.height()), (640, 360));
        let non_white =
            pixmap.pixels().iter().filter(|p| (p.red(), p.green(), p.blue()) != (255, 255, 255)).count();
        assert!(non_white > 1000, "{non_white} non-white pixels");
        let png = to_png(&d).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        // The IHDR chunk holds width and height, big-endian.
        assert_eq!(u32::from_be_bytes([png[16], png[17], png[18], png[19]]), 640);
        assert_eq!(u32::from_be_bytes([png[20], png[21], png[22], png[23]]), 360);
    }

    #[test]
    fn a_coloured_line_shows_its_colour() {
        let d = demo();
        let pixmap = render(&d).unwrap();
        let c = style::VERMILLION;
        let exact = pixmap
            .pixels()
            .iter()
            .filter(|p| (p.red(), p.green(), p.blue(), p.alpha()) == (c.r, c.g, c.b, 255))
            .count();
        assert!(exact > 100, "{exact} pixels of the reflected ray's colour");
    }

    #[test]
    fn text_leaves_ink_for_every_character() {
        // Each character drawn alone darkens some pixels.
        for c in "ăâîșțθn₁".chars() {
            let mut d = Drawing::new(960, 540).unwrap();
            d.text("label", DVec2::ZERO, &c.to_string(), TextOpts::LABEL.no_halo());
            let pixmap = render(&d).unwrap();
            let dark = pixmap.pixels().iter().filter(|p| p.red() < 128).count();
            assert!(dark > 10, "{c:?} left {dark} dark pixels");
        }
    }

    #[test]
    fn shapes_are_clipped_to_the_plot_area() {
        let mut d = Drawing::new(400, 300).unwrap();
        d.set_caption("caption");
        d.set_view(View::new(0.0, 1.0, 0.0, 1.0).unwrap());
        // A vertical line far taller than the view.
        d.segment("ray:primary", DVec2::new(0.5, -10.0), DVec2::new(0.5, 10.0), BLUE_LINE);
        let frame = d.frame();
        let pixmap = render(&d).unwrap();
        let x = frame.transform.to_px(DVec2::new(0.5, 0.5)).x.round();
        // 2 px below the plot area, the line is gone.
        let below = frame.plot.max.y.ceil() + 2.0;
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let p = pixmap.pixel(x as u32, below as u32).unwrap();
        assert_eq!((p.red(), p.green(), p.blue()), (255, 255, 255));
    }

    #[test]
    fn oversized_canvas_is_an_error() {
        let d = Drawing::new(u32::MAX, u32::MAX).unwrap();
        assert!(matches!(render(&d), Err(SkiaError::Canvas { .. })));
    }
}
