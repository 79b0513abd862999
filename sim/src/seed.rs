//! Seed derivation: one independent random stream per (run seed, sequence name, sweep, column),
//! so any sweep can be produced on its own (exact resume) and the bytes do not depend on the
//! number of threads.

/// SplitMix64 (a bijective mix of 64 bits) and FNV-1a of a name: the workspace's one copy.
pub(crate) use patchflow_dataset::{fnv1a as hash_name, splitmix64 as mix};

/// Key of one sweep's noise: all of its random draws derive from it.
pub fn sweep_key(seed: u64, sequence: &str, sweep: u32) -> u64 {
    mix(mix(seed ^ hash_name(sequence)) ^ u64::from(sweep))
}

/// Seed of a sub-stream `index` of `key` (a lidar column, a random actor, ...).
pub(crate) fn sub_seed(key: u64, index: u64) -> u64 {
    mix(key ^ mix(index.wrapping_add(0x5EED)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_differ_by_seed_name_and_sweep() {
        let base = sweep_key(7, "situation1", 3);
        assert_ne!(base, sweep_key(8, "situation1", 3));
        assert_ne!(base, sweep_key(7, "situation2", 3));
        assert_ne!(base, sweep_key(7, "situation1", 4));
        assert_eq!(base, sweep_key(7, "situation1", 3));
    }
}
