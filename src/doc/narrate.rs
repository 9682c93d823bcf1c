//! The narration of a trace: numbered steps a student can follow, each giving the lecture's
//! formula and then the numbers put into it, in English or Romanian (`whitted trace` without
//! `--json`). It reads the recorded events and tree only; it never traces anything itself.
//!
//! Every numbered step names the events it explains, as indices into the log's events (which are
//! the trace document's `events`, in the same order): a test step its test, a hit step its hit, a
//! ray's title the event that spawned the ray (`primary_ray`, `reflect`, `refract`), a light its
//! shadow ray and that ray's tests, a colour the hit and the rays it sums ([`Narration`]).

use super::TraceTarget;
use crate::geom::Vector;
use crate::record::event::{Event, LightTerm, ObjectRef};
use crate::record::{EventLog, RayNode};
use crate::scene::camera::Projection;
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use crate::trace::stats::Stats;
use std::fmt::Write;

/// The language of the narration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// English.
    En,
    /// Romanian, with diacritics.
    Ro,
}

/// A number as a person reads it: up to 6 significant digits, no `-0`.
#[must_use]
pub fn num(x: f64) -> String {
    if x == f64::INFINITY {
        return "∞".into();
    }
    if x == f64::NEG_INFINITY {
        return "−∞".into();
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    let s = if (1e-4..1e7).contains(&a) {
        // 1e-4 ≤ a < 1e7, so the exponent lies in [−4, 6] and the cast is exact.
        #[allow(clippy::cast_possible_truncation)]
        let exponent = a.log10().floor() as i64;
        let decimals = usize::try_from((5 - exponent).clamp(0, 12)).unwrap_or(0);
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{x:.5e}")
    };
    if s == "-0" {
        "0".into()
    } else {
        s.replace('-', "−")
    }
}

/// A number as the right operand of a subtraction: negative values in parentheses.
fn paren(x: f64) -> String {
    if x < 0.0 {
        format!("({})", num(x))
    } else {
        num(x)
    }
}

fn vec_str<V: Vector>(v: V) -> String {
    let parts: Vec<String> = v.to_vec().into_iter().map(num).collect();
    format!("({})", parts.join(", "))
}

fn rgb(c: Rgb) -> String {
    format!("({}, {}, {})", num(c.0[0]), num(c.0[1]), num(c.0[2]))
}

/// A narration and, for each of its numbered steps in order, the indices of the events it
/// explains.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Narration {
    /// The text `whitted trace` prints.
    pub text: String,
    /// Per numbered step (step k at `k − 1`), the indices into the log's (the document's) events.
    pub events: Vec<Vec<usize>>,
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
}

impl Narration {
    /// The numbered steps: [`steps`] of the text, each with its events.
    #[must_use]
    pub fn steps(&self) -> Vec<Step> {
        steps(&self.text)
            .into_iter()
            .enumerate()
            .map(|(k, text)| Step {
                number: k + 1,
                text,
                events: self.events.get(k).cloned().unwrap_or_default(),
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
    max_depth: u32,
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
        let pad = "   ".repeat(indent);
        let _ = writeln!(self.out, "{pad}{}. {title}", self.step);
        for l in lines {
            let _ = writeln!(self.out, "{pad}     {l}");
        }
    }

    fn object(&self, o: ObjectRef) -> String {
        let obj = &self.scene.objects[o.index];
        let base = match &obj.name {
            Some(n) => format!("“{n}” ({} {})", obj.shape.kind(), o.index),
            None => format!("{} {}", obj.shape.kind(), o.index),
        };
        match o.triangle {
            Some(t) => format!("{base}, {} {t}", self.t("triangle", "triunghiul")),
            None => base,
        }
    }

    fn kind_name(&self, node: &RayNode<V>) -> &'static str {
        use crate::record::event::RayKind::{Primary, Reflected, Transmitted};
        match node.start.kind {
            Primary => self.t("primary ray", "raza primară"),
            Reflected => self.t("reflected ray R", "raza reflectată R"),
            Transmitted => self.t("transmitted ray T", "raza transmisă T"),
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

    /// One intersection test as a line: its roots and what was taken.
    fn test_line(&self, e: &Event<V>) -> String {
        match e {
            Event::ObjectTest { roots, accepted, .. } => {
                let roots_s = if roots.is_empty() {
                    self.t("no real root: the ray misses", "nicio rădăcină reală: raza ratează").to_string()
                } else {
                    let r: Vec<String> = roots.iter().map(|x| num(*x)).collect();
                    format!("{} t = {}", self.t("roots", "rădăcini"), r.join(", "))
                };
                let acc = match accepted {
                    Some(t) => format!(
                        "→ {} t = {}",
                        self.t("accepted (least t > 0)", "acceptat (cel mai mic t > 0)"),
                        num(*t)
                    ),
                    None => self.t("→ no root with t > 0", "→ nicio rădăcină cu t > 0").to_string(),
                };
                format!("{roots_s} {acc}")
            }
            Event::BoundTest { volume, t_in, t_out, hit, .. } => format!(
                "{volume}: max tᵢ = {}, min tₑ = {} → {}",
                num(*t_in),
                num(*t_out),
                if *hit { self.t("hit", "intersectat") } else { self.t("missed", "ratat") }
            ),
            Event::NodeVisit { structure, node, .. } => format!("{structure} {node}"),
            Event::NodeSkip { structure, node, t_in, t_best } => format!(
                "{structure} {node}: tᵢ = {} > t = {} → {}",
                num(*t_in),
                num(*t_best),
                self.t("skipped", "sărit")
            ),
            Event::VoxelStep { cell, .. } => format!("{} {cell:?}", self.t("cell", "celula")),
            _ => String::new(),
        }
    }

    /// The steps of ray node `index` and its subtree; `opener` is the event that spawned the ray
    /// (its `primary_ray`, or the parent's `reflect`/`refract`).
    fn node(&mut self, index: usize, indent: usize, opener: Option<usize>) {
        let node = &self.log.nodes[index];
        let events = self.events_of(index);
        let opener = opener
            .or_else(|| events.iter().find(|(_, e)| matches!(e, Event::PrimaryRay { .. })).map(|(k, _)| *k));
        let hit_event =
            events.iter().find(|(_, e)| matches!(e, Event::Hit { .. } | Event::Miss { .. })).map(|(k, _)| *k);
        let title = format!(
            "{} — {} {} ({} {})",
            self.kind_name(node),
            self.t("level", "nivelul"),
            node.start.level,
            self.t("max_depth", "max_depth"),
            self.max_depth
        );
        let ray_line = format!(
            "r(t) = O + t·D, O = {}, D = {}",
            vec_str(node.start.origin),
            vec_str(node.start.direction)
        );
        self.step(indent, &title, &[ray_line], opener.into_iter().collect());
        let mut children = node.children.iter();
        let mut lights_done = false;
        // The events that spawned the children, for the colour step.
        let mut spawned: Vec<usize> = Vec::new();
        // Tests after the hit belong to the shadow ray that follows them.
        let mut seen_hit = false;
        let mut pending: Vec<Indexed<'a, V>> = Vec::new();
        self.shadow_tests.clear();
        for (k, e) in events {
            match e {
                Event::ObjectTest { .. } if seen_hit => pending.push((k, e)),
                Event::BoundTest { .. }
                | Event::NodeVisit { .. }
                | Event::NodeSkip { .. }
                | Event::VoxelStep { .. }
                    if seen_hit =>
                {
                    pending.push((k, e));
                }
                Event::ObjectTest { object, .. } => {
                    let title = format!(
                        "{} {}",
                        self.t("Intersection test with", "Test de intersecție cu"),
                        self.object(*object)
                    );
                    let line = self.test_line(e);
                    self.step(indent + 1, &title, &[line], vec![k]);
                }
                Event::Hit { object, t, point, normal, entering } => {
                    seen_hit = true;
                    let d = node.start.direction;
                    let dn = d.dot(*normal);
                    let side = if *entering {
                        self.t("D·N ≤ 0: the ray is entering, N_f = N", "D·N ≤ 0: raza intră, N_f = N")
                    } else {
                        self.t("D·N > 0: the ray is leaving, N_f = −N", "D·N > 0: raza iese, N_f = −N")
                    };
                    let title = format!(
                        "{} {}",
                        self.t("Nearest hit I on", "Cea mai apropiată intersecție I pe"),
                        self.object(*object)
                    );
                    let lines = vec![
                        format!("t = {}, I = r(t) = {}", num(*t), vec_str(*point)),
                        format!(
                            "N = {} ({})",
                            vec_str(*normal),
                            self.t("outward unit normal", "normala exterioară unitară")
                        ),
                        format!("D·N = {} — {side}", num(dn)),
                    ];
                    self.step(indent + 1, &title, &lines, vec![k]);
                }
                Event::Miss { color } => {
                    let title = self.t(
                        "No object is hit: the colour is the background",
                        "Niciun obiect intersectat: culoarea este fundalul",
                    );
                    self.step(indent + 1, title, &[format!("I = {}", rgb(*color))], vec![k]);
                }
                Event::ShadowRay { light, .. } => {
                    self.shadow_tests.push((*light, std::mem::take(&mut pending)));
                }
                Event::Reflect { origin, direction, offset } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    let title = self.t("Reflected ray R (ks > 0)", "Raza reflectată R (ks > 0)");
                    self.step(
                        indent + 1,
                        title,
                        &[
                            format!("R = 2(N_f·V)·N_f − V, V = −D → R = {}", vec_str(*direction)),
                            format!(
                                "{} δ = 2⁻⁴⁴·M = {} → O_R = I + δ·N_f = {}",
                                self.t("spawn offset", "deplasare"),
                                num(*offset),
                                vec_str(*origin)
                            ),
                        ],
                        vec![k],
                    );
                    spawned.push(k);
                    if let Some(&c) = children.next() {
                        self.node(c, indent + 1, Some(k));
                    }
                }
                Event::Refract { origin, direction, offset, n1, n2 } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    let title = self.t(
                        "Transmitted ray T (kt > 0), Snell: n1·sin θi = n2·sin θt",
                        "Raza transmisă T (kt > 0), Snell: n1·sin θi = n2·sin θt",
                    );
                    self.step(
                        indent + 1,
                        title,
                        &[
                            format!("n1 = {}, n2 = {}, η = n1/n2 = {}", num(*n1), num(*n2), num(n1 / n2)),
                            format!(
                                "T = η·D + (η·c − √k)·N_f, c = −D·N_f, k = (1 − η²) + (η·c)² → T = {}",
                                vec_str(*direction)
                            ),
                            format!(
                                "{} δ = {} → O_T = {}",
                                self.t("spawn offset", "deplasare"),
                                num(*offset),
                                vec_str(*origin)
                            ),
                        ],
                        vec![k],
                    );
                    spawned.push(k);
                    if let Some(&c) = children.next() {
                        self.node(c, indent + 1, Some(k));
                    }
                }
                Event::TotalInternalReflection { k: radicand, n1, n2 } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    let title = self.t(
                        "Total internal reflection: no T ray",
                        "Reflexie totală internă: nu există raza T",
                    );
                    self.step(
                        indent + 1,
                        title,
                        &[format!(
                            "n1 = {}, n2 = {}, k = (1 − η²) + (η·c)² = {} < 0 → {}",
                            num(*n1),
                            num(*n2),
                            num(*radicand),
                            self.t("the kt·T term is dropped", "termenul kt·T lipsește")
                        )],
                        vec![k],
                    );
                }
                Event::DepthLimit { level } => {
                    if !lights_done {
                        self.local_model(node, index, indent + 1, hit_event);
                        lights_done = true;
                    }
                    let title =
                        self.t("Depth limit: no secondary rays", "Limita de adâncime: fără raze secundare");
                    self.step(
                        indent + 1,
                        title,
                        &[format!("n = {level} > max_depth = {}", self.max_depth)],
                        vec![k],
                    );
                }
                Event::BoundTest { volume, t_in, t_out, hit, .. } => {
                    let title = format!(
                        "{} ({volume})",
                        self.t("Bounding-volume test", "Test cu volumul încadrator")
                    );
                    let verdict = if *hit {
                        self.t("hit", "intersectat")
                    } else {
                        self.t("missed: skipped", "ratat: obiectele sunt sărite")
                    };
                    self.step(
                        indent + 1,
                        &title,
                        &[format!("max tᵢ = {}, min tₑ = {} → {verdict}", num(*t_in), num(*t_out))],
                        vec![k],
                    );
                }
                Event::NodeVisit { structure, node, depth, t_in, t_out } => {
                    let title = format!(
                        "{} {structure} {node} ({} {depth})",
                        self.t("Visit node", "Vizitează nodul"),
                        self.t("depth", "adâncimea")
                    );
                    self.step(
                        indent + 1,
                        &title,
                        &[format!("t ∈ [{}, {}]", num(*t_in), num(*t_out))],
                        vec![k],
                    );
                }
                Event::NodeSkip { structure, node, t_in, t_best } => {
                    let title = format!("{} {structure} {node}", self.t("Skip node", "Sare peste nodul"));
                    let line = format!(
                        "tᵢ = {} > t = {}: {}",
                        num(*t_in),
                        num(*t_best),
                        self.t(
                            "its box starts beyond the nearest hit found",
                            "volumul său începe dincolo de cea mai apropiată intersecție găsită"
                        )
                    );
                    self.step(indent + 1, &title, &[line], vec![k]);
                }
                Event::VoxelStep { cell, t_max, .. } => {
                    let title = format!("{} {cell:?}", self.t("Grid cell", "Celula grilei"));
                    let t: Vec<String> = t_max.iter().map(|x| num(*x)).collect();
                    self.step(indent + 1, &title, &[format!("tMax = ({})", t.join(", "))], vec![k]);
                }
                Event::PrimaryRay { .. } | Event::Sample { .. } => {}
            }
        }
        if node.end.as_ref().is_some_and(|e| e.hit.is_some()) && !lights_done {
            self.local_model(node, index, indent + 1, hit_event);
        }
        let colour: Vec<usize> = hit_event.into_iter().chain(spawned).collect();
        self.sum(node, indent + 1, colour);
    }

    /// The local model's steps at the node's hit (event `hit`): its formula with the ambient
    /// term (the hit and every shadow ray), then one step per light.
    fn local_model(&mut self, node: &RayNode<V>, index: usize, indent: usize, hit_event: Option<usize>) {
        let Some(hit) = node.end.as_ref().and_then(|e| e.hit) else {
            return;
        };
        let material = self.scene.material_of(hit.object.index);
        let (ka, _) = material.colors_at(hit.point);
        let ambient = self.scene.ambient.modulate(ka);
        let title = self.t(
            "Local model: I_local = Ia·Ka + Σ Isrc·fat·s·lum·[kd·(N·L) + ks·(N·H)^n]",
            "Modelul local: I_local = Ia·Ka + Σ Isrc·fat·s·lum·[kd·(N·L) + ks·(N·H)^n]",
        );
        let lines = vec![format!("Ia·Ka = {} · {} = {}", rgb(self.scene.ambient), rgb(ka), rgb(ambient))];
        let shadows: Vec<Indexed<'a, V>> =
            self.events_of(index).into_iter().filter(|(_, e)| matches!(e, Event::ShadowRay { .. })).collect();
        let events = hit_event.into_iter().chain(shadows.iter().map(|(k, _)| *k)).collect();
        self.step(indent, title, &lines, events);
        for term in &node.lights {
            self.light(term, &shadows, indent + 1, material.n, hit_event);
        }
    }

    /// One light's step: its shadow ray and that ray's tests, or the hit (`hit_event`) when the
    /// light is behind the surface.
    fn light(
        &mut self,
        term: &LightTerm<V>,
        shadows: &[Indexed<'a, V>],
        indent: usize,
        n: f64,
        hit_event: Option<usize>,
    ) {
        let title = format!("{} {}", self.t("Light", "Sursa de lumină"), term.light);
        let mut lines = Vec::new();
        match term.l {
            Some(l) => lines.push(format!("L = {}, N·L = {}", vec_str(l), num(term.n_dot_l))),
            None => lines.push(
                self.t(
                    "the light sits at I: no direction, lum = 0",
                    "sursa este chiar în I: nicio direcție, lum = 0",
                )
                .to_string(),
            ),
        }
        if term.lum == 0.0 {
            lines.push(
                self.t(
                    "lum = 0 (N·L ≤ 0): the light is behind the surface, no shadow ray",
                    "lum = 0 (N·L ≤ 0): sursa este în spatele suprafeței, fără rază de umbră",
                )
                .to_string(),
            );
            self.step(indent, &title, &lines, hit_event.into_iter().collect());
            return;
        }
        lines.push(format!("lum = 1, fat = min(1, 1/(c0 + c1·d + c2·d²)) = {}", num(term.fat)));
        let mut events = Vec::new();
        for (k, e) in shadows {
            if let Event::ShadowRay { light, origin, direction, distance, occluders, s } = e {
                if *light != term.light {
                    continue;
                }
                events.push(*k);
                let mine =
                    || self.shadow_tests.iter().filter(|(l, _)| *l == term.light).flat_map(|(_, t)| t.iter());
                events.extend(mine().map(|(k, _)| *k));
                let tests: Vec<String> = mine()
                    .map(|(_, t)| match t {
                        Event::ObjectTest { object, .. } => {
                            format!("  · {}: {}", self.object(*object), self.test_line(t))
                        }
                        _ => format!("  · {}", self.test_line(t)),
                    })
                    .collect();
                lines.push(format!(
                    "{} O = {}, D = {}",
                    self.t("shadow ray from the offset origin", "raza de umbră din originea deplasată"),
                    vec_str(*origin),
                    vec_str(*direction)
                ));
                lines.extend(tests);
                let occ = if occluders.is_empty() {
                    self.t("nothing in between", "nimic între ele").to_string()
                } else {
                    let list: Vec<String> = occluders
                        .iter()
                        .map(|o| format!("{} (kt = {})", self.object(o.object), num(o.kt)))
                        .collect();
                    list.join(", ")
                };
                lines.push(format!(
                    "{} d_L = {}: {occ} → s = Π kt = {}",
                    self.t("segment to the light, length", "segment până la sursă, lungime"),
                    num(*distance),
                    num(*s)
                ));
            }
        }
        lines.push(format!("{} Isrc·fat·s·kd·(N·L) = {}", self.t("diffuse", "difuz"), rgb(term.diffuse)));
        lines.push(format!(
            "{} Isrc·fat·s·ks·(N·H)^n (n = {}) = {}",
            self.t("specular", "speculară"),
            num(n),
            rgb(term.specular)
        ));
        if events.is_empty() {
            events.extend(hit_event);
        }
        events.sort_unstable();
        self.step(indent, &title, &lines, events);
    }

    /// The colour step of a node: the hit and the rays it sums (`events`).
    fn sum(&mut self, node: &RayNode<V>, indent: usize, events: Vec<usize>) {
        let Some(end) = &node.end else { return };
        let Some(local) = end.local else { return };
        let Some(hit) = end.hit else { return };
        let m = self.scene.material_of(hit.object.index);
        let mut formula = format!("I = I_local {}", rgb(local));
        for &c in &node.children {
            let child = &self.log.nodes[c];
            let col = child.end.as_ref().map_or(Rgb::BLACK, |e| e.color);
            let (k, name, sym) = match child.start.kind {
                crate::record::event::RayKind::Transmitted => (m.kt, "kt", "T"),
                _ => (m.ks, "ks", "R"),
            };
            let _ = write!(formula, " + {name}·{sym} = {} · {}", num(k), rgb(col));
        }
        let title = self.t(
            "Colour of this ray: I = I_local + ks·R + kt·T",
            "Culoarea acestei raze: I = I_local + ks·R + kt·T",
        );
        self.step(indent, title, &[formula, format!("I = {}", rgb(end.color))], events);
    }
}

/// The numbered narration of a traced primary ray.
#[must_use]
pub fn narrate<V: Dim>(
    scene: &Scene<V>,
    log: &EventLog<V>,
    stats: &Stats,
    target: &TraceTarget,
    max_depth: u32,
    lang: Lang,
) -> String {
    narration(scene, log, stats, target, max_depth, lang).text
}

/// [`narrate`] with the events of each step.
#[must_use]
pub fn narration<V: Dim>(
    scene: &Scene<V>,
    log: &EventLog<V>,
    stats: &Stats,
    target: &TraceTarget,
    max_depth: u32,
    lang: Lang,
) -> Narration {
    let mut w = Writer {
        scene,
        log,
        lang,
        out: String::new(),
        step: 0,
        events: Vec::new(),
        max_depth,
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
    let cam = &scene.camera;
    if let (Some(pixel), Some(uv)) = (&target.pixel, &target.uv) {
        let win = &cam.window;
        let mut lines = vec![format!(
            "u = l + (r − l)·(i + 0.5)/Nx = {} + ({} − {})·({} + 0.5)/{} = {}",
            num(win.l),
            num(win.r),
            paren(win.l),
            pixel[0],
            cam.nx,
            num(uv[0])
        )];
        if V::DIM == 3 {
            lines.push(format!(
                "v = b + (t − b)·(j + 0.5)/Ny = {} + ({} − {})·({} + 0.5)/{} = {}",
                num(win.b),
                num(win.t),
                paren(win.b),
                pixel[1],
                cam.ny,
                num(uv[1])
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
            w.t("Primary ray through the window point S", "Raza primară prin punctul S al ferestrei"),
            &lines,
            primary,
        );
    }
    if let Some(root) = root {
        w.node(root, 0, None);
        if let Some(end) = &log.nodes[root].end {
            let title = w.t(
                "Pixel colour (linear RGB, clamped only when written)",
                "Culoarea pixelului (RGB liniar, limitată doar la scriere)",
            );
            let bytes = end.color.0.map(crate::image::to_byte);
            w.step(0, title, &[format!("{} → 8 bit {:?}", rgb(end.color), bytes)], root_events.clone());
        }
    }
    let r = stats.rays;
    let _ = writeln!(
        w.out,
        "{}: {} {}, {} {}, {} {}, {} {}; {} {}",
        w.t("Rays", "Raze"),
        r.primary,
        w.t("primary", "primare"),
        r.reflected,
        w.t("reflected", "reflectate"),
        r.transmitted,
        w.t("transmitted", "transmise"),
        r.shadow,
        w.t("shadow", "de umbră"),
        stats.tests.object,
        w.t("object tests", "teste de intersecție")
    );
    Narration { text: w.out, events: w.events }
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
}
