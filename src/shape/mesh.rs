//! A triangle mesh (product.md "Scene files": `mesh`; algorithm.md §11 "Triangles"): the
//! triangles of one OBJ file sharing one material, flat-shaded, each tested by the watertight
//! Woop–Benthin–Wald test. Vertices are stored once and triangles as index triples, so a
//! 1M-triangle mesh takes about 24 MB. A mesh is one object: its triangles are its parts, found
//! by the acceleration structures one by one and named by their index in the OBJ.
//! Degenerate (zero-area) triangles are skipped when the mesh is built and never hit.
//!
//! `parse_obj` reads the OBJ through `tobj`, its errors naming their line; `NoMesh` is the empty
//! mesh type of 2D.

use super::triangle::{crossing, crossing_sheared, Crossing, Shear};
use super::{Parts, SurfaceHit};
use crate::geom::ray::Ray;
use crate::geom::Vector;
use glam::{DVec2, DVec3};

/// The triangles of one OBJ file.
///
/// # Guarantees
/// Every face indexes `vertices`, has a non-zero area and its OBJ index in `ids` (ascending);
/// there is at least one face.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    vertices: Vec<DVec3>,
    faces: Vec<[u32; 3]>,
    ids: Vec<u32>,
    skipped: usize,
    scale: f64,
}

/// Why a mesh cannot be built.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MeshError {
    /// A face names a vertex that does not exist.
    VertexOutOfRange {
        /// The face's index.
        face: usize,
    },
    /// Every triangle has zero area (or there is none).
    NoTriangles {
        /// How many degenerate triangles were skipped.
        skipped: usize,
    },
    /// More triangles or vertices than 32-bit indices can name.
    TooLarge,
}

impl Mesh {
    /// A mesh from its vertices and triangles (index triples into `vertices`, in OBJ order).
    /// Triangles whose normal `(b − a) × (c − a)` cannot be normalised are skipped and counted.
    ///
    /// # Errors
    /// [`MeshError`] when a face indexes no vertex, when no triangle is left, or when there are
    /// more than 2³² − 1 vertices or faces.
    pub fn new(vertices: Vec<DVec3>, faces: &[[u32; 3]]) -> Result<Self, MeshError> {
        if u32::try_from(vertices.len()).is_err() || u32::try_from(faces.len()).is_err() {
            return Err(MeshError::TooLarge);
        }
        let mut kept = Vec::with_capacity(faces.len());
        let mut ids = Vec::with_capacity(faces.len());
        let mut skipped = 0;
        for (index, face) in faces.iter().enumerate() {
            if face.iter().any(|&v| v as usize >= vertices.len()) {
                return Err(MeshError::VertexOutOfRange { face: index });
            }
            let [a, b, c] = face.map(|v| vertices[v as usize]);
            if (b - a).cross(c - a).try_unit().is_none() {
                skipped += 1;
                continue;
            }
            kept.push(*face);
            // Fits: faces.len() fits in u32 (checked above).
            ids.push(u32::try_from(index).unwrap_or(u32::MAX));
        }
        if kept.is_empty() {
            return Err(MeshError::NoTriangles { skipped });
        }
        let scale = kept.iter().flatten().fold(0.0, |m: f64, &v| m.max(vertices[v as usize].max_abs()));
        Ok(Self { vertices, faces: kept, ids, skipped, scale })
    }

    /// The vertices of triangle `k` (a part index, not an OBJ index).
    #[inline]
    #[must_use]
    pub fn triangle(&self, k: usize) -> [DVec3; 3] {
        self.faces[k].map(|v| self.vertices[v as usize])
    }
}

/// What an OBJ text declares, counted before it is parsed: its `v` statements and the triangles
/// its `f` statements fan into (a face of k vertices makes k − 2). Counting reads the text once and
/// allocates nothing, so a mesh too large for the memory is refused before it is built.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ObjCounts {
    /// The vertices.
    pub vertices: u64,
    /// The triangles.
    pub triangles: u64,
}

/// Bytes a vertex costs while a mesh is read and kept: tobj's position and its index map entry,
/// the mesh's own copy. Measured with `check` on generated grids (see `ObjCounts::bytes_needed`).
const BYTES_PER_VERTEX: u64 = 160;
/// Bytes a triangle costs while a mesh is read and kept, and in the BVH built over it: tobj's
/// index triple, the mesh's face and id, the structure's primitive record and node share.
const BYTES_PER_TRIANGLE: u64 = 160;

impl ObjCounts {
    /// Counts the statements of `text` (see [`ObjCounts`]).
    #[must_use]
    pub fn of(text: &str) -> Self {
        let mut counts = Self::default();
        for line in text.lines() {
            let mut words = line.split_whitespace();
            match words.next() {
                Some("v") => counts.vertices += 1,
                Some("f") => counts.triangles += (words.count() as u64).saturating_sub(2),
                _ => {}
            }
        }
        counts
    }

    /// About how many bytes reading the mesh and building its structure take:
    /// `vertices · BYTES_PER_VERTEX + triangles · BYTES_PER_TRIANGLE`.
    #[must_use]
    pub fn bytes_needed(&self) -> u64 {
        self.vertices
            .saturating_mul(BYTES_PER_VERTEX)
            .saturating_add(self.triangles.saturating_mul(BYTES_PER_TRIANGLE))
    }
}

/// A problem in an OBJ file, with the line it is on when one line is to blame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjError {
    /// The 1-based line, if one line is to blame.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: String,
}

/// Reads Wavefront OBJ text with `tobj`: every `v` and every face, polygons fan-triangulated in
/// file order (so a triangle's index is its position among the triangles so made). Materials,
/// normals and texture coordinates are ignored: the mesh takes the scene's material and is
/// flat-shaded. Coordinates must be finite and at most `max_magnitude` (§11 "Validation").
///
/// # Errors
/// The first problem found, with its line: tobj names no line, so the line is the shortest
/// prefix of the text that tobj rejects (found by bisection, only when there is an error).
pub fn parse_obj(text: &str, max_magnitude: f64) -> Result<(Vec<DVec3>, Vec<[u32; 3]>), ObjError> {
    let (models, _) =
        read_models(text).map_err(|e| ObjError { line: failing_line(text), problem: e.to_string() })?;
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for model in models {
        let m = model.mesh;
        let offset = u32::try_from(vertices.len()).map_err(|_| too_large())?;
        for p in m.positions.chunks_exact(3) {
            let v = DVec3::new(p[0], p[1], p[2]);
            if !fits(v, max_magnitude) {
                // tobj lists a model's vertices in the order its faces first use them, not in the
                // file's: the file's own `v` statements say which one it is.
                let (line, n) = first_vertex_beyond(text, max_magnitude).unzip();
                let n = n.unwrap_or(vertices.len() + 1);
                return Err(ObjError {
                    line,
                    problem: format!("vertex {n}: every coordinate must be finite and at most {max_magnitude:e} in magnitude"),
                });
            }
            vertices.push(v);
        }
        for f in m.indices.chunks_exact(3) {
            faces.push([f[0] + offset, f[1] + offset, f[2] + offset]);
        }
    }
    Ok((vertices, faces))
}

fn too_large() -> ObjError {
    ObjError { line: None, problem: "more than 2^32 vertices".into() }
}

fn read_models(text: &str) -> tobj::LoadResult {
    let options =
        tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let mut reader = std::io::BufReader::new(ModelBreaks::new(text));
    tobj::load_obj_buf(&mut reader, &options, |_| Err(tobj::LoadError::OpenFileFailed))
}

/// Face statements a model of tobj's holds at most, by [`ModelBreaks`].
const FACES_PER_MODEL: usize = 1 << 16;

/// An OBJ text as tobj reads it, with a group statement (`g`) after every [`FACES_PER_MODEL`]-th
/// face statement. tobj keeps every face of the model it is reading (104 bytes each) and a map of
/// its vertices until the model ends, so a million triangles in one model took 222 MB at the
/// peak of loading; cut into models of at most [`FACES_PER_MODEL`] faces, it holds one model's.
/// The triangles are the same, in the same order: OBJ indices name the file's vertices whatever
/// the group, and [`parse_obj`] joins the models in order. A vertex used by two models is stored
/// by each (the same coordinates). A text of at most [`FACES_PER_MODEL`] faces reads as it is.
struct ModelBreaks<'a> {
    /// The text not yet read.
    rest: &'a [u8],
    /// The group statement still to be read (empty when none is due).
    pending: &'static [u8],
    /// Whether `rest` starts a line.
    line_start: bool,
    /// Whether the line being read is a face statement.
    face_line: bool,
    /// Face statements read.
    faces: usize,
}

impl<'a> ModelBreaks<'a> {
    fn new(text: &'a str) -> Self {
        Self { rest: text.as_bytes(), pending: b"", line_start: true, face_line: false, faces: 0 }
    }
}

impl std::io::Read for ModelBreaks<'_> {
    /// Copies from the pending group statement, else from the current line, up to its end.
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if !self.pending.is_empty() {
            let n = self.pending.len().min(buf.len());
            buf[..n].copy_from_slice(&self.pending[..n]);
            self.pending = &self.pending[n..];
            return Ok(n);
        }
        let len = self.rest.iter().position(|&b| b == b'\n').map_or(self.rest.len(), |at| at + 1);
        let line = &self.rest[..len];
        if self.line_start {
            // A statement's keyword is its line's first word, as tobj splits it.
            let keyword = line.split(u8::is_ascii_whitespace).find(|w| !w.is_empty());
            self.face_line = keyword == Some(b"f".as_slice());
        }
        let n = len.min(buf.len());
        buf[..n].copy_from_slice(&line[..n]);
        self.rest = &self.rest[n..];
        // The line is read to its newline: the next read starts a line (the last line of a text
        // without a final newline ends the text, and nothing follows it).
        self.line_start = n == len && line.last() == Some(&b'\n');
        if self.line_start && self.face_line {
            self.faces += 1;
            if self.faces.is_multiple_of(FACES_PER_MODEL) {
                self.pending = b"g\n";
            }
        }
        Ok(n)
    }
}

/// The 1-based line of the shortest prefix tobj rejects.
fn failing_line(text: &str) -> Option<usize> {
    let ends: Vec<usize> =
        text.match_indices('\n').map(|(i, _)| i + 1).chain(std::iter::once(text.len())).collect();
    // Invariant: the first `lo` lines parse, the first `hi` do not.
    let (mut lo, mut hi) = (0, ends.len());
    if read_models(text).is_ok() {
        return None;
    }
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if read_models(&text[..ends[mid - 1]]).is_ok() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(hi)
}

/// Whether a vertex is finite and within `max_magnitude` on every axis.
fn fits(v: DVec3, max_magnitude: f64) -> bool {
    v.is_finite_vec() && v.max_abs() <= max_magnitude
}

/// The 1-based line and the 1-based number of the file's first `v` statement whose coordinates
/// do not [`fits`] (read as tobj reads them: the first three numbers after `v`).
fn first_vertex_beyond(text: &str, max_magnitude: f64) -> Option<(usize, usize)> {
    let vertex = |line: &str| {
        let mut words = line.split_whitespace();
        (words.next() == Some("v"))
            .then(|| words.take(3).map(|w| w.parse::<f64>().unwrap_or(f64::NAN)).collect::<Vec<_>>())
    };
    text.lines()
        .enumerate()
        .filter_map(|(i, line)| Some((i + 1, vertex(line)?)))
        .enumerate()
        .find(|(_, (_, p))| p.len() == 3 && !fits(DVec3::new(p[0], p[1], p[2]), max_magnitude))
        .map(|(n, (line, _))| (line, n + 1))
}

impl Parts<DVec3> for Mesh {
    fn count(&self) -> usize {
        self.faces.len()
    }
    /// The Woop–Benthin–Wald hit of triangle k with `t > 0`; N = normalize((b − a) × (c − a)).
    #[inline]
    fn hit(&self, k: usize, ray: &Ray<DVec3>) -> Option<SurfaceHit<DVec3>> {
        let [a, b, c] = self.triangle(k);
        let x = crossing(&[a, b, c], ray)?;
        hit_of(a, b, c, &x)
    }
    fn roots(&self, k: usize, ray: &Ray<DVec3>) -> Vec<f64> {
        crossing(&self.triangle(k), ray).map(|x| x.t).into_iter().collect()
    }
    fn bounds(&self, k: usize) -> (DVec3, DVec3) {
        let [a, b, c] = self.triangle(k);
        (a.min(b).min(c), a.max(b).max(c))
    }
    fn points(&self, k: usize) -> Vec<DVec3> {
        self.triangle(k).to_vec()
    }
    fn id(&self, k: usize) -> usize {
        self.ids[k] as usize
    }
    fn scale(&self) -> f64 {
        self.scale
    }
    fn skipped(&self) -> usize {
        self.skipped
    }
    fn meets_box(&self, k: usize, lo: DVec3, hi: DVec3) -> bool {
        super::triangle::triangle_meets_box(&self.triangle(k), lo, hi)
    }
    type Prepared = Shear;
    #[inline]
    fn prepare(ray: &Ray<DVec3>) -> Shear {
        Shear::of(ray.dir)
    }
    /// [`Parts::hit`] with the ray's shear computed once. Inline in a native build's walks, out
    /// of line in the WebAssembly module, as [`crossing_sheared`] is.
    #[cfg_attr(not(target_family = "wasm"), inline(always))]
    #[cfg_attr(target_family = "wasm", inline)]
    fn hit_prepared(&self, k: usize, ray: &Ray<DVec3>, shear: &Shear) -> Option<SurfaceHit<DVec3>> {
        let [a, b, c] = self.triangle(k);
        let x = crossing_sheared(&[a, b, c], ray.origin, shear)?;
        hit_of(a, b, c, &x)
    }
    /// The t of [`Parts::hit_prepared`], which never fails for want of a normal: the same
    /// `(b − a) × (c − a)` was normalised when the mesh was built, or the triangle skipped.
    /// Inline as [`Parts::hit_prepared`] is.
    #[cfg_attr(not(target_family = "wasm"), inline(always))]
    #[cfg_attr(target_family = "wasm", inline)]
    fn hit_t_prepared(&self, k: usize, ray: &Ray<DVec3>, shear: &Shear) -> Option<f64> {
        let x = crossing_sheared(&self.triangle(k), ray.origin, shear)?;
        (x.t > 0.0).then_some(x.t)
    }
}

/// The hit of triangle `a, b, c` at crossing `x`, when `t > 0`: I from the barycentrics,
/// N = normalize((b − a) × (c − a)).
#[inline]
fn hit_of(a: DVec3, b: DVec3, c: DVec3, x: &Crossing) -> Option<SurfaceHit<DVec3>> {
    if !(x.t > 0.0) {
        return None;
    }
    let point = a * x.weights[0] + b * x.weights[1] + c * x.weights[2];
    let normal = (b - a).cross(c - a).try_unit()?;
    Some(SurfaceHit { t: x.t, point, normal })
}

/// 2D scenes have no meshes: this type has no values.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum NoMesh {}

impl Parts<DVec2> for NoMesh {
    fn count(&self) -> usize {
        match *self {}
    }
    fn hit(&self, _: usize, _: &Ray<DVec2>) -> Option<SurfaceHit<DVec2>> {
        match *self {}
    }
    fn roots(&self, _: usize, _: &Ray<DVec2>) -> Vec<f64> {
        match *self {}
    }
    fn bounds(&self, _: usize) -> (DVec2, DVec2) {
        match *self {}
    }
    fn points(&self, _: usize) -> Vec<DVec2> {
        match *self {}
    }
    fn id(&self, _: usize) -> usize {
        match *self {}
    }
    fn scale(&self) -> f64 {
        match *self {}
    }
    fn skipped(&self) -> usize {
        match *self {}
    }
    fn meets_box(&self, _: usize, _: DVec2, _: DVec2) -> bool {
        match *self {}
    }
    type Prepared = ();
    fn prepare(_: &Ray<DVec2>) {}
    fn hit_prepared(&self, _: usize, _: &Ray<DVec2>, (): &()) -> Option<SurfaceHit<DVec2>> {
        match *self {}
    }
    fn hit_t_prepared(&self, _: usize, _: &Ray<DVec2>, (): &()) -> Option<f64> {
        match *self {}
    }
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    fn square() -> Vec<DVec3> {
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(2.0, 0.0, 0.0)]
    }

    #[test]
    fn d4_degenerate_triangles_in_a_mesh_are_skipped_and_counted() {
        // Face 1 is the degenerate (0,0,0), (1,0,0), (2,0,0).
        let m = Mesh::new(square(), &[[0, 1, 2], [0, 1, 4], [0, 2, 3]]).unwrap();
        assert_eq!((m.count(), m.skipped()), (2, 1));
        assert_eq!((m.id(0), m.id(1)), (0, 2));
        let down = Ray::new(DVec3::new(0.25, 0.5, 1.0), DVec3::NEG_Z);
        let h = m.hit(1, &down).unwrap();
        assert_eq!(h.t, 1.0);
        assert_eq!(h.normal, DVec3::Z);
    }

    #[test]
    fn a_long_obj_is_read_as_models_of_bounded_size_with_the_same_triangles() {
        // A strip of quads, each fanned into two triangles: more faces than one model holds,
        // the last line without its newline, CRLF line ends, a blank line and a comment.
        let quads = FACES_PER_MODEL + 7;
        let mut text = String::from("# strip\r\n\r\n");
        for k in 0..=quads {
            text += &format!("v {k} 0 0\r\nv {k} 1 {}\r\n", k % 3);
        }
        for k in 0..quads {
            let a = 2 * k + 1;
            text += &format!("f {} {} {} {}\r\n", a, a + 2, a + 3, a + 1);
        }
        let text = text.trim_end();
        let (models, _) = read_models(text).unwrap();
        assert_eq!(models.len(), 2, "a group after every FACES_PER_MODEL faces");
        assert_eq!(models[0].mesh.indices.len(), 3 * 2 * FACES_PER_MODEL);
        let (vertices, faces) = parse_obj(text, 1e100).unwrap();
        assert_eq!(faces.len(), 2 * quads);
        // The triangles, in order, are the file's: quad k fans into (a, a+2, a+3), (a, a+3, a+1).
        let file_vertex = |i: usize| {
            DVec3::new((i / 2) as f64, (i % 2) as f64, if i % 2 == 1 { ((i / 2) % 3) as f64 } else { 0.0 })
        };
        for (t, face) in faces.iter().enumerate() {
            let a = 2 * (t / 2);
            let want = if t % 2 == 0 { [a, a + 2, a + 3] } else { [a, a + 3, a + 1] };
            assert_eq!(face.map(|v| vertices[v as usize]), want.map(file_vertex), "triangle {t}");
        }
    }

    #[test]
    fn obj_text_is_read_triangulated_and_errors_name_the_line() {
        let text = "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n";
        let (v, f) = parse_obj(text, 1e100).unwrap();
        assert_eq!(v.len(), 4);
        assert_eq!(f, vec![[0, 1, 2], [0, 2, 3], [0, 1, 2]]);
        let bad = "v 0 0 0\nv 1 0 0\nv 1 x 0\nf 1 2 3\n";
        let e = parse_obj(bad, 1e100).unwrap_err();
        assert_eq!(e.line, Some(3), "{e:?}");
        let out = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n";
        assert_eq!(parse_obj(out, 1e100).unwrap_err().line, Some(4));
        let huge = "v 0 0 0\nv 1e200 0 0\nv 1 1 0\nf 1 2 3\n";
        assert_eq!(parse_obj(huge, 1e100).unwrap_err().line, Some(2));
        // The file's fourth vertex, though the face names it first (tobj lists it first).
        let first_used = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e300 0 0\nf 4 2 3\n";
        let e = parse_obj(first_used, 1e100).unwrap_err();
        assert_eq!(e.line, Some(4), "{e:?}");
        assert!(e.problem.starts_with("vertex 4: "), "{e:?}");
    }

    #[test]
    fn bad_meshes_are_errors() {
        assert_eq!(Mesh::new(square(), &[[0, 1, 9]]), Err(MeshError::VertexOutOfRange { face: 0 }));
        assert_eq!(Mesh::new(square(), &[[0, 1, 4]]), Err(MeshError::NoTriangles { skipped: 1 }));
    }
}
