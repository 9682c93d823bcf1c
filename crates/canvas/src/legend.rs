//! The legend laid out, `Drawing`'s legend methods: [`Drawing::legend_entry`] adds a row
//! ([`LegendEntry`], with a [`LegendIcon`] of the line, arrow, dot or swatch it explains; both
//! beside the items), [`LegendPlace`] says where its box goes (a clear corner of the plot area, a
//! column beside it or a band under it), and here its box and rows are laid out in pixels
//! ([`LegendBox`]).

use glam::DVec2;

use super::drawing::Drawing;
/// The legend's rows and places, beside the items since [`Drawing`] stores them; here too for the
/// paths that name them through `legend`.
pub use super::items::{Corner, LegendEntry, LegendIcon, LegendPlace};
use super::style::{self, Pen, TextSize};
use super::text::{self, PlacedLine, Weight, LINE_SPACING};
use super::view::{PxRect, Transform};

/// One legend row laid out in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendRow {
    /// Where the sample starts (left end, vertical middle of the row).
    pub sample_from: DVec2,
    /// Where the sample ends.
    pub sample_to: DVec2,
    /// The row's text.
    pub label: PlacedLine,
}

/// The legend box laid out in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendBox {
    /// The box.
    pub rect: PxRect,
    /// Its rows, top to bottom, in the order of [`Drawing::legend`].
    pub rows: Vec<LegendRow>,
}

/// The legend box's padding around its rows, in reference pixels.
pub const LEGEND_PAD: f64 = 18.0;
/// The length of a row's sample line or arrow, in reference pixels: long enough to show a dash.
pub const LEGEND_SAMPLE: f64 = 64.0;
/// The gap between a row's sample and its text, in reference pixels.
pub const LEGEND_GAP: f64 = 16.0;

/// The legend's sizes in pixels at a drawing's scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LegendMetrics {
    /// [`LEGEND_PAD`], scaled.
    pub pad: f64,
    /// [`LEGEND_SAMPLE`], scaled.
    pub sample_len: f64,
    /// [`LEGEND_GAP`], scaled.
    pub gap: f64,
    /// A row's height: a body text line.
    pub row: f64,
}

/// Where the picture and the legend go: what [`Drawing::placed_legend`] decides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PlacedLegend {
    /// World → pixels for the plot area.
    pub transform: Transform,
    /// The plot area, in pixels.
    pub plot: PxRect,
    /// The legend box, or `None` without legend entries.
    pub legend: Option<PxRect>,
}

impl Drawing {
    /// Adds a legend row.
    pub fn legend_entry(&mut self, label: &str, style: Pen, sample: LegendIcon) -> &mut Self {
        self.legend.push(LegendEntry { label: label.to_owned(), style, sample });
        self
    }

    /// The legend's padding, sample length, gap before the text, and row height, in pixels.
    pub(super) fn legend_metrics(&self) -> LegendMetrics {
        let k = self.px_scale();
        LegendMetrics {
            pad: LEGEND_PAD * k,
            sample_len: LEGEND_SAMPLE * k,
            gap: LEGEND_GAP * k,
            row: TextSize::Body.px() * k * LINE_SPACING,
        }
    }

    /// The legend box's size in pixels, or `None` without legend entries.
    pub(super) fn legend_size(&self) -> Option<DVec2> {
        if self.legend.is_empty() {
            return None;
        }
        let size = TextSize::Body.px() * self.px_scale();
        let LegendMetrics { pad, sample_len, gap, row } = self.legend_metrics();
        let text_width = self
            .legend
            .iter()
            .map(|e| text::layout(&e.label, size, Weight::Regular).width)
            .fold(0.0, f64::max);
        Some(DVec2::new(
            pad * 2.0 + sample_len + gap + text_width,
            pad * 2.0 + row * self.legend.len() as f64,
        ))
    }

    /// The transform, the plot area and the legend box, with [`LegendPlace::Auto`] resolved.
    pub(super) fn placed_legend(&self) -> PlacedLegend {
        let Some(size) = self.legend_size() else {
            let plot = self.plot_area_beside(0.0);
            return PlacedLegend { transform: self.transform_in(&plot), plot, legend: None };
        };
        let inset = style::MARGIN * self.px_scale() * 0.3;
        let in_corner = |plot: &PxRect, corner: Corner| {
            let x = match corner {
                Corner::TopLeft | Corner::BottomLeft => plot.min.x + inset,
                Corner::TopRight | Corner::BottomRight => plot.max.x - inset - size.x,
            };
            let y = match corner {
                Corner::TopLeft | Corner::TopRight => plot.min.y + inset,
                Corner::BottomLeft | Corner::BottomRight => plot.max.y - inset - size.y,
            };
            PxRect { min: DVec2::new(x, y), max: DVec2::new(x, y) + size }
        };
        let outside = || {
            let plot = self.plot_area_beside(size.x);
            let margin = style::MARGIN * self.px_scale();
            let min = DVec2::new(plot.max.x + margin, plot.min.y);
            PlacedLegend {
                transform: self.transform_in(&plot),
                plot,
                legend: Some(PxRect { min, max: min + size }),
            }
        };
        let below = || {
            let plot = self.plot_area_above(size.y);
            let margin = style::MARGIN * self.px_scale();
            let min = DVec2::new(plot.max.x - size.x, plot.max.y + margin);
            PlacedLegend {
                transform: self.transform_in(&plot),
                plot,
                legend: Some(PxRect { min, max: min + size }),
            }
        };
        match self.legend_place {
            LegendPlace::Below => below(),
            LegendPlace::Inside(corner) => {
                let plot = self.plot_area_beside(0.0);
                PlacedLegend {
                    transform: self.transform_in(&plot),
                    plot,
                    legend: Some(in_corner(&plot, corner)),
                }
            }
            LegendPlace::Outside => outside(),
            LegendPlace::Auto => {
                let plot = self.plot_area_beside(0.0);
                let tf = self.transform_in(&plot);
                let segments = self.segments(&tf);
                let boxes = self.text_boxes(&tf);
                let clear = |r: &PxRect| {
                    let r = r.inflate(inset);
                    !segments.iter().any(|(a, b)| r.meets_segment(*a, *b))
                        && boxes.iter().all(|b| r.overlap(b) <= 0.0)
                };
                Corner::ALL
                    .iter()
                    .map(|c| in_corner(&plot, *c))
                    .find(|r| clear(r))
                    .map_or_else(outside, |r| PlacedLegend { transform: tf, plot, legend: Some(r) })
            }
        }
    }

    /// The legend's rows inside its box.
    pub(super) fn legend_rows(&self, rect: PxRect) -> LegendBox {
        let size = TextSize::Body.px() * self.px_scale();
        let LegendMetrics { pad, sample_len, gap, row } = self.legend_metrics();
        let cap = text::cap_height(size);
        let rows = self
            .legend
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let mid_y = rect.min.y + pad + row * (i as f64 + 0.5);
                let sample_from = DVec2::new(rect.min.x + pad, mid_y);
                let sample_to = sample_from + DVec2::new(sample_len, 0.0);
                let origin = DVec2::new(sample_to.x + gap, mid_y + cap / 2.0);
                let label = PlacedLine { text: e.label.clone(), origin, size };
                LegendRow { sample_from, sample_to, label }
            })
            .collect();
        LegendBox { rect, rows }
    }
}
