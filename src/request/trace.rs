//! One pixel or ray traced with the `EventLog` (`whitted trace`): the trace document (`--json`)
//! or the numbered narration with each step's events. With `--aa corners|adaptive` the pixel's
//! samples are traced instead of its centre (`sample::trace_pixel`, `doc::samples`).

use super::options::AccelChoice;
use super::target::Target;
use super::Failure;
use crate::accel::Accel;
use crate::doc::narrate::{narration, Lang, Narration};
use crate::doc::samples::{sample_narration, sampled_document};
use crate::doc::{trace_document, TraceTarget};
use crate::grade::exercise::{asked, Asked};
use crate::memory::budget;
use crate::record::stats::Stats;
use crate::record::{EventLog, BYTES_PER_RECORD, DEFAULT_LIMIT};
use crate::sample::{trace_pixel, PixelTrace, Sampling};
use crate::scene::material::Rgb;
use crate::scene::{AnyScene, Scene};
use crate::shape::Dim;
use crate::trace::Tracer;
use serde_json::Value;

/// What to trace and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    /// `--pixel` or `--ray`.
    pub target: Target,
    /// `--depth`: overrides the scene's `max_depth`.
    pub depth: Option<u32>,
    /// `--aa` (already chosen): corners and adaptive trace a pixel's samples.
    pub sampling: Sampling,
    /// `--accel`, `--bounds`, `--grid`.
    pub accel: AccelChoice,
    /// `--max-events`: the most events and ray nodes recorded; a trace that needs more is refused.
    pub max_events: usize,
}

/// A narration and what was traced.
#[derive(Clone, Debug, PartialEq)]
pub struct Narrated {
    /// The text and each step's events.
    pub narration: Narration,
    /// The pixel and `(u, v)` (None for a ray).
    pub target: TraceTarget,
    /// The rays traced and the tests done, by kind (the trace document's `stats`).
    pub stats: Stats,
}

/// A finished trace: the log and what it was asked as.
struct Done<V> {
    log: EventLog<V>,
    stats: Stats,
    target: TraceTarget,
    max_depth: u32,
    /// The root's colour (centre sampling) or the pixel's samples.
    outcome: Outcome,
}

enum Outcome {
    Center(Rgb),
    Samples(PixelTrace),
}

impl Trace {
    /// The events and nodes the log may keep: `--max-events`, checked against the memory budget
    /// before the work (`BYTES_PER_RECORD` each). A limit raised above the default that the budget
    /// cannot hold is refused with the number; the default is lowered to what the budget holds,
    /// so a small trace still runs on a small machine.
    fn record_limit(&self) -> Result<usize, Failure> {
        let budget = budget();
        let records = self.max_events as u64;
        if self.max_events > DEFAULT_LIMIT {
            let what = format!(
                "a trace of up to {records} events (--max-events, about {BYTES_PER_RECORD} bytes each)"
            );
            budget
                .check(records.saturating_mul(BYTES_PER_RECORD), &what, "choose a smaller --max-events")
                .map_err(|why| Failure::input(format!("trace: {why}")))?;
        }
        let held = usize::try_from(budget.bytes / BYTES_PER_RECORD).unwrap_or(usize::MAX);
        Ok(self.max_events.min(held.max(1)))
    }

    fn run<V: Dim>(&self, scene: &Scene<V>) -> Result<Done<V>, Failure> {
        let (ray, target) = self.target.primary(scene)?;
        let limit = self.record_limit()?;
        let options = self.accel.options(V::DIM)?;
        let accel = Accel::build_with(scene, &options);
        let mut tracer = Tracer::new(scene, &accel, EventLog::with_limit(limit));
        if let Some(d) = self.depth {
            tracer.max_depth = d;
        }
        let outcome = if self.sampling == Sampling::Center {
            let uv = target.uv.clone().unwrap_or_default();
            Outcome::Center(tracer.trace_primary(&ray, &uv))
        } else {
            let Some(pixel) = target.pixel.clone() else {
                return Err(Failure::input("--aa corners|adaptive samples a pixel: give --pixel, not --ray"));
            };
            Outcome::Samples(trace_pixel(
                &mut tracer,
                self.sampling,
                pixel[0],
                pixel.get(1).copied().unwrap_or(0),
            ))
        };
        let max_depth = tracer.max_depth;
        if tracer.recorder.overflowed() {
            let why = tracer.recorder.overflow_cause(max_depth, scene.worst_tree_rays(max_depth));
            return Err(Failure::input(format!("trace: {why} or raise --max-events")));
        }
        Ok(Done { stats: tracer.stats, log: tracer.recorder, target, max_depth, outcome })
    }

    /// The trace document (`whitted trace --json`) of a scene of known dimension.
    ///
    /// # Errors
    /// Bad input: the target, the grid, or samples asked of a ray.
    pub fn document_in<V: Dim>(&self, scene: &Scene<V>) -> Result<Value, Failure> {
        let done = self.run(scene)?;
        Ok(match &done.outcome {
            Outcome::Center(color) => trace_document(scene, &done.log, &done.stats, &done.target, *color),
            Outcome::Samples(traced) => {
                sampled_document(scene, &done.log, &done.stats, &done.target, self.sampling, traced)
            }
        })
    }

    /// The narration (`whitted trace`) of a scene of known dimension, with each step's events,
    /// and what was traced (the document's `pixel` and `uv`).
    ///
    /// # Errors
    /// As [`Trace::document_in`].
    pub fn narration_in<V: Dim>(&self, scene: &Scene<V>, lang: Lang) -> Result<Narrated, Failure> {
        let done = self.run(scene)?;
        let narration = match &done.outcome {
            Outcome::Center(_) => {
                narration(scene, &done.log, &done.stats, &done.target, done.max_depth, lang)
            }
            Outcome::Samples(traced) => {
                sample_narration(&done.target, self.sampling, traced, &done.stats, lang, &done.log)
            }
        };
        Ok(Narrated { narration, target: done.target, stats: done.stats })
    }

    /// What step `step` (from 1) of this trace's narration computes, for the page's exercise
    /// mode (`grade::exercise::asked`); None for a step that computes nothing to type, and for a
    /// pixel's samples (`--aa corners|adaptive`), whose steps are samples, not a ray tree.
    ///
    /// # Errors
    /// As [`Trace::document_in`].
    pub fn asked_in<V: Dim>(&self, scene: &Scene<V>, step: usize) -> Result<Option<Asked>, Failure> {
        let done = self.run(scene)?;
        let Outcome::Center(_) = done.outcome else { return Ok(None) };
        let told = narration(scene, &done.log, &done.stats, &done.target, done.max_depth, Lang::En);
        Ok(asked(&done.log, &told.events, step))
    }

    /// [`Trace::asked_in`] of a scene of either dimension.
    ///
    /// # Errors
    /// As [`Trace::document_in`].
    pub fn asked(&self, scene: &AnyScene, step: usize) -> Result<Option<Asked>, Failure> {
        match scene {
            AnyScene::Flat(s) => self.asked_in(s, step),
            AnyScene::Space(s) => self.asked_in(s, step),
        }
    }

    /// Checks the target and the structure as the trace will, without tracing, and returns the
    /// notes on the options the structure does not read (the command line says them before the
    /// trace, as it says the sampling's).
    ///
    /// # Errors
    /// As [`Trace::document_in`], but for a trace too large.
    pub fn check(&self, scene: &AnyScene) -> Result<Vec<String>, Failure> {
        fn checked<V: Dim>(t: &Trace, scene: &Scene<V>) -> Result<Vec<String>, Failure> {
            t.target.primary(scene)?;
            t.accel.options(V::DIM)?;
            Ok(t.accel.notes(t.accel.kind))
        }
        match scene {
            AnyScene::Flat(s) => checked(self, s),
            AnyScene::Space(s) => checked(self, s),
        }
    }

    /// [`Trace::document_in`] of a scene of either dimension.
    ///
    /// # Errors
    /// As [`Trace::document_in`].
    pub fn document(&self, scene: &AnyScene) -> Result<Value, Failure> {
        match scene {
            AnyScene::Flat(s) => self.document_in(s),
            AnyScene::Space(s) => self.document_in(s),
        }
    }

    /// [`Trace::narration_in`] of a scene of either dimension.
    ///
    /// # Errors
    /// As [`Trace::document_in`].
    pub fn narration(&self, scene: &AnyScene, lang: Lang) -> Result<Narrated, Failure> {
        match scene {
            AnyScene::Flat(s) => self.narration_in(s, lang),
            AnyScene::Space(s) => self.narration_in(s, lang),
        }
    }
}

/// The document as `whitted trace --json` prints it: pretty JSON and a newline.
///
/// # Errors
/// A serialisation failure (not bad input).
pub fn document_text(doc: &Value) -> Result<String, Failure> {
    serde_json::to_string_pretty(doc).map(|t| t + "\n").map_err(|e| Failure::other(e.to_string()))
}
