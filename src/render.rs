//! The whole image (algorithm.md §6 "for each pixel"): one primary ray through each pixel centre,
//! rows in parallel (rayon), traced with `NoRecorder` only, so rendering never pays for a trace.
//! A 2D scene renders its one row and repeats it down a strip `max(1, Nx/8)` rows tall.

use crate::accel::Accel;
use crate::image::Image;
use crate::record::NoRecorder;
use crate::scene::Scene;
use crate::shape::Dim;
use crate::trace::stats::Stats;
use crate::trace::Tracer;
use rayon::prelude::*;

/// What a render produced.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The image.
    pub image: Image,
    /// Rays and tests, summed over threads.
    pub stats: Stats,
    /// Pixels computed (a 2D strip counts its one row).
    pub pixels: u64,
}

/// Height of the strip a 2D scene renders to: `max(1, Nx/8)` (product.md).
#[must_use]
pub fn strip_height(nx: usize) -> usize {
    (nx / 8).max(1)
}

/// Renders every pixel centre of the scene's camera in the current rayon pool; a 2D scene's row
/// is repeated `strip_rows` times (default [`strip_height`]).
#[must_use]
pub fn render_centers<V: Dim>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    max_depth: u32,
    strip_rows: Option<usize>,
) -> Rendered {
    let cam = &scene.camera;
    let rows: Vec<(Vec<crate::scene::material::Rgb>, Stats)> = (0..cam.ny)
        .into_par_iter()
        .map(|j| {
            let mut tracer = Tracer::new(scene, accel, NoRecorder);
            tracer.max_depth = max_depth;
            let row = (0..cam.nx)
                .map(|i| {
                    let (u, v) = cam.pixel_center(i, j);
                    tracer.trace_primary(&cam.primary_ray(u, v), &[])
                })
                .collect();
            (row, tracer.stats)
        })
        .collect();
    let mut stats = Stats::default();
    let height = if V::DIM == 2 { strip_rows.unwrap_or_else(|| strip_height(cam.nx)) } else { cam.ny };
    let mut image = Image::new(cam.nx, height);
    for (j, (row, s)) in rows.into_iter().enumerate() {
        stats += s;
        image.pixels[j * cam.nx..(j + 1) * cam.nx].copy_from_slice(&row);
    }
    if V::DIM == 2 {
        let first: Vec<_> = image.pixels[..cam.nx].to_vec();
        for j in 1..height {
            image.pixels[j * cam.nx..(j + 1) * cam.nx].copy_from_slice(&first);
        }
    }
    Rendered { image, stats, pixels: (cam.nx * cam.ny) as u64 }
}
