//! `jagged-edges` (lecture "Deficiențele algoritmului", 1: "marginile au aspect zimțat";
//! algorithm.md §7, §8): the same crop of the scene's image rendered twice, side by side, each
//! pixel a square of its colour as the PNG stores it (`round(255·clamp(c, 0, 1))`): left with one
//! ray through each pixel's centre, where an edge is a staircase of whole pixels; right
//! supersampled (the pixel's corners, or adaptive subdivision), where the pixels the edge crosses
//! take the mean of their samples. Both are whole renders (`source::Jagged`), rows from the
//! bottom; the caption counts the primary rays each traced for the whole image.

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, Pen, TextOpts};
use crate::figure::labels::{scene_lead, Label};
use crate::figure::parts::swatch;
use crate::figure::plane::Planar;
use crate::figure::style::{self, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::sample::Sampling;

/// The gap between the two panels, in pixels of the crop.
const PANEL_GAP: f64 = 1.5;

/// The stroke of the pixel grid over a panel.
fn grid_pen() -> Pen {
    Pen::solid(style::WHITE.with_alpha(0.6), style::GRID_WIDTH * 0.5)
}

/// Draws the figure.
///
/// # Errors
/// When the two renders were not made.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let jagged = input.traces.jagged.as_ref().ok_or_else(|| FigureError("no render was made".into()))?;
    let (i0, j0) = jagged.corner;
    let (w, h) = jagged.size;
    let [centre, fine] = &jagged.renders;
    let heading = |sampling: Sampling| match sampling {
        Sampling::Center => input.t(Label::OneRayPerPixel).to_owned(),
        Sampling::Corners => input.t(Label::CornersPanel).to_owned(),
        Sampling::Adaptive { threshold, max_level } => format!(
            "{}: {} {}, K = {max_level}",
            input.t(Label::AdaptivePanel),
            input.t(Label::Threshold),
            slide_number(threshold)
        ),
    };
    d.set_title(input.t(Label::TitleJagged));
    let rows = if V::DIM == 2 { String::new() } else { format!(", j = {}…{}", j0, j0 + h - 1) };
    d.set_caption(&format!(
        "{}{}: i = {}…{}{rows} · {}: {} / {} · {}: {}",
        scene_lead(&input.traces.scene_name, input.lang),
        input.t(Label::Crop),
        i0,
        i0 + w - 1,
        input.t(Label::PrimaryForImage),
        centre.primary,
        fine.primary,
        input.t(Label::ChangedPixels),
        jagged.changed(),
    ));

    // A pixel is a unit square, rows from the bottom; a 2D strip's one row is drawn a quarter of
    // its width tall.
    let row_h = if V::DIM == 2 { (w as f64 / 4.0).max(1.0) } else { 1.0 };
    let (width, height) = (w as f64, row_h * h as f64);
    let shift = width + PANEL_GAP;
    d.fit_view(&[DVec2::ZERO, DVec2::new(width + shift, height * 1.12)], 0.02);
    for (k, render) in [centre, fine].into_iter().enumerate() {
        let x0 = shift * k as f64;
        for j in 0..h {
            for i in 0..w {
                let colour = swatch(render.image.get(i0 + i, j0 + j));
                let lo = DVec2::new(x0 + i as f64, j as f64 * row_h);
                d.rect("pixel", lo, lo + DVec2::new(1.0, row_h), grid_pen(), Some(colour));
            }
        }
        d.rect("crop", DVec2::new(x0, 0.0), DVec2::new(x0 + width, height), style::object(), None);
        let opts = TextOpts::LABEL.align(Align::ABOVE).size(TextSize::Body).bold().offset(0.0, 12.0);
        d.text("panel-title", DVec2::new(x0 + width / 2.0, height), &heading(render.sampling), opts);
    }
    Ok(())
}
