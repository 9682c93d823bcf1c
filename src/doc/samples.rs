//! The trace document and narration of one pixel traced with `--aa corners|adaptive`
//! (algorithm.md §8). The fields it adds (`sampling`, `samples`, `squares`; `tree` is null) are
//! specified in product.md "The trace document". A sample's first `sample` event comes right after
//! its ray's events, and its rays are numbered one sample's tree after another.
//! The pixel is traced alone: corners it shares with neighbouring pixels are traced here too.

use super::narrate::{rays_line, Lang, Narration};
use super::{color, event, float, node, stats, Namer, TraceTarget};
use crate::format::narration_number;
use crate::record::event::Event;
use crate::record::stats::Stats;
use crate::record::EventLog;
use crate::sample::{PixelTrace, Sampling};
use crate::scene::material::Rgb;
use crate::scene::Scene;
use crate::shape::Dim;
use serde_json::{json, Value};
use std::fmt::Write;

fn floats(xs: &[f64]) -> Value {
    Value::Array(xs.iter().map(|x| float(*x)).collect())
}

/// The trace document of a pixel traced with samples.
pub fn sampled_document<V: Dim>(
    scene: &Scene<V>,
    log: &EventLog<V>,
    stats_: &Stats,
    target: &TraceTarget,
    sampling: Sampling,
    pixel: &PixelTrace,
) -> Value {
    let namer = Namer::new(scene);
    let dims = V::DIM - 1;
    let samples: Vec<Value> = pixel
        .samples
        .iter()
        .map(|s| {
            let mut m = serde_json::Map::new();
            m.insert("label".into(), json!(s.label));
            m.insert("u".into(), float(s.uv[0]));
            if dims == 2 {
                m.insert("v".into(), float(s.uv[1]));
            }
            m.insert("lattice".into(), json!(s.lattice));
            m.insert("level".into(), json!(s.level));
            m.insert("reused".into(), json!(s.reused));
            m.insert("color".into(), color(s.color));
            m.insert("tree".into(), node(&namer, log, s.root));
            Value::Object(m)
        })
        .collect();
    let share = if dims == 2 { 0.25_f64 } else { 0.5 };
    let squares: Vec<Value> = pixel
        .squares
        .iter()
        .map(|q| {
            json!({
                "level": q.level,
                "lattice": q.lattice,
                "side": q.side,
                "corners": q.corners,
                "spread": float(q.spread),
                "split": q.split,
                "weight": share.powi(i32::try_from(q.level).unwrap_or(i32::MAX)),
                "color": color(q.color),
            })
        })
        .collect();
    json!({
        "pixel": target.pixel.as_ref().map_or(Value::Null, |p| json!(p)),
        "uv": target.uv.as_ref().map_or(Value::Null, |uv| floats(uv)),
        "color": color(pixel.color),
        "stats": stats(stats_),
        "tree": Value::Null,
        "sampling": {
            "aa": sampling.name(),
            "threshold": float(pixel.threshold),
            "max_level": pixel.max_level,
            "scale": 1_u64 << pixel.max_level,
        },
        "samples": samples,
        "squares": squares,
        "events": log.events.iter().map(|e| event(&namer, &e.event, e.ray, e.sample)).collect::<Vec<_>>(),
    })
}

fn rgb(c: Rgb) -> String {
    format!("({}, {}, {})", narration_number(c.0[0]), narration_number(c.0[1]), narration_number(c.0[2]))
}

/// The narration of a pixel traced with samples: the rule, each sample, each square and the mean.
/// (Each sample's own ray tree is in the `--json` document.)
#[must_use]
pub fn narrate_samples(
    target: &TraceTarget,
    sampling: Sampling,
    pixel: &PixelTrace,
    stats_: &Stats,
    lang: Lang,
) -> String {
    sample_narration::<f64>(target, sampling, pixel, stats_, lang, &EventLog::new()).text
}

/// [`narrate_samples`] with the events of its four steps, indices into `log`'s events: the pixel
/// (step 1, "its corners … the pixel is their mean") the primary rays of its level-0 samples, the
/// samples (step 2) every primary ray, the squares (step 3) and the mean of the leaves (step 4)
/// every read of a corner (`sample` events), of which the squares' and the leaves' colours are
/// made.
#[must_use]
pub fn sample_narration<V>(
    target: &TraceTarget,
    sampling: Sampling,
    pixel: &PixelTrace,
    stats_: &Stats,
    lang: Lang,
    log: &EventLog<V>,
) -> Narration {
    let of = |test: fn(&Event<V>) -> bool| -> Vec<usize> {
        log.events.iter().enumerate().filter(|(_, e)| test(&e.event)).map(|(k, _)| k).collect()
    };
    let corners: Vec<usize> =
        pixel.samples.iter().filter(|s| s.level == 0).filter_map(|s| log.spawned_by(s.root)).collect();
    let reads = of(|e| matches!(e, Event::Sample { .. }));
    let events = vec![corners, of(|e| matches!(e, Event::PrimaryRay { .. })), reads.clone(), reads];
    let t = |en: &'static str, ro: &'static str| if lang == Lang::En { en } else { ro };
    let mut out = String::new();
    let where_ = target
        .pixel
        .as_ref()
        .map_or(String::new(), |p| p.iter().map(ToString::to_string).collect::<Vec<_>>().join(", "));
    let _ = writeln!(out, "1. {} ({where_}), --aa {}", t("Pixel", "Pixelul"), sampling.name());
    let rule = if pixel.max_level == 0 {
        t(
            "   the 4 corners (2D: the 2 ends), shared with the neighbours; the pixel is their mean",
            "   cele 4 colțuri (2D: cele 2 capete), comune cu vecinii; pixelul este media lor",
        )
        .to_string()
    } else {
        format!(
            "{} {} {} K = {}",
            t(
                "   split a square while max over R, G, B of (max − min of its corners) ≥",
                "   se subdivizează un pătrat cât timp max pe R, G, B din (max − min al colțurilor) ≥",
            ),
            narration_number(pixel.threshold),
            t("and its level is below", "și nivelul său este sub"),
            pixel.max_level
        )
    };
    let _ = writeln!(out, "{rule}");
    let _ = writeln!(
        out,
        "2. {} ({}):",
        t("Samples, in the order traced", "Eșantioane, în ordinea trasării"),
        pixel.samples.len()
    );
    for s in &pixel.samples {
        let uv: Vec<String> = s.uv.iter().map(|x| narration_number(*x)).collect();
        let reused = if s.reused { t(", reused", ", refolosit") } else { "" };
        let _ = writeln!(
            out,
            "   {} ({}) {} {}{}: {}",
            s.label,
            uv.join(", "),
            t("level", "nivel"),
            s.level,
            reused,
            rgb(s.color)
        );
    }
    let _ = writeln!(out, "3. {}:", t("Squares (pre-order)", "Pătrate (în preordine)"));
    for q in &pixel.squares {
        let labels: Vec<&str> = q.corners.iter().map(|k| pixel.samples[*k].label.as_str()).collect();
        let what = if q.split { t("split", "subdivizat") } else { t("leaf", "frunză") };
        let _ = writeln!(
            out,
            "   {}{} {}: {} [{}], spread {} → {}, {}",
            "  ".repeat(q.level as usize),
            t("level", "nivel"),
            q.level,
            what,
            labels.join(", "),
            narration_number(q.spread),
            rgb(q.color),
            if q.split {
                t("mean of its parts", "media părților")
            } else {
                t("mean of its corners", "media colțurilor")
            }
        );
    }
    let bytes = pixel.color.0.map(crate::image::to_byte);
    let _ = writeln!(
        out,
        "4. {}: {} → 8 bit {:?}",
        t(
            "Pixel colour, the area-weighted mean of the leaves",
            "Culoarea pixelului, media ponderată cu aria a frunzelor"
        ),
        rgb(pixel.color),
        bytes
    );
    out.push_str(&rays_line(stats_, lang));
    // No ray tree to stand in: the steps are the pixel's.
    let places = vec![String::new(); events.len()];
    Narration { text: out, events, places }
}
