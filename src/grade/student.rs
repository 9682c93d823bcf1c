//! The student's trace document (docs/grading.md "The student trace format"), read with the
//! all-errors reader `json::reader`: every problem at once, each with its JSON path
//! (`ray.reflected.hit.t: must be a number, got a string`), unknown fields named with the closest
//! known one (`color` → `colour`).

use crate::json::reader::{join, type_name, ReadError, Reader};
use crate::json::{parse, Map, Value};
use crate::scene::material::Rgb;
use crate::shape::Dim;

/// The fields of the document (a contract: tests from outside use them).
pub const DOCUMENT_FIELDS: [&str; 4] = ["pixel", "window_point", "ray", "colour"];
/// The fields of a ray node.
pub const RAY_FIELDS: [&str; 8] =
    ["origin", "direction", "hit", "lights", "local", "reflected", "transmitted", "colour"];
/// The fields of a hit.
pub const HIT_FIELDS: [&str; 4] = ["object", "t", "point", "normal"];
/// The fields of one light's entry.
pub const LIGHT_FIELDS: [&str; 2] = ["n_dot_l", "shadow"];
/// The deepest ray a document may nest: the deepest tree `max_depth ≤ 64` allows, and one more
/// (a ray spawned one level too deep is a divergence to report, not a bad document).
pub const MAX_NESTING: usize = 66;

/// The whole document.
#[derive(Clone, Debug, PartialEq)]
pub struct Document<V> {
    /// `[i, j]` (`[i]` in 2D).
    pub pixel: Vec<usize>,
    /// `[u, v]` (`[u]` in 2D), if given.
    pub window_point: Option<Vec<f64>>,
    /// The primary ray P.
    pub ray: RayNode<V>,
    /// The pixel's colour.
    pub colour: Rgb,
}

/// One ray node of the student's tree; every field but P's origin and direction may be absent.
#[derive(Clone, Debug, PartialEq)]
pub struct RayNode<V> {
    /// The ray's origin.
    pub origin: Option<V>,
    /// The ray's direction (as written: its length is compared too).
    pub direction: Option<V>,
    /// The hit: absent, a miss (`null`) or a hit.
    pub hit: HitField<V>,
    /// One entry per light of the scene (None when absent or empty).
    pub lights: Option<Vec<LightEntry>>,
    /// `I_local`.
    pub local: Option<Rgb>,
    /// R, if spawned.
    pub reflected: Option<Box<RayNode<V>>>,
    /// T, if spawned.
    pub transmitted: Option<Box<RayNode<V>>>,
    /// The node's colour.
    pub colour: Option<Rgb>,
}

/// `hit` as written.
#[derive(Clone, Debug, PartialEq)]
pub enum HitField<V> {
    /// Not written: not checked.
    Absent,
    /// `null`: the ray hits nothing.
    Miss,
    /// A hit, each of its fields optional.
    Hit(Hit<V>),
}

/// A hit as written.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit<V> {
    /// The object: a name or an index.
    pub object: Option<ObjectId>,
    /// The distance along the ray.
    pub t: Option<f64>,
    /// I.
    pub point: Option<V>,
    /// The outward N (as written: its length is compared too).
    pub normal: Option<V>,
}

/// How a student names an object.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ObjectId {
    /// The scene's name for it.
    Name(String),
    /// Its index in `objects`.
    Index(usize),
}

/// One light's entry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightEntry {
    /// `N_f·L`.
    pub n_dot_l: Option<f64>,
    /// s (absent when `N_f·L ≤ 0`).
    pub shadow: Option<f64>,
}

/// What the reader must know of the scene: the dimension comes from `V`, and these.
#[derive(Clone, Copy, Debug)]
pub struct Expect {
    /// How many lights the scene has.
    pub lights: usize,
    /// How many objects (an index must name one).
    pub objects: usize,
    /// The image's columns and rows (rows = 1 in 2D).
    pub resolution: (usize, usize),
}

/// Reads a student's document for a scene of dimension `V`.
///
/// # Errors
/// Every problem, each with its JSON path.
pub fn read<V: Dim>(text: &str, expect: Expect) -> Result<Document<V>, Vec<ReadError>> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let value = parse(text).map_err(|e| vec![ReadError::syntax(&e)])?;
    let mut r = Reader::default();
    let doc = document::<V>(&mut r, &value, expect);
    r.finish(doc)
}

fn document<V: Dim>(r: &mut Reader, v: &Value, expect: Expect) -> Option<Document<V>> {
    let map = r.fields(v, "", &DOCUMENT_FIELDS)?;
    let pixel = pixel(r, map, V::DIM, expect.resolution);
    let window_point = map.get("window_point").and_then(|w| numbers(r, w, "window_point", V::DIM - 1));
    let ray = match map.get("ray") {
        Some(v) => ray::<V>(r, v, "ray", expect, 1),
        None => {
            r.err("ray", "missing (required)");
            None
        }
    };
    if let Some(ray) = &ray {
        for (field, present) in [("origin", ray.origin.is_some()), ("direction", ray.direction.is_some())] {
            if !present && map.get("ray").and_then(Value::as_object).is_some_and(|m| !m.contains_key(field)) {
                r.err(join("ray", field), "missing (required for the primary ray)");
            }
        }
    }
    let colour = required_colour(r, map, "", "colour");
    Some(Document { pixel: pixel?, window_point, ray: ray?, colour: colour? })
}

fn pixel(r: &mut Reader, map: &Map<'_>, dim: usize, (nx, ny): (usize, usize)) -> Option<Vec<usize>> {
    let Some(v) = map.get("pixel") else {
        r.err("pixel", "missing (required)");
        return None;
    };
    let want = dim - 1;
    let items = r.array(v, "pixel", |r, x, p| r.integer(x, p, 0, u64::MAX))?;
    if items.len() != want {
        r.err("pixel", format!("must have {want} whole number(s) in a {dim}D scene, got {}", items.len()));
        return None;
    }
    let limits = [nx, ny];
    let mut out = Vec::with_capacity(want);
    for (k, &n) in items.iter().enumerate() {
        match usize::try_from(n).ok().filter(|n| *n < limits[k]) {
            Some(n) => out.push(n),
            None => {
                r.err(
                    format!("pixel[{k}]"),
                    format!("{n} is outside the image: must be below {}", limits[k]),
                );
                return None;
            }
        }
    }
    Some(out)
}

/// `n` numbers (a vector of the scene's dimension, a window point, a colour).
fn numbers(r: &mut Reader, v: &Value, path: &str, n: usize) -> Option<Vec<f64>> {
    let items = r.array(v, path, |r, x, p| r.number(x, p))?;
    if items.len() != n {
        r.err(path, format!("must have {n} numbers, got {}", items.len()));
        return None;
    }
    Some(items)
}

fn vector<V: Dim>(r: &mut Reader, map: &Map<'_>, path: &str, key: &str) -> Option<V> {
    let v = map.get(key)?;
    numbers(r, v, &join(path, key), V::DIM).and_then(|x| V::from_slice(&x))
}

fn colour(r: &mut Reader, map: &Map<'_>, path: &str, key: &str) -> Option<Rgb> {
    let v = map.get(key)?;
    numbers(r, v, &join(path, key), 3).map(|c| Rgb([c[0], c[1], c[2]]))
}

fn required_colour(r: &mut Reader, map: &Map<'_>, path: &str, key: &str) -> Option<Rgb> {
    if map.get(key).is_none() {
        r.err(join(path, key), "missing (required)");
        return None;
    }
    colour(r, map, path, key)
}

fn number(r: &mut Reader, map: &Map<'_>, path: &str, key: &str) -> Option<f64> {
    map.get(key).and_then(|v| r.number(v, &join(path, key)))
}

fn ray<V: Dim>(r: &mut Reader, v: &Value, path: &str, expect: Expect, depth: usize) -> Option<RayNode<V>> {
    if depth > MAX_NESTING {
        r.err(path, format!("rays nested deeper than {MAX_NESTING} levels"));
        return None;
    }
    let map = r.fields(v, path, &RAY_FIELDS)?;
    let hit = match map.get("hit") {
        None => HitField::Absent,
        Some(Value::Null) => HitField::Miss,
        Some(h) => hit::<V>(r, h, &join(path, "hit"), expect).map_or(HitField::Absent, HitField::Hit),
    };
    let lights = map.get("lights").and_then(|l| lights(r, l, &join(path, "lights"), expect.lights));
    let mut child = |key: &str| {
        map.get(key).and_then(|c| ray::<V>(r, c, &join(path, key), expect, depth + 1)).map(Box::new)
    };
    let reflected = child("reflected");
    let transmitted = child("transmitted");
    Some(RayNode {
        origin: vector(r, map, path, "origin"),
        direction: vector(r, map, path, "direction"),
        hit,
        lights,
        local: colour(r, map, path, "local"),
        reflected,
        transmitted,
        colour: colour(r, map, path, "colour"),
    })
}

fn hit<V: Dim>(r: &mut Reader, v: &Value, path: &str, expect: Expect) -> Option<Hit<V>> {
    let map = r.fields(v, path, &HIT_FIELDS)?;
    let object = map.get("object").and_then(|o| {
        let p = join(path, "object");
        match o {
            Value::String(_) => o.as_str().map(|s| ObjectId::Name(s.to_owned())),
            _ if o.is_number() => r
                .integer(o, &p, 0, expect.objects.saturating_sub(1) as u64)
                .and_then(|n| usize::try_from(n).ok())
                .map(ObjectId::Index),
            _ => {
                r.err(p, format!("must be an object's name or index, got {}", type_name(o)));
                None
            }
        }
    });
    Some(Hit {
        object,
        t: number(r, map, path, "t"),
        point: vector(r, map, path, "point"),
        normal: vector(r, map, path, "normal"),
    })
}

fn lights(r: &mut Reader, v: &Value, path: &str, count: usize) -> Option<Vec<LightEntry>> {
    let entries = r.array(v, path, |r, x, p| {
        let map = r.fields(x, p, &LIGHT_FIELDS)?;
        Some(LightEntry { n_dot_l: number(r, map, p, "n_dot_l"), shadow: number(r, map, p, "shadow") })
    })?;
    if entries.is_empty() {
        return None;
    }
    if entries.len() != count {
        r.err(path, format!("must have one entry per light of the scene ({count}), got {}", entries.len()));
        return None;
    }
    Some(entries)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    const EXPECT: Expect = Expect { lights: 1, objects: 2, resolution: (4, 3) };

    fn errors(text: &str) -> Vec<String> {
        read::<DVec3>(text, EXPECT).unwrap_err().iter().map(ToString::to_string).collect()
    }

    #[test]
    fn a_minimal_document_reads() {
        let doc = read::<DVec3>(
            r#"{"pixel": [1, 2], "ray": {"origin": [0, 0, 0], "direction": [0, 0, -1]}, "colour": [1, 0, 0]}"#,
            EXPECT,
        )
        .unwrap();
        assert_eq!(doc.pixel, [1, 2]);
        assert_eq!(doc.ray.hit, HitField::Absent);
        assert_eq!(doc.colour, Rgb([1.0, 0.0, 0.0]));
    }

    #[test]
    fn every_error_is_named_by_its_path() {
        let text = r#"{"pixel": [9, 2], "color": [1, 0, 0],
            "ray": {"origin": [0, 0], "direction": [0, 0, -1],
                    "hit": {"object": 5, "t": "far"},
                    "lights": [{"n_dot_l": 1}, {"n_dot_l": 1}],
                    "reflected": {"hti": null}}}"#;
        assert_eq!(
            errors(text),
            [
                "color: unknown field `color`; did you mean `colour`?",
                "pixel[0]: 9 is outside the image: must be below 4",
                "ray.hit.object: must be an integer in [0, 1], got 5",
                "ray.hit.t: must be a number, got a string",
                "ray.lights: must have one entry per light of the scene (1), got 2",
                "ray.reflected.hti: unknown field `hti`; did you mean `hit`?",
                "ray.origin: must have 3 numbers, got 2",
                "colour: missing (required)",
            ]
        );
    }

    #[test]
    fn the_primary_ray_needs_its_origin_and_direction() {
        let e = errors(r#"{"pixel": [0, 0], "ray": {}, "colour": [0, 0, 0]}"#);
        assert_eq!(
            e,
            [
                "ray.origin: missing (required for the primary ray)",
                "ray.direction: missing (required for the primary ray)"
            ]
        );
    }
}
