//! The raster budget of a generation: the size a spec's hall may reach, checked before any
//! loop bound or allocation is derived from it.

use super::spec::{ConstructorConfig, Spec};
use crate::error::{ArenaError, Result};

/// Largest raster (cells) a generated map may need: hall area / Δ². 4·10⁷ cells at the
/// default Δ = 0.05 m is a 316 m × 316 m hall; the validator's distance transform and
/// labels take ~15 bytes per cell, so this keeps one candidate under ~0.6 GB.
pub const MAX_RASTER_CELLS: f64 = 4.0e7;

/// Refuse specs whose raster or loop bounds the generator cannot hold, before any
/// allocation or loop: the hall's raster must stay within [`MAX_RASTER_CELLS`].
pub fn check_raster_budget(spec: &Spec, cfg: &ConstructorConfig) -> Result<()> {
    let pad = 2.0 * (cfg.map_margin_m + cfg.wall_thickness_m) + spec.corridor_width_m;
    let cells =
        ((spec.hall_x_m + pad) / cfg.resolution_m) * ((spec.hall_y_m + pad) / cfg.resolution_m);
    if !(cells.is_finite() && cells <= MAX_RASTER_CELLS) {
        let side = MAX_RASTER_CELLS.sqrt() * cfg.resolution_m;
        return Err(ArenaError::Spec(format!(
            "hall_x_m × hall_y_m: a {}×{} m hall needs {cells:.3e} raster cells at {} m; \
             the generator allows at most {MAX_RASTER_CELLS:.0e} (about {side:.0}×{side:.0} m)",
            spec.hall_x_m, spec.hall_y_m, cfg.resolution_m
        )));
    }
    Ok(())
}
