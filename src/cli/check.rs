//! `whitted check`: validate a scene and say what it models — dimension, objects by type,
//! lights, which ray kinds can occur and why, the depth (`request::check`) — or every error at
//! once (exit code 2).

use super::{load_scene, print_out, Failure};
use clap::Args;
use std::path::PathBuf;
use whitted::request::check::report;

/// Options of `whitted check`.
#[derive(Args, Debug)]
pub struct CheckArgs {
    /// The scene file (JSON).
    scene: PathBuf,
}

/// Runs `whitted check`.
pub fn run(args: &CheckArgs) -> Result<(), Failure> {
    let scene = load_scene(&args.scene)?;
    print_out(&report(&scene, &args.scene.display().to_string()))
}
