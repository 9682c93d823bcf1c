//! The `objects` section: each object's type, name, material (a name, inline, or the default)
//! and shape. Each object is parsed from its text in turn (`json::parse_deferring`), so a long
//! list never lives as one tree.

use super::dim::LoadDim;
use super::materials;
use super::required_vector;
use super::schema::{geometry, NAME, OBJECT};
use super::ReadFile;
use crate::format::as_written;
use crate::geom::Vector;
use crate::json::reader::{join, positive, suggest, type_name, ReadError, Reader};
use crate::json::{Map, Value};
use crate::lang::{Both, Lang};
use crate::scene::material::Material;
use crate::scene::Object;
use crate::shape::aabox::AaBox;
use crate::shape::plane::Plane;
use crate::shape::sphere::Sphere;
use crate::shape::Shape;

/// The objects (none if the field is absent); an object with an error is left out. Inline
/// materials, and the default material if some object has none, are appended to `materials`.
pub(super) fn read<V: LoadDim>(
    r: &mut Reader,
    v: Option<&Value>,
    source: &str,
    materials: &mut Vec<Material>,
    names: &[String],
    read_file: ReadFile<'_>,
) -> Vec<Object<V>> {
    let Some(v) = v else { return vec![] };
    let Some(items) = v.as_array() else {
        r.err("objects", format!("must be an array, got {}", type_name(v)));
        return vec![];
    };
    let mut default_material: Option<usize> = None;
    let mut out = Vec::new();
    for (i, item) in items.iter().enumerate() {
        let path = format!("objects[{i}]");
        // Each object is parsed from its text here and its tree dropped after (json::parse_deferring).
        let item = match item.parsed() {
            Ok(item) => item,
            Err(e) => {
                // A number out of range is found only now: said as the whole file's syntax error is.
                let e = match item {
                    Value::Deferred(part) => e.within(source, part),
                    _ => e,
                };
                let ReadError { path, problem } = ReadError::syntax(&e);
                r.err(path, problem);
                continue;
            }
        };
        let item = item.as_ref();
        let Some(map) = item.as_object() else {
            r.err(path, format!("must be an object, got {}", type_name(item)));
            continue;
        };
        let Some(ty) = map.get("type").and_then(|t| r.string(t, &join(&path, "type"))) else {
            if !map.contains_key("type") {
                r.err(join(&path, "type"), format!("missing (one of: {})", V::TYPES.join(", ")));
            }
            continue;
        };
        let Some(geometry) = geometry(ty) else {
            let hint = suggest(ty, V::TYPES).map(|s| format!("; did you mean `{s}`?")).unwrap_or_default();
            r.err(
                join(&path, "type"),
                format!("unknown type `{ty}` (one of: {}){hint}", V::TYPES.join(", ")),
            );
            continue;
        };
        let known = [OBJECT, geometry].concat();
        r.fields(item, &path, &known);
        let name = map.get("name").and_then(|n| read_name(r, n, &join(&path, "name")));
        let material = match map.get("material") {
            None => Some(*default_material.get_or_insert_with(|| {
                materials.push(Material::DEFAULT);
                materials.len() - 1
            })),
            Some(Value::String(s)) => match names.iter().position(|n| n == s) {
                Some(k) => Some(k),
                None => {
                    let known: Vec<&str> = names.iter().map(String::as_str).collect();
                    let hint =
                        suggest(s, &known).map(|x| format!("; did you mean `{x}`?")).unwrap_or_default();
                    r.err(join(&path, "material"), format!("unknown material `{s}`{hint}"));
                    None
                }
            },
            Some(inline) => materials::read(r, inline, &join(&path, "material")).map(|m| {
                materials.push(m);
                materials.len() - 1
            }),
        };
        let shape = read_shape::<V>(r, ty, map, &path, read_file);
        if let (Some(shape), Some(material)) = (shape, material) {
            let scale = shape.scale();
            out.push(Object { name, shape, material, scale });
        }
    }
    out
}

/// An object's `name`: one string for every language, or `{"en": …, "ro": …}` with both; no
/// control or bidirectional character in either ([`Reader::name`]).
fn read_name(r: &mut Reader, v: &Value, path: &str) -> Option<Both> {
    match v {
        Value::String(_) => r.name(v, path).map(Both::same),
        Value::Object(_) => {
            let map = r.fields(v, path, NAME)?;
            let en = r.required_name(map, path, Lang::En.code());
            let ro = r.required_name(map, path, Lang::Ro.code());
            Some(Both { en: en?.to_owned(), ro: ro?.to_owned() })
        }
        _ => {
            r.err(path, format!("must be a string or {{\"en\": …, \"ro\": …}}, got {}", type_name(v)));
            None
        }
    }
}

fn read_shape<V: LoadDim>(
    r: &mut Reader,
    ty: &str,
    map: &Map<'_>,
    path: &str,
    read_file: ReadFile<'_>,
) -> Option<Shape<V>> {
    match ty {
        "mesh" => V::mesh(r, map, path, read_file).map(Shape::Mesh),
        "sphere" => {
            let center = required_vector::<V>(r, map, path, "center");
            let radius = r.required(map, path, "radius").and_then(|x| match positive(x) {
                Some(problem) => {
                    r.err(join(path, "radius"), problem);
                    None
                }
                None => Some(x),
            });
            Some(Shape::Sphere(Sphere { center: center?, radius: radius? }))
        }
        "plane" => {
            let point = required_vector::<V>(r, map, path, "point");
            let normal = required_vector::<V>(r, map, path, "normal").and_then(|n| {
                let unit = n.try_unit();
                if unit.is_none() {
                    r.err(join(path, "normal"), "must not be zero");
                }
                unit
            });
            Some(Shape::Plane(Plane { point: point?, normal: normal? }))
        }
        "box" => {
            let min = required_vector::<V>(r, map, path, "min");
            let max = required_vector::<V>(r, map, path, "max");
            let (min, max) = (min?, max?);
            for axis in 0..V::DIM {
                if min[axis] >= max[axis] {
                    let name = ["x", "y", "z"][axis];
                    r.err(
                        join(path, "max"),
                        format!(
                            "must exceed min on every axis, got {name}: min {} ≥ max {}",
                            as_written(min[axis]),
                            as_written(max[axis])
                        ),
                    );
                    return None;
                }
            }
            Some(Shape::Box(AaBox { min, max }))
        }
        _ => V::facet(r, ty, map, path).map(Shape::Facet),
    }
}

/// The `vertices` of a triangle or polygon: between `min` and `max` points.
pub(super) fn vertices<V: Vector>(
    r: &mut Reader,
    map: &Map<'_>,
    path: &str,
    min: usize,
    max: usize,
) -> Option<Vec<V>> {
    let p = join(path, "vertices");
    let Some(v) = map.get("vertices") else {
        r.err(p, "missing (required)");
        return None;
    };
    let Some(items) = v.as_array() else {
        r.err(p, format!("must be an array of points, got {}", type_name(v)));
        return None;
    };
    if items.len() < min || items.len() > max {
        let want = if min == max { format!("exactly {min}") } else { format!("at least {min}") };
        r.err(p, format!("must have {want} points, got {}", items.len()));
        return None;
    }
    let points: Vec<Option<V>> =
        items.iter().enumerate().map(|(i, x)| super::vector(r, x, &format!("{p}[{i}]"))).collect();
    points.into_iter().collect()
}
