//! `whitted-floor-simd`: the floor program's scene (this crate's library, src/lib.rs) traced in
//! packets of W rays, SIMD over the lanes, into the same bytes with the same rays: how much
//! faster exact code can go on one core.
//!
//! Every lane computes what the library's scalar tracer computes for its ray, operation for
//! operation in the same order (no FMA, no reassociation, no reciprocals; `floor`, `min`, `max`,
//! `copysign`, `clamp` and `powi` with the scalar semantics), so its bits are the scalar ones;
//! branches become masks and selects, and a lane's garbage on a path it does not take is dropped.
//!
//! - Primary rays: a packet is W neighbours in a row: generation, normalisation, the plane and
//!   both spheres, the nearest hit. The lanes on the floor are shaded in the packet (checker,
//!   shadow ray, the shadow test against all three objects); the floor has no children.
//! - The sphere pixels' ray trees (`WAVES`): a batch of such pixels is traced a level at a time,
//!   each level's rays in packets (nearest hit, shading with each lane's material, shadow ray,
//!   highlight, the reflected and transmitted rays into the next level), then the colours are
//!   summed from the deepest level up, I = (I_local + ks·R) + kt·T as the recursion sums them.
//!   Without `WAVES` they are traced one ray at a time by the library's scalar `shade`.
//!
//! Build-time knobs: `FLOOR_SIMD_LANES` (2, 4 or 8; default 8 with AVX-512, else 4),
//! `FLOOR_SIMD_DISPATCH` (0 or 1; default 1 on x86-64: a baseline build runs its packets in AVX2
//! code when the CPU has it, chosen at run time by `pulp`) and `FLOOR_SIMD_WAVES` (0 or 1;
//! default 1 with AVX2 or the dispatch); the first line of the output says which.
//! It prints what `whitted-floor` prints, writes the same PPM, and must give the same bytes:
//!
//! ```text
//! cargo build --release --manifest-path bench/floor/Cargo.toml
//! bench/floor/target/release/whitted-floor /tmp/floor.ppm
//! bench/floor/target/release/whitted-floor-simd /tmp/floor-simd.ppm
//! cmp /tmp/floor.ppm /tmp/floor-simd.ppm
//! ```
//!
//! For a CPU's own SIMD width: `RUSTFLAGS="-C target-cpu=native"` with its own
//! `CARGO_TARGET_DIR` (bench/README.md, "How far from the floor").
#![forbid(unsafe_code)]
// `!(x >= 0.0)` is false for NaN too, as §11 wants.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use glam::DVec3;
use whitted_floor::{run, to_byte, Camera, Material, Rays, Scene, OFFSET_SCALE};

/// Lanes per packet: 8 with AVX-512 (one register of f64), else 4 (two SSE2 registers, one
/// AVX one); `FLOOR_SIMD_LANES` at build time may say 2, 4 or 8.
const W: usize = match option_env!("FLOOR_SIMD_LANES") {
    Some(w) => match w.as_bytes() {
        b"2" => 2,
        b"8" => 8,
        _ => 4,
    },
    None if cfg!(target_feature = "avx512f") => 8,
    None => 4,
};

/// W lanes of f64. Every operation is the scalar one applied to each lane on its own (no FMA, no
/// reassociation, no reciprocal), so each lane's bits are those of the scalar code; LLVM turns
/// the lane loops into SIMD instructions.
#[derive(Clone, Copy)]
struct F([f64; W]);

/// W lanes of a condition, each all ones or all zeros (as SIMD compares give them).
#[derive(Clone, Copy)]
struct B([u64; W]);

impl F {
    #[inline(always)]
    fn splat(x: f64) -> F {
        F([x; W])
    }

    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> F {
        F(std::array::from_fn(|k| f(self.0[k])))
    }

    #[inline(always)]
    fn zip(self, other: F, f: impl Fn(f64, f64) -> f64) -> F {
        F(std::array::from_fn(|k| f(self.0[k], other.0[k])))
    }

    #[inline(always)]
    fn test(self, other: F, f: impl Fn(f64, f64) -> bool) -> B {
        B(std::array::from_fn(|k| if f(self.0[k], other.0[k]) { !0 } else { 0 }))
    }

    #[inline(always)]
    fn lt(self, other: F) -> B {
        self.test(other, |a, b| a < b)
    }

    #[inline(always)]
    fn le(self, other: F) -> B {
        self.test(other, |a, b| a <= b)
    }

    #[inline(always)]
    fn gt(self, other: F) -> B {
        self.test(other, |a, b| a > b)
    }

    #[inline(always)]
    fn ge(self, other: F) -> B {
        self.test(other, |a, b| a >= b)
    }

    #[inline(always)]
    fn eq(self, other: F) -> B {
        self.test(other, |a, b| a == b)
    }

    #[inline(always)]
    fn sqrt(self) -> F {
        self.map(f64::sqrt)
    }

    #[inline(always)]
    fn abs(self) -> F {
        self.map(f64::abs)
    }

    #[inline(always)]
    fn min(self, other: F) -> F {
        self.zip(other, f64::min)
    }

    #[inline(always)]
    fn max(self, other: F) -> F {
        self.zip(other, f64::max)
    }

    /// ⌊x⌋ per lane, exactly `f64::floor`.
    #[inline(always)]
    fn floor(self) -> F {
        #[cfg(target_feature = "sse4.1")]
        {
            self.map(f64::floor)
        }
        // Plain SSE2 has no rounding instruction (f64::floor is a call to libm per lane): round
        // to nearest by adding and taking away 2⁵² (exact below 2⁵², where the spacing of
        // |x| + 2⁵² is 1), then step down where that went up. Whole numbers, ±∞ and NaN (|x| ≥
        // 2⁵² or unordered) are themselves; −0 stays −0; (−1, −0) goes to −1, [0, 1) to +0.
        #[cfg(not(target_feature = "sse4.1"))]
        {
            const BIG: f64 = 4_503_599_627_370_496.0; // 2⁵²
            let small = self.abs().lt(F::splat(BIG));
            let near = ((self.abs() + F::splat(BIG)) - F::splat(BIG)).zip(self, f64::copysign);
            let floor = near.gt(self).select(near - F::splat(1.0), near);
            small.select(floor, self)
        }
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl std::ops::$trait for F {
            type Output = F;
            #[inline(always)]
            fn $method(self, other: F) -> F {
                self.zip(other, |a, b| a $op b)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl std::ops::Neg for F {
    type Output = F;
    #[inline(always)]
    fn neg(self) -> F {
        self.map(|a| -a)
    }
}

impl B {
    const NONE: B = B([0; W]);
    const ALL: B = B([!0; W]);

    #[inline(always)]
    fn and(self, other: B) -> B {
        B(std::array::from_fn(|k| self.0[k] & other.0[k]))
    }

    #[inline(always)]
    fn or(self, other: B) -> B {
        B(std::array::from_fn(|k| self.0[k] | other.0[k]))
    }

    #[inline(always)]
    fn not(self) -> B {
        B(self.0.map(|m| !m))
    }

    #[inline(always)]
    fn any(self) -> bool {
        self.0.iter().fold(0, |a, &m| a | m) != 0
    }

    #[cfg_attr(target_feature = "sse4.1", allow(dead_code))]
    #[inline(always)]
    fn all(self) -> bool {
        self.0.iter().fold(!0, |a, &m| a & m) != 0
    }

    #[inline(always)]
    fn count(self) -> u64 {
        self.0.iter().map(|&m| m & 1).sum()
    }

    #[inline(always)]
    fn lane(self, k: usize) -> bool {
        self.0[k] != 0
    }

    /// `a` where the lane is set, else `b`, bit for bit.
    #[inline(always)]
    fn select(self, a: F, b: F) -> F {
        F(std::array::from_fn(|k| {
            f64::from_bits((a.0[k].to_bits() & self.0[k]) | (b.0[k].to_bits() & !self.0[k]))
        }))
    }
}

/// W vectors, one a lane, as three rows of W coordinates.
#[derive(Clone, Copy)]
struct F3 {
    x: F,
    y: F,
    z: F,
}

impl F3 {
    #[inline(always)]
    fn splat(v: DVec3) -> F3 {
        F3 { x: F::splat(v.x), y: F::splat(v.y), z: F::splat(v.z) }
    }

    /// `DVec3::splat` per lane.
    #[inline(always)]
    fn same(a: F) -> F3 {
        F3 { x: a, y: a, z: a }
    }

    #[inline(always)]
    fn lane(self, k: usize) -> DVec3 {
        DVec3::new(self.x.0[k], self.y.0[k], self.z.0[k])
    }

    #[inline(always)]
    fn select(m: B, a: F3, b: F3) -> F3 {
        F3 { x: m.select(a.x, b.x), y: m.select(a.y, b.y), z: m.select(a.z, b.z) }
    }

    /// glam's order: (x·x' + y·y') + z·z'.
    #[inline(always)]
    fn dot(self, o: F3) -> F {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline(always)]
    fn unit(self) -> F3 {
        self / self.dot(self).sqrt()
    }

    #[inline(always)]
    fn max_abs(self) -> F {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }
}

impl std::ops::Add for F3 {
    type Output = F3;
    #[inline(always)]
    fn add(self, o: F3) -> F3 {
        F3 { x: self.x + o.x, y: self.y + o.y, z: self.z + o.z }
    }
}

impl std::ops::Sub for F3 {
    type Output = F3;
    #[inline(always)]
    fn sub(self, o: F3) -> F3 {
        F3 { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
}

impl std::ops::Neg for F3 {
    type Output = F3;
    #[inline(always)]
    fn neg(self) -> F3 {
        F3 { x: -self.x, y: -self.y, z: -self.z }
    }
}

/// `DVec3 * f64` per lane.
impl std::ops::Mul<F> for F3 {
    type Output = F3;
    #[inline(always)]
    fn mul(self, s: F) -> F3 {
        F3 { x: self.x * s, y: self.y * s, z: self.z * s }
    }
}

/// `DVec3 / f64` per lane.
impl std::ops::Div<F> for F3 {
    type Output = F3;
    #[inline(always)]
    fn div(self, s: F) -> F3 {
        F3 { x: self.x / s, y: self.y / s, z: self.z / s }
    }
}

/// `sphere_t` for a packet: which lanes hit, and their t.
#[inline(always)]
fn sphere_packet(o: F3, d: F3, c: DVec3, r: f64) -> (B, F) {
    let f = o - F3::splat(c);
    let b = f.dot(d);
    let perp = f - d * b;
    let rr = F::splat(r * r);
    let delta = rr - perp.dot(perp);
    let real = delta.ge(F::splat(0.0));
    let sign = b.ge(F::splat(0.0)).select(F::splat(1.0), F::splat(-1.0));
    let q = -(b + delta.sqrt().zip(sign, f64::copysign));
    let double = delta.eq(F::splat(0.0)).or(q.eq(F::splat(0.0)));
    let other = (f.dot(f) - rr) / q;
    let near = double.select(-b, q.min(other));
    let far = double.select(-b, q.max(other));
    let near_ahead = near.gt(F::splat(0.0));
    let hit = real.and(near_ahead.or(far.gt(F::splat(0.0))));
    (hit, near_ahead.select(near, far))
}

/// `plane_t` for a packet.
#[inline(always)]
fn plane_packet(o: F3, d: F3, p: DVec3, n: DVec3) -> (B, F) {
    let n = F3::splat(n);
    let t = (F3::splat(p) - o).dot(n) / d.dot(n);
    (t.gt(F::splat(0.0)).and(t.abs().lt(F::splat(f64::INFINITY))), t)
}

/// `spawn` per lane.
#[inline(always)]
fn spawn_packet(point: F3, n_f: F3, dir: F3, delta: F) -> F3 {
    let out = dir.dot(n_f).ge(F::splat(0.0));
    F3::select(out, point + n_f * delta, point - n_f * delta)
}

/// Whether the sphere pixels' ray trees are traced in packets too (a wave of rays a level at a
/// time, `trace_trees`), or one ray at a time by the scalar `trace`. The waves pay with AVX2 and
/// AVX-512 and lose with SSE2 alone (16 registers of 2 lanes: the packets spill); the default
/// follows the target, `FLOOR_SIMD_WAVES` = 0 or 1 at build time overrides it.
const WAVES: bool = match option_env!("FLOOR_SIMD_WAVES") {
    Some(w) => matches!(w.as_bytes(), [b'1', ..]),
    None => cfg!(target_feature = "avx2") || DISPATCH,
};

/// No child.
const NONE: u32 = u32::MAX;

/// The rays of one level, by coordinate, with the index of each one's parent (in the level
/// above, or the pixel for the first level).
#[derive(Default)]
struct Wave {
    o: [Vec<f64>; 3],
    d: [Vec<f64>; 3],
    parent: Vec<u32>,
}

impl Wave {
    #[inline(always)]
    fn len(&self) -> usize {
        self.parent.len()
    }

    /// Push a ray; its index.
    #[inline(always)]
    fn push(&mut self, o: DVec3, d: DVec3, parent: u32) -> u32 {
        for (k, c) in self.o.iter_mut().enumerate() {
            c.push(o[k]);
        }
        for (k, c) in self.d.iter_mut().enumerate() {
            c.push(d[k]);
        }
        self.parent.push(parent);
        (self.parent.len() - 1) as u32
    }

    #[inline(always)]
    fn clear(&mut self) {
        for c in self.o.iter_mut().chain(self.d.iter_mut()) {
            c.clear();
        }
        self.parent.clear();
    }

    /// Repeat the last ray's coordinates to a whole number of packets (`len` stays).
    #[inline(always)]
    fn pad(&mut self) {
        for c in self.o.iter_mut().chain(self.d.iter_mut()) {
            let last = *c.last().expect("a ray");
            c.resize(c.len().next_multiple_of(W), last);
        }
    }

    #[inline(always)]
    fn packet(&self, p: usize) -> (F3, F3) {
        let load = |c: &Vec<f64>| F(c[p..p + W].try_into().expect("W lanes"));
        (
            F3 { x: load(&self.o[0]), y: load(&self.o[1]), z: load(&self.o[2]) },
            F3 { x: load(&self.d[0]), y: load(&self.d[1]), z: load(&self.d[2]) },
        )
    }
}

/// The rays of one level as traced: local colour, the material's ks and kt, the index of each
/// child in the next level, and (once the level below has its own) the colour.
#[derive(Default)]
struct Nodes {
    local: Vec<DVec3>,
    ks: Vec<f64>,
    kt: Vec<f64>,
    reflected: Vec<u32>,
    transmitted: Vec<u32>,
    color: Vec<DVec3>,
}

impl Nodes {
    #[inline(always)]
    fn clear(&mut self) {
        self.local.clear();
        self.ks.clear();
        self.kt.clear();
        self.reflected.clear();
        self.transmitted.clear();
    }
}

/// Sphere pixels in a batch.
const TREES: usize = 256;

/// The waves and nodes of a batch of ray trees, a level each (levels 1 to max_depth + 1, and
/// an empty wave past the last).
struct Trees {
    waves: Vec<Wave>,
    nodes: Vec<Nodes>,
}

impl Trees {
    #[inline(always)]
    fn new(levels: usize) -> Trees {
        Trees {
            waves: (0..=levels).map(|_| Wave::default()).collect(),
            nodes: (0..=levels).map(|_| Nodes::default()).collect(),
        }
    }
}

/// What `shade_packet` gives for each lane.
struct Shaded {
    color: F3,
    ks: F,
    kt: F,
    reflect: B,
    r_origin: F3,
    r_dir: F3,
    transmit: B,
    t_origin: F3,
    t_dir: F3,
}

/// The checker's second colour: Σ ⌊p_k + 10⁻¹⁰⌋ odd. The sum is a whole number (or ±∞, NaN), so
/// `rem_euclid(2) == 1` holds exactly when half of it is a whole number and a half.
#[inline(always)]
fn odd_cell(point: F3) -> B {
    let e = F::splat(1e-10);
    let v = [point.x + e, point.y + e, point.z + e];
    // Plain SSE2 has no rounding instruction: where every |v| < 2⁵¹, v + 1.5·2⁵² is v rounded
    // to a whole number m (the spacing there is 1) whose lowest bit is m's parity; ⌊v⌋ is m, or
    // m − 1 where m > v. The three ⌊v⌋ then sum exactly (below 2⁵³), and the sum is odd when
    // an odd number of them are.
    #[cfg(not(target_feature = "sse4.1"))]
    {
        const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5·2⁵²
        const SMALL: f64 = 2_251_799_813_685_248.0; // 2⁵¹
        if v.iter().all(|c| c.abs().lt(F::splat(SMALL)).all()) {
            let mut odd = [0u64; W];
            for c in v {
                let m = c + F::splat(MAGIC);
                let down = (m - F::splat(MAGIC)).gt(c);
                for ((o, m), down) in odd.iter_mut().zip(m.0).zip(down.0) {
                    *o ^= (m.to_bits() ^ down) & 1;
                }
            }
            return B(odd.map(|o| 0u64.wrapping_sub(o)));
        }
    }
    let cells = v[0].floor() + v[1].floor() + v[2].floor();
    let half = cells * F::splat(0.5);
    (half - half.floor()).eq(F::splat(0.5))
}

/// `f64::powi` per lane as compiler-builtins' `__powidf2` computes it (square and multiply, from
/// the lowest bit); the exponents are ≥ 0.
#[inline(always)]
fn powi(a: F, n: [i32; W]) -> F {
    let mut a = a;
    let mut product = F::splat(1.0);
    let mut bits = n.map(|n| {
        assert!(n >= 0, "a negative exponent");
        n as u32
    });
    loop {
        let odd = B(bits.map(|b| if b & 1 != 0 { !0 } else { 0 }));
        product = odd.select(product * a, product);
        bits = bits.map(|b| b >> 1);
        if bits.iter().all(|&b| b == 0) {
            return product;
        }
        a = a * a;
    }
}

/// The scene traced in packets: the scalar tracer's fields and methods through `Deref`, the
/// packet code here.
struct Packets<'s>(&'s Scene);

impl std::ops::Deref for Packets<'_> {
    type Target = Scene;
    #[inline(always)]
    fn deref(&self) -> &Scene {
        self.0
    }
}

impl Packets<'_> {
    /// Every pixel centre into a fresh image of the file's bytes (row 0 at the bottom, §2; as
    /// `whitted render` keeps it), and the rays traced: the primary rays W at a time (a packet of
    /// W neighbours in a row), their floor hits shaded in the packet, the sphere hits one lane at
    /// a time by the scalar `shade`.
    /// Inlined into its caller, [`render_plain`] or [`Render`]'s dispatch, so that the whole trace
    /// is compiled inside the function that enables the CPU's features.
    #[inline(always)]
    fn render(&self, camera: &Camera) -> (Vec<[u8; 3]>, Rays) {
        let (l, r, b, t) = (-0.666_666_666_666_666_6, 0.666_666_666_666_666_6, -0.5, 0.5);
        let (nx, ny) = (camera.nx, camera.ny);
        assert!(nx % W == 0, "a row is a whole number of packets");
        let mut image = vec![[0; 3]; nx * ny];
        let mut rays = Rays::default();
        let eye = F3::splat(camera.eye);
        let u = F3::splat(camera.u);
        let w = F3::splat(camera.w * 1.0);
        let background = F3::splat(self.background);
        // With WAVES, the sphere pixels go to `trees`, traced a batch of about TREES pixels at a
        // time so that the waves stay small (in cache, and allocated once per render).
        let mut trees = Trees::new(self.max_depth as usize + 1);
        for j in 0..ny {
            let pv = b + (t - b) * (j as f64 + 0.5) / ny as f64;
            let v = F3::splat(camera.v * pv);
            for i0 in (0..nx).step_by(W) {
                let pu = F(std::array::from_fn(|k| l + (r - l) * ((i0 + k) as f64 + 0.5) / nx as f64));
                let s = eye + u * pu + v - w;
                let d = (s - eye).unit();
                rays.primary += W as u64;
                let (t, chosen) = self.nearest_packet(eye, d);
                let mut color = background;
                if chosen[0].any() {
                    color = F3::select(
                        chosen[0],
                        self.shade_floor_packet(eye, d, t, chosen[0], &mut rays),
                        color,
                    );
                }
                let spheres = chosen[1].or(chosen[2]);
                let pixels = &mut image[j * nx + i0..j * nx + i0 + W];
                for (k, pixel) in pixels.iter_mut().enumerate() {
                    if spheres.lane(k) && WAVES {
                        trees.waves[0].push(camera.eye, d.lane(k), (j * nx + i0 + k) as u32);
                    } else if spheres.lane(k) {
                        let object = if chosen[1].lane(k) { 1 } else { 2 };
                        let c = self.shade(camera.eye, d.lane(k), object, t.0[k], 1, &mut rays);
                        *pixel = [c.x, c.y, c.z].map(to_byte);
                    } else {
                        let c = color.lane(k);
                        *pixel = [c.x, c.y, c.z].map(to_byte);
                    }
                }
            }
            if trees.waves[0].len() >= TREES {
                self.trace_trees(&mut trees, &mut image, &mut rays);
            }
        }
        self.trace_trees(&mut trees, &mut image, &mut rays);
        (image, rays)
    }

    /// The ray trees of the pixels in `trees`' first wave, a level at a time (a wave), in
    /// packets of W rays; their colours into `image`; the waves emptied.
    #[inline(always)]
    fn trace_trees(&self, trees: &mut Trees, image: &mut [[u8; 3]], rays: &mut Rays) {
        let levels = trees.waves.len();
        let mut depth = 0;
        while depth < levels && trees.waves[depth].len() > 0 {
            let (here, below) = trees.waves.split_at_mut(depth + 1);
            let next = below.first_mut().expect("no child past max_depth + 1");
            self.trace_wave(&mut here[depth], depth as u32 + 1, next, &mut trees.nodes[depth], rays);
            depth += 1;
        }
        // Each node's colour, deepest level first: I = I_local + ks·R + kt·T.
        for level in (0..depth).rev() {
            let (here, below) = trees.nodes.split_at_mut(level + 1);
            let (nodes, below) = (&mut here[level], &below[0].color);
            nodes.color.clear();
            for i in 0..nodes.local.len() {
                let mut c = nodes.local[i];
                if nodes.reflected[i] != NONE {
                    c += below[nodes.reflected[i] as usize] * nodes.ks[i];
                }
                if nodes.transmitted[i] != NONE {
                    c += below[nodes.transmitted[i] as usize] * nodes.kt[i];
                }
                nodes.color.push(c);
            }
        }
        if depth > 0 {
            for (c, &pixel) in trees.nodes[0].color.iter().zip(&trees.waves[0].parent) {
                image[pixel as usize] = [c.x, c.y, c.z].map(to_byte);
            }
        }
        for wave in &mut trees.waves {
            wave.clear();
        }
    }

    /// Trace one wave (the rays of one level), W at a time, into `nodes`: each ray's local colour,
    /// its weights, and its children pushed onto `next` (their index in it noted in the node).
    #[inline(always)]
    fn trace_wave(&self, wave: &mut Wave, level: u32, next: &mut Wave, nodes: &mut Nodes, rays: &mut Rays) {
        let n = wave.len();
        wave.pad();
        nodes.clear();
        for p in (0..n).step_by(W) {
            let (o, d) = wave.packet(p);
            let (t, chosen) = self.nearest_packet(o, d);
            let live = B(std::array::from_fn(|k| if p + k < n { !0 } else { 0 }));
            let hit = chosen[0].or(chosen[1]).or(chosen[2]).and(live);
            // A packet whose hits are all on one object is shaded by a copy of `shade_packet`
            // for that object alone (the masks constant, the other objects' work folded away).
            let only =
                |k: usize| -> [B; 3] { std::array::from_fn(|j| if j == k { B::ALL } else { B::NONE }) };
            let on = |k: usize| chosen[k].and(hit).any();
            let shaded = match (on(0), on(1), on(2)) {
                (_, false, false) => self.shade_packet(o, d, t, only(0), hit, level, rays),
                (false, true, false) => self.shade_packet(o, d, t, only(1), hit, level, rays),
                (false, false, true) => self.shade_packet(o, d, t, only(2), hit, level, rays),
                _ => self.shade_packet(o, d, t, chosen, hit, level, rays),
            };
            for k in 0..W.min(n - p) {
                let (mut reflected, mut transmitted) = (NONE, NONE);
                if shaded.reflect.lane(k) {
                    rays.reflected += 1;
                    reflected = next.push(shaded.r_origin.lane(k), shaded.r_dir.lane(k), (p + k) as u32);
                }
                if shaded.transmit.lane(k) {
                    rays.transmitted += 1;
                    transmitted = next.push(shaded.t_origin.lane(k), shaded.t_dir.lane(k), (p + k) as u32);
                }
                nodes.local.push(if hit.lane(k) { shaded.color.lane(k) } else { self.background });
                nodes.ks.push(shaded.ks.0[k]);
                nodes.kt.push(shaded.kt.0[k]);
                nodes.reflected.push(reflected);
                nodes.transmitted.push(transmitted);
            }
        }
    }

    /// `shade` for the lanes of `hit` (which hit object k where `chosen[k]` is set), any
    /// material: the local colour, the weights ks and kt, and the children's rays where they are
    /// traced (`reflect`, `transmit`, empty past max_depth).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn shade_packet(
        &self,
        o: F3,
        d: F3,
        t: F,
        chosen: [B; 3],
        hit: B,
        level: u32,
        rays: &mut Rays,
    ) -> Shaded {
        let raw = o + d * t;
        let plane = chosen[0];
        let second = chosen[2];
        let [s1, s2] = &self.spheres;
        // The point and normal on a sphere, then on the plane where `plane` says.
        let pn = F3::splat(self.plane_normal);
        let (mut point, mut normal) = (raw, pn);
        if chosen[1].or(chosen[2]).any() {
            let center = F3::select(second, F3::splat(s2.center), F3::splat(s1.center));
            let radius = second.select(F::splat(s2.radius), F::splat(s1.radius));
            normal = (raw - center).unit();
            point = center + normal * radius;
        }
        if plane.any() {
            let plane_point = raw - pn * (raw - F3::splat(self.plane_point)).dot(pn);
            point = F3::select(plane, plane_point, point);
            normal = F3::select(plane, pn, normal);
        }
        let scale =
            plane.select(F::splat(self.plane_scale), second.select(F::splat(s2.scale), F::splat(s1.scale)));
        let mats = [&self.materials[0], &self.materials[s1.material], &self.materials[s2.material]];
        let pick = |f: &dyn Fn(&Material) -> f64| {
            plane.select(F::splat(f(mats[0])), second.select(F::splat(f(mats[2])), F::splat(f(mats[1]))))
        };
        let pick3 = |f: &dyn Fn(&Material) -> DVec3| {
            F3::select(
                plane,
                F3::splat(f(mats[0])),
                F3::select(second, F3::splat(f(mats[2])), F3::splat(f(mats[1]))),
            )
        };
        let (ks, kt, ior) = (pick(&|m| m.ks), pick(&|m| m.kt), pick(&|m| m.ior));
        let exponent: [i32; W] = std::array::from_fn(|k| {
            mats[if plane.lane(k) {
                0
            } else if second.lane(k) {
                2
            } else {
                1
            }]
            .n
        });
        let entering = d.dot(normal).le(F::splat(0.0));
        let n_f = F3::select(entering, normal, -normal);
        let delta = F::splat(OFFSET_SCALE) * point.max_abs().max(o.max_abs()).max(t.abs()).max(scale);
        let (mut ka, mut kd) = (pick3(&|m| m.ka), pick3(&|m| m.kd));
        for (k, m) in mats.iter().enumerate() {
            if let Some((ka2, kd2)) = m.checker {
                if chosen[k].and(hit).any() {
                    let second_colour = chosen[k].and(odd_cell(point));
                    ka = F3::select(second_colour, F3::splat(ka2), ka);
                    kd = F3::select(second_colour, F3::splat(kd2), kd);
                }
            }
        }
        let mut color = ka; // ambient (1, 1, 1)
        let light = F3::splat(self.light);
        let to_light = light - point;
        let l = to_light.unit();
        let n_dot_l = n_f.dot(l);
        let lit = n_dot_l.gt(F::splat(0.0)).and(hit);
        if lit.any() {
            rays.shadow += lit.count();
            let origin = spawn_packet(point, n_f, to_light, delta);
            let segment = light - origin;
            let length = segment.dot(segment).sqrt();
            let s = self.shadow_packet(origin, segment / length, length);
            let shiny = ks.gt(F::splat(0.0));
            let highlight = if shiny.and(lit).any() {
                shiny.select(powi(n_f.dot((l - d).unit()).max(F::splat(0.0)), exponent), F::splat(0.0))
            } else {
                F::splat(0.0)
            };
            color = F3::select(lit, color + (kd * (s * n_dot_l) + F3::same(s * ks * highlight)), color);
        }
        let deeper = if level > self.max_depth { B::NONE } else { hit };
        let reflect = deeper.and(ks.gt(F::splat(0.0)));
        let transmit = deeper.and(kt.gt(F::splat(0.0)));
        let mut shaded = Shaded {
            color,
            ks,
            kt,
            reflect,
            r_origin: point,
            r_dir: d,
            transmit: B::NONE,
            t_origin: point,
            t_dir: d,
        };
        if reflect.any() {
            let v = -d;
            let r = n_f * (F::splat(2.0) * n_f.dot(v)) - v;
            shaded.r_origin = spawn_packet(point, n_f, r, delta);
            shaded.r_dir = r;
        }
        if transmit.any() {
            // Swap n1, n2 for a leaving ray (§3).
            let one = F::splat(1.0);
            let eta = entering.select(one, ior) / entering.select(ior, one);
            let c = (-d.dot(n_f)).map(|c| c.clamp(-1.0, 1.0));
            let k = (one - eta * eta) + (eta * c) * (eta * c);
            let dir = d * eta + n_f * (eta * c - k.sqrt());
            shaded.transmit = transmit.and(k.ge(F::splat(0.0)));
            shaded.t_origin = spawn_packet(point, n_f, dir, delta);
            shaded.t_dir = dir;
        }
        shaded
    }

    /// `nearest` for a packet: the nearest t of each lane and which object each lane hit (a
    /// lane in none of the three masks hit nothing); equal t keeps the smaller index.
    #[inline(always)]
    fn nearest_packet(&self, o: F3, d: F3) -> (F, [B; 3]) {
        let (plane, t_plane) = plane_packet(o, d, self.plane_point, self.plane_normal);
        let mut best = t_plane;
        let mut any = plane;
        let mut chosen = [plane, B::NONE, B::NONE];
        for (k, s) in self.spheres.iter().enumerate() {
            let (hit, t) = sphere_packet(o, d, s.center, s.radius);
            let take = hit.and(any.not().or(t.lt(best)));
            best = take.select(t, best);
            for c in &mut chosen[..=k] {
                *c = c.and(take.not());
            }
            chosen[k + 1] = take;
            any = any.or(take);
        }
        (best, chosen)
    }

    /// `shade` at level 1 for the lanes of `mask`, which hit the floor (object 0) at t; the
    /// other lanes compute garbage that the caller drops. The floor has ks = kt = 0: no
    /// highlight and no children.
    #[inline(always)]
    fn shade_floor_packet(&self, o: F3, d: F3, t: F, mask: B, rays: &mut Rays) -> F3 {
        let m = self.materials[0];
        let n = F3::splat(self.plane_normal);
        let raw = o + d * t;
        let point = raw - n * (raw - F3::splat(self.plane_point)).dot(n);
        let entering = d.dot(n).le(F::splat(0.0));
        let n_f = F3::select(entering, n, -n);
        let delta = F::splat(OFFSET_SCALE)
            * point.max_abs().max(o.max_abs()).max(t.abs()).max(F::splat(self.plane_scale));
        let (ka, kd) = match m.checker {
            Some((ka2, kd2)) => {
                let odd = odd_cell(point);
                (
                    F3::select(odd, F3::splat(ka2), F3::splat(m.ka)),
                    F3::select(odd, F3::splat(kd2), F3::splat(m.kd)),
                )
            }
            None => (F3::splat(m.ka), F3::splat(m.kd)),
        };
        let light = F3::splat(self.light);
        let to_light = light - point;
        let l = to_light.unit();
        let n_dot_l = n_f.dot(l);
        let lit = n_dot_l.gt(F::splat(0.0)).and(mask);
        if !lit.any() {
            return ka;
        }
        rays.shadow += lit.count();
        let origin = spawn_packet(point, n_f, to_light, delta);
        let segment = light - origin;
        let length = segment.dot(segment).sqrt();
        let s = self.shadow_packet(origin, segment / length, length);
        let highlight = F::splat(0.0); // ks = 0
        let color = ka + (kd * (s * n_dot_l) + F3::same(s * F::splat(m.ks) * highlight));
        F3::select(lit, color, ka)
    }

    /// `shadow` for a packet.
    #[inline(always)]
    fn shadow_packet(&self, o: F3, d: F3, d_l: F) -> F {
        let (plane, t_plane) = plane_packet(o, d, self.plane_point, self.plane_normal);
        let blocked = plane.and(t_plane.lt(d_l));
        let mut s = F::splat(1.0);
        for sphere in &self.spheres {
            let (hit, t) = sphere_packet(o, d, sphere.center, sphere.radius);
            // Once s is 0 it stays +0 (kt ≥ 0), as the scalar early return gives.
            s = hit.and(t.lt(d_l)).select(s * F::splat(self.materials[sphere.material].kt), s);
        }
        blocked.select(F::splat(0.0), s)
    }
}

/// Whether the trace picks its instruction set when it runs (`pulp`): with AVX2 and FMA on the CPU,
/// a baseline x86-64 build runs its packets in AVX2 code, else in the SSE2 code it was built for.
/// On by default on x86-64 (a build for a target with AVX2 has nothing to choose: it keeps its
/// own code); `FLOOR_SIMD_DISPATCH` = 0 at build time turns it off.
const DISPATCH: bool = cfg!(target_arch = "x86_64")
    && !cfg!(target_feature = "avx2")
    && !matches!(option_env!("FLOOR_SIMD_DISPATCH"), Some(d) if matches!(d.as_bytes(), [b'0', ..]));

/// The render compiled once for the build's target, out of line, so that a profile shows the
/// trace phase as one function.
#[inline(never)]
fn render_plain(scene: &Scene, camera: &Camera) -> (Vec<[u8; 3]>, Rays) {
    Packets(scene).render(camera)
}

/// The render as `pulp` dispatches it: `with_simd` is compiled once per instruction set, each copy
/// inside a function with that set's target features, and `Arch::dispatch` calls the one the CPU
/// has. Every function of the packet path is `#[inline(always)]`, so that all of it lands in the
/// copy (a function left out of line would be compiled for the baseline target alone). A closure
/// does not do: its body is compiled outside the features' function.
#[cfg(target_arch = "x86_64")]
struct Render<'a> {
    scene: &'a Scene,
    camera: &'a Camera,
}

#[cfg(target_arch = "x86_64")]
impl pulp::WithSimd for Render<'_> {
    type Output = (Vec<[u8; 3]>, Rays);
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Self::Output {
        Packets(self.scene).render(self.camera)
    }
}

fn main() {
    // The CPU is asked once: its answer names the code in the header and picks it in every repetition.
    #[cfg(target_arch = "x86_64")]
    let arch = DISPATCH.then(pulp::Arch::new);
    #[cfg(target_arch = "x86_64")]
    let chosen = match arch {
        Some(pulp::Arch::V3(_)) => "AVX2 chosen at run time",
        Some(_) => "the build's target (no AVX2 on this CPU)",
        None => "the build's target",
    };
    #[cfg(not(target_arch = "x86_64"))]
    let chosen = "the build's target";
    let header = format!(
        "packets of {W} lanes, sphere pixels' trees {}, {chosen}",
        if WAVES { "in waves" } else { "by scalar recursion" },
    );
    run(Some(&header), |scene, camera| {
        // Behind the constant too, so that a build without the dispatch compiles no AVX2 copy.
        #[cfg(target_arch = "x86_64")]
        if DISPATCH {
            if let Some(arch) = arch {
                return arch.dispatch(Render { scene, camera });
            }
        }
        render_plain(scene, camera)
    });
}
