//! `whitted grade`: a student's trace document of one pixel checked against whitted's own trace
//! (`request::grade`, the library's `grade`): exit 0 when everything present agrees, 1 at the
//! first divergence (the report on stdout), 2 for a bad document or scene.

use super::trace::LangArg;
use super::{load_scene, print_json, print_out, read_text, Failure};
use clap::Args;
use std::path::PathBuf;
use whitted::request::grade::{answer, grade, tolerance, MAX_DOCUMENT_BYTES};

/// Options of `whitted grade`.
#[derive(Args, Debug)]
pub struct GradeArgs {
    /// The scene file (JSON).
    scene: PathBuf,
    /// The student's trace document of one pixel (docs/grading.md).
    student: PathBuf,
    /// The report's language.
    #[arg(long, value_enum, default_value = "en")]
    lang: LangArg,
    /// The relative tolerance (absolute below 1).
    #[arg(long, value_name = "X", value_parser = tolerance, default_value_t = whitted::grade::DEFAULT_TOLERANCE)]
    tolerance: f64,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
}

/// Runs `whitted grade`.
pub fn run(args: &GradeArgs) -> Result<(), Failure> {
    let scene = load_scene(&args.scene)?;
    let name = args.student.display().to_string();
    let text = read_text(&args.student, MAX_DOCUMENT_BYTES)
        .map_err(|e| Failure::input(format!("{name}: cannot read the document: {e}")))?;
    let graded = grade(&scene, &name, &text, args.tolerance)?;
    let text = answer(&graded, args.lang.lang(), args.json);
    if args.json {
        print_json(&text)?;
    } else {
        print_out(&text)?;
    }
    if graded.ok() {
        Ok(())
    } else {
        // The report is the answer; exit code 1 says it found a divergence.
        Err(Failure::other(String::new()))
    }
}
