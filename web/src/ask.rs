//! Reading a request: its fields checked by name, and each option written as the command line
//! writes it (`[400, 200]` → `400,200`) and parsed by the command line's own parsers
//! (`whitted::request::parse`), so a bad value gets the command line's words.

use serde_json::{Map, Value};
use whitted::accel::AccelKind;
use whitted::bounds::VolumeKind;
use whitted::doc::narrate::Lang;
use whitted::figure::FigureKind;
use whitted::request::options::{Aa, AccelChoice, SamplingOptions};
use whitted::request::parse;
use whitted::request::target::Target;
use whitted::request::Failure;

/// The fields of `options`, as the command line names them (`max_level` is `--max-level`).
pub const OPTIONS: [&str; 9] =
    ["depth", "aa", "threshold", "max_level", "accel", "bounds", "grid", "size", "max_events"];

/// A JSON value as an option's text: a string as it is, anything else as JSON.
fn text(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// A list's items joined by `sep` (`[400, 200]` → `400,200`), or the value's text when it is not
/// a list, for the parser to refuse.
fn joined(value: &Value, sep: &str) -> String {
    match value {
        Value::Array(items) => items.iter().map(text).collect::<Vec<_>>().join(sep),
        other => text(other),
    }
}

/// One of `names` by its name, else the message of a command line that lists them.
fn named<T: Copy>(flag: &str, value: &Value, names: &[(&str, T)]) -> Result<T, Failure> {
    let given = text(value);
    names.iter().find(|(n, _)| *n == given).map(|(_, t)| *t).ok_or_else(|| {
        let list: Vec<&str> = names.iter().map(|(n, _)| *n).collect();
        Failure::input(format!("{flag}: expected one of {}, got `{given}`", list.join(", ")))
    })
}

/// A request's object with the fields it may have.
pub struct Fields<'a> {
    map: &'a Map<String, Value>,
}

impl<'a> Fields<'a> {
    /// `value` as an object whose every field is in `known` (`what` names it in messages).
    pub fn of(what: &str, value: &'a Value, known: &[&str]) -> Result<Self, Failure> {
        let Value::Object(map) = value else {
            return Err(Failure::input(format!("{what}: expected an object, got `{value}`")));
        };
        if let Some(unknown) = map.keys().find(|k| !known.contains(&k.as_str())) {
            return Err(Failure::input(format!(
                "{what}: unknown field `{unknown}`; the fields are: {}",
                known.join(", ")
            )));
        }
        Ok(Self { map })
    }

    /// The field, if given and not null.
    pub fn get(&self, name: &str) -> Option<&'a Value> {
        self.map.get(name).filter(|v| !v.is_null())
    }

    /// A string field that must be given.
    pub fn string(&self, what: &str, name: &str) -> Result<&'a str, Failure> {
        match self.get(name) {
            Some(Value::String(s)) => Ok(s),
            Some(other) => Err(Failure::input(format!("{what}.{name}: expected a string, got `{other}`"))),
            None => Err(Failure::input(format!("{what}: `{name}` is missing"))),
        }
    }
}

/// The `rows` (or `columns`) of a render by bands: `[first, count]`, whole numbers (file rows,
/// the top one 0; a 2D line's pixels, the left one 0).
pub fn span(value: &Value, field: &str) -> Result<(usize, usize), Failure> {
    let pair = value.as_array().filter(|a| a.len() == 2).and_then(|a| {
        let first = usize::try_from(a[0].as_u64()?).ok()?;
        let count = usize::try_from(a[1].as_u64()?).ok()?;
        Some((first, count))
    });
    pair.filter(|(_, count)| *count > 0).ok_or_else(|| {
        Failure::input(format!(
            "request.{field}: expected [first, count], whole numbers, count ≥ 1, got `{value}`"
        ))
    })
}

/// The options of a request, parsed.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// `--depth`.
    pub depth: Option<u32>,
    /// `--aa`, `--threshold`, `--max-level`.
    pub sampling: SamplingOptions,
    /// `--accel`, `--bounds`, `--grid`.
    pub accel: AccelChoice,
    /// `--size`.
    pub size: Option<(usize, Option<usize>)>,
    /// `--max-events` (trace and narrate).
    pub max_events: Option<usize>,
}

/// The `options` object (absent: every default).
pub fn options(value: Option<&Value>) -> Result<Options, Failure> {
    let mut out = Options::default();
    let Some(value) = value else { return Ok(out) };
    let f = Fields::of("options", value, &OPTIONS)?;
    let input = Failure::input;
    if let Some(v) = f.get("depth") {
        out.depth = Some(parse::depth(&text(v)).map_err(input)?);
    }
    if let Some(v) = f.get("aa") {
        let modes = Aa::ALL.map(|a| (a.name(), a));
        out.sampling.aa = Some(named("--aa", v, &modes)?);
    }
    if let Some(v) = f.get("threshold") {
        out.sampling.threshold = Some(parse::threshold(&text(v)).map_err(input)?);
    }
    if let Some(v) = f.get("max_level") {
        out.sampling.max_level = Some(parse::max_level(&text(v)).map_err(input)?);
    }
    if let Some(v) = f.get("accel") {
        let kinds = AccelKind::ALL.map(|k| (k.name(), k));
        out.accel.kind = named("--accel", v, &kinds)?;
    }
    if let Some(v) = f.get("bounds") {
        let kinds = [VolumeKind::Sphere, VolumeKind::Aabb, VolumeKind::Kdop].map(|k| (k.name(), k));
        out.accel.volume = Some(named("--bounds", v, &kinds)?);
    }
    if let Some(v) = f.get("grid") {
        out.accel.grid = Some(parse::grid(&joined(v, ",")).map_err(|e| input(format!("--grid: {e}")))?);
    }
    if let Some(v) = f.get("max_events") {
        out.max_events = Some(parse::max_events(&text(v)).map_err(input)?);
    }
    if let Some(v) = f.get("size") {
        out.size = Some(parse::size(&joined(v, "x")).map_err(input)?);
    }
    Ok(out)
}

/// The `target` object: `{"pixel": [i, j]}` or `{"ray": [[o…], [d…]]}`, or absent.
pub fn target(value: Option<&Value>) -> Result<Target, Failure> {
    let Some(value) = value else { return Ok(Target::default()) };
    let f = Fields::of("target", value, &["pixel", "ray"])?;
    let input = Failure::input;
    let pixel = f.get("pixel").map(|v| parse::pixel(&joined(v, ","))).transpose().map_err(input)?;
    let ray = match f.get("ray") {
        Some(Value::Array(parts)) if parts.len() == 2 => Some(
            parse::ray(&format!("{}:{}", joined(&parts[0], ","), joined(&parts[1], ","))).map_err(input)?,
        ),
        Some(other) => Some(parse::ray(&text(other)).map_err(input)?),
        None => None,
    };
    if pixel.is_some() && ray.is_some() {
        return Err(Failure::input("target: give `pixel` or `ray`, not both"));
    }
    Ok(Target { pixel, ray })
}

/// The `lang` field (absent: English).
pub fn lang(value: Option<&Value>) -> Result<Lang, Failure> {
    value.map_or(Ok(Lang::En), |v| named("--lang", v, &[("en", Lang::En), ("ro", Lang::Ro)]))
}

/// The `kind` field of a figure, as `whitted figure KIND` refuses an unknown one.
pub fn kind(value: Option<&Value>) -> Result<FigureKind, Failure> {
    let Some(value) = value else { return Err(Failure::input("figure: `kind` is missing")) };
    let given = text(value);
    FigureKind::from_name(&given).ok_or_else(|| {
        let names: Vec<&str> = FigureKind::ALL.iter().map(|k| k.name()).collect();
        Failure::input(format!("unknown figure kind `{given}`; the kinds are: {}", names.join(", ")))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn options_are_parsed_by_the_command_line_parsers() {
        let o = options(Some(&json!({"depth": 3, "aa": "adaptive", "threshold": "inf", "max_level": 4,
            "accel": "grid", "grid": [4, 4, 2], "size": [64]})))
        .unwrap();
        assert_eq!(o.depth, Some(3));
        assert_eq!(o.sampling.threshold, Some(f64::INFINITY));
        assert_eq!(o.accel.grid, Some(vec![4, 4, 2]));
        assert_eq!(o.size, Some((64, None)));
        let err = |v: Value| options(Some(&v)).unwrap_err().message;
        assert_eq!(err(json!({"depth": 65})), "--depth: expected a whole number in [0, 64], got `65`");
        assert_eq!(
            err(json!({"size": [0, 4]})),
            "--size: expected WxH (or W) with whole numbers in [1, 65536], got `0x4`"
        );
        assert_eq!(err(json!({"threshold": -1})), "--threshold: must be a number ≥ 0 or inf, got -1");
        assert_eq!(err(json!({"grid": [0, 1, 1]})), "--grid: every cell count must be at least 1");
        assert_eq!(err(json!({"aa": "best"})), "--aa: expected one of center, corners, adaptive, got `best`");
        assert!(err(json!({"colour": 1})).starts_with("options: unknown field `colour`"));
    }

    #[test]
    fn targets() {
        let t = target(Some(&json!({"pixel": [400, 200]}))).unwrap();
        assert_eq!(t.pixel, Some((400, Some(200))));
        let t = target(Some(&json!({"ray": [[0, 0, 5], [0, 0, -1]]}))).unwrap();
        assert_eq!(t.ray, Some((vec![0.0, 0.0, 5.0], vec![0.0, 0.0, -1.0])));
        // A negative pixel parses, to be told it lies outside the image; a fraction does not.
        assert_eq!(target(Some(&json!({"pixel": [-1, 2]}))).unwrap().pixel, Some((-1, Some(2))));
        let err = target(Some(&json!({"pixel": [1.5, 2]}))).unwrap_err().message;
        assert!(err.starts_with("--pixel: expected I,J"), "{err}");
        assert!(target(Some(&json!({"ray": [[0, 0], [0, 0]]}))).unwrap_err().message.contains("non-zero"));
        assert!(target(None).unwrap().is_none());
    }
}
