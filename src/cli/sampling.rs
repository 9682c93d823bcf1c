//! `--aa center|corners|adaptive`, `--threshold X`, `--max-level K` (product.md; algorithm.md §8),
//! shared by `render`, `trace` and `figure`, turned into a validated `Sampling` once.

use super::{print_notes, Failure};
use clap::{Args, ValueEnum};
use whitted::request::options::{Aa, SamplingOptions};
use whitted::request::parse;
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

/// The anti-aliasing options. Each is optional so that a command knows which were given: a
/// threshold or level given to a mode other than adaptive is reported as ignored, and
/// `figure adaptive|heat-map` default to adaptive sampling with the given ones.
#[derive(Args, Clone, Copy, Debug)]
pub struct SamplingArgs {
    /// Anti-aliasing (algorithm.md §8) [default: center; for `figure adaptive` and `figure
    /// heat-map`: adaptive].
    #[arg(long = "aa", value_enum)]
    aa: Option<AaArg>,
    /// adaptive: a square splits while max over R, G, B of (max − min of its corners) ≥ X, on
    /// linear unclamped colours; X ≥ 0, or `inf` (never split: the same as corners) [default: 0.1].
    #[arg(long, value_name = "X", value_parser = parse::threshold, allow_hyphen_values = true)]
    threshold: Option<f64>,
    /// adaptive: at most K subdivisions, K ≤ 8 (0 is corners; K = 2 means up to 5×5 samples a
    /// pixel) [default: 2].
    #[arg(long = "max-level", value_name = "K", allow_hyphen_values = true,
          value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_LEVEL)))]
    max_level: Option<u32>,
}

impl SamplingArgs {
    /// The validated mode, centre sampling when `--aa` is not given.
    ///
    /// # Errors
    /// Bad input (exit 2) naming `--threshold` or `--max-level` (the parsers check them first).
    pub fn sampling(&self) -> Result<Sampling, Failure> {
        self.sampling_or(Aa::Center)
    }
    /// The validated mode, `default` when `--aa` is not given. A `--threshold` or `--max-level`
    /// that the mode does not use is said on stderr (the run goes on).
    ///
    /// # Errors
    /// As [`SamplingArgs::sampling`].
    pub fn sampling_or(&self, default: Aa) -> Result<Sampling, Failure> {
        let aa = self.aa.map(|a| match a {
            AaArg::Center => Aa::Center,
            AaArg::Corners => Aa::Corners,
            AaArg::Adaptive => Aa::Adaptive,
        });
        let given = SamplingOptions { aa, threshold: self.threshold, max_level: self.max_level };
        let chosen = given.choose(default)?;
        print_notes(&chosen.notes);
        Ok(chosen.sampling)
    }
}
