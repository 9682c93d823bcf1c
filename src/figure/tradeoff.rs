//! The plot of `whitted tradeoff` (product.md): each measured setting as a point, its trace time
//! across and its error against the reference (RMSE) up, one colour per sweep (sampling mode,
//! depth, structure), and the Pareto front — the settings that nothing beats in both time and
//! error — joined by a line and named.

use glam::DVec2;

use crate::canvas::{Align, Corner, Drawing, LegendPlace, Sample, Style, TextOpts, View};
use crate::figure::labels::{escape, Label};
use crate::figure::parts::num;
use crate::figure::style::{self, Rgba, TextSize};
use crate::figure::{FigureError, Options};
use crate::tradeoff::{setting_name, Measured, Sweep, Tradeoff};

/// The three sweeps in legend order, each with its name and colour.
const SWEEPS: [(Sweep, Label, Rgba); 3] = [
    (Sweep::Sampling, Label::SweepSampling, style::BLUE),
    (Sweep::Depth, Label::SweepDepth, style::VERMILLION),
    (Sweep::Accel, Label::SweepAccel, style::BLUISH_GREEN),
];

/// The height of the empty band above the plot that holds the legend, in plot heights.
const LEGEND_BAND: f64 = 0.4;

/// The colour of a sweep's points.
fn colour(sweep: Sweep) -> Rgba {
    SWEEPS.iter().find(|(s, _, _)| *s == sweep).map_or(style::BLUE, |(_, _, c)| *c)
}

/// A logarithmic axis over `[lo, hi]` (both > 0), widened to whole decades' 1-2-5 steps.
#[derive(Clone, Copy, Debug, PartialEq)]
struct LogAxis {
    lo: f64,
    hi: f64,
}

impl LogAxis {
    /// Steps of 1, 2 and 5 times a power of ten.
    const STEPS: [f64; 3] = [1.0, 2.0, 5.0];

    /// The axis around the positive finite values (None if there are none).
    fn around(values: impl IntoIterator<Item = f64>) -> Option<Self> {
        let (lo, hi) = values
            .into_iter()
            .filter(|v| *v > 0.0 && v.is_finite())
            .fold((f64::INFINITY, 0.0_f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if !(lo <= hi) {
            return None;
        }
        // The nearest 1-2-5 steps at or outside the values.
        let below = |v: f64| {
            let p = 10f64.powf(v.log10().floor());
            Self::STEPS.iter().rev().map(|m| m * p).find(|s| *s <= v).unwrap_or(p)
        };
        let above = |v: f64| {
            let p = 10f64.powf(v.log10().floor());
            Self::STEPS.iter().chain(&[10.0]).map(|m| m * p).find(|s| *s >= v).unwrap_or(10.0 * p)
        };
        let (lo, hi) = (below(lo), above(hi));
        Some(if hi > lo { Self { lo, hi } } else { Self { lo: lo / 2.0, hi: hi * 2.0 } })
    }
    /// Where `v` sits, 0 at `lo` and 1 at `hi` (values outside are clamped).
    fn at(self, v: f64) -> f64 {
        let v = v.clamp(self.lo, self.hi);
        (v / self.lo).log10() / (self.hi / self.lo).log10()
    }
    /// Whether the tick at `v` is named: every tick of an axis of two decades or less; on a
    /// longer one only the 1 and 5 steps, so that the names never crowd.
    fn names(self, v: f64) -> bool {
        let mantissa = v / 10f64.powf(v.log10().floor());
        (self.hi / self.lo) <= 100.0 || (mantissa - 2.0).abs() > 0.5
    }
    /// The 1-2-5 steps from `lo` to `hi`.
    fn ticks(self) -> Vec<f64> {
        let first = self.lo.log10().floor();
        let last = self.hi.log10().ceil();
        // Decades of an axis: a handful, exactly representable.
        #[allow(clippy::cast_possible_truncation)]
        let decades = (first as i32)..=(last as i32);
        decades
            .flat_map(|e| Self::STEPS.map(|m| m * 10f64.powi(e)))
            .filter(|v| *v >= self.lo * (1.0 - 1e-9) && *v <= self.hi * (1.0 + 1e-9))
            .collect()
    }
}

/// Draws the plot of a measurement with its Pareto front (indices into `measured.rows`).
///
/// # Errors
/// When the canvas is empty.
pub fn draw(
    measured: &Tradeoff,
    front: &[usize],
    scene_name: &str,
    opts: &Options,
) -> Result<Drawing, FigureError> {
    let mut d = Drawing::new(opts.width, opts.height)
        .ok_or_else(|| FigureError(format!("a {}×{} canvas is empty", opts.width, opts.height)))?;
    let t = |label: Label| label.text(opts.lang);
    let rows = &measured.rows;
    let base = rows.first().map_or(measured.reference.setting, |m| m.setting);
    d.set_title(t(Label::TitleTradeoff));
    d.set_caption(&format!(
        "{} {} · {} · {}: {}",
        t(Label::Scene),
        escape(scene_name),
        t(Label::ReferenceImage),
        t(Label::RendersEach),
        measured.runs,
    ));

    // World: log RMSE up [0, 1], log time across [0, x_end], so that the plot with its margins
    // (tick names left and below, the legend's band above) fills the plot area. The reference
    // (no error) is not a point of the plot, nor is a setting whose image equals it.
    let (left, bottom, right) = (0.1, 0.16, 0.03);
    let world_height = bottom + 1.0 + LEGEND_BAND;
    let world_width = d.plot_aspect() * world_height;
    let x_end = world_width * (1.0 - left - right);
    let shown: Vec<usize> = (0..rows.len()).filter(|&i| rows[i].error.rmse > 0.0).collect();
    // Times in milliseconds: short tick names from a tiny test scene to a large image.
    let ms = |m: &Measured| 1e3 * m.seconds;
    let time_axis = LogAxis::around(shown.iter().map(|&i| ms(&rows[i])));
    let error_axis = LogAxis::around(shown.iter().map(|&i| rows[i].error.rmse));
    let (Some(time_axis), Some(error_axis)) = (time_axis, error_axis) else {
        return Err(FigureError("no setting differs from the reference".into()));
    };
    let at = |m: &Measured| DVec2::new(x_end * time_axis.at(ms(m)), error_axis.at(m.error.rmse));
    d.set_view(
        View::new(-left * world_width, (1.0 - left) * world_width, -bottom, 1.0 + LEGEND_BAND)
            .ok_or_else(|| FigureError("the plot area is empty".into()))?,
    );

    // Axes, ticks and their names.
    let axis = Style::solid(style::DARK_GREY, style::GRID_WIDTH);
    let y_end = DVec2::new(0.0, 1.0);
    d.segment("axis", DVec2::ZERO, DVec2::new(x_end, 0.0), axis);
    d.segment("axis", DVec2::ZERO, y_end, axis);
    let tick_len = 0.015;
    for x in time_axis.ticks() {
        let p = DVec2::new(x_end * time_axis.at(x), 0.0);
        d.segment("axis", p, p - DVec2::new(0.0, tick_len), axis);
        if time_axis.names(x) {
            d.text("tick", p, &num(x), TextOpts::NOTE.align(Align::BELOW).offset(0.0, -14.0));
        }
    }
    for y in error_axis.ticks() {
        let p = DVec2::new(0.0, error_axis.at(y));
        d.segment("axis", p, p - DVec2::new(tick_len, 0.0), axis);
        if error_axis.names(y) {
            d.text("tick", p, &num(y), TextOpts::NOTE.align(Align::LEFT_OF).offset(-14.0, 0.0));
        }
    }
    let below_axis = TextOpts::LABEL.align(Align::BELOW).offset(0.0, -60.0);
    d.text("axis-name", DVec2::new(0.5 * x_end, 0.0), t(Label::AxisTime), below_axis);
    d.text("axis-name", y_end, t(Label::AxisRmse), TextOpts::LABEL.align(Align::RIGHT_OF).offset(16.0, 0.0));

    // The front first, under the points.
    let front: Vec<usize> = front.iter().copied().filter(|i| shown.contains(i)).collect();
    let front_points: Vec<DVec2> = front.iter().map(|&i| at(&rows[i])).collect();
    let front_style =
        Style::solid(style::DARK_GREY, style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH);
    if front_points.len() > 1 {
        d.line("pareto", front_points, front_style);
    }
    for &i in &shown {
        let m = &rows[i];
        let fill = colour(Sweep::of(&m.setting, &base));
        let radius = if front.contains(&i) { style::DOT_RADIUS * 1.4 } else { style::DOT_RADIUS };
        d.marker("setting", at(m), radius, fill, Style::solid(style::WHITE, 2.0));
    }
    // Names for the points of the front, clear of each other and inside the axes, a leader to a
    // name set apart.
    d.keep_labels_within(DVec2::ZERO, DVec2::new(x_end, 1.0 + LEGEND_BAND));
    for &i in &front {
        let m: &Measured = &rows[i];
        d.text(
            "setting-name",
            at(m),
            &escape(&setting_name(&m.setting, &base)),
            TextOpts::NOTE
                .align(Align::RIGHT_OF)
                .offset(22.0, 14.0)
                .size(TextSize::Small)
                .avoid_overlap_with_leader()
                .far(),
        );
    }

    for (sweep, label, fill) in SWEEPS {
        if rows.iter().any(|m| Sweep::of(&m.setting, &base) == sweep) {
            d.legend_entry(t(label), Style::NONE, Sample::Dot(fill));
        }
    }
    d.legend_entry(t(Label::ParetoFront), front_style, Sample::Line);
    d.legend_place = LegendPlace::Inside(Corner::TopRight);
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_axis_spans_whole_1_2_5_steps() {
        let axis = LogAxis::around([0.011, 0.2, 0.0, f64::NAN]).unwrap();
        assert_eq!((axis.lo, axis.hi), (0.01, 0.2));
        assert_eq!(axis.ticks(), vec![0.01, 0.02, 0.05, 0.1, 0.2]);
        assert!((axis.at(0.01)).abs() < 1e-12 && (axis.at(0.2) - 1.0).abs() < 1e-12);
        // One value: a step each side.
        let one = LogAxis::around([0.05]).unwrap();
        assert!(one.lo < 0.05 && one.hi > 0.05);
        assert!(LogAxis::around([0.0, -1.0]).is_none());
    }
}
