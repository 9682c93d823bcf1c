//! Scene text → [`AnyScene`] (product.md "Scene files" and "Defaults"; algorithm.md §11
//! "Validation instead of sanitising"). The JSON is parsed into a `json::Value` (duplicate keys kept, so reported) and read
//! field by field, so unknown fields, wrong types, wrong dimensions and invalid values are all
//! reported together, each with its JSON path; a JSON syntax error stops at the first (line and
//! column). Defaults are applied here and nowhere else.

use super::camera::{Camera, Projection, Window};
use super::error::{suggest, SceneError};
use super::light::Light;
use super::material::{Checker, Material, Rgb};
use super::{AnyScene, Object, Scene};
use crate::geom::frame::{self, Frame, FrameError};
use crate::geom::Vector;
use crate::json::{self, Map, Value};
use crate::shape::aabox::AaBox;
use crate::shape::mesh::{parse_obj, Mesh, MeshError};
use crate::shape::plane::Plane;
use crate::shape::polygon::{Polygon, PolygonError};
use crate::shape::sphere::Sphere;
use crate::shape::triangle::Triangle;
use crate::shape::{Dim, Shape};
use glam::{DVec2, DVec3};

/// The largest magnitude a scene number may have (§11): squares and triple sums stay finite.
pub const MAX_MAGNITUDE: f64 = 1e100;
/// The largest `max_depth` (§11); deeper trees would only multiply weights below any pixel step.
pub const MAX_DEPTH: u64 = 64;
/// The largest resolution along one axis (documented cap: 65 536 pixels).
pub const MAX_RESOLUTION: u64 = 1 << 16;
/// The largest scene file read (128 MiB, about a million objects written out).
pub const MAX_SCENE_BYTES: u64 = 128 << 20;
/// The largest mesh (OBJ) file read (512 MiB, about ten million triangles).
pub const MAX_OBJ_BYTES: u64 = 512 << 20;

const TOP: &[&str] =
    &["camera", "background", "ambient", "max_depth", "lights", "materials", "objects", "description"];
const CAMERA_3D: &[&str] = &["eye", "center", "up", "projection", "p", "window", "resolution"];
const CAMERA_2D: &[&str] = &["eye", "center", "projection", "p", "window", "resolution"];
const WINDOW_3D: &[&str] = &["l", "r", "b", "t"];
const WINDOW_2D: &[&str] = &["l", "r"];
const LIGHT: &[&str] = &["position", "intensity", "attenuation", "name"];
const MATERIAL: &[&str] = &["ka", "kd", "ks", "n", "kt", "ior", "checker"];
const CHECKER: &[&str] = &["size", "kd2", "ka2"];
const TYPES_3D: &[&str] = &["sphere", "plane", "box", "triangle", "mesh"];
const TYPES_2D: &[&str] = &["sphere", "plane", "box", "triangle", "segment", "polygon"];

/// How the loader gets the text of a file a scene names (a mesh's OBJ), from its caller: the
/// library reads no files. The name is as the scene writes it; the error is a reason.
pub type ReadFile<'a> = &'a dyn Fn(&str) -> Result<String, String>;

/// Parse and validate a scene that names no file (a `mesh` is an error here).
///
/// # Errors
/// Every problem found, each naming its JSON path; a syntax error alone if the text is not JSON.
pub fn load_str(text: &str) -> Result<AnyScene, Vec<SceneError>> {
    load_str_with(text, &|_| Err("this scene was given as text, with no folder to read files from".into()))
}

/// Parse and validate a scene, reading the files it names (a mesh's OBJ) through `read_file`.
///
/// # Errors
/// Every problem found, each naming its JSON path; a syntax error alone if the text is not JSON.
pub fn load_str_with(text: &str, read_file: ReadFile<'_>) -> Result<AnyScene, Vec<SceneError>> {
    let root = json::parse(text).map_err(|e| {
        vec![SceneError::new(
            "",
            format!("invalid JSON at line {}, column {}: {}", e.line, e.column, e.message),
        )]
    })?;
    let mut r = Reader::default();
    let Some(top) = r.fields(&root, "", TOP) else {
        return Err(r.errors);
    };
    let Some(camera) = top.get("camera") else {
        r.err("camera", "missing (required: eye, center, window, resolution)");
        return Err(r.errors);
    };
    match dimension_of(camera) {
        Some(2) => build::<DVec2>(r, top, read_file).map(AnyScene::Flat),
        Some(3) => build::<DVec3>(r, top, read_file).map(AnyScene::Space),
        _ => {
            r.err("camera.eye", "must be a point of 2 numbers (a 2D scene) or 3 numbers (a 3D scene)");
            Err(r.errors)
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

/// Collects errors while reading `Value`s.
#[derive(Default)]
struct Reader {
    errors: Vec<SceneError>,
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

fn type_name(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Formats a number as a person wrote it (`-1`, `0.5`).
fn num(x: f64) -> String {
    if x != 0.0 && !(1e-5..1e16).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

impl Reader {
    fn err(&mut self, path: impl Into<String>, problem: impl Into<String>) {
        self.errors.push(SceneError::new(path, problem));
    }

    /// An object whose keys are all in `known`; unknown keys are errors with a suggestion.
    /// A key written twice is an error too: which of its values a reader took would be a guess.
    fn fields<'a, 'j>(&mut self, v: &'a Value<'j>, path: &str, known: &[&str]) -> Option<&'a Map<'j>> {
        let Some(map) = v.as_object() else {
            self.err(path, format!("must be an object, got {}", type_name(v)));
            return None;
        };
        for key in map.duplicates() {
            self.err(join(path, key), "written more than once in this object; keep one");
        }
        for key in map.keys() {
            if !known.contains(&key) {
                let hint = match suggest(key, known) {
                    Some(s) => format!("unknown field `{key}`; did you mean `{s}`?"),
                    None => format!("unknown field `{key}`; expected one of: {}", known.join(", ")),
                };
                self.err(join(path, key), hint);
            }
        }
        Some(map)
    }

    fn number(&mut self, v: &Value, path: &str) -> Option<f64> {
        let Some(x) = v.as_f64() else {
            self.err(path, format!("must be a number, got {}", type_name(v)));
            return None;
        };
        if !x.is_finite() || x.abs() > MAX_MAGNITUDE {
            self.err(path, format!("must be at most {MAX_MAGNITUDE:e} in magnitude, got {}", num(x)));
            return None;
        }
        Some(x)
    }

    /// A required number.
    fn required(&mut self, map: &Map<'_>, path: &str, key: &str) -> Option<f64> {
        match map.get(key) {
            Some(v) => self.number(v, &join(path, key)),
            None => {
                self.err(join(path, key), "missing (required)");
                None
            }
        }
    }

    /// An optional number with its default; `check` returns the problem text, if any.
    fn optional(
        &mut self,
        map: &Map<'_>,
        path: &str,
        key: &str,
        default: f64,
        check: impl Fn(f64) -> Option<String>,
    ) -> f64 {
        let Some(v) = map.get(key) else {
            return default;
        };
        let p = join(path, key);
        match self.number(v, &p) {
            Some(x) => match check(x) {
                Some(problem) => {
                    self.err(p, problem);
                    default
                }
                None => x,
            },
            None => default,
        }
    }

    fn vector<V: Vector>(&mut self, v: &Value, path: &str) -> Option<V> {
        let Some(items) = v.as_array() else {
            self.err(path, format!("must be an array of {} numbers, got {}", V::DIM, type_name(v)));
            return None;
        };
        if items.len() != V::DIM {
            self.err(
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
            match self.number(item, &format!("{path}[{i}]")) {
                Some(x) => out[i] = x,
                None => ok = false,
            }
        }
        ok.then_some(out)
    }

    fn required_vector<V: Vector>(&mut self, map: &Map<'_>, path: &str, key: &str) -> Option<V> {
        match map.get(key) {
            Some(v) => self.vector(v, &join(path, key)),
            None => {
                self.err(join(path, key), "missing (required)");
                None
            }
        }
    }

    /// A colour: an RGB triple, or where `grey` allows it one number for a grey; each channel
    /// checked by `range`.
    fn color(&mut self, v: &Value, path: &str, range: (f64, f64), grey: bool) -> Option<Rgb> {
        let form = if grey { "one number or 3 numbers (RGB)" } else { "3 numbers (RGB)" };
        let rgb = if let Some(items) = v.as_array() {
            if items.len() != 3 {
                self.err(path, format!("must be {form}, got {}", items.len()));
                return None;
            }
            let mut c = [0.0; 3];
            for (i, item) in items.iter().enumerate() {
                c[i] = self.number(item, &format!("{path}[{i}]"))?;
            }
            c
        } else if grey && v.is_number() {
            [self.number(v, path)?; 3]
        } else {
            let got = v.as_f64().map_or_else(|| type_name(v).to_owned(), num);
            self.err(path, format!("must be {form}, got {got}"));
            return None;
        };
        for x in rgb {
            if x < range.0 || x > range.1 {
                let bounds = if range.1.is_finite() {
                    format!("in [{}, {}]", num(range.0), num(range.1))
                } else {
                    format!("≥ {}", num(range.0))
                };
                self.err(path, format!("every channel must be {bounds}, got {}", num(x)));
                return None;
            }
        }
        Some(Rgb(rgb))
    }

    /// A material colour (`ka`, `kd`, `kd2`, `ka2`): one number for a grey, or an RGB triple.
    fn optional_color(
        &mut self,
        map: &Map<'_>,
        path: &str,
        key: &str,
        default: Rgb,
        range: (f64, f64),
    ) -> Rgb {
        map.get(key).and_then(|v| self.color(v, &join(path, key), range, true)).unwrap_or(default)
    }

    /// A light's colour (`background`, `ambient`, `intensity`): an RGB triple only. product.md lets
    /// one number stand for a grey in the material colours alone.
    fn optional_rgb(&mut self, map: &Map<'_>, path: &str, key: &str, default: Rgb) -> Rgb {
        map.get(key)
            .and_then(|v| self.color(v, &join(path, key), (0.0, f64::INFINITY), false))
            .unwrap_or(default)
    }

    fn integer(&mut self, v: &Value, path: &str, min: u64, max: u64) -> Option<u64> {
        let Some(n) = v.as_u64() else {
            let got = match v.as_f64() {
                Some(x) => num(x),
                None => type_name(v).to_string(),
            };
            self.err(path, format!("must be an integer in [{min}, {max}], got {got}"));
            return None;
        };
        if n < min || n > max {
            self.err(path, format!("must be an integer in [{min}, {max}], got {n}"));
            return None;
        }
        Some(n)
    }

    fn string<'a>(&mut self, v: &'a Value, path: &str) -> Option<&'a str> {
        let s = v.as_str();
        if s.is_none() {
            self.err(path, format!("must be a string, got {}", type_name(v)));
        }
        s
    }
}

fn positive(x: f64) -> Option<String> {
    (x <= 0.0).then(|| format!("must be > 0, got {}", num(x)))
}

fn unit_interval(x: f64) -> Option<String> {
    (!(0.0..=1.0).contains(&x)).then(|| format!("must be in [0, 1], got {}", num(x)))
}

fn non_negative(x: f64) -> Option<String> {
    (x < 0.0).then(|| format!("must be ≥ 0, got {}", num(x)))
}

/// What differs between 2D and 3D when reading a scene.
trait LoadDim: Dim {
    const CAMERA: &'static [&'static str];
    const WINDOW: &'static [&'static str];
    const TYPES: &'static [&'static str];
    /// The observer frame from eye, centre and (in 3D) `up`.
    fn frame(r: &mut Reader, camera: &Map<'_>, eye: Self, center: Self) -> Option<Frame<Self>>;
    /// The flat primitive of an object of the given type.
    fn facet(r: &mut Reader, ty: &str, map: &Map<'_>, path: &str) -> Option<Self::Facet>;
    /// `Ny` from the resolution array.
    fn rows(r: &mut Reader, res: &[Value], path: &str) -> Option<usize>;
    /// A `mesh` object (3D only).
    fn mesh(r: &mut Reader, map: &Map<'_>, path: &str, read_file: ReadFile<'_>) -> Option<Self::Mesh>;
}

fn frame_error(r: &mut Reader, e: FrameError) {
    match e {
        FrameError::EyeIsCenter => r.err("camera.center", "must differ from camera.eye"),
        FrameError::UpParallel => r.err("camera.up", "parallel to eye − center (or zero): no camera frame"),
    }
}

impl LoadDim for DVec3 {
    const CAMERA: &'static [&'static str] = CAMERA_3D;
    const WINDOW: &'static [&'static str] = WINDOW_3D;
    const TYPES: &'static [&'static str] = TYPES_3D;
    fn frame(r: &mut Reader, camera: &Map<'_>, eye: Self, center: Self) -> Option<Frame<Self>> {
        let up = match camera.get("up") {
            Some(v) => r.vector::<DVec3>(v, "camera.up")?,
            None => DVec3::Y,
        };
        frame::look_at(eye, center, up).map_err(|e| frame_error(r, e)).ok()
    }
    fn facet(r: &mut Reader, ty: &str, map: &Map<'_>, path: &str) -> Option<Triangle> {
        if ty != "triangle" {
            r.err(join(path, "type"), format!("`{ty}` exists only in 2D scenes"));
            return None;
        }
        let vs = vertices::<DVec3>(r, map, path, 3, 3)?;
        let t = Triangle::new(vs[0], vs[1], vs[2]);
        if t.is_none() {
            r.err(join(path, "vertices"), "zero-area triangle");
        }
        t
    }
    fn rows(r: &mut Reader, res: &[Value], path: &str) -> Option<usize> {
        if res.len() != 2 {
            r.err(path, format!("must be [Nx, Ny] in a 3D scene, got {} numbers", res.len()));
            return None;
        }
        resolution_axis(r, &res[1], &format!("{path}[1]"))
    }
    fn mesh(r: &mut Reader, map: &Map<'_>, path: &str, read_file: ReadFile<'_>) -> Option<Mesh> {
        let p = join(path, "obj");
        let Some(v) = map.get("obj") else {
            r.err(p, "missing (required: the OBJ file, relative to the scene file)");
            return None;
        };
        let name = r.string(v, &p)?;
        let text = match read_file(name) {
            Ok(t) => t,
            Err(e) => {
                r.err(p, format!("cannot read `{name}`: {e}"));
                return None;
            }
        };
        let (vertices, faces) = match parse_obj(&text, MAX_MAGNITUDE) {
            Ok(x) => x,
            Err(e) => {
                let at = e.line.map(|l| format!(" line {l}")).unwrap_or_default();
                r.err(p, format!("{name}{at}: {}", e.problem));
                return None;
            }
        };
        match Mesh::new(vertices, &faces) {
            Ok(m) => Some(m),
            Err(e) => {
                let problem = match e {
                    MeshError::VertexOutOfRange { face } => {
                        format!("triangle {face} names a vertex that does not exist")
                    }
                    MeshError::NoTriangles { skipped: 0 } => "contains no triangles".into(),
                    MeshError::NoTriangles { skipped } => format!("all {skipped} triangles have zero area"),
                    MeshError::TooLarge => "more than 2^32 − 1 vertices or triangles".into(),
                };
                r.err(p, format!("{name}: {problem}"));
                None
            }
        }
    }
}

impl LoadDim for DVec2 {
    const CAMERA: &'static [&'static str] = CAMERA_2D;
    const WINDOW: &'static [&'static str] = WINDOW_2D;
    const TYPES: &'static [&'static str] = TYPES_2D;
    fn frame(r: &mut Reader, _camera: &Map<'_>, eye: Self, center: Self) -> Option<Frame<Self>> {
        frame::look_at_2d(eye, center).map_err(|e| frame_error(r, e)).ok()
    }
    fn facet(r: &mut Reader, ty: &str, map: &Map<'_>, path: &str) -> Option<Polygon> {
        let built = match ty {
            "segment" => {
                let a = r.required_vector::<DVec2>(map, path, "a");
                let b = r.required_vector::<DVec2>(map, path, "b");
                Polygon::segment(a?, b?)
            }
            "triangle" => Polygon::closed(vertices::<DVec2>(r, map, path, 3, 3)?),
            _ => Polygon::closed(vertices::<DVec2>(r, map, path, 3, usize::MAX)?),
        };
        let at = if ty == "segment" { join(path, "b") } else { join(path, "vertices") };
        built
            .map_err(|e| match e {
                PolygonError::ZeroLength if ty == "segment" => r.err(at, "zero-length segment (a = b)"),
                PolygonError::ZeroLength => r.err(at, "two consecutive vertices coincide"),
                PolygonError::ZeroArea => r.err(at, format!("zero-area {ty}")),
                PolygonError::NotSimple => r.err(at, "edges cross: the polygon must be simple"),
            })
            .ok()
    }
    fn rows(r: &mut Reader, res: &[Value], path: &str) -> Option<usize> {
        if res.len() != 1 {
            r.err(path, format!("must be [Nx] in a 2D scene, got {} numbers", res.len()));
            return None;
        }
        Some(1)
    }
    fn mesh(r: &mut Reader, _: &Map<'_>, path: &str, _: ReadFile<'_>) -> Option<Self::Mesh> {
        r.err(join(path, "type"), "`mesh` exists only in 3D scenes");
        None
    }
}

fn resolution_axis(r: &mut Reader, v: &Value, path: &str) -> Option<usize> {
    r.integer(v, path, 1, MAX_RESOLUTION).and_then(|n| usize::try_from(n).ok())
}

fn vertices<V: Vector>(r: &mut Reader, map: &Map<'_>, path: &str, min: usize, max: usize) -> Option<Vec<V>> {
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
        items.iter().enumerate().map(|(i, x)| r.vector(x, &format!("{p}[{i}]"))).collect();
    points.into_iter().collect()
}

fn build<V: LoadDim>(
    mut r: Reader,
    top: &Map<'_>,
    read_file: ReadFile<'_>,
) -> Result<Scene<V>, Vec<SceneError>> {
    let camera = read_camera::<V>(&mut r, &top["camera"]);
    let background = r.optional_rgb(top, "", "background", Rgb::BLACK);
    let ambient = r.optional_rgb(top, "", "ambient", Rgb::grey(1.0));
    let max_depth = match top.get("max_depth") {
        Some(v) => r.integer(v, "max_depth", 0, MAX_DEPTH).unwrap_or(0),
        None => 5,
    };
    let lights = read_lights::<V>(&mut r, top.get("lights"));
    let (mut materials, names) = read_named_materials(&mut r, top.get("materials"));
    let objects = read_objects::<V>(&mut r, top.get("objects"), &mut materials, &names, read_file);
    match camera {
        Some(camera) if r.errors.is_empty() => Ok(Scene {
            camera,
            background,
            ambient,
            max_depth: u32::try_from(max_depth).unwrap_or(0),
            lights,
            materials,
            objects,
        }),
        _ => Err(r.errors),
    }
}

fn read_camera<V: LoadDim>(r: &mut Reader, v: &Value) -> Option<Camera<V>> {
    let cam = r.fields(v, "camera", V::CAMERA)?;
    let eye = r.required_vector::<V>(cam, "camera", "eye");
    let center = r.required_vector::<V>(cam, "camera", "center");
    let frame = match (eye, center) {
        (Some(e), Some(c)) => V::frame(r, cam, e, c),
        _ => None,
    };
    let projection = match cam.get("projection") {
        None => Some(Projection::Perspective),
        Some(p) => match r.string(p, "camera.projection") {
            Some("perspective") => Some(Projection::Perspective),
            Some("orthographic") => Some(Projection::Orthographic),
            Some(other) => {
                r.err(
                    "camera.projection",
                    format!("must be \"perspective\" or \"orthographic\", got \"{other}\""),
                );
                None
            }
            None => None,
        },
    };
    let p = r.optional(cam, "camera", "p", 1.0, positive);
    let window = match cam.get("window") {
        Some(w) => read_window::<V>(r, w),
        None => {
            r.err("camera.window", "missing (required)");
            None
        }
    };
    let (nx, ny) = match cam.get("resolution") {
        Some(Value::Array(res)) if !res.is_empty() => {
            let nx = resolution_axis(r, &res[0], "camera.resolution[0]");
            let ny = V::rows(r, res, "camera.resolution");
            (nx, ny)
        }
        Some(other) => {
            r.err("camera.resolution", format!("must be an array of pixel counts, got {}", type_name(other)));
            (None, None)
        }
        None => {
            r.err("camera.resolution", "missing (required)");
            (None, None)
        }
    };
    Some(Camera {
        eye: eye?,
        center: center?,
        frame: frame?,
        projection: projection?,
        p,
        window: window?,
        nx: nx?,
        ny: ny?,
    })
}

fn read_window<V: LoadDim>(r: &mut Reader, v: &Value) -> Option<Window> {
    let w = r.fields(v, "camera.window", V::WINDOW)?;
    let l = r.required(w, "camera.window", "l");
    let rr = r.required(w, "camera.window", "r");
    let (b, t) = if V::DIM == 3 {
        (r.required(w, "camera.window", "b"), r.required(w, "camera.window", "t"))
    } else {
        (Some(0.0), Some(0.0))
    };
    let (l, rr, b, t) = (l?, rr?, b?, t?);
    let mut ok = true;
    if rr <= l {
        r.err("camera.window", format!("r must be > l, got l = {}, r = {}", num(l), num(rr)));
        ok = false;
    }
    if V::DIM == 3 && t <= b {
        r.err("camera.window", format!("t must be > b, got b = {}, t = {}", num(b), num(t)));
        ok = false;
    }
    // The window's width must itself be finite and non-zero in f64.
    if !((rr - l).is_finite() && (t - b).is_finite()) {
        r.err("camera.window", "too large: its sides overflow");
        ok = false;
    }
    ok.then_some(Window { l, r: rr, b, t })
}

fn read_lights<V: LoadDim>(r: &mut Reader, v: Option<&Value>) -> Vec<Light<V>> {
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
            r.string(n, &join(&path, "name"));
        }
        let position = r.required_vector::<V>(map, &path, "position");
        let intensity = r.optional_rgb(map, &path, "intensity", Rgb::grey(1.0));
        let attenuation = match map.get("attenuation") {
            None => [1.0, 0.0, 0.0],
            Some(a) => {
                let p = join(&path, "attenuation");
                match a.as_array() {
                    Some(cs) if cs.len() == 3 => {
                        let mut c = [0.0; 3];
                        for (k, x) in cs.iter().enumerate() {
                            let q = format!("{p}[{k}]");
                            if let Some(x) = r.number(x, &q) {
                                if x < 0.0 {
                                    r.err(q, format!("must be ≥ 0, got {}", num(x)));
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
                        [1.0, 0.0, 0.0]
                    }
                }
            }
        };
        if let Some(position) = position {
            out.push(Light { position, intensity, attenuation });
        }
    }
    out
}

fn read_material(r: &mut Reader, v: &Value, path: &str) -> Option<Material> {
    let map = r.fields(v, path, MATERIAL)?;
    let d = Material::DEFAULT;
    let ka = r.optional_color(map, path, "ka", d.ka, (0.0, 1.0));
    let kd = r.optional_color(map, path, "kd", d.kd, (0.0, 1.0));
    let ks = r.optional(map, path, "ks", d.ks, unit_interval);
    let n = r.optional(map, path, "n", d.n, non_negative);
    let kt = r.optional(map, path, "kt", d.kt, unit_interval);
    let ior = r.optional(map, path, "ior", d.ior, positive);
    let checker = match map.get("checker") {
        None => None,
        Some(c) => {
            let p = join(path, "checker");
            let cm = r.fields(c, &p, CHECKER)?;
            let size = r.optional(cm, &p, "size", 1.0, positive);
            let kd2 = match cm.get("kd2") {
                Some(x) => r.color(x, &join(&p, "kd2"), (0.0, 1.0), true),
                None => {
                    r.err(join(&p, "kd2"), "missing (required)");
                    None
                }
            };
            let ka2 = r.optional_color(cm, &p, "ka2", ka, (0.0, 1.0));
            Some(Checker { size, kd2: kd2?, ka2 })
        }
    };
    Some(Material { ka, kd, ks, n, kt, ior, checker })
}

fn read_named_materials(r: &mut Reader, v: Option<&Value>) -> (Vec<Material>, Vec<String>) {
    let Some(v) = v else { return (vec![], vec![]) };
    let Some(map) = v.as_object() else {
        r.err("materials", format!("must be an object of named materials, got {}", type_name(v)));
        return (vec![], vec![]);
    };
    let mut mats = Vec::new();
    let mut names = Vec::new();
    for (name, m) in map {
        let m = read_material(r, m, &format!("materials.{name}")).unwrap_or(Material::DEFAULT);
        mats.push(m);
        names.push(name.to_owned());
    }
    (mats, names)
}

fn read_objects<V: LoadDim>(
    r: &mut Reader,
    v: Option<&Value>,
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
        let geometry: &[&str] = match ty {
            "sphere" => &["center", "radius"],
            "plane" => &["point", "normal"],
            "box" => &["min", "max"],
            "triangle" | "polygon" => &["vertices"],
            "segment" => &["a", "b"],
            "mesh" => &["obj"],
            _ => {
                let hint =
                    suggest(ty, V::TYPES).map(|s| format!("; did you mean `{s}`?")).unwrap_or_default();
                r.err(
                    join(&path, "type"),
                    format!("unknown type `{ty}` (one of: {}){hint}", V::TYPES.join(", ")),
                );
                continue;
            }
        };
        let mut known = vec!["type", "name", "material"];
        known.extend_from_slice(geometry);
        r.fields(item, &path, &known);
        let name = map.get("name").and_then(|n| r.string(n, &join(&path, "name"))).map(str::to_string);
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
            Some(inline) => read_material(r, inline, &join(&path, "material")).map(|m| {
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
            let center = r.required_vector::<V>(map, path, "center");
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
            let point = r.required_vector::<V>(map, path, "point");
            let normal = r.required_vector::<V>(map, path, "normal").and_then(|n| {
                let unit = n.try_unit();
                if unit.is_none() {
                    r.err(join(path, "normal"), "must not be zero");
                }
                unit
            });
            Some(Shape::Plane(Plane { point: point?, normal: normal? }))
        }
        "box" => {
            let min = r.required_vector::<V>(map, path, "min");
            let max = r.required_vector::<V>(map, path, "max");
            let (min, max) = (min?, max?);
            for axis in 0..V::DIM {
                if min[axis] >= max[axis] {
                    let name = ["x", "y", "z"][axis];
                    r.err(
                        join(path, "max"),
                        format!(
                            "must exceed min on every axis, got {name}: min {} ≥ max {}",
                            num(min[axis]),
                            num(max[axis])
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

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

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
