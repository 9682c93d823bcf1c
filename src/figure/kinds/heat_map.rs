//! `heat-map` (lecture "Îmbunătățirea calității imaginii", algorithm.md §8; the cost of §7): the
//! number of samples (primary rays) whose colour entered each pixel of a whole render — a corner
//! shared by neighbours counted in each of them, while the caption counts the rays traced, each
//! shared corner once — for one sampling
//! mode, on a colour scale (viridis, readable with any common colour-vision deficiency) that
//! every heat map shares, logarithmic from 1 to 81 samples, so that two maps compare: 1 with
//! `center`, 4 with `corners`, 4 to (2^K + 1)² with `adaptive`, where the image changes. The counts
//! are the render's own (`Rendered::rays_per_pixel`); rows count from the bottom.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, LegendIcon, Pen};
use crate::figure::labels::Label;
use crate::figure::plane::Planar;
use crate::figure::style::{self, Rgba};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::sample::Sampling;

/// Up to this many distinct counts get a colour (and a legend line) each.
const MAX_LISTED: usize = 6;
/// Otherwise the counts fall into this many equal bins.
const BINS: u32 = 5;

/// Viridis at five stops, dark (few rays) to light (many).
const VIRIDIS: [Rgba; 5] = [
    Rgba::rgb(0x44, 0x01, 0x54),
    Rgba::rgb(0x3B, 0x52, 0x8B),
    Rgba::rgb(0x21, 0x91, 0x8C),
    Rgba::rgb(0x5E, 0xC9, 0x62),
    Rgba::rgb(0xFD, 0xE7, 0x25),
];

/// The colour of `f` in [0, 1] on the scale (linear between the stops).
fn scale_colour(f: f64) -> Rgba {
    let f = f.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f64;
    // f lies in [0, 4], so the index is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let k = (f.floor() as usize).min(VIRIDIS.len() - 2);
    let t = f - k as f64;
    let mix = |a: u8, b: u8| {
        let v = f64::from(a) + (f64::from(b) - f64::from(a)) * t;
        // v lies between two bytes.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let byte = v.round().clamp(0.0, 255.0) as u8;
        byte
    };
    let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
    Rgba::rgb(mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b))
}

/// The count at the light end of the one scale every heat map shares: (2^K + 1)² samples, the
/// most a pixel reads when adaptive sampling splits to K = 3, the deepest the lessons go; larger
/// counts take the light end too.
const SCALE_TOP: f64 = 81.0;

/// Where `n` samples fall on the shared scale, in [0, 1]: `log n / log SCALE_TOP`.
fn scale_place(n: f64) -> f64 {
    (n.max(1.0).ln() / SCALE_TOP.ln()).clamp(0.0, 1.0)
}

/// Draws the figure.
///
/// # Errors
/// When no render's counts were recorded.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let counts = input.traces.counts.as_ref().ok_or_else(|| FigureError("no render was counted".into()))?;
    let cam = &input.scene.camera;
    let (nx, ny) = (cam.nx, cam.ny);
    let lo = counts.per_pixel.iter().copied().min().unwrap_or(0);
    let hi = counts.per_pixel.iter().copied().max().unwrap_or(0);
    // Few distinct counts: one colour each. Many: BINS equal bins of counts, one colour each, so
    // that the legend names every count that occurs and every colour drawn.
    let mut distinct: Vec<u32> = counts.per_pixel.clone();
    distinct.sort_unstable();
    distinct.dedup();
    let bins: Vec<(u32, u32)> = if distinct.len() <= MAX_LISTED {
        distinct.iter().map(|n| (*n, *n)).collect()
    } else {
        let width = (hi - lo + 1).div_ceil(BINS);
        (0..BINS)
            .map(|k| (lo + k * width, (lo + (k + 1) * width - 1).min(hi)))
            .filter(|(a, _)| *a <= hi)
            .collect()
    };
    // Every map on one scale (issue 32 item 3: maps a caption compares read alike): a count's
    // place on it is log n / log SCALE_TOP, so 1 sample is the darkest and 81 the lightest in
    // every figure; a bin of counts takes its middle's.
    let shade = |k: usize| {
        let (a, b) = bins[k];
        scale_colour(scale_place(f64::from(a + b) / 2.0))
    };
    let colour = |n: u32| shade(bins.iter().position(|(a, b)| (*a..=*b).contains(&n)).unwrap_or(0));

    d.set_title(input.t(Label::TitleHeatMap));
    // The sampling as the command line writes it in English (`--aa adaptive`), in words in Romanian.
    let kind = |en: &str, word: Label| match input.lang {
        crate::figure::Lang::En => en.to_owned(),
        crate::figure::Lang::Ro => input.t(word).to_owned(),
    };
    let aa = input.t(Label::SamplingIs);
    let mode = match counts.sampling {
        Sampling::Center => format!("{aa} {}", kind("center", Label::SamplingCentre)),
        Sampling::Corners => format!("{aa} {}", kind("corners", Label::SamplingCorners)),
        Sampling::Adaptive { threshold, max_level } => {
            format!(
                "{aa} {}, {} = {}, K = {max_level}",
                kind("adaptive", Label::SamplingAdaptive),
                input.t(Label::Threshold),
                slide_number(threshold)
            )
        }
    };
    let pixels = counts.per_pixel.len().max(1);
    let sum: u64 = counts.per_pixel.iter().map(|n| u64::from(*n)).sum();
    let rows = if V::DIM == 2 { String::new() } else { format!(" · {}", input.t(Label::RowsFromBottom)) };
    d.set_caption(&format!(
        "{}{mode} · {} · {}: {} · {}: {}{rows}",
        crate::figure::labels::scene_lead(&input.traces.scene_name, input.lang),
        input.t(Label::HeatMapCounts),
        input.t(Label::RaysTraced),
        counts.traced,
        input.t(Label::MeanPerPixel),
        slide_number(sum as f64 / pixels as f64),
    ));
    // The legend is the scale: every count, or every bin of counts, that a pixel has.
    let unit = input.t(Label::SamplesUnit);
    for (k, (a, b)) in bins.iter().enumerate() {
        if !counts.per_pixel.iter().any(|n| (*a..=*b).contains(n)) {
            continue;
        }
        let range = if a == b { a.to_string() } else { format!("{a}–{b}") };
        d.legend_entry(&format!("{range} {unit}"), Pen::NONE, LegendIcon::Swatch(shade(k)));
    }
    d.legend_entry(
        &format!("{}: 1 … {}", input.t(Label::OneScale), slide_number(SCALE_TOP)),
        // No icon: the line of no stroke leaves its place blank.
        Pen::NONE,
        LegendIcon::Line,
    );
    d.legend_place = crate::canvas::LegendPlace::Outside;

    // One cell per pixel, y up so that row j = 0 is the bottom; a 2D image is one row, drawn as
    // tall as an eighth of its width. Equal neighbours in a row share one rectangle.
    let row_h = if V::DIM == 2 { (nx as f64 / 8.0).max(1.0) } else { 1.0 };
    d.fit_view(&[DVec2::ZERO, DVec2::new(nx as f64, row_h * ny as f64)], 0.02);
    // Each rectangle reaches at least a pixel and a half into its right and upper neighbours,
    // which are drawn after it and cover it: no anti-aliased seam shows between cells.
    let (width, height) = (nx as f64, row_h * ny as f64);
    let reach = 1.5 / d.transform().len_px(1.0).max(1e-9);
    for j in 0..ny {
        let row = &counts.per_pixel[j * nx..(j + 1) * nx];
        let mut start = 0;
        for i in 1..=nx {
            if i == nx || row[i] != row[start] {
                let y = j as f64 * row_h;
                let fill = colour(row[start]);
                let hi = DVec2::new((i as f64 + reach).min(width), (y + row_h + reach).min(height));
                d.rect("cell", DVec2::new(start as f64, y), hi, Pen::NONE, Some(fill));
                start = i;
            }
        }
    }
    d.rect("image", DVec2::ZERO, DVec2::new(width, height), style::object(), None);
    Ok(())
}
