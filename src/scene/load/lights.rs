//! The `lights` section: position, intensity (RGB) and attenuation `[c0, c1, c2]` of each.

use super::dim::LoadDim;
use super::materials::optional_rgb;
use super::required_vector;
use super::schema::{DEFAULT_ATTENUATION, DEFAULT_INTENSITY, LIGHT};
use crate::json::reader::{join, non_negative, type_name, Reader};
use crate::json::Value;
use crate::scene::light::Light;

/// The lights (none if the field is absent); a light with an error is left out.
pub(super) fn read<V: LoadDim>(r: &mut Reader, v: Option<&Value>) -> Vec<Light<V>> {
    let Some(v) = v else { return vec![] };
    let Some(items) = v.as_array() else {
        r.err("lights", format!("must be an array, got {}", type_name(v)));
        return vec![];
    };
    let mut out = Vec::new();
    for (i, item) in items.iter().enumerate() {
        let path = format!("lights[{i}]");
        let Some(map) = r.fields(item, &path, LIGHT) else {
            continue;
        };
        if let Some(n) = map.get("name") {
            r.name(n, &join(&path, "name"));
        }
        let position = required_vector::<V>(r, map, &path, "position");
        let intensity = optional_rgb(r, map, &path, "intensity", DEFAULT_INTENSITY);
        let attenuation = match map.get("attenuation") {
            None => DEFAULT_ATTENUATION,
            Some(a) => attenuation(r, a, &join(&path, "attenuation")),
        };
        if let Some(position) = position {
            out.push(Light { position, intensity, attenuation });
        }
    }
    out
}

/// `[c0, c1, c2]`, each ≥ 0 and not all 0.
fn attenuation(r: &mut Reader, a: &Value, p: &str) -> [f64; 3] {
    match a.as_array() {
        Some(cs) if cs.len() == 3 => {
            let mut c = [0.0; 3];
            for (k, x) in cs.iter().enumerate() {
                let q = format!("{p}[{k}]");
                if let Some(x) = r.number(x, &q) {
                    if let Some(problem) = non_negative(x) {
                        r.err(q, problem);
                    }
                    c[k] = x;
                }
            }
            if c.iter().all(|x| *x == 0.0) {
                r.err(p, "must not be all 0 (c0, c1, c2)");
            }
            c
        }
        _ => {
            r.err(p, "must be [c0, c1, c2]");
            DEFAULT_ATTENUATION
        }
    }
}
