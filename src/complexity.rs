//! The lecture's cost, measured (algorithm.md §7 "Cost"): with one ray per pixel ray tracing
//! costs `O(p·n)` — every ray is tested against all n objects — and bounding volumes and
//! grouping bring it down towards `O(log n)`. [`crowd`] makes a scene of n spheres (circles in
//! 2D) in the view of a given scene's camera; [`measure`] renders it once with each structure
//! (`accel`, brute force first) and counts the tests per ray, the render's own counts. The
//! `complexity` figure draws what it returns; `benches/complexity.rs` times the same scenes.

use crate::accel::{Accel, AccelKind};
use crate::render::render_centers;
use crate::scene::material::Material;
use crate::scene::{Object, Scene};
use crate::shape::sphere::Sphere;
use crate::shape::{Dim, Shape};

/// The object counts of the `complexity` figure: n = 10 … 10 000, a decade apart.
pub const SIZES: [usize; 4] = [10, 100, 1_000, 10_000];

/// The pixels across of the `complexity` figure's renders: 12 × 9 in 3D (108 primary rays),
/// 12 in 2D. Tests per ray hardly change with the resolution, and 10 000 objects tested by brute
/// force stay a few million tests.
pub const FIGURE_WIDTH: usize = 12;

/// The share of the visible half-width that the crowd's cube (square in 2D) fills around the
/// point looked at.
const FILL: f64 = 0.8;

/// A sphere's radius is `RADIUS_SHARE · h / n^(1/dim)` for a cube of half-side h: the spheres
/// then fill about the same share of the cube whatever n (6.5 % of its volume in 3D).
const RADIUS_SHARE: f64 = 0.5;

/// A fixed, portable sequence in [−1, 1) (xorshift64*), seeded by `seed`.
struct Sequence(u64);

impl Sequence {
    fn next(&mut self) -> f64 {
        let s = &mut self.0;
        *s ^= *s >> 12;
        *s ^= *s << 25;
        *s ^= *s >> 27;
        // The top 53 bits make a double in [0, 1) exactly.
        (s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// `template` with its objects replaced by `n` spheres of the default material at
/// pseudo-random places (the same for a given n on every run) in the cube of half-side
/// `h = FILL · (visible half-width at the point looked at)` around the camera's centre C, radius
/// `RADIUS_SHARE · h / n^(1/dim)`; the camera `width` pixels across (the template's aspect
/// kept, 1 row in 2D), ray casting (`max_depth` 0), the template's lights.
#[must_use]
pub fn crowd<V: Dim>(template: &Scene<V>, n: usize, width: usize) -> Scene<V> {
    let cam = &template.camera;
    let half = cam.window.l.abs().max(cam.window.r.abs());
    let visible = match cam.projection {
        crate::scene::camera::Projection::Perspective => half * (cam.center - cam.eye).length() / cam.p,
        crate::scene::camera::Projection::Orthographic => half,
    };
    let h = FILL * visible;
    let radius = RADIUS_SHARE * h / (n.max(1) as f64).powf(1.0 / V::DIM as f64);
    let mut seq = Sequence(0x9E37_79B9_7F4A_7C15_u64 ^ n as u64);
    let objects = (0..n)
        .map(|_| {
            let mut center = cam.center;
            for a in 0..V::DIM {
                center[a] += h * seq.next();
            }
            let shape = Shape::Sphere(Sphere { center, radius });
            let scale = shape.scale();
            Object { name: None, shape, material: 0, scale }
        })
        .collect();
    let mut scene = template.clone();
    scene.objects = objects;
    scene.materials = vec![Material::DEFAULT];
    scene.max_depth = 0;
    let width = width.max(1);
    let rows = if V::DIM == 2 { 1 } else { (width * cam.ny / cam.nx.max(1)).max(1) };
    scene.camera.nx = width;
    scene.camera.ny = rows;
    scene
}

/// What one render of a crowd cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cost {
    /// The objects in the scene.
    pub n: usize,
    /// The structure that found the hits.
    pub kind: AccelKind,
    /// Every ray traced (primary and shadow).
    pub rays: u64,
    /// The ray–object tests.
    pub object_tests: u64,
    /// Every test: objects, bounding volumes, tree nodes and grid voxels.
    pub tests: u64,
}

impl Cost {
    /// Object tests per ray: `object_tests / rays`.
    #[must_use]
    pub fn object_tests_per_ray(&self) -> f64 {
        self.object_tests as f64 / self.rays.max(1) as f64
    }
    /// Tests of every kind per ray: `tests / rays`.
    #[must_use]
    pub fn tests_per_ray(&self) -> f64 {
        self.tests as f64 / self.rays.max(1) as f64
    }
}

/// The cost of rendering `crowd(template, n, width)` with each structure of
/// [`AccelKind::ALL`] (brute force first), for each n of `sizes`: one centre-sampled render
/// each, its own counts.
#[must_use]
pub fn measure<V: Dim>(template: &Scene<V>, sizes: &[usize], width: usize) -> Vec<Cost> {
    let mut costs = Vec::new();
    for &n in sizes {
        let scene = crowd(template, n, width);
        for kind in AccelKind::ALL {
            let accel = Accel::build(&scene, kind);
            let stats = render_centers(&scene, &accel, 0, Some(1)).stats;
            let t = stats.tests;
            costs.push(Cost {
                n,
                kind,
                rays: stats.rays.total(),
                object_tests: t.object,
                tests: t.object + t.bound + t.node + t.voxel,
            });
        }
    }
    costs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load::load_str;
    use crate::scene::AnyScene;

    fn template() -> Scene<glam::DVec3> {
        let text = r#"{"camera": {"eye": [0, 0.5, 4], "center": [0, 0, 0],
            "window": {"l": -0.5, "r": 0.5, "b": -0.375, "t": 0.375}, "resolution": [64, 48]},
            "lights": [{"position": [3, 4, 5]}]}"#;
        match load_str(text) {
            Ok(AnyScene::Space(s)) => s,
            _ => panic!("a 3D scene"),
        }
    }

    #[test]
    fn brute_force_tests_every_object_on_every_ray() {
        let costs = measure(&template(), &[10, 100], 8);
        let brute: Vec<&Cost> = costs.iter().filter(|c| c.kind == AccelKind::None).collect();
        assert_eq!(brute.len(), 2);
        for c in brute {
            // Each primary ray tests all n; a shadow ray stops at its first opaque occluder.
            assert!(c.object_tests_per_ray() <= c.n as f64 && c.object_tests_per_ray() > 0.5 * c.n as f64);
        }
        let bvh = costs.iter().find(|c| c.kind == AccelKind::Bvh && c.n == 100).unwrap();
        assert!(bvh.object_tests_per_ray() < 20.0, "{bvh:?}");
    }

    #[test]
    fn a_crowd_is_the_same_on_every_run_and_sized_by_n() {
        let (a, b) = (crowd(&template(), 50, 8), crowd(&template(), 50, 8));
        assert_eq!(a.objects.len(), 50);
        assert_eq!((a.camera.nx, a.camera.ny), (8, 6));
        for (x, y) in a.objects.iter().zip(&b.objects) {
            assert_eq!(format!("{:?}", x.shape), format!("{:?}", y.shape));
        }
    }
}
