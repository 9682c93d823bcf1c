//! A 3D triangle, watertight (algorithm.md §11 "Triangles"): the Woop–Benthin–Wald test —
//! translate to the ray origin, shear so the ray is the +z axis, three 2D edge functions — with an
//! exact re-evaluation where an edge function is 0 and no determinant epsilon.
//! Outward normal `(b − a) × (c − a)` normalised (counter-clockwise seen from outside, §3).
//!
//! `crossing` is shared with meshes.

use super::{Facet, SurfaceHit};
use crate::geom::diff_of_products;
use crate::geom::ray::Ray;
use crate::geom::Vector;
use glam::DVec3;

/// A triangle with vertices a, b, c (non-degenerate: checked when the scene loads).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// The vertices a, b, c.
    pub vertices: [DVec3; 3],
    /// The outward unit normal `normalize((b − a) × (c − a))`.
    pub normal: DVec3,
}

/// Where the ray's line crosses the triangle's plane inside it: distance and barycentrics.
pub(crate) struct Crossing {
    /// Distance along the ray's line (any sign).
    pub t: f64,
    /// Barycentric weights of a, b, c.
    pub weights: [f64; 3],
}

impl Triangle {
    /// A triangle, or `None` when its area is zero (or its normal cannot be formed).
    #[must_use]
    pub fn new(a: DVec3, b: DVec3, c: DVec3) -> Option<Self> {
        let normal = (b - a).cross(c - a).try_unit()?;
        Some(Self { vertices: [a, b, c], normal })
    }

    #[inline]
    fn crossing(&self, ray: &Ray<DVec3>) -> Option<Crossing> {
        crossing(&self.vertices, ray)
    }
}

/// What the Woop–Benthin–Wald test takes from the ray's direction alone, the same for every
/// triangle the ray meets: the axis `kz` where `|D|` is largest (x and y swapped when `D_kz < 0`,
/// to keep the winding) and the shear `S = (D_kx/D_kz, D_ky/D_kz, 1/D_kz)`. A mesh computes it
/// once per ray ([`super::Parts::prepare`]) instead of once per triangle; the test is the same,
/// bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shear {
    sx: f64,
    sy: f64,
    sz: f64,
    /// The axes `kx, ky, kz`, as bytes: the search keeps a `Shear` beside every question, and
    /// a smaller one is cheaper to set up and to move.
    k: [u8; 3],
}

impl Shear {
    /// The shear of direction `d`.
    #[inline]
    #[must_use]
    pub fn of(d: DVec3) -> Self {
        // Permute so that z is the axis where |D| is largest; swap x and y to keep the winding.
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        // Shear constants. The axes are 0, 1 or 2: they fit in a byte.
        #[allow(clippy::cast_possible_truncation)]
        let k = [kx as u8, ky as u8, kz as u8];
        Self { sx: d[kx] / d[kz], sy: d[ky] / d[kz], sz: 1.0 / d[kz], k }
    }
}

/// The Woop–Benthin–Wald test of the triangle `vertices`; `None` if the line misses or is
/// edge-on. Shared by scene triangles and mesh triangles.
#[inline]
pub(crate) fn crossing(vertices: &[DVec3; 3], ray: &Ray<DVec3>) -> Option<Crossing> {
    crossing_sheared(vertices, ray.origin, &Shear::of(ray.dir))
}

/// [`crossing`] of a ray from `origin` whose direction's shear is `shear`.
///
/// Inline in the walks of a native build: out of line, each test paid a call and the loads of
/// its arguments, 1.09× of mesh-100k's and mesh-1000k's render (bench/README.md, "Decisions
/// that were measured"). The WebAssembly module keeps it out of line, for its 3 MB budget.
#[cfg_attr(not(target_family = "wasm"), inline(always))]
#[cfg_attr(target_family = "wasm", inline)]
pub(crate) fn crossing_sheared(vertices: &[DVec3; 3], origin: DVec3, shear: &Shear) -> Option<Crossing> {
    let Shear { sx, sy, sz, k } = *shear;
    let [kx, ky, kz] = k.map(usize::from);
    // As arrays: a vector indexed by a run-time axis goes through a `match`, an array is a load.
    let [a, b, c] = vertices.map(|p| (p - origin).to_array());
    let sheared = |p: [f64; 3]| (p[kx] - sx * p[kz], p[ky] - sy * p[kz]);
    let (ax, ay) = sheared(a);
    let (bx, by) = sheared(b);
    let (cx, cy) = sheared(c);
    // Edge functions; an exact zero is re-evaluated with the error-free product difference.
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    if u == 0.0 || v == 0.0 || w == 0.0 {
        u = diff_of_products(cx, by, cy, bx);
        v = diff_of_products(ax, cy, ay, cx);
        w = diff_of_products(bx, ay, by, ax);
    }
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        // Edge-on triangles are invisible (§11).
        return None;
    }
    let t_scaled = u * (sz * a[kz]) + v * (sz * b[kz]) + w * (sz * c[kz]);
    let t = t_scaled / det;
    if !t.is_finite() {
        return None;
    }
    Some(Crossing { t, weights: [u / det, v / det, w / det] })
}

impl Facet<DVec3> for Triangle {
    #[inline]
    fn hit(&self, ray: &Ray<DVec3>) -> Option<SurfaceHit<DVec3>> {
        let x = self.crossing(ray)?;
        if !(x.t > 0.0) {
            return None;
        }
        // The hit point from the barycentrics, which lie on the triangle's plane by construction.
        let [a, b, c] = self.vertices;
        let point = a * x.weights[0] + b * x.weights[1] + c * x.weights[2];
        Some(SurfaceHit { t: x.t, point, normal: self.normal })
    }
    fn roots(&self, ray: &Ray<DVec3>) -> Vec<f64> {
        self.crossing(ray).map(|x| x.t).into_iter().collect()
    }
    fn bounds(&self) -> (DVec3, DVec3) {
        let [a, b, c] = self.vertices;
        (a.min(b).min(c), a.max(b).max(c))
    }
    fn scale(&self) -> f64 {
        self.vertices.iter().fold(0.0, |m, p| m.max(p.max_abs()))
    }
    fn points(&self) -> Vec<DVec3> {
        self.vertices.to_vec()
    }
    fn kind(&self) -> &'static str {
        "triangle"
    }
    fn meets_box(&self, lo: DVec3, hi: DVec3) -> bool {
        triangle_meets_box(&self.vertices, lo, hi)
    }
}

/// Whether the triangle `vertices` shares a point with the closed box `[lo, hi]`: no separating
/// axis among the box's 3 normals, the triangle's normal and the 9 products `e_i × a_j` of its
/// edges and the box's axes (Akenine-Möller's test). On an axis `m`, with the box's centre at
/// the origin, the triangle projects to `[min m·v_k, max m·v_k]` and the box to
/// `±Σ h_j·|m_j|`. Shared by scene triangles and mesh triangles.
pub(crate) fn triangle_meets_box(vertices: &[DVec3; 3], lo: DVec3, hi: DVec3) -> bool {
    let (c, h) = ((lo + hi) * 0.5, (hi - lo) * 0.5);
    let v = vertices.map(|p| p - c);
    let edges = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    let separates = |m: DVec3| {
        let p = v.map(|q| m.dot(q));
        let r = h.x * m.x.abs() + h.y * m.y.abs() + h.z * m.z.abs();
        p[0].min(p[1]).min(p[2]) > r || p[0].max(p[1]).max(p[2]) < -r
    };
    let mut axes = vec![DVec3::X, DVec3::Y, DVec3::Z, edges[0].cross(edges[1])];
    for e in edges {
        axes.extend([DVec3::X, DVec3::Y, DVec3::Z].map(|a| e.cross(a)));
    }
    !axes.into_iter().any(separates)
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn d1_shared_edge_regression() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(0.7, 0.9, 0.4);
        let c1 = DVec3::new(0.7, 0.2, 0.5);
        let c2 = DVec3::new(0.1, 0.9, 0.2);
        let t1 = Triangle::new(a, c1, b).unwrap();
        let t2 = Triangle::new(a, b, c2).unwrap();
        let ray = Ray::new(
            DVec3::new(0.3, -0.4, 2.0),
            DVec3::new(-0.102_923_780_281_094_08, 0.338_928_019_481_781_2, -0.935_165_489_666_297_6),
        );
        let h1 = t1.hit(&ray);
        let h2 = t2.hit(&ray);
        assert!(h1.is_some() || h2.is_some(), "the shared edge leaked");
        let t = h1.or(h2).unwrap().t;
        assert!((t - 1.815_518_235_821_386_8).abs() < 1e-15, "{t}");
    }

    #[test]
    fn d3_needle_triangle() {
        let tri = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1e-12, 0.0)).unwrap();
        let h = tri.hit(&Ray::new(DVec3::new(0.5, 5e-13, 1.0), DVec3::NEG_Z)).unwrap();
        assert_eq!(h.t, 1.0);
    }

    #[test]
    fn d4_degenerate_rejected_and_edge_on_invisible() {
        assert!(Triangle::new(DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)).is_none());
        let tri = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y).unwrap();
        let ray = Ray::new(DVec3::new(-1.0, 0.2, 0.0), DVec3::X);
        assert!(tri.hit(&ray).is_none());
        assert!(tri.roots(&ray).is_empty());
    }

    #[test]
    fn d2_watertight_over_a_fan() {
        // Six triangles around the vertex (0.3, 0.2, 0); rays aimed at the vertex and along edges.
        let centre = DVec3::new(0.3, 0.2, 0.0);
        let ring: Vec<DVec3> = (0..6)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::PI / 3.0 + 0.1;
                centre + DVec3::new(a.cos(), a.sin(), 0.05 * f64::from(k % 2))
            })
            .collect();
        let fan: Vec<Triangle> =
            (0..6).map(|k| Triangle::new(centre, ring[k], ring[(k + 1) % 6]).unwrap()).collect();
        let mut leaks = 0;
        for i in 0..500u32 {
            let s = f64::from(i) / 500.0;
            for target in [centre, centre + (ring[(i % 6) as usize] - centre) * s] {
                let eye = DVec3::new(0.1 + 0.001 * f64::from(i), -0.3, 3.0);
                let ray = Ray::new(eye, (target - eye).normalize());
                if fan.iter().all(|t| t.hit(&ray).is_none()) {
                    leaks += 1;
                }
            }
        }
        assert_eq!(leaks, 0);
    }
}
