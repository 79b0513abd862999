//! A height slice's beam counts, traced once per cell size: on the slice's own map window grown
//! by the sensor's travel over a sweep or two, so the next sweep's difference map cuts the
//! previous counts from it instead of tracing the beams again (thesis 2.1.2 needs both sweeps'
//! maps on the current window).

use std::sync::{Arc, Mutex, PoisonError};

use crate::features::beam_counts::BeamCounts;
use crate::features::grid::GridWindow;
use crate::features::sliced_beam::SlicedBeam;

/// Room around a traced window, metres: a car at 72 km/h travels 2 m in a 10 Hz sweep. A map
/// window further away (the moving classifier's look-back half a second, a faster ego) traces
/// the beams again; the counts are the same either way.
const ROOM_M: f64 = 2.0;

/// The counts traced so far, at most one per cell size (the latest window asked for).
#[derive(Default)]
pub(crate) struct TracedCounts {
    traced: Mutex<Vec<Arc<BeamCounts>>>,
}

impl TracedCounts {
    /// Counts of `beams` on a window holding `window`, and where `window` starts in it (column,
    /// row): the counts traced before if they hold it, else traced now on `window` with
    /// [`ROOM_M`] of room, replacing those of the same cell size.
    pub(crate) fn holding(
        &self,
        beams: &[SlicedBeam],
        window: &GridWindow,
    ) -> (Arc<BeamCounts>, (usize, usize)) {
        let held = self.lock().iter().find_map(|counts| {
            window
                .offset_in(counts.window())
                .map(|at| (Arc::clone(counts), at))
        });
        if let Some(held) = held {
            return held;
        }
        // Traced without the lock: a sweep's two cell sizes are traced in parallel.
        let room = (ROOM_M / window.cell_m).ceil() as usize;
        let counts = Arc::new(BeamCounts::trace(beams, &window.padded(room)));
        let mut traced = self.lock();
        traced.retain(|c| c.window().cell_m.to_bits() != window.cell_m.to_bits());
        traced.push(Arc::clone(&counts));
        (counts, (room, room))
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<Arc<BeamCounts>>> {
        // The counts are whole or absent whatever a panicking holder did.
        self.traced.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl Clone for TracedCounts {
    /// The clone shares the counts traced so far.
    fn clone(&self) -> Self {
        Self {
            traced: Mutex::new(self.lock().clone()),
        }
    }
}

impl PartialEq for TracedCounts {
    /// Counts are a cache of the beams: slices are equal by their beams and points alone.
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl std::fmt::Debug for TracedCounts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TracedCounts({} windows)", self.lock().len())
    }
}
