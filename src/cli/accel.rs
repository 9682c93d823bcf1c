//! The acceleration options shared by `render`, `trace` and `figure`: `--accel`, `--bounds`,
//! `--grid` (algorithm.md §9), turned into `request::options::AccelChoice` (checked there).

use clap::{Args, ValueEnum};
use whitted::accel::AccelKind;
use whitted::bounds::VolumeKind;
use whitted::request::options::AccelChoice;
use whitted::request::parse;

/// Which structure finds hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
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
    pub accel: AccelArg,
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
    /// The choice for a command that traces with `--accel`'s structure.
    pub fn choice(&self) -> AccelChoice {
        self.choice_for(self.accel)
    }

    /// The choice, for `request::options::AccelChoice::options`, of a command that traces with
    /// `used` whatever `--accel` says (a figure of a structure). As `--threshold` without adaptive
    /// sampling, `--bounds` and `--grid` are said ignored on stderr unless `used` reads them.
    pub fn choice_for(&self, used: AccelArg) -> AccelChoice {
        let name = used.to_possible_value().map(|v| v.get_name().to_owned()).unwrap_or_default();
        if self.bounds.is_some() && used != AccelArg::Bounds {
            eprintln!("whitted: --bounds applies to --accel bounds only; ignored with --accel {name}");
        }
        if self.grid.is_some() && used != AccelArg::Grid {
            eprintln!("whitted: --grid applies to --accel grid only; ignored with --accel {name}");
        }
        let kind = match self.accel {
            AccelArg::None => AccelKind::None,
            AccelArg::Bounds => AccelKind::Bounds,
            AccelArg::Bvh => AccelKind::Bvh,
            AccelArg::Grid => AccelKind::Grid,
            AccelArg::Octree => AccelKind::Octree,
        };
        let volume = match self.bounds.unwrap_or(BoundsArg::Aabb) {
            BoundsArg::Sphere => VolumeKind::Sphere,
            BoundsArg::Aabb => VolumeKind::Aabb,
            BoundsArg::Kdop => VolumeKind::Kdop,
        };
        AccelChoice { kind, volume, grid: self.grid.clone().map(|Cells(g)| g) }
    }
}
