//! The acceleration options shared by `render` and `trace`: `--accel`, `--bounds`, `--grid`
//! (algorithm.md §9), turned once into `accel::AccelOptions`.

use clap::{Args, ValueEnum};
use whitted::accel::{AccelKind, AccelOptions};
use whitted::bounds::VolumeKind;

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
    /// The per-object bounding volume of --accel bounds.
    #[arg(long, value_enum, default_value = "aabb")]
    bounds: BoundsArg,
    /// The grid's cells per axis, NX,NY,NZ (NX,NY in 2D), for --accel grid (default: about 4
    /// cells per object).
    // Spelled `::std::vec::Vec` so that clap's derive takes the parser's whole `Vec` as the one
    // value (a bare `Vec` makes it expect many `usize`s and panic when the option is given).
    #[arg(long, value_parser = cells)]
    grid: Option<::std::vec::Vec<usize>>,
}

impl AccelArgs {
    /// The options, checked against the scene's dimension.
    ///
    /// # Errors
    /// A message when `--grid` has the wrong number of axes.
    pub fn options(&self, dim: usize) -> Result<AccelOptions, String> {
        if let Some(g) = &self.grid {
            if g.len() != dim {
                return Err(format!("--grid: a {dim}D scene needs {dim} cell counts, got {}", g.len()));
            }
        }
        let kind = match self.accel {
            AccelArg::None => AccelKind::None,
            AccelArg::Bounds => AccelKind::Bounds,
            AccelArg::Bvh => AccelKind::Bvh,
            AccelArg::Grid => AccelKind::Grid,
            AccelArg::Octree => AccelKind::Octree,
        };
        let volume = match self.bounds {
            BoundsArg::Sphere => VolumeKind::Sphere,
            BoundsArg::Aabb => VolumeKind::Aabb,
            BoundsArg::Kdop => VolumeKind::Kdop,
        };
        Ok(AccelOptions { kind, volume, grid: self.grid.clone() })
    }
}

/// Parses `NX,NY[,NZ]`: each at least 1, at most 2^24 cells in all.
fn cells(s: &str) -> Result<Vec<usize>, String> {
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
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_cells_parse() {
        assert_eq!(cells("4,4,4"), Ok(vec![4, 4, 4]));
        assert_eq!(cells("8,2"), Ok(vec![8, 2]));
        assert!(cells("0,1,1").is_err());
        assert!(cells("4").is_err());
        assert!(cells("4096,4096,4096").is_err());
    }
}
