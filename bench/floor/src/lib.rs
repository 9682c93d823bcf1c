//! Whitted's bench scene (`bench/scenes/whitted.json`) traced at 640x480, one ray per pixel
//! centre, by code that knows nothing but this scene: one plane, two spheres, one light, every
//! formula of algorithm.md that whitted uses (the stable sphere roots of §11, the spawn offset
//! δ = 2⁻⁴⁴·M, the shadow factor s = Π kt, N_f, Snell with TIR), written straight, with no
//! acceleration structure, no shape dispatch, no statistics of tests and no recorder.
//!
//! This library holds the scene, the scalar tracer ([`Scene::render`]) and what both programs
//! share ([`run`]): `whitted-floor` (src/main.rs) traces one ray at a time;
//! `whitted-floor-simd` (src/bin/whitted-floor-simd.rs) traces packets of rays, SIMD over the
//! lanes, into the same bytes. Each prints the trace time of each of 5 repetitions in one process
//! (or as many as its second argument says), the rays by kind (which must equal
//! `whitted render bench/scenes/whitted.json --aa center`'s), and writes the image as a binary
//! PPM so that its bytes can be compared with whitted's PNG. The gap between its time and
//! whitted's is what whitted's generality costs on this scene.
//!
//! Run: `cargo run --release --manifest-path bench/floor/Cargo.toml --bin whitted-floor -- /tmp/floor.ppm [REPETITIONS]`
#![forbid(unsafe_code)]
// `!(x >= 0.0)` is false for NaN too, as §11 wants.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use glam::DVec3;
use std::time::Instant;

/// A material, with whitted's defaults where the scene writes nothing.
#[derive(Clone, Copy)]
pub struct Material {
    pub ka: DVec3,
    pub kd: DVec3,
    pub ks: f64,
    pub n: i32,
    pub kt: f64,
    pub ior: f64,
    /// `(ka2, kd2)` of a checker of size 1.
    pub checker: Option<(DVec3, DVec3)>,
}

/// A sphere with its material index and its scale for the spawn offset (§11: ‖C‖∞ + r; a
/// plane's is ‖P‖∞).
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
    pub material: usize,
    pub scale: f64,
}

pub struct Scene {
    pub plane_point: DVec3,
    pub plane_normal: DVec3,
    /// The plane's scale for the spawn offset (§11: ‖P‖∞).
    pub plane_scale: f64,
    /// The plane is object 0, the spheres 1 and 2; materials: floor, mirror, glass.
    pub spheres: [Sphere; 2],
    pub materials: [Material; 3],
    pub light: DVec3,
    pub background: DVec3,
    pub max_depth: u32,
}

/// A perspective camera with p = 1 and the window [−2/3, 2/3] × [−1/2, 1/2].
pub struct Camera {
    pub eye: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
    pub nx: usize,
    pub ny: usize,
}

#[derive(Default)]
pub struct Rays {
    pub primary: u64,
    pub reflected: u64,
    pub transmitted: u64,
    pub shadow: u64,
}

/// 2⁻⁴⁴.
pub const OFFSET_SCALE: f64 = 1.0 / 17_592_186_044_416.0;

pub fn unit(v: DVec3) -> DVec3 {
    v / v.dot(v).sqrt()
}

/// round(255·clamp(c, 0, 1)), half away from zero (§5), as whitted's `image::to_byte` computes
/// it: 0 below x = 255·c = 0.5, else ⌊x + 0.5⌋ by the saturating cast.
pub fn to_byte(c: f64) -> u8 {
    let x = 255.0 * c;
    if x < 0.5 {
        0
    } else {
        (x + 0.5) as u8
    }
}

pub fn max_abs(v: DVec3) -> f64 {
    v.x.abs().max(v.y.abs()).max(v.z.abs())
}

/// The least root t > 0 of |O + tD − C|² = r² (§11: f = O − C, b' = f·D,
/// Δ' = r² − |f − b'D|², q = −(b' + sign(b')√Δ'), roots q and c/q).
pub fn sphere_t(o: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<f64> {
    let f = o - c;
    let b = f.dot(d);
    let perp = f - d * b;
    let delta = r * r - perp.dot(perp);
    if !(delta >= 0.0) {
        return None;
    }
    let roots = if delta == 0.0 {
        (-b, -b)
    } else {
        let q = -(b + delta.sqrt().copysign(if b >= 0.0 { 1.0 } else { -1.0 }));
        if q == 0.0 {
            (-b, -b)
        } else {
            let other = (f.dot(f) - r * r) / q;
            (q.min(other), q.max(other))
        }
    };
    if roots.0 > 0.0 {
        Some(roots.0)
    } else if roots.1 > 0.0 {
        Some(roots.1)
    } else {
        None
    }
}

/// t = (P − O)·N / (D·N), when finite and positive.
pub fn plane_t(o: DVec3, d: DVec3, p: DVec3, n: DVec3) -> Option<f64> {
    let t = (p - o).dot(n) / d.dot(n);
    (t > 0.0 && t.is_finite()).then_some(t)
}

pub fn spawn(point: DVec3, n_f: DVec3, dir: DVec3, delta: f64) -> DVec3 {
    if dir.dot(n_f) >= 0.0 {
        point + n_f * delta
    } else {
        point - n_f * delta
    }
}

impl Scene {
    /// The nearest hit: (object, t); equal t keeps the smaller index.
    pub fn nearest(&self, o: DVec3, d: DVec3) -> Option<(usize, f64)> {
        let mut best = plane_t(o, d, self.plane_point, self.plane_normal).map(|t| (0, t));
        for (k, s) in self.spheres.iter().enumerate() {
            if let Some(t) = sphere_t(o, d, s.center, s.radius) {
                if best.is_none_or(|(_, bt)| t < bt) {
                    best = Some((k + 1, t));
                }
            }
        }
        best
    }

    /// s = Π kt over the objects with 0 < t < d_L, in index order.
    pub fn shadow(&self, o: DVec3, d: DVec3, d_l: f64) -> f64 {
        let mut s = 1.0;
        if plane_t(o, d, self.plane_point, self.plane_normal).is_some_and(|t| t < d_l) {
            return 0.0; // the floor is opaque
        }
        for sphere in &self.spheres {
            if sphere_t(o, d, sphere.center, sphere.radius).is_some_and(|t| t < d_l) {
                s *= self.materials[sphere.material].kt;
                if s == 0.0 {
                    return 0.0;
                }
            }
        }
        s
    }

    /// Every pixel centre into a fresh image of the file's bytes (row 0 at the bottom, §2; as
    /// `whitted render` keeps it), and the rays traced.
    /// Not inlined, so that a profile shows the trace phase as one function.
    #[inline(never)]
    pub fn render(&self, camera: &Camera) -> (Vec<[u8; 3]>, Rays) {
        let (l, r, b, t) = (-0.666_666_666_666_666_6, 0.666_666_666_666_666_6, -0.5, 0.5);
        let (nx, ny) = (camera.nx, camera.ny);
        let mut image = vec![[0; 3]; nx * ny];
        let mut rays = Rays::default();
        for j in 0..ny {
            for i in 0..nx {
                let pu = l + (r - l) * (i as f64 + 0.5) / nx as f64;
                let pv = b + (t - b) * (j as f64 + 0.5) / ny as f64;
                let s = camera.eye + camera.u * pu + camera.v * pv - camera.w * 1.0;
                rays.primary += 1;
                let c = self.trace(camera.eye, unit(s - camera.eye), 1, &mut rays);
                image[j * nx + i] = [c.x, c.y, c.z].map(to_byte);
            }
        }
        (image, rays)
    }

    /// I = I_local + ks·R + kt·T, children while level ≤ max_depth.
    pub fn trace(&self, o: DVec3, d: DVec3, level: u32, rays: &mut Rays) -> DVec3 {
        let Some((object, t)) = self.nearest(o, d) else {
            return self.background;
        };
        self.shade(o, d, object, t, level, rays)
    }

    /// `trace` past `nearest`: the ray hit `object` at t.
    pub fn shade(&self, o: DVec3, d: DVec3, object: usize, t: f64, level: u32, rays: &mut Rays) -> DVec3 {
        let raw = o + d * t;
        let (point, normal, material, scale) = if object == 0 {
            let n = self.plane_normal;
            (raw - n * (raw - self.plane_point).dot(n), n, 0, self.plane_scale)
        } else {
            let s = &self.spheres[object - 1];
            let n = unit(raw - s.center);
            (s.center + n * s.radius, n, s.material, s.scale)
        };
        let entering = d.dot(normal) <= 0.0;
        let n_f = if entering { normal } else { -normal };
        let delta = OFFSET_SCALE * max_abs(point).max(max_abs(o)).max(t.abs()).max(scale);
        let m = self.materials[material];
        let (ka, kd) = match m.checker {
            Some((ka2, kd2)) => {
                let cells: f64 = (0..3).map(|k| (point[k] + 1e-10).floor()).sum();
                if cells.rem_euclid(2.0) == 1.0 {
                    (ka2, kd2)
                } else {
                    (m.ka, m.kd)
                }
            }
            None => (m.ka, m.kd),
        };
        let mut color = ka; // ambient (1, 1, 1)
        let to_light = self.light - point;
        let l = unit(to_light);
        let n_dot_l = n_f.dot(l);
        if n_dot_l > 0.0 {
            rays.shadow += 1;
            let origin = spawn(point, n_f, to_light, delta);
            let segment = self.light - origin;
            let s = self.shadow(origin, unit(segment), segment.length());
            let highlight = if m.ks > 0.0 { n_f.dot(unit(l - d)).max(0.0).powi(m.n) } else { 0.0 };
            color += kd * (s * n_dot_l) + DVec3::splat(s * m.ks * highlight);
        }
        if level > self.max_depth {
            return color;
        }
        if m.ks > 0.0 {
            let v = -d;
            let r = n_f * (2.0 * n_f.dot(v)) - v;
            rays.reflected += 1;
            color += self.trace(spawn(point, n_f, r, delta), r, level + 1, rays) * m.ks;
        }
        if m.kt > 0.0 {
            // Swap n1, n2 for a leaving ray (§3).
            let (n1, n2) = if entering { (1.0, m.ior) } else { (m.ior, 1.0) };
            let eta = n1 / n2;
            let c = (-d.dot(n_f)).clamp(-1.0, 1.0);
            let k = (1.0 - eta * eta) + (eta * c) * (eta * c);
            if k >= 0.0 {
                let dir = d * eta + n_f * (eta * c - k.sqrt());
                rays.transmitted += 1;
                color += self.trace(spawn(point, n_f, dir, delta), dir, level + 1, rays) * m.kt;
            }
        }
        color
    }
}

/// Whitted's bench scene and its camera, as `bench/scenes/whitted.json` writes them.
pub fn whitted_scene() -> (Scene, Camera) {
    let grey = DVec3::splat;
    let mirror =
        Material { ka: grey(0.07), kd: grey(0.175), ks: 0.75, n: 64, kt: 0.0, ior: 1.0, checker: None };
    let glass =
        Material { ka: grey(0.01), kd: grey(0.05), ks: 0.2, n: 128, kt: 0.9, ior: 1.5, checker: None };
    let floor = Material {
        ka: DVec3::new(0.135, 0.018, 0.012),
        kd: DVec3::new(0.765, 0.102, 0.068),
        ks: 0.0,
        n: 1,
        kt: 0.0,
        ior: 1.0,
        checker: Some((DVec3::new(0.1425, 0.1275, 0.015), DVec3::new(0.8075, 0.7225, 0.085))),
    };
    let sphere = |center: DVec3, radius: f64, material| Sphere {
        center,
        radius,
        material,
        scale: max_abs(center) + radius,
    };
    let plane_point = DVec3::new(0.0, -1.25, 0.0);
    let scene = Scene {
        plane_point,
        plane_normal: DVec3::Y,
        plane_scale: max_abs(plane_point),
        spheres: [sphere(DVec3::new(-0.9, -0.25, -1.6), 1.0, 1), sphere(DVec3::new(0.45, 0.2, 0.9), 0.75, 2)],
        materials: [floor, mirror, glass],
        light: DVec3::new(4.0, 6.0, 6.0),
        background: DVec3::new(0.35, 0.6, 0.95),
        max_depth: 4,
    };
    // The camera frame of §2: w = normalize(eye − center), u = normalize(up × w), v = w × u.
    let eye = DVec3::new(0.0, 0.8, 5.0);
    let w = unit(eye - DVec3::new(0.0, -0.2, 0.0));
    let u = unit(DVec3::Y.cross(w));
    let camera = Camera { eye, u, v: w.cross(u), w, nx: 640, ny: 480 };
    (scene, camera)
}

/// What both programs do around their render: `render` timed over the repetitions the second
/// argument asks for (5 by default), the rays by kind, and the PPM written where the first argument
/// says (top row first: rows count from the bottom, §2). `header`, if any, is printed first.
pub fn run(header: Option<&str>, render: impl Fn(&Scene, &Camera) -> (Vec<[u8; 3]>, Rays)) {
    let (scene, camera) = whitted_scene();
    let repetitions = std::env::args().nth(2).map_or(5, |n| n.parse().expect("repetitions: a whole number"));
    if let Some(header) = header {
        println!("{header}");
    }
    let mut rendered = None;
    for rep in 0..repetitions {
        let start = Instant::now();
        rendered = Some(render(&scene, &camera));
        println!("repetition {rep}: {:.4} s", start.elapsed().as_secs_f64());
    }
    let Some((image, rays)) = rendered else { return };
    let (nx, ny) = (camera.nx, camera.ny);
    println!(
        "rays: {} primary, {} reflected, {} transmitted, {} shadow",
        rays.primary, rays.reflected, rays.transmitted, rays.shadow
    );
    if let Some(path) = std::env::args().nth(1) {
        let mut bytes = format!("P6\n{nx} {ny}\n255\n").into_bytes();
        for j in (0..ny).rev() {
            bytes.extend(image[j * nx..(j + 1) * nx].iter().flatten());
        }
        std::fs::write(&path, bytes).expect("write the PPM");
    }
}
