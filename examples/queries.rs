//! whitted's search alone, as a query server for `bench/embree.py`: the same batches of rays the
//! Embree harness (`bench/embree_harness.c`) answers, timed the same way, so that the two peers'
//! ns per ray measure the same thing: the queries, without the camera, the shading or the image.
//!
//! The server loads a scene with whitted's own loader, builds the structure a render builds
//! (`Accel::build_for_render` with the default options) and answers each ray through the very
//! functions the tracer calls: `Accel::nearest` for a ray, `Accel::occluders` for a shadow
//! segment, with no recorder (`NoRecorder`), as `whitted render` does.
//!
//! Protocol, little-endian binary on stdin / stdout (the harness's, but for the start: the server
//! reads its scene from the file named on its command line, so nothing is uploaded):
//!   out  f64 build_s, f64 0 (the harness's memory growth: not measured here), f64 0 (a version)
//!   then any number of batches:
//!   in   u32 op (1 nearest, 2 occluded, 0 end), u64 n, n rays of 7 f32 (origin, direction, tfar)
//!   out  nearest:  f64 seconds, then n i32 primitive (−1: no hit) and n f32 t
//!        occluded: f64 seconds, then n u8 (1: something lies on the segment)
//!        end:      f64 peak_mb (this process's VmHWM), and the program exits
//! A primitive is a mesh's triangle by its index in the OBJ, else the object's index. A ray's
//! direction arrives in f32, so not quite of unit length: it is made unit in f64 before the clock
//! starts (whitted's rays are unit, §2), and t is given back along the direction as sent, tfar
//! taken along it, as Embree reads them. The seconds time the queries alone.
//!
//! Build and run (embree.py does both): `cargo build --release --example queries`, then
//! `target/release/examples/queries SCENE.json`.
#![forbid(unsafe_code)]

use glam::DVec3;
use std::io::{self, BufReader, BufWriter, Read, Write};
use std::path::Path;
use std::time::Instant;
use whitted::accel::{Accel, AccelKind, AccelOptions};
use whitted::geom::ray::Ray;
use whitted::record::event::ObjectRef;
use whitted::record::stats::Stats;
use whitted::record::NoRecorder;
use whitted::scene::load::load_str_with;
use whitted::scene::{AnyScene, Scene};

/// Floats a ray takes in a batch: origin (3), direction (3), tfar (1).
const RAY_FLOATS: usize = 7;
/// The batch operations.
const OP_END: u32 = 0;
const OP_NEAREST: u32 = 1;
const OP_OCCLUDED: u32 = 2;
/// The largest scene and OBJ files read, bytes (the bench's meshes are under 64 MB).
const MAX_FILE_BYTES: u64 = 1 << 30;

fn main() {
    if let Err(e) = serve() {
        eprintln!("queries: {e}");
        std::process::exit(1);
    }
}

/// Loads the scene named on the command line and answers batches until the end.
fn serve() -> Result<(), String> {
    let path = std::env::args().nth(1).ok_or("usage: queries SCENE.json")?;
    let scene = match load(Path::new(&path))? {
        AnyScene::Space(s) => s,
        AnyScene::Flat(_) => return Err("the bench's scenes are 3D".into()),
    };
    let clock = Instant::now();
    let accel = Accel::build_for_render(&scene, &AccelOptions::of(AccelKind::Bvh));
    let build_s = clock.elapsed().as_secs_f64();
    let server = Server { scene: &scene, accel: &accel };
    let mut input = BufReader::new(io::stdin().lock());
    let mut output = BufWriter::new(io::stdout().lock());
    put(&mut output, &[build_s.to_le_bytes(), 0f64.to_le_bytes(), 0f64.to_le_bytes()].concat())?;
    loop {
        let op = u32::from_le_bytes(take(&mut input)?);
        if op == OP_END {
            put(&mut output, &peak_mb().to_le_bytes())?;
            return Ok(());
        }
        let n = usize::try_from(u64::from_le_bytes(take(&mut input)?)).map_err(|e| e.to_string())?;
        let rays = read_rays(&mut input, n)?;
        match op {
            OP_NEAREST => server.nearest(&rays, &mut output)?,
            OP_OCCLUDED => server.occluded(&rays, &mut output)?,
            other => return Err(format!("unknown operation {other}")),
        }
    }
}

/// A ray of a batch, unit and in f64: the ray, and the length of the direction as sent (t along
/// the sent direction is t along the unit one divided by it).
struct Query {
    ray: Ray<DVec3>,
    length: f64,
    tfar: f64,
}

/// What answers the queries: the scene and the structure a render builds over it.
struct Server<'s> {
    scene: &'s Scene<DVec3>,
    accel: &'s Accel<DVec3>,
}

impl Server<'_> {
    /// Answers a batch of nearest-hit queries: seconds, primitives, t.
    fn nearest(&self, rays: &[Query], out: &mut impl Write) -> Result<(), String> {
        let mut stats = Stats::default();
        let mut hits = Vec::with_capacity(rays.len());
        let clock = Instant::now();
        for q in rays {
            hits.push(
                self.accel.nearest(self.scene, &q.ray, &mut stats, &mut NoRecorder).map(|(o, h)| (o, h.t)),
            );
        }
        let seconds = clock.elapsed().as_secs_f64();
        let mut bytes = seconds.to_le_bytes().to_vec();
        for hit in &hits {
            let prim = hit.map_or(-1, |(o, _)| primitive(o));
            bytes.extend_from_slice(&prim.to_le_bytes());
        }
        for (hit, q) in hits.iter().zip(rays) {
            // t along the direction as sent, in f32 as Embree answers.
            let t = hit.map_or(f64::INFINITY, |(_, t)| t / q.length);
            #[allow(clippy::cast_possible_truncation)]
            bytes.extend_from_slice(&(t as f32).to_le_bytes());
        }
        put(out, &bytes)
    }

    /// Answers a batch of shadow segments: seconds, whether each is blocked.
    fn occluded(&self, rays: &[Query], out: &mut impl Write) -> Result<(), String> {
        let mut stats = Stats::default();
        let mut blocked = vec![0u8; rays.len()];
        let clock = Instant::now();
        for (q, b) in rays.iter().zip(&mut blocked) {
            // The bench's scenes are opaque: the first occluder reported ends the search.
            self.accel.occluders(self.scene, &q.ray, q.tfar * q.length, &mut stats, &mut NoRecorder, |_| {
                *b = 1;
                false
            });
        }
        let seconds = clock.elapsed().as_secs_f64();
        put(out, &[&seconds.to_le_bytes()[..], &blocked].concat())
    }
}

/// Embree's primitive number: a mesh's triangle by its OBJ index, else the object.
fn primitive(o: ObjectRef) -> i32 {
    i32::try_from(o.triangle.unwrap_or(o.index)).unwrap_or(i32::MAX)
}

/// Reads n rays and makes each direction unit in f64.
fn read_rays(input: &mut impl Read, n: usize) -> Result<Vec<Query>, String> {
    let mut raw = vec![0u8; n * RAY_FLOATS * 4];
    input.read_exact(&mut raw).map_err(|e| format!("a short batch: {e}"))?;
    let floats: Vec<f64> =
        raw.chunks_exact(4).map(|b| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))).collect();
    Ok(floats
        .chunks_exact(RAY_FLOATS)
        .map(|r| {
            let dir = DVec3::new(r[3], r[4], r[5]);
            let length = dir.length();
            Query { ray: Ray::new(DVec3::new(r[0], r[1], r[2]), dir / length), length, tfar: r[6] }
        })
        .collect())
}

/// The scene at `path`, its OBJ files read beside it.
fn load(path: &Path) -> Result<AnyScene, String> {
    let read = |p: &Path| -> Result<String, String> {
        let text = std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()))?;
        if text.len() as u64 > MAX_FILE_BYTES {
            return Err(format!("{}: larger than {MAX_FILE_BYTES} bytes", p.display()));
        }
        Ok(text)
    };
    let folder = path.parent().unwrap_or_else(|| Path::new("."));
    let text = read(path)?;
    load_str_with(&text, &|name: &str| read(&folder.join(name)))
        .map_err(|errors| errors.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n"))
}

/// This process's peak resident memory, MB (VmHWM; 0 where /proc is not there).
fn peak_mb() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(0.0, |kb| kb / 1024.0)
}

fn take<const N: usize>(input: &mut impl Read) -> Result<[u8; N], String> {
    let mut bytes = [0u8; N];
    input.read_exact(&mut bytes).map_err(|e| format!("stdin ended: {e}"))?;
    Ok(bytes)
}

fn put(out: &mut impl Write, bytes: &[u8]) -> Result<(), String> {
    out.write_all(bytes).and_then(|()| out.flush()).map_err(|e| format!("stdout: {e}"))
}
