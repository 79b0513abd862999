//! Seed derivation: one independent random stream per (run seed, sequence name, sweep, column),
//! so any sweep can be produced on its own (exact resume) and the bytes do not depend on the
//! number of threads.

/// SplitMix64 finaliser: a bijective mix of 64 bits.
pub(crate) fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// FNV-1a of a name: stable across platforms and Rust versions (unlike `DefaultHasher`).
pub(crate) fn hash_name(name: &str) -> u64 {
    name.bytes().fold(0xCBF2_9CE4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3)
    })
}

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
