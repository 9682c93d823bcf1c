//! `whitted tradeoff`: what accuracy costs, measured (product.md). The sweeps of
//! `whitted::tradeoff` are rendered `--runs` times each in this process; stdout gets a Markdown
//! table per sweep with a line per row saying why (or, with `--json`, the same figures as JSON),
//! and with `--out DIR` the plots go to DIR: the error against the rays traced of the sampling
//! and of the depth sweep, and the rays per pixel of adaptive sampling as a heat map.

use super::figure::{scene_name, Format};
use super::trace::LangArg;
use super::{load_scene, output, print_json, print_out, thread_pool, write_file, Failure};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::{json, Value};
use std::fmt::Write;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use whitted::accel::{AccelKind, AccelOptions};
use whitted::canvas::svg::SvgText;
use whitted::doc::{float, stats};
use whitted::figure::labels::Label;
use whitted::figure::plane::Planar;
use whitted::figure::source::TraceOptions;
use whitted::figure::tradeoff as tradeoff_plot;
use whitted::figure::{FigureKind, Options};
use whitted::render::{check_fits, RenderConfig};
use whitted::request::figure::{figure_in, Request};
use whitted::request::options::{canvas, resize};
use whitted::request::parse;
use whitted::request::target::Target;
use whitted::sample::{Sampling, DEFAULT_MAX_LEVEL, DEFAULT_THRESHOLD};
use whitted::scene::{AnyScene, Scene};
use whitted::tradeoff::{self, Measured, Measurement, Sweep, Timing, Tradeoff, DEFAULT_RUNS};

/// Options of `whitted tradeoff`.
#[derive(Args, Debug)]
pub struct TradeoffArgs {
    /// The scene file (JSON).
    scene: PathBuf,
    /// Also draw the plots into this folder (created if missing), PNG and SVG: the error against
    /// the rays traced with the Pareto front, for sampling (sampling.*) and depth (depth.*); and
    /// the rays per pixel of adaptive sampling (threshold 0.1, K = 2) as a heat map (heat-map.*).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the measurements as JSON instead of a Markdown table.
    #[arg(long)]
    json: bool,
    /// Renders per setting; the table shows their median time and its spread (min–max).
    #[arg(long, default_value_t = DEFAULT_RUNS, value_parser = parse::runs, allow_hyphen_values = true)]
    runs: u32,
    /// Worker threads (default: one per core).
    #[arg(long, value_parser = parse::threads, allow_hyphen_values = true)]
    threads: Option<u32>,
    /// Render at WxH instead of the scene's resolution (the window stays); W alone for a 2D scene.
    #[arg(long, value_parser = parse::size, allow_hyphen_values = true)]
    size: Option<(usize, Option<usize>)>,
    /// The language of the plots' labels.
    #[arg(long, value_enum, default_value = "en")]
    lang: LangArg,
}

/// The plots of `--out`, each written as PNG and SVG: one per sweep with an error (by
/// [`Sweep::name`]), and the heat map.
const PLOTS: [&str; 3] = ["sampling", "depth", "heat-map"];
/// The sweeps that have a plot (a structure changes no pixel: its error is 0).
const PLOTTED: [Sweep; 2] = [Sweep::Sampling, Sweep::Depth];
/// The plots' formats, by extension.
const PLOT_FORMATS: [(&str, Format); 2] = [("png", Format::Png), ("svg", Format::Svg)];

/// The file of one plot in the folder of `--out`.
fn plot_file(dir: &Path, stem: &str, ext: &str) -> PathBuf {
    dir.join(format!("{stem}.{ext}"))
}

/// Runs `whitted tradeoff`.
pub fn run(args: &TradeoffArgs) -> Result<(), Failure> {
    // The plots' folder and files are checked before the measurements: created, writable, and
    // none of them the scene.
    if let Some(dir) = &args.out {
        output::create_folder(dir)?;
        for stem in PLOTS {
            for (ext, _) in PLOT_FORMATS {
                output::check(&plot_file(dir, stem, ext), &[ext], &[&args.scene])?;
            }
        }
    }
    let pool = thread_pool(args.threads)?;
    let threads = pool.current_num_threads();
    match load_scene(&args.scene)? {
        AnyScene::Flat(mut s) => {
            resize(&mut s, args.size);
            pool.install(|| report(&s, args, threads))
        }
        AnyScene::Space(mut s) => {
            resize(&mut s, args.size);
            pool.install(|| report(&s, args, threads))
        }
    }
}

fn report<V: Planar>(scene: &Scene<V>, args: &TradeoffArgs, threads: usize) -> Result<(), Failure> {
    // The dearest render is the sampling sweep's reference: it must fit.
    let reference = Sweep::Sampling.reference(scene.max_depth);
    let config = RenderConfig { sampling: reference.sampling, ..RenderConfig::centers(reference.depth) };
    check_fits(scene, &config, threads).map_err(|e| Failure::input(format!("tradeoff: {e}")))?;
    let lang = args.lang.lang();
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = ProgressBar::new(tradeoff::plan(scene.max_depth).len() as u64);
        let template = format!(
            "{{elapsed_precise}} [{{bar:30}}] {{pos}}/{{len}} {}: {{msg}}",
            Label::ProgressSettings.text(lang)
        );
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar
    });
    let measured = tradeoff::run(scene, args.runs as usize, |sweep, setting, is_reference| {
        if let Some(bar) = &bar {
            let name = sweep.setting_name(setting);
            bar.set_message(if is_reference {
                format!("{} ({name})", Label::ProgressReference.text(lang))
            } else {
                name
            });
            bar.inc(1);
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let (nx, ny) = (scene.camera.nx, scene.camera.ny);
    if args.json {
        let doc = json!({
            "scene": args.scene.display().to_string(),
            "size": if V::DIM == 2 { json!([nx]) } else { json!([nx, ny]) },
            "threads": threads,
            "runs": measured.runs,
            "errors_on": "linear RGB clamped to [0, 1]",
            "pareto_on": "rays traced",
            "sweeps": measured.sweeps.iter().map(sweep_json).collect::<Vec<_>>(),
        });
        print_json(&format!("{doc:#}\n"))?;
    } else {
        print_out(&tables(scene, args, threads, &measured))?;
    }
    plots(scene, args, &measured)
}

fn sweep_json(m: &Measurement) -> Value {
    json!({
        "sweep": m.sweep.name(),
        "reference": row_json(m.sweep, &m.reference, ""),
        "rows": m.rows.iter().zip(m.reasons()).map(|(r, why)| row_json(m.sweep, r, &why)).collect::<Vec<_>>(),
        "pareto": m.pareto_front(),
    })
}

fn row_json(sweep: Sweep, m: &Measured, why: &str) -> Value {
    let s = m.setting;
    // The keys of `render --json` and of a sampled trace document: `aa`, then its parameters.
    let mut sampling = json!({"aa": s.sampling.name()});
    if let Sampling::Adaptive { threshold, max_level } = s.sampling {
        sampling["threshold"] = float(threshold);
        sampling["max_level"] = json!(max_level);
    }
    let r = m.stats.rays;
    let mut counts = stats(&m.stats);
    counts["rays"]["total"] = json!(r.total());
    counts["tests"]["total"] = json!(m.tests());
    let mut row = json!({
        "name": sweep.setting_name(&s),
        "sampling": sampling,
        "max_depth": s.depth,
        "accel": s.accel.name(),
        "seconds": {"min": m.time.min, "median": m.time.median, "max": m.time.max},
        "pixels": m.pixels,
        "rays": counts["rays"],
        "rays_per_pixel": {"primary": m.per_pixel(r.primary), "reflected": m.per_pixel(r.reflected),
                           "transmitted": m.per_pixel(r.transmitted), "shadow": m.per_pixel(r.shadow),
                           "total": m.rays_per_pixel()},
        "tests": counts["tests"],
        "tests_per_ray": m.tests_per_ray(),
        "rmse": m.error.rmse,
        "max_error": m.error.max,
        "off_share": m.error.off,
    });
    if !why.is_empty() {
        row["why"] = json!(why);
    }
    row
}

/// A time with its spread, in ms: `12.3 (11.9–14.0)`.
fn time_ms(t: &Timing) -> String {
    format!("{:.1} ({:.1}–{:.1})", 1e3 * t.median, 1e3 * t.min, 1e3 * t.max)
}

fn tables<V: Planar>(scene: &Scene<V>, args: &TradeoffArgs, threads: usize, measured: &Tradeoff) -> String {
    let cam = &scene.camera;
    let size = if V::DIM == 2 { format!("{}", cam.nx) } else { format!("{}x{}", cam.nx, cam.ny) };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "What accuracy costs: {} at {size}, {threads} thread(s), {} render(s) a setting.\n\
         Each sweep varies one thing from the scene's render (centre sampling, max_depth {}, bvh) and \
         compares each image with a reference that differs from it in that thing only; errors on the \
         linear colours clamped to [0, 1]. Cost: rays traced and intersection tests (the render's \
         counts, the same on any machine); the Pareto front is decided on rays; the time is the \
         median trace time (min–max over the runs).",
        args.scene.display(),
        measured.runs,
        measured.base.depth,
    );
    for m in &measured.sweeps {
        let front = m.pareto_front();
        let _ = writeln!(out, "\n## {}: reference {}\n", m.sweep.name(), describe(&m.reference));
        let _ = writeln!(
            out,
            "| {} | rays/pixel | primary | reflected | transmitted | shadow | tests/ray | time ms (min–max) | RMSE | max error | off > 1/255 | Pareto |",
            m.sweep.name()
        );
        let _ = writeln!(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
        let row = |out: &mut String, r: &Measured, pareto: &str| {
            let k = r.stats.rays;
            let _ = writeln!(
                out,
                "| {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {:.5} | {:.4} | {:.2} % | {pareto} |",
                m.sweep.setting_name(&r.setting),
                r.rays_per_pixel(),
                r.per_pixel(k.primary),
                r.per_pixel(k.reflected),
                r.per_pixel(k.transmitted),
                r.per_pixel(k.shadow),
                r.tests_per_ray(),
                time_ms(&r.time),
                r.error.rmse,
                r.error.max,
                100.0 * r.error.off,
            );
        };
        // A structure's error is 0 by design: no front, the cost is in its tests.
        let with_front = m.sweep != Sweep::Accel;
        for (i, r) in m.rows.iter().enumerate() {
            row(&mut out, r, if with_front && front.contains(&i) { "yes" } else { "" });
        }
        row(&mut out, &m.reference, "reference");
        let _ = writeln!(out);
        for (r, why) in m.rows.iter().zip(m.reasons()) {
            let _ = writeln!(out, "- {}: {why}.", m.sweep.setting_name(&r.setting));
        }
    }
    out
}

/// A setting in full: `adaptive 0, K = 3, max_depth 4, bvh`.
fn describe(m: &Measured) -> String {
    let s = m.setting;
    format!("{}, max_depth {}, {}", tradeoff::sampling_name(s.sampling), s.depth, s.accel.name())
}

/// The plots of `--out DIR`: `sampling` and `depth` (error against rays traced, the Pareto front),
/// and `heat-map` (the rays per pixel of adaptive sampling at threshold 0.1, K = 2, the default of
/// `whitted figure adaptive`, where the counts vary with the image), each `.png` and `.svg`.
fn plots<V: Planar>(scene: &Scene<V>, args: &TradeoffArgs, measured: &Tradeoff) -> Result<(), Failure> {
    let Some(dir) = &args.out else { return Ok(()) };
    let (width, height) = canvas(None)?;
    let opts = Options { lang: args.lang.lang(), width, height };
    let name = scene_name(&args.scene);
    let mut drawings = Vec::new();
    for sweep in PLOTTED {
        let Some(m) = measured.sweeps.iter().find(|m| m.sweep == sweep) else { continue };
        match tradeoff_plot::draw(m, &m.pareto_front(), &name, &opts) {
            Ok(plot) => drawings.push((sweep.name(), plot)),
            Err(e) => eprintln!("whitted tradeoff: no {} plot: {e}", sweep.name()),
        }
    }
    let heat = figure_in(
        scene,
        &name,
        &Request {
            kind: FigureKind::HeatMap,
            target: Target::default(),
            tracing: TraceOptions {
                depth: None,
                sampling: Sampling::Adaptive { threshold: DEFAULT_THRESHOLD, max_level: DEFAULT_MAX_LEVEL },
                accel: AccelOptions::of(AccelKind::Bvh),
            },
            opts,
        },
    )?
    .drawing;
    drawings.push(("heat-map", heat));
    for (stem, drawing) in &drawings {
        for (ext, format) in PLOT_FORMATS {
            write_file(&plot_file(dir, stem, ext), &format.encode(drawing, SvgText::Embed)?)?;
        }
    }
    Ok(())
}
