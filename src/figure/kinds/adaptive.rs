//! `adaptive` (lecture "Îmbunătățirea calității imaginii (2)", algorithm.md §8.2): one pixel's
//! recorded adaptive subdivision — the squares of each level shaded darker, the samples labelled
//! in the order they were traced as the lecture does (CA, CB, …), the ones another square read
//! again ringed, each leaf's colour (the mean of its corners) at its centre — and beside it the
//! rule, the counts and the area-weighted mean, with the recorded numbers. Each leaf says why it
//! stopped: under the threshold, or at the maximum level K. In 2D the pixel is an interval and
//! each level's intervals are drawn under it. A pixel sampled uniformly (`--aa corners`, the
//! lecture's "uniformă", §8.1) is drawn as that method: its 4 shared corners and their mean.

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign};
use crate::figure::labels::Label;
use crate::figure::parts::{self, rgb_text, swatch, text_column};
use crate::figure::plane::Planar;
use crate::figure::style::{self, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::record::event::Event;
use crate::sample::{PixelTrace, SquareRecord};

/// The shade of a square of `level`: grey, darker with each level.
fn shade(level: u32) -> style::Rgba {
    style::DARK_GREY.with_alpha(0.06 + 0.14 * f64::from(level))
}

/// Draws the figure.
///
/// # Errors
/// When the trace holds no sampled pixel.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let pixel =
        traced.samples.as_ref().ok_or_else(|| FigureError("the trace holds no sampled pixel".into()))?;
    let (i, j) = match traced.targets.first() {
        Some(crate::figure::source::Target::Pixel { i, j, .. }) => (*i, *j),
        _ => (0, 0),
    };
    let scale = f64::from(1u32 << pixel.max_level);
    // A lattice point of this pixel in the unit square (2D: on the unit interval, y = 0).
    let local = |lattice: &[u64]| -> DVec2 {
        let x = (lattice[0] as f64 - i as f64 * scale) / scale;
        let y = lattice.get(1).map_or(0.0, |y| (*y as f64 - j as f64 * scale) / scale);
        DVec2::new(x, y)
    };
    let flat = V::DIM == 2;
    let deepest = pixel.squares.iter().map(|s| s.level).max().unwrap_or(0);

    if pixel.uniform {
        d.set_title(input.t(Label::TitleUniform));
        d.set_caption(&format!("{} · {}", input.traced(traced), input.t(Label::UniformRule)));
    } else {
        d.set_title(input.t(Label::TitleAdaptive));
        let rule = format!(
            "{} = {}, K = {}",
            input.t(Label::Threshold),
            slide_number(pixel.threshold),
            pixel.max_level
        );
        d.set_caption(&format!("{} · {rule}", input.traced(traced)));
    }
    for level in (0..=deepest).filter(|_| !pixel.uniform) {
        d.legend_entry(
            &format!("{} {level}", input.t(Label::Level)),
            Pen::NONE,
            LegendIcon::Swatch(shade(level)),
        );
    }
    // A uniform pixel's four corners are drawn in their colours (the mean is theirs); the adaptive
    // figure's many samples stay black dots, their colours in the leaves.
    let sample_icon = if pixel.uniform {
        (style::outline(style::BLACK), LegendIcon::Dot(style::LIGHT_GREY))
    } else {
        (Pen::NONE, LegendIcon::Dot(style::BLACK))
    };
    d.legend_entry(input.t(Label::SampleTraced), sample_icon.0, sample_icon.1);
    // A pixel no square split (threshold ∞, or K = 0) reads nothing again: no ring to explain.
    if pixel.samples.iter().any(|s| s.reused) {
        d.legend_entry(input.t(Label::SampleReused), reused_ring(), LegendIcon::Dot(style::WHITE));
    }
    if pixel.uniform {
        d.legend_entry(input.t(Label::UniformMean), mean_outline(), LegendIcon::Dot(style::LIGHT_GREY));
    } else {
        for stop in [Stop::Threshold, Stop::MaxLevel] {
            if pixel.squares.iter().any(|s| stop_of(s, pixel) == Some(stop)) {
                d.legend_entry(input.t(stop.label()), stop.outline(), LegendIcon::Dot(style::LIGHT_GREY));
            }
        }
    }
    let (bottom, top) = if flat { (-0.2 * f64::from(deepest + 1) - 0.1, 0.12) } else { (-0.05, 1.08) };
    let column = parts::fit_with_column(d, &[DVec2::new(-0.08, bottom), DVec2::new(1.08, top)], 0.02, 0.45);

    // The squares, parents first so that each leaf shows its own level's shade.
    let rect_of = |s: &SquareRecord| -> (DVec2, DVec2) {
        let lo = local(&s.lattice);
        let side = s.side as f64 / scale;
        if flat {
            let top = -0.2 * f64::from(s.level) - 0.05;
            (DVec2::new(lo.x, top - 0.14), DVec2::new(lo.x + side, top))
        } else {
            (lo, lo + DVec2::splat(side))
        }
    };
    // The events each item draws: the pixel the primary rays of its corners (the narration's
    // step 1), a sample its primary ray and every read of it (`sample` events), a square (and its
    // leaf colour) its corners'.
    let log = &traced.log;
    let pixel_events: Vec<usize> =
        pixel.samples.iter().filter(|s| s.level == 0).filter_map(|s| log.spawned_by(s.root)).collect();
    if flat {
        d.with_events(pixel_events.iter().copied(), |d| {
            d.rect("pixel", DVec2::ZERO, DVec2::new(1.0, BAR), style::object(), None);
        });
    }
    let sample_events: Vec<Vec<usize>> = (pixel.samples.iter().enumerate())
        .map(|(k, sample)| {
            let reads = (log.events.iter().enumerate())
                .filter(|(_, l)| l.sample == Some(k) && matches!(l.event, Event::Sample { .. }))
                .map(|(index, _)| index);
            log.spawned_by(sample.root).into_iter().chain(reads).collect()
        })
        .collect();
    let square_events = |s: &SquareRecord| -> Vec<usize> {
        s.corners.iter().filter_map(|c| sample_events.get(*c)).flatten().copied().collect()
    };
    for s in &pixel.squares {
        let (lo, hi) = rect_of(s);
        d.with_events(square_events(s), |d| {
            d.rect(
                &format!("square:{}", s.level),
                lo,
                hi,
                Pen::solid(style::DARK_GREY, style::GRID_WIDTH),
                Some(shade(s.level)),
            );
        });
    }
    if !flat {
        d.with_events(pixel_events.iter().copied(), |d| {
            d.rect("pixel", DVec2::ZERO, DVec2::ONE, style::object(), None);
        });
    }
    for s in pixel.squares.iter().filter(|s| !s.split) {
        let (lo, hi) = rect_of(s);
        let stop = stop_of(s, pixel).unwrap_or(Stop::Threshold);
        let (tag, outline) = if pixel.uniform {
            ("leaf-colour:uniform".to_owned(), mean_outline())
        } else {
            (format!("leaf-colour:{}", stop.class()), stop.outline())
        };
        d.with_events(square_events(s), |d| {
            d.marker(&tag, (lo + hi) / 2.0, 16.0, swatch(s.color), outline);
        });
    }
    for (sample, events) in pixel.samples.iter().zip(&sample_events) {
        let at = local(&sample.lattice);
        d.with_events(events.iter().copied(), |d| {
            if sample.reused {
                d.marker("sample:reused", at, RING_RADIUS, style::WHITE.with_alpha(0.0), reused_ring());
            }
            if pixel.uniform {
                d.marker("sample", at, CORNER_RADIUS, swatch(sample.color), style::outline(style::BLACK));
            } else {
                d.marker("sample", at, 8.0, style::BLACK, Pen::NONE);
            }
        });
    }
    for (sample, events) in pixel.samples.iter().zip(&sample_events) {
        let at = local(&sample.lattice);
        d.with_events(events.iter().copied(), |d| {
            let small = TextOpts::NOTE.size(TextSize::Small);
            if flat {
                // Centred above the pixel's bar (whose bottom edge holds the points), clear of it.
                let above = Align { h: HAlign::Center, v: VAlign::Bottom };
                d.text(
                    "sample-name",
                    at + DVec2::new(0.0, BAR),
                    &sample.label,
                    small.align(above).offset(0.0, 6.0),
                );
            } else {
                // Up and to the right of its point, as the lecture's figure writes them; a ringed
                // one's corner outside its ring (|(14, 12)| = 18.4 > RING_RADIUS).
                let up_right = Align { h: HAlign::Left, v: VAlign::Bottom };
                let (dx, dy) = if sample.reused || pixel.uniform { (14.0, 12.0) } else { (8.0, 6.0) };
                d.text("sample-name", at, &sample.label, small.align(up_right).offset(dx, dy));
            }
        });
    }

    text_column(d, column + DVec2::new(0.04, -0.02), &numbers(input, pixel), TextSize::Body, 50.0);
    Ok(())
}

/// Why a leaf square was not split (lecture: "până la un nivel maxim prestabilit sau până când
/// diferența dintre cele 4 culori scade sub un prag dat").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stop {
    /// Its corners differ by less than the threshold.
    Threshold,
    /// Its corners differ by the threshold or more, but it is at level K.
    MaxLevel,
}

impl Stop {
    fn label(self) -> Label {
        match self {
            Stop::Threshold => Label::LeafUnderThreshold,
            Stop::MaxLevel => Label::LeafAtMaxLevel,
        }
    }

    /// The item tag's suffix.
    fn class(self) -> &'static str {
        match self {
            Stop::Threshold => "threshold",
            Stop::MaxLevel => "max-level",
        }
    }

    /// The leaf colour disc's outline: black, or a thick vermillion ring at the maximum level.
    fn outline(self) -> Pen {
        match self {
            Stop::Threshold => style::outline(style::BLACK),
            Stop::MaxLevel => Pen::solid(style::VERMILLION, style::OBJECT_WIDTH * 1.5),
        }
    }
}

/// Why square `s` is a leaf, or None when it was split: the rule splits while `spread ≥
/// threshold` and `level < K`, so a leaf either fell under the threshold or reached level K.
fn stop_of(s: &SquareRecord, pixel: &PixelTrace) -> Option<Stop> {
    if s.split {
        None
    } else if s.spread < pixel.threshold {
        Some(Stop::Threshold)
    } else {
        Some(Stop::MaxLevel)
    }
}

/// The height of a 2D pixel's bar, in pixel widths: its bottom edge holds the samples.
const BAR: f64 = 0.02;

/// The radius of the ring around a sample that another square read again (reference pixels).
const RING_RADIUS: f64 = 17.0;

/// The ring of a sample that another square read again.
fn reused_ring() -> Pen {
    Pen::solid(style::ORANGE, style::CONSTRUCTION_WIDTH)
}

/// The radius, in reference pixels, of a uniform pixel's corner, filled with its colour.
const CORNER_RADIUS: f64 = 14.0;

/// How much thicker than a corner's the outline of a uniform pixel's mean is, so that the mean
/// and the samples it averages read apart, in the figure and in its legend.
const MEAN_OUTLINE_SCALE: f64 = 2.0;

/// The outline of a uniform pixel's mean: a corner's, [`MEAN_OUTLINE_SCALE`] times as thick.
fn mean_outline() -> Pen {
    let pen = style::outline(style::BLACK);
    pen.with_width(pen.width * MEAN_OUTLINE_SCALE)
}

/// The text beside the pixel: the rule, the samples, a deepest leaf's mean and the pixel's.
fn numbers<V: Planar>(input: &Input<'_, V>, pixel: &PixelTrace) -> Vec<String> {
    let k = pixel.max_level;
    let per_side = (1u64 << k) + 1;
    let full = if V::DIM == 2 { per_side } else { per_side * per_side };
    let corners = if V::DIM == 2 { 2 } else { 4 };
    // The corner reads that traced no new ray: every square reads its corners, and only the
    // first read of a lattice point traces it (a `sample` event with `reused: true` each).
    let reads: usize = pixel.squares.iter().map(|s| s.corners.len()).sum();
    let rule = if pixel.uniform {
        let shared = if V::DIM == 2 { Label::UniformShared2d } else { Label::UniformShared };
        let mut lines = vec![input.t(Label::UniformCorners).to_owned()];
        lines.extend(input.t(shared).lines().map(str::to_owned));
        lines
    } else if k == 0 {
        vec![input.t(Label::CornersOnly).to_owned()]
    } else {
        vec![
            format!("{}:", input.t(Label::SplitWhen)),
            format!(
                "   max − min ≥ {} (R, G, B), {} < K = {k}",
                slide_number(pixel.threshold),
                input.t(Label::Level)
            ),
        ]
    };
    let mut lines = rule;
    let traced = pixel.samples.len();
    if !pixel.uniform {
        lines.push(format!("{}: {traced} / {full}", input.t(Label::SamplesTraced)));
        lines.push(format!("{}: {}", input.t(Label::Reused), reads.saturating_sub(traced)));
    }
    // A uniform pixel's corners, each as traced: the mean below is theirs.
    if pixel.uniform {
        lines.extend(pixel.samples.iter().map(|s| format!("{} = {}", s.label, rgb_text(s.color))));
    }
    // The deepest leaf's colour, the lecture's (CN + CL + CG + CM)/4.
    if let Some(leaf) = pixel.squares.iter().filter(|s| !s.split).max_by_key(|s| s.level) {
        let names: Vec<&str> = leaf.corners.iter().map(|c| pixel.samples[*c].label.as_str()).collect();
        lines.push(format!("({})/{corners} = {}", names.join(" + "), rgb_text(leaf.color)));
    }
    if pixel.uniform {
        return lines;
    }
    let (level, leaf) = (input.t(Label::LevelSymbol), input.t(Label::LeafSymbol));
    let base = if V::DIM == 2 { 2 } else { 4 };
    lines.push(format!(
        "{} = Σ {base}^{{−{level}}}·C_{{{leaf}}} = {}",
        input.t(Label::PixelColour),
        rgb_text(pixel.color)
    ));
    lines
}
