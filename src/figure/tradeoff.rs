//! The plots of `whitted tradeoff` (product.md): one per sweep that has an error (sampling,
//! depth), each setting a point with its name, the rays traced per pixel across (the cost, which
//! no machine's load changes) and its error against the sweep's reference (RMSE) up, on log scales;
//! the Pareto front — the settings that nothing beats in both rays and error — joined by a line.
//! A setting whose image is the reference's (RMSE 0) sits on a row of its own under the log
//! scale, named `0`.

use glam::DVec2;

use crate::canvas::{Align, Corner, Drawing, LegendIcon, LegendPlace, Pen, TextOpts, View};
use crate::figure::labels::Label;
use crate::figure::style::{self, Rgba, TextSize};
use crate::figure::{FigureError, Lang, Options};
use crate::format::markup_escape;
use crate::format::slide_number;
use crate::sample::Sampling;
use crate::tradeoff::{Measured, Measurement, Setting, Sweep};

/// The height of the empty band above the plot that holds the legend, in plot heights.
const LEGEND_BAND: f64 = 0.3;
/// Where the row of error-0 settings sits under the log scale, in plot heights.
const ZERO_ROW: f64 = 0.0;
/// Where the log scale starts when a zero row is drawn, in plot heights.
const LOG_FROM_WITH_ZERO: f64 = 0.1;

/// Where across the plot (a share of its width) the points' names move to their left.
const NAME_LEFT_FROM: f64 = 0.75;
/// The longest log axis, in decades, whose 5 steps are named besides its powers of ten.
const NAMED_FIVES_UP_TO: f64 = 3.0;

/// The colour of a sweep's points.
fn colour(sweep: Sweep) -> Rgba {
    if sweep == Sweep::Depth {
        style::VERMILLION
    } else {
        style::BLUE
    }
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
    /// Whether the tick at `v` is named: every tick of an axis of two decades or less; on one of
    /// up to [`NAMED_FIVES_UP_TO`] decades the 1 and 5 steps; on a longer one the powers of ten
    /// alone, so that the names never crowd.
    fn names(self, v: f64) -> bool {
        let mantissa = v / 10f64.powf(v.log10().floor());
        let decades = (self.hi / self.lo).log10();
        decades <= 2.0 + 1e-9
            || (mantissa - 1.0).abs() < 0.5
            || (decades <= NAMED_FIVES_UP_TO + 1e-9 && (mantissa - 5.0).abs() < 0.5)
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

/// A point's name in `lang`, short so that names do not crowd (the legend says what they are):
/// `centre`, `corners`, `0.1, K = 2` (adaptive), `3` (a depth limit), `grid`.
fn point_name(sweep: Sweep, setting: &Setting, lang: Lang) -> String {
    match sweep {
        Sweep::Sampling => match setting.sampling {
            Sampling::Center => Label::SamplingCentre.text(lang).to_owned(),
            Sampling::Corners => Label::SamplingCorners.text(lang).to_owned(),
            Sampling::Adaptive { threshold, max_level } => {
                format!("{}, K = {max_level}", slide_number(threshold))
            }
        },
        Sweep::Depth => setting.depth.to_string(),
        Sweep::Accel => setting.accel.name().to_owned(),
    }
}

/// The names of settings that fall on one point, as one: `5 … 8` for a run of depths, else the
/// names joined by ` = `.
fn group_name(sweep: Sweep, settings: &[&Setting], lang: Lang) -> String {
    match settings {
        [one] => point_name(sweep, one, lang),
        [first, .., last] if sweep == Sweep::Depth => format!("{} … {}", first.depth, last.depth),
        many => many.iter().map(|s| point_name(sweep, s, lang)).collect::<Vec<_>>().join(" = "),
    }
}

/// A reference's setting in full, for the caption: `adaptive 0, K = 3`, `depth limit 16`.
fn reference_name(sweep: Sweep, setting: &Setting, lang: Lang) -> String {
    match (sweep, setting.sampling) {
        (Sweep::Sampling, Sampling::Adaptive { .. }) => {
            format!("{} {}", Label::SamplingAdaptive.text(lang), point_name(sweep, setting, lang))
        }
        (Sweep::Depth, _) => format!("{} {}", Label::DepthLimit.text(lang), setting.depth),
        _ => point_name(sweep, setting, lang),
    }
}

/// The words of a sweep's plot.
struct SweepWords {
    /// The plot's title.
    title: Label,
    /// The caption's note on the reference.
    reference: Label,
    /// The legend's note on the points' names.
    points: Label,
}

/// The words of a sweep's plot; none for the structures, whose error is 0 by design (nothing
/// to plot).
fn words(sweep: Sweep) -> Option<SweepWords> {
    match sweep {
        Sweep::Sampling => Some(SweepWords {
            title: Label::TitleTradeoffSampling,
            reference: Label::ReferenceSampling,
            points: Label::PointsSampling,
        }),
        Sweep::Depth => Some(SweepWords {
            title: Label::TitleTradeoffDepth,
            reference: Label::ReferenceDepth,
            points: Label::PointsDepth,
        }),
        Sweep::Accel => None,
    }
}

/// Draws the plot of one sweep with its Pareto front (indices into `measured.rows`).
///
/// # Errors
/// When the canvas is empty, the sweep is the structures' (their error is 0: nothing to plot), or
/// no setting traced a ray.
pub fn draw(
    measured: &Measurement,
    front: &[usize],
    scene_name: &str,
    opts: &Options,
) -> Result<Drawing, FigureError> {
    let mut d = Drawing::new(opts.width, opts.height)
        .ok_or_else(|| FigureError(format!("a {}×{} canvas is empty", opts.width, opts.height)))?;
    let lang = opts.lang;
    let t = |label: Label| label.text(lang);
    let (sweep, rows) = (measured.sweep, &measured.rows);
    let reference = &measured.reference;
    let SweepWords { title, reference: reference_note, points: points_note } =
        words(sweep).ok_or_else(|| FigureError("a structure changes no pixel: no error to plot".into()))?;
    d.set_title(t(title));
    d.set_caption(&format!(
        "{} {} · {} ({} {} {}) · {}",
        t(Label::Scene),
        markup_escape(scene_name),
        t(reference_note),
        slide_number(reference.rays_per_pixel()),
        t(Label::RaysPerPixelShort),
        markup_escape(&reference_name(sweep, &reference.setting, lang)),
        t(Label::TimesInTable),
    ));

    // World: the error up [0, 1] (log above the zero row, when there is one), log rays across
    // [0, x_end], so that the plot with its margins (tick names left and below, the legend's band
    // above) fills the plot area.
    let (left, bottom, right) = (0.1, 0.16, 0.03);
    let world_height = bottom + 1.0 + LEGEND_BAND;
    let world_width = d.plot_aspect() * world_height;
    let x_end = world_width * (1.0 - left - right);
    let rays_axis = LogAxis::around(rows.iter().map(Measured::rays_per_pixel))
        .ok_or_else(|| FigureError("no setting traced a ray".into()))?;
    let has_zero = rows.iter().any(|m| m.error.rmse == 0.0);
    let error_axis = LogAxis::around(rows.iter().map(|m| m.error.rmse));
    let log_from = if has_zero { LOG_FROM_WITH_ZERO } else { 0.0 };
    let y_of = |rmse: f64| match error_axis {
        Some(axis) if rmse > 0.0 => log_from + (1.0 - log_from) * axis.at(rmse),
        _ => ZERO_ROW,
    };
    let at = |m: &Measured| DVec2::new(x_end * rays_axis.at(m.rays_per_pixel()), y_of(m.error.rmse));
    d.set_view(
        View::new(-left * world_width, (1.0 - left) * world_width, -bottom, 1.0 + LEGEND_BAND)
            .ok_or_else(|| FigureError("the plot area is empty".into()))?,
    );

    // Axes, ticks and their names.
    let axis = Pen::solid(style::DARK_GREY, style::GRID_WIDTH);
    let y_end = DVec2::new(0.0, 1.0);
    d.segment("axis", DVec2::ZERO, DVec2::new(x_end, 0.0), axis);
    d.segment("axis", DVec2::ZERO, y_end, axis);
    let tick_len = 0.015;
    for x in rays_axis.ticks() {
        let p = DVec2::new(x_end * rays_axis.at(x), 0.0);
        d.segment("axis", p, p - DVec2::new(0.0, tick_len), axis);
        if rays_axis.names(x) {
            d.text("tick", p, &slide_number(x), TextOpts::NOTE.align(Align::BELOW).offset(0.0, -14.0));
        }
    }
    let y_ticks = error_axis.map(LogAxis::ticks).unwrap_or_default();
    let tick_name = TextOpts::NOTE.align(Align::LEFT_OF).offset(-14.0, 0.0);
    for v in &y_ticks {
        let p = DVec2::new(0.0, y_of(*v));
        d.segment("axis", p, p - DVec2::new(tick_len, 0.0), axis);
        if error_axis.is_some_and(|a| a.names(*v)) {
            d.text("tick", p, &slide_number(*v), tick_name);
        }
    }
    if has_zero {
        let p = DVec2::new(0.0, ZERO_ROW);
        d.segment("axis", p, p - DVec2::new(tick_len, 0.0), axis);
        d.text("tick", p, "0", tick_name);
    }
    let below_axis = TextOpts::LABEL.align(Align::BELOW).offset(0.0, -60.0);
    d.text("axis-name", DVec2::new(0.5 * x_end, 0.0), t(Label::AxisRaysPerPixel), below_axis);
    // The error axis's name above its top, clear of the points' names below.
    d.text(
        "axis-name",
        y_end,
        t(Label::AxisRmse),
        TextOpts::LABEL.align(Align::RIGHT_OF).offset(-40.0, 56.0),
    );

    // The front first, under the points.
    let front_points: Vec<DVec2> = front.iter().map(|&i| at(&rows[i])).collect();
    let front_style =
        Pen::solid(style::DARK_GREY, style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH);
    if front_points.len() > 1 {
        d.line("pareto", front_points, front_style);
    }
    // The points, those on one spot (the same rays and error) as one.
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for i in 0..rows.len() {
        let same = |j: usize| {
            rows[j].stats.rays == rows[i].stats.rays
                && rows[j].error.rmse.to_bits() == rows[i].error.rmse.to_bits()
        };
        match groups.iter_mut().find(|g| same(g[0])) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    let fill = colour(sweep);
    for g in &groups {
        let on_front = g.iter().any(|i| front.contains(i));
        let radius = if on_front { style::DOT_RADIUS * 1.4 } else { style::DOT_RADIUS };
        d.marker("setting", at(&rows[g[0]]), radius, fill, Pen::solid(style::WHITE, 2.0));
    }
    // Every point named, clear of the others and inside the axes, a leader to a name set apart.
    d.keep_labels_within(DVec2::ZERO, DVec2::new(x_end, 1.0 + LEGEND_BAND));
    for g in &groups {
        let settings: Vec<&Setting> = g.iter().map(|&i| &rows[i].setting).collect();
        let p = at(&rows[g[0]]);
        // Names go right of their points, but left of those near the right end, where there is
        // no room.
        let side = if p.x < NAME_LEFT_FROM * x_end {
            TextOpts::NOTE.align(Align::RIGHT_OF).offset(22.0, 14.0)
        } else {
            TextOpts::NOTE.align(Align::LEFT_OF).offset(-22.0, 14.0)
        };
        d.text(
            "setting-name",
            p,
            &markup_escape(&group_name(sweep, &settings, lang)),
            side.size(TextSize::Small).avoid_overlap_with_leader().far(),
        );
    }

    d.legend_entry(t(points_note), Pen::NONE, LegendIcon::Dot(fill));
    d.legend_entry(t(Label::ParetoFront), front_style, LegendIcon::Line);
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

    #[test]
    fn a_long_log_axis_names_fewer_ticks() {
        let named = |lo: f64, hi: f64| {
            let axis = LogAxis::around([lo, hi]).unwrap();
            axis.ticks().into_iter().filter(|v| axis.names(*v)).collect::<Vec<_>>()
        };
        assert_eq!(named(0.01, 0.2), vec![0.01, 0.02, 0.05, 0.1, 0.2]);
        assert_eq!(named(0.001, 0.5), vec![0.001, 0.005, 0.01, 0.05, 0.1, 0.5]);
        assert_eq!(named(1e-6, 0.5).len(), 6, "{:?}", named(1e-6, 0.5));
    }

    #[test]
    fn settings_on_one_point_share_a_name() {
        let depth = |d| Setting { depth: d, ..Setting::scene_render(4) };
        let (five, eight) = (depth(5), depth(8));
        assert_eq!(group_name(Sweep::Depth, &[&five, &eight], Lang::Ro), "5 … 8");
        assert_eq!(group_name(Sweep::Depth, &[&five], Lang::En), "5");
        assert_eq!(reference_name(Sweep::Depth, &depth(16), Lang::Ro), "adâncimea maximă 16");
        let adaptive = Setting { sampling: Sampling::Adaptive { threshold: 0.1, max_level: 2 }, ..depth(4) };
        let centre = Setting { sampling: Sampling::Center, ..depth(4) };
        assert_eq!(group_name(Sweep::Sampling, &[&centre, &adaptive], Lang::Ro), "centru = 0.1, K = 2");
    }
}
