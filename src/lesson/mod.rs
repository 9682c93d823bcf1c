//! A lesson: one section of the lecture as a small JSON file naming its figures, each a kind, a
//! scene and a caption in both languages, with the claims the figure must show. The format, every
//! field and its limits are product.md "Lessons"; [`claim`] checks the claims.
//!
//! This module reads text and returns values, naming every problem of a file at once ([`parse`],
//! through `json::reader`). The pages that show the lessons are `site`'s; the command line
//! (`cli::lessons`) reads the files and writes the outputs.

pub mod claim;

use crate::accel::grid::MAX_CELLS_PER_AXIS;
use crate::figure::FigureKind;
use crate::format::as_written;
use crate::json::reader::{ray_problem, type_name, ReadError, Reader};
use crate::json::{self, Map, Value};
use crate::lang::{Lang, CODES};
use crate::sample::{Sampling, DEFAULT_MAX_LEVEL, DEFAULT_THRESHOLD, MAX_LEVEL};
use crate::scene::load::MAX_DEPTH;

pub use crate::lang::Both;

/// One figure of a lesson.
#[derive(Clone, Debug, PartialEq)]
pub struct FigureSpec {
    /// The diagram.
    pub kind: FigureKind,
    /// The scene file, relative to the lesson file.
    pub scene: String,
    /// The pixel `(i, j)` (`j` absent in 2D); none lets the figure pick.
    pub pixel: Option<(usize, Option<usize>)>,
    /// A ray given by hand: origin and direction components.
    pub ray: Option<(Vec<f64>, Vec<f64>)>,
    /// Overrides the scene's `max_depth`.
    pub depth: Option<u32>,
    /// The sampling of `adaptive` and `heat-map` (`aa`, `threshold`, `max_level`).
    pub sampling: Option<Sampling>,
    /// The grid's cells per axis (`grid`), for `grid-dda`.
    pub grid: Option<Vec<usize>>,
    /// A title of the lesson's own in both languages, instead of the kind's (`title`), where the
    /// lesson says it better (the aliasing lesson's projections).
    pub title: Option<Both>,
    /// What the figure shows, in both languages.
    pub caption: Both,
    /// What it must show, checked on its traces and drawing (`claims`).
    pub claims: Vec<claim::Claim>,
}

impl FigureSpec {
    /// The pixel as `--pixel` writes it: `I,J`, or `I` in 2D.
    #[must_use]
    pub fn pixel_arg(&self) -> Option<String> {
        self.pixel.map(|(i, j)| j.map_or_else(|| i.to_string(), |j| format!("{i},{j}")))
    }
    /// The ray as `--ray` writes it: `OX,OY,OZ:DX,DY,DZ`.
    #[must_use]
    pub fn ray_arg(&self) -> Option<String> {
        let join = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
        self.ray.as_ref().map(|(o, d)| format!("{}:{}", join(o), join(d)))
    }
}

/// A lesson: one section of the lecture.
#[derive(Clone, Debug, PartialEq)]
pub struct Lesson {
    /// Its name, for `--only` and file names (lowercase letters, digits and `-`).
    pub name: String,
    /// Its title.
    pub title: Both,
    /// An introduction (may be empty).
    pub text: Both,
    /// Its figures, in order.
    pub figures: Vec<FigureSpec>,
    /// Its exercise sheets (`whitted exercises`), written beside its pages; may be empty.
    pub exercises: Vec<ExerciseSpec>,
}

/// One exercise sheet of a lesson: a pixel of a scene, and the seed that picks its questions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExerciseSpec {
    /// The scene file, relative to the lesson file.
    pub scene: String,
    /// `[i, j]` (`[i]` in 2D).
    pub pixel: (usize, Option<usize>),
    /// `--seed` (default 1).
    pub seed: u64,
}

impl Lesson {
    /// The file stem of figure `index` (from 0): `NAME-K-KIND`.
    #[must_use]
    pub fn file_stem(&self, index: usize) -> String {
        format!("{}-{}-{}", self.name, index + 1, self.figures[index].kind.name())
    }
    /// The files of exercise sheet `index` (from 0): `NAME-exercises-K.html`, `NAME-answers-K.html`.
    #[must_use]
    pub fn exercise_files(&self, index: usize) -> (String, String) {
        (
            format!("{}-exercises-{}.html", self.name, index + 1),
            format!("{}-answers-{}.html", self.name, index + 1),
        )
    }
}

/// Reads a lesson file's text; every problem is reported, each naming its field.
///
/// # Errors
/// The list of problems: invalid JSON, a missing or unknown field, a wrong type, an unknown kind.
pub fn parse(text: &str) -> Result<Lesson, Vec<String>> {
    let value = json::parse(text).map_err(|e| vec![ReadError::syntax(&e).to_string()])?;
    let mut errors = Vec::new();
    let Some(root) = value.as_object() else {
        return Err(vec!["a lesson is a JSON object".into()]);
    };
    unknown(root, "", &["name", "title", "text", "figures", "exercises"], &mut errors);
    let name = match root.get("name").and_then(Value::as_str) {
        Some(n)
            if !n.is_empty()
                && n.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-') =>
        {
            n.to_owned()
        }
        _ => {
            errors.push("name: must be lowercase letters, digits and `-`".into());
            String::new()
        }
    };
    let title = both(root.get("title"), "title", &mut errors);
    let text = root.get("text").map_or_else(Both::default, |t| both(Some(t), "text", &mut errors));
    let mut figures = Vec::new();
    match root.get("figures").and_then(Value::as_array) {
        Some(list) if !list.is_empty() => {
            for (k, f) in list.iter().enumerate() {
                if let Some(spec) = figure(f, &format!("figures[{k}]"), &mut errors) {
                    figures.push(spec);
                }
            }
        }
        _ => errors.push("figures: must be a non-empty array".into()),
    }
    let mut exercises = Vec::new();
    match root.get("exercises").map(Value::as_array) {
        None => {}
        Some(Some(list)) => {
            for (k, e) in list.iter().enumerate() {
                if let Some(spec) = exercise(e, &format!("exercises[{k}]"), &mut errors) {
                    exercises.push(spec);
                }
            }
        }
        Some(None) => errors.push("exercises: must be an array".into()),
    }
    if errors.is_empty() {
        Ok(Lesson { name, title, text, figures, exercises })
    } else {
        Err(errors)
    }
}

/// One exercise sheet: `{ "scene": …, "pixel": [i, j], "seed": N }`.
fn exercise(value: &Value, path: &str, errors: &mut Vec<String>) -> Option<ExerciseSpec> {
    let Some(map) = value.as_object() else {
        errors.push(format!("{path}: must be an object"));
        return None;
    };
    unknown(map, &format!("{path}."), &["scene", "pixel", "seed"], errors);
    let scene = map.get("scene").and_then(Value::as_str).map(str::to_owned);
    if scene.is_none() {
        errors.push(format!("{path}.scene: must be the path of a scene file"));
    }
    let whole = |v: &Value| v.as_u64().and_then(|n| usize::try_from(n).ok());
    let pixel = match map
        .get("pixel")
        .and_then(Value::as_array)
        .map(|a| a.iter().map(whole).collect::<Option<Vec<_>>>())
    {
        Some(Some(p)) if p.len() == 1 => Some((p[0], None)),
        Some(Some(p)) if p.len() == 2 => Some((p[0], Some(p[1]))),
        _ => {
            errors.push(format!("{path}.pixel: must be [i, j] (or [i] in 2D) with whole numbers"));
            None
        }
    };
    let seed = match map.get("seed") {
        None => Some(1),
        Some(v) => {
            let n = v.as_u64();
            if n.is_none() {
                errors.push(format!("{path}.seed: must be a whole number ≥ 0"));
            }
            n
        }
    };
    Some(ExerciseSpec { scene: scene?, pixel: pixel?, seed: seed? })
}

/// Runs `read` with the scenes' all-errors [`Reader`] and adds what it found to `errors`, so a
/// lesson words a problem as a scene does.
fn with_reader<T>(errors: &mut Vec<String>, read: impl FnOnce(&mut Reader) -> T) -> T {
    let mut r = Reader::default();
    let value = read(&mut r);
    errors.extend(r.into_errors().iter().map(ToString::to_string));
    value
}

/// Reports every field of `map` not in `known` (with the closest known one), and every field
/// written twice; `path` is the object's, ending in `.` (empty at the top).
fn unknown(map: &Map<'_>, path: &str, known: &[&str], errors: &mut Vec<String>) {
    let path = path.strip_suffix('.').unwrap_or(path);
    with_reader(errors, |r| r.keys(map, path, known));
}

/// `{ "en": …, "ro": … }`.
fn both(value: Option<&Value>, path: &str, errors: &mut Vec<String>) -> Both {
    let Some(map) = value.and_then(Value::as_object) else {
        errors.push(format!("{path}: must be {{ \"en\": \"…\", \"ro\": \"…\" }}"));
        return Both::default();
    };
    with_reader(errors, |r| {
        r.keys(map, path, CODES);
        let mut get = |lang: Lang| r.required_string(map, path, lang.code()).unwrap_or_default().to_owned();
        Both { en: get(Lang::En), ro: get(Lang::Ro) }
    })
}

/// One figure spec at `path`.
fn figure(value: &Value, path: &str, errors: &mut Vec<String>) -> Option<FigureSpec> {
    let Some(map) = value.as_object() else {
        errors.push(format!("{path}: must be an object"));
        return None;
    };
    let fields = [
        "kind",
        "scene",
        "pixel",
        "ray",
        "depth",
        "aa",
        "threshold",
        "max_level",
        "grid",
        "title",
        "caption",
        "claims",
    ];
    unknown(map, &format!("{path}."), &fields, errors);
    let kind = map.get("kind").and_then(Value::as_str).and_then(FigureKind::from_name);
    if kind.is_none() {
        let names: Vec<&str> = FigureKind::ALL.iter().map(|k| k.name()).collect();
        errors.push(format!("{path}.kind: must be one of {}", names.join(", ")));
    }
    let scene = map.get("scene").and_then(Value::as_str).map(str::to_owned);
    if scene.is_none() {
        errors.push(format!("{path}.scene: must be the path of a scene file"));
    }
    let whole = |v: &Value| v.as_u64().and_then(|n| usize::try_from(n).ok());
    let pixel =
        match map.get("pixel").map(|p| p.as_array().map(|a| a.iter().map(whole).collect::<Option<Vec<_>>>()))
        {
            None => None,
            Some(Some(Some(p))) if p.len() == 1 => Some((p[0], None)),
            Some(Some(Some(p))) if p.len() == 2 => Some((p[0], Some(p[1]))),
            Some(_) => {
                errors.push(format!("{path}.pixel: must be [i, j] (or [i] in 2D) with whole numbers"));
                None
            }
        };
    let numbers =
        |v: Option<&Value>| -> Option<Vec<f64>> { v?.as_array()?.iter().map(Value::as_f64).collect() };
    // The ray as `--ray` would take it (`ray_problem`): the command shown beside the figure runs.
    let ray = match map.get("ray") {
        None => None,
        Some(r) => {
            let form = "must be { \"origin\": [..], \"direction\": [..] }";
            match (numbers(r.get("origin")), numbers(r.get("direction"))) {
                (Some(o), Some(d)) => match ray_problem(&o, &d) {
                    None => Some((o, d)),
                    Some(problem) => {
                        errors.push(format!("{path}.ray: {form} with {problem}"));
                        None
                    }
                },
                _ => {
                    errors.push(format!("{path}.ray: {form}, 2 or 3 numbers each"));
                    None
                }
            }
        }
    };
    if pixel.is_some() && ray.is_some() {
        errors.push(format!("{path}: give pixel or ray, not both"));
    }
    let depth = map.get("depth").and_then(|d| {
        let n = with_reader(errors, |r| r.integer(d, &format!("{path}.depth"), 0, MAX_DEPTH));
        n.and_then(|n| u32::try_from(n).ok())
    });
    let sampling = sampling(map, path, errors);
    let grid = match map.get("grid") {
        None => None,
        Some(g) => {
            let cells: Option<Vec<usize>> = g.as_array().and_then(|a| {
                a.iter()
                    .map(|x| {
                        x.as_u64()
                            .and_then(|n| usize::try_from(n).ok())
                            .filter(|n| (1..=MAX_CELLS_PER_AXIS).contains(n))
                    })
                    .collect()
            });
            if cells.as_ref().is_none_or(|c| !(2..=3).contains(&c.len())) {
                errors.push(format!("{path}.grid: must be 2 or 3 cell counts in [1, {MAX_CELLS_PER_AXIS}]"));
            }
            cells
        }
    };
    let title = map.get("title").map(|t| both(Some(t), &format!("{path}.title"), errors));
    let caption = both(map.get("caption"), &format!("{path}.caption"), errors);
    let claims = claim::parse(map.get("claims"), &format!("{path}.claims"), errors);
    Some(FigureSpec { kind: kind?, scene: scene?, pixel, ray, depth, sampling, grid, title, caption, claims })
}

/// `aa` (`center`, `corners`, `adaptive`) with `threshold` (default 0.1) and `max_level` (default 2).
fn sampling(map: &Map<'_>, path: &str, errors: &mut Vec<String>) -> Option<Sampling> {
    let aa = map.get("aa")?;
    // Each value is checked as written, and its error names its own field and quotes it.
    let threshold = match map.get("threshold") {
        None => Some(DEFAULT_THRESHOLD),
        Some(t) => match t.as_f64() {
            Some(x) if x >= 0.0 => Some(x),
            Some(x) => {
                errors.push(format!("{path}.threshold: must be a number ≥ 0, got {}", as_written(x)));
                None
            }
            None => {
                errors.push(format!("{path}.threshold: must be a number ≥ 0, got {}", type_name(t)));
                None
            }
        },
    };
    let max_level = match map.get("max_level") {
        None => Some(DEFAULT_MAX_LEVEL),
        Some(k) => {
            with_reader(errors, |r| r.integer(k, &format!("{path}.max_level"), 0, u64::from(MAX_LEVEL)))
                .and_then(|k| u32::try_from(k).ok())
        }
    };
    let made = match aa.as_str() {
        Some("center") => Ok(Sampling::Center),
        Some("corners") => Ok(Sampling::Corners),
        Some("adaptive") => {
            let (threshold, max_level) = (threshold?, max_level?);
            Sampling::adaptive(threshold, max_level).map_err(|e| e.to_string())
        }
        _ => Err("must be center, corners or adaptive".to_owned()),
    };
    made.map_err(|e| errors.push(format!("{path}.aa: {e}"))).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"{ "name": "rays", "title": { "en": "Rays", "ro": "Raze" },
        "figures": [ { "kind": "rays", "scene": "s.json", "pixel": [3], "aa": "adaptive", "max_level": 3,
                       "caption": { "en": "a", "ro": "b" } },
                     { "kind": "refraction", "scene": "t.json", "ray": { "origin": [0, 0], "direction": [1, 0] },
                       "depth": 2, "title": { "en": "T", "ro": "Ț" }, "caption": { "en": "c", "ro": "d" } } ] }"#;

    #[test]
    fn a_lesson_reads() {
        let lesson = parse(GOOD).unwrap();
        assert_eq!(lesson.name, "rays");
        assert_eq!(lesson.figures[0].pixel, Some((3, None)));
        assert_eq!(lesson.figures[1].ray, Some((vec![0.0, 0.0], vec![1.0, 0.0])));
        assert_eq!(lesson.figures[1].depth, Some(2));
        assert_eq!(lesson.figures[0].sampling, Some(Sampling::Adaptive { threshold: 0.1, max_level: 3 }));
        assert_eq!(lesson.figures[1].sampling, None);
        assert_eq!(lesson.file_stem(1), "rays-2-refraction");
        assert_eq!(lesson.title.get(Lang::Ro), "Raze");
        assert_eq!(lesson.figures[0].title, None);
        assert_eq!(lesson.figures[1].title.as_ref().map(|t| t.get(Lang::Ro)), Some("Ț"));
    }

    #[test]
    fn a_lesson_lists_its_exercise_sheets() {
        let text = GOOD.replacen("\"figures\"", "\"exercises\": [ { \"scene\": \"s.json\", \"pixel\": [4, 2], \"seed\": 7 },\n            { \"scene\": \"t.json\", \"pixel\": [1] } ], \"figures\"", 1);
        let lesson = parse(&text).unwrap();
        assert_eq!(
            lesson.exercises[0],
            ExerciseSpec { scene: "s.json".into(), pixel: (4, Some(2)), seed: 7 }
        );
        assert_eq!(lesson.exercises[1].seed, 1);
        assert_eq!(lesson.exercise_files(1), ("rays-exercises-2.html".into(), "rays-answers-2.html".into()));
        assert!(parse(GOOD).unwrap().exercises.is_empty());
        let bad = GOOD.replacen(
            "\"figures\"",
            "\"exercises\": [ { \"scene\": 1, \"pixel\": [-1], \"seeds\": 2 } ], \"figures\"",
            1,
        );
        let all = parse(&bad).unwrap_err().join("\n");
        for expected in ["exercises[0].seeds: unknown field", "exercises[0].scene:", "exercises[0].pixel:"] {
            assert!(all.contains(expected), "{expected} in {all}");
        }
    }

    #[test]
    fn every_problem_is_named() {
        let bad = r#"{ "name": "A b", "title": { "en": "x" }, "extra": 1,
            "figures": [ { "kind": "rainbow", "scene": "s.json", "pixel": [-1], "caption": { "en": "a", "ro": "b" } } ] }"#;
        let errors = parse(bad).unwrap_err();
        let all = errors.join("\n");
        for expected in
            ["name:", "title.ro:", "extra: unknown field", "figures[0].kind:", "figures[0].pixel:"]
        {
            assert!(all.contains(expected), "{expected} in {all}");
        }
    }

    #[test]
    fn a_lesson_is_told_its_errors_in_the_words_of_a_scene() {
        // The scene loader's reader: a suggestion for a typo, a key written twice, the value found.
        let bad = r#"{ "name": "rays", "title": { "en": "x", "ro": 2 }, "figurs": [],
            "figures": [ { "kind": "rays", "scene": "s.json", "depth": 65, "depht": 1, "depth": 2,
                           "caption": { "en": "a", "ro": "b", "ro": "c" } } ] }"#;
        assert_eq!(
            parse(bad).unwrap_err(),
            [
                "figurs: unknown field `figurs`; did you mean `figures`?",
                "title.ro: must be a string, got a number",
                "figures[0].depth: written more than once in this object; keep one",
                "figures[0].depht: unknown field `depht`; did you mean `depth`?",
                "figures[0].depth: must be an integer in [0, 64], got 65",
                "figures[0].caption.ro: written more than once in this object; keep one",
            ]
        );
        let e = parse("{ \"name\": ").unwrap_err();
        assert!(e[0].starts_with("invalid JSON at line 1, column"), "{e:?}");
    }

    /// A lesson of one figure with `fields` added to it.
    fn one_figure(fields: &str) -> Result<Lesson, Vec<String>> {
        parse(&format!(
            r#"{{ "name": "a", "title": {{ "en": "x", "ro": "y" }}, "figures": [ {{ "kind": "rays",
                "scene": "s.json", "caption": {{ "en": "a", "ro": "b" }}, {fields} }} ] }}"#
        ))
    }

    #[test]
    fn sampling_values_are_quoted_as_written_in_their_own_fields() {
        let e = one_figure(r#""aa": "adaptive", "threshold": -1e-7, "max_level": "2""#).unwrap_err();
        assert_eq!(
            e,
            [
                "figures[0].threshold: must be a number ≥ 0, got -1e-7",
                "figures[0].max_level: must be an integer in [0, 8], got a string",
            ]
        );
        let e = one_figure(r#""aa": "adaptive", "threshold": "0.1", "max_level": 9"#).unwrap_err();
        assert_eq!(
            e,
            [
                "figures[0].threshold: must be a number ≥ 0, got a string",
                "figures[0].max_level: must be an integer in [0, 8], got 9",
            ]
        );
    }

    #[test]
    fn a_ray_the_command_line_would_refuse_is_refused_at_load() {
        let ray = |o: &str, d: &str| one_figure(&format!(r#""ray": {{ "origin": {o}, "direction": {d} }}"#));
        let form = r#"figures[0].ray: must be { "origin": [..], "direction": [..] }"#;
        assert_eq!(ray("[0, 0]", "[0, 0]").unwrap_err(), [format!("{form} with a non-zero direction")]);
        assert_eq!(
            ray("[0, 1e300]", "[1, 0]").unwrap_err(),
            [format!("{form} with finite numbers of magnitude at most 1e100")]
        );
        assert_eq!(
            ray("[0, 0]", "[1, 0, 0]").unwrap_err(),
            [format!("{form} with 2 or 3 numbers on each side")]
        );
        assert!(ray("[0, 1e100]", "[1e-300, -2]").is_ok());
    }
}
