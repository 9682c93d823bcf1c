//! `uv-map` (lecture "Corespondența imagine – fereastra vizuală", algorithm.md §2 "Pixel → (u, v)"):
//! the image's pixel grid beside the view window with its corners (l, t) and (r, b), the chosen
//! pixel (i, j) with rows counted from the bottom, and its centre carried by the window–viewport
//! transform to the (u, v) that the trace's primary ray recorded, with the formula and its numbers.
//! In 2D the image is one row above the window's segment [l, r].

use glam::DVec2;

use super::Input;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign};
use crate::figure::labels::Label;
use crate::figure::parts::text_column;
use crate::figure::plane::Planar;
use crate::figure::source::FigureTrace;
use crate::figure::style::{self, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;
use crate::record::event::Event;
use crate::scene::camera::Camera;

/// The pixel and the `(u, v)` its primary ray recorded.
struct Mapped {
    i: usize,
    j: usize,
    uv: Vec<f64>,
    /// The index of the `primary_ray` event that carries `uv`.
    event: usize,
}

/// Above this many pixels across (or down) the image, the chosen pixel's own square is drawn under
/// about 8 px at slide size (the image is drawn some 450 px tall): what marks it is the ring around
/// its centre, and the legend says so.
const SWATCH_MAX_PIXELS: usize = 60;

/// Draws the figure.
///
/// # Errors
/// When the trace has no primary ray through a pixel.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let mapped =
        mapped(traced).ok_or_else(|| FigureError("the trace has no primary ray through a pixel".into()))?;
    let cam = &input.scene.camera;
    d.set_title(input.t(Label::TitleUvMap));
    let rows = if V::DIM == 2 { String::new() } else { format!(" · {}", input.t(Label::RowsFromBottom)) };
    d.set_caption(&format!("{}{rows}", input.traced(traced)));
    // The legend shows the pixel as it is seen: its yellow square, or the ringed centre when the
    // square is too small to see.
    if cam.nx.max(cam.ny) > SWATCH_MAX_PIXELS {
        d.legend_entry(
            input.t(Label::PixelCentreRinged),
            style::outline(style::BLACK),
            LegendIcon::Dot(style::HIT),
        );
    } else {
        d.legend_entry(
            input.t(Label::ChosenPixel),
            style::outline(style::BLACK),
            LegendIcon::Swatch(style::HIGHLIGHT),
        );
    }
    d.legend_entry(input.t(Label::WindowViewport), style::normal(), LegendIcon::Arrow);
    if V::DIM == 2 {
        one_row(input, d, cam, &mapped);
    } else {
        two_panels(input, d, cam, &mapped);
    }
    Ok(())
}

/// The traced pixel and the `(u, v)` of its `primary_ray` event.
fn mapped<V>(traced: &FigureTrace<V>) -> Option<Mapped> {
    let (i, j) = match traced.targets.first()? {
        crate::figure::source::Target::Pixel { i, j, .. } => (*i, *j),
        crate::figure::source::Target::Ray => return None,
    };
    let (event, uv) = traced.log.events.iter().enumerate().find_map(|(k, l)| match &l.event {
        Event::PrimaryRay { uv, .. } if !uv.is_empty() => Some((k, uv.clone())),
        _ => None,
    })?;
    Some(Mapped { i, j, uv, event })
}

/// Grid lines every `step` cells: every cell up to 48 a side, else a round step.
fn grid_step(n: usize) -> usize {
    if n <= 48 {
        return 1;
    }
    let raw = n / 16;
    [1, 2, 5, 10, 20, 25, 50, 100, 200, 250, 500, 1000].into_iter().find(|s| *s >= raw).unwrap_or(raw)
}

/// The lines `0, step, 2·step, …, n` (the last always included).
fn grid_lines(n: usize, step: usize) -> Vec<usize> {
    let mut lines: Vec<usize> = (0..=n).step_by(step).collect();
    if lines.last() != Some(&n) {
        lines.push(n);
    }
    lines
}

/// A pixel-centre formula with the numbers put in, `c = lo + (hi − lo)·(k + 0.5)/N_axis = …`;
/// `names` are the letters of c, lo, hi, k and the axis.
fn centre_formula(names: [&str; 5], (lo, hi): (f64, f64), k: usize, n: usize, value: f64) -> String {
    let [c, lo_name, hi_name, k_name, axis] = names;
    format!(
        "{c} = {lo_name} + ({hi_name} − {lo_name})·({k_name} + 0.5)/N_{axis} = {} + {}·({k} + 0.5)/{n} = {}",
        slide_number(lo),
        slide_number(hi - lo),
        slide_number(value)
    )
}

/// The formula line of u (§2).
fn formula_u<V: Planar>(cam: &Camera<V>, m: &Mapped) -> String {
    let w = &cam.window;
    centre_formula(["u", "l", "r", "i", "x"], (w.l, w.r), m.i, cam.nx, m.uv[0])
}

/// The formula line of v (§2).
fn formula_v<V: Planar>(cam: &Camera<V>, m: &Mapped) -> String {
    let w = &cam.window;
    centre_formula(["v", "b", "t", "j", "y"], (w.b, w.t), m.j, cam.ny, m.uv.get(1).copied().unwrap_or(0.0))
}

/// 3D: the image (left, pixel units scaled to height 1) and the window (right, (u, v) scaled by
/// the same height), the pixel's cell in both, and the arrow between the two centres.
fn two_panels<V: Planar>(input: &Input<'_, V>, d: &mut Drawing, cam: &Camera<V>, m: &Mapped) {
    let w = cam.window;
    let (nx, ny) = (cam.nx as f64, cam.ny as f64);
    let cell = 1.0 / ny;
    let image_w = nx * cell;
    let gap = 0.8;
    let x0 = image_w + gap;
    let scale = 1.0 / (w.t - w.b);
    let window_w = (w.r - w.l) * scale;
    let to_window = |u: f64, v: f64| DVec2::new(x0 + (u - w.l) * scale, (v - w.b) * scale);
    let points = [DVec2::new(-0.12, -0.62), DVec2::new(x0 + window_w + 0.1, 1.2)];
    d.fit_view(&points, 0.02);

    // The grids: the same lines in pixel units on the left and in (u, v) on the right.
    let (sx, sy) = (grid_step(cam.nx), grid_step(cam.ny));
    for i in grid_lines(cam.nx, sx) {
        let x = i as f64 * cell;
        d.segment("grid", DVec2::new(x, 0.0), DVec2::new(x, 1.0), style::grid());
        let u = cam.u_at(i as f64);
        d.segment("grid", to_window(u, w.b), to_window(u, w.t), style::grid());
    }
    for j in grid_lines(cam.ny, sy) {
        let y = j as f64 * cell;
        d.segment("grid", DVec2::new(0.0, y), DVec2::new(image_w, y), style::grid());
        let v = cam.v_at(j as f64);
        d.segment("grid", to_window(w.l, v), to_window(w.r, v), style::grid());
    }
    d.rect("image", DVec2::ZERO, DVec2::new(image_w, 1.0), style::object(), None);
    d.rect("window", to_window(w.l, w.b), to_window(w.r, w.t), style::object(), None);

    // The pixel's cell in both, its centre and where it lands.
    let (i, j) = (m.i as f64, m.j as f64);
    let lo = DVec2::new(i * cell, j * cell);
    let hl = Some(style::HIGHLIGHT);
    let (u0, v0) = (cam.u_at(i), cam.v_at(j));
    let (u1, v1) = (cam.u_at(i + 1.0), cam.v_at(j + 1.0));
    let centre = lo + DVec2::splat(cell / 2.0);
    let uv = to_window(m.uv[0], m.uv.get(1).copied().unwrap_or(0.0));
    // A ring keeps the pixel visible when the grid is fine.
    let ring = Pen::solid(style::BLACK, style::CONSTRUCTION_WIDTH);
    d.with_events([m.event], |d| {
        d.rect("pixel", lo, lo + DVec2::splat(cell), style::outline(style::BLACK), hl);
        d.rect("pixel", to_window(u0, v0), to_window(u1, v1), style::outline(style::BLACK), hl);
        d.marker("pixel-ring", centre, 22.0, style::HIGHLIGHT.with_alpha(0.0), ring);
        d.marker("uv-ring", uv, 22.0, style::HIGHLIGHT.with_alpha(0.0), ring);
        d.arrow(style::MAPPING_TAG, centre, uv, style::normal());
        d.dot("pixel-centre", centre, style::HIT);
        d.dot("uv", uv, style::HIT);
    });

    // The u and v axes of the window, where they cross it.
    if w.l < 0.0 && w.r > 0.0 {
        d.arrow("axis", to_window(0.0, w.b), to_window(0.0, w.t + 0.08 / scale), style::normal());
        d.text(
            "label",
            to_window(0.0, w.t + 0.08 / scale),
            "v",
            TextOpts::LABEL.align(Align::LEFT_OF).offset(-10.0, -6.0),
        );
    }
    if w.b < 0.0 && w.t > 0.0 {
        d.arrow("axis", to_window(w.l, 0.0), to_window(w.r + 0.12 / scale, 0.0), style::normal());
        d.text(
            "label",
            to_window(w.r + 0.12 / scale, 0.0),
            "u",
            TextOpts::LABEL.align(Align::BELOW).offset(0.0, -8.0),
        );
    }

    // Titles of the panels and the corners.
    let above = TextOpts::LABEL.align(Align::ABOVE).size(TextSize::Body).offset(0.0, 10.0);
    d.text(
        "label",
        DVec2::new(image_w / 2.0, 1.0),
        &format!("{}: N_x × N_y = {} × {}", input.t(Label::Image), cam.nx, cam.ny),
        above,
    );
    let right_above = above.align(Align { h: HAlign::Right, v: VAlign::Bottom });
    d.text("label", to_window(w.r, w.t), input.t(Label::ViewWindow), right_above);
    let corner = TextOpts::LABEL.size(TextSize::Body);
    d.text(
        "label",
        to_window(w.l, w.t),
        &format!("(l, t) = ({}, {})", slide_number(w.l), slide_number(w.t)),
        corner.align(Align { h: HAlign::Right, v: VAlign::Bottom }).offset(-8.0, 4.0),
    );
    d.text(
        "label",
        to_window(w.r, w.b),
        &format!("(r, b) = ({}, {})", slide_number(w.r), slide_number(w.b)),
        corner.align(Align { h: HAlign::Right, v: VAlign::Top }).offset(0.0, -8.0),
    );

    // Indices along the image's edges: 0 and the last, and the pixel's own, rows from the bottom.
    let note = TextOpts::NOTE;
    for (k, text) in [(0, "0".to_owned()), (cam.nx - 1, format!("{}", cam.nx - 1))] {
        d.text(
            "tick",
            DVec2::new((k as f64 + 0.5) * cell, 0.0),
            &text,
            note.align(Align::BELOW).offset(0.0, -6.0),
        );
    }
    for (k, text) in [(0, "0".to_owned()), (cam.ny - 1, format!("{}", cam.ny - 1))] {
        d.text(
            "tick",
            DVec2::new(0.0, (k as f64 + 0.5) * cell),
            &text,
            note.align(Align::LEFT_OF).offset(-8.0, 0.0),
        );
    }
    d.text(
        "tick",
        DVec2::new(centre.x, 0.0),
        &format!("i = {}", m.i),
        note.align(Align::BELOW).offset(0.0, -40.0),
    );
    d.text(
        "tick",
        DVec2::new(0.0, centre.y),
        &format!("j = {}", m.j),
        note.align(Align::LEFT_OF).offset(-60.0, 0.0),
    );
    // The numbers only, as the pixel's (i, j): the formulas under the image name them u and v,
    // and a shorter label keeps off the window's v axis.
    let uv_text =
        format!("({}, {})", slide_number(m.uv[0]), slide_number(m.uv.get(1).copied().unwrap_or(0.0)));
    d.with_events([m.event], |d| {
        d.text("label", centre, &format!("({}, {})", m.i, m.j), TextOpts::LABEL.avoid_overlap());
        d.text("label", uv, &uv_text, TextOpts::LABEL.avoid_overlap());
    });

    let lines = [formula_u(cam, m), formula_v(cam, m)];
    text_column(d, DVec2::new(0.0, -0.2), &lines, TextSize::Body, 50.0);
}

/// 2D: the row of pixels above the window's segment [l, r], both `width` wide.
fn one_row<V: Planar>(input: &Input<'_, V>, d: &mut Drawing, cam: &Camera<V>, m: &Mapped) {
    let w = cam.window;
    let width = 4.0;
    let cell = width / cam.nx as f64;
    let strip = cell.max(0.3);
    let top = 1.0;
    let to_line = |u: f64| DVec2::new((u - w.l) / (w.r - w.l) * width, 0.0);
    d.fit_view(&[DVec2::new(-0.3, -0.9), DVec2::new(width + 0.3, top + strip + 0.4)], 0.02);

    let step = grid_step(cam.nx);
    for i in grid_lines(cam.nx, step) {
        let x = i as f64 * cell;
        d.segment("grid", DVec2::new(x, top), DVec2::new(x, top + strip), style::grid());
        d.segment(
            "grid",
            to_line(cam.u_at(i as f64)) - DVec2::new(0.0, 0.05),
            to_line(cam.u_at(i as f64)) + DVec2::new(0.0, 0.05),
            style::grid(),
        );
    }
    d.rect("image", DVec2::new(0.0, top), DVec2::new(width, top + strip), style::object(), None);
    d.segment("window", to_line(w.l), to_line(w.r), Pen::solid(style::BLACK, style::OBJECT_WIDTH * 1.5));

    let i = m.i as f64;
    let lo = DVec2::new(i * cell, top);
    let (a, b) = (to_line(cam.u_at(i)), to_line(cam.u_at(i + 1.0)));
    let centre = lo + DVec2::new(cell / 2.0, strip / 2.0);
    let u = to_line(m.uv[0]);
    d.with_events([m.event], |d| {
        d.rect(
            "pixel",
            lo,
            lo + DVec2::new(cell, strip),
            style::outline(style::BLACK),
            Some(style::HIGHLIGHT),
        );
        d.segment("pixel", a, b, Pen::solid(style::HIGHLIGHT, style::OBJECT_WIDTH * 3.0));
        d.arrow(style::MAPPING_TAG, centre, u, style::normal());
        d.dot("pixel-centre", centre, style::HIT);
        d.dot("uv", u, style::HIT);
    });

    let above = TextOpts::LABEL.align(Align::ABOVE).size(TextSize::Body).offset(0.0, 10.0);
    d.text(
        "label",
        DVec2::new(width / 2.0, top + strip),
        &format!("{}: N_x = {}", input.t(Label::Image), cam.nx),
        above,
    );
    let below = TextOpts::LABEL.align(Align::BELOW).size(TextSize::Body).offset(0.0, -14.0);
    d.text("label", to_line(w.l), &format!("l = {}", slide_number(w.l)), below);
    d.text("label", to_line(w.r), &format!("r = {}", slide_number(w.r)), below);
    d.with_events([m.event], |d| {
        d.text("label", u, &format!("u = {}", slide_number(m.uv[0])), below.offset(0.0, -60.0));
    });
    d.text(
        "label",
        to_line(w.l),
        input.t(Label::ViewWindow),
        TextOpts::LABEL.align(Align::ABOVE).size(TextSize::Body).offset(60.0, 10.0),
    );
    let note = TextOpts::NOTE.align(Align::BELOW).offset(0.0, -6.0);
    let every = cam.nx <= 16;
    // A sparse row numbers its ends only: the pixel's own column is named by "i = …" beside the
    // mapping arrow, which would run through a number printed under the pixel.
    for k in 0..cam.nx {
        if every || k == 0 || k == cam.nx - 1 {
            d.text("tick", DVec2::new((k as f64 + 0.5) * cell, top), &format!("{k}"), note);
        }
    }
    d.text(
        "label",
        DVec2::new(centre.x, top),
        &format!("i = {}", m.i),
        below.offset(-20.0, -50.0).align(Align { h: HAlign::Right, v: VAlign::Top }),
    );
    text_column(d, DVec2::new(0.0, -0.45), &[formula_u(cam, m)], TextSize::Body, 50.0);
}
