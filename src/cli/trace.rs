//! `whitted trace`: one pixel (or one ray) traced with `EventLog` (`request::trace`); `--json`
//! prints the trace document, otherwise the numbered narration (`doc::narrate`) in English or
//! Romanian. With `--aa corners|adaptive` the pixel's samples are traced instead of its centre.

use super::accel::AccelArgs;
use super::sampling::SamplingArgs;
use super::{load_scene, print_out, Failure};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use whitted::doc::narrate::Lang;
use whitted::request::parse;
use whitted::request::target::Target;
use whitted::request::trace::{document_text, Trace};

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
    #[arg(long, value_parser = parse::pixel, conflicts_with = "ray", required_unless_present = "ray")]
    pixel: Option<(usize, Option<usize>)>,
    /// A ray given by hand: OX,OY,OZ:DX,DY,DZ (OX,OY:DX,DY in 2D); traced as a primary ray.
    #[arg(long, value_parser = parse::ray)]
    ray: Option<(Vec<f64>, Vec<f64>)>,
    /// Override the scene's max_depth (0 = ray casting).
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=64))]
    depth: Option<u32>,
    /// The narration's language.
    #[arg(long, value_enum, default_value = "en")]
    lang: LangArg,
    /// With --pixel: corners or adaptive trace the pixel's samples instead of its centre.
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    accel: AccelArgs,
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
    let scene = load_scene(&what.scene)?;
    let trace = Trace {
        target: Target { pixel: what.pixel, ray: what.ray.clone() },
        depth: what.depth,
        sampling: what.sampling.sampling()?,
        accel: what.accel.choice(),
    };
    if json {
        document_text(&trace.document(&scene)?)
    } else {
        Ok(trace.narration(&scene, what.lang())?.narration.text)
    }
}
