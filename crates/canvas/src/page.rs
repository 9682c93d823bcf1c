//! The page layout shared by both back ends ([`Drawing::frame`] → [`PageLayout`]): a title band at the
//! top, a caption band at the bottom (wrapped to the canvas width), the plot area between them,
//! and the view scaled uniformly into the plot area once the legend has its place.

use glam::DVec2;

use super::drawing::Drawing;
use super::items::LegendPlace;
use super::legend::{LegendBox, PlacedLegend};
use super::style::{self, TextSize};
use super::text::{self, PlacedLine, Weight, LINE_SPACING};
use super::view::{PxRect, Transform};

/// The canvas layout shared by the back ends (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct PageLayout {
    /// The world → pixel map.
    pub transform: Transform,
    /// The plot area in pixels.
    pub plot: PxRect,
    /// The title line, centred at the top.
    pub title: Option<PlacedLine>,
    /// The caption lines, centred at the bottom.
    pub caption: Vec<PlacedLine>,
    /// The legend box, if there are legend entries.
    pub legend: Option<LegendBox>,
}

impl Drawing {
    /// The plot area before the legend is placed: the canvas less its margin, the title and
    /// caption bands and, for [`LegendPlace::Outside`], the legend column (for
    /// [`LegendPlace::Below`], the legend band). [`View::fit`] and
    /// [`Drawing::fit_view`] fit to this area.
    pub(super) fn plot_area(&self) -> PxRect {
        match (self.legend_place, self.legend_size()) {
            (LegendPlace::Outside, Some(size)) => self.plot_area_beside(size.x),
            (LegendPlace::Below, Some(size)) => self.plot_area_above(size.y),
            _ => self.plot_area_beside(0.0),
        }
    }

    /// The plot area with a legend band `band` pixels tall under it, and a margin between them.
    pub(super) fn plot_area_above(&self, band: f64) -> PxRect {
        let mut plot = self.plot_area_beside(0.0);
        plot.max.y = (plot.max.y - band - style::MARGIN * self.px_scale()).max(plot.min.y + 1.0);
        plot
    }

    /// The world → pixel scale of the picture: how large the figure draws its view.
    #[must_use]
    pub fn picture_scale(&self) -> f64 {
        self.placed_legend().transform.scale()
    }

    /// The plot area with a legend column `column` pixels wide (0 for none) on the right.
    pub(super) fn plot_area_beside(&self, column: f64) -> PxRect {
        let k = self.px_scale();
        let (w, h) = (f64::from(self.width()), f64::from(self.height()));
        let margin = style::MARGIN * k;
        let mut top = margin;
        let mut bottom = h - margin;
        if self.title.is_some() {
            top += TextSize::Title.px() * k * LINE_SPACING;
        }
        let lines = self.caption_lines().len();
        if lines > 0 {
            bottom -= TextSize::Body.px() * k * LINE_SPACING * lines as f64 + margin * 0.5;
        }
        // A canvas too small for its bands still gets a plot area of one pixel.
        let bottom = bottom.max(top + 1.0);
        let left = margin.min(w / 2.0);
        let right = if column > 0.0 { w - margin - column - margin } else { w - margin };
        let right = right.max(left + 1.0);
        PxRect { min: DVec2::new(left, top), max: DVec2::new(right, bottom) }
    }

    /// The caption, wrapped to the canvas width.
    pub(super) fn caption_lines(&self) -> Vec<String> {
        let Some(caption) = &self.caption else {
            return Vec::new();
        };
        let k = self.px_scale();
        let max_width = f64::from(self.width()) - 2.0 * style::MARGIN * k;
        text::wrap_even(caption, TextSize::Body.px() * k, Weight::Regular, max_width)
    }

    /// The world → pixel map: the view scaled uniformly to fit the plot area, centred (the plot
    /// area after the legend is placed, as in [`Drawing::frame`]).
    #[must_use]
    pub fn transform(&self) -> Transform {
        self.placed_legend().transform
    }

    /// The view scaled uniformly to fit `plot`, centred.
    pub(super) fn transform_in(&self, plot: &PxRect) -> Transform {
        Transform::fit(&self.view, plot, self.px_scale())
    }
    /// Lays out the canvas for the back ends: transform, plot area, title, caption and legend.
    #[must_use]
    pub fn frame(&self) -> PageLayout {
        let PlacedLegend { transform: tf, plot, legend: legend_rect } = self.placed_legend();
        let k = self.px_scale();
        let w = f64::from(self.width());
        let h = f64::from(self.height());
        let margin = style::MARGIN * k;

        let title = self.title.as_ref().map(|t| {
            let size = TextSize::Title.px() * k;
            let laid = text::layout(t, size, Weight::Bold);
            let origin = DVec2::new((w - laid.width) / 2.0, margin + text::cap_height(size));
            PlacedLine { text: t.clone(), origin, size }
        });

        let caption_size = TextSize::Body.px() * k;
        let lines = self.caption_lines();
        let step = caption_size * LINE_SPACING;
        let first = h
            - margin
            - step * (lines.len().saturating_sub(1)) as f64
            - text::layout("g", caption_size, Weight::Regular).descent;
        let caption = lines
            .into_iter()
            .enumerate()
            .map(|(i, line)| {
                let width = text::layout(&line, caption_size, Weight::Regular).width;
                let origin = DVec2::new((w - width) / 2.0, first + step * i as f64);
                PlacedLine { text: line, origin, size: caption_size }
            })
            .collect();

        let legend = legend_rect.map(|rect| self.legend_rows(rect));
        PageLayout { transform: tf, plot, title, caption, legend }
    }
}
