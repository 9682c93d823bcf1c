//! The lecture's §7 claim, measured (algorithm.md §7 "Cost", §9): tests per ray and time per ray
//! for every `--accel` on scenes of n = 10, 100, 1 000, 10 000 and 100 000 spheres. Brute force
//! should grow as O(n), the hierarchies as O(log n). Single thread; ray casting (`max_depth` 0)
//! with one light, so primary and shadow rays; times are medians of 3 renders in this process.
//!
//! Writes `bench/complexity.md` (the table, with date, machine and command) and the plots
//! `bench/complexity.png` (tests per ray) and `bench/complexity-time.png` (time per ray).
//!
//! Run: `cargo bench --bench complexity` (`-- --quick`: one render each, a smaller image, and
//! nothing written).
#![allow(clippy::print_stdout)]

use glam::DVec2;
use std::fmt::Write;
use std::time::Instant;
use whitted::accel::{Accel, AccelKind};
use whitted::canvas::{Align, Dash, Drawing, LegendIcon, Pen, TextOpts, View};
use whitted::figure::style::{self, Rgba, TextSize};
use whitted::render::render_centers;
use whitted::scene::load::load_str;
use whitted::scene::{AnyScene, Scene};

const SIZES: [usize; 5] = [10, 100, 1_000, 10_000, 100_000];

/// n spheres at pseudo-random places around the point looked at, seen from (0, 0.5, 4):
/// `whitted::complexity::crowd`, the scenes of the `complexity` figure (a cube of half-side 0.8
/// of the visible half-width, radius 0.5·h/∛n, about 6.5 % of the cube filled whatever n); the
/// same scene for a given n on every run.
fn scene(n: usize, width: usize) -> Scene<glam::DVec3> {
    let text = format!(
        r#"{{"camera": {{"eye": [0, 0.5, 4], "center": [0, 0, 0], "window": {{"l": -0.5, "r": 0.5, "b": -0.375, "t": 0.375}}, "resolution": [{width}, {}]}},
            "max_depth": 0, "lights": [{{"position": [3, 4, 5]}}]}}"#,
        width * 3 / 4
    );
    match load_str(&text) {
        Ok(AnyScene::Space(s)) => whitted::complexity::crowd(&s, n, width),
        _ => unreachable!("the template scene is valid"),
    }
}

/// One measured configuration.
struct Row {
    n: usize,
    kind: AccelKind,
    tests_per_ray: f64,
    object_tests_per_ray: f64,
    micros_per_ray: f64,
    build_ms: f64,
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// The date today (UTC), from the system clock: days since 1970 → civil date.
fn today() -> String {
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let days = i64::try_from(secs / 86_400).unwrap_or(0) + 719_468;
    let era = days.div_euclid(146_097);
    let doe = days - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year}-{month:02}-{day:02}")
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    format!("{cpu} ({cores} cores), one thread used")
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (width, runs) = if quick { (32, 1) } else { (64, 5) };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("one worker thread");
    let mut rows = Vec::new();
    for n in SIZES {
        let scene = scene(n, width);
        for kind in AccelKind::ALL {
            let start = Instant::now();
            let accel = Accel::build(&scene, kind);
            let build_ms = start.elapsed().as_secs_f64() * 1e3;
            let mut times = Vec::new();
            let mut stats = None;
            for _ in 0..runs {
                let start = Instant::now();
                let r = pool.install(|| render_centers(&scene, &accel, 0, None));
                times.push(start.elapsed().as_secs_f64());
                stats = Some(r.stats);
            }
            let s = stats.expect("at least one run");
            let rays = s.rays.total() as f64;
            let t = s.tests;
            let row = Row {
                n,
                kind,
                tests_per_ray: (t.object + t.bound + t.node + t.voxel) as f64 / rays,
                object_tests_per_ray: t.object as f64 / rays,
                micros_per_ray: median(times) / rays * 1e6,
                build_ms,
            };
            println!(
                "n = {:>6}  {:<7} {:>10.1} tests/ray ({:>9.2} object)  {:>9.3} µs/ray  build {:>8.2} ms",
                row.n,
                row.kind.name(),
                row.tests_per_ray,
                row.object_tests_per_ray,
                row.micros_per_ray,
                row.build_ms
            );
            rows.push(row);
        }
    }
    let table = markdown(&rows, width, runs);
    println!("\n{table}");
    if quick {
        return;
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("bench");
    std::fs::write(root.join("complexity.md"), &table).expect("write bench/complexity.md");
    let tests = plot(&rows, "Tests per ray (log–log)", "tests per ray", |r| r.tests_per_ray);
    std::fs::write(root.join("complexity.png"), tests).expect("write bench/complexity.png");
    let time = plot(&rows, "Time per ray (log–log)", "µs per ray", |r| r.micros_per_ray);
    std::fs::write(root.join("complexity-time.png"), time).expect("write bench/complexity-time.png");
    println!("wrote bench/complexity.md, bench/complexity.png, bench/complexity-time.png");
}

fn markdown(rows: &[Row], width: usize, runs: usize) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "Measured {} on {}; `cargo bench --bench complexity`.", today(), machine());
    let _ = writeln!(
        out,
        "Random spheres in [−1, 1]³ (radius 0.5/∛n), {width}x{} pixels, one ray per pixel, `max_depth` 0, one light (primary + shadow rays); time = trace phase, median of {runs}.\n",
        width * 3 / 4
    );
    let _ = writeln!(out, "| n | accel | tests per ray | object tests per ray | µs per ray | build (ms) |");
    let _ = writeln!(out, "|---:|---|---:|---:|---:|---:|");
    for r in rows {
        let _ = writeln!(
            out,
            "| {} | {} | {:.1} | {:.2} | {:.3} | {:.2} |",
            r.n,
            r.kind.name(),
            r.tests_per_ray,
            r.object_tests_per_ray,
            r.micros_per_ray,
            r.build_ms
        );
    }
    let _ = writeln!(out, "\nTests are object tests + bounding-volume tests + node visits + voxel steps.");
    out
}

/// A log–log plot of `value` against n, one line per structure, as PNG bytes.
fn plot(rows: &[Row], title: &str, ylabel: &str, value: impl Fn(&Row) -> f64) -> Vec<u8> {
    let colors = [style::VERMILLION, style::ORANGE, style::BLUE, style::BLUISH_GREEN, style::REDDISH_PURPLE];
    let ys: Vec<f64> = rows.iter().map(|r| value(r).max(1e-9).log10()).collect();
    let (ylo, yhi) = (
        ys.iter().copied().fold(f64::INFINITY, f64::min).floor(),
        ys.iter().copied().fold(f64::NEG_INFINITY, f64::max).ceil(),
    );
    // World: x = log10 n, y = log10 value, stretched so the decades fill a 16:9 plot.
    let sy = 4.0 / (yhi - ylo).max(1.0);
    let at = |x: f64, y: f64| DVec2::new(x, (y - ylo) * sy);
    let mut d = Drawing::slide();
    d.set_title(title);
    if let Some(view) = View::new(0.3, 5.6, -0.6, 4.5) {
        d.set_view(view);
    }
    let axis = Pen::solid(style::DARK_GREY, style::GRID_WIDTH);
    let grid = Pen::solid(Rgba { a: 80, ..style::LIGHT_GREY }, 1.5);
    d.line("axis", [at(1.0, ylo), at(5.0, ylo)], axis);
    d.line("axis", [at(1.0, ylo), at(1.0, yhi)], axis);
    for k in 1..=5 {
        let x = f64::from(k);
        d.line("grid", [at(x, ylo), at(x, yhi)], grid);
        d.text(
            "tick",
            at(x, ylo),
            &format!("10^{{{k}}}"),
            TextOpts::NOTE.offset(0.0, -18.0).align(Align::BELOW),
        );
    }
    let mut y = ylo;
    while y <= yhi {
        d.line("grid", [at(1.0, y), at(5.0, y)], grid);
        d.text(
            "tick",
            at(1.0, y),
            &format!("10^{{{y}}}"),
            TextOpts::NOTE.offset(-14.0, 0.0).align(Align::LEFT_OF),
        );
        y += 1.0;
    }
    d.text(
        "label",
        at(3.0, ylo),
        "n (objects)",
        TextOpts::LABEL.size(TextSize::Body).offset(0.0, -70.0).align(Align::BELOW),
    );
    d.text(
        "label",
        at(1.0, yhi),
        ylabel,
        TextOpts::LABEL.size(TextSize::Body).offset(0.0, 30.0).align(Align::ABOVE),
    );
    for (kind, color) in AccelKind::ALL.iter().zip(colors) {
        let pts: Vec<DVec2> = rows
            .iter()
            .filter(|r| r.kind == *kind)
            .map(|r| at((r.n as f64).log10(), value(r).max(1e-9).log10()))
            .collect();
        // `bounds` does as many tests as `none` (bound tests instead of object tests): dashed,
        // so that the line beneath shows.
        let s = Pen::solid(color, style::RAY_WIDTH);
        let s = if *kind == AccelKind::Bounds { s.dashed(Dash { on: 24.0, off: 18.0 }) } else { s };
        d.line(&format!("accel:{}", kind.name()), pts.clone(), s);
        for p in pts {
            d.dot(&format!("accel:{}", kind.name()), p, color);
        }
        d.legend_entry(kind.name(), s, LegendIcon::Line);
    }
    whitted::canvas::skia::to_png(&d).expect("the plot renders")
}
