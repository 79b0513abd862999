//! The work a scenario implies, estimated from its fields before anything is built or cast
//! (issue 26): rays per sweep × sweeps, actors (listed and random), the street world's ground
//! cells × street segments (every ground vertex looks for its nearest street) and pieces, and
//! the bytes its sequence takes on disk. `generate` reports it up front and refuses a run whose
//! bytes would not fit on the disk.

use super::Scenario;
use super::bounds::{gigabytes, show};
use super::world_limits::WorldSize;

/// Bytes one point takes on disk: `velodyne` (16), `labels` (4), `flow` (12), `time` (4) and
/// `ring` (2).
const DISK_BYTES_PER_POINT: u64 = 38;
/// Bytes one object's truth takes in a sweep's `objects` JSON (measured: about 460).
const DISK_BYTES_PER_OBJECT: u64 = 600;
/// Bytes one static piece takes in `static.json` (measured: about 270).
const DISK_BYTES_PER_PIECE: u64 = 300;
/// Bytes of a sequence's fixed files (`scenario.toml`, `sensor.json`, markers, calibration).
const DISK_BYTES_PER_SEQUENCE: u64 = 64 << 10;
/// Bytes one sweep's lines take in `poses.txt`, `poses_estimated.txt` and `times.txt`, and the
/// marker's digests.
const DISK_BYTES_PER_SWEEP_LINES: u64 = 600;

/// What generating a scenario's sequence takes, estimated from its fields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkEstimate {
    /// Sweeps in the sequence.
    pub sweeps: u32,
    /// Rays cast per sweep (every one can become a point).
    pub rays_per_sweep: u64,
    /// Moving actors: listed plus random cars and pedestrians (the ego not counted).
    pub actors: u64,
    /// Ground cells of the street world (0 on the `ideal` world).
    pub ground_cells: f64,
    /// Street segments the ground is laid along.
    pub street_segments: u64,
    /// Static pieces (colliders) of the world, an upper estimate, structures included.
    pub world_pieces: f64,
    /// Bytes the sequence takes on disk at most (every ray a point).
    pub disk_bytes: u64,
}

impl WorkEstimate {
    /// The estimate for `s`, from its fields alone.
    pub fn of(s: &Scenario) -> Self {
        let rays_per_sweep = u64::from(s.lidar.channels) * u64::from(s.lidar.azimuth_steps);
        let actors = s.actors.len() as u64
            + u64::from(s.traffic.random_cars)
            + u64::from(s.traffic.random_pedestrians);
        let world = WorldSize::of(s);
        let structures: u64 = s.structures.iter().map(|st| st.box_count()).sum();
        let world_pieces = world.map_or(structures as f64, |w| w.pieces);
        let sweeps = u64::from(s.sweeps);
        let per_sweep = rays_per_sweep
            .saturating_mul(DISK_BYTES_PER_POINT)
            .saturating_add((actors + 1).saturating_mul(DISK_BYTES_PER_OBJECT))
            .saturating_add(DISK_BYTES_PER_SWEEP_LINES);
        let disk_bytes = sweeps
            .saturating_mul(per_sweep)
            .saturating_add((world_pieces * DISK_BYTES_PER_PIECE as f64) as u64)
            .saturating_add(DISK_BYTES_PER_SEQUENCE);
        Self {
            sweeps: s.sweeps,
            rays_per_sweep,
            actors,
            ground_cells: world.map_or(0.0, |w| w.ground_cells),
            street_segments: world.map_or(0, |w| w.streets),
            world_pieces,
            disk_bytes,
        }
    }

    /// Rays cast in the whole sequence.
    pub fn rays(&self) -> u64 {
        self.rays_per_sweep.saturating_mul(u64::from(self.sweeps))
    }

    /// The estimate in one line, e.g. for a log: "3 sweeps × 23040 rays, 1 actors, 0 ground
    /// cells × 0 street segments, 12 world pieces, up to 3 MB on disk".
    pub fn summary(&self) -> String {
        format!(
            "{} sweeps × {} rays, {} actors, {} ground cells × {} street segments, {} world pieces, up to {} on disk",
            self.sweeps,
            self.rays_per_sweep,
            self.actors,
            show(self.ground_cells.round()),
            self.street_segments,
            show(self.world_pieces.round()),
            gigabytes(self.disk_bytes)
        )
    }

    /// True when building the world or casting may take more than a few seconds: a progress
    /// display should show the world build, not only the sweeps.
    pub fn world_build_is_long(&self) -> bool {
        self.ground_cells * self.street_segments as f64 > LONG_GROUND_WORK
            || self.world_pieces > LONG_PIECES
            || self.actors > LONG_ACTORS
    }
}

/// Ground cells × street segments beyond which a world build takes seconds.
const LONG_GROUND_WORK: f64 = 1e9;
/// Static pieces beyond which a world build takes seconds.
const LONG_PIECES: f64 = 50_000.0;
/// Actors beyond which setting up their bodies takes seconds.
const LONG_ACTORS: u64 = 2_000;

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> Scenario {
        let text = "sweeps = 3\nrealism = \"ideal\"\n[lidar]\nchannels = 8\nazimuth_steps = 100\nblocks = 10\n\
            [ego]\npath_m = [[0.0, 0.0], [40.0, 0.0]]\nspeed_mps = 2.0\n\
            [[actors]]\nname = \"car\"\npath_m = [[8.0, -6.0], [8.0, 40.0]]\nspeed_mps = 6.0\n";
        Scenario::from_toml(text, "tiny.toml", "tiny").unwrap()
    }

    #[test]
    fn the_estimate_counts_rays_actors_and_bytes_of_every_sweep() {
        let e = WorkEstimate::of(&tiny());
        assert_eq!((e.sweeps, e.rays_per_sweep, e.actors), (3, 800, 1));
        assert_eq!(e.rays(), 2400);
        // Every ray a point of 38 bytes, plus objects, lines and the fixed files (no street
        // world on the ideal rung).
        assert!(e.disk_bytes >= 2400 * 38, "{}", e.disk_bytes);
        assert!(e.disk_bytes < 2400 * 38 + (1 << 20), "{}", e.disk_bytes);
        assert_eq!((e.ground_cells, e.street_segments), (0.0, 0));
        assert!(
            e.summary().contains("3 sweeps × 800 rays"),
            "{}",
            e.summary()
        );
    }

    #[test]
    fn many_sweeps_of_many_rays_are_terabytes() {
        let mut s = tiny();
        s.sweeps = 100_000;
        s.lidar.channels = 128;
        s.lidar.azimuth_steps = 20_000;
        let e = WorkEstimate::of(&s);
        assert!(e.disk_bytes > 9_000_000_000_000, "{}", e.disk_bytes);
        assert!(e.summary().contains("GB"), "{}", e.summary());
    }
}
