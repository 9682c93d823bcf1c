//! The trace document (product.md "The trace document"), the serialized public interface of
//! `whitted trace --json`:
//!
//! - `pixel`: `[i, j]` (`[i]` in 2D) or null; `uv`: `[u, v]` (`[u]` in 2D) or null;
//! - `color`: the root's linear RGB (with samples: the pixel's weighted mean);
//! - `stats`: `{ rays: {primary, reflected, transmitted, shadow}, tests: {object, bound, node, voxel} }`;
//! - `tree`: the root ray node `{ kind, level, origin, direction, hit, lights, local, color, children }`,
//!   `hit` = null or `{ object, t, point, normal, entering }`, each light
//!   `{ light, L, n_dot_l, lum, fat, shadow, diffuse, specular }`;
//! - `events`: every event in order, each `{ kind, ray, …fields }` (see `record::event`).
//!
//! A pixel traced with `--aa corners|adaptive` adds `sampling`, `samples` and `squares` and has
//! `tree` = null: see [`samples`].
//!
//! Objects are named by `name` when they have one, else by their index (a number). JSON has no
//! infinity: ±∞ is written `"inf"`/`"-inf"`; a NaN is never written (it would be a bug).

pub mod narrate;
pub mod round;
pub mod samples;

use crate::geom::Vector;
use crate::record::event::{Event, LightTerm, NodeHit, ObjectRef};
use crate::record::stats::Stats;
use crate::record::{EventLog, RayNode};
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use serde_json::{json, Map, Value};

/// A float as JSON: ±∞ as the strings `"inf"`/`"-inf"`.
#[must_use]
pub fn float(x: f64) -> Value {
    if x == f64::INFINITY {
        json!("inf")
    } else if x == f64::NEG_INFINITY {
        json!("-inf")
    } else {
        json!(x)
    }
}

/// A vector as a JSON array of its components.
pub fn vector<V: Vector>(v: V) -> Value {
    Value::Array(v.to_vec().into_iter().map(float).collect())
}

/// A colour as `[r, g, b]`.
#[must_use]
pub fn color(c: Rgb) -> Value {
    Value::Array(c.0.iter().map(|x| float(*x)).collect())
}

/// The statistics object shared by `trace --json` and `render --json`.
#[must_use]
pub fn stats(s: &Stats) -> Value {
    json!({
        "rays": {
            "primary": s.rays.primary,
            "reflected": s.rays.reflected,
            "transmitted": s.rays.transmitted,
            "shadow": s.rays.shadow,
        },
        "tests": {
            "object": s.tests.object,
            "bound": s.tests.bound,
            "node": s.tests.node,
            "voxel": s.tests.voxel,
        },
    })
}

/// Names objects as the document does: `name`, else the index.
pub struct Namer<'a, V: Dim> {
    scene: &'a Scene<V>,
}

impl<'a, V: Dim> Namer<'a, V> {
    /// A namer for the scene's objects.
    pub fn new(scene: &'a Scene<V>) -> Self {
        Self { scene }
    }
    /// The object's `name`, else its index.
    #[must_use]
    pub fn object(&self, o: ObjectRef) -> Value {
        match &self.scene.objects[o.index].name {
            // The English name: the document is the machine interface, the same whatever the
            // narration's language (product.md "The trace document").
            Some(n) => json!(n.en),
            None => json!(o.index),
        }
    }
    fn with_object(&self, map: &mut Map<String, Value>, o: ObjectRef) {
        map.insert("object".into(), self.object(o));
        if let Some(t) = o.triangle {
            map.insert("triangle".into(), json!(t));
        }
    }
    fn hit(&self, h: &NodeHit<V>) -> Value {
        let mut m = Map::new();
        self.with_object(&mut m, h.object);
        m.insert("t".into(), float(h.t));
        m.insert("point".into(), vector(h.point));
        m.insert("normal".into(), vector(h.normal));
        m.insert("entering".into(), json!(h.entering));
        Value::Object(m)
    }
}

fn light_term<V: Vector>(l: &LightTerm<V>) -> Value {
    json!({
        "light": l.light,
        "L": l.l.map_or(Value::Null, vector),
        "n_dot_l": float(l.n_dot_l),
        "lum": float(l.lum),
        "fat": float(l.fat),
        "shadow": l.shadow.map_or(Value::Null, float),
        "diffuse": color(l.diffuse),
        "specular": color(l.specular),
    })
}

/// The ray node at `index` of the log and its subtree.
pub fn node<V: Dim>(namer: &Namer<'_, V>, log: &EventLog<V>, index: usize) -> Value {
    let n: &RayNode<V> = &log.nodes[index];
    let end = n.end.as_ref();
    json!({
        "kind": n.start.kind.name(),
        "level": n.start.level,
        "origin": vector(n.start.origin),
        "direction": vector(n.start.direction),
        "hit": end.and_then(|e| e.hit.as_ref()).map_or(Value::Null, |h| namer.hit(h)),
        "lights": n.lights.iter().map(light_term).collect::<Vec<_>>(),
        "local": end.and_then(|e| e.local).map_or(Value::Null, color),
        "color": end.map_or(Value::Null, |e| color(e.color)),
        "children": n.children.iter().map(|c| node(namer, log, *c)).collect::<Vec<_>>(),
    })
}

/// One event as `{ kind, ray, …fields }`.
pub fn event<V: Dim>(
    namer: &Namer<'_, V>,
    event: &Event<V>,
    ray: Option<usize>,
    sample: Option<usize>,
) -> Value {
    let mut m = Map::new();
    m.insert("kind".into(), json!(event.kind()));
    m.insert("ray".into(), ray.map_or(Value::Null, |r| json!(r)));
    if let Some(s) = sample {
        m.insert("sample".into(), json!(s));
    }
    let mut put = |k: &str, v: Value| {
        m.insert(k.into(), v);
    };
    match event {
        Event::PrimaryRay { origin, direction, uv } => {
            put("origin", vector(*origin));
            put("direction", vector(*direction));
            put("uv", if uv.is_empty() { Value::Null } else { json!(uv) });
        }
        Event::ObjectTest { object, roots, accepted } => {
            put("object", namer.object(*object));
            if let Some(t) = object.triangle {
                put("triangle", json!(t));
            }
            put("roots", Value::Array(roots.iter().map(|x| float(*x)).collect()));
            put("accepted", accepted.map_or(Value::Null, float));
        }
        Event::Hit { object, t, point, normal, entering } => {
            put("object", namer.object(*object));
            if let Some(tri) = object.triangle {
                put("triangle", json!(tri));
            }
            put("t", float(*t));
            put("point", vector(*point));
            put("normal", vector(*normal));
            put("entering", json!(entering));
        }
        Event::Miss { color: c } => put("color", color(*c)),
        Event::ShadowRay { light, origin, direction, distance, occluders, s } => {
            put("light", json!(light));
            put("origin", vector(*origin));
            put("direction", vector(*direction));
            put("distance", float(*distance));
            let occ: Vec<Value> = occluders
                .iter()
                .map(|o| {
                    let mut m = Map::new();
                    namer.with_object(&mut m, o.object);
                    m.insert("kt".into(), float(o.kt));
                    Value::Object(m)
                })
                .collect();
            put("occluders", Value::Array(occ));
            put("s", float(*s));
        }
        Event::Reflect { origin, direction, offset } => {
            put("origin", vector(*origin));
            put("direction", vector(*direction));
            put("offset", float(*offset));
        }
        Event::Refract { origin, direction, offset, n1, n2 } => {
            put("origin", vector(*origin));
            put("direction", vector(*direction));
            put("offset", float(*offset));
            put("n1", float(*n1));
            put("n2", float(*n2));
        }
        Event::TotalInternalReflection { k, n1, n2 } => {
            put("k", float(*k));
            put("n1", float(*n1));
            put("n2", float(*n2));
        }
        Event::DepthLimit { level } => put("level", json!(level)),
        Event::BoundTest { volume, object, intervals, t_in, t_out, hit } => {
            put("volume", json!(volume));
            put("object", object.map_or(Value::Null, |o| namer.object(o)));
            put(
                "intervals",
                Value::Array(intervals.iter().map(|[a, b]| json!([float(*a), float(*b)])).collect()),
            );
            put("t_in", float(*t_in));
            put("t_out", float(*t_out));
            put("hit", json!(hit));
        }
        Event::NodeVisit { structure, node, depth, t_in, t_out } => {
            put("structure", json!(structure));
            put("node", json!(node));
            put("depth", json!(depth));
            put("t_in", float(*t_in));
            put("t_out", float(*t_out));
        }
        Event::NodeSkip { structure, node, t_in, t_best } => {
            put("structure", json!(structure));
            put("node", json!(node));
            put("t_in", float(*t_in));
            put("t_best", float(*t_best));
        }
        Event::VoxelStep { cell, t_max, t_delta, objects } => {
            put("cell", json!(cell));
            put("t_max", Value::Array(t_max.iter().map(|x| float(*x)).collect()));
            put("t_delta", Value::Array(t_delta.iter().map(|x| float(*x)).collect()));
            put("objects", Value::Array(objects.iter().map(|o| namer.object(*o)).collect()));
        }
        Event::Sample { uv, level, color: c, reused } => {
            put("u", float(uv[0]));
            if uv.len() > 1 {
                put("v", float(uv[1]));
            }
            put("level", json!(level));
            put("color", color(*c));
            put("reused", json!(reused));
        }
    }
    Value::Object(m)
}

/// What a trace was asked for: a pixel, or a ray given by hand.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceTarget {
    /// `[i, j]` (`[i]` in 2D), or None for `--ray`.
    pub pixel: Option<Vec<usize>>,
    /// `[u, v]` (`[u]` in 2D), or None for `--ray`.
    pub uv: Option<Vec<f64>>,
}

/// The whole trace document of one traced primary ray (the first root of the log).
pub fn trace_document<V: Dim>(
    scene: &Scene<V>,
    log: &EventLog<V>,
    stats: &Stats,
    target: &TraceTarget,
    color_of_root: Rgb,
) -> Value {
    let namer = Namer::new(scene);
    let tree = log.roots().next().map_or(Value::Null, |r| node(&namer, log, r));
    json!({
        "pixel": target.pixel.as_ref().map_or(Value::Null, |p| json!(p)),
        "uv": target.uv.as_ref().map_or(Value::Null, |uv| Value::Array(uv.iter().map(|x| float(*x)).collect())),
        "color": color(color_of_root),
        "stats": self::stats(stats),
        "tree": tree,
        "events": log.events.iter().map(|e| event(&namer, &e.event, e.ray, e.sample)).collect::<Vec<_>>(),
    })
}
