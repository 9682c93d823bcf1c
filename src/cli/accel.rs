//! The acceleration options shared by `render` and `trace`: `--accel`, `--bounds`, `--grid`
//! (algorithm.md §9), turned once into `accel::AccelOptions`.

use clap::{Args, ValueEnum};
use whitted::accel::{AccelKind, AccelOptions};
use whitted::bounds::VolumeKind;

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

impl AccelArgs {
    /// The options, checked against the scene's dimension.
    ///
    /// # Errors
    /// A message when `--grid` has the wrong number of axes.
    pub fn options(&self, dim: usize) -> Result<AccelOptions, String> {
        self.options_for(dim, self.accel)
    }

    /// [`Self::options`] for a command that traces with `used` whatever `--accel` says (a figure of
    /// a structure): `--bounds` and `--grid` are said ignored unless `used` reads them.
    ///
    /// # Errors
    /// A message when `--grid` has the wrong number of axes.
    pub fn options_for(&self, dim: usize, used: AccelArg) -> Result<AccelOptions, String> {
        if let Some(Cells(g)) = &self.grid {
            if g.len() != dim {
                return Err(format!("--grid: a {dim}D scene needs {dim} cell counts, got {}", g.len()));
            }
        }
        // As `--threshold` without adaptive sampling: an option the structure does not read is said.
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
        Ok(AccelOptions { kind, volume, grid: self.grid.clone().map(|Cells(g)| g) })
    }
}

/// Parses `NX,NY[,NZ]`: each at least 1, at most 2^24 cells in all.
fn cells(s: &str) -> Result<Cells, String> {
    let n: Vec<usize> = s
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
    if total.is_none_or(|t| t > whitted::accel::grid::MAX_CELLS) {
        return Err(format!("at most {} cells in all", whitted::accel::grid::MAX_CELLS));
    }
    Ok(Cells(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_cells_parse() {
        assert_eq!(cells("4,4,4"), Ok(Cells(vec![4, 4, 4])));
        assert_eq!(cells("8,2"), Ok(Cells(vec![8, 2])));
        assert!(cells("0,1,1").is_err());
        assert!(cells("4").is_err());
        assert!(cells("4096,4096,4096").is_err());
    }
}
