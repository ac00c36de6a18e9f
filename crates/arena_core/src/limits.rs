//! Budgets and plausible ranges checked at the door, before anything is allocated: the
//! pixel budget of a raster (from its header, before decoding), the resolution, extent
//! and origin of a map, and counts derived from a length and a spacing. Every refusal
//! is an [`ArenaError`] naming the field and the allowed range.

use crate::error::{ArenaError, Result};

/// Default pixel budget of one raster (width × height). At ~31 MB per MP for a build
/// (BENCHMARKS.md) this keeps the peak near 6 GB; raise it with [`MAX_PIXELS_ENV`].
pub const DEFAULT_MAX_PIXELS: u64 = 200_000_000;
/// Environment variable overriding [`DEFAULT_MAX_PIXELS`] (a positive integer).
pub const MAX_PIXELS_ENV: &str = "ROBORACER_ARENA_MAX_PIXELS";
/// Allowed map resolution (m per cell), inclusive. 1 mm to 1 m covers indoor SLAM maps
/// (typically 0.025–0.1) and coarse outdoor ones.
pub const RESOLUTION_RANGE_M: (f64, f64) = (1e-3, 1.0);
/// Resolution range (m per cell) the raster validator measures at (wider than
/// [`RESOLUTION_RANGE_M`], which bounds the maps read from disk): beyond it the
/// arithmetic of the measurement loses meaning. The constructor builds at no finer
/// resolution than its lower end. Here, below both, so neither depends on the other.
pub const VALIDATOR_RESOLUTION_RANGE_M: (f64, f64) = (1e-4, 10.0);
/// Largest side of a map in metres (cells × resolution): bounds every mesh and sample
/// count derived from metres, whatever the resolution.
pub const MAX_EXTENT_M: f64 = 5_000.0;
/// Largest |x| and |y| of a map origin (m): beyond it float32 stage coordinates lose
/// centimetre precision.
pub const MAX_ORIGIN_M: f64 = 100_000.0;
/// Largest |yaw| of a map origin (rad).
pub const MAX_YAW_RAD: f64 = 2.0 * std::f64::consts::PI + 1e-9;
/// Most samples, vertices or rings one derived count may reach.
pub const MAX_DERIVED_COUNT: f64 = 5_000_000.0;

/// A number for an error message: short scientific notation when it is huge or tiny
/// (`1e300`, not three hundred digits).
pub fn show(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-3..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The pixel budget in force: [`MAX_PIXELS_ENV`] if set, else [`DEFAULT_MAX_PIXELS`].
pub fn max_pixels() -> Result<u64> {
    match std::env::var(MAX_PIXELS_ENV) {
        Err(_) => Ok(DEFAULT_MAX_PIXELS),
        Ok(s) => s
            .trim()
            .parse::<u64>()
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| {
                ArenaError::invalid(format!(
                    "{MAX_PIXELS_ENV} must be a positive whole number of pixels, got {s:?}"
                ))
            }),
    }
}

/// Refuse a `width` × `height` raster above the pixel budget (overflow-safe).
pub fn check_cells(width: usize, height: usize, what: &str) -> Result<()> {
    let budget = max_pixels()?;
    let n = (width as u128) * (height as u128);
    if n > budget as u128 {
        return Err(ArenaError::invalid(format!(
            "{what} is {width}×{height} = {n} pixels, over the pixel budget of {budget} \
             (set {MAX_PIXELS_ENV} to raise it)"
        )));
    }
    Ok(())
}

/// Refuse a resolution outside [`RESOLUTION_RANGE_M`] (NaN and ±inf included).
pub fn check_resolution(resolution: f64) -> Result<()> {
    let (lo, hi) = RESOLUTION_RANGE_M;
    if !(lo..=hi).contains(&resolution) {
        return Err(ArenaError::invalid(format!(
            "resolution must be in [{lo}, {hi}] m per cell, got {}",
            show(resolution)
        )));
    }
    Ok(())
}

/// Refuse an origin that is not finite or beyond [`MAX_ORIGIN_M`] / [`MAX_YAW_RAD`].
pub fn check_origin(origin: [f64; 3]) -> Result<()> {
    let [x, y, yaw] = origin;
    let span = -MAX_ORIGIN_M..=MAX_ORIGIN_M;
    if !(span.contains(&x) && span.contains(&y)) {
        return Err(ArenaError::invalid(format!(
            "origin x and y must be in [-{MAX_ORIGIN_M}, {MAX_ORIGIN_M}] m, got [{}, {}]",
            show(x),
            show(y)
        )));
    }
    if !(-MAX_YAW_RAD..=MAX_YAW_RAD).contains(&yaw) {
        return Err(ArenaError::invalid(format!(
            "origin yaw must be in [-2π, 2π] rad, got {}",
            show(yaw)
        )));
    }
    Ok(())
}

/// Every check a map header (size, resolution, origin) must pass before its cells are
/// read: non-empty, within the pixel budget, resolution and origin in range, and no side
/// longer than [`MAX_EXTENT_M`].
pub fn check_grid_header(
    width: usize,
    height: usize,
    resolution: f64,
    origin: [f64; 3],
) -> Result<()> {
    if width == 0 || height == 0 {
        return Err(ArenaError::invalid(format!(
            "map is {width}×{height} cells: it must have at least one cell"
        )));
    }
    check_cells(width, height, "map")?;
    check_resolution(resolution)?;
    check_origin(origin)?;
    let side = width.max(height) as f64 * resolution;
    if side > MAX_EXTENT_M {
        let most = MAX_EXTENT_M / width.max(height) as f64;
        return Err(ArenaError::invalid(format!(
            "map would span {side:.0} m ({}×{} cells at {resolution} m): at most \
             {MAX_EXTENT_M} m per side, so resolution must be ≤ {most:.3e} for this image",
            width, height
        )));
    }
    Ok(())
}

/// Refuse a value outside `[lo, hi]` (NaN included), naming `field`.
pub fn check_range(field: &str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<()> {
    if !(lo..=hi).contains(&value) {
        return Err(ArenaError::invalid(format!(
            "{field} must be in [{lo}, {hi}]{unit}, got {}",
            show(value)
        )));
    }
    Ok(())
}

/// The count `length_m / spacing_m` (rounded up), refused when it would exceed
/// [`MAX_DERIVED_COUNT`]; the message names `field` and the smallest allowed spacing.
pub fn derived_count(field: &str, length_m: f64, spacing_m: f64) -> Result<usize> {
    derived_count_each(field, length_m, spacing_m, 1)
}

/// [`derived_count`] for items of `each` elements (e.g. vertices per ring): the total
/// `count × each` is what must stay within [`MAX_DERIVED_COUNT`].
pub fn derived_count_each(
    field: &str,
    length_m: f64,
    spacing_m: f64,
    each: usize,
) -> Result<usize> {
    let n = (length_m / spacing_m).ceil();
    let total = n * each.max(1) as f64;
    if !(total.is_finite() && total <= MAX_DERIVED_COUNT) {
        let min = length_m * each.max(1) as f64 / MAX_DERIVED_COUNT;
        return Err(ArenaError::invalid(format!(
            "{field} = {} m would need {total:.3e} samples over {length_m:.1} m; \
             it must be ≥ {min:.3e} m for this map",
            show(spacing_m)
        )));
    }
    Ok(n.max(0.0) as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_checks_refuse_bombs_and_nonsense() {
        assert!(check_grid_header(100, 100, 0.05, [0.0, 0.0, 0.0]).is_ok());
        // 150000² overflows no integer here and is refused by the budget.
        let e = check_grid_header(150_000, 150_000, 0.05, [0.0; 3]).unwrap_err();
        assert!(e.to_string().contains("pixel budget"), "{e}");
        assert!(check_cells(usize::MAX, usize::MAX, "x").is_err());
        for r in [
            f64::NAN,
            f64::INFINITY,
            1e300,
            1e-300,
            1e6,
            1000.0,
            0.0,
            -0.05,
        ] {
            let e = check_grid_header(10, 10, r, [0.0; 3]).unwrap_err();
            assert!(e.to_string().contains("resolution"), "{r}: {e}");
        }
        for o in [
            [1e300, -1e300, 0.0],
            [f64::NAN, 0.0, 0.0],
            [0.0, 0.0, f64::INFINITY],
        ] {
            assert!(check_grid_header(10, 10, 0.05, o).is_err(), "{o:?}");
        }
        // 1 m per cell is fine for a small map, not for one 10 km wide.
        assert!(check_grid_header(100, 100, 1.0, [0.0; 3]).is_ok());
        assert!(check_grid_header(10_000, 100, 1.0, [0.0; 3]).is_err());
        assert!(check_grid_header(0, 10, 0.05, [0.0; 3]).is_err());
    }

    #[test]
    fn derived_counts_are_bounded() {
        assert_eq!(derived_count("s", 10.0, 0.1).unwrap(), 100);
        let e = derived_count("geometry.centreline_spacing_m", 100.0, 1e-7).unwrap_err();
        assert!(e.to_string().contains("centreline_spacing_m"), "{e}");
        assert!(derived_count("s", 10.0, 0.0).is_err());
        assert!(derived_count("s", f64::NAN, 0.1).is_err());
    }
}
