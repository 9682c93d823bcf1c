//! `heat-map` (lecture "Îmbunătățirea calității imaginii", algorithm.md §8; the cost of §7): the
//! number of samples (primary rays) whose colour entered each pixel of a whole render — a corner
//! shared by neighbours counted in each of them, while the caption counts the rays traced, each
//! shared corner once — for one sampling
//! mode, on a colour scale (viridis, readable with any common colour-vision deficiency) that
//! every heat map shares, so that two maps compare: ten bins of equal width on a logarithmic
//! scale from 1 to 81 samples (1 with `center`, 4 with `corners`, 4 to (2^K + 1)² with
//! `adaptive`, where the image changes), each bin one colour, the ten spread over the whole of
//! viridis, so that neighbouring bins stay apart on a slide. The counts are the render's own
//! (`Rendered::rays_per_pixel`); rows count from the bottom.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, LegendIcon, Pen};
use crate::figure::labels::Label;
use crate::figure::plane::Planar;
use crate::figure::style::{self, Rgba};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::sample::Sampling;

/// Viridis at nine stops (0, 1/8 … 1), dark (few rays) to light (many): its lightness grows
/// evenly, so that order reads without hue.
const VIRIDIS: [Rgba; 9] = [
    Rgba::rgb(0x44, 0x01, 0x54),
    Rgba::rgb(0x47, 0x2D, 0x7B),
    Rgba::rgb(0x3B, 0x52, 0x8B),
    Rgba::rgb(0x2C, 0x72, 0x8E),
    Rgba::rgb(0x21, 0x91, 0x8C),
    Rgba::rgb(0x28, 0xAE, 0x80),
    Rgba::rgb(0x5E, 0xC9, 0x62),
    Rgba::rgb(0xAD, 0xDC, 0x30),
    Rgba::rgb(0xFD, 0xE7, 0x25),
];

/// The colour of `f` in [0, 1] on the scale (linear between the stops).
fn scale_colour(f: f64) -> Rgba {
    let f = f.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f64;
    // f lies in [0, 8], so the index is exact.
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

/// The shared scale's bins, by their least count: bin k holds the counts n with
/// `SCALE_TOP^(k/10) ≤ n < SCALE_TOP^((k+1)/10)`, so its least count is `⌈81^(k/10)⌉` (the last
/// bin runs on past 81). Ten bins of equal width on the logarithmic scale: a K = 2 map (4 to 25
/// samples) spans five of them, a K = 3 map (4 to 81) seven, each in its own colour.
const SCALE_BINS: [u32; 10] = [1, 2, 3, 4, 6, 9, 14, 22, 34, 53];

/// The least CIE76 colour difference between neighbouring bins of the shared scale, and so
/// between neighbouring swatches of any legend: about four times the just noticeable difference
/// (ΔE ≈ 2.3, side by side), since a slide sets a map's small cells far from their swatch and a
/// projector washes colours out; the top two swatches of the old scale (19–23 and 24–25 samples
/// of a K = 2 map) were 7.3 apart and read as one.
pub const MIN_SWATCH_DELTA_E: f64 = 10.0;

/// The bin of the shared scale that `n` samples fall in.
fn scale_bin(n: u32) -> usize {
    SCALE_BINS.iter().rposition(|least| *least <= n).unwrap_or(0)
}

/// The colour of bin `k` of the shared scale: the bins spread evenly over the whole of viridis,
/// the first at its dark end and the last at its light end.
fn bin_colour(k: usize) -> Rgba {
    scale_colour(k as f64 / (SCALE_BINS.len() - 1) as f64)
}

/// Draws the figure.
///
/// # Errors
/// When no render's counts were recorded.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let counts = input.traces.counts.as_ref().ok_or_else(|| FigureError("no render was counted".into()))?;
    let cam = &input.scene.camera;
    let (nx, ny) = (cam.nx, cam.ny);
    // Every map on one scale (issue 32 item 3: maps a caption compares read alike): a count's
    // colour is its bin's on the shared scale, whatever else the map holds.
    let colour = |n: u32| bin_colour(scale_bin(n));

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
    // The legend is the scale where this map lies on it: every bin that a pixel's count falls
    // in, named by the least and the most count of the map's pixels in it.
    let unit = input.t(Label::SamplesUnit);
    let mut held: Vec<(usize, u32)> = counts.per_pixel.iter().map(|n| (scale_bin(*n), *n)).collect();
    held.sort_unstable();
    held.dedup();
    for bin in held.chunk_by(|x, y| x.0 == y.0) {
        let (k, a, b) = (bin[0].0, bin[0].1, bin[bin.len() - 1].1);
        let range = if a == b { a.to_string() } else { format!("{a}–{b}") };
        d.legend_entry(&format!("{range} {unit}"), Pen::NONE, LegendIcon::Swatch(bin_colour(k)));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bins_are_equal_steps_of_the_logarithmic_scale() {
        for (k, least) in SCALE_BINS.iter().enumerate() {
            // ⌈81^(k/10)⌉, with room for the rounding of an exact power (81^(5/10) = 9).
            let edge = SCALE_TOP.powf(k as f64 / SCALE_BINS.len() as f64);
            // Both sides are small whole numbers, exact in f64.
            #[allow(clippy::float_cmp)]
            let same = f64::from(*least) == (edge - 1e-9).ceil();
            assert!(same, "bin {k}: {least} against 81^({k}/10) = {edge}");
        }
        assert_eq!(scale_bin(1), 0);
        assert_eq!(scale_bin(4), 3);
        assert_eq!(scale_bin(25), 7);
        assert_eq!(scale_bin(81), 9);
        assert_eq!(scale_bin(289), 9);
    }

    #[test]
    fn neighbouring_bins_differ_and_darken_towards_fewer_samples() {
        for k in 1..SCALE_BINS.len() {
            let (a, b) = (bin_colour(k - 1), bin_colour(k));
            let delta = a.delta_e76(b);
            assert!(delta >= MIN_SWATCH_DELTA_E, "bins {} and {k}: ΔE {delta:.1}", k - 1);
            assert!(a.lab()[0] < b.lab()[0], "bin {k} is not lighter than bin {}", k - 1);
        }
    }
}
