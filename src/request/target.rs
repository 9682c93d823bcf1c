//! What a trace follows: `--pixel I,J` (validated against the image; rows from the bottom) or
//! `--ray O:D` (validated against the dimension), turned into the primary ray and the document's
//! `pixel`/`uv`; or, for a figure, nothing (the figure picks a pixel itself).

use super::parse::PixelArg;
use super::Failure;
use crate::doc::TraceTarget;
use crate::figure::source::Aim;
use crate::geom::ray::Ray;
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
