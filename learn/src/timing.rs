//! Wall-time measurement of pipeline stages, reported with each result so callers can show what
//! a scan's steps cost (SPEC §8).

use std::time::Instant;

/// Runs `work`, adding its wall time in seconds to `secs`.
pub(crate) fn timed<T>(secs: &mut f64, work: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let value = work();
    *secs += start.elapsed().as_secs_f64();
    value
}
