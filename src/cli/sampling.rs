//! `--aa center|corners|adaptive`, `--threshold X`, `--max-level K` (product.md; algorithm.md §8),
//! shared by `render` and `trace`, turned into a validated `Sampling` once.

use super::{parse, Failure};
use clap::{Args, ValueEnum};
use whitted::sample::{Sampling, MAX_LEVEL};

/// The `--aa` modes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AaArg {
    /// One ray through each pixel centre (the lecture's one ray per pixel).
    Center,
    /// The 4 pixel corners, each shared with the neighbours: (Nx + 1)(Ny + 1) rays; a pixel is their mean.
    Corners,
    /// Whitted's adaptive subdivision: split a square while its 4 corners differ by ≥ --threshold,
    /// at most --max-level times; the pixel is the area-weighted mean of its leaf squares.
    Adaptive,
}

/// The anti-aliasing options.
#[derive(Args, Clone, Copy, Debug)]
pub struct SamplingArgs {
    /// Anti-aliasing (algorithm.md §8).
    #[arg(long = "aa", value_enum, default_value = "center")]
    aa: AaArg,
    /// adaptive: a square splits while max over R, G, B of (max − min of its corners) ≥ X, on
    /// linear unclamped colours; X ≥ 0, or `inf` (never split: the same as corners).
    #[arg(long, value_name = "X", value_parser = parse::threshold, default_value = "0.1", allow_hyphen_values = true)]
    threshold: f64,
    /// adaptive: at most K subdivisions, K ≤ 8 (0 is corners; K = 2 means up to 5×5 samples a pixel).
    #[arg(long = "max-level", value_name = "K", default_value = "2", allow_hyphen_values = true,
          value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_LEVEL)))]
    max_level: u32,
}

impl SamplingArgs {
    /// The validated mode.
    ///
    /// # Errors
    /// Bad input (exit 2) naming `--threshold` or `--max-level` (the parsers check them first).
    pub fn sampling(&self) -> Result<Sampling, Failure> {
        match self.aa {
            AaArg::Center => Ok(Sampling::Center),
            AaArg::Corners => Ok(Sampling::Corners),
            AaArg::Adaptive => {
                Sampling::adaptive(self.threshold, self.max_level).map_err(|e| Failure::input(e.to_string()))
            }
        }
    }
}
