//! Scene text → [`AnyScene`] (product.md "Scene files" and "Defaults"; algorithm.md §11
//! "Validation instead of sanitising"). The JSON is parsed into a `json::Value` (duplicate keys
//! kept, so reported) and read field by field with the all-errors [`Reader`], so unknown fields,
//! wrong types, wrong dimensions and invalid values are all reported together, each with its JSON
//! path; a JSON syntax error stops at the first (line and column). Defaults are applied here and
//! nowhere else.
//!
//! [`schema`] holds the fields, limits and defaults on one screen; the sections read the parts:
//! [`camera`] (eye, frame, window, resolution), [`lights`], [`materials`] (with the colours),
//! [`objects`] (types, names, materials, shapes); `dim` says what differs between 2D and 3D.
//!
//! `load_str_with` takes a `ReadFile` closure for the files a scene names (a mesh's OBJ), so the
//! library reads no file itself; `build` and the point `vector` are shared by the sections.

mod camera;
mod dim;
mod lights;
mod materials;
mod objects;
pub mod schema;

pub use schema::{MAX_DEPTH, MAX_MAGNITUDE, MAX_OBJ_BYTES, MAX_RESOLUTION, MAX_SCENE_BYTES};

use super::{AnyScene, Scene};
use crate::geom::Vector;
use crate::json::reader::{join, type_name, ReadError, Reader};
use crate::json::{self, Map, Value};
use dim::LoadDim;
use glam::{DVec2, DVec3};
use schema::{DEFAULT_AMBIENT, DEFAULT_BACKGROUND, DEFAULT_MAX_DEPTH, TOP};

/// How the loader gets the text of a file a scene names (a mesh's OBJ), from its caller: the
/// library reads no files. The name is as the scene writes it; the error is a reason.
pub type ReadFile<'a> = &'a dyn Fn(&str) -> Result<String, String>;

/// Parse and validate a scene that names no file (a `mesh` is an error here).
///
/// # Errors
/// Every problem found, each naming its JSON path; a syntax error alone if the text is not JSON.
pub fn load_str(text: &str) -> Result<AnyScene, Vec<ReadError>> {
    load_str_with(text, &|_| Err("this scene was given as text, with no folder to read files from".into()))
}

/// Parse and validate a scene, reading the files it names (a mesh's OBJ) through `read_file`.
///
/// # Errors
/// Every problem found, each naming its JSON path; a syntax error alone if the text is not JSON.
pub fn load_str_with(text: &str, read_file: ReadFile<'_>) -> Result<AnyScene, Vec<ReadError>> {
    let root = json::parse_deferring(text, "objects").map_err(|e| vec![ReadError::syntax(&e)])?;
    let mut r = Reader::default();
    let Some(top) = r.fields(&root, "", TOP) else {
        return Err(r.into_errors());
    };
    let Some(camera) = top.get("camera") else {
        r.err("camera", "missing (required: eye, center, window, resolution)");
        return Err(r.into_errors());
    };
    match dimension_of(camera) {
        Some(2) => build::<DVec2>(r, top, text, read_file).map(AnyScene::Flat),
        Some(3) => build::<DVec3>(r, top, text, read_file).map(AnyScene::Space),
        _ => {
            r.err("camera.eye", "must be a point of 2 numbers (a 2D scene) or 3 numbers (a 3D scene)");
            Err(r.into_errors())
        }
    }
}

/// The dimension a camera's `eye` (or `center`) decides.
fn dimension_of(camera: &Value) -> Option<usize> {
    ["eye", "center"]
        .iter()
        .filter_map(|k| camera.get(k)?.as_array().map(Vec::len))
        .find(|n| *n == 2 || *n == 3)
}

fn build<V: LoadDim>(
    mut r: Reader,
    top: &Map<'_>,
    source: &str,
    read_file: ReadFile<'_>,
) -> Result<Scene<V>, Vec<ReadError>> {
    let camera = camera::read::<V>(&mut r, &top["camera"]);
    let background = materials::optional_rgb(&mut r, top, "", "background", DEFAULT_BACKGROUND);
    let ambient = materials::optional_rgb(&mut r, top, "", "ambient", DEFAULT_AMBIENT);
    let max_depth = match top.get("max_depth") {
        Some(v) => r.integer(v, "max_depth", 0, MAX_DEPTH).unwrap_or(0),
        None => DEFAULT_MAX_DEPTH,
    };
    let lights = lights::read::<V>(&mut r, top.get("lights"));
    let (mut materials, names) = materials::read_named(&mut r, top.get("materials"));
    let objects = objects::read::<V>(&mut r, top.get("objects"), source, &mut materials, &names, read_file);
    let scene = camera.map(|camera| Scene {
        camera,
        background,
        ambient,
        max_depth: u32::try_from(max_depth).unwrap_or(0),
        lights,
        materials,
        objects,
    });
    r.finish(scene)
}

/// A point or direction of the scene's dimension: `V::DIM` numbers.
fn vector<V: Vector>(r: &mut Reader, v: &Value, path: &str) -> Option<V> {
    let Some(items) = v.as_array() else {
        r.err(path, format!("must be an array of {} numbers, got {}", V::DIM, type_name(v)));
        return None;
    };
    if items.len() != V::DIM {
        r.err(
            path,
            format!(
                "must have {} numbers (a {}D scene, as the camera says), got {}",
                V::DIM,
                V::DIM,
                items.len()
            ),
        );
        return None;
    }
    let mut out = V::ZERO;
    let mut ok = true;
    for (i, item) in items.iter().enumerate() {
        match r.number(item, &format!("{path}[{i}]")) {
            Some(x) => out[i] = x,
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// A required [`vector`] `key` of `map`.
fn required_vector<V: Vector>(r: &mut Reader, map: &Map<'_>, path: &str, key: &str) -> Option<V> {
    match map.get(key) {
        Some(v) => vector(r, v, &join(path, key)),
        None => {
            r.err(join(path, key), "missing (required)");
            None
        }
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::scene::camera::Projection;
    use crate::scene::material::Rgb;
    use crate::shape::Shape;

    fn errors(text: &str) -> Vec<String> {
        match load_str(text) {
            Ok(_) => vec![],
            Err(e) => e.iter().map(ToString::to_string).collect(),
        }
    }

    const CAM: &str = r#""camera": {"eye": [0,0,5], "center": [0,0,0], "window": {"l":-1,"r":1,"b":-1,"t":1}, "resolution": [4,3]}"#;

    #[test]
    fn minimal_scene_gets_the_defaults() {
        let AnyScene::Space(s) = load_str(&format!("{{{CAM}}}")).unwrap() else { panic!() };
        assert_eq!(s.max_depth, 5);
        assert_eq!(s.background, Rgb::BLACK);
        assert_eq!(s.ambient, Rgb::grey(1.0));
        assert_eq!(s.camera.projection, Projection::Perspective);
        assert_eq!((s.camera.nx, s.camera.ny), (4, 3));
    }

    #[test]
    fn every_error_at_once_with_its_path() {
        let text = format!(
            r#"{{{CAM}, "objects": [
              {{"type": "sphere", "center": [0,0], "radius": -1}},
              {{"type": "sphere", "center": [0,0,0], "radus": 1}},
              {{"type": "box", "min": [0,0,0], "max": [1,1,1], "material": "glas"}}
            ], "materials": {{"glass": {{"ior": 0, "kt": 2}}}}}}"#
        );
        let e = errors(&text);
        assert!(
            e.contains(
                &"objects[0].center: must have 3 numbers (a 3D scene, as the camera says), got 2".into()
            ),
            "{e:?}"
        );
        assert!(e.contains(&"objects[0].radius: must be > 0, got -1".into()), "{e:?}");
        assert!(
            e.iter()
                .any(|x| x.starts_with("objects[1].radus: unknown field `radus`; did you mean `radius`?")),
            "{e:?}"
        );
        assert!(
            e.iter().any(|x| x.starts_with(
                "objects[2].material: unknown material `glas`; did you mean `glass`?"
            )),
            "{e:?}"
        );
        assert!(e.contains(&"materials.glass.ior: must be > 0, got 0".into()), "{e:?}");
        assert!(e.contains(&"materials.glass.kt: must be in [0, 1], got 2".into()), "{e:?}");
    }

    #[test]
    fn a_grey_number_is_a_material_colour_only() {
        // product.md: `ka`, `kd`, `kd2`, `ka2` take one number (grey) or RGB; the light colours
        // (`background`, `ambient`, `intensity`) are RGB triples.
        let text = format!(
            r#"{{{CAM}, "background": 0.2, "ambient": [0.1, 0.1, 0.1],
                "lights": [{{"position": [0, 5, 0], "intensity": 1}}],
                "objects": [{{"type": "plane", "point": [0,0,0], "normal": [0,1,0],
                  "material": {{"ka": 0.1, "kd": 0.5, "checker": {{"kd2": 0.2, "ka2": 0}}}}}}]}}"#
        );
        let e = errors(&text);
        assert_eq!(
            e,
            vec![
                "background: must be 3 numbers (RGB), got 0.2".to_owned(),
                "lights[0].intensity: must be 3 numbers (RGB), got 1".to_owned(),
            ]
        );
        // A list of the wrong length is told the form its field takes.
        let text = format!(
            r#"{{{CAM}, "ambient": [0.1, 0.1],
                "objects": [{{"type": "plane", "point": [0,0,0], "normal": [0,1,0],
                  "material": {{"kd": [0.5, 0.5]}}}}]}}"#
        );
        assert_eq!(
            errors(&text),
            vec![
                "ambient: must be 3 numbers (RGB), got 2".to_owned(),
                "objects[0].material.kd: must be one number or 3 numbers (RGB), got 2".to_owned(),
            ]
        );
    }

    #[test]
    fn json_syntax_error_has_line_and_column() {
        let e = errors("{\n  \"camera\": ,\n}");
        assert_eq!(e.len(), 1);
        assert!(e[0].starts_with("invalid JSON at line 2, column"), "{e:?}");
    }

    #[test]
    fn camera_errors() {
        let e = errors(
            r#"{"camera": {"eye": [0,0,5], "center": [0,0,0], "up": [0,0,1], "window": {"l":1,"r":1,"b":-1,"t":1}, "resolution": [0,3]}}"#,
        );
        assert!(e.iter().any(|x| x.starts_with("camera.up: parallel")), "{e:?}");
        assert!(e.iter().any(|x| x.starts_with("camera.window: r must be > l")), "{e:?}");
        assert!(e.contains(&"camera.resolution[0]: must be an integer in [1, 65536], got 0".into()), "{e:?}");
        let e = errors(
            r#"{"camera": {"eye": [0,0,5], "center": [0,0,5], "window": {"l":-1,"r":1,"b":-1,"t":1}, "resolution": [2,2], "p": 0}}"#,
        );
        assert!(e.iter().any(|x| x.starts_with("camera.center: must differ")), "{e:?}");
        assert!(e.contains(&"camera.p: must be > 0, got 0".into()), "{e:?}");
    }

    #[test]
    fn two_d_scene_and_its_primitives() {
        let text = r#"{"camera": {"eye": [0, 5], "center": [0, 0], "window": {"l": -1, "r": 1}, "resolution": [8]},
            "objects": [{"type": "segment", "a": [0,0], "b": [1,0]},
                        {"type": "polygon", "vertices": [[0,0],[1,0],[1,1],[0,1]]},
                        {"type": "triangle", "vertices": [[0,0],[1,0],[2,0]]}]}"#;
        let e = errors(text);
        assert_eq!(e, vec!["objects[2].vertices: zero-area triangle".to_string()]);
    }

    #[test]
    fn meshes_are_read_through_the_caller_and_errors_name_file_and_line() {
        let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n";
        let read =
            |name: &str| if name == "tri.obj" { Ok(obj.to_string()) } else { Err("not found".to_string()) };
        let text = format!(
            r#"{{{CAM}, "objects": [{{"type": "mesh", "obj": "tri.obj", "name": "m", "material": {{"kd": 0.5}}}}]}}"#
        );
        let AnyScene::Space(s) = load_str_with(&text, &read).unwrap() else { panic!() };
        let Shape::Mesh(m) = &s.objects[0].shape else { panic!() };
        use crate::shape::Parts;
        assert_eq!((m.count(), m.skipped()), (1, 1));
        let e = load_str_with(&text.replace("tri.obj", "gone.obj"), &read).unwrap_err();
        assert_eq!(e[0].to_string(), "objects[0].obj: cannot read `gone.obj`: not found");
        let bad = |_: &str| Ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n".to_string());
        let e = load_str_with(&text, &bad).unwrap_err();
        assert!(e[0].to_string().starts_with("objects[0].obj: tri.obj line 4: "), "{e:?}");
        assert!(load_str(&text).is_err(), "load_str reads no file");
        let flat = r#"{"camera": {"eye": [0, 5], "center": [0, 0], "window": {"l": -1, "r": 1}, "resolution": [8]},
            "objects": [{"type": "mesh", "obj": "tri.obj"}]}"#;
        assert_eq!(
            errors_with(flat, &read),
            vec!["objects[0].type: `mesh` exists only in 3D scenes".to_string()]
        );
    }

    fn errors_with(text: &str, read: ReadFile<'_>) -> Vec<String> {
        match load_str_with(text, read) {
            Ok(_) => vec![],
            Err(e) => e.iter().map(ToString::to_string).collect(),
        }
    }

    #[test]
    fn a_name_is_one_string_or_one_per_language() {
        use crate::lang::{Both, Lang};
        let text = format!(
            r#"{{{CAM}, "objects": [
              {{"type": "sphere", "center": [0,0,0], "radius": 1, "name": {{"en": "mirror", "ro": "oglindă"}}}},
              {{"type": "sphere", "center": [0,0,0], "radius": 1, "name": "A"}}]}}"#
        );
        let AnyScene::Space(s) = load_str(&text).unwrap() else { panic!() };
        assert_eq!(s.objects[0].name, Some(Both { en: "mirror".into(), ro: "oglindă".into() }));
        assert_eq!(s.object_label(0, Lang::Ro), "oglindă");
        assert_eq!(s.object_label(0, Lang::En), "mirror");
        assert_eq!(s.object_label(1, Lang::Ro), "A");
        let text = format!(
            r#"{{{CAM}, "objects": [
              {{"type": "sphere", "center": [0,0,0], "radius": 1, "name": {{"en": "mirror"}}}},
              {{"type": "sphere", "center": [0,0,0], "radius": 1, "name": {{"en": "a", "ro": "a", "fr": "a"}}}},
              {{"type": "sphere", "center": [0,0,0], "radius": 1, "name": {{"en": "a", "ro": 2}}}},
              {{"type": "sphere", "center": [0,0,0], "radius": 1, "name": 3}}]}}"#
        );
        assert_eq!(
            errors(&text),
            vec![
                "objects[0].name.ro: missing (required)".to_owned(),
                "objects[1].name.fr: unknown field `fr`; expected one of: en, ro".to_owned(),
                "objects[2].name.ro: must be a string, got a number".to_owned(),
                "objects[3].name: must be a string or {\"en\": …, \"ro\": …}, got a number".to_owned(),
            ]
        );
    }

    #[test]
    fn degenerate_triangle_and_zero_normal() {
        let text = format!(
            r#"{{{CAM}, "objects": [{{"type": "triangle", "vertices": [[0,0,0],[1,0,0],[2,0,0]]}},
               {{"type": "plane", "point": [0,0,0], "normal": [0,0,0]}}]}}"#
        );
        let e = errors(&text);
        assert!(e.contains(&"objects[0].vertices: zero-area triangle".into()), "{e:?}");
        assert!(e.contains(&"objects[1].normal: must not be zero".into()), "{e:?}");
    }
}
