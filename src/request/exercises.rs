//! `whitted exercises`: an exercise sheet and its answers from one pixel's trace (issue 31 item
//! 6). The questions follow the narration's steps in the lecture's order — (u, v), the primary
//! ray, the nearest t, N and whether the ray enters, R, T or total internal reflection, the
//! shadow factor, I_local, the pixel's colour, and with `--accel grid` the next voxel of the
//! DDA — each stating the numbers it needs, read from the recorded trace; the answer to each is the narration's own step, worked as `whitted trace` works
//! it. Both pages are printable HTML with the pixel's figures inline as SVG. `--seed` picks which
//! ray a question asks about where several would do, and which questions stay when there are more
//! than [`MAX_QUESTIONS`].

use super::figure::{figure, Request};
use super::options::AccelChoice;
use super::target::Target;
use super::Failure;
use crate::accel::{Accel, AccelOptions};
use crate::canvas::svg::to_svg;
use crate::doc::narrate::{narration, Step};
use crate::doc::TraceTarget;
use crate::figure::source::TraceOptions;
use crate::figure::{FigureKind, Options};
use crate::format::{html_escape, narration_number};
use crate::geom::Vector;
use crate::lang::Lang;
use crate::record::event::Event;
use crate::record::names::Names;
use crate::record::EventLog;
use crate::scene::{AnyScene, Scene};
use crate::shape::Dim;
use crate::trace::Tracer;

/// The fewest questions a sheet holds (fewer only when the trace has fewer kinds of steps: a miss).
pub const MIN_QUESTIONS: usize = 6;
/// The most questions a sheet holds.
pub const MAX_QUESTIONS: usize = 10;

/// The two pages.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Sheets {
    /// `exercises.html`.
    pub exercises: String,
    /// `answers.html`.
    pub answers: String,
    /// How many questions.
    pub count: usize,
}

/// One question: its statement and the steps of the narration that answer it.
struct Question {
    statement: String,
    answer: Vec<Step>,
    /// Kept when a sheet has too many questions (what only this structure asks).
    keep: bool,
}

/// A small deterministic generator for `--seed` (xorshift64*).
struct Seeded(u64);

impl Seeded {
    fn next(&mut self) -> u64 {
        let mut x = self.0.max(1);
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn pick<T: Copy>(&mut self, items: &[T]) -> Option<T> {
        if items.is_empty() {
            return None;
        }
        let k = usize::try_from(self.next() % items.len() as u64).unwrap_or(0);
        Some(items[k])
    }
}

fn t(lang: Lang, en: &'static str, ro: &'static str) -> &'static str {
    match lang {
        Lang::En => en,
        Lang::Ro => ro,
    }
}

fn vec_text<V: Vector>(v: V) -> String {
    let parts: Vec<String> = v.to_vec().into_iter().map(narration_number).collect();
    format!("({})", parts.join(", "))
}

/// The sheets of pixel `pixel` of `scene` (called `name` on the pages).
///
/// # Errors
/// Bad input: the pixel outside the image; a figure that cannot be drawn.
pub fn sheets(
    scene: &AnyScene,
    name: &str,
    pixel: (i64, Option<i64>),
    lang: Lang,
    seed: u64,
    accel: &AccelChoice,
) -> Result<Sheets, Failure> {
    let target = Target { pixel: Some(pixel), ray: None };
    let questions = match scene {
        AnyScene::Flat(s) => questions(s, &target, lang, seed, &accel.options(2)?)?,
        AnyScene::Space(s) => questions(s, &target, lang, seed, &accel.options(3)?)?,
    };
    let mut figures = Vec::new();
    for kind in [FigureKind::Rays, FigureKind::RayTree] {
        let request = Request {
            kind,
            target: target.clone(),
            tracing: TraceOptions::SCENE,
            // Laid out as on a slide (the figures' reference size); the page scales the SVG down.
            opts: Options::slide(lang),
        };
        figures.push(to_svg(&figure(scene, name, &request)?.drawing));
    }
    let at = match pixel {
        (i, Some(j)) => format!("({i}, {j})"),
        (i, None) => format!("({i})"),
    };
    let heading = format!("{} — {} {at}", html_escape(name), t(lang, "pixel", "pixelul"));
    let mut ex = page(lang, &format!("{} {heading}", t(lang, "Exercises:", "Exerciții:")));
    let mut ans = page(lang, &format!("{} {heading}", t(lang, "Answers:", "Răspunsuri:")));
    ex.push_str(&format!(
        "<p>{}</p>\n<figure>{}</figure>\n<ol>\n",
        t(
            lang,
            "Work each question by hand with the lecture's formulas; the numbers you need are given. The answers are in answers.html.",
            "Rezolvați fiecare întrebare de mână cu formulele din curs; numerele necesare sunt date. Răspunsurile sunt în answers.html."
        ),
        figures[0]
    ));
    ans.push_str(&format!("<figure>{}</figure>\n<ol>\n", figures[1]));
    for q in &questions {
        ex.push_str(&format!("<li><p>{}</p><div class=\"space\"></div></li>\n", html_escape(&q.statement)));
        ans.push_str(&format!("<li><p>{}</p>", html_escape(&q.statement)));
        for step in &q.answer {
            ans.push_str(&format!(
                "<p class=\"place\">{} {} — {}</p><pre>{}</pre>",
                t(lang, "Step", "Pasul"),
                step.number,
                html_escape(&step.place),
                html_escape(step.text.trim_end())
            ));
        }
        ans.push_str("</li>\n");
    }
    for p in [&mut ex, &mut ans] {
        p.push_str("</ol>\n</body>\n</html>\n");
    }
    Ok(Sheets { exercises: ex, answers: ans, count: questions.len() })
}

/// The head of a printable page.
fn page(lang: Lang, title: &str) -> String {
    let code = match lang {
        Lang::En => "en",
        Lang::Ro => "ro",
    };
    format!(
        "<!DOCTYPE html>\n<html lang=\"{code}\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n<style>\n\
         body {{ font-family: sans-serif; max-width: 48em; margin: 2em auto; line-height: 1.4; }}\n\
         figure {{ margin: 1em 0; }} figure svg {{ width: 100%; height: auto; }}\n\
         li {{ margin-bottom: 1.2em; break-inside: avoid; }} .space {{ height: 5em; border-bottom: 1px dotted #999; }}\n\
         pre {{ white-space: pre-wrap; background: #f5f5f5; padding: 0.6em; }} .place {{ color: #555; font-size: 0.9em; }}\n\
         @media print {{ body {{ margin: 0; }} }}\n</style>\n</head>\n<body>\n<h1>{title}</h1>\n"
    )
}

/// The questions of one pixel, in the narration's order.
fn questions<V: Dim>(
    scene: &Scene<V>,
    target: &Target,
    lang: Lang,
    seed: u64,
    structure: &AccelOptions,
) -> Result<Vec<Question>, Failure> {
    let (ray, traced) = target.primary(scene)?;
    let accel = Accel::build_with(scene, structure);
    let mut tracer = Tracer::new(scene, &accel, EventLog::new());
    let uv = traced.uv.clone().unwrap_or_default();
    tracer.trace_primary(&ray, &uv);
    let log = tracer.recorder;
    let told = narration(
        scene,
        &log,
        &tracer.stats,
        &TraceTarget { pixel: traced.pixel.clone(), uv: traced.uv.clone() },
        scene.max_depth,
        lang,
    );
    let steps = told.steps();
    let names = Names::of(&log);
    let mut rng = Seeded(seed ^ 0x9E37_79B9_7F4A_7C15);
    // The first step that tells event `e`, and the last.
    let first = |e: usize| steps.iter().find(|s| s.events.contains(&e));
    let last = |e: usize| steps.iter().rev().find(|s| s.events.contains(&e));
    let of_kind = |test: &dyn Fn(&Event<V>) -> bool| -> Vec<usize> {
        (0..log.events.len()).filter(|&k| test(&log.events[k].event)).collect()
    };
    let cam = &scene.camera;
    let pixel = traced.pixel.clone().unwrap_or_default();
    let mut out: Vec<Question> = Vec::new();
    let mut ask = |statement: String, step: Option<&Step>| {
        if let Some(step) = step {
            out.push(Question { statement, answer: vec![step.clone()], keep: false });
        }
    };
    // (u, v) and the primary ray: the pixel's two steps.
    let win = &cam.window;
    let uv_q = if V::DIM == 3 {
        format!(
            "{} (i, j) = ({}, {}), Nx × Ny = {} × {}, l = {}, r = {}, b = {}, t = {}: {}",
            t(lang, "Pixel", "Pixelul"),
            pixel[0],
            pixel.get(1).copied().unwrap_or(0),
            cam.nx,
            cam.ny,
            narration_number(win.l),
            narration_number(win.r),
            narration_number(win.b),
            narration_number(win.t),
            t(
                lang,
                "compute (u, v) of its centre on the view window.",
                "calculați (u, v) ale centrului său pe fereastra vizuală."
            )
        )
    } else {
        format!(
            "{} i = {}, Nx = {}, l = {}, r = {}: {}",
            t(lang, "Pixel", "Pixelul"),
            pixel[0],
            cam.nx,
            narration_number(win.l),
            narration_number(win.r),
            t(
                lang,
                "compute u of its centre on the view window.",
                "calculați u al centrului său pe fereastra vizuală."
            )
        )
    };
    ask(uv_q, steps.first());
    let primary = of_kind(&|e| matches!(e, Event::PrimaryRay { .. }));
    let frame = if V::DIM == 3 {
        format!("u = {}, v = {}, w = {}", vec_text(cam.frame.u), vec_text(cam.frame.v), vec_text(cam.frame.w))
    } else {
        format!("u = {}, w = {}", vec_text(cam.frame.u), vec_text(cam.frame.w))
    };
    let pq = format!(
        "{} O = {}, {frame}, p = {}, {} = ({}): {}",
        t(lang, "Observer", "Observatorul"),
        vec_text(cam.eye),
        narration_number(cam.p),
        if V::DIM == 3 { "(u, v)" } else { "u" },
        uv.iter().map(|x| narration_number(*x)).collect::<Vec<_>>().join(", "),
        t(
            lang,
            "compute the window point S and the primary ray P (origin, unit direction).",
            "calculați punctul S al ferestrei și raza primară P (origine, direcție unitară)."
        )
    );
    ask(pq, primary.first().and_then(|&e| steps.iter().filter(|s| s.events.contains(&e)).nth(1)));
    // The nearest hit of one ray (P, or another by the seed), and N with entering at one hit.
    let hits = of_kind(&|e| matches!(e, Event::Hit { .. }));
    if let Some(h) = hits.first().copied() {
        let node = log.events[h].ray.unwrap_or(0);
        let start = &log.nodes[node].start;
        let objects: Vec<String> = (0..scene.objects.len()).map(|k| scene.object_label(k, lang)).collect();
        ask(
            format!(
                "{} {}: O = {}, D = {}. {} {}. {}",
                t(lang, "The ray", "Raza"),
                names.ray_text(node),
                vec_text(start.origin),
                vec_text(start.direction),
                t(lang, "Objects:", "Obiecte:"),
                objects.join(", "),
                t(
                    lang,
                    "Which object does it hit first, and at which t?",
                    "Ce obiect lovește prima dată și la ce t?"
                )
            ),
            first(h),
        );
    }
    if let Some(h) = rng.pick(&hits) {
        if let Event::Hit { point, object, .. } = &log.events[h].event {
            let node = log.events[h].ray.unwrap_or(0);
            ask(
                format!(
                    "{} {} {} {} {} I = {}, D = {}: {}",
                    t(lang, "The ray", "Raza"),
                    names.ray_text(node),
                    t(lang, "hits", "lovește"),
                    scene.object_label(object.index, lang),
                    t(lang, "at", "în"),
                    vec_text(*point),
                    vec_text(log.nodes[node].start.direction),
                    t(
                        lang,
                        "compute the outward normal N, say whether the ray enters, and give N_f.",
                        "calculați normala exterioară N, spuneți dacă raza intră și dați N_f."
                    )
                ),
                first(h),
            );
        }
    }
    // R and T (or total internal reflection) at one hit each.
    for (kind_en, kind_ro, test) in [
        (
            "compute the reflected direction R.",
            "calculați direcția reflectată R.",
            (|e: &Event<V>| matches!(e, Event::Reflect { .. })) as fn(&Event<V>) -> bool,
        ),
        (
            "compute the transmitted direction T, or show that the light is totally reflected.",
            "calculați direcția transmisă T sau arătați că are loc reflexia totală internă.",
            |e: &Event<V>| matches!(e, Event::Refract { .. } | Event::TotalInternalReflection { .. }),
        ),
    ] {
        if let Some(e) = rng.pick(&of_kind(&test)) {
            let node = log.events[e].ray.unwrap_or(0);
            if let Some(Event::Hit { point, normal, .. }) = log.ended_by(node).map(|h| &log.events[h].event) {
                let material = scene.material_of(
                    log.nodes[node].end.as_ref().and_then(|x| x.hit).map_or(0, |h| h.object.index),
                );
                ask(
                    format!(
                        "{} {}, I = {}, D = {}, N = {} (ior = {}): {}",
                        t(lang, "At the hit of", "În punctul lovit de"),
                        names.ray_text(node),
                        vec_text(*point),
                        vec_text(log.nodes[node].start.direction),
                        vec_text(*normal),
                        narration_number(material.ior),
                        t(lang, kind_en, kind_ro)
                    ),
                    first(e),
                );
            }
        }
    }
    // One shadow ray's factor, the local model at that hit, and the pixel's colour.
    let shadows = of_kind(&|e| matches!(e, Event::ShadowRay { .. }));
    if let Some(e) = rng.pick(&shadows) {
        if let Event::ShadowRay { light, origin, .. } = &log.events[e].event {
            let node = log.events[e].ray.unwrap_or(0);
            ask(
                format!(
                    "{} {} {} {} {} {}: {}",
                    t(lang, "From the hit of", "Din punctul lovit de"),
                    names.ray_text(node),
                    t(lang, "at", "în"),
                    vec_text(*origin),
                    t(lang, "toward light", "spre sursa"),
                    vec_text(scene.lights[*light].position),
                    t(
                        lang,
                        "which objects lie on the shadow ray, and what is its factor s?",
                        "ce obiecte se află pe raza de umbră și cât este factorul s?"
                    )
                ),
                last(e),
            );
            let m = scene
                .material_of(log.nodes[node].end.as_ref().and_then(|x| x.hit).map_or(0, |h| h.object.index));
            ask(
                format!(
                    "{} {}: ka = ({}), kd = ({}), ks = {}, n = {}; {}",
                    t(lang, "At the hit of", "În punctul lovit de"),
                    names.ray_text(node),
                    m.ka.0.map(narration_number).join(", "),
                    m.kd.0.map(narration_number).join(", "),
                    narration_number(m.ks),
                    narration_number(m.n),
                    t(
                        lang,
                        "compute I_local with the lecture's local model.",
                        "calculați I_local cu modelul local din curs."
                    )
                ),
                first(e),
            );
        }
    }
    ask(
        t(
            lang,
            "Sum the ray tree from the leaves up, I = I_local + ks·R + kt·T: what is the pixel's colour, and its 8-bit value?",
            "Însumați arborele de raze de la frunze în sus, I = I_local + ks·R + kt·T: care este culoarea pixelului și valoarea ei pe 8 biți?",
        )
        .to_owned(),
        steps.last(),
    );
    // With a grid, the next voxel of one cell the DDA leaves (the seed picks which), after the
    // primary ray's questions.
    if let Some(q) = next_voxel(&log, &names, &steps, &mut rng, lang) {
        out.insert(2.min(out.len()), q);
    }
    // Keep at most MAX_QUESTIONS, dropping by the seed, the first two, the last and the kept ones
    // kept.
    while out.len() > MAX_QUESTIONS {
        let droppable: Vec<usize> = (2..out.len() - 1).filter(|&k| !out[k].keep).collect();
        let Some(k) = rng.pick(&droppable) else { break };
        out.remove(k);
    }
    Ok(out)
}

/// "Which voxel does the ray enter next?" for one cell of the grid's walk that another follows
/// on the same ray: the cell, D, and tMax and tDelta per axis (the next boundary of each axis);
/// answered by the cell's step (its exit t = min tMax) and the next cell's. The DDA steps along
/// the axis of the least tMax, by the sign of D on that axis (Amanatides–Woo).
fn next_voxel<V: Dim>(
    log: &EventLog<V>,
    names: &Names,
    steps: &[Step],
    rng: &mut Seeded,
    lang: Lang,
) -> Option<Question> {
    let cells: Vec<usize> =
        (0..log.events.len()).filter(|&k| matches!(log.events[k].event, Event::VoxelStep { .. })).collect();
    // A cell with a next one in the same walk (nothing but the cell's tests between them: a hit
    // ends the walk, and a shadow ray's walk is another), each told by a step of its own.
    let told = |e: usize| steps.iter().find(|s| s.events.contains(&e)).cloned();
    let same_walk = |a: usize, b: usize| {
        log.events[a].ray == log.events[b].ray
            && log.events[a + 1..b].iter().all(|l| matches!(l.event, Event::ObjectTest { .. }))
    };
    let pairs: Vec<(usize, usize)> = cells
        .windows(2)
        .filter(|w| same_walk(w[0], w[1]))
        .filter(|w| told(w[0]).zip(told(w[1])).is_some_and(|(a, b)| a.number != b.number))
        .map(|w| (w[0], w[1]))
        .collect();
    let (here, next) = rng.pick(&pairs)?;
    let Event::VoxelStep { cell, t_max, t_delta, .. } = &log.events[here].event else { return None };
    let node = log.events[here].ray?;
    let ints = |v: &[i64]| v.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ");
    let nums = |v: &[f64]| v.iter().map(|x| narration_number(*x)).collect::<Vec<_>>().join(", ");
    let statement = format!(
        "{} {} {} [{}], D = {}; tMax = ({}) {}, tDelta = ({}). {}",
        t(lang, "The ray", "Raza"),
        names.ray_text(node),
        t(lang, "walks the grid and is in voxel", "parcurge grila și se află în voxelul"),
        ints(cell),
        vec_text(log.nodes[node].start.direction),
        nums(t_max),
        t(lang, "(the t of its next boundary on each axis)", "(t-ul următoarei frontiere pe fiecare axă)"),
        nums(t_delta),
        t(
            lang,
            "At which t does it leave this voxel, and which voxel does it enter next?",
            "La ce t părăsește voxelul și în ce voxel intră apoi?"
        )
    );
    Some(Question { statement, answer: vec![told(here)?, told(next)?], keep: true })
}
