//! The comparison itself: the student's tree walked in the narration's order (the window point;
//! per ray its origin, direction, object, t, point, normal, each light's `n_dot_l` and `shadow`,
//! `I_local`, then R's subtree, then T's, then the ray's colour; last the pixel's colour), each
//! student ray traced by whitted from the student's own origin and direction at its level, until
//! the first divergence.

use super::diagnose::{self, close, LocalInputs, Mistake, Spawn};
use super::student::{Document, HitField, ObjectId, RayNode};
use super::{Divergence, Grade, Quantity, Shown, OFFSET_SLACK};
use crate::accel::{Accel, AccelKind};
use crate::doc::narrate::narration;
use crate::doc::TraceTarget;
use crate::geom::optics::indices;
use crate::geom::ray::Ray;
use crate::json::reader::MAX_MAGNITUDE;
use crate::lang::Lang;
use crate::record::event::{Event, RayKind};
use crate::record::names::subscript;
use crate::record::stats::Stats;
use crate::record::{EventLog, NoRecorder};
use crate::scene::camera::Projection;
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use crate::trace::Tracer;

/// The formulas, as the narration writes them.
mod formula {
    /// A formula in English and Romanian (the same where it is only mathematics).
    pub type Formula = [&'static str; 2];
    const fn same(f: &'static str) -> Formula {
        [f, f]
    }
    pub const WINDOW_POINT: Formula = same("u = l + (r − l)·(i + 0.5)/Nx, v = b + (t − b)·(j + 0.5)/Ny");
    pub const PERSPECTIVE: Formula = same("O = eye, D = (S − O)/|S − O|, S = O + u·u + v·v − p·w");
    pub const ORTHOGRAPHIC: Formula = same("S = O + u·u + v·v − p·w, D = −w");
    pub const SPAWN_ORIGIN: Formula = ["I ± δ·N_f (δ a small offset)", "I ± δ·N_f (δ o deplasare mică)"];
    pub const REFLECT: Formula = same("R = D − 2(D·N_f)·N_f");
    pub const REFRACT: Formula = same("T = η·D + (η·c − √k)·N_f, η = n1/n2, c = −D·N_f, k = 1 − η²(1 − c²)");
    pub const NEAREST: Formula =
        ["the nearest t > 0 of O + t·D over the objects", "cel mai mic t > 0 al lui O + t·D peste obiecte"];
    pub const POINT: Formula = same("I = O + t·D");
    pub const NORMAL: Formula = [
        "N = the outward unit normal at I (sphere: (I − C)/r)",
        "N = normala exterioară unitară în I (sferă: (I − C)/r)",
    ];
    pub const N_DOT_L: Formula = same("N_f·L, L = (S_light − I)/|S_light − I|");
    pub const SHADOW: Formula = [
        "s = Π kt over the objects with 0 < t < d_L on the segment I → light",
        "s = Π kt peste obiectele cu 0 < t < d_L de pe segmentul I → sursă",
    ];
    pub const LOCAL: Formula = same("I_local = Ia·Ka + Σ Isrc·fat·s·lum·[kd·(N·L) + ks·(N·H)^n]");
    pub const COLOUR: Formula = same("I = I_local + ks·R + kt·T");
    pub const SPAWNS: Formula = [
        "children iff n ≤ max_depth; R iff ks > 0; T iff kt > 0 and k ≥ 0",
        "copii dacă n ≤ max_depth; R dacă ks > 0; T dacă kt > 0 și k ≥ 0",
    ];
}

/// Stops the walk at the first divergence (recorded in the walker).
struct Stop;

type Flow<T = ()> = Result<T, Stop>;

/// Where a ray stands: the keys from P, its name and level.
#[derive(Clone)]
struct Place {
    path: Vec<&'static str>,
    /// The names from P down to this ray.
    chain: Vec<String>,
    name: String,
    level: u32,
}

/// What the parent expects of a ray: whitted's origin and direction, and for a secondary ray how
/// it was spawned.
struct Start<V> {
    origin: V,
    direction: V,
    /// For a secondary ray: its kind, the parent's I, and the spawn's optics.
    spawn: Option<(RayKind, V, Spawn<V>)>,
}

struct Walker<'a, V: Dim> {
    scene: &'a Scene<V>,
    accel: Accel<V>,
    tol: f64,
    checked: usize,
    not_checked: Vec<String>,
    /// Hits numbered so far (I₁, I₂ … in pre-order).
    hits: usize,
    first: Option<Divergence>,
}

fn vector<V: Dim>(v: V) -> Shown {
    Shown::Vector(v.to_vec())
}

fn rgb(c: Rgb) -> Shown {
    Shown::Vector(c.0.to_vec())
}

/// Compares the student's document with whitted's trace of the same pixel.
#[must_use]
pub fn compare<V: Dim>(scene: &Scene<V>, doc: &Document<V>, tol: f64) -> Grade {
    let mut w = Walker {
        scene,
        accel: Accel::build(scene, AccelKind::Bvh),
        tol,
        checked: 0,
        not_checked: Vec::new(),
        hits: 0,
        first: None,
    };
    let _ = w.pixel(doc);
    let mut first = w.first.take();
    if let Some(d) = &mut first {
        d.step = step_of(scene, &doc.pixel, d);
    }
    Grade { pixel: doc.pixel.clone(), tolerance: tol, checked: w.checked, not_checked: w.not_checked, first }
}

impl<V: Dim> Walker<'_, V> {
    fn agree(&mut self) {
        self.checked += 1;
    }

    fn absent(&mut self, place: &Place, what: &str) {
        self.not_checked.push(format!("{}.{what}", place.name));
    }

    #[allow(clippy::too_many_arguments)] // a divergence has this many parts
    fn diverge(
        &mut self,
        place: &Place,
        quantity: Quantity,
        light: Option<usize>,
        expected: Shown,
        found: Shown,
        formula: formula::Formula,
        inputs: Vec<(String, Shown)>,
        diagnosis: Option<Mistake>,
    ) -> Stop {
        self.first = Some(Divergence {
            path: place.path.clone(),
            chain: place.chain.clone(),
            ray: place.name.clone(),
            level: place.level,
            quantity,
            light,
            expected,
            found,
            formula,
            inputs,
            diagnosis,
            step: None,
        });
        Stop
    }

    /// The window point, P's tree, and the pixel's colour.
    fn pixel(&mut self, doc: &Document<V>) -> Flow {
        let cam = &self.scene.camera;
        let (i, j) = (doc.pixel[0], doc.pixel.get(1).copied().unwrap_or(0));
        let (u, v) = cam.pixel_center(i, j);
        let uv = |u: f64, v: f64| if V::DIM == 2 { vec![u] } else { vec![u, v] };
        // What the two pixel mistakes would give: the corner (no +0.5), the row from the top.
        let corner = (cam.u_at(i as f64), cam.v_at(j as f64));
        let from_top = cam.pixel_center(i, cam.ny - 1 - j);
        let place = Place { path: Vec::new(), chain: vec!["P".to_owned()], name: "P".to_owned(), level: 1 };
        let pixel_inputs = || {
            let win = &cam.window;
            let mut inputs = vec![
                ("i".to_owned(), Shown::Number(i as f64)),
                ("l".to_owned(), Shown::Number(win.l)),
                ("r".to_owned(), Shown::Number(win.r)),
                ("Nx".to_owned(), Shown::Number(cam.nx as f64)),
            ];
            if V::DIM == 3 {
                inputs.extend([
                    ("j".to_owned(), Shown::Number(j as f64)),
                    ("b".to_owned(), Shown::Number(win.b)),
                    ("t".to_owned(), Shown::Number(win.t)),
                    ("Ny".to_owned(), Shown::Number(cam.ny as f64)),
                ]);
            }
            inputs
        };
        let tol = self.tol;
        let pixel_mistake = |found: &[f64], of: &dyn Fn(f64, f64) -> Vec<f64>| {
            let differs = |(a, b): (f64, f64)| !close(&of(a, b), &of(u, v), tol, 0.0);
            if differs(corner) && close(found, &of(corner.0, corner.1), tol, 0.0) {
                Some(Mistake::NoHalfPixel)
            } else if differs(from_top) && close(found, &of(from_top.0, from_top.1), tol, 0.0) {
                Some(Mistake::RowsFromTop)
            } else {
                None
            }
        };
        match &doc.window_point {
            Some(found) if close(found, &uv(u, v), self.tol, 0.0) => self.agree(),
            Some(found) => {
                let diagnosis = pixel_mistake(found, &uv);
                let inputs = pixel_inputs();
                return Err(self.diverge(
                    &place,
                    Quantity::WindowPoint,
                    None,
                    Shown::Vector(uv(u, v)),
                    Shown::Vector(found.clone()),
                    formula::WINDOW_POINT,
                    inputs,
                    diagnosis,
                ));
            }
            None => self.not_checked.push("window_point".to_owned()),
        }
        let primary = cam.primary_ray(u, v);
        // P's origin and direction as the pixel mistakes would make them.
        let origin_of = |a: f64, b: f64| cam.primary_ray(a, b).origin.to_vec();
        let direction_of = |a: f64, b: f64| cam.primary_ray(a, b).dir.to_vec();
        let s = &doc.ray;
        let p_formula = if cam.projection == Projection::Perspective {
            formula::PERSPECTIVE
        } else {
            formula::ORTHOGRAPHIC
        };
        let found_uv = doc.window_point.clone().unwrap_or_else(|| uv(u, v));
        let s_point = cam.window_point(found_uv[0], found_uv.get(1).copied().unwrap_or(0.0));
        let p_inputs = vec![
            ("(u, v)".to_owned(), Shown::Vector(found_uv.clone())),
            ("O".to_owned(), vector(cam.eye)),
            ("S".to_owned(), vector(s_point)),
        ];
        if let Some(o) = s.origin {
            if !close(&o.to_vec(), &primary.origin.to_vec(), self.tol, 0.0) {
                let diagnosis = pixel_mistake(&o.to_vec(), &origin_of);
                return Err(self.diverge(
                    &place,
                    Quantity::Origin,
                    None,
                    vector(primary.origin),
                    vector(o),
                    p_formula,
                    p_inputs,
                    diagnosis,
                ));
            }
        }
        if let Some(d) = s.direction {
            if !close(&d.to_vec(), &primary.dir.to_vec(), self.tol, 0.0) {
                let diagnosis = if diagnose::unnormalized(d, primary.dir, self.tol) {
                    Some(Mistake::UnnormalizedDirection)
                } else {
                    pixel_mistake(&d.to_vec(), &direction_of)
                };
                return Err(self.diverge(
                    &place,
                    Quantity::Direction,
                    None,
                    vector(primary.dir),
                    vector(d),
                    p_formula,
                    p_inputs,
                    diagnosis,
                ));
            }
        }
        // P's origin and direction are required, so both were compared above.
        self.checked += 2;
        let start = Start { origin: primary.origin, direction: primary.dir, spawn: None };
        let colour = self.node(s, &start, &place, Some(doc.colour))?;
        if s.colour.is_some() {
            if close(&doc.colour.0, &colour.0, self.tol, 0.0) {
                self.agree();
            } else {
                return Err(self.diverge(
                    &place,
                    Quantity::Colour,
                    None,
                    rgb(colour),
                    rgb(doc.colour),
                    formula::COLOUR,
                    vec![("P".to_owned(), rgb(colour))],
                    None,
                ));
            }
        }
        Ok(())
    }

    /// whitted's trace of one ray at `level` (the depth left as it is there).
    fn trace(&self, origin: V, direction: V, level: u32) -> EventLog<V> {
        let mut tracer = Tracer::new(self.scene, &self.accel, EventLog::new());
        tracer.max_depth = self.scene.max_depth.saturating_sub(level - 1);
        tracer.trace_primary(&Ray::new(origin, direction), &[]);
        tracer.recorder
    }

    /// One ray node and its subtree; returns its colour (the student's where given, for the
    /// parent's sum). `top_colour` stands for P's colour when P does not give its own.
    #[allow(clippy::too_many_lines)] // the narration's order, one quantity after the other
    fn node(
        &mut self,
        s: &RayNode<V>,
        start: &Start<V>,
        place: &Place,
        top_colour: Option<Rgb>,
    ) -> Flow<Rgb> {
        let tol = self.tol;
        // A secondary ray's origin and direction (P's were compared with the pixel).
        if let Some((kind, point, spawn)) = start.spawn {
            let inputs = vec![
                ("D".to_owned(), vector(spawn.d)),
                ("N_f".to_owned(), vector(spawn.n_f)),
                ("I".to_owned(), vector(point)),
            ];
            match s.origin {
                Some(o) => {
                    let slack = OFFSET_SLACK * point.max_abs().max(1.0);
                    if close(&o.to_vec(), &start.origin.to_vec(), tol, slack) {
                        self.agree();
                    } else {
                        return Err(self.diverge(
                            place,
                            Quantity::Origin,
                            None,
                            vector(start.origin),
                            vector(o),
                            formula::SPAWN_ORIGIN,
                            inputs,
                            None,
                        ));
                    }
                }
                None => self.absent(place, "origin"),
            }
            match s.direction {
                Some(d) if close(&d.to_vec(), &start.direction.to_vec(), tol, 0.0) => self.agree(),
                Some(d) => {
                    let transmitted = (kind == RayKind::Transmitted).then_some(spawn);
                    let diagnosis = diagnose::direction(d, start.direction, transmitted, tol);
                    let (formula, mut inputs) = match kind {
                        RayKind::Transmitted => (formula::REFRACT, inputs),
                        _ => (formula::REFLECT, inputs),
                    };
                    if kind == RayKind::Transmitted {
                        inputs.push(("n1".to_owned(), Shown::Number(spawn.n1)));
                        inputs.push(("n2".to_owned(), Shown::Number(spawn.n2)));
                    }
                    return Err(self.diverge(
                        place,
                        Quantity::Direction,
                        None,
                        vector(start.direction),
                        vector(d),
                        formula,
                        inputs,
                        diagnosis,
                    ));
                }
                None => self.absent(place, "direction"),
            }
        }
        let origin = s.origin.unwrap_or(start.origin);
        let direction = s.direction.and_then(crate::geom::Vector::try_unit).unwrap_or(start.direction);
        let log = self.trace(origin, direction, place.level);
        let root = &log.nodes[0];
        let Some(end) = root.end.clone() else { return Ok(Rgb::BLACK) };
        let ray_inputs = || vec![("O".to_owned(), vector(origin)), ("D".to_owned(), vector(direction))];
        let scene = self.scene;
        let name_of = |index: usize| {
            scene.objects[index].name.as_ref().map_or_else(|| index.to_string(), |n| n.en.clone())
        };
        // The hit.
        let hit = end.hit;
        if hit.is_some() {
            self.hits += 1;
        }
        let k = self.hits;
        match (&s.hit, hit) {
            (HitField::Absent, _) => {
                self.absent(place, "hit");
            }
            (HitField::Miss, None) => self.agree(),
            (HitField::Miss, Some(h)) => {
                return Err(self.diverge(
                    place,
                    Quantity::Object,
                    None,
                    Shown::Name(name_of(h.object.index)),
                    Shown::Nothing,
                    formula::NEAREST,
                    ray_inputs(),
                    None,
                ));
            }
            (HitField::Hit(sh), None) => {
                let found = sh.object.as_ref().map_or(Shown::Name(String::new()), |o| match o {
                    ObjectId::Name(n) => Shown::Name(n.clone()),
                    ObjectId::Index(i) => Shown::Name(i.to_string()),
                });
                return Err(self.diverge(
                    place,
                    Quantity::Object,
                    None,
                    Shown::Nothing,
                    found,
                    formula::NEAREST,
                    ray_inputs(),
                    None,
                ));
            }
            (HitField::Hit(sh), Some(h)) => {
                let index = h.object.index;
                match &sh.object {
                    Some(o) => {
                        let same = match o {
                            ObjectId::Index(i) => *i == index,
                            ObjectId::Name(n) => {
                                *n == index.to_string()
                                    || scene.objects[index]
                                        .name
                                        .as_ref()
                                        .is_some_and(|b| b.en == *n || b.ro == *n)
                            }
                        };
                        if !same {
                            let found = match o {
                                ObjectId::Name(n) => n.clone(),
                                ObjectId::Index(i) => i.to_string(),
                            };
                            return Err(self.diverge(
                                place,
                                Quantity::Object,
                                None,
                                Shown::Name(name_of(index)),
                                Shown::Name(found),
                                formula::NEAREST,
                                ray_inputs(),
                                None,
                            ));
                        }
                        self.agree();
                    }
                    None => self.absent(place, "hit.object"),
                }
                match sh.t {
                    Some(t) if close(&[t], &[h.t], tol, 0.0) => self.agree(),
                    Some(t) => {
                        return Err(self.diverge(
                            place,
                            Quantity::T,
                            None,
                            Shown::Number(h.t),
                            Shown::Number(t),
                            formula::NEAREST,
                            ray_inputs(),
                            None,
                        ))
                    }
                    None => self.absent(place, "hit.t"),
                }
                match sh.point {
                    Some(p) if close(&p.to_vec(), &h.point.to_vec(), tol, 0.0) => self.agree(),
                    Some(p) => {
                        let mut inputs = ray_inputs();
                        inputs.push(("t".to_owned(), Shown::Number(sh.t.unwrap_or(h.t))));
                        return Err(self.diverge(
                            place,
                            Quantity::Point,
                            None,
                            vector(h.point),
                            vector(p),
                            formula::POINT,
                            inputs,
                            None,
                        ));
                    }
                    None => self.absent(place, "hit.point"),
                }
                match sh.normal {
                    Some(n) if close(&n.to_vec(), &h.normal.to_vec(), tol, 0.0) => self.agree(),
                    Some(n) => {
                        let diagnosis =
                            diagnose::unnormalized(n, h.normal, tol).then_some(Mistake::UnnormalizedNormal);
                        return Err(self.diverge(
                            place,
                            Quantity::Normal,
                            None,
                            vector(h.normal),
                            vector(n),
                            formula::NORMAL,
                            vec![("I".to_owned(), vector(sh.point.unwrap_or(h.point)))],
                            diagnosis,
                        ));
                    }
                    None => self.absent(place, "hit.normal"),
                }
            }
        }
        let Some(h) = hit else {
            // A miss: the background, no lights, no children.
            return self.colour(s, place, end.color, Rgb::BLACK, &[], top_colour);
        };
        let n_f = if h.entering { h.normal } else { -h.normal };
        let material = scene.material_of(h.object.index);
        // The lights, in the scene's order.
        match &s.lights {
            None => self.absent(place, "lights"),
            Some(entries) => {
                for (j, (entry, term)) in entries.iter().zip(&root.lights).enumerate() {
                    let light_inputs = || {
                        vec![
                            ("I".to_owned(), vector(h.point)),
                            ("N_f".to_owned(), vector(n_f)),
                            ("S_light".to_owned(), vector(scene.lights[j].position)),
                        ]
                    };
                    match entry.n_dot_l {
                        Some(x) if close(&[x], &[term.n_dot_l], tol, 0.0) => self.agree(),
                        Some(x) => {
                            let flipped = !h.entering && close(&[x], &[-term.n_dot_l], tol, 0.0);
                            return Err(self.diverge(
                                place,
                                Quantity::NDotL,
                                Some(j),
                                Shown::Number(term.n_dot_l),
                                Shown::Number(x),
                                formula::N_DOT_L,
                                light_inputs(),
                                flipped.then_some(Mistake::NormalNotFlipped),
                            ));
                        }
                        None => self.absent(place, &format!("lights[{j}].n_dot_l")),
                    }
                    match (entry.shadow, term.shadow) {
                        (Some(x), Some(e)) if close(&[x], &[e], tol, 0.0) => self.agree(),
                        (None, Some(_)) => self.absent(place, &format!("lights[{j}].shadow")),
                        (None, None) => {}
                        (Some(x), e) => {
                            let diagnosis = e.and_then(|e| self.shadow_mistake(&log, j, x, e, material.kt));
                            return Err(self.diverge(
                                place,
                                Quantity::Shadow,
                                Some(j),
                                e.map_or(Shown::NoShadowRay, Shown::Number),
                                Shown::Number(x),
                                formula::SHADOW,
                                light_inputs(),
                                diagnosis,
                            ));
                        }
                    }
                }
            }
        }
        // I_local.
        let local = end.local.unwrap_or(Rgb::BLACK);
        match s.local {
            Some(c) if close(&c.0, &local.0, tol, 0.0) => self.agree(),
            Some(c) => {
                let inputs = LocalInputs {
                    scene,
                    material,
                    point: h.point,
                    n_f,
                    view: -direction,
                    lights: &root.lights,
                };
                let diagnosis = inputs.diagnose(c, local, tol);
                let mut shown = vec![("N_f".to_owned(), vector(n_f)), ("V".to_owned(), vector(-direction))];
                for term in &root.lights {
                    let j = term.light;
                    shown.push((format!("N_f·L{}", j + 1), Shown::Number(term.n_dot_l)));
                    if let Some(sv) = term.shadow {
                        shown.push((format!("s{}", j + 1), Shown::Number(sv)));
                    }
                    shown.push((format!("fat{}", j + 1), Shown::Number(term.fat)));
                }
                return Err(self.diverge(
                    place,
                    Quantity::Local,
                    None,
                    rgb(local),
                    rgb(c),
                    formula::LOCAL,
                    shown,
                    diagnosis,
                ));
            }
            None => self.absent(place, "local"),
        }
        // The children, R then T, compared when the student wrote the hit.
        let mut weighted: Vec<(f64, Rgb)> = Vec::new();
        let student_local = s.local.unwrap_or(local);
        if matches!(s.hit, HitField::Hit(_)) {
            let (n1, n2) = indices(h.entering, material.ior);
            let spawn = Spawn { d: direction, n_f, n1, n2, entering: h.entering };
            for (kind, key, letter, weight) in [
                (RayKind::Reflected, "reflected", "R", material.ks),
                (RayKind::Transmitted, "transmitted", "T", material.kt),
            ] {
                let whitted = root.children.iter().copied().find(|&c| log.nodes[c].start.kind == kind);
                let student = if kind == RayKind::Reflected { &s.reflected } else { &s.transmitted };
                let mut path = place.path.clone();
                path.push(key);
                let name = subscript(letter, &[k]);
                let mut chain = place.chain.clone();
                chain.push(name.clone());
                let child = Place { path, chain, name, level: place.level + 1 };
                match (whitted, student) {
                    (Some(c), Some(sc)) => {
                        let node = &log.nodes[c];
                        let start = Start {
                            origin: node.start.origin,
                            direction: node.start.direction,
                            spawn: Some((kind, h.point, spawn)),
                        };
                        let colour = self.node(sc, &start, &child, None)?;
                        weighted.push((weight, colour));
                    }
                    (None, None) => {}
                    (whitted, _) => {
                        let missing = whitted.is_some();
                        let tir = log.events.iter().any(|e| {
                            e.ray == Some(0) && matches!(e.event, Event::TotalInternalReflection { .. })
                        });
                        let diagnosis = if missing {
                            (place.level == scene.max_depth).then_some(Mistake::DepthOffByOne)
                        } else if place.level > scene.max_depth {
                            Some(Mistake::DepthOffByOne)
                        } else if kind == RayKind::Transmitted && material.kt == 0.0 {
                            Some(Mistake::TransmitKt0)
                        } else if kind == RayKind::Transmitted && tir {
                            Some(Mistake::NoTir)
                        } else {
                            None
                        };
                        let (quantity, expected, found) = if missing {
                            (Quantity::Missing, Shown::Ray(key), Shown::NoRay)
                        } else {
                            (Quantity::Extra, Shown::NoRay, Shown::Ray(key))
                        };
                        let inputs = vec![
                            ("n".to_owned(), Shown::Number(f64::from(place.level))),
                            ("max_depth".to_owned(), Shown::Number(f64::from(scene.max_depth))),
                            ("ks".to_owned(), Shown::Number(material.ks)),
                            ("kt".to_owned(), Shown::Number(material.kt)),
                        ];
                        return Err(self.diverge(
                            &child,
                            quantity,
                            None,
                            expected,
                            found,
                            formula::SPAWNS,
                            inputs,
                            diagnosis,
                        ));
                    }
                }
            }
        } else {
            for &c in &root.children {
                let node = &log.nodes[c];
                let weight = if node.start.kind == RayKind::Reflected { material.ks } else { material.kt };
                weighted.push((weight, node.end.as_ref().map_or(Rgb::BLACK, |e| e.color)));
            }
        }
        let expected = weighted.iter().fold(local, |sum, (kw, c)| sum + *c * *kw);
        self.colour(s, place, expected, student_local, &weighted, top_colour)
    }

    /// The node's colour against `expected` (its local term and its children's weighted colours,
    /// the student's own where given, for the diagnosis).
    fn colour(
        &mut self,
        s: &RayNode<V>,
        place: &Place,
        expected: Rgb,
        local: Rgb,
        weighted: &[(f64, Rgb)],
        top_colour: Option<Rgb>,
    ) -> Flow<Rgb> {
        let Some(found) = s.colour.or(top_colour) else {
            self.absent(place, "colour");
            return Ok(expected);
        };
        if close(&found.0, &expected.0, self.tol, 0.0) {
            self.agree();
            return Ok(found);
        }
        let diagnosis = diagnose::colour(found, expected, local, weighted, self.tol);
        let mut inputs = vec![("I_local".to_owned(), rgb(local))];
        for (k, c) in weighted {
            inputs.push((format!("k = {}", crate::format::narration_number(*k)), rgb(*c)));
        }
        Err(self.diverge(
            place,
            Quantity::Colour,
            None,
            rgb(expected),
            rgb(found),
            formula::COLOUR,
            inputs,
            diagnosis,
        ))
    }

    /// Why a shadow factor differs: the segment taken as a half-line past the light (found = the s
    /// of the half-line), or else the object hit counted as its own occluder (found = s·kt of itself).
    fn shadow_mistake(
        &self,
        log: &EventLog<V>,
        light: usize,
        found: f64,
        expected: f64,
        kt_self: f64,
    ) -> Option<Mistake> {
        let tol = self.tol;
        let (origin, direction) = log.events.iter().find_map(|e| match &e.event {
            Event::ShadowRay { light: l, origin, direction, .. } if e.ray == Some(0) && *l == light => {
                Some((*origin, *direction))
            }
            _ => None,
        })?;
        let mut s = 1.0;
        let scene = self.scene;
        self.accel.occluders(
            scene,
            &Ray::new(origin, direction),
            MAX_MAGNITUDE,
            &mut Stats::default(),
            &mut NoRecorder,
            |o| {
                let kt = scene.material_of(o.index).kt;
                s *= kt;
                kt > 0.0
            },
        );
        // Past the light first: where something lies beyond it, the half-line explains the found s.
        if close(&[found], &[s], tol, 0.0) {
            return Some(Mistake::OccludersBeyondLight);
        }
        (!close(&[expected * kt_self], &[expected], tol, 0.0)
            && close(&[found], &[expected * kt_self], tol, 0.0))
        .then_some(Mistake::NoShadowOffset)
    }
}

/// The step of `whitted trace SCENE --pixel I,J` that computes the diverging quantity: found in
/// whitted's own trace of the pixel by the ray's path and the event that quantity comes from.
fn step_of<V: Dim>(scene: &Scene<V>, pixel: &[usize], d: &Divergence) -> Option<usize> {
    step_in(scene, pixel, d, &Accel::build(scene, AccelKind::Bvh), scene.max_depth)
}

/// The step that computes the diverging quantity in the narration traced with `accel` and depth
/// limit `depth` (the page's narration, whose structure may add or remove steps: a BVH's node
/// visits, every object's test without one); None when that trace has no such ray.
#[must_use]
pub fn step_in<V: Dim>(
    scene: &Scene<V>,
    pixel: &[usize],
    d: &Divergence,
    accel: &Accel<V>,
    depth: u32,
) -> Option<usize> {
    let cam = &scene.camera;
    let (i, j) = (pixel[0], pixel.get(1).copied().unwrap_or(0));
    let (u, v) = cam.pixel_center(i, j);
    let uv = if V::DIM == 2 { vec![u] } else { vec![u, v] };
    let mut tracer = Tracer::new(scene, accel, EventLog::new());
    tracer.max_depth = depth;
    tracer.trace_primary(&cam.primary_ray(u, v), &uv);
    let log = tracer.recorder;
    let target = TraceTarget { pixel: Some(pixel.to_vec()), uv: Some(uv) };
    let told = narration(scene, &log, &tracer.stats, &target, depth, Lang::En);
    let first_with = |event: usize| told.events.iter().position(|s| s.contains(&event)).map(|k| k + 1);
    let last_with = |event: usize| told.events.iter().rposition(|s| s.contains(&event)).map(|k| k + 1);
    // The node of the path; a missing or extra ray stands at its parent.
    let spawn_problem = matches!(d.quantity, Quantity::Missing | Quantity::Extra);
    let keys = if spawn_problem { &d.path[..d.path.len().saturating_sub(1)] } else { &d.path[..] };
    let mut node = log.roots().next()?;
    for key in keys {
        let kind = if *key == "reflected" { RayKind::Reflected } else { RayKind::Transmitted };
        node = log.nodes[node].children.iter().copied().find(|&c| log.nodes[c].start.kind == kind)?;
    }
    let hit = log.ended_by(node);
    match d.quantity {
        Quantity::WindowPoint => first_with(log.spawned_by(node)?),
        Quantity::Origin | Quantity::Direction => {
            let event = log.spawned_by(node)?;
            // P's primary event is told by the pixel's step and then by P's own.
            let with: Vec<usize> =
                (1..=told.events.len()).filter(|k| told.events[k - 1].contains(&event)).collect();
            with.get(usize::from(node == 0)).or(with.first()).copied()
        }
        Quantity::Object | Quantity::T | Quantity::Point | Quantity::Normal => first_with(hit?),
        // The local model's step lists every shadow ray of the hit, and each light's step its own.
        Quantity::NDotL | Quantity::Shadow => {
            let light = d.light.unwrap_or(0);
            log.shadow_events(node, light).first().and_then(|&e| last_with(e)).or_else(|| first_with(hit?))
        }
        Quantity::Local => {
            log.shadow_events(node, 0).first().and_then(|&e| first_with(e)).or_else(|| first_with(hit?))
        }
        // The hit is told by its step, the node's colour and, for P, the pixel's colour last.
        Quantity::Colour => {
            let hit = hit?;
            let with: Vec<usize> =
                (1..=told.events.len()).filter(|k| told.events[k - 1].contains(&hit)).collect();
            let back = if node == 0 && with.len() > 2 { 2 } else { 1 };
            with.get(with.len().saturating_sub(back)).copied()
        }
        Quantity::Missing | Quantity::Extra => {
            let spawns = log.indices_of(node, |e| {
                matches!(
                    e,
                    Event::Reflect { .. }
                        | Event::Refract { .. }
                        | Event::TotalInternalReflection { .. }
                        | Event::DepthLimit { .. }
                )
            });
            spawns.first().and_then(|&e| first_with(e)).or_else(|| last_with(hit?))
        }
    }
}
