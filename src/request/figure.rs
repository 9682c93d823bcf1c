//! One diagram (`whitted figure KIND`): its traces recorded (`figure::source`), drawn
//! (`figure::draw`), and what the figure picked when no pixel was given.

use super::options::Aa;
use super::target::Target;
use super::Failure;
use crate::accel::{AccelKind, AccelOptions};
use crate::canvas::Drawing;
use crate::doc::TraceTarget;
use crate::figure::labels::{self, Label};
use crate::figure::plane::Planar;
use crate::figure::source::{self, Pick, TraceOptions};
use crate::figure::{self as fig, FigureKind, Options};
use crate::lesson::claim::{self, Claim, Verdict};
use crate::lesson::FigureSpec;
use crate::sample::Sampling;
use crate::scene::{AnyScene, Scene};

/// One figure to make: its kind, what to trace, how to draw.
#[derive(Clone, Debug, PartialEq)]
pub struct Request {
    /// The diagram.
    pub kind: FigureKind,
    /// `--pixel` or `--ray`; neither lets the figure pick a pixel.
    pub target: Target,
    /// Depth, structure and sampling.
    pub tracing: TraceOptions,
    /// Language and size.
    pub opts: Options,
}

impl Request {
    /// The request a lesson's figure makes, drawn with `opts`: its pixel or ray, depth, sampling
    /// (the centre when it names none) and grid, the rest of the structure as the kind wants it.
    #[must_use]
    pub fn of_lesson(spec: &FigureSpec, opts: Options) -> Self {
        // Past i64::MAX a pixel is outside the image anyway, and is refused as such.
        let signed = |k: usize| i64::try_from(k).unwrap_or(i64::MAX);
        Self {
            kind: spec.kind,
            target: Target {
                pixel: spec.pixel.map(|(i, j)| (signed(i), j.map(signed))),
                ray: spec.ray.clone(),
            },
            tracing: TraceOptions {
                depth: spec.depth,
                sampling: spec.sampling.unwrap_or(Sampling::Center),
                accel: AccelOptions { grid: spec.grid.clone(), ..TraceOptions::SCENE.accel },
            },
            opts,
        }
    }
}

/// A drawn figure and what it traced.
#[derive(Clone, Debug)]
pub struct Made {
    /// The display list (to PNG through `canvas::skia`, to SVG through `canvas::svg`).
    pub drawing: Drawing,
    /// The main trace's pixel and `(u, v)` (both None for a ray, or for `heat-map`, which traces
    /// no single pixel).
    pub traced: TraceTarget,
    /// When the figure chose the pixel itself: which and why, as its caption says it
    /// (`pixel (400, 200) (picked: its trace has the most kinds of rays)`).
    pub pick: Option<String>,
}

/// The sampling `--aa` defaults to for a kind: adaptive for `adaptive` and `heat-map`, else the
/// centre.
#[must_use]
pub fn default_aa(kind: FigureKind) -> Aa {
    match kind {
        FigureKind::Adaptive | FigureKind::HeatMap | FigureKind::JaggedEdges => Aa::Adaptive,
        _ => Aa::Center,
    }
}

/// The structure a figure of `kind` traces with: its own for the structure kinds, else `asked`
/// (`--accel`); what decides which of `--bounds` and `--grid` it reads.
#[must_use]
pub fn structure(kind: FigureKind, asked: AccelKind) -> AccelKind {
    match kind {
        FigureKind::SlabTest | FigureKind::KayKajiya => AccelKind::Bounds,
        FigureKind::Bvh => AccelKind::Bvh,
        FigureKind::GridDda => AccelKind::Grid,
        FigureKind::Octree => AccelKind::Octree,
        FigureKind::Discriminant => AccelKind::None,
        _ => asked,
    }
}

/// Records and draws one figure of a loaded scene called `name` (its file stem, for captions).
///
/// # Errors
/// Bad input: the target, or traces that lack what the kind draws.
pub fn figure(scene: &AnyScene, name: &str, request: &Request) -> Result<Made, Failure> {
    match scene {
        AnyScene::Flat(s) => figure_in(s, name, request),
        AnyScene::Space(s) => figure_in(s, name, request),
    }
}

/// [`figure`] of a scene of known dimension.
///
/// # Errors
/// As [`figure`].
pub fn figure_in<V: Planar>(scene: &Scene<V>, name: &str, request: &Request) -> Result<Made, Failure> {
    figure_claimed(scene, name, request, &[]).map(|(made, _)| made)
}

/// [`figure`] with its lesson's claims checked on the traces and the drawing it made
/// (`lesson::claim`), a verdict per claim in their order.
///
/// # Errors
/// As [`figure`].
pub fn figure_checked(
    scene: &AnyScene,
    name: &str,
    request: &Request,
    claims: &[Claim],
) -> Result<(Made, Vec<Verdict>), Failure> {
    match scene {
        AnyScene::Flat(s) => figure_claimed(s, name, request, claims),
        AnyScene::Space(s) => figure_claimed(s, name, request, claims),
    }
}

/// [`figure_checked`] in a scene of known dimension.
fn figure_claimed<V: Planar>(
    scene: &Scene<V>,
    name: &str,
    request: &Request,
    claims: &[Claim],
) -> Result<(Made, Vec<Verdict>), Failure> {
    let aim = request.target.aim(scene)?;
    let traces = source::record(request.kind, scene, name, &aim, &request.tracing)
        .map_err(|e| Failure::input(format!("{}: {e}", request.kind.name())))?;
    let drawing = fig::draw(request.kind, &traces, scene, &request.opts)
        .map_err(|e| Failure::input(format!("{}: {e}", request.kind.name())))?;
    let lang = request.opts.lang;
    let main = traces.traces.first();
    let first = main.and_then(|t| t.targets.first());
    let traced = match first {
        Some(source::Target::Pixel { i, j, uv }) => TraceTarget {
            pixel: Some(if V::DIM == 2 { vec![*i] } else { vec![*i, *j] }),
            uv: Some(uv.clone()),
        },
        _ => TraceTarget { pixel: None, uv: None },
    };
    let pick = match (main, first) {
        (Some(t), Some(what)) if t.pick != Pick::Given => labels::pick_reason(t.pick, lang).map(|why| {
            format!("{} ({}: {why})", labels::target(what, V::DIM, lang), Label::Picked.text(lang))
        }),
        _ => None,
    };
    let verdicts = claim::check_all(claims, &traces, scene, &drawing);
    Ok((Made { drawing, traced, pick }, verdicts))
}
