//! The `materials` section (named materials, and the inline material of an object) and the
//! colours: a material colour is one number (grey) or RGB in [0, 1]; a light colour is RGB ≥ 0.

use super::schema::{CHECKER, DEFAULT_CHECKER_SIZE, MATERIAL, RADIANCE, REFLECTANCE};
use crate::format::as_written;
use crate::json::reader::{join, non_negative, positive, type_name, unit_interval, Reader};
use crate::json::{Map, Value};
use crate::scene::material::{Checker, Material, Rgb};

/// A colour: an RGB triple, or where `grey` allows it one number for a grey; each channel
/// checked by `range`.
fn color(r: &mut Reader, v: &Value, path: &str, range: (f64, f64), grey: bool) -> Option<Rgb> {
    let form = if grey { "one number or 3 numbers (RGB)" } else { "3 numbers (RGB)" };
    let rgb = if let Some(items) = v.as_array() {
        if items.len() != 3 {
            r.err(path, format!("must be {form}, got {}", items.len()));
            return None;
        }
        let mut c = [0.0; 3];
        for (i, item) in items.iter().enumerate() {
            c[i] = r.number(item, &format!("{path}[{i}]"))?;
        }
        c
    } else if grey && v.is_number() {
        [r.number(v, path)?; 3]
    } else {
        let got = v.as_f64().map_or_else(|| type_name(v).to_owned(), as_written);
        r.err(path, format!("must be {form}, got {got}"));
        return None;
    };
    for x in rgb {
        if x < range.0 || x > range.1 {
            let bounds = if range.1.is_finite() {
                format!("in [{}, {}]", as_written(range.0), as_written(range.1))
            } else {
                format!("≥ {}", as_written(range.0))
            };
            r.err(path, format!("every channel must be {bounds}, got {}", as_written(x)));
            return None;
        }
    }
    Some(Rgb(rgb))
}

/// A material colour (`ka`, `kd`, `kd2`, `ka2`): one number for a grey, or an RGB triple.
fn optional_color(r: &mut Reader, map: &Map<'_>, path: &str, key: &str, default: Rgb) -> Rgb {
    map.get(key).and_then(|v| color(r, v, &join(path, key), REFLECTANCE, true)).unwrap_or(default)
}

/// A light's colour (`background`, `ambient`, `intensity`): an RGB triple only. product.md lets
/// one number stand for a grey in the material colours alone.
pub(super) fn optional_rgb(r: &mut Reader, map: &Map<'_>, path: &str, key: &str, default: Rgb) -> Rgb {
    map.get(key).and_then(|v| color(r, v, &join(path, key), RADIANCE, false)).unwrap_or(default)
}

/// A material at `path`, its defaults `Material::DEFAULT`.
pub(super) fn read(r: &mut Reader, v: &Value, path: &str) -> Option<Material> {
    let map = r.fields(v, path, MATERIAL)?;
    let d = Material::DEFAULT;
    let ka = optional_color(r, map, path, "ka", d.ka);
    let kd = optional_color(r, map, path, "kd", d.kd);
    let ks = r.optional(map, path, "ks", d.ks, unit_interval);
    let n = r.optional(map, path, "n", d.n, non_negative);
    let kt = r.optional(map, path, "kt", d.kt, unit_interval);
    let ior = r.optional(map, path, "ior", d.ior, positive);
    let checker = match map.get("checker") {
        None => None,
        Some(c) => {
            let p = join(path, "checker");
            let cm = r.fields(c, &p, CHECKER)?;
            let size = r.optional(cm, &p, "size", DEFAULT_CHECKER_SIZE, positive);
            let kd2 = match cm.get("kd2") {
                Some(x) => color(r, x, &join(&p, "kd2"), REFLECTANCE, true),
                None => {
                    r.err(join(&p, "kd2"), "missing (required)");
                    None
                }
            };
            let ka2 = optional_color(r, cm, &p, "ka2", ka);
            Some(Checker { size, kd2: kd2?, ka2 })
        }
    };
    Some(Material { ka, kd, ks, n, kt, ior, checker })
}

/// The named materials of `materials`, in file order, with their names.
pub(super) fn read_named(r: &mut Reader, v: Option<&Value>) -> (Vec<Material>, Vec<String>) {
    let Some(v) = v else { return (vec![], vec![]) };
    let Some(map) = v.as_object() else {
        r.err("materials", format!("must be an object of named materials, got {}", type_name(v)));
        return (vec![], vec![]);
    };
    let mut mats = Vec::new();
    let mut names = Vec::new();
    for (name, m) in map {
        r.name_text(name, &format!("materials.{name}"));
        let m = read(r, m, &format!("materials.{name}")).unwrap_or(Material::DEFAULT);
        mats.push(m);
        names.push(name.to_owned());
    }
    (mats, names)
}
