//! `whitted tradeoff`: what accuracy costs, measured (product.md). Every setting of
//! `whitted::tradeoff::settings` is rendered `--runs` times in this process; stdout gets a
//! Markdown table (or, with `--json`, the same figures as JSON), and with `--out DIR` the plots go
//! to DIR: the error against the time with the Pareto front, and the reference's rays-per-pixel
//! heat map.

use super::figure::{scene_name, Format};
use super::trace::LangArg;
use super::{load_scene, output, print_out, thread_pool, write_file, Failure};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::{json, Value};
use std::fmt::Write;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use whitted::accel::{AccelKind, AccelOptions};
use whitted::doc::{float, stats};
use whitted::figure::labels::Label;
use whitted::figure::plane::Planar;
use whitted::figure::source::Tracing;
use whitted::figure::tradeoff as tradeoff_plot;
use whitted::figure::{FigureKind, Options};
use whitted::render::{check_fits, RenderConfig};
use whitted::request::figure::{figure_in, Request};
use whitted::request::options::{canvas, resize};
use whitted::request::parse;
use whitted::request::target::Target;
use whitted::sample::{Sampling, DEFAULT_MAX_LEVEL, DEFAULT_THRESHOLD};
use whitted::scene::{AnyScene, Scene};
use whitted::tradeoff::{self, Measured, Tradeoff, REFERENCE_DEPTH, REFERENCE_SAMPLING};

/// Options of `whitted tradeoff`.
#[derive(Args, Debug)]
pub struct TradeoffArgs {
    /// The scene file (JSON).
    scene: PathBuf,
    /// Also draw the plots into this folder (created if missing): the error against the time
    /// with the Pareto front, and the reference's rays-per-pixel heat map, PNG and SVG.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the measurements as JSON instead of a Markdown table.
    #[arg(long)]
    json: bool,
    /// Renders per setting; the time is their median.
    #[arg(long, default_value_t = 3, value_parser = parse::runs, allow_hyphen_values = true)]
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

/// The plots of `--out`, each written as PNG and SVG.
const PLOTS: [&str; 2] = ["tradeoff", "heat-map"];
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
    // The reference render is the most demanding one, and its image is kept beside each other.
    let reference = RenderConfig { sampling: REFERENCE_SAMPLING, ..RenderConfig::centers(REFERENCE_DEPTH) };
    check_fits(scene, &reference, threads).map_err(|e| Failure::input(format!("tradeoff: {e}")))?;
    let settings = tradeoff::settings(scene.max_depth);
    let (total, base) = (settings.len() + 1, settings[0]);
    let lang = args.lang.lang();
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = ProgressBar::new(total as u64);
        let template = format!(
            "{{elapsed_precise}} [{{bar:30}}] {{pos}}/{{len}} {}: {{msg}}",
            Label::ProgressSettings.text(lang)
        );
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar
    });
    let measured = tradeoff::run(scene, args.runs as usize, |setting| {
        if let Some(bar) = &bar {
            let reference = setting.sampling == REFERENCE_SAMPLING && setting.depth == REFERENCE_DEPTH;
            bar.set_message(if reference {
                Label::ProgressReference.text(lang).to_owned()
            } else {
                tradeoff::setting_name(setting, &base)
            });
            bar.inc(1);
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let front = tradeoff::pareto_front(&measured.rows);
    let (nx, ny) = (scene.camera.nx, scene.camera.ny);
    if args.json {
        let doc = json!({
            "scene": args.scene.display().to_string(),
            "size": if V::DIM == 2 { json!([nx]) } else { json!([nx, ny]) },
            "threads": threads,
            "runs": measured.runs,
            "errors_on": "linear RGB clamped to [0, 1]",
            "reference": row_json(&measured.reference),
            "rows": measured.rows.iter().map(row_json).collect::<Vec<_>>(),
            "pareto": front,
        });
        print_out(&format!("{doc:#}\n"));
    } else {
        print_out(&table(scene, args, threads, &measured, &front));
    }
    plots(scene, args, &measured, &front)
}

fn row_json(m: &Measured) -> Value {
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
    json!({
        "sampling": sampling,
        "max_depth": s.depth,
        "accel": s.accel.name(),
        "seconds": m.seconds,
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
    })
}

fn table<V: Planar>(
    scene: &Scene<V>,
    args: &TradeoffArgs,
    threads: usize,
    measured: &Tradeoff,
    front: &[usize],
) -> String {
    let cam = &scene.camera;
    let size = if V::DIM == 2 { format!("{}", cam.nx) } else { format!("{}x{}", cam.nx, cam.ny) };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "What accuracy costs: {} at {size}, {threads} thread(s), median of {} render(s) a setting.\n\
         Error against the reference (adaptive, threshold 0, K = 3, max_depth {REFERENCE_DEPTH}) on the \
         linear colours clamped to [0, 1]; Pareto: on the front of time against RMSE.\n",
        args.scene.display(),
        measured.runs,
    );
    let _ = writeln!(
        out,
        "| sampling | max_depth | accel | time (ms) | rays/pixel | primary | reflected | transmitted | shadow | tests/ray | RMSE | max error | off > 1/255 | Pareto |"
    );
    let _ = writeln!(out, "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    let row = |out: &mut String, m: &Measured, pareto: &str| {
        let r = m.stats.rays;
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.3} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.5} | {:.4} | {:.2} % | {pareto} |",
            tradeoff::sampling_name(m.setting.sampling),
            m.setting.depth,
            m.setting.accel.name(),
            1e3 * m.seconds,
            m.rays_per_pixel(),
            m.per_pixel(r.primary),
            m.per_pixel(r.reflected),
            m.per_pixel(r.transmitted),
            m.per_pixel(r.shadow),
            m.tests_per_ray(),
            m.error.rmse,
            m.error.max,
            100.0 * m.error.off,
        );
    };
    for (i, m) in measured.rows.iter().enumerate() {
        row(&mut out, m, if front.contains(&i) { "yes" } else { "" });
    }
    row(&mut out, &measured.reference, "reference");
    out
}

/// The plots of `--out DIR`: `tradeoff.png`/`.svg` (error against time, the Pareto front) and
/// `heat-map.png`/`.svg` (the rays per pixel of adaptive sampling at threshold 0.1, K = 2, the
/// default of `whitted figure adaptive`, where the counts vary with the image).
fn plots<V: Planar>(
    scene: &Scene<V>,
    args: &TradeoffArgs,
    measured: &Tradeoff,
    front: &[usize],
) -> Result<(), Failure> {
    let Some(dir) = &args.out else { return Ok(()) };
    let (width, height) = canvas(None)?;
    let opts = Options { lang: args.lang.lang(), width, height };
    let name = scene_name(&args.scene);
    // A scene whose every image equals the reference (nothing but background, say) has no
    // point to plot: the table says so, and only the heat map is drawn.
    let plot = match tradeoff_plot::draw(measured, front, &name, &opts) {
        Ok(plot) => Some(plot),
        Err(e) => {
            eprintln!("whitted tradeoff: no plot of error against time: {e}");
            None
        }
    };
    let heat = figure_in(
        scene,
        &name,
        &Request {
            kind: FigureKind::HeatMap,
            target: Target::default(),
            tracing: Tracing {
                depth: None,
                sampling: Sampling::Adaptive { threshold: DEFAULT_THRESHOLD, max_level: DEFAULT_MAX_LEVEL },
                accel: AccelOptions::of(AccelKind::Bvh),
            },
            opts,
        },
    )?
    .drawing;
    for (stem, drawing) in PLOTS.into_iter().zip([plot.as_ref(), Some(&heat)]) {
        let Some(drawing) = drawing else { continue };
        for (ext, format) in PLOT_FORMATS {
            write_file(&plot_file(dir, stem, ext), &format.encode(drawing)?)?;
        }
    }
    Ok(())
}
