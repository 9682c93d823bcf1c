//! The acceleration options shared by `render`, `trace` and `figure`: `--accel`, `--bounds`,
//! `--grid` (algorithm.md §9), turned into `request::options::AccelChoice` (checked there).

use super::{print_notes, Failure};
use clap::{Args, ValueEnum};
use whitted::accel::{AccelKind, AccelOptions};
use whitted::bounds::VolumeKind;
use whitted::request::options::AccelChoice;
use whitted::request::parse;

/// Which structure finds hits.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum AccelArg {
    /// Brute force: every object (§7, O(n) per ray).
    None,
    /// A bounding volume per object, tested first (--bounds).
    Bounds,
    /// A bounding volume hierarchy (binned SAH).
    Bvh,
    /// A regular grid walked by the 3D DDA (--grid to choose its cells).
    Grid,
    /// An octree (a quadtree in 2D).
    Octree,
}

/// The bounding volume of `--accel bounds`.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum BoundsArg {
    /// A bounding sphere (circle).
    Sphere,
    /// An axis-aligned box (the slab test).
    Aabb,
    /// Kay–Kajiya slabs: 4 pairs in 2D, 7 in 3D.
    Kdop,
}

/// `--accel`, `--bounds`, `--grid`.
#[derive(Args, Debug, Clone)]
pub struct AccelArgs {
    /// The acceleration structure.
    #[arg(long, value_enum, default_value = "bvh")]
    accel: AccelArg,
    /// The per-object bounding volume of --accel bounds [default: aabb].
    #[arg(long, value_enum)]
    bounds: Option<BoundsArg>,
    /// The grid's cells per axis, NX,NY,NZ (NX,NY in 2D), for --accel grid (default: about 4
    /// cells per object).
    #[arg(long, value_parser = cells, allow_hyphen_values = true)]
    grid: Option<Cells>,
}

/// The cells per axis of `--grid` (a newtype, so that clap takes it as one value).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cells(Vec<usize>);

/// `--grid`'s parser: `request::parse::grid`.
fn cells(s: &str) -> Result<Cells, String> {
    parse::grid(s).map(Cells)
}

impl AccelArgs {
    /// The choice, for `request::options::AccelChoice`.
    pub fn choice(&self) -> AccelChoice {
        let kind = match self.accel {
            AccelArg::None => AccelKind::None,
            AccelArg::Bounds => AccelKind::Bounds,
            AccelArg::Bvh => AccelKind::Bvh,
            AccelArg::Grid => AccelKind::Grid,
            AccelArg::Octree => AccelKind::Octree,
        };
        let volume = self.bounds.map(|b| match b {
            BoundsArg::Sphere => VolumeKind::Sphere,
            BoundsArg::Aabb => VolumeKind::Aabb,
            BoundsArg::Kdop => VolumeKind::Kdop,
        });
        AccelChoice { kind, volume, grid: self.grid.clone().map(|Cells(g)| g) }
    }

    /// The options, checked against the scene's dimension, for a command that traces with `used`
    /// (a figure of a structure uses its own): `--bounds` and `--grid` are said ignored on stderr
    /// unless `used` reads them.
    ///
    /// # Errors
    /// Bad input when `--grid` has the wrong number of axes.
    pub fn options_for(&self, dim: usize, used: AccelKind) -> Result<AccelOptions, Failure> {
        let choice = self.choice();
        let options = choice.options(dim)?;
        print_notes(&choice.notes(used));
        Ok(options)
    }
}
