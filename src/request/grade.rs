//! `whitted grade`'s answer: a student's trace document graded against the scene (`grade`), its
//! errors worded as a scene's are (one line per problem, with the document's name and JSON path),
//! and the report as text or JSON. Shared by the command line and the page.

use super::Failure;
use crate::accel::{Accel, AccelOptions};
use crate::grade::{self, report, walk, Grade};
use crate::lang::Lang;
use crate::scene::{AnyScene, Scene};
use crate::shape::Dim;

/// The largest student document read: a tree of depth 64 with every field is far smaller.
pub const MAX_DOCUMENT_BYTES: u64 = 16 << 20;

/// `--tolerance X`: a number in (0, 1).
///
/// # Errors
/// A message naming `--tolerance` and its range.
pub fn tolerance(text: &str) -> Result<f64, String> {
    let x: f64 = text.trim().parse().map_err(|_| format!("--tolerance: expected a number, got `{text}`"))?;
    match grade::tolerance_problem(x) {
        Some(problem) => Err(problem),
        None => Ok(x),
    }
}

/// Grades the document `text` (called `name` in errors) against `scene`.
///
/// # Errors
/// Bad input: every problem of the document, one line each, `NAME: PATH: PROBLEM`.
pub fn grade(scene: &AnyScene, name: &str, text: &str, tolerance: f64) -> Result<Grade, Failure> {
    if let Some(problem) = grade::tolerance_problem(tolerance) {
        return Err(Failure::input(problem));
    }
    grade::grade(scene, text, tolerance).map_err(|errors| {
        let lines: Vec<String> = errors.iter().map(|e| format!("{name}: {e}")).collect();
        Failure::input(lines.join("\n"))
    })
}

/// The step of the narration traced with `accel` and `depth` (the page's, which may narrate with
/// another structure than `whitted trace`'s default) that computes the first divergence of `g`.
#[must_use]
pub fn page_step(scene: &AnyScene, g: &Grade, accel: &AccelOptions, depth: Option<u32>) -> Option<usize> {
    fn step<V: Dim>(s: &Scene<V>, g: &Grade, accel: &AccelOptions, depth: Option<u32>) -> Option<usize> {
        let d = g.first.as_ref()?;
        let built = Accel::build_with(s, accel);
        walk::step_in(s, &g.pixel, d, &built, depth.unwrap_or(s.max_depth))
    }
    match scene {
        AnyScene::Flat(s) => step(s, g, accel, depth),
        AnyScene::Space(s) => step(s, g, accel, depth),
    }
}

/// The report: the text in `lang`, or the JSON (pretty, with a newline).
#[must_use]
pub fn answer(g: &Grade, lang: Lang, json: bool) -> String {
    if json {
        serde_json::to_string_pretty(&report::json(g, lang)).map_or_else(|e| e.to_string(), |t| t + "\n")
    } else {
        report::text(g, lang)
    }
}
