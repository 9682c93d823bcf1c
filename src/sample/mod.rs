//! Pixel → rays → colour (algorithm.md §8, "Better images: more primary rays"): the sampling
//! modes ([`Sampling`]: one ray through the centre, the 4 shared corners, Whitted's adaptive
//! subdivision), and one pixel's samples traced with the `EventLog` for `whitted trace --aa`.
//!
//! Every mode but the centre works on one integer lattice: with K = `max_level`, the point
//! `(x, y) = (i·2^K + a, j·2^K + b)` sits at `u = l + (r − l)·(x/2^K)/Nx`, `v = b + (t − b)·(y/2^K)/Ny`
//! (`corners`); a pixel's square is split while its corners differ (`adaptive`); `shared` keeps
//! every lattice sample traced once for the whole image, across threads.
//!
//! `Sampling::adaptive` validates the threshold and K (at most `MAX_LEVEL`). `trace_pixel` traces one pixel's
//! samples with the `EventLog` into a `PixelTrace` (`samples`, `squares`, `color`), its samples
//! labelled as the lecture does, `CA`, `CB`, ….

pub mod adaptive;
pub mod breadth;
pub mod corners;
pub mod shared;

use crate::record::event::Event;
use crate::record::{EventLog, Recorder};
use crate::scene::material::Rgb;
use crate::shape::Dim;
use crate::trace::Tracer;
use adaptive::{sample_level, subdivide, SampleSource, Square, SquareSink};
use corners::Lattice;
use std::collections::HashMap;
use std::fmt;

/// The largest `--max-level`: samples grow as 4^K (numerics.md H1), so K is capped at 8.
pub const MAX_LEVEL: u32 = 8;
/// `--threshold`'s default (product.md).
pub const DEFAULT_THRESHOLD: f64 = 0.1;
/// `--max-level`'s default (product.md).
pub const DEFAULT_MAX_LEVEL: u32 = 2;

/// How a pixel becomes rays (product.md `--aa`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sampling {
    /// One ray through the pixel centre (§2), the lecture's default.
    Center,
    /// The 4 pixel corners, shared with the neighbours (§8.1): `(Nx + 1)(Ny + 1)` rays.
    Corners,
    /// Whitted's adaptive subdivision (§8.2).
    Adaptive {
        /// A square splits while `max over channels of (max − min of its corners) ≥ threshold`.
        threshold: f64,
        /// K: at most K subdivisions (level-K squares are never split).
        max_level: u32,
    },
}

/// Why a sampling mode was refused (numerics.md H1).
#[derive(Clone, Debug, PartialEq)]
pub enum SamplingError {
    /// The threshold is NaN or negative.
    Threshold(f64),
    /// The level is above [`MAX_LEVEL`].
    MaxLevel(u32),
}

impl fmt::Display for SamplingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Threshold(x) => write!(f, "--threshold: must be a number ≥ 0 or inf, got {x}"),
            Self::MaxLevel(k) => write!(f, "--max-level: must be at most {MAX_LEVEL}, got {k}"),
        }
    }
}

impl std::error::Error for SamplingError {}

impl Sampling {
    /// The adaptive mode, validated: the threshold is finite or `+∞` and `≥ 0` (a NaN would never
    /// split, a negative one always: numerics.md H1), and `max_level ≤ 8`. Threshold 0 is valid
    /// (everything splits down to level K); `+∞` never splits (= `Corners`).
    ///
    /// # Errors
    /// [`SamplingError`] naming the option.
    pub fn adaptive(threshold: f64, max_level: u32) -> Result<Self, SamplingError> {
        if !(threshold >= 0.0) {
            return Err(SamplingError::Threshold(threshold));
        }
        if max_level > MAX_LEVEL {
            return Err(SamplingError::MaxLevel(max_level));
        }
        Ok(Self::Adaptive { threshold, max_level })
    }
    /// The name on the command line: `center`, `corners`, `adaptive`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Center => "center",
            Self::Corners => "corners",
            Self::Adaptive { .. } => "adaptive",
        }
    }
    /// The lattice rule `(threshold, K)` of a mode that samples corners; `Corners` is the adaptive
    /// rule with `K = 0` (§8: "K = 0 is the 4-corner method"). None for `Center`.
    #[must_use]
    pub fn rule(self) -> Option<(f64, u32)> {
        match self {
            Self::Center => None,
            Self::Corners => Some((f64::INFINITY, 0)),
            Self::Adaptive { threshold, max_level } => Some((threshold, max_level)),
        }
    }
}

/// One sample of a traced pixel (product.md `samples`).
#[derive(Clone, Debug, PartialEq)]
pub struct SampleRecord {
    /// The lecture's label, in the order traced: `CA`, `CB`, … `CZ`, `CAA`, …
    pub label: String,
    /// Global lattice coordinates `[x, y]` = `[i·2^K + a, j·2^K + b]` (`[x]` in 2D).
    pub lattice: Vec<u64>,
    /// `[u, v]` (`[u]` in 2D).
    pub uv: Vec<f64>,
    /// The level at which the point first appears: 0 for the pixel's corners, k for the new corners
    /// of the k-th subdivision.
    pub level: u32,
    /// The traced colour (linear, unclamped).
    pub color: Rgb,
    /// True iff another square of this pixel read the sample after it was traced (it was shared
    /// inside the pixel, not traced again).
    pub reused: bool,
    /// The index of its primary ray node in the log.
    pub root: usize,
}

/// One square (a pixel's interval in 2D) of a traced pixel's subdivision, in pre-order.
#[derive(Clone, Debug, PartialEq)]
pub struct SquareRecord {
    /// 0 for the pixel itself; a level-k square is a quarter (2D: half) of a level k−1 one.
    pub level: u32,
    /// Global lattice coordinates of its lower-left corner (`[x]` in 2D).
    pub lattice: Vec<u64>,
    /// Its side in lattice units, `2^(K − level)`.
    pub side: u64,
    /// Its corner samples (indices into the samples): lower-left, lower-right, upper-left,
    /// upper-right (2D: left, right).
    pub corners: Vec<usize>,
    /// `max over channels of (max − min)` of the corners.
    pub spread: f64,
    /// Whether it was split into 4 (2D: 2).
    pub split: bool,
    /// A leaf's colour is the mean of its corners; a split square's the mean of its children.
    pub color: Rgb,
}

/// One pixel's samples, squares and colour, traced with the `EventLog`.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelTrace {
    /// The lecture's uniform supersampling (`Corners`: the 4 corners, no rule to split), as
    /// opposed to adaptive subdivision, whatever its threshold.
    pub uniform: bool,
    /// The threshold used.
    pub threshold: f64,
    /// K.
    pub max_level: u32,
    /// Every sample, in the order traced.
    pub samples: Vec<SampleRecord>,
    /// Every square, in pre-order (children lower-left, lower-right, upper-left, upper-right).
    pub squares: Vec<SquareRecord>,
    /// The pixel: the area-weighted mean of its leaves.
    pub color: Rgb,
}

/// The lecture's sample names in the order traced: `CA` … `CZ`, then `CAA`, `CAB`, …
/// (the letters count in bijective base 26).
#[must_use]
pub fn label(index: usize) -> String {
    let mut letters = Vec::new();
    let mut n = index + 1;
    while n > 0 {
        n -= 1;
        // n % 26 < 26, so the cast is exact.
        #[allow(clippy::cast_possible_truncation)]
        letters.push(char::from(b'A' + (n % 26) as u8));
        n /= 26;
    }
    letters.reverse();
    format!("C{}", letters.into_iter().collect::<String>())
}

/// Traces pixel `(i, j)` (`j = 0` in 2D) with the sampling mode `sampling` (not `Center`),
/// recording into the tracer's `EventLog`: each sample's events carry its index (`current_sample`),
/// and every time a square reads a corner a `sample` event is recorded (`reused` = the sample was
/// already traced for another square of this pixel). Corners shared with neighbouring pixels are
/// traced here too: the pixel is traced alone.
///
/// # Panics
/// If `sampling` is `Center` (the caller traces the centre ray itself).
pub fn trace_pixel<V: Dim>(
    tracer: &mut Tracer<'_, V, EventLog<V>>,
    sampling: Sampling,
    i: usize,
    j: usize,
) -> PixelTrace {
    let (threshold, max_level) = sampling.rule().expect("trace_pixel samples corners, not the centre");
    let lattice = Lattice::new(&tracer.scene.camera, max_level);
    let mut source = LoggedSource { tracer, lattice, i, j, seen: HashMap::new(), samples: Vec::new() };
    let mut sink = Recorded { squares: Vec::new(), local_corners: Vec::new(), lattice, i, j };
    let color = subdivide(&mut source, &mut sink, lattice.dims(), threshold, max_level);
    source.tracer.recorder.current_sample = None;
    for (square, corners) in sink.squares.iter_mut().zip(&sink.local_corners) {
        square.corners = corners.iter().map(|p| source.seen[p]).collect();
    }
    let uniform = sampling == Sampling::Corners;
    PixelTrace { uniform, threshold, max_level, samples: source.samples, squares: sink.squares, color }
}

/// The samples of one traced pixel: traced on first use, remembered by local lattice point.
struct LoggedSource<'t, 's, V: Dim> {
    tracer: &'t mut Tracer<'s, V, EventLog<V>>,
    lattice: Lattice,
    i: usize,
    j: usize,
    seen: HashMap<(u32, u32), usize>,
    samples: Vec<SampleRecord>,
}

impl<V: Dim> SampleSource for LoggedSource<'_, '_, V> {
    fn color(&mut self, a: u32, b: u32) -> Rgb {
        if let Some(&k) = self.seen.get(&(a, b)) {
            let color = self.samples[k].color;
            self.reuse(a, b, color);
            return color;
        }
        let k = self.samples.len();
        let (x, y) = self.lattice.global(self.i, self.j, a, b);
        let (u, v) = self.lattice.uv(&self.tracer.scene.camera, x, y);
        let dims = self.lattice.dims();
        let uv = if dims == 1 { vec![u] } else { vec![u, v] };
        let lattice = if dims == 1 { vec![x] } else { vec![x, y] };
        self.tracer.recorder.current_sample = Some(k);
        let root = self.tracer.recorder.nodes.len();
        let ray = self.tracer.scene.camera.primary_ray(u, v);
        let color = self.tracer.trace_primary(&ray, &uv);
        let level = sample_level(a, b, self.lattice.max_level);
        self.samples.push(SampleRecord {
            label: label(k),
            lattice,
            uv: uv.clone(),
            level,
            color,
            reused: false,
            root,
        });
        self.seen.insert((a, b), k);
        self.tracer.recorder.event(|| Event::Sample { uv, level, color, reused: false });
        color
    }
    fn reuse(&mut self, a: u32, b: u32, color: Rgb) {
        let k = self.seen[&(a, b)];
        let s = &mut self.samples[k];
        s.reused = true;
        let (uv, level) = (s.uv.clone(), s.level);
        self.tracer.recorder.current_sample = Some(k);
        self.tracer.recorder.event(|| Event::Sample { uv, level, color, reused: true });
    }
}

/// Keeps every square the subdivision visits, with its local corners `(a, b)`, whose sample
/// indices [`trace_pixel`] looks up once the subdivision is done.
struct Recorded {
    squares: Vec<SquareRecord>,
    local_corners: Vec<Vec<(u32, u32)>>,
    lattice: Lattice,
    i: usize,
    j: usize,
}

impl SquareSink for Recorded {
    const RECORDS: bool = true;
    fn open(&mut self, square: &Square) -> usize {
        let (x, y) = self.lattice.global(self.i, self.j, square.a, square.b);
        let (a, b, side) = (square.a, square.b, square.side);
        self.local_corners.push(if self.lattice.dims() == 1 {
            vec![(a, 0), (a + side, 0)]
        } else {
            vec![(a, b), (a + side, b), (a, b + side), (a + side, b + side)]
        });
        self.squares.push(SquareRecord {
            level: square.level,
            lattice: if self.lattice.dims() == 1 { vec![x] } else { vec![x, y] },
            side: u64::from(square.side),
            corners: Vec::new(),
            spread: square.spread,
            split: square.split,
            color: Rgb::BLACK,
        });
        self.squares.len() - 1
    }
    fn close(&mut self, index: usize, color: Rgb) {
        self.squares[index].color = color;
    }
}
