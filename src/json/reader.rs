//! The all-errors reader of an input file's JSON tree (scenes, lessons): it walks the tree field
//! by field and, instead of stopping at the first problem, collects every one as a [`ReadError`]
//! naming its JSON path (`objects[2].radius: must be > 0, got -1`). The wording lives here once,
//! so a scene and a lesson word the same problem alike:
//!
//! - an unknown field is named with the closest known one ([`suggest`]), else the list of fields;
//! - a key written twice is an error (which of its values a reader took would be a guess);
//! - a number must be finite and at most [`MAX_MAGNITUDE`] in magnitude (algorithm.md §11);
//! - a syntax error is said with its line and column, and stops the reading.
//!
//! What a field means (its range, its default) is the caller's: the predicates [`positive`],
//! [`unit_interval`] and [`non_negative`] return the problem text for [`Reader::optional`].

use super::{Map, SyntaxError, Value};
use crate::format::{as_written, is_hidden_control};
use std::fmt;

/// The largest magnitude an input number may have (§11): squares and triple sums stay finite.
pub const MAX_MAGNITUDE: f64 = 1e100;

/// What is wrong with a ray given by hand (`--ray`, a lesson's `ray`), worded to follow "with"
/// (`with a non-zero direction`), or `None`: 2 or 3 numbers on each side, each finite and at most
/// [`MAX_MAGNITUDE`] in magnitude, and a direction that is not zero (it is normalised). One check
/// for both, so a lesson names no ray that the command shown beside its figure would refuse.
#[must_use]
pub fn ray_problem(origin: &[f64], direction: &[f64]) -> Option<&'static str> {
    if origin.len() != direction.len() || !(2..=3).contains(&origin.len()) {
        return Some("2 or 3 numbers on each side");
    }
    if origin.iter().chain(direction).any(|x| !(x.abs() <= MAX_MAGNITUDE)) {
        return Some("finite numbers of magnitude at most 1e100");
    }
    if direction.iter().all(|x| *x == 0.0) {
        return Some("a non-zero direction");
    }
    None
}

/// One problem in an input file, with the JSON path of the field it concerns.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    /// The JSON path, e.g. `objects[2].radius` (empty for the whole document).
    pub path: String,
    /// What is wrong, e.g. `must be > 0, got -1`.
    pub problem: String,
}

impl ReadError {
    /// An error at `path`.
    pub fn new(path: impl Into<String>, problem: impl Into<String>) -> Self {
        Self { path: path.into(), problem: problem.into() }
    }

    /// The error of a text that is not JSON, for the whole document.
    #[must_use]
    pub fn syntax(e: &SyntaxError) -> Self {
        Self::new("", format!("invalid JSON at line {}, column {}: {}", e.line, e.column, e.message))
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.problem)
        } else {
            write!(f, "{}: {}", self.path, self.problem)
        }
    }
}

impl std::error::Error for ReadError {}

/// Collects the errors found while reading [`Value`]s; each method reads one value at a path,
/// reports what is wrong with it, and returns what it could read.
#[derive(Debug, Default)]
pub struct Reader {
    errors: Vec<ReadError>,
}

/// `path.key`, or `key` at the top.
#[must_use]
pub fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// How an error names the type of a value it did not expect: `a number`, `an array`, ….
#[must_use]
pub fn type_name(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
        Value::Deferred(_) => "a value",
    }
}

/// The closest of `known` to `word` by Levenshtein distance (`strsim`), if it is close enough to
/// be a typo: at most 2 edits (a third of a long name), and fewer than the name has letters, so
/// that no name is offered for a word it shares nothing with (`b` is not a typo of `l`).
#[must_use]
pub fn suggest<'a>(word: &str, known: &[&'a str]) -> Option<&'a str> {
    known
        .iter()
        .map(|k| (strsim::levenshtein(word, k), *k))
        .filter(|(d, k)| {
            let letters = k.chars().count();
            *d <= 2.max(letters / 3) && *d < letters
        })
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// `x > 0`, else the problem.
#[must_use]
pub fn positive(x: f64) -> Option<String> {
    (x <= 0.0).then(|| format!("must be > 0, got {}", as_written(x)))
}

/// `x ∈ [0, 1]`, else the problem.
#[must_use]
pub fn unit_interval(x: f64) -> Option<String> {
    (!(0.0..=1.0).contains(&x)).then(|| format!("must be in [0, 1], got {}", as_written(x)))
}

/// `x ≥ 0`, else the problem.
#[must_use]
pub fn non_negative(x: f64) -> Option<String> {
    (x < 0.0).then(|| format!("must be ≥ 0, got {}", as_written(x)))
}

impl Reader {
    /// Reports `problem` at `path`.
    pub fn err(&mut self, path: impl Into<String>, problem: impl Into<String>) {
        self.errors.push(ReadError::new(path, problem));
    }

    /// True iff nothing was reported.
    #[must_use]
    pub fn is_clean(&self) -> bool {
        self.errors.is_empty()
    }

    /// Everything reported, in the order found.
    #[must_use]
    pub fn into_errors(self) -> Vec<ReadError> {
        self.errors
    }

    /// `value` if nothing was reported, else every error.
    ///
    /// # Errors
    /// Every problem reported.
    pub fn finish<T>(self, value: Option<T>) -> Result<T, Vec<ReadError>> {
        match value {
            Some(v) if self.errors.is_empty() => Ok(v),
            _ => Err(self.errors),
        }
    }

    /// An object whose keys are all in `known`; unknown keys are errors with a suggestion.
    /// A key written twice is an error too: which of its values a reader took would be a guess.
    pub fn fields<'a, 'j>(&mut self, v: &'a Value<'j>, path: &str, known: &[&str]) -> Option<&'a Map<'j>> {
        let Some(map) = v.as_object() else {
            self.err(path, format!("must be an object, got {}", type_name(v)));
            return None;
        };
        self.keys(map, path, known);
        Some(map)
    }

    /// Reports the keys of `map` not in `known` (with a suggestion) and the keys written twice.
    pub fn keys(&mut self, map: &Map<'_>, path: &str, known: &[&str]) {
        for key in map.duplicates() {
            self.err(join(path, key), "written more than once in this object; keep one");
        }
        for key in map.keys() {
            if !known.contains(&key) {
                let hint = match suggest(key, known) {
                    Some(s) => format!("unknown field `{key}`; did you mean `{s}`?"),
                    None => format!("unknown field `{key}`; expected one of: {}", known.join(", ")),
                };
                self.err(join(path, key), hint);
            }
        }
    }

    /// A finite number at most [`MAX_MAGNITUDE`] in magnitude.
    pub fn number(&mut self, v: &Value, path: &str) -> Option<f64> {
        let Some(x) = v.as_f64() else {
            self.err(path, format!("must be a number, got {}", type_name(v)));
            return None;
        };
        if !x.is_finite() || x.abs() > MAX_MAGNITUDE {
            self.err(path, format!("must be at most {MAX_MAGNITUDE:e} in magnitude, got {}", as_written(x)));
            return None;
        }
        Some(x)
    }

    /// A required number.
    pub fn required(&mut self, map: &Map<'_>, path: &str, key: &str) -> Option<f64> {
        match map.get(key) {
            Some(v) => self.number(v, &join(path, key)),
            None => {
                self.err(join(path, key), "missing (required)");
                None
            }
        }
    }

    /// An optional number with its default; `check` returns the problem text, if any.
    pub fn optional(
        &mut self,
        map: &Map<'_>,
        path: &str,
        key: &str,
        default: f64,
        check: impl Fn(f64) -> Option<String>,
    ) -> f64 {
        let Some(v) = map.get(key) else {
            return default;
        };
        let p = join(path, key);
        match self.number(v, &p) {
            Some(x) => match check(x) {
                Some(problem) => {
                    self.err(p, problem);
                    default
                }
                None => x,
            },
            None => default,
        }
    }

    /// A whole number in `[min, max]`, written without fraction or exponent.
    pub fn integer(&mut self, v: &Value, path: &str, min: u64, max: u64) -> Option<u64> {
        let Some(n) = v.as_u64() else {
            let got = match v.as_f64() {
                Some(x) => as_written(x),
                None => type_name(v).to_string(),
            };
            self.err(path, format!("must be an integer in [{min}, {max}], got {got}"));
            return None;
        };
        if n < min || n > max {
            self.err(path, format!("must be an integer in [{min}, {max}], got {n}"));
            return None;
        }
        Some(n)
    }

    /// A string.
    pub fn string<'a>(&mut self, v: &'a Value, path: &str) -> Option<&'a str> {
        let s = v.as_str();
        if s.is_none() {
            self.err(path, format!("must be a string, got {}", type_name(v)));
        }
        s
    }

    /// A name a reader will see (an object's, a material's, a light's): a string holding no
    /// control or bidirectional character ([`is_hidden_control`]), which a terminal would execute
    /// instead of showing; the first one found is named by its code point.
    pub fn name<'a>(&mut self, v: &'a Value, path: &str) -> Option<&'a str> {
        let s = self.string(v, path)?;
        self.name_text(s, path).then_some(s)
    }

    /// Checks a name's text, as [`Reader::name`] does (also for a key: a material's name);
    /// false after reporting it.
    pub fn name_text(&mut self, s: &str, path: &str) -> bool {
        let Some(c) = s.chars().find(|c| is_hidden_control(*c)) else { return true };
        self.err(
            path,
            format!(
                "a name must not hold a control or bidirectional character, found U+{:04X}",
                u32::from(c)
            ),
        );
        false
    }

    /// A required name ([`Reader::name`]).
    pub fn required_name<'a>(&mut self, map: &'a Map<'_>, path: &str, key: &str) -> Option<&'a str> {
        let s = self.required_string(map, path, key)?;
        self.name_text(s, &join(path, key)).then_some(s)
    }

    /// A required string.
    pub fn required_string<'a>(&mut self, map: &'a Map<'_>, path: &str, key: &str) -> Option<&'a str> {
        match map.get(key) {
            Some(v) => self.string(v, &join(path, key)),
            None => {
                self.err(join(path, key), "missing (required)");
                None
            }
        }
    }

    /// An array, each item read by `item` at `path[i]`; `None` if it is not an array or any item
    /// failed (every item is read, so every error is reported).
    pub fn array<T>(
        &mut self,
        v: &Value,
        path: &str,
        mut item: impl FnMut(&mut Self, &Value, &str) -> Option<T>,
    ) -> Option<Vec<T>> {
        let Some(items) = v.as_array() else {
            self.err(path, format!("must be an array, got {}", type_name(v)));
            return None;
        };
        let read: Vec<Option<T>> =
            items.iter().enumerate().map(|(i, x)| item(self, x, &format!("{path}[{i}]"))).collect();
        read.into_iter().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::json::parse;

    fn errors(r: Reader) -> Vec<String> {
        r.into_errors().iter().map(ToString::to_string).collect()
    }

    #[test]
    fn suggests_the_nearest_field() {
        assert_eq!(suggest("radus", &["center", "radius", "material"]), Some("radius"));
        assert_eq!(suggest("zzzzzz", &["center", "radius"]), None);
        // A 3D window's `b` given to a 2D scene's window (l, r): no one-letter name to offer.
        assert_eq!(suggest("b", &["l", "r"]), None);
        assert_eq!(suggest("ambeint", &["ambient", "background"]), Some("ambient"));
    }

    #[test]
    fn unknown_and_repeated_fields_are_named_with_their_path() {
        let v = parse(r#"{"radus": 1, "center": 0, "center": 1, "zzzzzz": 2}"#).unwrap();
        let mut r = Reader::default();
        assert!(r.fields(&v, "objects[0]", &["center", "radius"]).is_some());
        assert_eq!(
            errors(r),
            [
                "objects[0].center: written more than once in this object; keep one",
                "objects[0].radus: unknown field `radus`; did you mean `radius`?",
                "objects[0].zzzzzz: unknown field `zzzzzz`; expected one of: center, radius",
            ]
        );
    }

    #[test]
    fn numbers_integers_and_arrays_report_every_item() {
        let v = parse(r#"[1, "x", 2e200, 0.5, -3]"#).unwrap();
        let mut r = Reader::default();
        assert_eq!(r.array(&v, "a", |r, x, p| r.number(x, p)), None);
        assert_eq!(
            errors(r),
            ["a[1]: must be a number, got a string", "a[2]: must be at most 1e100 in magnitude, got 2e200"]
        );
        let mut r = Reader::default();
        let items = v.as_array().unwrap();
        assert_eq!(r.integer(&items[0], "n", 0, 64), Some(1));
        assert_eq!(r.integer(&items[3], "n", 0, 64), None);
        assert_eq!(r.integer(&items[4], "n", 0, 64), None);
        assert_eq!(
            errors(r),
            ["n: must be an integer in [0, 64], got 0.5", "n: must be an integer in [0, 64], got -3"]
        );
        assert_eq!(positive(0.0).as_deref(), Some("must be > 0, got 0"));
        assert_eq!(unit_interval(2.0).as_deref(), Some("must be in [0, 1], got 2"));
        assert_eq!(non_negative(-1e-7).as_deref(), Some("must be ≥ 0, got -1e-7"));
    }
}
