//! What a trace follows: `--pixel I,J` (validated against the image; rows from the bottom) or
//! `--ray O:D` (validated against the dimension), turned into the primary ray and the document's
//! `pixel`/`uv`; or, for a figure, nothing (the figure picks a pixel itself). `--object NAME`
//! becomes a `--pixel` first ([`object_pixel`]), so every command that takes a pixel can take it.

use super::parse::PixelArg;
use super::Failure;
use crate::accel::{Accel, AccelKind};
use crate::doc::TraceTarget;
use crate::figure::source::Aim;
use crate::geom::ray::Ray;
use crate::record::stats::Stats;
use crate::record::NoRecorder;
use crate::scene::AnyScene;
use crate::scene::Scene;
use crate::shape::Dim;

/// `--pixel` and `--ray` as given (at most one; a figure takes neither).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Target {
    /// `--pixel I,J` (`I` in 2D): column and optional row, as typed (signed: a negative one is
    /// told it lies outside the image).
    pub pixel: Option<PixelArg>,
    /// `--ray O:D`: the origin's and the direction's components, already parsed.
    pub ray: Option<(Vec<f64>, Vec<f64>)>,
}

impl Target {
    /// Whether neither is given.
    #[must_use]
    pub fn is_none(&self) -> bool {
        self.pixel.is_none() && self.ray.is_none()
    }

    /// The primary ray and what it was asked as.
    ///
    /// # Errors
    /// Bad input: a pixel outside the image or with the wrong number of coordinates, a ray of the
    /// wrong dimension, or neither given.
    pub fn primary<V: Dim>(&self, scene: &Scene<V>) -> Result<(Ray<V>, TraceTarget), Failure> {
        let cam = &scene.camera;
        if let Some((i, j)) = self.pixel {
            let j = match (V::DIM, j) {
                (2, None | Some(0)) => 0,
                (2, Some(j)) => {
                    return Err(Failure::input(format!(
                        "--pixel: a 2D image has one row (j = 0), got j = {j}"
                    )))
                }
                (_, None) => return Err(Failure::input("--pixel: a 3D scene needs I,J".to_string())),
                (_, Some(j)) => j,
            };
            let inside = |k: i64, n: usize| usize::try_from(k).ok().filter(|k| *k < n);
            let (Some(i), Some(j)) = (inside(i, cam.nx), inside(j, cam.ny)) else {
                return Err(Failure::input(format!(
                    "--pixel: ({i}, {j}) is outside the image: i must be in [0, {}), j in [0, {})",
                    cam.nx, cam.ny
                )));
            };
            let (u, v) = cam.pixel_center(i, j);
            let ray = cam.primary_ray(u, v);
            let (pixel, uv) = if V::DIM == 2 { (vec![i], vec![u]) } else { (vec![i, j], vec![u, v]) };
            return Ok((ray, TraceTarget { pixel: Some(pixel), uv: Some(uv) }));
        }
        let Some((o, d)) = &self.ray else {
            return Err(Failure::input("give --pixel I,J or --ray O:D"));
        };
        let wrong = |what: &str, n: usize| {
            Failure::input(format!(
                "--ray: the {what} must have {} numbers in a {}D scene, got {n}",
                V::DIM,
                V::DIM
            ))
        };
        let origin = V::from_slice(o).ok_or_else(|| wrong("origin", o.len()))?;
        let dir = V::from_slice(d).ok_or_else(|| wrong("direction", d.len()))?;
        let dir = dir.try_unit().ok_or_else(|| Failure::input("--ray: the direction must not be zero"))?;
        Ok((Ray::new(origin, dir), TraceTarget { pixel: None, uv: None }))
    }

    /// What a figure traces: the pixel or ray (checked as [`Target::primary`] checks them), or
    /// [`Aim::Auto`] when neither is given.
    ///
    /// # Errors
    /// As [`Target::primary`].
    pub fn aim<V: Dim>(&self, scene: &Scene<V>) -> Result<Aim<V>, Failure> {
        if self.is_none() {
            return Ok(Aim::Auto);
        }
        let (ray, traced) = self.primary(scene)?;
        Ok(match traced.pixel.as_deref() {
            Some([i]) => Aim::Pixel(*i, 0),
            Some([i, j]) => Aim::Pixel(*i, *j),
            _ => Aim::Ray(ray),
        })
    }
}

/// The pixel that shows object `name` (`--object NAME`): among the pixels whose primary ray
/// (through the pixel's centre) has that object as its nearest hit, the one nearest their
/// centroid, ties to the first in scan order (rows from the bottom, columns from the left). The
/// centroid of what the camera sees stands for the object's projected centre, and the pixel nearest
/// it is a hit by construction: it shows the object's middle, not a grazing edge. Every object
/// named `name` counts; each pixel costs one nearest-hit query, no shading and no recording.
///
/// # Errors
/// Bad input: no object has that name (the message lists the names), or no pixel sees it.
pub fn object_pixel(scene: &AnyScene, name: &str) -> Result<PixelArg, Failure> {
    match scene {
        AnyScene::Flat(s) => pixel_showing(s, name),
        AnyScene::Space(s) => pixel_showing(s, name),
    }
}

fn pixel_showing<V: Dim>(scene: &Scene<V>, name: &str) -> Result<PixelArg, Failure> {
    // A name per language answers to either (`--object oglindă` or `--object mirror`).
    let named: Vec<usize> = (0..scene.objects.len())
        .filter(|&k| scene.objects[k].name.as_ref().is_some_and(|n| n.en == name || n.ro == name))
        .collect();
    if named.is_empty() {
        let mut names: Vec<&str> = Vec::new();
        for n in scene.objects.iter().filter_map(|o| o.name.as_ref().map(|n| n.en.as_str())) {
            if !names.contains(&n) {
                names.push(n);
            }
        }
        let list = if names.is_empty() { "none has a name".to_owned() } else { names.join(", ") };
        return Err(Failure::input(format!(
            "--object: no object is named `{name}`; the named objects: {list}"
        )));
    }
    let cam = &scene.camera;
    let accel = Accel::build(scene, AccelKind::Bvh);
    let mut stats = Stats::default();
    let mut seen: Vec<(usize, usize)> = Vec::new();
    for j in 0..cam.ny {
        for i in 0..cam.nx {
            let (u, v) = cam.pixel_center(i, j);
            let hit = accel.nearest(scene, &cam.primary_ray(u, v), &mut stats, &mut NoRecorder);
            if hit.is_some_and(|(o, _)| named.contains(&o.index)) {
                seen.push((i, j));
            }
        }
    }
    let Some(&first) = seen.first() else {
        return Err(Failure::input(format!("--object: no pixel's primary ray hits `{name}` first")));
    };
    #[allow(clippy::cast_precision_loss)] // pixel indices are far below 2^52
    let (ci, cj) = {
        let n = seen.len() as f64;
        let (si, sj) = seen.iter().fold((0.0, 0.0), |(a, b), &(i, j)| (a + i as f64, b + j as f64));
        (si / n, sj / n)
    };
    #[allow(clippy::cast_precision_loss)]
    let distance = |&(i, j): &(usize, usize)| (i as f64 - ci).powi(2) + (j as f64 - cj).powi(2);
    // Strictly nearer replaces: of equal distances the first in scan order stays.
    let (i, j) =
        seen.iter().copied().fold(first, |best, p| if distance(&p) < distance(&best) { p } else { best });
    let index = |k: usize| i64::try_from(k).unwrap_or(i64::MAX);
    Ok((index(i), (V::DIM == 3).then(|| index(j))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load::load_str;

    /// A 2D scene of 9 pixels over [−1, 1] looking down at a circle `a` under pixels 1 and 2
    /// (u = −0.667, −0.444 … centres) and a wide floor line `b`.
    const FLAT: &str = r#"{ "camera": { "eye": [0, 5], "center": [0, 0], "window": { "l": -1, "r": 1 },
        "resolution": [9] },
        "objects": [ { "type": "sphere", "name": "a", "center": [-2.2, 0], "radius": 0.9 },
                     { "type": "plane", "name": "b", "point": [0, -1], "normal": [0, 1] },
                     { "type": "sphere", "center": [40, 0], "radius": 1 } ] }"#;

    #[test]
    fn an_object_is_shown_by_the_pixel_nearest_the_middle_of_its_pixels() {
        let scene = load_str(FLAT).unwrap();
        let AnyScene::Flat(flat) = &scene else { panic!("2D") };
        // Every pixel that sees `a`, by brute force; the answer is the one nearest their mean.
        let cam = &flat.camera;
        let sees: Vec<i64> = (0..cam.nx)
            .filter(|&i| {
                let (u, v) = cam.pixel_center(i, 0);
                let accel = Accel::build(flat, AccelKind::None);
                let hit = accel.nearest(flat, &cam.primary_ray(u, v), &mut Stats::default(), &mut NoRecorder);
                hit.is_some_and(|(o, _)| o.index == 0)
            })
            .map(|i| i64::try_from(i).unwrap())
            .collect();
        assert!(sees.len() >= 2, "{sees:?}");
        let (i, j) = object_pixel(&scene, "a").unwrap();
        assert_eq!(j, None);
        assert!(sees.contains(&i), "{i} not in {sees:?}");
        #[allow(clippy::cast_precision_loss)]
        let mean = sees.iter().sum::<i64>() as f64 / sees.len() as f64;
        #[allow(clippy::cast_precision_loss)]
        let off = |k: i64| (k as f64 - mean).abs();
        assert!(sees.iter().all(|&k| off(i) <= off(k)), "{i} vs {sees:?}");
        // `b` is seen by the pixels `a` does not hide; its middle pixel is one of them.
        let (b, _) = object_pixel(&scene, "b").unwrap();
        assert!(!sees.contains(&b));
    }

    #[test]
    fn an_unknown_or_unseen_object_is_bad_input_naming_the_objects() {
        let scene = load_str(FLAT).unwrap();
        let e = object_pixel(&scene, "c").unwrap_err();
        assert!(e.input);
        assert_eq!(e.message, "--object: no object is named `c`; the named objects: a, b");
        let text = FLAT.replace(
            "\"center\": [40, 0], \"radius\": 1",
            "\"name\": \"far\", \"center\": [40, 0], \"radius\": 1",
        );
        let e = object_pixel(&load_str(&text).unwrap(), "far").unwrap_err();
        assert!(e.input && e.message.contains("no pixel"), "{}", e.message);
    }
}
