//! `--aa center|corners|adaptive`, `--threshold X`, `--max-level K` (product.md; algorithm.md §8),
//! shared by `render` and `trace`, turned into a validated `Sampling` once.

use super::{parse, Failure};
use clap::{Args, ValueEnum};
use whitted::sample::{Sampling, DEFAULT_MAX_LEVEL, DEFAULT_THRESHOLD, MAX_LEVEL};

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
        self.sampling_or(AaArg::Center)
    }
    /// The validated mode, `default` when `--aa` is not given. A `--threshold` or `--max-level`
    /// that the mode does not use is said on stderr (the run goes on).
    ///
    /// # Errors
    /// As [`SamplingArgs::sampling`].
    pub fn sampling_or(&self, default: AaArg) -> Result<Sampling, Failure> {
        let aa = self.aa.unwrap_or(default);
        if aa != AaArg::Adaptive {
            let mode = aa.to_possible_value().map(|v| v.get_name().to_owned()).unwrap_or_default();
            for (given, flag) in
                [(self.threshold.is_some(), "--threshold"), (self.max_level.is_some(), "--max-level")]
            {
                if given {
                    eprintln!("whitted: {flag} applies to --aa adaptive only; ignored with --aa {mode}");
                }
            }
        }
        match aa {
            AaArg::Center => Ok(Sampling::Center),
            AaArg::Corners => Ok(Sampling::Corners),
            AaArg::Adaptive => Sampling::adaptive(
                self.threshold.unwrap_or(DEFAULT_THRESHOLD),
                self.max_level.unwrap_or(DEFAULT_MAX_LEVEL),
            )
            .map_err(|e| Failure::input(e.to_string())),
        }
    }
}
