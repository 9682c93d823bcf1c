//! `whitted-floor`: Whitted's bench scene traced one ray at a time by the scalar tracer of this
//! crate's library (src/lib.rs), timed, its rays counted and its image written as a PPM.
//!
//! Run: `cargo run --release --manifest-path bench/floor/Cargo.toml --bin whitted-floor -- /tmp/floor.ppm [REPETITIONS]`
#![forbid(unsafe_code)]

fn main() {
    whitted_floor::run(None, whitted_floor::Scene::render);
}
