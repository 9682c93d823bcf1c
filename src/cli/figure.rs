//! `whitted figure KIND SCENE`: record the traces the kind reads (`figure::source`), draw them
//! (`figure::draw`) and write a PNG or an SVG, chosen by the file extension; `--list` names every
//! kind with one line.

use super::accel::AccelArgs;
use super::sampling::SamplingArgs;
use super::trace::{pixel_of, LangArg};
use super::{load_scene, output, print_out, write_file, Failure};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use whitted::canvas::svg::SvgText;
use whitted::canvas::Drawing;
use whitted::canvas::{skia, svg};
use whitted::figure::source::TraceOptions;
use whitted::figure::{FigureKind, Options};
use whitted::request::figure::{default_aa, figure, structure, Request};
use whitted::request::options::canvas;
use whitted::request::parse::{self, PixelArg};
use whitted::request::target::Target;
use whitted::scene::AnyScene;

/// Options of `whitted figure`.
#[derive(Args, Debug)]
pub struct FigureArgs {
    /// The diagram: uv-map, projections, rays, refraction, local-model, ray-tree, shadows, … (see --list).
    #[arg(required_unless_present = "list", value_parser = kind)]
    kind: Option<FigureKind>,
    /// The scene file (JSON).
    #[arg(required_unless_present = "list")]
    scene: Option<PathBuf>,
    /// The pixel: I,J (column from the left, row from the BOTTOM); in 2D, I. Without it (and
    /// without --ray) the figure picks a telling pixel and says which in its caption.
    #[arg(long, value_parser = parse::pixel, conflicts_with_all = ["ray", "object"], allow_hyphen_values = true)]
    pixel: Option<PixelArg>,
    /// A ray given by hand: OX,OY,OZ:DX,DY,DZ (OX,OY:DX,DY in 2D); traced as a primary ray.
    #[arg(long, value_parser = parse::ray, conflicts_with = "object", allow_hyphen_values = true)]
    ray: Option<(Vec<f64>, Vec<f64>)>,
    /// The pixel that shows the object of this name (as `whitted trace --object`).
    #[arg(long, value_name = "NAME")]
    object: Option<String>,
    /// The file to write: .png or .svg (default: KIND.png in the current folder).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// The labels' language.
    #[arg(long, value_enum, default_value = "en")]
    lang: LangArg,
    /// How an SVG draws its words (a PNG ignores it).
    #[arg(long, value_enum, default_value = "embed")]
    svg_text: SvgTextArg,
    /// Canvas size WxH in pixels (default 1920x1080; W alone keeps 16:9).
    #[arg(long, value_parser = parse::size, allow_hyphen_values = true)]
    size: Option<(usize, Option<usize>)>,
    /// Override the scene's max_depth (0 = ray casting).
    #[arg(long, value_parser = parse::depth, allow_hyphen_values = true)]
    depth: Option<u32>,
    /// Sampling, for `adaptive` and `heat-map` (default: adaptive, threshold 0.1, K = 2); the
    /// other kinds trace the pixel's centre.
    #[command(flatten)]
    sampling: SamplingArgs,
    /// The structure (--accel, --bounds, --grid) the other kinds trace with; `slab-test`,
    /// `kay-kajiya`, `bvh`, `grid-dda` and `octree` use their own, keeping --grid's cells.
    #[command(flatten)]
    accel: AccelArgs,
    /// The figure's title, instead of the kind's (a lesson's own wording; the text markup of
    /// labels: `n_1`, `t_{ex}`).
    #[arg(long, value_name = "TEXT")]
    title: Option<String>,
    /// Print every kind with one line and exit.
    #[arg(long)]
    list: bool,
}

/// How an SVG draws its words: `--svg-text`.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SvgTextArg {
    /// As text, in the subsets of the fonts it prints with, embedded.
    Embed,
    /// As glyph outlines (`<path>`), the words kept in an invisible `<text>` for screen readers
    /// and search; no font embedded.
    Paths,
}

impl SvgTextArg {
    /// The canvas's choice.
    pub fn text(self) -> SvgText {
        match self {
            Self::Embed => SvgText::Embed,
            Self::Paths => SvgText::Paths,
        }
    }
}

/// `KIND` → a figure kind, naming the valid ones otherwise.
fn kind(text: &str) -> Result<FigureKind, String> {
    FigureKind::from_name(text).ok_or_else(|| {
        let names: Vec<&str> = FigureKind::ALL.iter().map(|k| k.name()).collect();
        format!("unknown figure kind `{text}`; the kinds are: {}", names.join(", "))
    })
}

/// Runs `whitted figure`.
pub fn run(args: &FigureArgs) -> Result<(), Failure> {
    if args.list {
        let lines: Vec<String> =
            FigureKind::ALL.iter().map(|k| format!("{:<12} {}\n", k.name(), k.description())).collect();
        return print_out(&lines.concat());
    }
    let (Some(kind), Some(scene_path)) = (args.kind, args.scene.as_ref()) else {
        return Err(Failure::input("give KIND and SCENE, or --list"));
    };
    let output = args.output.clone().unwrap_or_else(|| PathBuf::from(format!("{}.png", kind.name())));
    let format = Format::of(&output, scene_path)?;
    let (width, height) = canvas(args.size)?;
    let scene = load_scene(scene_path)?;
    let pixel = pixel_of(&scene, args.pixel, args.object.as_deref())?;
    let request = Request {
        kind,
        target: Target { pixel, ray: args.ray.clone() },
        tracing: TraceOptions {
            depth: args.depth,
            sampling: args.sampling.sampling_or(default_aa(kind))?,
            accel: args.accel.options_for(dim_of(&scene), structure(kind, args.accel.choice().kind))?,
        },
        opts: Options { lang: args.lang.lang(), width, height },
    };
    let mut made = figure(&scene, &scene_name(scene_path), &request)?;
    if let Some(title) = &args.title {
        made.drawing.set_title(title);
    }
    write_file(&output, &format.encode(&made.drawing, args.svg_text.text())?)
}

/// The dimension of a loaded scene.
fn dim_of(scene: &AnyScene) -> usize {
    match scene {
        AnyScene::Flat(_) => 2,
        AnyScene::Space(_) => 3,
    }
}

/// The scene's name for captions: its file stem.
pub fn scene_name(path: &Path) -> String {
    path.file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
}

/// The two output formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// A PNG through tiny-skia.
    Png,
    /// An SVG document.
    Svg,
}

impl Format {
    /// The format a file name asks for by its extension, the file checked before the work as an
    /// output of `scene` (`output::check`: not the scene, a folder that can be written).
    pub fn of(path: &Path, scene: &Path) -> Result<Self, Failure> {
        Ok([Self::Png, Self::Svg][output::check(path, &["png", "svg"], &[scene])?])
    }
    /// The file's bytes; an SVG's words drawn as `text` says.
    pub fn encode(self, drawing: &Drawing, text: SvgText) -> Result<Vec<u8>, Failure> {
        match self {
            Self::Png => skia::to_png(drawing).map_err(|e| Failure::other(e.to_string())),
            Self::Svg => Ok(svg::to_svg_with(drawing, text).into_bytes()),
        }
    }
}
