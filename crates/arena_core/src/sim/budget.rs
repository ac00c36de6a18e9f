//! The size budget of one simulator, checked before anything is allocated: a failed
//! allocation aborts the process (SIGABRT), which no caller can catch. This is the one
//! rule; the Python env checks its sizes with [`check_size`] too (through the binding),
//! adding its stacked observation frames.

use crate::error::{ArenaError, Result};

/// Most vehicles (envs × vehicles per env) one simulator holds: each env is a rapier
/// world of its own (about 80 kB with 1081 beams, README "Limits"), so at most ~1.3 GB.
pub const MAX_VEHICLES: u64 = 16_384;
/// Most float32 scan values (vehicles × beams × frames) a batch's buffers hold: 2²⁸,
/// 1 GiB.
pub const MAX_SCAN_VALUES: u64 = 1 << 28;

/// Refuse `num_envs` × `vehicles_per_env` above [`MAX_VEHICLES`], or `frames` scans of
/// `beams` beams per vehicle above [`MAX_SCAN_VALUES`] (overflow-safe), with a
/// [`ArenaError::Config`] naming the sizes. The simulator itself holds one frame.
pub fn check_size(num_envs: u64, vehicles_per_env: u64, beams: u64, frames: u64) -> Result<()> {
    let vehicles = u128::from(num_envs) * u128::from(vehicles_per_env);
    if vehicles > u128::from(MAX_VEHICLES) {
        return Err(ArenaError::config(format!(
            "num_envs x vehicles_per_env = {num_envs} x {vehicles_per_env} = {vehicles} vehicles, \
             more than the {MAX_VEHICLES} one simulator holds; use fewer envs or several \
             processes (Ray)"
        )));
    }
    let values = vehicles * u128::from(beams) * u128::from(frames);
    if values > u128::from(MAX_SCAN_VALUES) {
        return Err(ArenaError::config(format!(
            "scan buffers of {vehicles} vehicles x {beams} beams x {frames} frame(s) = {values} \
             values, more than the {MAX_SCAN_VALUES} allowed; use fewer envs, beams or stacked \
             frames"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_budget_is_inclusive_and_overflow_safe() {
        assert!(check_size(MAX_VEHICLES, 1, 1, 1).is_ok());
        assert!(matches!(
            check_size(MAX_VEHICLES + 1, 1, 1, 1),
            Err(ArenaError::Config(_))
        ));
        assert!(check_size(1 << 14, 1, 1 << 14, 1).is_ok());
        assert!(matches!(
            check_size(1 << 14, 1, 1 << 14, 2),
            Err(ArenaError::Config(_))
        ));
        assert!(check_size(u64::MAX, u64::MAX, u64::MAX, u64::MAX).is_err());
    }
}
