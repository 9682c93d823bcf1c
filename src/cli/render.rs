//! `whitted render`: load → build the acceleration structure → render (with the `--aa` sampling,
//! a progress bar on stderr when it is a terminal) → PNG → the one-line summary (pixels, samples,
//! rays by kind, tests, Mrays/s, time) on stderr, `--json` statistics on stdout.

use super::accel::AccelArgs;
use super::sampling::SamplingArgs;
use super::{default_output, load_scene, output, print_json, thread_pool, write_file, Failure};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;
use whitted::accel::AccelOptions;
use whitted::format::terminal_text;
use whitted::image::Image;
use whitted::request::options::resize;
use whitted::request::parse;
use whitted::request::render::{self as job, Job, Outcome};
use whitted::sample::Sampling;
use whitted::scene::{AnyScene, Scene};
use whitted::shape::Dim;

/// Options of `whitted render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// The scene file (JSON).
    scene: PathBuf,
    /// The PNG to write (default: the scene's name with .png, in the current folder); it is
    /// replaced only by a complete image, never left torn.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Override the scene's max_depth (0 = ray casting).
    #[arg(long, value_parser = parse::depth, allow_hyphen_values = true)]
    depth: Option<u32>,
    /// Resolution WxH (keeps the window); in 2D, W or WxH (H = the strip's rows).
    #[arg(long, value_parser = parse::size, allow_hyphen_values = true)]
    size: Option<(usize, Option<usize>)>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = parse::threads, allow_hyphen_values = true)]
    threads: Option<u32>,
    /// Print the run's statistics as one JSON object on stdout.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    accel: AccelArgs,
}

/// Runs `whitted render`.
pub fn run(args: &RenderArgs) -> Result<(), Failure> {
    let sampling = args.sampling.sampling()?;
    // The output is checked before the work: not the scene, a PNG, in a folder that can be written.
    let output = args.output.clone().unwrap_or_else(|| default_output(&args.scene, "png"));
    output::check(&output, &["png"], &[&args.scene])?;
    let start = Instant::now();
    let scene = load_scene(&args.scene)?;
    let load_seconds = start.elapsed().as_secs_f64();
    let pool = thread_pool(args.threads)?;
    let threads = pool.current_num_threads();
    let dim = match &scene {
        AnyScene::Flat(_) => 2,
        AnyScene::Space(_) => 3,
    };
    let options = args.accel.options_for(dim, args.accel.choice().kind)?;
    let outcome = match scene {
        AnyScene::Flat(mut s) => {
            let rows = resize(&mut s, args.size);
            pool.install(|| render_scene(&s, args, sampling, &options, rows))
        }
        AnyScene::Space(mut s) => {
            let rows = resize(&mut s, args.size);
            pool.install(|| render_scene(&s, args, sampling, &options, rows))
        }
    }?;
    let png = png(&outcome.rendered.image).map_err(Failure::other)?;
    write_file(&output, &png)?;
    let stats = &outcome.rendered.stats;
    let rays = stats.rays;
    let mrays = rays.total() as f64 / outcome.seconds.max(1e-9) / 1e6;
    eprintln!(
        "whitted: {}x{} → {} | {} pixels, {} samples ({}) | rays: {} primary, {} reflected, {} transmitted, {} shadow | tests: {} object, {} bound, {} node, {} voxel | {} | {:.3} s trace, {:.2} Mrays/s, {} threads",
        outcome.rendered.image.width,
        outcome.rendered.image.height,
        terminal_text(&output.display().to_string()),
        outcome.rendered.pixels,
        rays.primary,
        describe(sampling),
        rays.primary,
        rays.reflected,
        rays.transmitted,
        rays.shadow,
        stats.tests.object,
        stats.tests.bound,
        stats.tests.node,
        stats.tests.voxel,
        outcome.accel,
        outcome.seconds,
        mrays,
        threads,
    );
    if args.json {
        let doc = outcome.json(load_seconds, threads, Some(&output.display().to_string()));
        print_json(&format!("{doc}\n"))?;
    }
    Ok(())
}

/// The sampling mode as the summary line shows it.
fn describe(sampling: Sampling) -> String {
    match sampling {
        Sampling::Adaptive { threshold, max_level } => {
            format!("adaptive, threshold {threshold}, max level {max_level}")
        }
        other => other.name().to_string(),
    }
}

fn render_scene<V: Dim>(
    scene: &Scene<V>,
    args: &RenderArgs,
    sampling: Sampling,
    options: &AccelOptions,
    strip_rows: Option<usize>,
) -> Result<Outcome, Failure> {
    // A progress bar over pixel rows, only for a person watching a terminal.
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = ProgressBar::new(scene.camera.ny as u64);
        if let Ok(style) =
            ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} rows, eta {eta}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar
    });
    let tick = |rows: u64| {
        if let Some(bar) = &bar {
            bar.inc(rows);
        }
    };
    let outcome = job::run(
        scene,
        &Job {
            depth: args.depth,
            sampling,
            accel: options,
            strip_rows,
            progress: bar.is_some().then_some(&tick as &(dyn Fn(u64) + Sync)),
        },
    )?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(outcome)
}

/// The image as PNG bytes, 8-bit RGB in file order ([`Image::to_rgb8`]). The command line's own:
/// the `image` crate is a dependency of the `cli` feature only, so the library built for the
/// browser (which never writes a PNG) does not compile it.
///
/// # Errors
/// Only if the encoder fails (it does not for valid sizes).
fn png(image: &Image<[u8; 3]>) -> Result<Vec<u8>, String> {
    use image::ImageEncoder;
    let width = u32::try_from(image.width).map_err(|e| e.to_string())?;
    let height = u32::try_from(image.height).map_err(|e| e.to_string())?;
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(&image.to_rgb8(), width, height, image::ExtendedColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}
