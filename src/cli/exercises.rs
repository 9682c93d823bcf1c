//! `whitted exercises`: an exercise sheet and its worked answers for one pixel
//! (`request::exercises`), written as `exercises.html` and `answers.html` in `--out`.

use super::accel::AccelArgs;
use super::figure::scene_name;
use super::trace::LangArg;
use super::{load_scene, output, print_out, write_file, Failure};
use clap::Args;
use std::path::PathBuf;
use whitted::request::exercises::sheets;
use whitted::request::parse::{self, PixelArg};

/// Options of `whitted exercises`.
#[derive(Args, Debug)]
pub struct ExercisesArgs {
    /// The scene file (JSON).
    scene: PathBuf,
    /// The pixel: I,J (column from the left, row from the BOTTOM); in 2D, I.
    #[arg(long, value_parser = parse::pixel, allow_hyphen_values = true)]
    pixel: PixelArg,
    /// The sheets' language.
    #[arg(long, value_enum, default_value = "en")]
    lang: LangArg,
    /// Picks which ray a question asks about where several would do.
    #[arg(long, value_name = "N", default_value_t = 1)]
    seed: u64,
    /// The folder for exercises.html and answers.html.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// The structure the trace walks (`--accel grid` adds the next-voxel question).
    #[command(flatten)]
    accel: AccelArgs,
}

/// Runs `whitted exercises`.
pub fn run(args: &ExercisesArgs) -> Result<(), Failure> {
    let scene = load_scene(&args.scene)?;
    let made = sheets(
        &scene,
        &scene_name(&args.scene),
        args.pixel,
        args.lang.lang(),
        args.seed,
        &args.accel.choice(),
    )?;
    output::create_folder(&args.out)?;
    write_file(&args.out.join("exercises.html"), made.exercises.as_bytes())?;
    write_file(&args.out.join("answers.html"), made.answers.as_bytes())?;
    print_out(&format!(
        "{} questions: {}, {}\n",
        made.count,
        args.out.join("exercises.html").display(),
        args.out.join("answers.html").display()
    ))?;
    Ok(())
}
