//! The narration of a trace: numbered steps a student can follow, each giving the lecture's
//! formula and then the numbers put into it, in English or Romanian (`whitted trace` without
//! `--json`). It reads the recorded events and tree only; it never traces anything itself.
//!
//! Rays and hits carry the figures' names (`record::names`: P, R₁, T₂, I₃, L₄), so a line of the
//! narration and an arrow of a figure say the same thing. Every numbered step names the events it
//! explains, as indices into the log's events (which are the trace document's `events`, in the
//! same order): a test step its test, a hit step its hit, a ray's title the event that spawned
//! the ray (`primary_ray`, `reflect`, `refract`), a light its shadow ray and that ray's tests, a
//! colour the hit and the rays it sums ([`Narration`]); and where it stands in the ray tree
//! (`P → T₁ → R₂ @ glass, level 3`, [`Step::place`]).
//!
//! One file per family of steps: `ray` (a ray, its tests and its hit), `optics` (R, T, total
//! internal reflection, the depth limit, the spawn offset), `light` (the local model, each light
//! and its shadow ray, the colour sum).

mod light;
mod optics;
mod ray;

use super::TraceTarget;
use crate::geom::Vector;
use crate::record::event::{Event, ObjectRef};
use crate::record::names::Names;
use crate::record::stats::Stats;
use crate::record::EventLog;
use crate::scene::camera::Projection;
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use std::fmt::Write;

use crate::format::narration_number;
pub use crate::lang::Lang;

/// An angle given by its cosine, in degrees with two decimals: `acos(c)` as `30.00°` (c clamped
/// to [−1, 1], which rounding may leave by an ulp).
fn degrees(cos: f64) -> String {
    format!("{:.2}°", cos.clamp(-1.0, 1.0).acos().to_degrees())
}

/// A number as the right operand of a subtraction: negative values in parentheses.
fn paren(x: f64) -> String {
    if x < 0.0 {
        format!("({})", narration_number(x))
    } else {
        narration_number(x)
    }
}

fn vec_str<V: Vector>(v: V) -> String {
    let parts: Vec<String> = v.to_vec().into_iter().map(narration_number).collect();
    format!("({})", parts.join(", "))
}

fn rgb(c: Rgb) -> String {
    format!("({}, {}, {})", narration_number(c.0[0]), narration_number(c.0[1]), narration_number(c.0[2]))
}

/// A narration and, for each of its numbered steps in order, the indices of the events it
/// explains and where it stands.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Narration {
    /// The text `whitted trace` prints.
    pub text: String,
    /// Per numbered step (step k at `k − 1`), the indices into the log's (the document's) events.
    pub events: Vec<Vec<usize>>,
    /// Per numbered step, where it stands: the rays from P down to the ray it explains, the object
    /// that ray hits and its level (`P → T₁ → R₂ @ glass, level 3`), or the pixel for the steps
    /// that come before P or after its colour; empty where there is no ray tree (samples).
    pub places: Vec<String>,
}

/// One numbered step of a narration.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Step {
    /// Its number, from 1.
    pub number: usize,
    /// Its text as [`steps`] cuts it from the narration.
    pub text: String,
    /// The indices of the events it explains.
    pub events: Vec<usize>,
    /// Where it stands in the ray tree ([`Narration::places`]).
    pub place: String,
}

impl Narration {
    /// The numbered steps: [`steps`] of the text, each with its events and place.
    #[must_use]
    pub fn steps(&self) -> Vec<Step> {
        steps(&self.text)
            .into_iter()
            .enumerate()
            .map(|(k, text)| Step {
                number: k + 1,
                text,
                events: self.events.get(k).cloned().unwrap_or_default(),
                place: self.places.get(k).cloned().unwrap_or_default(),
            })
            .collect()
    }
}

/// An event of the log with its index.
type Indexed<'a, V> = (usize, &'a Event<V>);

struct Writer<'a, V: Dim> {
    scene: &'a Scene<V>,
    log: &'a EventLog<V>,
    lang: Lang,
    out: String,
    step: usize,
    /// The events of each step written so far.
    events: Vec<Vec<usize>>,
    /// The place of each step written so far.
    places: Vec<String>,
    /// The ray node the steps being written explain (None: the pixel's steps).
    at: Option<usize>,
    /// The place of the steps outside the ray tree: the pixel, or the ray given by hand.
    outside: String,
    max_depth: u32,
    /// The figures' names of the rays and hits.
    names: Names,
    /// The tests of each shadow ray of the node being told: (light, tests).
    shadow_tests: Vec<(usize, Vec<Indexed<'a, V>>)>,
}

impl<'a, V: Dim> Writer<'a, V> {
    fn t(&self, en: &'static str, ro: &'static str) -> &'static str {
        match self.lang {
            Lang::En => en,
            Lang::Ro => ro,
        }
    }

    /// A numbered step: its title, then indented lines; it explains `events`.
    fn step(&mut self, indent: usize, title: &str, lines: &[String], events: Vec<usize>) {
        self.step += 1;
        self.events.push(events);
        let place = self.place();
        self.places.push(place);
        let pad = "   ".repeat(indent);
        let _ = writeln!(self.out, "{pad}{}. {title}", self.step);
        for l in lines {
            let _ = writeln!(self.out, "{pad}     {l}");
        }
    }

    /// Where the current step stands: `P → T₁ → R₂ @ glass, level 3`.
    fn place(&self) -> String {
        let Some(node) = self.at else { return self.outside.clone() };
        let ray = &self.log.nodes[node];
        let what = match ray.end.as_ref().and_then(|e| e.hit) {
            Some(hit) => self.scene.object_label(hit.object.index, self.lang),
            None => self.t("background", "fundal").to_owned(),
        };
        format!("{} @ {what}, {} {}", self.names.path_text(node), self.t("level", "nivelul"), ray.start.level)
    }

    /// A shape's kind as the narration's language names it (Romanian with its article, as in
    /// "sfera 2").
    fn kind_word(&self, kind: &'static str) -> &'static str {
        if self.lang == Lang::En {
            return kind;
        }
        match kind {
            "circle" => "cercul",
            "sphere" => "sfera",
            "line" => "dreapta",
            "plane" => "planul",
            "rectangle" => "dreptunghiul",
            "box" => "paralelipipedul",
            "triangle" => "triunghiul",
            "polygon" => "poligonul",
            "segment" => "segmentul",
            "mesh" => "rețeaua poligonală",
            other => other,
        }
    }

    fn object(&self, o: ObjectRef) -> String {
        let obj = &self.scene.objects[o.index];
        let kind = self.kind_word(obj.shape.kind());
        let base = match &obj.name {
            // Quoted as each language quotes: “mirror” in English, „oglindă” in Romanian.
            Some(n) => {
                let (open, close) = match self.lang {
                    Lang::En => ('“', '”'),
                    Lang::Ro => ('„', '”'),
                };
                format!("{open}{}{close} ({kind} {})", n.get(self.lang), o.index)
            }
            None => format!("{kind} {}", o.index),
        };
        match o.triangle {
            Some(t) => format!("{base}, {} {t}", self.t("triangle", "triunghiul")),
            None => base,
        }
    }

    fn events_of(&self, node: usize) -> Vec<Indexed<'a, V>> {
        let log = self.log;
        log.events
            .iter()
            .enumerate()
            .filter(|(_, e)| e.ray == Some(node))
            .map(|(k, e)| (k, &e.event))
            .collect()
    }
}

/// The numbered narration of a traced primary ray: its text, and each step's events and place.
#[must_use]
pub fn narration<V: Dim>(
    scene: &Scene<V>,
    log: &EventLog<V>,
    stats: &Stats,
    target: &TraceTarget,
    max_depth: u32,
    lang: Lang,
) -> Narration {
    let outside = match (&target.pixel, lang) {
        (Some(p), Lang::En) => format!("pixel ({})", join(p)),
        (Some(p), Lang::Ro) => format!("pixelul ({})", join(p)),
        (None, Lang::En) => "the ray given".to_owned(),
        (None, Lang::Ro) => "raza dată".to_owned(),
    };
    let mut w = Writer {
        scene,
        log,
        lang,
        out: String::new(),
        step: 0,
        events: Vec::new(),
        places: Vec::new(),
        at: None,
        outside,
        max_depth,
        names: Names::of(log),
        shadow_tests: Vec::new(),
    };
    let root = log.roots().next();
    // The root's primary ray and its hit or miss: what the pixel's steps and its colour explain.
    let root_events: Vec<usize> = root.map_or_else(Vec::new, |r| {
        w.events_of(r)
            .into_iter()
            .filter(|(_, e)| matches!(e, Event::PrimaryRay { .. } | Event::Hit { .. } | Event::Miss { .. }))
            .map(|(k, _)| k)
            .collect()
    });
    let primary: Vec<usize> = root_events.first().copied().into_iter().collect();
    if let (Some(pixel), Some(uv)) = (&target.pixel, &target.uv) {
        pixel_steps(&mut w, pixel, uv, primary);
    }
    if let Some(root) = root {
        w.node(root, 0, None);
        w.at = None;
        if let Some(end) = &log.nodes[root].end {
            let title = w.t(
                "Pixel colour (linear RGB, clamped only when written)",
                "Culoarea pixelului (RGB liniar, limitată doar la scriere)",
            );
            let bytes = end.color.0.map(crate::image::to_byte);
            w.step(0, title, &[format!("{} → 8 bit {:?}", rgb(end.color), bytes)], root_events.clone());
        }
    }
    w.out.push_str(&rays_line(stats, lang));
    Narration { text: w.out, events: w.events, places: w.places }
}

/// The closing line: how many rays of each kind and how many object tests. Romanian agrees the
/// noun with the number as the lecture does ("1 rază primară", "4 raze", "20 de raze").
#[must_use]
pub fn rays_line(stats: &Stats, lang: Lang) -> String {
    let r = stats.rays;
    let tests = stats.tests.object;
    match lang {
        Lang::En => format!(
            "Rays: {} primary, {} reflected, {} transmitted, {} shadow; {tests} object tests\n",
            r.primary, r.reflected, r.transmitted, r.shadow
        ),
        Lang::Ro => format!(
            "Raze: {}, {}, {}, {}; {}\n",
            count_ro(r.primary, "rază primară", "raze primare"),
            count_ro(r.reflected, "rază reflectată", "raze reflectate"),
            count_ro(r.transmitted, "rază transmisă", "raze transmise"),
            count_ro(r.shadow, "rază de umbră", "raze de umbră"),
            count_ro(tests, "test de intersecție", "teste de intersecție")
        ),
    }
}

/// `n` and a Romanian noun phrase agreed with it: the singular for 1, "de" before the plural
/// when the number's last two digits are 00 or 20–99 (n ≥ 20), the plural alone otherwise.
fn count_ro(n: u64, one: &str, many: &str) -> String {
    match n {
        1 => format!("1 {one}"),
        n if n >= 20 && (n % 100 == 0 || n % 100 >= 20) => format!("{n} de {many}"),
        n => format!("{n} {many}"),
    }
}

fn join(p: &[usize]) -> String {
    p.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
}

/// The pixel's two steps: its (u, v) on the window, then the primary ray through S.
fn pixel_steps<V: Dim>(w: &mut Writer<'_, V>, pixel: &[usize], uv: &[f64], primary: Vec<usize>) {
    let cam = &w.scene.camera;
    let win = &cam.window;
    let mut lines = vec![format!(
        "u = l + (r − l)·(i + 0.5)/Nx = {} + ({} − {})·({} + 0.5)/{} = {}",
        narration_number(win.l),
        narration_number(win.r),
        paren(win.l),
        pixel[0],
        cam.nx,
        narration_number(uv[0])
    )];
    if V::DIM == 3 {
        lines.push(format!(
            "v = b + (t − b)·(j + 0.5)/Ny = {} + ({} − {})·({} + 0.5)/{} = {}",
            narration_number(win.b),
            narration_number(win.t),
            paren(win.b),
            pixel[1],
            cam.ny,
            narration_number(uv[1])
        ));
    }
    let title = if V::DIM == 3 {
        format!(
            "{} (i, j) = ({}, {}) {}",
            w.t("Pixel", "Pixelul"),
            pixel[0],
            pixel[1],
            w.t("— column from the left, row from the bottom", "— coloana de la stânga, rândul de jos")
        )
    } else {
        format!("{} i = {}", w.t("Pixel", "Pixelul"), pixel[0])
    };
    w.step(0, &title, &lines, primary.clone());
    let s = cam.window_point(uv[0], uv.get(1).copied().unwrap_or(0.0));
    let lines = match cam.projection {
        Projection::Perspective => vec![
            format!("S = O + u·u + v·v − p·w = {}", vec_str(s)),
            format!(
                "{} O = {}, D = (S − O)/|S − O|",
                w.t("perspective: from the observer", "perspectivă: din observator"),
                vec_str(cam.eye)
            ),
        ],
        Projection::Orthographic => vec![
            format!("S = O + u·u + v·v − p·w = {}", vec_str(s)),
            w.t("orthographic: from S along D = −w", "ortografică: din S pe direcția D = −w").to_string(),
        ],
    };
    w.step(
        0,
        w.t("Primary ray P through the window point S", "Raza primară P prin punctul S al ferestrei"),
        &lines,
        primary,
    );
}

/// A narration cut into its numbered steps: each from its `k. title` line (k = 1, 2, … in turn,
/// indented by a multiple of 3 spaces, one level of nesting each) up to the next, its detail lines
/// (indented 5 more) included, without the final newline.
#[must_use]
pub fn steps(narration: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for line in narration.lines() {
        let next = format!("{}. ", out.len() + 1);
        let body = line.trim_start_matches(' ');
        let indent = line.len() - body.len();
        if (body.starts_with(&next) && indent % 3 == 0) || out.is_empty() {
            out.push(line.to_owned());
        } else if let Some(last) = out.last_mut() {
            last.push('\n');
            last.push_str(line);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_narration_is_cut_at_its_numbered_steps_only() {
        let text = "1. Pixel\n     u = 0.5\n2. Ray\n   3. Test\n        roots t = 2. 5\n        4. not a step\n   4. Hit\n";
        assert_eq!(
            steps(text),
            vec![
                "1. Pixel\n     u = 0.5",
                "2. Ray",
                "   3. Test\n        roots t = 2. 5\n        4. not a step",
                "   4. Hit"
            ]
        );
        assert!(steps("").is_empty());
    }

    #[test]
    fn romanian_counts_agree_with_their_number() {
        let c = |n| count_ro(n, "rază primară", "raze primare");
        assert_eq!(c(0), "0 raze primare");
        assert_eq!(c(1), "1 rază primară");
        assert_eq!(c(19), "19 raze primare");
        assert_eq!(c(20), "20 de raze primare");
        assert_eq!(c(101), "101 raze primare");
        assert_eq!(c(120), "120 de raze primare");
        assert_eq!(c(200), "200 de raze primare");
    }

    #[test]
    fn angles_are_read_from_their_cosines() {
        assert_eq!(degrees(0.5), "60.00°");
        assert_eq!(degrees(1.0 + f64::EPSILON), "0.00°");
        assert_eq!(degrees(0.0), "90.00°");
    }
}
