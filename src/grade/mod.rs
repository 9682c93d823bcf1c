//! Grading a student's ray tracer (docs/grading.md): the student's trace of one pixel
//! ([`student`]) is lined up with whitted's own ray tree ray by ray (P, R₁, T₁ … as
//! `record::names` names them), every quantity the student wrote is compared in the narration's
//! order with a relative tolerance ([`walk`]), and the first divergence is reported with its
//! formula, its inputs from the student's own earlier values and, where a classic mistake
//! explains it, that mistake and the lecture's rule ([`diagnose`]); [`report`] words it in
//! English or Romanian, or as JSON. [`exercise`] asks a student for the quantity one narration
//! step computes and checks the typed answer with the same agreement rule (the page's exercise
//! mode).
//!
//! Each student ray is traced by whitted from the student's own origin and direction, so the
//! expected values of a ray depend only on what the student got right before it: another spawn
//! offset or rounding upstream does not make every later number differ.
//!
//! The library computes; it does not print or read files: `whitted grade` (`src/cli/grade.rs`)
//! and the page (`web/`) call [`grade`].

pub mod diagnose;
pub mod exercise;
pub mod report;
pub mod student;
pub mod walk;

use crate::json::reader::ReadError;
use crate::scene::{AnyScene, Scene};
use crate::shape::Dim;
pub use diagnose::Mistake;

/// The default relative tolerance (docs/grading.md "Tolerance").
pub const DEFAULT_TOLERANCE: f64 = 1e-4;
/// How far a secondary ray's origin may sit from whitted's, relative to `max(1, ‖I‖∞)`: every
/// tracer moves the origin off the surface by an offset of its own (§11 "The spawn offset").
pub const OFFSET_SLACK: f64 = 1e-3;

/// The quantities compared, in the narration's order within a ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// `[u, v]` of the pixel's centre.
    WindowPoint,
    /// A ray's origin.
    Origin,
    /// A ray's direction.
    Direction,
    /// The object hit (or none).
    Object,
    /// The hit's t.
    T,
    /// The hit point I.
    Point,
    /// The outward normal N.
    Normal,
    /// One light's `N_f·L`.
    NDotL,
    /// One light's shadow factor s.
    Shadow,
    /// `I_local`.
    Local,
    /// A node's colour, or the pixel's.
    Colour,
    /// A ray the lecture spawns that the student does not.
    Missing,
    /// A ray the student spawns where the lecture spawns none.
    Extra,
}

impl Quantity {
    /// The name in `--json` (a contract, docs/grading.md).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::WindowPoint => "window_point",
            Self::Origin => "origin",
            Self::Direction => "direction",
            Self::Object => "object",
            Self::T => "t",
            Self::Point => "point",
            Self::Normal => "normal",
            Self::NDotL => "n_dot_l",
            Self::Shadow => "shadow",
            Self::Local => "local",
            Self::Colour => "colour",
            Self::Missing => "missing",
            Self::Extra => "extra",
        }
    }
}

/// A value shown as expected or found.
#[derive(Clone, Debug, PartialEq)]
pub enum Shown {
    /// A vector or a colour.
    Vector(Vec<f64>),
    /// A number.
    Number(f64),
    /// An object's name (or index, as text).
    Name(String),
    /// No hit: the ray meets nothing.
    Nothing,
    /// No shadow ray (`N_f·L ≤ 0`).
    NoShadowRay,
    /// A ray (of a `missing`/`extra` divergence): its kind's key.
    Ray(&'static str),
    /// No ray.
    NoRay,
}

/// The first divergence.
#[derive(Clone, Debug, PartialEq)]
pub struct Divergence {
    /// The keys from the primary ray down to the diverging ray (`[]` for P).
    pub path: Vec<&'static str>,
    /// Its name: `P`, `R₂`, `T₁`.
    pub ray: String,
    /// The names from P down to it: `P`, `T₁`, `R₂`.
    pub chain: Vec<String>,
    /// Its level (P = 1).
    pub level: u32,
    /// What differs.
    pub quantity: Quantity,
    /// The light, for `n_dot_l` and `shadow`.
    pub light: Option<usize>,
    /// whitted's value.
    pub expected: Shown,
    /// The student's.
    pub found: Shown,
    /// The formula, as the narration writes it, in English and Romanian.
    pub formula: [&'static str; 2],
    /// The formula's inputs, from the student's own earlier values where there are some.
    pub inputs: Vec<(String, Shown)>,
    /// The classic mistake that explains it, if one does.
    pub diagnosis: Option<Mistake>,
    /// The step of `whitted trace SCENE --pixel I,J` that computes it (from 1), if found.
    pub step: Option<usize>,
}

/// The outcome of grading one document.
#[derive(Clone, Debug, PartialEq)]
pub struct Grade {
    /// The pixel graded.
    pub pixel: Vec<usize>,
    /// The tolerance used.
    pub tolerance: f64,
    /// How many quantities were compared and agreed.
    pub checked: usize,
    /// The quantities the document does not give (`R₁.local`), in the order they would be compared.
    pub not_checked: Vec<String>,
    /// The first divergence, if any.
    pub first: Option<Divergence>,
}

impl Grade {
    /// True iff everything present agrees.
    #[must_use]
    pub fn ok(&self) -> bool {
        self.first.is_none()
    }
}

/// Why a tolerance is refused, if it is.
#[must_use]
pub fn tolerance_problem(tol: f64) -> Option<String> {
    (!(tol > 0.0 && tol < 1.0)).then(|| format!("--tolerance must be in (0, 1), got {tol}"))
}

/// Grades the student's document `text` against `scene` (docs/grading.md).
///
/// # Errors
/// A bad document: every problem with its JSON path.
pub fn grade(scene: &AnyScene, text: &str, tolerance: f64) -> Result<Grade, Vec<ReadError>> {
    match scene {
        AnyScene::Flat(s) => grade_in(s, text, tolerance),
        AnyScene::Space(s) => grade_in(s, text, tolerance),
    }
}

/// [`grade`] in a scene of known dimension.
///
/// # Errors
/// As [`grade`].
pub fn grade_in<V: Dim>(scene: &Scene<V>, text: &str, tolerance: f64) -> Result<Grade, Vec<ReadError>> {
    let cam = &scene.camera;
    let expect = student::Expect {
        lights: scene.lights.len(),
        objects: scene.objects.len(),
        resolution: (cam.nx, cam.ny),
    };
    let doc = student::read::<V>(text, expect)?;
    Ok(walk::compare(scene, &doc, tolerance))
}
