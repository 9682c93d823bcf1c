//! Helpers shared by the integration tests: write a scene ([`SceneText`]) or edit a fixture
//! ([`fixture_with`]), load it, trace a pixel or a ray with `EventLog`, build the trace document,
//! run the `whitted` binary ([`whitted`], [`whitted_with_input`]) on files in a [`Scratch`]
//! folder, removed when the test ends.

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use whitted::accel::{Accel, AccelKind};
use whitted::doc::{trace_document, TraceTarget};
use whitted::geom::ray::Ray;
use whitted::record::EventLog;
use whitted::scene::load::load_str;
use whitted::scene::{AnyScene, Scene};
use whitted::shape::Dim;
use whitted::trace::Tracer;

/// A valid 3D scene from JSON text (panics with the errors otherwise).
pub fn scene3(text: &str) -> Scene<glam::DVec3> {
    match load_str(text) {
        Ok(AnyScene::Space(s)) => s,
        Ok(AnyScene::Flat(_)) => panic!("expected a 3D scene"),
        Err(e) => panic!("invalid scene: {e:?}"),
    }
}

/// A valid 2D scene from JSON text.
pub fn scene2(text: &str) -> Scene<glam::DVec2> {
    match load_str(text) {
        Ok(AnyScene::Flat(s)) => s,
        Ok(AnyScene::Space(_)) => panic!("expected a 2D scene"),
        Err(e) => panic!("invalid scene: {e:?}"),
    }
}

/// Reads a fixture scene from `tests/data/scenes`.
pub fn fixture(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scenes").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The path of a fixture scene, for the binary.
pub fn fixture_path(name: &str) -> String {
    format!("{}/tests/data/scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// A fixture's text with fields changed: each `(pointer, value)` sets the field at a JSON pointer
/// (`/max_depth`, `/materials/glass/kt`). Panics naming the pointer when the fixture has no such
/// field, where a text `replace` would silently change nothing.
pub fn fixture_with(name: &str, changes: &[(&str, Value)]) -> String {
    edited(&fixture(name), changes)
}

/// A scene's text with fields changed, as [`fixture_with`] does.
pub fn edited(text: &str, changes: &[(&str, Value)]) -> String {
    let mut doc: Value = serde_json::from_str(text).unwrap_or_else(|e| panic!("not JSON: {e}"));
    for (pointer, value) in changes {
        let field = doc.pointer_mut(pointer).unwrap_or_else(|| panic!("the scene has no field {pointer}"));
        *field = value.clone();
    }
    doc.to_string()
}

/// A scene written by a test: a camera on the z axis (the y axis in 2D) looking at the origin
/// through the window [-1, 1]² ([-1, 1] in 2D), and what the test adds. Built as JSON, so a test
/// says only what it is about; [`SceneText::text`] for the binary or an invalid scene,
/// [`SceneText::space`] for the validated 3D scene.
#[derive(Clone, Debug)]
pub struct SceneText(Value);

impl SceneText {
    /// A 3D scene: eye (0, 0, 5), `nx × ny` pixels.
    pub fn space3(nx: usize, ny: usize) -> Self {
        Self(json!({"camera": {"eye": [0, 0, 5], "center": [0, 0, 0],
            "window": {"l": -1, "r": 1, "b": -1, "t": 1}, "resolution": [nx, ny]}}))
    }
    /// A 2D scene: eye (0, 5), `nx` pixels.
    pub fn flat2(nx: usize) -> Self {
        Self(
            json!({"camera": {"eye": [0, 5], "center": [0, 0], "window": {"l": -1, "r": 1}, "resolution": [nx]}}),
        )
    }
    /// Sets the field at a JSON pointer (`/max_depth`, `/camera/eye`); its parent must exist.
    #[must_use]
    pub fn set(mut self, pointer: &str, value: Value) -> Self {
        let (parent, key) = pointer.rsplit_once('/').unwrap_or_else(|| panic!("not a pointer: {pointer}"));
        let map = self.0.pointer_mut(parent).and_then(Value::as_object_mut);
        map.unwrap_or_else(|| panic!("no object at {parent}")).insert(key.to_owned(), value);
        self
    }
    /// Sets the camera's eye.
    #[must_use]
    pub fn eye(self, eye: Value) -> Self {
        self.set("/camera/eye", eye)
    }
    /// Sets the camera's window (`{"l", "r"}` in 2D, `{"l", "r", "b", "t"}` in 3D).
    #[must_use]
    pub fn window(self, window: Value) -> Self {
        self.set("/camera/window", window)
    }
    /// Appends an object.
    #[must_use]
    pub fn object(self, object: Value) -> Self {
        self.push("objects", object)
    }
    /// Appends objects.
    #[must_use]
    pub fn objects(self, objects: impl IntoIterator<Item = Value>) -> Self {
        objects.into_iter().fold(self, Self::object)
    }
    /// Appends a light.
    #[must_use]
    pub fn light(self, light: Value) -> Self {
        self.push("lights", light)
    }
    /// Names a material (`"materials": {NAME: …}`), for objects that refer to it by name.
    #[must_use]
    pub fn material(mut self, name: &str, material: Value) -> Self {
        let map = self.0.as_object_mut().unwrap().entry("materials").or_insert_with(|| json!({}));
        map.as_object_mut().unwrap().insert(name.to_owned(), material);
        self
    }
    fn push(mut self, list: &str, item: Value) -> Self {
        let items = self.0.as_object_mut().unwrap().entry(list).or_insert_with(|| json!([]));
        items.as_array_mut().unwrap().push(item);
        self
    }
    /// The scene's JSON text.
    pub fn text(&self) -> String {
        self.0.to_string()
    }
    /// The scene's JSON text with more top-level fields written as given, after the others: for
    /// what a JSON value cannot hold (`1e400`, a key written twice) or a text too large to build
    /// as values. Each raw text is pasted as it is, valid JSON or not.
    pub fn text_with(&self, raw: &[(&str, &str)]) -> String {
        let mut text = self.text();
        let end = text.pop();
        assert_eq!(end, Some('}'), "a scene is an object");
        for (key, value) in raw {
            text.push_str(&format!(",{}:{value}", Value::from(*key)));
        }
        text.push('}');
        text
    }
    /// The validated 3D scene.
    pub fn space(&self) -> Scene<glam::DVec3> {
        scene3(&self.text())
    }
}

/// Traces pixel `(i, j)` and returns the trace document.
pub fn trace_pixel<V: Dim>(scene: &Scene<V>, i: usize, j: usize) -> Value {
    let cam = &scene.camera;
    let (u, v) = cam.pixel_center(i, j);
    let uv = if V::DIM == 2 { vec![u] } else { vec![u, v] };
    let pixel = if V::DIM == 2 { vec![i] } else { vec![i, j] };
    trace(scene, &cam.primary_ray(u, v), TraceTarget { pixel: Some(pixel), uv: Some(uv) })
}

/// Traces a ray given by hand and returns the trace document.
pub fn trace_ray<V: Dim>(scene: &Scene<V>, ray: &Ray<V>) -> Value {
    trace(scene, ray, TraceTarget { pixel: None, uv: None })
}

fn trace<V: Dim>(scene: &Scene<V>, ray: &Ray<V>, target: TraceTarget) -> Value {
    let accel = Accel::build(scene, AccelKind::None);
    let mut tracer = Tracer::new(scene, &accel, EventLog::new());
    let uv = target.uv.clone().unwrap_or_default();
    let color = tracer.trace_primary(ray, &uv);
    trace_document(scene, &tracer.recorder, &tracer.stats, &target, color)
}

/// The events of a document of one kind.
pub fn events<'a>(doc: &'a Value, kind: &str) -> Vec<&'a Value> {
    doc["events"].as_array().unwrap().iter().filter(|e| e["kind"] == kind).collect()
}

/// A float field.
pub fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// Asserts that no float in the document is NaN (serde_json would have written null) and that
/// every non-finite value is one of the documented strings.
pub fn assert_finite(doc: &Value) {
    match doc {
        Value::Number(n) => assert!(n.as_f64().is_some_and(f64::is_finite)),
        Value::String(s) if s.contains("inf") => assert!(s == "inf" || s == "-inf"),
        Value::Array(a) => a.iter().for_each(assert_finite),
        Value::Object(m) => m.values().for_each(assert_finite),
        _ => {}
    }
}

/// Runs the `whitted` binary: (exit code, stdout, stderr). Its files go in a [`Scratch`] folder.
pub fn whitted(args: &[&str]) -> (i32, String, String) {
    let out =
        std::process::Command::new(env!("CARGO_BIN_EXE_whitted")).args(args).output().expect("run whitted");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs the `whitted` binary with `input` on its stdin (the answers `whitted step` reads):
/// (exit code, stdout, stderr).
pub fn whitted_with_input(args: &[&str], input: &str) -> (i32, String, String) {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run whitted");
    child.stdin.take().unwrap().write_all(input.as_bytes()).expect("write whitted's input");
    let out = child.wait_with_output().expect("run whitted");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A folder of one test's own, for the scenes it writes and the files the binary writes: fresh
/// (a rerun never finds an earlier run's files) and removed when dropped, also when the test
/// fails (`tempfile::TempDir`).
pub struct Scratch(tempfile::TempDir);

impl Scratch {
    /// A new empty folder in the system's temporary folder.
    pub fn new() -> Self {
        Self(tempfile::Builder::new().prefix("whitted-test-").tempdir().expect("a temporary folder"))
    }
    /// The folder.
    pub fn path(&self) -> &Path {
        self.0.path()
    }
    /// The path of `name` in the folder (`name` may hold `/`).
    pub fn join(&self, name: impl AsRef<Path>) -> PathBuf {
        self.path().join(name)
    }
    /// The path of `name` in the folder as an argument for the binary.
    pub fn arg(&self, name: &str) -> String {
        self.join(name).to_str().expect("a UTF-8 temporary path").to_owned()
    }
    /// Writes `name` in the folder and returns its path as an argument.
    pub fn write(&self, name: &str, contents: impl AsRef<[u8]>) -> String {
        std::fs::write(self.join(name), contents).unwrap_or_else(|e| panic!("{name}: {e}"));
        self.arg(name)
    }
}

/// The lesson files of `lessons/`, sorted: each one's path and text.
pub fn lesson_files() -> Vec<(PathBuf, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    paths.into_iter().map(|p| (p.clone(), std::fs::read_to_string(&p).unwrap())).collect()
}

/// The trace document (`whitted trace --json`) of pixel `pixel` (`[i]` in 2D, `[i, j]` in 3D) of
/// a lesson figure's scene (`lessons/` + `spec.scene`), at the figure's depth, one sample at the
/// pixel's centre.
pub fn lesson_trace(spec: &whitted::lesson::FigureSpec, pixel: &[usize]) -> Value {
    use whitted::request::trace::Trace;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let scene = load_str(&std::fs::read_to_string(dir.join(&spec.scene)).unwrap()).unwrap();
    let signed = |k: usize| i64::try_from(k).unwrap();
    let trace = Trace {
        target: whitted::request::target::Target {
            pixel: Some((signed(pixel[0]), pixel.get(1).copied().map(signed))),
            ray: None,
        },
        depth: spec.depth,
        sampling: whitted::sample::Sampling::Center,
        accel: whitted::request::options::AccelChoice::default(),
        max_events: whitted::record::DEFAULT_LIMIT,
    };
    trace.document(&scene).unwrap_or_else(|e| panic!("{}", e.message))
}
