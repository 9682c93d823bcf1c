//! What a scene is, after validation (product.md "Scene files", algorithm.md §11 "Validation
//! instead of sanitising"). The path is JSON text → `load` (every check, every default) →
//! [`Scene`], valid by construction.
//!
//! An `Object` carries its `scale` for the spawn offset, computed at load; `AnyScene` is a 2D or a
//! 3D scene.

pub mod camera;
pub mod light;
pub mod load;
pub mod material;

use crate::lang::{Both, Lang};
use crate::shape::{Dim, Shape};
use camera::Camera;
use glam::{DVec2, DVec3};
use light::Light;
use material::{Material, Rgb};

/// One object of the scene: its shape, its material and its optional name.
#[derive(Clone, Debug)]
pub struct Object<V: Dim> {
    /// The `name` field, if given: one string for every language, or one per language
    /// (`{"en": "mirror", "ro": "oglindă"}`).
    pub name: Option<Both>,
    /// The geometry.
    pub shape: Shape<V>,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// `shape.scale()`, computed once: the object's part of the spawn offset's magnitude M
    /// (§11), which every hit on it needs.
    pub scale: f64,
}

/// A validated scene in 2D (`V = DVec2`) or 3D (`V = DVec3`).
///
/// # Guarantees
/// Every number is finite and at most 1e100 in magnitude; directions are unit; radii, `p`, the
/// window and the resolution are positive; every material index is valid; every coefficient is in
/// its range (§11); `max_depth ≤ 64`; there is no mix of dimensions.
#[derive(Clone, Debug)]
pub struct Scene<V: Dim> {
    /// The camera.
    pub camera: Camera<V>,
    /// The colour of a ray that hits nothing.
    pub background: Rgb,
    /// Ia, the ambient light.
    pub ambient: Rgb,
    /// Children are spawned by a node at level n iff `n ≤ max_depth` (§6).
    pub max_depth: u32,
    /// Point lights.
    pub lights: Vec<Light<V>>,
    /// Every material: the named ones first, in file order, then the inline ones.
    pub materials: Vec<Material>,
    /// The objects, in file order (the index breaks ties of equal t, §6).
    pub objects: Vec<Object<V>>,
}

impl<V: Dim> Scene<V> {
    /// The material of object `index`.
    #[must_use]
    pub fn material_of(&self, index: usize) -> &Material {
        &self.materials[self.objects[index].material]
    }
    /// True iff some object transmits (`kt > 0`): otherwise no T ray can ever be spawned.
    #[must_use]
    pub fn has_transparent(&self) -> bool {
        (0..self.objects.len()).any(|i| self.material_of(i).transmits())
    }
    /// True iff some object reflects (`ks > 0`).
    #[must_use]
    pub fn has_reflective(&self) -> bool {
        (0..self.objects.len()).any(|i| self.material_of(i).reflects())
    }
    /// The most ray nodes one primary ray's tree can hold at `max_depth`: levels 1 to
    /// `max_depth + 1` (§6), doubling at each level when some object both reflects and transmits
    /// (`2^(max_depth+1) − 1`), one a level when rays only reflect or only transmit, 1 otherwise.
    #[must_use]
    pub fn worst_tree_rays(&self, max_depth: u32) -> f64 {
        let both = (0..self.objects.len()).any(|i| {
            let m = self.material_of(i);
            m.reflects() && m.transmits()
        });
        let levels = f64::from(max_depth) + 1.0;
        if both {
            levels.exp2() - 1.0
        } else if self.has_reflective() || self.has_transparent() {
            levels
        } else {
            1.0
        }
    }
    /// How an object is called in `lang`: its `name` in that language, else its index.
    #[must_use]
    pub fn object_label(&self, index: usize, lang: Lang) -> String {
        match &self.objects[index].name {
            Some(n) => n.get(lang).to_owned(),
            None => format!("objects[{index}]"),
        }
    }
}

/// A scene of either dimension; the camera's vectors decide which.
#[derive(Clone, Debug)]
pub enum AnyScene {
    /// A 2D scene.
    Flat(Scene<DVec2>),
    /// A 3D scene.
    Space(Scene<DVec3>),
}

/// Scenes the tests of several modules share.
#[cfg(test)]
pub(crate) mod fixtures {
    use proptest::prelude::*;

    /// A 2D scene of `nx` pixels: a checkered floor line, a glass circle and a mirror one, two
    /// lights, `max_depth` 3.
    pub fn line(nx: usize) -> String {
        format!(
            r#"{{ "camera": {{ "eye": [0, 6], "center": [0, 0], "window": {{ "l": -1.5, "r": 1.5 }}, "resolution": [{nx}] }},
            "max_depth": 3, "lights": [ {{ "position": [3, 5] }}, {{ "position": [-2, 1] }} ],
            "objects": [
              {{ "type": "plane", "point": [0, -2], "normal": [0, 1],
                "material": {{ "kd": [0.8, 0.7, 0.2], "checker": {{ "size": 0.3, "kd2": [0.1, 0.2, 0.3] }} }} }},
              {{ "type": "sphere", "center": [0.3, 1], "radius": 0.8, "material": {{ "ks": 0.2, "kt": 0.9, "ior": 1.5 }} }},
              {{ "type": "sphere", "center": [-1.5, -1], "radius": 0.5, "material": {{ "ks": 0.8 }} }} ] }}"#
        )
    }

    /// The materials of [`objects`]' spheres: matte, mirror, glass, and a transparent one of
    /// index 1.
    pub const MATERIALS: [&str; 4] = [
        r#"{ "kd": [0.6, 0.5, 0.4] }"#,
        r#"{ "ks": 0.6, "kd": 0.3 }"#,
        r#"{ "ks": 0.1, "kt": 0.8, "ior": 1.33 }"#,
        r#"{ "kt": 0.5, "ior": 1.0, "kd": 0.2 }"#,
    ];

    /// The JSON objects of a checkered floor through (0, −1, 0) with `normal` and `spheres`,
    /// each `(centre, radius, material)`, the material an index in [`MATERIALS`].
    pub fn objects(normal: (f64, f64, f64), spheres: &[((f64, f64, f64), f64, usize)]) -> String {
        let mut objects = vec![format!(
            r#"{{ "type": "plane", "point": [0, -1, 0], "normal": [{}, {}, {}],
                "material": {{ "kd": [0.7, 0.2, 0.1], "checker": {{ "size": 0.7, "kd2": [0.9, 0.9, 0.2] }} }} }}"#,
            normal.0, normal.1, normal.2
        )];
        for ((x, y, z), r, m) in spheres {
            objects.push(format!(
                r#"{{ "type": "sphere", "center": [{x}, {y}, {z}], "radius": {r}, "material": {} }}"#,
                MATERIALS[*m]
            ));
        }
        objects.join(",")
    }

    /// Up to 3 random spheres for [`objects`]: centre, radius and an index in [`MATERIALS`].
    pub fn random_spheres() -> impl Strategy<Value = Vec<((f64, f64, f64), f64, usize)>> {
        prop::collection::vec(
            ((-2.0..2.0f64, -1.0..2.0f64, -2.0..2.0f64), 0.1..1.2f64, 0..MATERIALS.len()),
            0..4,
        )
    }

    /// One or two random light positions for [`lights`].
    pub fn random_lights() -> impl Strategy<Value = Vec<(f64, f64, f64)>> {
        prop::collection::vec((-5.0..5.0f64, -2.0..6.0f64, -5.0..5.0f64), 1..3)
    }

    /// A random eye in front of the scene's origin (the camera looks at (0, 0, 0)).
    pub fn random_eye() -> impl Strategy<Value = (f64, f64, f64)> {
        (-4.0..4.0f64, -0.5..4.0f64, 2.0..7.0f64)
    }

    /// The JSON lights of white point lights at `positions`.
    pub fn lights(positions: &[(f64, f64, f64)]) -> String {
        let lights: Vec<String> =
            positions.iter().map(|(x, y, z)| format!(r#"{{ "position": [{x}, {y}, {z}] }}"#)).collect();
        lights.join(",")
    }
}
