//! `whitted trace`: one pixel (or one ray) traced with `EventLog` (`request::trace`); `--json`
//! prints the trace document, otherwise the numbered narration (`doc::narrate`) in English or
//! Romanian. With `--aa corners|adaptive` the pixel's samples are traced instead of its centre.
//!
//! `TraceWhat` and `narration` are shared with `step`.

use super::accel::AccelArgs;
use super::sampling::SamplingArgs;
use super::{load_scene, print_json, print_notes, print_out, Failure};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use whitted::doc::narrate::{Lang, Narration};
use whitted::request::parse::{self, PixelArg};
use whitted::request::target::{object_pixel, Target};
use whitted::request::trace::{document_text, Trace};
use whitted::scene::AnyScene;

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
    #[arg(long, value_parser = parse::pixel, conflicts_with_all = ["ray", "object"],
          required_unless_present_any = ["ray", "object"], allow_hyphen_values = true)]
    pixel: Option<PixelArg>,
    /// A ray given by hand: OX,OY,OZ:DX,DY,DZ (OX,OY:DX,DY in 2D); traced as a primary ray.
    #[arg(long, value_parser = parse::ray, conflicts_with = "object", allow_hyphen_values = true)]
    ray: Option<(Vec<f64>, Vec<f64>)>,
    /// The pixel that shows the object of this name: of the pixels whose primary ray hits it
    /// first, the one nearest their centroid.
    #[arg(long, value_name = "NAME")]
    object: Option<String>,
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
    let text = traced(&args.what, args.json)?;
    if args.json {
        print_json(&text)
    } else {
        print_out(&text)
    }
}

/// The numbered narration of what `what` asks for, with each step's events and place (`whitted
/// step` shows it a step at a time).
pub fn narration(what: &TraceWhat) -> Result<Narration, Failure> {
    let (scene, trace) = prepared(what)?;
    Ok(trace.narration(&scene, what.lang())?.narration)
}

/// The trace document (`json`) or the narration's text.
fn traced(what: &TraceWhat, json: bool) -> Result<String, Failure> {
    if !json {
        return Ok(narration(what)?.text);
    }
    let (scene, trace) = prepared(what)?;
    document_text(&trace.document(&scene)?)
}

/// The `--pixel` that `--object NAME` stands for, said on stderr; else `pixel` as given.
pub fn pixel_of(
    scene: &AnyScene,
    pixel: Option<PixelArg>,
    object: Option<&str>,
) -> Result<Option<PixelArg>, Failure> {
    let Some(name) = object else { return Ok(pixel) };
    let (i, j) = object_pixel(scene, name)?;
    let at = j.map_or_else(|| i.to_string(), |j| format!("{i},{j}"));
    print_notes(&[format!("--object {name}: --pixel {at}")]);
    Ok(Some((i, j)))
}

/// The scene and the trace `what` asks for, checked, with the notes on ignored options said.
fn prepared(what: &TraceWhat) -> Result<(AnyScene, Trace), Failure> {
    let scene = load_scene(&what.scene)?;
    let pixel = pixel_of(&scene, what.pixel, what.object.as_deref())?;
    let trace = Trace {
        target: Target { pixel, ray: what.ray.clone() },
        depth: what.depth,
        sampling: what.sampling.sampling()?,
        accel: what.accel.choice(),
        max_events: what.max_events,
    };
    // The target and the structure are checked first, and what the structure ignores is said.
    print_notes(&trace.check(&scene)?);
    Ok((scene, trace))
}
