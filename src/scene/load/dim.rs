//! What differs between 2D and 3D when reading a scene: the camera's fields and frame, the
//! resolution's rows, the object types, the flat primitive (a 3D triangle; a 2D segment, triangle
//! or polygon) and meshes (3D only).

use super::schema::{
    CAMERA_2D, CAMERA_3D, DEFAULT_UP, MAX_MAGNITUDE, TYPES_2D, TYPES_3D, WINDOW_2D, WINDOW_3D,
};
use super::{camera, objects, required_vector, vector, ReadFile};
use crate::geom::frame::{self, Frame};
use crate::json::reader::{join, Reader};
use crate::json::{Map, Value};
use crate::memory::budget;
use crate::shape::mesh::{parse_obj, Mesh, MeshError, ObjCounts};
use crate::shape::polygon::{Polygon, PolygonError};
use crate::shape::triangle::Triangle;
use crate::shape::Dim;
use glam::{DVec2, DVec3};

pub(super) trait LoadDim: Dim {
    /// The camera's fields.
    const CAMERA: &'static [&'static str];
    /// The window's fields.
    const WINDOW: &'static [&'static str];
    /// The object types.
    const TYPES: &'static [&'static str];
    /// The observer frame from eye, centre and (in 3D) `up`, and that `up` (zero in 2D).
    fn frame(r: &mut Reader, camera: &Map<'_>, eye: Self, center: Self) -> Option<(Frame<Self>, Self)>;
    /// The flat primitive of an object of the given type.
    fn facet(r: &mut Reader, ty: &str, map: &Map<'_>, path: &str) -> Option<Self::Facet>;
    /// `Ny` from the resolution array.
    fn rows(r: &mut Reader, res: &[Value], path: &str) -> Option<usize>;
    /// A `mesh` object (3D only).
    fn mesh(r: &mut Reader, map: &Map<'_>, path: &str, read_file: ReadFile<'_>) -> Option<Self::Mesh>;
}

impl LoadDim for DVec3 {
    const CAMERA: &'static [&'static str] = CAMERA_3D;
    const WINDOW: &'static [&'static str] = WINDOW_3D;
    const TYPES: &'static [&'static str] = TYPES_3D;
    fn frame(r: &mut Reader, camera: &Map<'_>, eye: Self, center: Self) -> Option<(Frame<Self>, Self)> {
        let up = match camera.get("up") {
            Some(v) => vector::<DVec3>(r, v, "camera.up")?,
            None => DEFAULT_UP,
        };
        frame::look_at(eye, center, up).map_err(|e| camera::frame_error(r, e)).ok().map(|f| (f, up))
    }
    fn facet(r: &mut Reader, ty: &str, map: &Map<'_>, path: &str) -> Option<Triangle> {
        if ty != "triangle" {
            r.err(join(path, "type"), format!("`{ty}` exists only in 2D scenes"));
            return None;
        }
        let vs = objects::vertices::<DVec3>(r, map, path, 3, 3)?;
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
        camera::resolution_axis(r, &res[1], &format!("{path}[1]"))
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
        // What the mesh will take, from its counts, before tobj allocates it.
        let counts = ObjCounts::of(&text);
        let what = format!("{name}: {} vertices and {} triangles", counts.vertices, counts.triangles);
        if let Err(why) = budget().check(counts.bytes_needed(), &what, "use a mesh with fewer triangles") {
            r.err(p, why);
            return None;
        }
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
    fn frame(r: &mut Reader, _camera: &Map<'_>, eye: Self, center: Self) -> Option<(Frame<Self>, Self)> {
        frame::look_at_2d(eye, center).map_err(|e| camera::frame_error(r, e)).ok().map(|f| (f, DVec2::ZERO))
    }
    fn facet(r: &mut Reader, ty: &str, map: &Map<'_>, path: &str) -> Option<Polygon> {
        let built = match ty {
            "segment" => {
                let a = required_vector::<DVec2>(r, map, path, "a");
                let b = required_vector::<DVec2>(r, map, path, "b");
                Polygon::segment(a?, b?)
            }
            "triangle" => Polygon::closed(objects::vertices::<DVec2>(r, map, path, 3, 3)?),
            _ => Polygon::closed(objects::vertices::<DVec2>(r, map, path, 3, usize::MAX)?),
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
