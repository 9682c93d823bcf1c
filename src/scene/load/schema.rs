//! The scene format on one screen (product.md "Scene files" and "Defaults"): the fields each
//! object may have, the limits the loader enforces and the defaults it applies. The sections
//! (`camera`, `lights`, `materials`, `objects`) read with these names and nothing else.

use crate::scene::camera::Projection;
use crate::scene::material::Rgb;
use glam::DVec3;

pub use crate::json::reader::MAX_MAGNITUDE;

/// The largest `max_depth` (§11); deeper trees would only multiply weights below any pixel step.
pub const MAX_DEPTH: u64 = 64;
/// The largest resolution along one axis (documented cap: 65 536 pixels).
pub const MAX_RESOLUTION: u64 = 1 << 16;
/// The largest scene file read (128 MiB, about a million objects written out).
pub const MAX_SCENE_BYTES: u64 = 128 << 20;
/// The largest mesh (OBJ) file read (512 MiB, about ten million triangles).
pub const MAX_OBJ_BYTES: u64 = 512 << 20;

/// `max_depth` when the scene leaves it out.
pub const DEFAULT_MAX_DEPTH: u64 = 5;
/// `background` when left out: black.
pub const DEFAULT_BACKGROUND: Rgb = Rgb::BLACK;
/// `ambient` when left out: white, so that `ka` alone sets the ambient term.
pub const DEFAULT_AMBIENT: Rgb = Rgb::grey(1.0);
/// `camera.up` (3D) when left out.
pub const DEFAULT_UP: DVec3 = DVec3::Y;
/// `camera.projection` when left out.
pub const DEFAULT_PROJECTION: Projection = Projection::Perspective;
/// `camera.p`, the eye–window distance, when left out.
pub const DEFAULT_P: f64 = 1.0;
/// A light's `intensity` when left out: white.
pub const DEFAULT_INTENSITY: Rgb = Rgb::grey(1.0);
/// A light's `attenuation` `[c0, c1, c2]` when left out: none (`1 / (c0 + c1·d + c2·d²)` = 1).
pub const DEFAULT_ATTENUATION: [f64; 3] = [1.0, 0.0, 0.0];
/// A checker's square `size` when left out. (A material's own defaults: `Material::DEFAULT`.)
pub const DEFAULT_CHECKER_SIZE: f64 = 1.0;

/// The range of a material colour's channels (`ka`, `kd`, `kd2`, `ka2`).
pub const REFLECTANCE: (f64, f64) = (0.0, 1.0);
/// The range of a light colour's channels (`background`, `ambient`, `intensity`).
pub const RADIANCE: (f64, f64) = (0.0, f64::INFINITY);

/// The top-level fields.
pub const TOP: &[&str] =
    &["camera", "background", "ambient", "max_depth", "lights", "materials", "objects", "description"];
/// The camera's fields in a 3D scene.
pub const CAMERA_3D: &[&str] = &["eye", "center", "up", "projection", "p", "window", "resolution"];
/// The camera's fields in a 2D scene (no `up`).
pub const CAMERA_2D: &[&str] = &["eye", "center", "projection", "p", "window", "resolution"];
/// The window's fields in a 3D scene.
pub const WINDOW_3D: &[&str] = &["l", "r", "b", "t"];
/// The window's fields in a 2D scene (a segment of the line).
pub const WINDOW_2D: &[&str] = &["l", "r"];
/// A light's fields.
pub const LIGHT: &[&str] = &["position", "intensity", "attenuation", "name"];
/// A material's fields.
pub const MATERIAL: &[&str] = &["ka", "kd", "ks", "n", "kt", "ior", "checker"];
/// A checker's fields.
pub const CHECKER: &[&str] = &["size", "kd2", "ka2"];
/// The object types of a 3D scene.
pub const TYPES_3D: &[&str] = &["sphere", "plane", "box", "triangle", "mesh"];
/// The object types of a 2D scene.
pub const TYPES_2D: &[&str] = &["sphere", "plane", "box", "triangle", "segment", "polygon"];
/// The fields every object may have besides its geometry.
pub const OBJECT: &[&str] = &["type", "name", "material"];
/// The fields of an object's `name` given per language (both required).
pub const NAME: &[&str] = crate::lang::CODES;

/// The geometry fields of an object of type `ty`, if it is a type of either dimension.
#[must_use]
pub fn geometry(ty: &str) -> Option<&'static [&'static str]> {
    Some(match ty {
        "sphere" => &["center", "radius"],
        "plane" => &["point", "normal"],
        "box" => &["min", "max"],
        "triangle" | "polygon" => &["vertices"],
        "segment" => &["a", "b"],
        "mesh" => &["obj"],
        _ => return None,
    })
}
