//! A drawing as plain text, one line per display-list item ([`Drawing::to_text`]): what the
//! figure shows, in world coordinates rounded to 3 decimals, with each stroke and fill — stable
//! across platforms and readable in a diff, for snapshot tests and for reading a figure without
//! drawing it.
//!
//! ```text
//! title: All the rays of one pixel
//! view: x -5.078 … 6.316, y -2.480 … 6.480
//! legend: primary ray P
//! items:
//!   object:1: circle (0.100, 1.000) r 0.800 fill #56b4e9@64 #000000 w4.000
//!   ray:primary: arrow (0.000, 6.000) → (0.298, 3.617) #0072b2 w6.000
//! ```
//!
//! An item line is `tag: geometry` then its stroke (colour, width in reference pixels, `dashed`)
//! when it draws one; a colour is `#rrggbb`, with `@alpha` (0–255) unless opaque; a label is its
//! markup quoted as Rust quotes a string, its anchor and its offset in reference pixels.

use std::fmt::Write as _;

use glam::DVec2;

use super::drawing::Drawing;
use super::items::{Item, Mark};
use super::style::Rgba;

/// A number of the listing: fixed, 3 decimals, `-0.000` written `0.000`.
#[must_use]
pub fn listing_number(x: f64) -> String {
    let s = format!("{x:.3}");
    if s == "-0.000" {
        "0.000".into()
    } else {
        s
    }
}

/// A point of the listing: `(x, y)`.
fn point(v: DVec2) -> String {
    format!("({}, {})", listing_number(v.x), listing_number(v.y))
}

/// `p q r …`: a polyline's or polygon's points.
fn points(vs: &[DVec2]) -> String {
    vs.iter().map(|v| point(*v)).collect::<Vec<_>>().join(" ")
}

/// A colour of the listing: `#rrggbb`, then `@alpha` unless opaque.
fn colour(rgba: Rgba) -> String {
    if rgba.a == 255 {
        rgba.hex()
    } else {
        format!("{}@{}", rgba.hex(), rgba.a)
    }
}

/// ` fill COLOUR`, or nothing without a fill.
fn fill(f: Option<Rgba>) -> String {
    f.map(|f| format!(" fill {}", colour(f))).unwrap_or_default()
}

impl Item {
    /// The item's line of [`Drawing::to_text`]: tag, geometry, stroke.
    #[must_use]
    pub fn to_text(&self) -> String {
        let st = &self.pen;
        let stroke = if st.strokes() {
            let dashed = if st.dash.is_some() { " dashed" } else { "" };
            format!(" {} w{}{dashed}", colour(st.color), listing_number(st.width))
        } else {
            String::new()
        };
        let geometry = match &self.mark {
            Mark::Line { points: vs } => format!("line {}", points(vs)),
            Mark::Arrow { from, to, .. } => format!("arrow {} → {}", point(*from), point(*to)),
            Mark::Circle { center, radius, fill: f } => {
                format!("circle {} r {}{}", point(*center), listing_number(*radius), fill(*f))
            }
            Mark::Dot { center, radius, fill: f } => {
                format!("dot {} r{}px fill {}", point(*center), listing_number(*radius), colour(*f))
            }
            Mark::Polygon { points: vs, fill: f } => format!("polygon {}{}", points(vs), fill(*f)),
            Mark::Rect { min, max, fill: f } => format!("rect {} {}{}", point(*min), point(*max), fill(*f)),
            Mark::Text(t) => format!("text {:?} at {} + {}px", t.text, point(t.anchor), point(t.offset)),
        };
        format!("{}: {geometry}{stroke}", self.tag)
    }
}

impl Drawing {
    /// The drawing as text (see the module doc): `title:` and `caption:` when set, `view:`, a
    /// `legend:` line per legend row, then `items:` and an indented line per item, in order.
    #[must_use]
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        // Writing into a String cannot fail, so the results of writeln! are ignored.
        if let Some(title) = &self.title {
            let _ = writeln!(out, "title: {title}");
        }
        if let Some(caption) = &self.caption {
            let _ = writeln!(out, "caption: {caption}");
        }
        let v = &self.view;
        let _ = writeln!(
            out,
            "view: x {} … {}, y {} … {}",
            listing_number(v.xmin()),
            listing_number(v.xmax()),
            listing_number(v.ymin()),
            listing_number(v.ymax())
        );
        for entry in &self.legend {
            let _ = writeln!(out, "legend: {}", entry.label);
        }
        out.push_str("items:\n");
        for item in &self.items {
            let _ = writeln!(out, "  {}", item.to_text());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::style::{self, Dash, Pen};
    use crate::{TextOpts, View};

    #[test]
    fn every_shape_has_its_line() {
        let mut d = Drawing::slide();
        d.set_title("T").set_view(View::new(-1.0, 2.0, -0.0004, 1.0).unwrap());
        let line = Pen::solid(style::BLUE, 6.0);
        d.segment("ray", DVec2::ZERO, DVec2::new(1.0, -0.0001), line)
            .arrow("r", DVec2::ZERO, DVec2::Y, line.dashed(Dash { on: 1.0, off: 1.0 }))
            .circle("o", DVec2::ZERO, 0.5, Pen::NONE, Some(style::SKY_BLUE.with_alpha(0.25)))
            .dot("hit", DVec2::X, style::BLACK)
            .polygon("p", [DVec2::ZERO, DVec2::X, DVec2::Y], line, None)
            .rect("cell", DVec2::ONE, DVec2::ZERO, Pen::NONE, Some(style::YELLOW))
            .text("label", DVec2::ZERO, "θ_i \"q\"", TextOpts::LABEL.offset(2.0, -3.0));
        d.legend_entry("primary", line, crate::LegendIcon::Line);
        let expected = "title: T\n\
            view: x -1.000 … 2.000, y 0.000 … 1.000\n\
            legend: primary\n\
            items:\n  \
            ray: line (0.000, 0.000) (1.000, 0.000) #0072b2 w6.000\n  \
            r: arrow (0.000, 0.000) → (0.000, 1.000) #0072b2 w6.000 dashed\n  \
            o: circle (0.000, 0.000) r 0.500 fill #56b4e9@64\n  \
            hit: dot (1.000, 0.000) r10.000px fill #000000\n  \
            p: polygon (0.000, 0.000) (1.000, 0.000) (0.000, 1.000) #0072b2 w6.000\n  \
            cell: rect (0.000, 0.000) (1.000, 1.000) fill #f0e442\n  \
            label: text \"θ_i \\\"q\\\"\" at (0.000, 0.000) + (2.000, -3.000)px\n";
        assert_eq!(d.to_text(), expected);
    }
}
