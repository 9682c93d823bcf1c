//! The vector back end: a [`Drawing`] → SVG text, for print.
//!
//! It reads the same display list through the same [`PageLayout`] (transform, plot area, title,
//! caption, legend) as the raster back end, so the two agree. Each display-list item becomes
//! exactly one `<g data-tag="…" data-events="…">` group (`data-events`: the indices of the trace
//! events the item draws, space-separated, possibly empty); the title, caption and legend are
//! groups with a `class` and no `data-tag`. Text stays text: `<text>` in the embedded fonts, whose
//! subsets (cut to the characters the SVG prints, [`subset`]) the `<defs>` carry as `@font-face`
//! rules with base64 `data:` URLs under a family of the SVG's own (then the reader's Noto Sans,
//! then any sans-serif), with sub- and superscripts as `<tspan dy="…" font-size="…">` (lowered or
//! raised by the layout's own shift, where the PNG puts them, not by the reader's
//! `baseline-shift`) and the halo as a white stroke painted first. Each `<text>` has the
//! `textLength` it was laid out with, so a reader that falls back to another font keeps every
//! line's width. On request ([`SvgText::Paths`]) the words are drawn as glyph outlines instead,
//! each line a `<path>` beside its `<text>` made invisible, and no font is embedded.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use ab_glyph::Font as _;

use glam::DVec2;

use super::style::{self, Pen, Rgba};
use super::subset;
use super::text::{self, Face, Script, Weight};
use super::{
    ArrowPx, Drawing, HAlign, LegendBox, LegendIcon, Mark, PageLayout, PlacedLine, PxRect, Text, Transform,
};

/// The id of the clip path that keeps shapes inside the plot area.
const CLIP_ID: &str = "plot-area";

/// How an SVG draws its words.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SvgText {
    /// As `<text>` in the subsets of the fonts it prints with, embedded (the default): small,
    /// selectable, and the same glyphs on any machine that reads web fonts.
    #[default]
    Embed,
    /// As `<path>` glyph outlines in the text's colour, each line beside an invisible `<text>`
    /// (`fill-opacity="0"`) of the same words at the same place, which a screen reader reads and a
    /// search finds: the same glyphs in a reader that ignores embedded fonts (a print shop's, a
    /// drawing program's), for a larger file.
    Paths,
}

/// The SVG document of `drawing`, its words in embedded fonts ([`SvgText::Embed`]).
#[must_use]
pub fn to_svg(drawing: &Drawing) -> String {
    to_svg_with(drawing, SvgText::Embed)
}

/// The SVG document of `drawing`, its words drawn as `text` says.
#[must_use]
pub fn to_svg_with(drawing: &Drawing, text: SvgText) -> String {
    let frame = drawing.frame();
    let (w, h) = (drawing.width(), drawing.height());
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    // Writing into a String cannot fail, so the results of write! are ignored throughout.
    let plot = frame.plot;
    // The body first: the fonts embedded in the head are cut to the characters it prints.
    let mut body = String::new();
    body.push_str("<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
    let tf = frame.transform;
    for item in &drawing.items {
        let clip = if matches!(item.mark, Mark::Text(_)) {
            String::new()
        } else {
            format!(" clip-path=\"url(#{CLIP_ID})\"")
        };
        let events: Vec<String> = item.events.iter().map(ToString::to_string).collect();
        let _ = write!(
            body,
            "<g data-tag=\"{}\" data-events=\"{}\"{clip}>",
            xml_escape(&item.tag),
            events.join(" ")
        );
        shape(&mut body, &tf, &item.pen, &item.mark, text);
        body.push_str("</g>\n");
    }
    chrome(&mut body, drawing, &frame, text);
    // Glyphs drawn as paths need no font: the invisible words take the reader's.
    let (faces, families) = match text {
        SvgText::Embed => font_faces(&printed_text(&body)),
        SvgText::Paths => (String::new(), Vec::new()),
    };
    // The embedded faces first, then the reader's own copies, then any sans-serif.
    let mut family: Vec<String> = families;
    family.extend([text::FAMILY, text::MATH_FAMILY, "sans-serif"].map(str::to_owned));
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\" font-family=\"{}\">",
        xml_escape(&family.join(", "))
    );
    let _ = writeln!(
        out,
        "<defs>{faces}<clipPath id=\"{CLIP_ID}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\
         </clipPath></defs>",
        svg_coordinate(plot.min.x),
        svg_coordinate(plot.min.y),
        svg_coordinate(plot.width()),
        svg_coordinate(plot.height())
    );
    out.push_str(&body);
    out.push_str("</svg>\n");
    out
}

/// The characters the `<text>` elements of an SVG `body` print, by weight: the content between
/// each `<text …>` and its `</text>`, tags taken out and XML's entities read back (the body is
/// this module's own writing, so this small reading of it is exact).
fn printed_text(body: &str) -> BTreeMap<Weight, BTreeSet<char>> {
    let mut out: BTreeMap<Weight, BTreeSet<char>> = BTreeMap::new();
    let mut rest = body;
    while let Some(start) = rest.find("<text ") {
        let Some(open_end) = rest[start..].find('>') else { break };
        let open = &rest[start..start + open_end];
        let weight = if open.contains("font-weight=\"bold\"") { Weight::Bold } else { Weight::Regular };
        let content_start = start + open_end + 1;
        let Some(len) = rest[content_start..].find("</text>") else { break };
        let content = &rest[content_start..content_start + len];
        let mut plain = String::new();
        let mut in_tag = false;
        for c in content.chars() {
            match c {
                '<' => in_tag = true,
                '>' => in_tag = false,
                c if !in_tag => plain.push(c),
                _ => {}
            }
        }
        let plain = plain
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&apos;", "'")
            .replace("&amp;", "&");
        out.entry(weight).or_default().extend(plain.chars());
        rest = &rest[content_start + len..];
    }
    out
}

/// The `<style>` with an `@font-face` per face that draws some of `printed` (its characters by
/// weight): a subset of the embedded file ([`subset`]) as a base64 `data:` URL, so that the SVG
/// prints with the PNG's glyphs and advances on a machine without Noto Sans (issue 32 item 6);
/// and the families it defines, for the root's `font-family`. Each family is named after a hash
/// of its subsets (`whitted-…`): an SVG set inline in a page, beside others, styles the whole
/// page, and a shared name would let one figure's subset draw another's text. Empty when
/// nothing is printed.
fn font_faces(printed: &BTreeMap<Weight, BTreeSet<char>>) -> (String, Vec<String>) {
    let mut by_face: BTreeMap<Face, BTreeSet<char>> = BTreeMap::new();
    for (weight, chars) in printed {
        for c in chars {
            by_face.entry(text::face_of(*c, *weight)).or_default().insert(*c);
        }
    }
    let subsets: Vec<(Face, Vec<u8>)> = by_face
        .into_iter()
        .filter_map(|(face, chars)| {
            let font = face.font();
            Some((face, subset::subset(text::face_file(face), chars, |c| font.glyph_id(c).0)?))
        })
        .collect();
    // The main family (regular and bold) and the math family, each named by its bytes' hash.
    let name = |math: bool| {
        let bytes = subsets.iter().filter(|(f, _)| (*f == Face::Math) == math).flat_map(|(_, b)| b.iter());
        format!("whitted-{:016x}", fnv1a(bytes.copied()))
    };
    let (main, math) = (name(false), name(true));
    let mut css = String::new();
    let mut families = Vec::new();
    for (face, bytes) in &subsets {
        let (family, weight) = match face {
            Face::Regular => (&main, "normal"),
            Face::Bold => (&main, "bold"),
            Face::Math => (&math, "normal"),
        };
        if !families.contains(family) {
            families.push(family.clone());
        }
        let _ = write!(
            css,
            "@font-face{{font-family:\"{family}\";font-weight:{weight};\
             src:url(data:font/ttf;base64,{})format(\"truetype\")}}",
            subset::base64(bytes)
        );
    }
    families.sort_by_key(|f| *f != main);
    let style = if css.is_empty() { css } else { format!("<style>{css}</style>") };
    (style, families)
}

/// The 64-bit FNV-1a hash of `bytes`: a name for a subset that two different subsets do not
/// share in practice.
fn fnv1a(bytes: impl IntoIterator<Item = u8>) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes.into_iter().fold(OFFSET, |h, b| (h ^ u64::from(b)).wrapping_mul(PRIME))
}

/// A coordinate or length in an SVG attribute, in pixels: two decimals, no trailing zeros, no `-0`.
/// A hundredth of a pixel is below what a screen or printer shows. The minus is ASCII `-`, as
/// SVG's number syntax requires. The top-level `format` module lists every format and why.
#[must_use]
pub fn svg_coordinate(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// Text for the SVG's XML content and attribute values: `& < > " '` become entities.
/// The control characters XML 1.0 forbids are dropped, since one would make the file unreadable.
#[must_use]
pub fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if u32::from(c) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => {}
            c => out.push(c),
        }
    }
    out
}

/// `stroke`, `stroke-width`, dash and opacity attributes of a style (or `stroke="none"`).
fn stroke_attrs(tf: &Transform, style: &Pen) -> String {
    if !style.strokes() {
        return " stroke=\"none\"".to_owned();
    }
    let mut s = format!(
        " stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"",
        style.color.hex(),
        svg_coordinate(tf.ref_px(style.width))
    );
    if let Some(dash) = style.dash {
        let _ = write!(
            s,
            " stroke-dasharray=\"{} {}\"",
            svg_coordinate(tf.ref_px(dash.on)),
            svg_coordinate(tf.ref_px(dash.off))
        );
    } else {
        s.push_str(" stroke-linecap=\"round\"");
    }
    if style.color.a < 255 {
        let _ = write!(s, " stroke-opacity=\"{}\"", svg_coordinate(style.color.opacity()));
    }
    s
}

/// `fill` and opacity attributes of an optional fill.
fn fill_attrs(fill: Option<Rgba>) -> String {
    match fill {
        None => " fill=\"none\"".to_owned(),
        Some(c) if c.a < 255 => {
            format!(" fill=\"{}\" fill-opacity=\"{}\"", c.hex(), svg_coordinate(c.opacity()))
        }
        Some(c) => format!(" fill=\"{}\"", c.hex()),
    }
}

/// `x,y x,y …` of pixel points.
fn points_attr(points: impl IntoIterator<Item = DVec2>) -> String {
    let pairs: Vec<String> =
        points.into_iter().map(|p| format!("{},{}", svg_coordinate(p.x), svg_coordinate(p.y))).collect();
    pairs.join(" ")
}

/// The elements of one shape.
fn shape(out: &mut String, tf: &Transform, style: &Pen, shape: &Mark, mode: SvgText) {
    match shape {
        Mark::Line { points } => {
            let pts = points_attr(points.iter().map(|p| tf.to_px(*p)));
            let _ = write!(out, "<polyline points=\"{pts}\" fill=\"none\"{}/>", stroke_attrs(tf, style));
        }
        Mark::Arrow { from, to, head } => {
            arrow(out, tf, tf.to_px(*from), tf.to_px(*to), tf.ref_px(*head), style);
        }
        Mark::Circle { center, radius, fill } => {
            let c = tf.to_px(*center);
            let _ = write!(
                out,
                "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{}{}/>",
                svg_coordinate(c.x),
                svg_coordinate(c.y),
                svg_coordinate(tf.len_px(*radius)),
                fill_attrs(*fill),
                stroke_attrs(tf, style)
            );
        }
        Mark::Dot { center, radius, fill } => {
            dot(out, tf, tf.to_px(*center), tf.ref_px(*radius), *fill, style);
        }
        Mark::Polygon { points, fill } => {
            let pts = points_attr(points.iter().map(|p| tf.to_px(*p)));
            let _ =
                write!(out, "<polygon points=\"{pts}\"{}{}/>", fill_attrs(*fill), stroke_attrs(tf, style));
        }
        Mark::Rect { min, max, fill } => {
            let a = tf.to_px(DVec2::new(min.x, max.y));
            let b = tf.to_px(DVec2::new(max.x, min.y));
            rect(out, tf, &PxRect { min: a, max: b }, *fill, style);
        }
        Mark::Text(label) => {
            let placed = Drawing::place_text(label, tf);
            if let Some((a, b)) = placed.leader {
                let pts = points_attr([a, b]);
                let _ = write!(
                    out,
                    "<polyline points=\"{pts}\" fill=\"none\"{}/>",
                    stroke_attrs(tf, &style::leader())
                );
            }
            let halo = label.halo.then(|| tf.ref_px(style::HALO_WIDTH));
            text_element(out, label, placed.origin, placed.size, (style.color, halo), mode);
        }
    }
}

/// A pixel rectangle.
fn rect(out: &mut String, tf: &Transform, r: &PxRect, fill: Option<Rgba>, style: &Pen) {
    let _ = write!(
        out,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"{}{}/>",
        svg_coordinate(r.min.x),
        svg_coordinate(r.min.y),
        svg_coordinate(r.width()),
        svg_coordinate(r.height()),
        fill_attrs(fill),
        stroke_attrs(tf, style)
    );
}

/// A round marker of pixel radius `r`.
fn dot(out: &mut String, tf: &Transform, c: DVec2, r: f64, fill: Rgba, outline: &Pen) {
    let _ = write!(
        out,
        "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{}{}/>",
        svg_coordinate(c.x),
        svg_coordinate(c.y),
        svg_coordinate(r),
        fill_attrs(Some(fill)),
        stroke_attrs(tf, outline)
    );
}

/// An arrow between pixel points: the shaft as a line, the head as a filled polygon.
fn arrow(out: &mut String, tf: &Transform, a: DVec2, b: DVec2, head: f64, style: &Pen) {
    let Some(arrow) = ArrowPx::new(a, b, head) else {
        return;
    };
    let _ = write!(
        out,
        "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"{}/>",
        svg_coordinate(arrow.shaft_from.x),
        svg_coordinate(arrow.shaft_from.y),
        svg_coordinate(arrow.shaft_to.x),
        svg_coordinate(arrow.shaft_to.y),
        stroke_attrs(tf, style)
    );
    let _ = write!(
        out,
        "<polygon points=\"{}\"{} stroke=\"none\"/>",
        points_attr(arrow.head),
        fill_attrs(Some(style.color))
    );
}

/// A `<text>` element for a label, anchored so a substitute font keeps the alignment.
fn text_element(
    out: &mut String,
    label: &Text,
    origin: DVec2,
    size: f64,
    (color, halo): (Rgba, Option<f64>),
    mode: SvgText,
) {
    let width = text::layout(&label.text, size, label.weight).width;
    let (x, anchor) = match label.align.h {
        HAlign::Left => (origin.x, "start"),
        HAlign::Center => (origin.x + width / 2.0, "middle"),
        HAlign::Right => (origin.x + width, "end"),
    };
    text_line(out, &label.text, DVec2::new(x, origin.y), anchor, size, label.weight, (color, halo), mode);
}

/// One line of markup as `<text>` with `<tspan>`s for its scripts; drawn as glyph outlines
/// first when `mode` asks for paths, the `<text>` then invisible.
#[allow(clippy::too_many_arguments)]
#[allow(clippy::float_cmp)] // a shift of exactly 0 (a run on the baseline) needs no `dy`
fn text_line(
    out: &mut String,
    markup: &str,
    at: DVec2,
    anchor: &str,
    size: f64,
    weight: Weight,
    (color, halo): (Rgba, Option<f64>),
    mode: SvgText,
) {
    let laid = text::layout(markup, size, weight);
    let width = laid.width;
    if mode == SvgText::Paths {
        let start = match anchor {
            "middle" => at.x - width / 2.0,
            "end" => at.x - width,
            _ => at.x,
        };
        glyph_path(out, &laid, DVec2::new(start, at.y), color, halo);
    }
    let _ = write!(
        out,
        "<text x=\"{}\" y=\"{}\" font-size=\"{}\" text-anchor=\"{anchor}\" fill=\"{}\"",
        svg_coordinate(at.x),
        svg_coordinate(at.y),
        svg_coordinate(size),
        color.hex()
    );
    if mode == SvgText::Paths {
        // The words are there to be read and found, not seen: the path above draws them.
        out.push_str(" fill-opacity=\"0\"");
    }
    if weight == Weight::Bold {
        out.push_str(" font-weight=\"bold\"");
    }
    // The line keeps the width it was laid out with in the embedded font, whatever font the
    // reader substitutes (a wider one would run a centred caption past the picture's edge).
    if width > 0.0 {
        let _ = write!(out, " textLength=\"{}\" lengthAdjust=\"spacingAndGlyphs\"", svg_coordinate(width));
    }
    // Spaces are laid out as the PNG lays them out (an indented line, two spaces), not collapsed.
    if markup.contains("  ") || markup.starts_with(' ') || markup.ends_with(' ') {
        out.push_str(" xml:space=\"preserve\"");
    }
    if let (Some(width), SvgText::Embed) = (halo, mode) {
        let _ = write!(
            out,
            " stroke=\"#ffffff\" stroke-width=\"{}\" stroke-linejoin=\"round\" \
             paint-order=\"stroke\"",
            svg_coordinate(width)
        );
    }
    out.push('>');
    // Each run is lowered or raised by the layout's own shift (`Script::shift`, in em of the
    // line's size) as an explicit `dy` from where the run before left the baseline: a reader's
    // `baseline-shift="sub"` takes the font's subscript offset, which Chromium sets lower than
    // the PNG does.
    let mut rise = 0.0;
    for run in text::runs(markup, weight) {
        let content = xml_escape(&run.text);
        let shift = size * run.script.shift();
        let dy = rise - shift;
        rise = shift;
        let font_size = match run.script {
            Script::Normal => String::new(),
            Script::Sub | Script::Super => {
                format!(" font-size=\"{}\"", svg_coordinate(size * run.script.scale()))
            }
        };
        if dy == 0.0 && font_size.is_empty() {
            out.push_str(&content);
        } else {
            let dy = if dy == 0.0 { String::new() } else { format!(" dy=\"{}\"", svg_coordinate(dy)) };
            let _ = write!(out, "<tspan{dy}{font_size}>{content}</tspan>");
        }
    }
    out.push_str("</text>");
}

/// The glyph outlines of a laid-out line whose baseline starts at pixel `origin`, as one
/// `<path>` in `color` (with the white halo stroked under it when `halo` is given), hidden from
/// screen readers, which read the invisible `<text>` beside it.
fn glyph_path(out: &mut String, laid: &text::TextLayout, origin: DVec2, color: Rgba, halo: Option<f64>) {
    let mut d = PathData(String::new());
    text::outline(laid, origin, &mut d);
    if d.0.is_empty() {
        return;
    }
    let _ = write!(out, "<path d=\"{}\" fill=\"{}\"", d.0.trim_start(), color.hex());
    if let Some(width) = halo {
        let _ = write!(
            out,
            " stroke=\"#ffffff\" stroke-width=\"{}\" stroke-linejoin=\"round\" paint-order=\"stroke\"",
            svg_coordinate(width)
        );
    }
    out.push_str(" aria-hidden=\"true\"/>");
}

/// SVG path data (`M x y L … Q … C … Z`, absolute pixel coordinates) written by a
/// [`text::PathSink`].
struct PathData(String);

impl PathData {
    fn command(&mut self, letter: char, points: &[DVec2]) {
        let _ = write!(self.0, " {letter}");
        for p in points {
            let _ = write!(self.0, " {} {}", svg_coordinate(p.x), svg_coordinate(p.y));
        }
    }
}

impl text::PathSink for PathData {
    fn move_to(&mut self, p: DVec2) {
        self.command('M', &[p]);
    }
    fn line_to(&mut self, p: DVec2) {
        self.command('L', &[p]);
    }
    fn quad_to(&mut self, c: DVec2, p: DVec2) {
        self.command('Q', &[c, p]);
    }
    fn cubic_to(&mut self, c1: DVec2, c2: DVec2, p: DVec2) {
        self.command('C', &[c1, c2, p]);
    }
    fn close(&mut self) {
        self.0.push_str(" Z");
    }
}

/// A placed chrome line (its origin is the baseline start).
fn chrome_line(out: &mut String, line: &PlacedLine, weight: Weight, mode: SvgText) {
    text_line(out, &line.text, line.origin, "start", line.size, weight, (style::TEXT, None), mode);
}

/// The title, caption and legend groups.
fn chrome(out: &mut String, drawing: &Drawing, frame: &PageLayout, mode: SvgText) {
    if let Some(title) = &frame.title {
        out.push_str("<g class=\"title\">");
        chrome_line(out, title, Weight::Bold, mode);
        out.push_str("</g>\n");
    }
    if !frame.caption.is_empty() {
        out.push_str("<g class=\"caption\">");
        for line in &frame.caption {
            chrome_line(out, line, Weight::Regular, mode);
        }
        out.push_str("</g>\n");
    }
    if let Some(legend) = &frame.legend {
        legend_group(out, drawing, &frame.transform, legend, mode);
    }
}

/// The legend box.
fn legend_group(out: &mut String, drawing: &Drawing, tf: &Transform, legend: &LegendBox, mode: SvgText) {
    out.push_str("<g class=\"legend\">");
    let border = Pen::solid(style::LIGHT_GREY, style::GRID_WIDTH);
    rect(out, tf, &legend.rect, Some(style::WHITE.with_alpha(0.92)), &border);
    for (entry, row) in drawing.legend.iter().zip(&legend.rows) {
        let (a, z) = (row.sample_from, row.sample_to);
        let mid = (a + z) / 2.0;
        match entry.sample {
            LegendIcon::Line => {
                let _ = write!(
                    out,
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"{}/>",
                    svg_coordinate(a.x),
                    svg_coordinate(a.y),
                    svg_coordinate(z.x),
                    svg_coordinate(z.y),
                    stroke_attrs(tf, &entry.style)
                );
            }
            LegendIcon::Arrow => {
                let head = tf.ref_px(style::arrow_head(entry.style.width));
                arrow(out, tf, a, z, head, &entry.style);
            }
            LegendIcon::Dot(fill) => {
                dot(out, tf, mid, tf.ref_px(style::DOT_RADIUS * 1.2), fill, &entry.style)
            }
            LegendIcon::Swatch(fill) => {
                let half = DVec2::splat(row.label.size * 0.4);
                rect(out, tf, &PxRect { min: mid - half, max: mid + half }, Some(fill), &entry.style);
            }
        }
        chrome_line(out, &row.label, Weight::Regular, mode);
    }
    out.push_str("</g>\n");
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::{TextOpts, View};
    use ab_glyph::FontRef;

    use crate::style::test_strokes::{BLUE_LINE, DASHED, FILL, GREEN_LINE, OUTLINE};

    fn demo() -> Drawing {
        let mut d = Drawing::new(960, 540).unwrap();
        d.set_title("Refracție <T> & \"R\"").set_caption("θ_t = arcsin(n_1/n_2 · sin θ_i)");
        d.set_view(View::new(-2.0, 2.0, -1.0, 1.0).unwrap());
        d.segment("ray:primary", DVec2::new(-2.0, 0.0), DVec2::ZERO, BLUE_LINE)
            .arrow("ray:transmitted", DVec2::ZERO, DVec2::new(1.0, -1.0), GREEN_LINE)
            .circle("object:0", DVec2::ZERO, 0.5, OUTLINE, Some(FILL))
            .dot("hit", DVec2::ZERO, style::BLACK)
            .polygon("object:1", [DVec2::ZERO, DVec2::X, DVec2::Y], OUTLINE, None)
            .rect("cell", DVec2::ZERO, DVec2::ONE, style::grid(), Some(style::YELLOW))
            .segment("normal", DVec2::ZERO, DVec2::Y, DASHED)
            .text("label", DVec2::new(0.5, 0.5), "θ_t & t_{ex} <K_s>", TextOpts::LABEL)
            .text("a\"b", DVec2::new(-0.5, 0.5), "n_1", TextOpts::LABEL);
        d.legend_entry("primary", BLUE_LINE, LegendIcon::Line)
            .legend_entry("T", GREEN_LINE, LegendIcon::Arrow)
            .legend_entry("hit", Pen::NONE, LegendIcon::Dot(style::BLACK))
            .legend_entry("object", OUTLINE, LegendIcon::Swatch(FILL));
        d
    }

    /// The bytes of base64 `text` (RFC 4648, padded).
    fn unbase64(text: &str) -> Vec<u8> {
        let value = |c: u8| match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => panic!("not base64: {c}"),
        };
        let mut out = Vec::new();
        for quad in text.as_bytes().chunks(4) {
            let pad = quad.iter().filter(|c| **c == b'=').count();
            let n = quad.iter().filter(|c| **c != b'=').fold(0u32, |n, c| (n << 6) | value(*c)) << (6 * pad);
            out.extend(&n.to_be_bytes()[1..4 - pad]);
        }
        out
    }

    /// Issue 32 item 6: the SVG embeds, under a family of its own that the root names first, a
    /// subset of each face it prints with, and each subset draws every character printed in it
    /// with the embedded font's glyph and advance.
    #[test]
    #[allow(clippy::float_cmp)] // advances read from the same font units must be the very same
    fn the_svg_embeds_the_subset_of_the_fonts_it_prints_with() {
        let d = demo();
        let svg = to_svg(&d);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let family = doc.root_element().attribute("font-family").unwrap();
        assert!(family.starts_with("whitted-"), "{family}");
        assert!(family.ends_with("Noto Sans, Noto Sans Math, sans-serif"), "{family}");
        let css = doc.descendants().find(|n| n.has_tag_name("style")).unwrap().text().unwrap().to_owned();
        let printed = printed_text(&svg[svg.find("</defs>").unwrap()..]);
        assert!(printed[&Weight::Bold].contains(&'ț') && printed[&Weight::Regular].contains(&'θ'));
        let mut faces = 0;
        for rule in css.split("@font-face").skip(1) {
            faces += 1;
            let weight = if rule.contains("font-weight:bold") { Weight::Bold } else { Weight::Regular };
            let start = rule.find("base64,").unwrap() + "base64,".len();
            let bytes = unbase64(&rule[start..start + rule[start..].find(')').unwrap()]);
            let part = FontRef::try_from_slice(&bytes).unwrap();
            let whole = text::font(weight);
            // The first family is regular and bold; another is the math face's.
            let math = !rule.contains(family.split(", ").next().unwrap());
            for c in printed[&weight].iter().filter(|c| !c.is_whitespace()) {
                if (text::face_of(*c, weight) == Face::Math) != math {
                    continue;
                }
                let source = if math { text::math_font() } else { whole };
                let (a, b) = (source.glyph_id(*c), part.glyph_id(*c));
                assert_ne!(b.0, 0, "{c:?} missing from the {weight:?} subset");
                assert_eq!(source.h_advance_unscaled(a), part.h_advance_unscaled(b), "{c:?}");
            }
            assert!(bytes.len() < 40_000, "a subset of {} bytes", bytes.len());
        }
        // Regular and bold (the title); the demo prints nothing of the math face.
        assert_eq!(faces, 2, "{css}");
    }

    /// The bounds of the points of absolute path data (`M x y L … Q … C … Z`): a curve lies in
    /// the hull of its points, and a TrueType glyph's box holds every point of its outline.
    fn path_bounds(d: &str) -> PxRect {
        let numbers: Vec<f64> = d.split_whitespace().filter_map(|w| w.parse().ok()).collect();
        let points: Vec<DVec2> = numbers.chunks(2).map(|p| DVec2::new(p[0], p[1])).collect();
        let min = points.iter().copied().reduce(DVec2::min).unwrap();
        let max = points.iter().copied().reduce(DVec2::max).unwrap();
        PxRect { min, max }
    }

    /// `--svg-text paths` (issue 32 item 6): every line of words is a `<path>` of its glyphs whose
    /// box is the layout's ink box (the one the label checks use: the glyphs' ink up and down, the
    /// advance across, less the side bearings), with the same words beside it in a `<text>` that
    /// is not painted (`fill-opacity="0"`) but read by a screen reader and found by a search; no
    /// font is embedded.
    #[test]
    fn words_drawn_as_paths_lie_in_the_layout_s_ink_box_and_stay_readable() {
        let d = demo();
        let svg = to_svg_with(&d, SvgText::Paths);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        assert!(!svg.contains("@font-face") && !svg.contains("<style"));
        let texts: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("text")).collect();
        let paths = doc.descendants().filter(|n| n.has_tag_name("path")).count();
        assert_eq!(paths, texts.len(), "a path per line of words");
        for t in &texts {
            assert_eq!(t.attribute("fill-opacity"), Some("0"), "a visible <text>");
            assert_eq!(t.attribute("stroke"), None, "a visible halo");
        }
        let embedded = to_svg(&d);
        let words = |svg: &str| {
            let doc = roxmltree::Document::parse(svg).unwrap();
            let all: Vec<String> = doc
                .descendants()
                .filter(|n| n.has_tag_name("text"))
                .map(|t| t.descendants().filter_map(|n| n.text()).collect())
                .collect();
            all
        };
        assert_eq!(words(&svg), words(&embedded), "the same words, readable");
        let tf = d.frame().transform;
        let groups = doc.descendants().filter(|n| n.has_tag_name("g") && n.attribute("data-tag").is_some());
        let mut labels = 0;
        for (g, item) in groups.zip(&d.items) {
            let Mark::Text(label) = &item.mark else { continue };
            labels += 1;
            let path = g.children().find(|c| c.has_tag_name("path")).unwrap();
            let drawn = path_bounds(path.attribute("d").unwrap());
            let ink = Drawing::ink_box(label, &tf);
            let size = tf.ref_px(label.size.px());
            // Up and down: the very ink (to the SVG's hundredth of a pixel); across: within the
            // side bearings of the first and last glyph.
            assert!((drawn.min.y - ink.min.y).abs() < 0.02 && (drawn.max.y - ink.max.y).abs() < 0.02);
            let what = format!("{:?}: drawn {drawn:?}, ink {ink:?}", label.text);
            assert!(drawn.min.x >= ink.min.x - 0.01 && drawn.min.x - ink.min.x < 0.25 * size, "{what}");
            assert!(drawn.max.x <= ink.max.x + 0.01 && ink.max.x - drawn.max.x < 0.25 * size, "{what}");
        }
        assert_eq!(labels, 2);
    }

    #[test]
    fn svg_parses_and_has_one_group_per_item() {
        let d = demo();
        let svg = to_svg(&d);
        let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        assert_eq!(root.attribute("width"), Some("960"));
        let tagged: Vec<_> =
            doc.descendants().filter(|n| n.has_tag_name("g") && n.attribute("data-tag").is_some()).collect();
        assert_eq!(tagged.len(), d.items.len());
        assert_eq!(svg.matches("<g data-tag=").count(), d.items.len());
        for (node, item) in tagged.iter().zip(&d.items) {
            assert_eq!(node.attribute("data-tag"), Some(item.tag.as_str()));
        }
    }

    #[test]
    fn text_keeps_its_characters_and_scripts() {
        let svg = to_svg(&demo());
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let label = doc
            .descendants()
            .find(|n| n.attribute("data-tag") == Some("label"))
            .and_then(|g| g.children().find(|c| c.has_tag_name("text")))
            .unwrap();
        let all: String = label.descendants().filter(|n| n.is_text()).filter_map(|n| n.text()).collect();
        assert_eq!(all, "θt & tex <Ks>");
        // Each subscript lowered by the layout's own shift (0.2 em of the line), at 0.7 of its
        // size, and the run after it raised back: where the PNG draws them.
        let size: f64 = label.attribute("font-size").unwrap().parse().unwrap();
        let dy = |n: &roxmltree::Node| n.attribute("dy").map(|v| v.parse::<f64>().unwrap());
        let spans: Vec<_> = label.children().filter(|n| n.has_tag_name("tspan")).collect();
        let subs: Vec<_> = spans.iter().filter(|n| n.attribute("font-size").is_some()).collect();
        assert_eq!(subs.len(), 3);
        for sub in &subs {
            assert!((dy(sub).unwrap() - 0.2 * size).abs() < 0.01, "{:?}", sub.attribute("dy"));
        }
        let total: f64 = spans.iter().filter_map(dy).sum();
        assert!(total.abs() < 0.02, "the line ends on its baseline: {total}");
        assert!(!svg.contains("baseline-shift"));
        assert!(svg.contains("Refracție &lt;T&gt; &amp; &quot;R&quot;"));
    }

    #[test]
    fn an_indented_line_keeps_its_spaces() {
        let mut d = Drawing::new(960, 540).unwrap();
        d.text("note", DVec2::ZERO, "   indented", TextOpts::LABEL).text(
            "plain",
            DVec2::Y,
            "a b",
            TextOpts::LABEL,
        );
        let svg = to_svg(&d);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let text_of = |tag: &str| {
            doc.descendants()
                .find(|n| n.attribute("data-tag") == Some(tag))
                .and_then(|g| g.children().find(|c| c.has_tag_name("text")))
                .unwrap()
        };
        let space = ("http://www.w3.org/XML/1998/namespace", "space");
        assert_eq!(text_of("note").attribute(space), Some("preserve"));
        assert_eq!(text_of("plain").attribute(space), None, "single spaces need nothing");
    }

    #[test]
    fn escaping() {
        assert_eq!(xml_escape("a<b>&\"c'\u{1}"), "a&lt;b&gt;&amp;&quot;c&apos;");
        assert_eq!(svg_coordinate(-0.001), "0");
        assert_eq!(svg_coordinate(2.5), "2.5");
        assert_eq!(svg_coordinate(3.0), "3");
    }
}
