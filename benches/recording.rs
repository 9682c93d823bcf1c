//! What recording costs (issue: "Recording costs nothing when off"): renders the example scenes
//! single-threaded three ways in one run — with `NoRecorder`, with a recorder that only counts
//! its calls, and with a fresh `EventLog` per pixel — and prints the time ratios.
//!
//! Run: `cargo bench --bench recording` (add `-- --quick` for one repetition).
#![allow(clippy::print_stdout)]

use std::path::Path;
use std::time::Instant;
use whitted::accel::{Accel, AccelKind};
use whitted::record::{CountingRecorder, EventLog, NoRecorder, Recorder};
use whitted::scene::load::load_str;
use whitted::scene::{AnyScene, Scene};
use whitted::shape::Dim;
use whitted::trace::Tracer;

/// Renders every pixel centre once on this thread; `fresh` makes the recorder of each pixel.
fn render_with<V: Dim, R: Recorder<V>>(
    scene: &Scene<V>,
    accel: &Accel<V>,
    mut fresh: impl FnMut() -> R,
) -> (f64, u64) {
    let cam = &scene.camera;
    let start = Instant::now();
    let mut checksum = 0u64;
    for j in 0..cam.ny {
        for i in 0..cam.nx {
            let (u, v) = cam.pixel_center(i, j);
            let mut tracer = Tracer::new(scene, accel, fresh());
            let c = tracer.trace_primary(&cam.primary_ray(u, v), &[u, v]);
            checksum = checksum.wrapping_add(c.0.iter().map(|x| x.to_bits()).fold(0, u64::wrapping_add));
            std::hint::black_box(&tracer.recorder);
        }
    }
    (start.elapsed().as_secs_f64(), checksum)
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

fn bench<V: Dim>(name: &str, scene: &Scene<V>, reps: usize) {
    let accel = Accel::build(scene, AccelKind::None);
    let (mut none, mut count, mut log) = (vec![], vec![], vec![]);
    let mut sums = [0u64; 3];
    for _ in 0..reps {
        let (t, s) = render_with(scene, &accel, || NoRecorder);
        none.push(t);
        sums[0] = s;
        let (t, s) = render_with(scene, &accel, CountingRecorder::default);
        count.push(t);
        sums[1] = s;
        let (t, s) = render_with(scene, &accel, EventLog::new);
        log.push(t);
        sums[2] = s;
    }
    assert!(sums[0] == sums[1] && sums[1] == sums[2], "recording changed the image");
    let (n, c, l) = (median(none), median(count), median(log));
    println!("| {name} | {n:.3} | {c:.3} | {l:.3} | {:.3} | {:.2} |", c / n, l / n);
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let reps = if quick { 1 } else { 5 };
    println!("| scene | NoRecorder (s) | counting (s) | EventLog (s) | counting / none | EventLog / none |");
    println!("|---|---:|---:|---:|---:|---:|");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for name in ["whitted.json", "flat.json"] {
        let text = std::fs::read_to_string(dir.join(name)).expect("example scene");
        match load_str(&text).expect("valid example scene") {
            AnyScene::Flat(mut s) => {
                // One row of 64 pixels is too short to time: widen it, keeping the window.
                s.camera.nx = 50_000;
                bench(name, &s, reps);
            }
            AnyScene::Space(s) => bench(name, &s, reps),
        }
    }
}
