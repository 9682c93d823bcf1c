//! A lesson figure's point as a checked claim (product.md "Lessons", "Claims"): each figure of a
//! lesson file lists what it must show (`"claims": [{ "kind": "incidence", "min": 20, "max": 60 }]`),
//! and `whitted lessons` measures each claim on the figure's recorded traces (or, for what is a
//! matter of the picture — a visible margin, a ray drawn through an object — on its display list)
//! before it writes anything, so that a scene or pixel that stops showing its point fails loudly.
//!
//! A claim is a [`Measure`] (a closed set, one number each) and the range `[min, max]` it must
//! fall in (either end may be left out, not both).
//!
//! `measure` reads the `FigureInput` and the `Drawing`; a `Verdict` carries the message.
//! `request::figure::figure_checked` makes a figure and checks its claims.

use glam::DVec2;

use super::unknown;
use crate::accel::{AccelKind, Layout};
use crate::canvas::{Drawing, Item, Mark};
use crate::complexity::Cost;
use crate::figure::plane::{segment_gap, Planar};
use crate::figure::source::{
    first_hit, grid_pitfall, incidence_deg, met, refraction_node, search_events, tir_node, vectors_apart_deg,
    FigureInput, GridPitfall,
};
use crate::json::Value;
use crate::record::event::{Event, RayKind};
use crate::record::EventLog;
use crate::scene::Scene;

/// The event names an `events` claim may count (the trace document's `type`s).
pub const EVENT_NAMES: [&str; 13] = [
    "primary_ray",
    "object_test",
    "hit",
    "miss",
    "shadow_ray",
    "reflect",
    "refract",
    "total_internal_reflection",
    "depth_limit",
    "sample",
    "bound_test",
    "node_visit",
    "voxel_step",
];

/// A drawn ray counts as passing through an object when more of it than this share of the
/// view's width lies inside the object's solid outline (about 10 px of a slide's 1920): a ray
/// that ends on the surface it hits, or leaves it, keeps a sliver of that length at most.
pub const CROSSING_TOLERANCE: f64 = 0.005;

/// What a shadow ray met, for `shadows` claims.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowCase {
    /// Stopped by an opaque object: `s = 0`.
    Blocked,
    /// Attenuated by transparent objects only: `0 < s < 1`.
    Attenuated,
    /// Nothing in the way: `s = 1`.
    Clear,
}

impl ShadowCase {
    const NAMES: [(&'static str, Self); 3] =
        [("blocked", Self::Blocked), ("attenuated", Self::Attenuated), ("clear", Self::Clear)];
    /// Its name in a lesson file.
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::NAMES.iter().find(|(_, c)| *c == self).map_or("", |(n, _)| n)
    }
}

/// What a claim measures: one number per figure, from its traces or its drawing.
#[derive(Clone, Debug, PartialEq)]
pub enum Measure {
    /// `events`: how many events of this type (`"event"`) the main trace recorded (e.g.
    /// `voxel_step` ≥ 2, `total_internal_reflection` ≥ 1, `reflect` ≤ 0 for ray casting).
    Events(&'static str),
    /// `level`: the deepest level of the main trace's ray tree (P is level 1, §6), of the rays
    /// of one kind when `"ray"` says which (`primary`, `reflected`, `transmitted`).
    Level(Option<RayKind>),
    /// `shadows`: how many shadow rays of the main trace met what `"s"` says: `blocked`
    /// (`s = 0`), `attenuated` (`0 < s < 1`) or `clear` (`s = 1`).
    Shadows(ShadowCase),
    /// `incidence`: θᵢ in degrees, `acos |D·N|`, at the node the `refraction` figure draws
    /// (its clearest refraction, else its first total internal reflection).
    Incidence,
    /// `specular`: the largest specular term `Isrc·fat·s·ks·(N·H)^n` (any channel, any light)
    /// at the main trace's first hit: a highlight the `local-model` figure can show.
    Specular,
    /// `apart`: the smallest angle in degrees between two of the vectors the `local-model`
    /// figure draws at the main trace's first hit (N, V, and each light's L and H).
    Apart,
    /// `samples`: the samples traced for the `adaptive` figure's pixel.
    Samples,
    /// `leaf-levels`: how many different levels the pixel's unsplit squares have.
    LeafLevels,
    /// `heat-values`: how many different per-pixel counts the `heat-map` shows.
    HeatValues,
    /// `nodes`: the nodes of the hierarchy (`bvh`, `octree`) the figure draws.
    Nodes,
    /// `nodes-missed`: the node visits of the main ray whose box it misses (pruned subtrees).
    NodesMissed,
    /// `grid-pitfall`: the lecture's pitfall, as voxels walked from the voxel where an object
    /// was found beyond the voxel's exit to the later voxel that accepts the hit (that object,
    /// or a nearer one); 0 when the walk does not show it.
    GridPitfall,
    /// `miss-margin`: the gap on the page between the volume (`slab-test`, `kay-kajiya`) and
    /// the drawn ray that passes it (a ray is the `ray:` items of one colour), in % of the
    /// view's width; none when no drawn ray passes it.
    MissMargin,
    /// `intervals`: the shortest drawn slab interval [tᵢ, tₑ] of the interval chart, in % of
    /// its t axis: an interval squeezed to a dot is not seen.
    Intervals,
    /// `false-crossings`: how many (drawn ray, object) pairs show the ray passing through the
    /// solid outline of an object it neither hits, starts on, nor is stopped by (a 3D scene's
    /// out-of-plane objects are dashed and do not count).
    FalseCrossings,
    /// `off-centre`: how far the traced pixel's centre lies from the image's centre, in % of
    /// the image's size, on the nearer-to-centre axis (rows from the bottom are visible only
    /// away from the middle).
    OffCentre,
    /// `frame-error`: how far the camera frame the `camera-frame` figure prints is from lookAt's
    /// definition (§2): the largest of `|w − (O − C)/|O − C||`, `|u·up|`, `|u·w|`, `|v − w × u|`
    /// and `||u| − 1|` (in 2D, `|u − (w_y, −w_x)|`).
    FrameError,
    /// `discriminant-cases`: how many of the three cases (no root, one root, two roots) the
    /// `discriminant` figure's rays show, read from their `object_test` events on its sphere.
    DiscriminantCases,
    /// `changed-pixels`: the pixels of the `jagged-edges` crop whose colour (in the file's bytes)
    /// supersampling changed.
    ChangedPixels,
    /// `brute-force-growth`: brute force's object tests per ray at the `complexity` figure's
    /// largest n over those at its smallest (the lecture's O(n): about their ratio, 1000).
    BruteForceGrowth,
    /// `inset-hits`: the hit points drawn in the figure's inset (the crowded spot magnified,
    /// `figure::inset`): 0 without one.
    InsetHits,
    /// `structure-growth`: the largest growth, over the same range of n, of all tests per ray of
    /// a hierarchy or grid (`bvh`, `grid`, `octree`).
    StructureGrowth,
}

impl Measure {
    /// The kinds' names in a lesson file, in this order.
    pub const KINDS: [&'static str; 22] = [
        "events",
        "level",
        "shadows",
        "incidence",
        "specular",
        "samples",
        "leaf-levels",
        "heat-values",
        "nodes",
        "nodes-missed",
        "grid-pitfall",
        "miss-margin",
        "intervals",
        "false-crossings",
        "off-centre",
        "apart",
        "frame-error",
        "discriminant-cases",
        "changed-pixels",
        "brute-force-growth",
        "structure-growth",
        "inset-hits",
    ];

    /// The claim's name with its parameter: `events voxel_step`, `shadows blocked`.
    #[must_use]
    pub fn describe(&self) -> String {
        let name = |k: usize| Self::KINDS[k].to_owned();
        match self {
            Self::Events(e) => format!("events {e}"),
            Self::Level(None) => name(1),
            Self::Level(Some(k)) => format!("level of {} rays", k.name()),
            Self::Shadows(c) => format!("shadows {}", c.name()),
            Self::Incidence => "incidence θᵢ (°)".into(),
            Self::Specular => name(4),
            Self::Samples => name(5),
            Self::LeafLevels => name(6),
            Self::HeatValues => name(7),
            Self::Nodes => name(8),
            Self::NodesMissed => name(9),
            Self::GridPitfall => "grid-pitfall (voxels from the early find to the accepted hit)".into(),
            Self::MissMargin => "miss-margin (% of the view's width)".into(),
            Self::Intervals => "intervals (shortest, % of the t axis)".into(),
            Self::FalseCrossings => name(13),
            Self::OffCentre => "off-centre (% of the image)".into(),
            Self::Apart => "apart (least angle between N, V, L, H, °)".into(),
            Self::FrameError => name(16),
            Self::DiscriminantCases => name(17),
            Self::ChangedPixels => name(18),
            Self::BruteForceGrowth => {
                "brute-force-growth (object tests per ray, largest n over smallest)".into()
            }
            Self::StructureGrowth => "structure-growth (all tests per ray, largest n over smallest)".into(),
            Self::InsetHits => name(21),
        }
    }
}

/// One claim: a measure and the range it must fall in.
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// What is measured.
    pub measure: Measure,
    /// The least value that holds.
    pub min: Option<f64>,
    /// The largest value that holds.
    pub max: Option<f64>,
}

impl Claim {
    /// Whether `measured` (none: it could not be measured) holds.
    #[must_use]
    pub fn holds(&self, measured: Option<f64>) -> bool {
        measured.is_some_and(|m| self.min.is_none_or(|lo| m >= lo) && self.max.is_none_or(|hi| m <= hi))
    }

    /// The range wanted: `≥ 2`, `≤ 0`, `in [20, 60]`.
    #[must_use]
    pub fn wanted(&self) -> String {
        match (self.min, self.max) {
            (Some(lo), Some(hi)) => format!("in [{lo}, {hi}]"),
            (Some(lo), None) => format!("≥ {lo}"),
            (None, Some(hi)) => format!("≤ {hi}"),
            (None, None) => "any".into(),
        }
    }
}

/// A claim checked: what was measured (none when it could not be) and whether it holds.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// The claim.
    pub claim: Claim,
    /// The measured value.
    pub measured: Option<f64>,
}

impl Verdict {
    /// Whether the claim holds.
    #[must_use]
    pub fn holds(&self) -> bool {
        self.claim.holds(self.measured)
    }

    /// The line `whitted lessons` prints for it: `grid figure 2 (grid-dda): claim events
    /// voxel_step: wanted ≥ 2, measured 1`.
    #[must_use]
    pub fn message(&self, lesson: &str, figure: usize, kind: &str) -> String {
        let measured =
            self.measured.map_or_else(|| "nothing to measure".to_owned(), |m| format!("{}", round(m)));
        format!(
            "{lesson} figure {figure} ({kind}): claim {}: wanted {}, measured {measured}",
            self.claim.measure.describe(),
            self.claim.wanted()
        )
    }
}

/// A measured value as messages print it: 4 significant decimals at most.
fn round(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}

/// Reads a figure's `claims` at `path` (an array of `{ "kind": …, "min": …, "max": … }` with
/// `event`, `ray` or `s` where the kind takes one); every problem goes to `errors`.
pub fn parse(value: Option<&Value>, path: &str, errors: &mut Vec<String>) -> Vec<Claim> {
    let Some(value) = value else { return Vec::new() };
    let Some(list) = value.as_array() else {
        errors.push(format!("{path}: must be an array of claims"));
        return Vec::new();
    };
    let mut claims = Vec::new();
    for (k, item) in list.iter().enumerate() {
        let at = format!("{path}[{k}]");
        let Some(map) = item.as_object() else {
            errors.push(format!("{at}: must be an object with a kind"));
            continue;
        };
        let kind = map.get("kind").and_then(Value::as_str).unwrap_or("");
        let param = match kind {
            "events" => Some("event"),
            "level" => Some("ray"),
            "shadows" => Some("s"),
            _ => None,
        };
        let mut known = vec!["kind", "min", "max"];
        known.extend(param);
        unknown(map, &format!("{at}."), &known, errors);
        let word = |name: &str| map.get(name).and_then(Value::as_str);
        let measure = match kind {
            "events" => match EVENT_NAMES.iter().find(|e| Some(**e) == word("event")) {
                Some(e) => Some(Measure::Events(e)),
                None => {
                    errors.push(format!("{at}.event: must be one of {}", EVENT_NAMES.join(", ")));
                    None
                }
            },
            "level" => match word("ray") {
                None if map.get("ray").is_none() => Some(Measure::Level(None)),
                Some("primary") => Some(Measure::Level(Some(RayKind::Primary))),
                Some("reflected") => Some(Measure::Level(Some(RayKind::Reflected))),
                Some("transmitted") => Some(Measure::Level(Some(RayKind::Transmitted))),
                _ => {
                    errors.push(format!("{at}.ray: must be primary, reflected or transmitted"));
                    None
                }
            },
            "shadows" => match ShadowCase::NAMES.iter().find(|(n, _)| Some(*n) == word("s")) {
                Some((_, c)) => Some(Measure::Shadows(*c)),
                None => {
                    errors.push(format!("{at}.s: must be blocked, attenuated or clear"));
                    None
                }
            },
            "incidence" => Some(Measure::Incidence),
            "specular" => Some(Measure::Specular),
            "samples" => Some(Measure::Samples),
            "leaf-levels" => Some(Measure::LeafLevels),
            "heat-values" => Some(Measure::HeatValues),
            "nodes" => Some(Measure::Nodes),
            "nodes-missed" => Some(Measure::NodesMissed),
            "grid-pitfall" => Some(Measure::GridPitfall),
            "miss-margin" => Some(Measure::MissMargin),
            "intervals" => Some(Measure::Intervals),
            "false-crossings" => Some(Measure::FalseCrossings),
            "off-centre" => Some(Measure::OffCentre),
            "apart" => Some(Measure::Apart),
            "frame-error" => Some(Measure::FrameError),
            "discriminant-cases" => Some(Measure::DiscriminantCases),
            "changed-pixels" => Some(Measure::ChangedPixels),
            "brute-force-growth" => Some(Measure::BruteForceGrowth),
            "structure-growth" => Some(Measure::StructureGrowth),
            "inset-hits" => Some(Measure::InsetHits),
            _ => {
                errors.push(format!("{at}.kind: must be one of {}", Measure::KINDS.join(", ")));
                None
            }
        };
        let mut bound = |name: &str| match map.get(name) {
            None => None,
            Some(v) => {
                let x = v.as_f64().filter(|x| x.is_finite());
                if x.is_none() {
                    errors.push(format!("{at}.{name}: must be a number"));
                }
                x
            }
        };
        let (min, max) = (bound("min"), bound("max"));
        if map.get("min").is_none() && map.get("max").is_none() {
            errors.push(format!("{at}: give min, max or both"));
        }
        if let (Some(lo), Some(hi)) = (min, max) {
            if lo > hi {
                errors.push(format!("{at}: min {lo} is above max {hi}"));
            }
        }
        if let Some(measure) = measure {
            claims.push(Claim { measure, min, max });
        }
    }
    claims
}

/// Checks every claim on a figure's traces, scene and drawing.
#[must_use]
pub fn check_all<V: Planar>(
    claims: &[Claim],
    traces: &FigureInput<V>,
    scene: &Scene<V>,
    drawing: &Drawing,
) -> Vec<Verdict> {
    claims
        .iter()
        .map(|c| Verdict { claim: c.clone(), measured: measure(&c.measure, traces, scene, drawing) })
        .collect()
}

/// Measures `what` on a figure (none when the figure has nothing to measure it on).
#[must_use]
pub fn measure<V: Planar>(
    what: &Measure,
    traces: &FigureInput<V>,
    scene: &Scene<V>,
    drawing: &Drawing,
) -> Option<f64> {
    let main = traces.traces.first();
    let log = main.map(|t| &t.log);
    let count = |n: usize| Some(n as f64);
    match what {
        Measure::Events(name) => count(log?.events.iter().filter(|l| l.event.kind() == *name).count()),
        Measure::Level(kind) => Some(
            log?.nodes
                .iter()
                .filter(|n| kind.is_none_or(|k| n.start.kind == k))
                .map(|n| f64::from(n.start.level))
                .fold(0.0, f64::max),
        ),
        Measure::Shadows(case) => count(
            log?.events
                .iter()
                .filter(|l| match &l.event {
                    Event::ShadowRay { occluders, s, .. } => match case {
                        ShadowCase::Blocked => !occluders.is_empty() && *s == 0.0,
                        ShadowCase::Attenuated => *s > 0.0 && *s < 1.0,
                        ShadowCase::Clear => occluders.is_empty(),
                    },
                    _ => false,
                })
                .count(),
        ),
        Measure::Incidence => incidence(traces),
        Measure::Specular => {
            let log = log?;
            let node = &log.nodes[first_hit(log)?];
            node.lights.iter().flat_map(|t| t.specular.0).reduce(f64::max)
        }
        Measure::Apart => vectors_apart_deg(&log?.nodes[first_hit(log?)?]),
        Measure::Samples => count(main?.samples.as_ref()?.samples.len()),
        Measure::LeafLevels => {
            let squares = &main?.samples.as_ref()?.squares;
            let mut levels: Vec<u32> = squares.iter().filter(|q| !q.split).map(|q| q.level).collect();
            levels.sort_unstable();
            levels.dedup();
            count(levels.len())
        }
        Measure::HeatValues => {
            let mut values = traces.counts.as_ref()?.per_pixel.clone();
            values.sort_unstable();
            values.dedup();
            count(values.len())
        }
        Measure::Nodes => match traces.accel.layout() {
            Layout::Tree(nodes) => count(nodes.len()),
            _ => None,
        },
        Measure::NodesMissed => count(
            search_events(log?, 0)
                .filter(|e| matches!(e, Event::NodeVisit { t_in, t_out, .. } if !met(*t_in, *t_out)))
                .count(),
        ),
        Measure::GridPitfall => Some(pitfall_voxels(log?)),
        Measure::MissMargin => miss_margin(drawing),
        Measure::Intervals => shortest_interval(drawing),
        Measure::FalseCrossings => count(false_crossings(drawing, log?, scene.objects.len())),
        Measure::InsetHits => count(
            drawing
                .tagged("hit")
                .filter(|i| match i.mark {
                    crate::canvas::Mark::Dot { center, .. } => {
                        drawing.insets.iter().any(|k| k.in_panel(center))
                    }
                    _ => false,
                })
                .count(),
        ),
        Measure::OffCentre => {
            let cam = &scene.camera;
            let off = |k: usize, n: usize| ((k as f64 + 0.5) / n as f64 - 0.5).abs() * 100.0;
            match &main?.targets.first()? {
                crate::figure::source::Target::Pixel { i, j, .. } => {
                    let across = off(*i, cam.nx);
                    Some(if V::DIM == 2 { across } else { across.min(off(*j, cam.ny)) })
                }
                crate::figure::source::Target::Ray => None,
            }
        }
        Measure::FrameError => Some(frame_error(scene)),
        Measure::DiscriminantCases => {
            let log = log?;
            let focus = traces.focus?;
            let mut counts: Vec<usize> = log
                .roots()
                .filter_map(|k| {
                    log.events.iter().filter(|l| l.ray == Some(k)).find_map(|l| match &l.event {
                        Event::ObjectTest { object, roots, .. } if object.index == focus => Some(roots.len()),
                        _ => None,
                    })
                })
                .collect();
            counts.sort_unstable();
            counts.dedup();
            count(counts.len())
        }
        Measure::ChangedPixels => count(traces.jagged.as_ref()?.changed()),
        Measure::BruteForceGrowth => growth(&traces.costs, &[AccelKind::None], Cost::object_tests_per_ray),
        Measure::StructureGrowth => {
            growth(&traces.costs, &[AccelKind::Bvh, AccelKind::Grid, AccelKind::Octree], Cost::tests_per_ray)
        }
    }
}

/// [`Measure::FrameError`].
fn frame_error<V: Planar>(scene: &Scene<V>) -> f64 {
    let cam = &scene.camera;
    let f = &cam.frame;
    let Some(w) = (cam.eye - cam.center).try_unit() else { return f64::INFINITY };
    let mut errors = vec![(f.w - w).length(), (f.u.length() - 1.0).abs(), f.u.dot(f.w).abs()];
    if V::DIM == 3 {
        let mut v = V::ZERO;
        // v = w × u, written out on the axes.
        v[0] = f.w[1] * f.u[2] - f.w[2] * f.u[1];
        v[1] = f.w[2] * f.u[0] - f.w[0] * f.u[2];
        v[2] = f.w[0] * f.u[1] - f.w[1] * f.u[0];
        errors.extend([(f.v - v).length(), f.u.dot(cam.up).abs() / cam.up.length()]);
    } else {
        let mut u = V::ZERO;
        u[0] = w[1];
        u[1] = -w[0];
        errors.push((f.u - u).length());
    }
    errors.into_iter().fold(0.0, f64::max)
}

/// The largest ratio, over `kinds`, of `value` at the largest n measured to `value` at the
/// smallest.
fn growth(costs: &[Cost], kinds: &[AccelKind], value: fn(&Cost) -> f64) -> Option<f64> {
    let (lo, hi) = (costs.iter().map(|c| c.n).min()?, costs.iter().map(|c| c.n).max()?);
    kinds
        .iter()
        .filter_map(|k| {
            let at = |n: usize| costs.iter().find(|c| c.kind == *k && c.n == n).map(value);
            Some(at(hi)? / at(lo)?)
        })
        .reduce(f64::max)
}

/// θᵢ at the node the `refraction` figure draws: its clearest refraction, else the first total
/// internal reflection of the main trace or of the second one.
fn incidence<V: Planar>(traces: &FigureInput<V>) -> Option<f64> {
    let main = &traces.traces.first()?.log;
    if let Some((k, _)) = refraction_node(main) {
        return incidence_deg(&main.nodes[k]);
    }
    traces.traces.iter().find_map(|t| tir_node(&t.log).and_then(|k| incidence_deg(&t.log.nodes[k])))
}

/// [`Measure::GridPitfall`]: from the step whose cell found an object beyond its exit to the last
/// step (the one that accepted the hit), when the accepted hit is that object or a nearer one.
fn pitfall_voxels<V>(log: &EventLog<V>) -> f64 {
    let Some(GridPitfall { step, object: early, t: t_early, .. }) = grid_pitfall(log) else { return 0.0 };
    let steps = search_events(log, 0).filter(|e| matches!(e, Event::VoxelStep { .. })).count();
    let accepted = search_events(log, 0)
        .chain(log.events.iter().filter(|l| l.ray == Some(0)).map(|l| &l.event))
        .find_map(|e| match e {
            Event::Hit { object, t, .. } => Some((object.index, *t)),
            _ => None,
        });
    match accepted {
        Some((object, t)) if (object == early || t < t_early) && steps > step + 1 => {
            (steps - 1 - step) as f64
        }
        _ => 0.0,
    }
}

/// The segments an item draws (a polyline's pieces, an arrow's shaft).
fn segments(item: &Item) -> Vec<(DVec2, DVec2)> {
    match &item.mark {
        Mark::Line { points } => points.windows(2).map(|w| (w[0], w[1])).collect(),
        Mark::Arrow { from, to, .. } => vec![(*from, *to)],
        _ => Vec::new(),
    }
}

/// A solid closed outline: its edges (a circle as a 96-gon).
fn closed_edges(item: &Item) -> Option<Vec<(DVec2, DVec2)>> {
    /// The sides of the polygon a circle is measured as (its chord error is r·(1 − cos(π/96)),
    /// 0.05 % of r).
    const CIRCLE_SIDES: usize = 96;
    let ring = |pts: Vec<DVec2>| -> Vec<(DVec2, DVec2)> {
        (0..pts.len()).map(|k| (pts[k], pts[(k + 1) % pts.len()])).collect()
    };
    match &item.mark {
        Mark::Polygon { points, .. } if points.len() >= 3 => Some(ring(points.clone())),
        Mark::Rect { min, max, .. } => {
            Some(ring(vec![*min, DVec2::new(max.x, min.y), *max, DVec2::new(min.x, max.y)]))
        }
        Mark::Circle { center, radius, .. } => Some(ring(
            (0..CIRCLE_SIDES)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / CIRCLE_SIDES as f64;
                    *center + DVec2::new(a.cos(), a.sin()) * *radius
                })
                .collect(),
        )),
        _ => None,
    }
}

/// The parameter `s ∈ [0, 1]` along `a → b` where it crosses `c → d`, if it does.
fn crossing(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Option<f64> {
    let (r, q) = (b - a, d - c);
    let den = r.perp_dot(q);
    if den.abs() < 1e-300 {
        return None;
    }
    let s = (c - a).perp_dot(q) / den;
    let u = (c - a).perp_dot(r) / den;
    ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&u)).then_some(s)
}

/// Whether `p` lies inside the closed polygon `edges` (even–odd rule).
fn inside(p: DVec2, edges: &[(DVec2, DVec2)]) -> bool {
    let mut odd = false;
    for (a, b) in edges {
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            odd = !odd;
        }
    }
    odd
}

/// The length of segment `a → b` inside the closed polygon `edges`.
fn length_inside(a: DVec2, b: DVec2, edges: &[(DVec2, DVec2)]) -> f64 {
    let mut cuts: Vec<f64> = vec![0.0, 1.0];
    cuts.extend(edges.iter().filter_map(|(c, d)| crossing(a, b, *c, *d)));
    cuts.sort_by(f64::total_cmp);
    cuts.windows(2)
        .filter(|w| inside(a + (b - a) * (0.5 * (w[0] + w[1])), edges))
        .map(|w| (w[1] - w[0]) * (b - a).length())
        .sum()
}

/// [`Measure::MissMargin`].
fn miss_margin(drawing: &Drawing) -> Option<f64> {
    let volume = drawing.tagged("volume").find_map(closed_edges)?;
    let mut rays: Vec<(crate::figure::style::Rgba, Vec<(DVec2, DVec2)>)> = Vec::new();
    for item in drawing.items.iter().filter(|i| i.tag.starts_with("ray:")) {
        match rays.iter_mut().find(|(c, _)| *c == item.pen.color) {
            Some((_, segs)) => segs.extend(segments(item)),
            None => rays.push((item.pen.color, segments(item))),
        }
    }
    let width = drawing.view.width();
    rays.iter()
        .filter(|(_, segs)| !segs.is_empty())
        .map(|(_, segs)| {
            segs.iter()
                .map(|(a, b)| {
                    let through = inside(*a, &volume) || length_inside(*a, *b, &volume) > 0.0;
                    let gap =
                        volume.iter().map(|(c, d)| segment_gap(*a, *b, *c, *d)).fold(f64::INFINITY, f64::min);
                    if through {
                        0.0
                    } else {
                        gap
                    }
                })
                .fold(f64::INFINITY, f64::min)
        })
        .filter(|gap| *gap > 0.0)
        .reduce(f64::min)
        .map(|gap| 100.0 * gap / width)
}

/// [`Measure::Intervals`].
fn shortest_interval(drawing: &Drawing) -> Option<f64> {
    let axis = drawing.tagged("t-axis").flat_map(segments).map(|(a, b)| (b - a).length()).reduce(f64::max)?;
    let shortest =
        drawing.tagged("interval").flat_map(segments).map(|(a, b)| (b - a).length()).reduce(f64::min)?;
    Some(100.0 * shortest / axis)
}

/// The objects a drawn ray may touch: those its events hit, are stopped by, test as a volume,
/// or the surface it starts on.
fn allowed<V>(item: &Item, log: &EventLog<V>) -> Vec<usize> {
    let surface = |node: Option<usize>| {
        node.and_then(|n| log.nodes.get(n)?.end.as_ref()?.hit.as_ref().map(|h| h.object.index))
    };
    let mut objects = Vec::new();
    for logged in item.events.iter().filter_map(|e| log.events.get(*e)) {
        match &logged.event {
            Event::Hit { object, .. } => objects.push(object.index),
            Event::BoundTest { object: Some(o), .. } => objects.push(o.index),
            Event::ShadowRay { occluders, .. } => {
                objects.extend(occluders.iter().map(|o| o.object.index));
                objects.extend(surface(logged.ray));
            }
            Event::Reflect { .. } | Event::Refract { .. } | Event::TotalInternalReflection { .. } => {
                objects.extend(surface(logged.ray));
            }
            _ => {}
        }
    }
    objects
}

/// [`Measure::FalseCrossings`].
fn false_crossings<V>(drawing: &Drawing, log: &EventLog<V>, objects: usize) -> usize {
    let tolerance = CROSSING_TOLERANCE * drawing.view.width();
    let outlines: Vec<(usize, &Item)> = drawing
        .items
        .iter()
        .filter(|i| i.pen.dash.is_none())
        .filter_map(|i| Some((i.tag.strip_prefix("object:")?.parse::<usize>().ok()?, i)))
        .filter(|(k, _)| *k < objects)
        .collect();
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for (r, ray) in drawing.items.iter().enumerate().filter(|(_, i)| i.tag.starts_with("ray:")) {
        let ok = allowed(ray, log);
        for (object, outline) in outlines.iter().filter(|(k, _)| !ok.contains(k)) {
            let through = segments(ray).iter().any(|(a, b)| match closed_edges(outline) {
                Some(edges) => length_inside(*a, *b, &edges) > tolerance,
                // An open outline (a plane's line): crossed away from the ray's ends.
                None => segments(outline).iter().any(|(c, d)| {
                    crossing(*a, *b, *c, *d).is_some_and(|s| {
                        let len = (*b - *a).length();
                        s * len > tolerance && (1.0 - s) * len > tolerance
                    })
                }),
            });
            if through && !pairs.contains(&(r, *object)) {
                pairs.push((r, *object));
            }
        }
    }
    pairs.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> (Vec<Claim>, Vec<String>) {
        let value = crate::json::parse(text).unwrap();
        let mut errors = Vec::new();
        let claims = parse(Some(&value), "figures[0].claims", &mut errors);
        (claims, errors)
    }

    #[test]
    fn claims_read_with_their_parameters() {
        let (claims, errors) = read(
            r#"[ { "kind": "events", "event": "voxel_step", "min": 2 },
                 { "kind": "incidence", "min": 20, "max": 60 },
                 { "kind": "shadows", "s": "blocked", "min": 1 },
                 { "kind": "level", "ray": "transmitted", "min": 2 } ]"#,
        );
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(claims[0], Claim { measure: Measure::Events("voxel_step"), min: Some(2.0), max: None });
        assert_eq!(claims[1].wanted(), "in [20, 60]");
        assert_eq!(claims[2].measure, Measure::Shadows(ShadowCase::Blocked));
        assert_eq!(claims[3].measure, Measure::Level(Some(RayKind::Transmitted)));
    }

    #[test]
    fn every_bad_claim_is_named() {
        let (_, errors) = read(
            r#"[ { "kind": "rainbow", "min": 1 }, { "kind": "events", "event": "bounce", "min": 1 },
                 { "kind": "nodes", "min": 1, "colour": "red" }, { "kind": "nodes" },
                 { "kind": "incidence", "min": 60, "max": 20 }, { "kind": "heat-values", "min": "3" } ]"#,
        );
        let all = errors.join("\n");
        for expected in [
            "figures[0].claims[0].kind: must be one of events,",
            "figures[0].claims[1].event: must be one of",
            "figures[0].claims[2].colour: unknown field",
            "figures[0].claims[3]: give min, max or both",
            "figures[0].claims[4]: min 60 is above max 20",
            "figures[0].claims[5].min: must be a number",
        ] {
            assert!(all.contains(expected), "{expected} in {all}");
        }
    }

    #[test]
    fn a_range_holds_inclusively_and_nothing_measured_fails() {
        let claim = Claim { measure: Measure::Incidence, min: Some(20.0), max: Some(60.0) };
        assert!(claim.holds(Some(20.0)) && claim.holds(Some(60.0)));
        assert!(!claim.holds(Some(5.0)) && !claim.holds(None));
        let verdict = Verdict { claim, measured: Some(5.000_04) };
        assert_eq!(
            verdict.message("secondary-rays", 1, "refraction"),
            "secondary-rays figure 1 (refraction): claim incidence θᵢ (°): wanted in [20, 60], measured 5"
        );
    }

    #[test]
    fn a_segment_inside_a_square_is_measured() {
        let v = DVec2::new;
        let square = vec![
            (v(0., 0.), v(1., 0.)),
            (v(1., 0.), v(1., 1.)),
            (v(1., 1.), v(0., 1.)),
            (v(0., 1.), v(0., 0.)),
        ];
        assert!((length_inside(v(-1., 0.5), v(2., 0.5), &square) - 1.0).abs() < 1e-12);
        assert!(length_inside(v(-1., 2.), v(2., 2.), &square).abs() < 1e-12);
        assert!((segment_gap(v(-1., 1.5), v(2., 1.5), v(0., 1.), v(1., 1.)) - 0.5).abs() < 1e-12);
    }
}
