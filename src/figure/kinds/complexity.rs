//! `complexity` (lecture "Deficiențele algoritmului", 2: "pentru o rază/pixel este de O(p·n)";
//! "Complexitatea se poate reduce la O(log(n))"; algorithm.md §7 "Cost"): tests per ray against
//! the number of objects n = 10 … 10 000, measured by `crate::complexity::measure` on crowds of
//! random spheres in the scene's view, one render per point, on log–log axes. Left, the
//! ray–object tests per ray: brute force tests all n (a slope of one decade per decade), the
//! structures a handful. Right, every test per ray (objects, bounding volumes, tree nodes, grid
//! voxels), where a volume per object still tests n volumes and the hierarchies and grids grow
//! slowly. The caption gives the numbers at the largest n.

use glam::DVec2;

use super::Input;
use crate::accel::AccelKind;
use crate::canvas::{Align, Drawing, HAlign, LegendIcon, Pen, TextOpts, VAlign};
use crate::complexity::{Cost, FIGURE_WIDTH};
use crate::figure::labels::{scene_lead, Label};
use crate::figure::parts::panel_heading;
use crate::figure::plane::Planar;
use crate::figure::style::{self, Rgba, TextSize};
use crate::figure::FigureError;
use crate::format::slide_number;

/// The gap between the two plots, in decades of n.
const PLOT_GAP: f64 = 1.0;

/// A plot's height, as a share of its width (its n axis).
const PLOT_HEIGHT: f64 = 1.1;

/// A plot: its heading and the number per ray it draws.
type Panel = (Label, fn(&Cost) -> f64);

/// The decade of `x` (> 0), rounded down or up: tests per ray lie far inside i32's range.
fn decade(x: f64, up: bool) -> i32 {
    let l = x.log10();
    let l = if up { l.ceil() } else { l.floor() };
    // Clamped to ±300 first, so the cast is exact.
    #[allow(clippy::cast_possible_truncation)]
    let d = l.clamp(-300.0, 300.0) as i32;
    d
}

/// A structure's colour, name and dash on the plots.
fn look(kind: AccelKind) -> (Rgba, Label, bool) {
    match kind {
        AccelKind::None => (style::BLACK, Label::BruteForce, false),
        AccelKind::Bounds => (style::REDDISH_PURPLE, Label::PerObjectVolumes, true),
        AccelKind::Bvh => (style::BLUE, Label::BvhName, false),
        AccelKind::Grid => (style::BLUISH_GREEN, Label::RegularGrid, false),
        AccelKind::Octree => (style::VERMILLION, Label::OctreeName, false),
    }
}

/// The pen of a structure's line.
fn pen(kind: AccelKind) -> Pen {
    let (colour, _, dashed) = look(kind);
    let pen = Pen::solid(colour, style::CONSTRUCTION_WIDTH * 1.3);
    if dashed {
        pen.dashed(style::CONSTRUCTION_DASH)
    } else {
        pen
    }
}

/// `10 000` for 10⁴: whole numbers with thin groups, fractions as a slide writes them.
fn tick(power: i32) -> String {
    let value = 10f64.powi(power);
    if power >= 0 {
        // A power of ten from 1 to 10^15 is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let whole = value as u64;
        let digits = whole.to_string();
        let mut out = String::new();
        for (k, c) in digits.chars().enumerate() {
            if k > 0 && (digits.len() - k).is_multiple_of(3) && digits.len() > 4 {
                out.push(' ');
            }
            out.push(c);
        }
        out
    } else {
        slide_number(value)
    }
}

/// Draws the figure.
///
/// # Errors
/// When nothing was measured.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let costs = &input.traces.costs;
    let (Some(first), Some(last)) = (costs.iter().map(|c| c.n).min(), costs.iter().map(|c| c.n).max()) else {
        return Err(FigureError("nothing was measured".into()));
    };
    let kinds: Vec<AccelKind> =
        AccelKind::ALL.into_iter().filter(|k| costs.iter().any(|c| c.kind == *k)).collect();
    let panels: [Panel; 2] = [
        (Label::ObjectTestsPerRay, Cost::object_tests_per_ray),
        (Label::AllTestsPerRay, Cost::tests_per_ray),
    ];
    // One y axis for both plots, whole decades around every positive value.
    let values: Vec<f64> = costs
        .iter()
        .flat_map(|c| [c.object_tests_per_ray(), c.tests_per_ray()])
        .filter(|v| *v > 0.0)
        .collect();
    let lo_decade = decade(values.iter().copied().fold(f64::INFINITY, f64::min), false).min(0);
    let hi_decade = decade(values.iter().copied().fold(1.0, f64::max), true).max(lo_decade + 1);
    let (n_lo, n_hi) =
        (decade(first as f64, false), decade(last as f64, true).max(decade(first as f64, false) + 1));
    let (x_lo, x_hi) = (f64::from(n_lo), f64::from(n_hi));
    let (lo_decade_i, hi_decade_i) = (lo_decade, hi_decade);
    let (lo_decade, hi_decade) = (f64::from(lo_decade), f64::from(hi_decade));
    let span = x_hi - x_lo;
    let shift = span + PLOT_GAP;
    // The y axis spans PLOT_HEIGHT of the x axis's world units.
    let y_scale = PLOT_HEIGHT * span / (hi_decade - lo_decade);
    let to_page = |panel: usize, n: f64, v: f64| {
        DVec2::new(n.log10() - x_lo + shift * panel as f64, (v.log10() - lo_decade) * y_scale)
    };

    d.set_title(input.t(Label::TitleComplexity));
    let at_last: Vec<String> = kinds
        .iter()
        .filter_map(|k| costs.iter().find(|c| c.kind == *k && c.n == last))
        .map(|c| {
            format!(
                "{} {} / {}",
                input.t(look(c.kind).1),
                slide_number(c.object_tests_per_ray()),
                slide_number(c.tests_per_ray())
            )
        })
        .collect();
    let rows = if V::DIM == 2 {
        String::new()
    } else {
        format!(" × {}", FIGURE_WIDTH * input.scene.camera.ny / input.scene.camera.nx.max(1))
    };
    d.set_caption(&format!(
        "{}{} · {FIGURE_WIDTH}{rows} px · {} · n = {}: {}",
        scene_lead(&input.traces.scene_name, input.lang),
        input.t(Label::CrowdCaption),
        input.t(Label::RayCastingCount),
        tick(decade(last as f64, false)),
        at_last.join(", "),
    ));
    for k in &kinds {
        d.legend_entry(input.t(look(*k).1), pen(*k), LegendIcon::Line);
    }
    let top = (hi_decade - lo_decade) * y_scale;
    d.fit_view(
        &[DVec2::new(-0.35 * span, -0.3 * top), DVec2::new(shift + span + 0.05 * span, top * 1.12)],
        0.02,
    );

    let axis = Pen::solid(style::BLACK, style::CONSTRUCTION_WIDTH);
    let grid = Pen::solid(style::LIGHT_GREY, style::GRID_WIDTH);
    let small = |h: HAlign, v: VAlign| TextOpts::LABEL.size(TextSize::Small).align(Align { h, v });
    for (panel, (heading, _)) in panels.iter().enumerate() {
        let x0 = shift * panel as f64;
        // Decades of y: grid lines and their values.
        for p in lo_decade_i..=hi_decade_i {
            let y = (f64::from(p) - lo_decade) * y_scale;
            d.segment("grid", DVec2::new(x0, y), DVec2::new(x0 + span, y), grid);
            d.text(
                "tick",
                DVec2::new(x0, y),
                &tick(p),
                small(HAlign::Right, VAlign::Middle).offset(-10.0, 0.0),
            );
        }
        // Decades of n.
        for p in n_lo..=n_hi {
            let x = x0 + f64::from(p) - x_lo;
            d.segment("grid", DVec2::new(x, 0.0), DVec2::new(x, top), grid);
            d.text(
                "tick",
                DVec2::new(x, 0.0),
                &tick(p),
                small(HAlign::Center, VAlign::Top).offset(0.0, -8.0),
            );
        }
        d.segment("axis", DVec2::new(x0, 0.0), DVec2::new(x0 + span, 0.0), axis);
        d.segment("axis", DVec2::new(x0, 0.0), DVec2::new(x0, top), axis);
        panel_heading(d, DVec2::new(x0 + span / 2.0, top), input.t(*heading));
        let opts = TextOpts::LABEL.size(TextSize::Small).align(Align::BELOW).offset(0.0, -52.0);
        d.text("axis-title", DVec2::new(x0 + span / 2.0, 0.0), input.t(Label::ObjectsN), opts);
    }
    for (panel, (_, value)) in panels.iter().enumerate() {
        for k in &kinds {
            let mut line: Vec<(usize, f64)> = costs
                .iter()
                .filter(|c| c.kind == *k)
                .map(|c| (c.n, value(c)))
                .filter(|(_, v)| *v > 0.0)
                .collect();
            line.sort_by_key(|(n, _)| *n);
            let points: Vec<DVec2> = line.iter().map(|(n, v)| to_page(panel, *n as f64, *v)).collect();
            d.line("cost", points.clone(), pen(*k));
            for p in points {
                d.marker("cost-point", p, style::DOT_RADIUS * 0.7, look(*k).0, Pen::NONE);
            }
        }
    }
    Ok(())
}
