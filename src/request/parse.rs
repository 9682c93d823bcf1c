//! The options' values as the command line writes them, parsed and checked: `--pixel I,J`,
//! `--ray OX,OY,OZ:DX,DY,DZ`, `--size WxH`, `--threshold X`, `--grid NX,NY[,NZ]`, `--depth N`,
//! `--max-level K`, `--threads N`, `--runs N`, `--max-events N`. The command line hands clap these parsers; the WebAssembly binding writes a
//! request's numbers in the same form and parses them here, so both refuse a value with the same
//! words.

use crate::accel::grid::MAX_CELLS;
use crate::json::reader::ray_problem;
use crate::sample::MAX_LEVEL;

/// A pixel as typed: column and optional row, signed so that `--pixel -1,2` reaches the check
/// against the image and is told it lies outside, instead of being taken for a flag.
pub type PixelArg = (i64, Option<i64>);

/// `I,J` or `I` (2D) → column and optional row; whether they lie in the image is the caller's
/// check, which knows its size.
///
/// # Errors
/// A message naming the expected form.
pub fn pixel(text: &str) -> Result<PixelArg, String> {
    let bad = || format!("--pixel: expected I,J (or I in 2D) with whole numbers, got `{text}`");
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    match parts.as_slice() {
        [i] => Ok((i.parse().map_err(|_| bad())?, None)),
        [i, j] => Ok((i.parse().map_err(|_| bad())?, Some(j.parse().map_err(|_| bad())?))),
        _ => Err(bad()),
    }
}

/// `OX,OY,OZ:DX,DY,DZ` (2 components each in 2D) → origin and direction components.
///
/// # Errors
/// A message naming the expected form.
pub fn ray(text: &str) -> Result<(Vec<f64>, Vec<f64>), String> {
    let bad =
        |why: &str| format!("--ray: expected OX,OY,OZ:DX,DY,DZ (OX,OY:DX,DY in 2D), {why}, got `{text}`");
    let (o, d) = text.split_once(':').ok_or_else(|| bad("missing `:`"))?;
    let nums = |s: &str| -> Result<Vec<f64>, String> {
        s.split(',')
            .map(|x| x.trim().parse::<f64>().ok())
            .collect::<Option<Vec<f64>>>()
            .ok_or_else(|| bad("with numbers"))
    };
    let (o, d) = (nums(o)?, nums(d)?);
    match ray_problem(&o, &d) {
        Some(problem) => Err(bad(&format!("with {problem}"))),
        None => Ok((o, d)),
    }
}

/// A whole number in `[min, max]`, for the option `name`: negative numbers reach here (the options
/// allow hyphen values) and are told their range instead of being taken for a flag.
fn whole(name: &str, text: &str, min: u64, max: u64) -> Result<u64, String> {
    text.trim()
        .parse::<i128>()
        .ok()
        .and_then(|n| u64::try_from(n).ok())
        .filter(|n| (min..=max).contains(n))
        .ok_or_else(|| format!("{name}: expected a whole number in [{min}, {max}], got `{text}`"))
}

/// `--depth N`: `[0, MAX_DEPTH]` (the scene's own limit on `max_depth`).
///
/// # Errors
/// A message naming `--depth` and its range.
pub fn depth(text: &str) -> Result<u32, String> {
    let n = whole("--depth", text, 0, crate::scene::load::MAX_DEPTH)?;
    u32::try_from(n).map_err(|e| e.to_string())
}

/// `--threads N`: `[1, MAX_THREADS]`.
///
/// # Errors
/// A message naming `--threads` and its range.
pub fn threads(text: &str) -> Result<u32, String> {
    let n = whole("--threads", text, 1, u64::from(crate::render::MAX_THREADS))?;
    u32::try_from(n).map_err(|e| e.to_string())
}

/// `--runs N` of `tradeoff`: `[1, MAX_RUNS]`.
///
/// # Errors
/// A message naming `--runs` and its range.
pub fn runs(text: &str) -> Result<u32, String> {
    let n = whole("--runs", text, 1, u64::from(crate::tradeoff::MAX_RUNS))?;
    u32::try_from(n).map_err(|e| e.to_string())
}

/// `--max-events N`: at least 1, at most `MAX_EVENTS_LIMIT`.
///
/// # Errors
/// A message naming `--max-events` and its range.
pub fn max_events(text: &str) -> Result<usize, String> {
    let n = whole("--max-events", text, 1, crate::record::MAX_LIMIT as u64)?;
    usize::try_from(n).map_err(|e| e.to_string())
}

/// `WxH` or `W` → width and optional height.
///
/// # Errors
/// A message naming the expected form.
pub fn size(text: &str) -> Result<(usize, Option<usize>), String> {
    let most = crate::scene::load::MAX_RESOLUTION;
    let bad = || format!("--size: expected WxH (or W) with whole numbers in [1, {most}], got `{text}`");
    let check = |s: &str| {
        s.trim()
            .parse::<u64>()
            .ok()
            .filter(|n| (1..=most).contains(n))
            .and_then(|n| usize::try_from(n).ok())
            .ok_or_else(bad)
    };
    match text.split_once(['x', 'X']) {
        Some((w, h)) => Ok((check(w)?, Some(check(h)?))),
        None => Ok((check(text)?, None)),
    }
}

/// `X`: a number ≥ 0 or `inf` (numerics.md H1: a NaN would never split, a negative threshold
/// always).
///
/// # Errors
/// A message naming `--threshold`.
pub fn threshold(text: &str) -> Result<f64, String> {
    let x: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("--threshold: expected a number ≥ 0 or inf, got `{text}`"))?;
    crate::sample::Sampling::adaptive(x, 0).map_err(|e| e.to_string())?;
    Ok(x)
}

/// `NX,NY[,NZ]`: the grid's cells per axis, each at least 1, at most [`MAX_CELLS`] in all.
///
/// # Errors
/// A message naming `--grid`'s form or limit.
pub fn grid(text: &str) -> Result<Vec<usize>, String> {
    let n: Vec<usize> = text
        .split(',')
        .map(|x| x.trim().parse::<usize>().map_err(|_| format!("`{x}` is not a cell count")))
        .collect::<Result<_, _>>()?;
    if !(2..=3).contains(&n.len()) {
        return Err(format!("expected NX,NY,NZ (or NX,NY in 2D), got {} numbers", n.len()));
    }
    if n.contains(&0) {
        return Err("every cell count must be at least 1".into());
    }
    let total = n.iter().try_fold(1usize, |a, &b| a.checked_mul(b));
    if total.is_none_or(|t| t > MAX_CELLS) {
        return Err(format!("at most {MAX_CELLS} cells in all"));
    }
    Ok(n)
}

/// `--max-level K`: `[0, MAX_LEVEL]` (the binding's; the command line lets clap check it).
///
/// # Errors
/// A message naming `--max-level` and its range.
pub fn max_level(text: &str) -> Result<u32, String> {
    let n = whole("--max-level", text, 0, u64::from(MAX_LEVEL))?;
    u32::try_from(n).map_err(|e| e.to_string())
}

#[cfg(test)]
// These tests pin exact IEEE results on purpose (numerics.md gives bit-exact expectations).
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn pixels() {
        assert_eq!(pixel("12,7"), Ok((12, Some(7))));
        assert_eq!(pixel("3"), Ok((3, None)));
        assert!(pixel("1,2,3").is_err());
        assert_eq!(pixel("-1,2"), Ok((-1, Some(2))));
        assert!(pixel("1.5,2").is_err());
        assert!(pixel("a").is_err());
    }

    #[test]
    fn rays() {
        assert_eq!(ray("0,0,5:0,0,-1"), Ok((vec![0.0, 0.0, 5.0], vec![0.0, 0.0, -1.0])));
        assert!(ray("0,0,5").is_err());
        assert!(ray("0,0,5:0,0").is_err());
        assert!(ray("0,0,5:0,0,0").is_err());
        assert!(ray("0,0,nan:0,0,1").is_err());
        // The scene's own bound on a number (MAX_MAGNITUDE = 1e100), through `ray_problem`.
        assert!(ray("0,0,1e100:0,0,1").is_ok());
        assert!(ray("0,0,2e100:0,0,1").is_err());
    }

    #[test]
    fn a_lessons_ray_reads_back_from_the_command_shown_beside_its_figure() {
        let text = r#"{ "name": "a", "title": { "en": "x", "ro": "y" }, "figures": [ { "kind": "rays",
            "scene": "s.json", "caption": { "en": "a", "ro": "b" },
            "ray": { "origin": [0, 1e100], "direction": [1e-300, -2] } } ] }"#;
        let spec = &crate::lesson::parse(text).unwrap().figures[0];
        assert_eq!(ray(&spec.ray_arg().unwrap()), Ok(spec.ray.clone().unwrap()));
    }

    #[test]
    fn thresholds() {
        assert_eq!(threshold("0.1"), Ok(0.1));
        assert_eq!(threshold("0"), Ok(0.0));
        assert_eq!(threshold("inf"), Ok(f64::INFINITY));
        for bad in ["nan", "NaN", "-0.1", "-inf", "x"] {
            let e = threshold(bad).unwrap_err();
            assert!(e.starts_with("--threshold"), "{e}");
        }
    }

    #[test]
    fn grid_cells() {
        assert_eq!(grid("4,4,4"), Ok(vec![4, 4, 4]));
        assert_eq!(grid("8,2"), Ok(vec![8, 2]));
        assert!(grid("0,1,1").is_err());
        assert!(grid("4").is_err());
        assert!(grid("4096,4096,4096").is_err());
    }

    #[test]
    fn depths_and_levels() {
        assert_eq!(depth("64"), Ok(64));
        assert_eq!(depth("65").unwrap_err(), "--depth: expected a whole number in [0, 64], got `65`");
        assert!(depth("-1").is_err() && depth("1.5").is_err());
        assert_eq!(max_level("8"), Ok(8));
        assert!(max_level("9").unwrap_err().starts_with("--max-level"));
    }

    #[test]
    fn sizes() {
        assert_eq!(size("640x480"), Ok((640, Some(480))));
        assert_eq!(size("64"), Ok((64, None)));
        assert!(size("0x4").is_err());
        assert!(size("axb").is_err());
    }
}
