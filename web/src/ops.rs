//! The requests (`web/README.md`): `check`, `info`, `render`, `trace`, `narrate`, `figure`,
//! `kinds`, `grade`, `exercise`. Each reads its fields, calls the library function the command line calls
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
use whitted::grade::exercise;
use whitted::record::DEFAULT_LIMIT;
use whitted::request::figure::{default_aa, figure, structure, Request};
use whitted::request::grade::{grade, page_step};
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
const FIELDS: [&str; 14] = [
    "op",
    "scene",
    "objs",
    "name",
    "options",
    "target",
    "lang",
    "kind",
    "rows",
    "columns",
    "student",
    "tolerance",
    "step",
    "answer",
];

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
        "grade" => grade_op(&f),
        "exercise" => exercise_op(&f),
        other => Err(Failure::input(format!(
            "request.op: unknown `{other}`; the ops are: check, info, render, trace, narrate, figure, kinds, grade, exercise"
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
    for field in BAND_FIELDS {
        if let Some(span) = f.get(field) {
            return band_op(&options, scene(f)?, (field, ask::span(span, field)?), chosen.sampling);
        }
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

/// The fields that ask a render for a band: `rows` of a 3D image, `columns` of a 2D scene's
/// line.
const BAND_FIELDS: [&str; 2] = ["rows", "columns"];

/// A render's band, for a page that shows the render's progress: file rows `[first, first +
/// count)` of a 3D image (the top row 0), or pixels `[first, first + count)` of a 2D scene's line
/// (`columns`), in any sampling mode; the same colours and counts as those pixels of the whole
/// render (`render::band`).
fn band_op(
    options: &ask::Options,
    scene: AnyScene,
    band: (&str, (usize, usize)),
    sampling: Sampling,
) -> Result<Answer, Failure> {
    match scene {
        AnyScene::Flat(mut s) => band_of(&mut s, options, band, sampling),
        AnyScene::Space(mut s) => band_of(&mut s, options, band, sampling),
    }
}

fn band_of<V: Dim>(
    s: &mut Scene<V>,
    options: &ask::Options,
    (field, (first, count)): (&str, (usize, usize)),
    sampling: Sampling,
) -> Result<Answer, Failure> {
    let flat = V::DIM == 2;
    let wanted = if flat { "columns" } else { "rows" };
    if field != wanted {
        return Err(Failure::input(format!(
            "request.{field}: a {}D scene renders in bands of {wanted}; ask for `{wanted}`",
            V::DIM
        )));
    }
    let strip = resize(s, options.size);
    let (w, h) = image_size(s, strip);
    fits("render", w, h)?;
    let len = if flat { w } else { h };
    if first >= len {
        return Err(Failure::input(format!(
            "request.{field}: the image has {len} {field}, got first {first}"
        )));
    }
    let accel = whitted::accel::Accel::build_for_render(s, &options.accel.options(V::DIM)?);
    // File row f is image row j = Ny − 1 − f: the band's rows from the bottom.
    let range = if flat {
        first..first.saturating_add(count)
    } else {
        let top = h - first;
        top.saturating_sub(count)..top
    };
    let depth = options.depth.unwrap_or(s.max_depth);
    let (band, stats) = whitted::render::band(s, &accel, (sampling, depth), range);
    let mut doc = whitted::doc::stats(&stats);
    doc[field] = json!([first, if flat { band.width } else { band.height }]);
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

/// The name a student's document goes by in its errors (`student.json: PATH: PROBLEM`).
pub const STUDENT_NAME: &str = "student.json";

/// `tolerance`: a number in (0, 1), the grader's default when absent.
fn tolerance(f: &Fields<'_>) -> Result<f64, Failure> {
    let tol = match f.get("tolerance") {
        None => return Ok(whitted::grade::DEFAULT_TOLERANCE),
        Some(Value::Number(n)) => n.as_f64().unwrap_or(f64::NAN),
        Some(other) => {
            return Err(Failure::input(format!("request.tolerance: expected a number, got `{other}`")))
        }
    };
    whitted::grade::tolerance_problem(tol).map_or(Ok(tol), |problem| Err(Failure::input(problem)))
}

/// `whitted grade --json` of the student's document (`student`, its text) against the scene,
/// through the library function the command line calls (`request::grade::grade`), plus `text`,
/// the report as `whitted grade --lang LANG` prints it, `words`, the divergence in the page's
/// words, and `page_step`, the step of this page's narration (traced with `options`) that
/// computes it. A divergence is an answer (code 0, `ok: false`); a bad document answers its
/// errors, each with its JSON path (code 2).
fn grade_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let lang = ask::lang(f.get("lang"))?;
    let options = ask::options(f.get("options"))?;
    let tol = tolerance(f)?;
    let student = f.string("request", "student")?;
    let scene = scene(f)?;
    let graded = grade(&scene, STUDENT_NAME, student, tol)?;
    let accel = options.accel.options(dim(&scene))?;
    let mut answer = whitted::grade::report::json(&graded, lang);
    answer["text"] = json!(whitted::grade::report::text(&graded, lang));
    answer["words"] = whitted::grade::report::words(&graded, lang);
    answer["page_step"] = json!(page_step(&scene, &graded, &accel, options.depth));
    Ok(Answer::ok(answer.to_string()))
}

/// Exercise mode: what step `step` of the pixel's narration (traced as `narrate` traces it)
/// computes, `asked` (its quantity, name and how many numbers; null when the step computes
/// nothing to type), and with `answer` (the typed text) each component right or wrong and how far
/// off, by the grader's rule ‖f − e‖∞ ≤ tol·max(1, ‖e‖∞). The step's values are not answered:
/// the page shows the worked step only when asked.
fn exercise_op(f: &Fields<'_>) -> Result<Answer, Failure> {
    let tol = tolerance(f)?;
    let step = match f.get("step") {
        Some(Value::Number(n)) => n.as_u64().and_then(|k| usize::try_from(k).ok()).filter(|&k| k >= 1),
        _ => None,
    }
    .ok_or_else(|| Failure::input("request.step: expected a step number (1, 2, …)"))?;
    let TraceAsked { scene, trace, .. } = trace_of(f, "exercise")?;
    let asked = trace.asked(&scene, step)?;
    let mut answer = json!({
        "step": step,
        "tolerance": tol,
        "asked": asked.as_ref().map_or(Value::Null, |a| json!({
            "quantity": a.quantity.name(), "name": a.name, "count": a.expected.len(),
        })),
    });
    if let (Some(typed), Some(a)) = (f.get("answer"), &asked) {
        let text = typed.as_str().ok_or_else(|| Failure::input("request.answer: expected the typed text"))?;
        let found = exercise::parse(text).map_err(|e| Failure::input(format!("answer: {e}")))?;
        let checked =
            exercise::check(&a.expected, &found, tol).map_err(|e| Failure::input(format!("answer: {e}")))?;
        let components: Vec<Value> = checked
            .components
            .iter()
            .map(|c| json!({"found": c.found, "right": c.right, "off": c.off}))
            .collect();
        answer["ok"] = json!(checked.ok);
        answer["components"] = Value::Array(components);
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Whitted's scene and the pixel the secondary-rays lesson's first view follows.
    const WHITTED: &str = include_str!("../../scenes/whitted.json");
    const PIXEL: [usize; 2] = [422, 292];
    /// `python3 examples/student/tracer.py scenes/whitted.json --pixel 422,292`, and with
    /// `--mistake reflect-sign` (tests/integration/web.rs checks they are the tracer's output).
    const CORRECT: &str = include_str!("../../tests/data/grade/whitted-422-292.json");
    const REFLECT_SIGN: &str = include_str!("../../tests/data/grade/whitted-422-292-reflect-sign.json");

    fn ask(request: &Value) -> (u8, Value) {
        let answer = call(request.to_string().as_bytes());
        (answer.code, serde_json::from_str(&answer.json).unwrap())
    }

    /// The view's narration (`--accel none`, as a figure without a structure narrates).
    fn exercise(step: usize, answer: Option<&str>) -> (u8, Value) {
        let mut r = json!({"op": "exercise", "scene": WHITTED, "target": {"pixel": PIXEL},
            "options": {"accel": "none"}, "step": step});
        if let Some(a) = answer {
            r["answer"] = json!(a);
        }
        ask(&r)
    }

    #[test]
    fn grade_passes_the_correct_document_and_names_the_first_divergence_in_the_pages_step() {
        let (code, ok) = ask(&json!({"op": "grade", "scene": WHITTED, "student": CORRECT}));
        assert_eq!(code, 0, "{ok}");
        assert_eq!(ok["ok"], true);
        assert_eq!(ok["pixel"], json!(PIXEL));
        assert!(ok["checked"].as_u64().unwrap() >= 70, "{ok}");
        assert!(ok["first"].is_null() && ok["words"].is_null() && ok["page_step"].is_null());
        assert!(ok["text"].as_str().unwrap().contains("Everything agrees"));
        // The mistake: R₁'s direction, step 11 of `whitted trace` (the BVH's node visit counts),
        // step 10 of the page's narration without a structure ("Reflected ray R₁ at I₁").
        let (code, bad) = ask(&json!({"op": "grade", "scene": WHITTED, "student": REFLECT_SIGN,
            "options": {"accel": "none"}, "lang": "ro"}));
        assert_eq!(code, 0, "a divergence is an answer: {bad}");
        let first = &bad["first"];
        assert_eq!(bad["ok"], false);
        assert_eq!((first["ray"].as_str(), first["quantity"].as_str()), (Some("R₁"), Some("direction")));
        assert_eq!(first["path"], json!(["reflected"]));
        assert_eq!(first["diagnosis"], "reflect-sign");
        assert_eq!(first["step"], 11);
        assert_eq!(bad["page_step"], 10);
        let words = &bad["words"];
        assert_eq!(words["chain"], "P → R₁");
        assert_eq!(words["quantity"], "direcția");
        assert!(words["diagnosis"].as_str().unwrap().contains("semnul greșit"), "{words}");
        assert!(words["expected"].as_str().unwrap().starts_with("(0.801716"), "{words}");
        assert!(words["found"].as_str().unwrap().starts_with("(−0.801716"), "{words}");
        assert!(bad["text"].as_str().unwrap().starts_with("whitted grade: pixelul (422, 292)"));
    }

    #[test]
    fn grade_lists_every_error_of_a_bad_document_with_its_json_path() {
        let doc =
            r#"{"pixel": [422, 292], "ray": {"origin": [0, 0.8, 5], "direction": "up"}, "colour": [1, 2]}"#;
        let (code, answer) = ask(&json!({"op": "grade", "scene": WHITTED, "student": doc}));
        assert_eq!(code, 2, "{answer}");
        let errors: Vec<&str> =
            answer["errors"].as_array().unwrap().iter().filter_map(Value::as_str).collect();
        assert!(errors.len() >= 2, "{errors:?}");
        assert!(errors.iter().all(|e| e.starts_with("student.json: ")), "{errors:?}");
        assert!(errors.iter().any(|e| e.contains("ray.direction")), "{errors:?}");
        assert!(errors.iter().any(|e| e.contains("colour")), "{errors:?}");
        let (code, answer) =
            ask(&json!({"op": "grade", "scene": WHITTED, "student": CORRECT, "tolerance": 2}));
        assert_eq!(code, 2);
        assert!(answer["errors"][0].as_str().unwrap().contains("--tolerance must be in (0, 1)"));
    }

    #[test]
    fn exercise_asks_what_each_step_computes() {
        let asked = |k| exercise(k, None).1["asked"].clone();
        let is = |k, quantity: &str, name: &str, count: usize| {
            assert_eq!(asked(k), json!({"quantity": quantity, "name": name, "count": count}), "step {k}");
        };
        is(1, "window_point", "(u, v)", 2);
        is(2, "direction", "D", 3);
        is(4, "t", "t", 1);
        is(7, "point", "I₁", 3);
        is(8, "local", "I_local", 3);
        is(9, "shadow", "s (L₁)", 1);
        is(10, "direction", "R₁", 3);
        is(16, "direction", "T₁", 3);
        is(77, "colour", "I", 3);
        is(78, "colour", "I (pixel)", 3);
        // A test without a root, and a light behind the surface (N·L ≤ 0), compute nothing.
        assert!(asked(5).is_null());
        assert!(asked(39).is_null());
    }

    #[test]
    fn exercise_says_which_components_are_right_and_how_far_off_the_others_are() {
        // R₁ = (0.801716, 0.511449, 0.309308) as the narration prints it: 6 digits agree.
        let (code, right) = exercise(10, Some("(0.801716, 0.511449, 0.309308)"));
        assert_eq!(code, 0, "{right}");
        assert_eq!(right["ok"], true);
        assert_eq!(right["components"].as_array().unwrap().len(), 3);
        assert!(right.get("expected").is_none(), "the value itself is not answered");
        // The sign of V mistaken in x alone, and y rounded to 3 digits: z right.
        let (_, wrong) = exercise(10, Some("−0.801716 0.511 0.309308"));
        assert_eq!(wrong["ok"], false);
        let c = &wrong["components"];
        assert_eq!(
            (c[0]["right"].as_bool(), c[1]["right"].as_bool(), c[2]["right"].as_bool()),
            (Some(false), Some(false), Some(true))
        );
        assert!((c[0]["off"].as_f64().unwrap() - 1.603432).abs() < 1e-5, "{c}");
        assert!((c[1]["off"].as_f64().unwrap() - 0.000449).abs() < 1e-5, "{c}");
        // t at step 6 (the glass): 3.56438.
        assert_eq!(exercise(6, Some("3.56438")).1["ok"], true);
        // Typing mistakes and impossible steps are refused in words.
        let (code, e) = exercise(10, Some("0.8, x, 0.3"));
        assert_eq!(code, 2);
        assert_eq!(e["errors"][0], "answer: `x` is not a number");
        let (code, e) = exercise(10, Some("0.8 0.5"));
        assert_eq!(code, 2);
        assert!(e["errors"][0].as_str().unwrap().contains("expected 3 number"), "{e}");
        assert_eq!(exercise(0, None).0, 2);
        assert!(exercise(500, None).1["asked"].is_null());
    }
}
