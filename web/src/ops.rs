//! The requests (`web/README.md`): `check`, `info`, `render`, `trace`, `narrate`, `figure`,
//! `kinds`. Each reads its fields, calls the library function the command line calls
//! (`whitted::request`), and answers JSON; a failure answers `{"errors": [...]}` with the command
//! line's words, one line each, and its exit code (2 bad input, 1 anything else).

use crate::ask::{self, Fields, Options};
use serde_json::{json, Map, Value};
use std::path::Path;
use whitted::canvas::svg;
use whitted::clock::Stopwatch;
use whitted::doc::narrate::Lang;
use whitted::doc::TraceTarget;
use whitted::figure::source::TraceOptions;
use whitted::figure::FigureKind;
use whitted::record::DEFAULT_LIMIT;
use whitted::request::figure::{default_aa, figure, structure, Request};
use whitted::request::options::{canvas, resize, Aa};
use whitted::request::render::{self as job, Job};
use whitted::request::target::Target;
use whitted::request::trace::{document_text, Trace};
use whitted::request::{check, Failure};
use whitted::sample::Sampling;
use whitted::scene::load::load_str_with;
use whitted::scene::{AnyScene, Scene};
use whitted::shape::Dim;

/// What a call answers: its code, the JSON text, and the binary answer (a render's RGBA).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Answer {
    /// 0 ok, 2 bad input, 1 anything else.
    pub code: u8,
    /// The answer's JSON (for `trace`, the trace document as `whitted trace --json` prints it).
    pub json: String,
    /// A render's RGBA8, top row first; empty otherwise.
    pub bytes: Vec<u8>,
}

impl Answer {
    fn ok(json: String) -> Self {
        Self { code: 0, json, bytes: Vec::new() }
    }
    fn failed(f: &Failure) -> Self {
        Self::ok(json!({ "errors": f.message.lines().collect::<Vec<_>>() }).to_string()).with_code(f.code())
    }
    fn with_code(self, code: u8) -> Self {
        Self { code, ..self }
    }
}

/// The most pixels a render in the page may have: a wasm32 module addresses at most 4 GiB, and a
/// render holds 24 bytes a pixel (linear RGB) and 4 more for the RGBA answer; 2^23 pixels (a
/// 4096×2048 image) take about 235 MB. The command line has no such limit.
pub const MAX_PAGE_PIXELS: usize = 1 << 23;

/// Refuses an image of `nx` × `ny` pixels beyond [`MAX_PAGE_PIXELS`] (`what` names it).
fn fits(what: &str, nx: usize, ny: usize) -> Result<(), Failure> {
    if nx.saturating_mul(ny) > MAX_PAGE_PIXELS {
        return Err(Failure::input(format!(
            "{what}: the page renders at most {MAX_PAGE_PIXELS} pixels (4096x2048), got {nx}x{ny}; give a smaller --size"
        )));
    }
    Ok(())
}

/// The image a scene renders to: its camera's pixels, or a 2D strip's rows.
fn image_size<V: Dim>(scene: &Scene<V>, strip_rows: Option<usize>) -> (usize, usize) {
    let cam = &scene.camera;
    if V::DIM == 2 {
        (cam.nx, strip_rows.unwrap_or_else(|| whitted::render::strip_height(cam.nx)))
    } else {
        (cam.nx, cam.ny)
    }
}

/// The fields a request may have.
const FIELDS: [&str; 9] = ["op", "scene", "objs", "name", "options", "target", "lang", "kind", "rows"];

/// The name a request's scene goes by when it gives none (in `check`'s text, captions and
/// commands).
pub const DEFAULT_NAME: &str = "scene.json";

/// Runs one request (UTF-8 JSON) and answers it. Never panics on any input.
#[must_use]
pub fn call(request: &[u8]) -> Answer {
    match run(request) {
        Ok(answer) => answer,
        Err(f) => Answer::failed(&f),
    }
}

fn run(request: &[u8]) -> Result<Answer, Failure> {
    let text =
        std::str::from_utf8(request).map_err(|e| Failure::input(format!("request: not UTF-8: {e}")))?;
    let value: Value = serde_json::from_str(text).map_err(|e| Failure::input(format!("request: {e}")))?;
    let f = Fields::of("request", &value, &FIELDS)?;
    match f.string("request", "op")? {
        "check" => check_op(&f),
        "info" => info_op(&f),
        "render" => render_op(&f),
        "trace" => trace_op(&f),
        "narrate" => narrate_op(&f),
        "figure" => figure_op(&f),
        "kinds" => Ok(kinds()),
        other => Err(Failure::input(format!(
            "request.op: unknown `{other}`; the ops are: check, info, render, trace, narrate, figure, kinds"
        ))),
    }
}

/// The scene's name (`name`, else [`DEFAULT_NAME`]).
fn name<'a>(f: &Fields<'a>) -> Result<&'a str, Failure> {
    if f.get("name").is_some() {
        f.string("request", "name")
    } else {
        Ok(DEFAULT_NAME)
    }
}

/// The scene's file stem, as captions name it.
fn stem(name: &str) -> String {
    Path::new(name).file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
}

/// The request's scene, loaded with its meshes' OBJ texts from `objs`; every problem is one line.
fn scene(f: &Fields<'_>) -> Result<AnyScene, Failure> {
    let text = f.string("request", "scene")?;
    let objs: Map<String, Value> = match f.get("objs") {
        None => Map::new(),
        Some(Value::Object(m)) => m.clone(),
        Some(other) => {
            return Err(Failure::input(format!("request.objs: expected an object, got `{other}`")))
        }
    };
    let read = |file: &str| match objs.get(file) {
        Some(Value::String(s)) => Ok(s.clone()),
        Some(_) => Err(format!("request.objs.{file} is not a string")),
        None => Err("not among the request's objs".to_string()),
    };
    load_str_with(text, &read).map_err(|errors| {
        Failure::input(errors.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n"))
    })
}

fn dim(scene: &AnyScene) -> usize {
    match scene {
        AnyScene::Flat(_) => 2,
        AnyScene::Space(_) => 3,
    }
}

/// `--size` is a camera's only for `render` (and `info`), a canvas's for `figure`; `trace` and
/// `narrate` take none, as `whitted trace` takes none.
fn no_size(options: &Options, op: &str) -> Result<(), Failure> {
    if options.size.is_some() {
        return Err(Failure::input(format!(
            "--size: `{op}` takes no --size (the pixel is one of the scene's)"
        )));
    }
    Ok(())
}

fn check_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let name = name(f)?;
    Ok(match scene(f) {
        Ok(s) => Answer::ok(json!({"ok": true, "errors": [], "text": check::report(&s, name)}).to_string()),
        Err(e) if e.input => {
            let errors: Vec<&str> = e.message.lines().collect();
            Answer::ok(json!({"ok": false, "errors": errors, "text": ""}).to_string()).with_code(e.code())
        }
        Err(e) => return Err(e),
    })
}

fn info_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let options = ask::options(f.get("options"))?;
    let info = match scene(f)? {
        AnyScene::Flat(mut s) => info(&mut s, &options),
        AnyScene::Space(mut s) => info(&mut s, &options),
    };
    Ok(Answer::ok(info.to_string()))
}

fn info<V: Dim>(scene: &mut Scene<V>, options: &Options) -> Value {
    let rows = resize(scene, options.size);
    let (width, height) = image_size(scene, rows);
    json!({
        "dimension": V::DIM,
        "width": width,
        "height": height,
        "objects": (0..scene.objects.len()).map(|i| scene.object_label(i, Lang::En)).collect::<Vec<_>>(),
        "max_depth": options.depth.unwrap_or(scene.max_depth),
    })
}

fn render_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let options = ask::options(f.get("options"))?;
    let chosen = options.sampling.choose(Aa::Center)?;
    if let Some(rows) = f.get("rows") {
        return band_op(&options, scene(f)?, ask::rows(rows)?, chosen.sampling);
    }
    let watch = Stopwatch::start();
    let scene = scene(f)?;
    let load_seconds = watch.seconds();
    let accel = options.accel.options(dim(&scene))?;
    let run = |strip_rows| Job {
        depth: options.depth,
        sampling: chosen.sampling,
        accel: &accel,
        strip_rows,
        progress: None,
    };
    let outcome = match scene {
        AnyScene::Flat(mut s) => {
            let rows = resize(&mut s, options.size);
            let (w, h) = image_size(&s, rows);
            fits("render", w, h)?;
            job::run(&s, &run(rows))?
        }
        AnyScene::Space(mut s) => {
            let rows = resize(&mut s, options.size);
            let (w, h) = image_size(&s, rows);
            fits("render", w, h)?;
            job::run(&s, &run(rows))?
        }
    };
    let mut doc = outcome.json(load_seconds, rayon::current_num_threads(), None);
    let notes: Vec<String> =
        chosen.notes.into_iter().chain(options.accel.notes(options.accel.kind)).collect();
    doc["notes"] = json!(notes);
    Ok(Answer { code: 0, json: doc.to_string(), bytes: outcome.rendered.image.to_rgba8() })
}

/// A render's band of file rows `[first, first + count)` (the top row 0), for a page that shows
/// the render's progress: the same colours and counts as those rows of the whole render
/// (`render::center_band`). Only a centre-sampled 3D image is rendered by bands: a 2D strip is one
/// row, and corners and adaptive sampling share lattice rows between pixel rows.
fn band_op(
    options: &ask::Options,
    scene: AnyScene,
    (first, count): (usize, usize),
    sampling: Sampling,
) -> Result<Answer, Failure> {
    let AnyScene::Space(mut s) = scene else {
        return Err(Failure::input("request.rows: a 2D scene renders one row; render it whole"));
    };
    if sampling != Sampling::Center {
        return Err(Failure::input(format!(
            "request.rows: --aa {} shares samples between rows; render it whole",
            sampling.name()
        )));
    }
    resize(&mut s, options.size);
    let (w, h) = image_size(&s, None);
    fits("render", w, h)?;
    if first >= h {
        return Err(Failure::input(format!("request.rows: the image has {h} rows, got first row {first}")));
    }
    let accel = whitted::accel::Accel::build_with(&s, &options.accel.options(3)?).for_render();
    // File row f is image row j = Ny − 1 − f: the band's rows from the bottom.
    let top = h - first;
    let bottom = top.saturating_sub(count);
    let depth = options.depth.unwrap_or(s.max_depth);
    let (band, stats) = whitted::render::center_band(&s, &accel, depth, bottom..top);
    let mut doc = whitted::doc::stats(&stats);
    doc["rows"] = json!([first, band.height]);
    doc["width"] = json!(w);
    doc["height"] = json!(h);
    doc["accel"] = json!(accel.kind().name());
    doc["notes"] = json!(options.accel.notes(options.accel.kind));
    Ok(Answer { code: 0, json: doc.to_string(), bytes: band.to_rgba8() })
}

/// What a `trace` or `narrate` request asks for.
struct TraceAsked {
    /// The scene.
    scene: AnyScene,
    /// The trace: target, depth, sampling, structure, limit.
    trace: Trace,
    /// The request's options, as given.
    options: Options,
    /// Notes on ignored options.
    notes: Vec<String>,
}

/// The trace a `trace` or `narrate` request asks for, and the notes on ignored options.
fn trace_of(f: &Fields<'_>, op: &str) -> Result<TraceAsked, Failure> {
    let options = ask::options(f.get("options"))?;
    no_size(&options, op)?;
    let target = ask::target(f.get("target"))?;
    let scene = scene(f)?;
    let chosen = options.sampling.choose(Aa::Center)?;
    let trace = Trace {
        target,
        depth: options.depth,
        sampling: chosen.sampling,
        accel: options.accel.clone(),
        max_events: options.max_events.unwrap_or(DEFAULT_LIMIT),
    };
    let notes = chosen.notes.into_iter().chain(trace.check(&scene)?).collect();
    Ok(TraceAsked { scene, trace, options, notes })
}

fn trace_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let TraceAsked { scene, trace, .. } = trace_of(f, "trace")?;
    Ok(Answer::ok(document_text(&trace.document(&scene)?)?))
}

fn narrate_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let lang = ask::lang(f.get("lang"))?;
    let TraceAsked { scene, trace, options, notes } = trace_of(f, "narrate")?;
    let narrated = trace.narration(&scene, lang)?;
    let steps: Vec<Value> = narrated
        .narration
        .steps()
        .into_iter()
        .map(|s| json!({"step": s.number, "text": s.text, "events": s.events, "place": s.place}))
        .collect();
    let mut answer = json!({
        "command": command(name(f)?, &trace.target, &options, lang),
        "steps": steps,
        "notes": notes,
        "stats": whitted::doc::stats(&narrated.stats),
    });
    traced(&mut answer, &narrated.target);
    Ok(Answer::ok(answer.to_string()))
}

/// Adds the document's `pixel` and `uv` to an answer.
fn traced(answer: &mut Value, target: &TraceTarget) {
    answer["pixel"] = target.pixel.as_ref().map_or(Value::Null, |p| json!(p));
    answer["uv"] = target.uv.as_ref().map_or(Value::Null, |uv| json!(uv));
}

/// The `whitted trace` command that gives the same narration.
fn command(scene: &str, target: &Target, options: &Options, lang: Lang) -> String {
    let nums = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    let mut cmd = format!("whitted trace {scene}");
    match (&target.pixel, &target.ray) {
        (Some((i, Some(j))), _) => cmd.push_str(&format!(" --pixel {i},{j}")),
        (Some((i, None)), _) => cmd.push_str(&format!(" --pixel {i}")),
        (None, Some((o, d))) => cmd.push_str(&format!(" --ray={}:{}", nums(o), nums(d))),
        (None, None) => {}
    }
    if let Some(d) = options.depth {
        cmd.push_str(&format!(" --depth {d}"));
    }
    let s = &options.sampling;
    if let Some(aa) = s.aa {
        cmd.push_str(&format!(" --aa {}", aa.name()));
    }
    if let Some(t) = s.threshold {
        cmd.push_str(&format!(" --threshold {t}"));
    }
    if let Some(k) = s.max_level {
        cmd.push_str(&format!(" --max-level {k}"));
    }
    let a = &options.accel;
    let default = whitted::request::options::AccelChoice::default();
    if a.kind != default.kind {
        cmd.push_str(&format!(" --accel {}", a.kind.name()));
    }
    if let Some(volume) = a.volume {
        cmd.push_str(&format!(" --bounds {}", volume.name()));
    }
    if let Some(g) = &a.grid {
        cmd.push_str(&format!(" --grid {}", g.iter().map(ToString::to_string).collect::<Vec<_>>().join(",")));
    }
    if let Some(n) = options.max_events {
        cmd.push_str(&format!(" --max-events {n}"));
    }
    if lang == Lang::Ro {
        cmd.push_str(" --lang ro");
    }
    cmd
}

fn figure_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let lang = ask::lang(f.get("lang"))?;
    let kind = ask::kind(f.get("kind"))?;
    let options = ask::options(f.get("options"))?;
    let target = ask::target(f.get("target"))?;
    let scene = scene(f)?;
    if kind == FigureKind::HeatMap {
        let (w, h) = match &scene {
            AnyScene::Flat(s) => image_size(s, None),
            AnyScene::Space(s) => image_size(s, None),
        };
        fits("heat-map", w, h)?;
    }
    let chosen = options.sampling.choose(default_aa(kind))?;
    let (width, height) = canvas(options.size)?;
    let request = Request {
        kind,
        target,
        tracing: TraceOptions {
            depth: options.depth,
            sampling: chosen.sampling,
            accel: options.accel.options(dim(&scene))?,
        },
        opts: whitted::figure::Options { lang, width, height },
    };
    let made = figure(&scene, &stem(name(f)?), &request)?;
    let notes: Vec<String> =
        chosen.notes.into_iter().chain(options.accel.notes(structure(kind, options.accel.kind))).collect();
    let mut answer = json!({"svg": svg::to_svg(&made.drawing), "pick": made.pick, "notes": notes});
    traced(&mut answer, &made.traced);
    Ok(Answer::ok(answer.to_string()))
}

fn kinds() -> Answer {
    let kinds: Vec<Value> =
        FigureKind::ALL.iter().map(|k| json!({"name": k.name(), "about": k.description()})).collect();
    Answer::ok(json!({ "kinds": kinds }).to_string())
}
