//! `whitted trace`: one pixel (or one ray) traced with `EventLog`; `--json` prints the trace
//! document, otherwise the numbered narration (`doc::narrate`) in English or Romanian. With
//! `--aa corners|adaptive` the pixel's samples are traced instead of its centre (`sample::trace_pixel`,
//! `doc::samples`).

use super::accel::AccelArgs;
use super::parse::PixelArg;
use super::sampling::SamplingArgs;
use super::{load_scene, parse, print_out, Failure};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use whitted::accel::Accel;
use whitted::doc::narrate::{narrate, Lang};
use whitted::doc::samples::{narrate_samples, sampled_document};
use whitted::doc::{trace_document, TraceTarget};
use whitted::geom::ray::Ray;
use whitted::record::{overflow_message, EventLog};
use whitted::sample::{trace_pixel, Sampling};
use whitted::scene::{AnyScene, Scene};
use whitted::shape::Dim;
use whitted::trace::Tracer;

/// The narration's language.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum LangArg {
    /// English.
    En,
    /// Romanian (with diacritics).
    Ro,
}

impl LangArg {
    /// The library's language.
    pub fn lang(self) -> Lang {
        match self {
            Self::En => Lang::En,
            Self::Ro => Lang::Ro,
        }
    }
}

/// What `trace` and `step` trace and how they tell it: the scene, the pixel or ray, the depth,
/// the language, the sampling and the structure.
#[derive(Args, Debug)]
pub struct TraceWhat {
    /// The scene file (JSON).
    scene: PathBuf,
    /// The pixel: I,J (column from the left, row from the BOTTOM); in 2D, I (or I,0).
    #[arg(long, value_parser = parse::pixel, conflicts_with = "ray", required_unless_present = "ray",
          allow_hyphen_values = true)]
    pixel: Option<PixelArg>,
    /// A ray given by hand: OX,OY,OZ:DX,DY,DZ (OX,OY:DX,DY in 2D); traced as a primary ray.
    #[arg(long, value_parser = parse::ray, allow_hyphen_values = true)]
    ray: Option<(Vec<f64>, Vec<f64>)>,
    /// Override the scene's max_depth (0 = ray casting).
    #[arg(long, value_parser = parse::depth, allow_hyphen_values = true)]
    depth: Option<u32>,
    /// The narration's language.
    #[arg(long, value_enum, default_value = "en")]
    lang: LangArg,
    /// With --pixel: corners or adaptive trace the pixel's samples instead of its centre.
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    accel: AccelArgs,
    /// The most events and ray nodes recorded; a trace that needs more is refused (a ray tree grows
    /// as 2^depth where objects both reflect and transmit).
    #[arg(long, value_name = "N", value_parser = parse::max_events, allow_hyphen_values = true,
          default_value_t = whitted::record::DEFAULT_LIMIT)]
    max_events: usize,
}

impl TraceWhat {
    /// The narration's language.
    pub fn lang(&self) -> Lang {
        self.lang.lang()
    }
}

/// Options of `whitted trace`.
#[derive(Args, Debug)]
pub struct TraceArgs {
    #[command(flatten)]
    what: TraceWhat,
    /// Print the trace document (JSON) instead of the narration.
    #[arg(long)]
    json: bool,
}

/// Runs `whitted trace`.
pub fn run(args: &TraceArgs) -> Result<(), Failure> {
    print_out(&traced(&args.what, args.json)?);
    Ok(())
}

/// The numbered narration of what `what` asks for (`whitted step` shows it a step at a time).
pub fn narration(what: &TraceWhat) -> Result<String, Failure> {
    traced(what, false)
}

/// The trace document (`json`) or the narration.
fn traced(what: &TraceWhat, json: bool) -> Result<String, Failure> {
    match load_scene(&what.scene)? {
        AnyScene::Flat(s) => trace_scene(&s, what, json),
        AnyScene::Space(s) => trace_scene(&s, what, json),
    }
}

/// The primary ray and what it was asked as: `--pixel I,J` (validated against the image) or
/// `--ray O:D` (validated against the dimension); shared by `trace`, `figure` and `lessons`.
pub fn target<V: Dim>(
    scene: &Scene<V>,
    pixel: Option<PixelArg>,
    ray: Option<&(Vec<f64>, Vec<f64>)>,
) -> Result<(Ray<V>, TraceTarget), Failure> {
    let cam = &scene.camera;
    if let Some((i, j)) = pixel {
        let j = match (V::DIM, j) {
            (2, None | Some(0)) => 0,
            (2, Some(j)) => {
                return Err(Failure::input(format!("--pixel: a 2D image has one row (j = 0), got j = {j}")))
            }
            (_, None) => return Err(Failure::input("--pixel: a 3D scene needs I,J".to_string())),
            (_, Some(j)) => j,
        };
        let inside = |k: i64, n: usize| usize::try_from(k).ok().filter(|k| *k < n);
        let (Some(i), Some(j)) = (inside(i, cam.nx), inside(j, cam.ny)) else {
            return Err(Failure::input(format!(
                "--pixel: ({i}, {j}) is outside the image: i must be in [0, {}), j in [0, {})",
                cam.nx, cam.ny
            )));
        };
        let (u, v) = cam.pixel_center(i, j);
        let ray = cam.primary_ray(u, v);
        let (pixel, uv) = if V::DIM == 2 { (vec![i], vec![u]) } else { (vec![i, j], vec![u, v]) };
        return Ok((ray, TraceTarget { pixel: Some(pixel), uv: Some(uv) }));
    }
    let Some((o, d)) = ray else {
        return Err(Failure::input("give --pixel I,J or --ray O:D"));
    };
    let wrong = |what: &str, n: usize| {
        Failure::input(format!(
            "--ray: the {what} must have {} numbers in a {}D scene, got {n}",
            V::DIM,
            V::DIM
        ))
    };
    let origin = V::from_slice(o).ok_or_else(|| wrong("origin", o.len()))?;
    let dir = V::from_slice(d).ok_or_else(|| wrong("direction", d.len()))?;
    let dir = dir.try_unit().ok_or_else(|| Failure::input("--ray: the direction must not be zero"))?;
    Ok((Ray::new(origin, dir), TraceTarget { pixel: None, uv: None }))
}

fn trace_scene<V: Dim>(scene: &Scene<V>, args: &TraceWhat, json: bool) -> Result<String, Failure> {
    let sampling = args.sampling.sampling()?;
    let (ray, target) = target(scene, args.pixel, args.ray.as_ref())?;
    let options = args.accel.options(V::DIM).map_err(Failure::input)?;
    let accel = Accel::build_with(scene, &options);
    let mut tracer = Tracer::new(scene, &accel, EventLog::with_limit(args.max_events));
    if let Some(d) = args.depth {
        tracer.max_depth = d;
    }
    let overflow = |log: &EventLog<V>, depth: u32| {
        if log.overflowed() {
            let why = overflow_message(log.limit(), depth, scene.worst_tree_rays(depth));
            return Err(Failure::input(format!("trace: {why} or raise --max-events")));
        }
        Ok(())
    };
    let pretty = |doc: &serde_json::Value| {
        serde_json::to_string_pretty(doc).map(|t| t + "\n").map_err(|e| Failure::other(e.to_string()))
    };
    if sampling != Sampling::Center {
        let Some(pixel) = target.pixel.clone() else {
            return Err(Failure::input("--aa corners|adaptive samples a pixel: give --pixel, not --ray"));
        };
        let traced = trace_pixel(&mut tracer, sampling, pixel[0], pixel.get(1).copied().unwrap_or(0));
        overflow(&tracer.recorder, tracer.max_depth)?;
        return if json {
            pretty(&sampled_document(scene, &tracer.recorder, &tracer.stats, &target, sampling, &traced))
        } else {
            Ok(narrate_samples(&target, sampling, &traced, &tracer.stats, args.lang.lang()))
        };
    }
    let uv = target.uv.clone().unwrap_or_default();
    let color = tracer.trace_primary(&ray, &uv);
    overflow(&tracer.recorder, tracer.max_depth)?;
    if json {
        pretty(&trace_document(scene, &tracer.recorder, &tracer.stats, &target, color))
    } else {
        Ok(narrate(scene, &tracer.recorder, &tracer.stats, &target, tracer.max_depth, args.lang.lang()))
    }
}
