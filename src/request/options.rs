//! The options shared by `render`, `trace`, `figure` (and the binding's requests), turned once
//! into the library's types: the sampling of `--aa`/`--threshold`/`--max-level` (algorithm.md §8)
//! with a note for each option the mode ignores, the structure of `--accel`/`--bounds`/`--grid`
//! (§9) checked against the scene's dimension, and `--size` applied to a camera or a canvas.

use super::Failure;
use crate::accel::{AccelKind, AccelOptions};
use crate::bounds::VolumeKind;
use crate::figure::style::{REFERENCE_HEIGHT, REFERENCE_WIDTH};
use crate::figure::MAX_CANVAS_PIXELS;
use crate::sample::{Sampling, DEFAULT_MAX_LEVEL, DEFAULT_THRESHOLD};
use crate::scene::Scene;
use crate::shape::Dim;

/// The `--aa` modes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aa {
    /// One ray through each pixel centre.
    Center,
    /// The 4 shared pixel corners.
    Corners,
    /// Whitted's adaptive subdivision.
    Adaptive,
}

impl Aa {
    /// Every mode, in `--aa`'s order.
    pub const ALL: [Self; 3] = [Self::Center, Self::Corners, Self::Adaptive];

    /// The name `--aa` takes.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Center => "center",
            Self::Corners => "corners",
            Self::Adaptive => "adaptive",
        }
    }

    /// The mode called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|a| a.name() == name)
    }
}

/// `--aa`, `--threshold`, `--max-level` as given: each optional, so that an option the mode does
/// not use is noted, and `figure adaptive|heat-map` default to adaptive with the given ones.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SamplingOptions {
    /// `--aa`.
    pub aa: Option<Aa>,
    /// `--threshold` (already checked by `parse::threshold`, checked again here).
    pub threshold: Option<f64>,
    /// `--max-level`.
    pub max_level: Option<u32>,
}

/// A validated sampling mode and the notes on the options it ignores.
#[derive(Clone, Debug, PartialEq)]
pub struct Chosen {
    /// The mode.
    pub sampling: Sampling,
    /// One line per ignored option, e.g. `--threshold applies to --aa adaptive only; ignored
    /// with --aa center` (the command line prints them on stderr after `whitted: `).
    pub notes: Vec<String>,
}

impl SamplingOptions {
    /// The validated mode, `default` when `--aa` is not given.
    ///
    /// # Errors
    /// Bad input naming `--threshold` or `--max-level`.
    pub fn choose(&self, default: Aa) -> Result<Chosen, Failure> {
        let aa = self.aa.unwrap_or(default);
        let mut notes = Vec::new();
        if aa != Aa::Adaptive {
            for (given, flag) in
                [(self.threshold.is_some(), "--threshold"), (self.max_level.is_some(), "--max-level")]
            {
                if given {
                    notes.push(format!(
                        "{flag} applies to --aa adaptive only; ignored with --aa {}",
                        aa.name()
                    ));
                }
            }
        }
        let sampling = match aa {
            Aa::Center => Sampling::Center,
            Aa::Corners => Sampling::Corners,
            Aa::Adaptive => Sampling::adaptive(
                self.threshold.unwrap_or(DEFAULT_THRESHOLD),
                self.max_level.unwrap_or(DEFAULT_MAX_LEVEL),
            )
            .map_err(|e| Failure::input(e.to_string()))?,
        };
        Ok(Chosen { sampling, notes })
    }
}

/// `--accel`, `--bounds`, `--grid` as given (the defaults: `bvh`, `aabb`, the grid's heuristic);
/// `--bounds` and `--grid` optional, so that one the structure does not read is noted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AccelChoice {
    /// `--accel`.
    pub kind: AccelKind,
    /// `--bounds`.
    pub volume: Option<VolumeKind>,
    /// `--grid`, already parsed by `parse::grid`.
    pub grid: Option<Vec<usize>>,
}

impl Default for AccelChoice {
    fn default() -> Self {
        Self { kind: AccelKind::Bvh, volume: None, grid: None }
    }
}

impl AccelChoice {
    /// The options, checked against the scene's dimension.
    ///
    /// # Errors
    /// Bad input when `--grid` has the wrong number of axes.
    pub fn options(&self, dim: usize) -> Result<AccelOptions, Failure> {
        if let Some(g) = &self.grid {
            if g.len() != dim {
                return Err(Failure::input(format!(
                    "--grid: a {dim}D scene needs {dim} cell counts, got {}",
                    g.len()
                )));
            }
        }
        Ok(AccelOptions {
            kind: self.kind,
            volume: self.volume.unwrap_or(VolumeKind::Aabb),
            grid: self.grid.clone(),
        })
    }

    /// One line per option the structure `used` does not read (as `--threshold` without adaptive
    /// sampling): `--bounds applies to --accel bounds only; ignored with --accel bvh`. A figure of
    /// a structure traces with its own, whatever `--accel` says.
    #[must_use]
    pub fn notes(&self, used: AccelKind) -> Vec<String> {
        let mut notes = Vec::new();
        if self.volume.is_some() && used != AccelKind::Bounds {
            notes.push(format!(
                "--bounds applies to --accel bounds only; ignored with --accel {}",
                used.name()
            ));
        }
        if self.grid.is_some() && used != AccelKind::Grid {
            notes.push(format!("--grid applies to --accel grid only; ignored with --accel {}", used.name()));
        }
        notes
    }
}

/// Applies `--size` to a scene's camera: the window stays, the pixel count changes. A 3D image
/// given only W keeps its aspect, `H = max(1, round(W·Ny/Nx))`; a 2D strip takes W as its pixels
/// and returns H, the strip's rows, for the renderer.
pub fn resize<V: Dim>(scene: &mut Scene<V>, size: Option<(usize, Option<usize>)>) -> Option<usize> {
    let (w, h) = size?;
    let cam = &mut scene.camera;
    if V::DIM == 2 {
        cam.nx = w;
        return h;
    }
    let h = h.unwrap_or_else(|| {
        let scaled = (w * cam.ny + cam.nx / 2) / cam.nx;
        scaled.max(1)
    });
    cam.nx = w;
    cam.ny = h;
    None
}

/// A figure's canvas for `--size` (1920×1080 without it; W alone keeps 16:9), at most
/// [`MAX_CANVAS_PIXELS`].
///
/// # Errors
/// Bad input naming `--size` when the canvas is larger.
pub fn canvas(size: Option<(usize, Option<usize>)>) -> Result<(u32, u32), Failure> {
    let Some((w, h)) = size else { return Ok((REFERENCE_WIDTH, REFERENCE_HEIGHT)) };
    let h = h.unwrap_or(((w * 9 + 8) / 16).max(1));
    if w as u64 * h as u64 > MAX_CANVAS_PIXELS {
        return Err(Failure::input(format!(
            "--size: a {w}x{h} canvas is more than the {MAX_CANVAS_PIXELS} pixels a figure may have; choose a \
             smaller --size"
        )));
    }
    // parse::size caps both at 65536.
    Ok((u32::try_from(w).unwrap_or(u32::MAX), u32::try_from(h).unwrap_or(u32::MAX)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ignored_options_are_noted_and_adaptive_is_checked() {
        let given = SamplingOptions { aa: None, threshold: Some(0.2), max_level: Some(3) };
        let chosen = given.choose(Aa::Center).unwrap();
        assert_eq!(chosen.sampling, Sampling::Center);
        assert_eq!(
            chosen.notes,
            [
                "--threshold applies to --aa adaptive only; ignored with --aa center",
                "--max-level applies to --aa adaptive only; ignored with --aa center"
            ]
        );
        let adaptive = given.choose(Aa::Adaptive).unwrap();
        assert_eq!(adaptive.sampling, Sampling::Adaptive { threshold: 0.2, max_level: 3 });
        assert!(adaptive.notes.is_empty());
        let bad = SamplingOptions { aa: Some(Aa::Adaptive), threshold: None, max_level: Some(9) };
        assert!(bad.choose(Aa::Center).unwrap_err().message.starts_with("--max-level"));
    }

    #[test]
    fn a_grid_must_match_the_dimension() {
        let choice = AccelChoice { kind: AccelKind::Grid, grid: Some(vec![2, 2]), ..AccelChoice::default() };
        assert!(choice.options(2).is_ok());
        assert_eq!(choice.options(3).unwrap_err().message, "--grid: a 3D scene needs 3 cell counts, got 2");
        assert!(choice.notes(AccelKind::Grid).is_empty());
        assert_eq!(
            choice.notes(AccelKind::Bvh),
            ["--grid applies to --accel grid only; ignored with --accel bvh"]
        );
    }

    #[test]
    fn canvases() {
        assert_eq!(canvas(None), Ok((1920, 1080)));
        assert_eq!(canvas(Some((640, None))), Ok((640, 360)));
        assert_eq!(canvas(Some((64, Some(64)))), Ok((64, 64)));
        assert!(canvas(Some((65536, Some(65536)))).unwrap_err().message.starts_with("--size: a 65536x65536"));
    }
}
