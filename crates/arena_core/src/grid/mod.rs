//! ROS occupancy grids: the one interface between every track source and the builder.
//!
//! Storage follows the image file: row 0 is the *top* row, so `data[row * width + col]`.
//! The ROS map frame puts the origin at the lower-left pixel corner, x right, y up, and
//! rotates by the origin yaw; [`OccupancyGrid::cell_center`] does that conversion.

pub mod edt;
pub mod flood;
pub mod image;
pub mod mapfile;
pub mod pgm;
pub mod png_io;
pub mod rasterise;
pub mod regions;

/// Occupancy value of a free cell (ROS map_saver convention).
pub const FREE: u8 = 254;
/// Occupancy value of an occupied cell.
pub const OCCUPIED: u8 = 0;
/// Occupancy value of an unknown cell.
pub const UNKNOWN: u8 = 205;

/// A trinary occupancy grid in the ROS map frame.
#[derive(Debug, Clone, PartialEq)]
pub struct OccupancyGrid {
    pub width: usize,
    pub height: usize,
    /// Metres per cell.
    pub resolution: f64,
    /// Pose of the lower-left corner of the lower-left cell: x, y (m), yaw (rad).
    pub origin: [f64; 3],
    /// `FREE`, `OCCUPIED` or `UNKNOWN`, row-major, row 0 at the top.
    pub data: Vec<u8>,
}

impl OccupancyGrid {
    /// A grid filled with one value.
    pub fn filled(
        width: usize,
        height: usize,
        resolution: f64,
        origin: [f64; 3],
        value: u8,
    ) -> Self {
        OccupancyGrid {
            width,
            height,
            resolution,
            origin,
            data: vec![value; width * height],
        }
    }

    /// The door check of every function taking a grid from outside: size within the
    /// pixel budget, resolution, origin and extent in range (see [`crate::limits`]), and
    /// exactly `width × height` cells.
    pub fn check(&self) -> crate::Result<()> {
        crate::limits::check_grid_header(self.width, self.height, self.resolution, self.origin)?;
        if self.data.len() != self.width * self.height {
            return Err(crate::ArenaError::invalid(format!(
                "map holds {} cells for {}×{}",
                self.data.len(),
                self.width,
                self.height
            )));
        }
        Ok(())
    }

    #[inline]
    pub fn index(&self, col: usize, row: usize) -> usize {
        row * self.width + col
    }

    #[inline]
    pub fn get(&self, col: usize, row: usize) -> u8 {
        self.data[self.index(col, row)]
    }

    /// Number of cells in megapixels (the paper's "raster MP").
    pub fn megapixels(&self) -> f64 {
        (self.width * self.height) as f64 / 1e6
    }

    /// Map-frame coordinates (m) of a point given in cell units measured from the
    /// lower-left grid corner (u right, v up). Honours the origin yaw.
    #[inline]
    pub fn grid_to_world(&self, u: f64, v: f64) -> [f64; 2] {
        let (s, c) = self.origin[2].sin_cos();
        let (x, y) = (u * self.resolution, v * self.resolution);
        [
            self.origin[0] + c * x - s * y,
            self.origin[1] + s * x + c * y,
        ]
    }

    /// Inverse of [`grid_to_world`](Self::grid_to_world): map-frame metres → (u, v) cell units.
    #[inline]
    pub fn world_to_grid(&self, x: f64, y: f64) -> [f64; 2] {
        let (s, c) = self.origin[2].sin_cos();
        let (dx, dy) = (x - self.origin[0], y - self.origin[1]);
        [
            (c * dx + s * dy) / self.resolution,
            (-s * dx + c * dy) / self.resolution,
        ]
    }

    /// Map-frame centre of cell (col, row), row 0 being the top image row.
    #[inline]
    pub fn cell_center(&self, col: usize, row: usize) -> [f64; 2] {
        self.grid_to_world(col as f64 + 0.5, (self.height - 1 - row) as f64 + 0.5)
    }

    /// Cell containing a map-frame point, if inside the grid.
    pub fn world_to_cell(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        let [u, v] = self.world_to_grid(x, y);
        if u < 0.0 || v < 0.0 || u >= self.width as f64 || v >= self.height as f64 {
            return None;
        }
        let col = u as usize;
        let row = self.height - 1 - v as usize;
        Some((col, row))
    }

    /// Boolean mask of cells equal to `value`.
    pub fn mask_of(&self, value: u8) -> Vec<bool> {
        self.data.iter().map(|&d| d == value).collect()
    }
}

/// Value of a cell-centred field (row 0 at the top, like the grid) at grid point (u, v)
/// in cell units from the lower-left corner, bilinearly interpolated between cell
/// centres and clamped at the border.
pub fn bilinear(f: &[f32], w: usize, h: usize, u: f64, v: f64) -> f64 {
    bilinear_with(w, h, u, v, |i| f[i])
}

/// [`bilinear`] of a field given by its value at each cell index (row-major, row 0 at
/// the top), for fields cheaper to evaluate at four cells than to store whole.
pub fn bilinear_with(w: usize, h: usize, u: f64, v: f64, f: impl Fn(usize) -> f32) -> f64 {
    let x = (u - 0.5).clamp(0.0, (w - 1) as f64);
    let y = (v - 0.5).clamp(0.0, (h - 1) as f64);
    let (c0, v0) = (x.floor() as usize, y.floor() as usize);
    let (c1, v1) = ((c0 + 1).min(w - 1), (v0 + 1).min(h - 1));
    let (tx, ty) = (x - c0 as f64, y - v0 as f64);
    let at = |c: usize, vv: usize| f((h - 1 - vv) * w + c) as f64;
    let a = at(c0, v0) * (1.0 - tx) + at(c1, v0) * tx;
    let b = at(c0, v1) * (1.0 - tx) + at(c1, v1) * tx;
    a * (1.0 - ty) + b * ty
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_center_round_trips_with_yaw() {
        let g = OccupancyGrid::filled(10, 5, 0.1, [1.0, -2.0, 0.3], FREE);
        for (col, row) in [(0, 0), (9, 4), (3, 2)] {
            let [x, y] = g.cell_center(col, row);
            assert_eq!(g.world_to_cell(x, y), Some((col, row)));
        }
        assert_eq!(g.world_to_cell(-50.0, 0.0), None);
    }

    #[test]
    fn lower_left_cell_is_last_row() {
        let g = OccupancyGrid::filled(4, 3, 1.0, [0.0, 0.0, 0.0], FREE);
        assert_eq!(g.cell_center(0, 2), [0.5, 0.5]);
        assert_eq!(g.cell_center(3, 0), [3.5, 2.5]);
    }
}
