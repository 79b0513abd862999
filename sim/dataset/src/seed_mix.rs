//! The workspace's one SplitMix64 mix and FNV-1a name hash, for seeded streams that do not
//! depend on threads or on which other items are drawn. It sits in the lowest crate because the
//! simulator, the feature sampler and the occupancy maps all derive seeds with it.

/// SplitMix64's increment (the golden ratio in 64 bits, Steele, Lea and Flood 2014).
pub const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's finaliser alone: a bijective mix of 64 bits (two xor-shift-multiply rounds and a
/// last xor-shift), for callers that combine their inputs themselves.
pub fn splitmix64_finalize(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// One step of SplitMix64: the increment added, then the finaliser.
pub fn splitmix64(x: u64) -> u64 {
    splitmix64_finalize(x.wrapping_add(GOLDEN_GAMMA))
}

/// FNV-1a of a name: stable across platforms and Rust versions (unlike `DefaultHasher`).
pub fn fnv1a(name: &str) -> u64 {
    name.bytes().fold(0xCBF2_9CE4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_of_zero_is_the_published_first_output() {
        // The first output of SplitMix64 seeded with 0 (Vigna's reference implementation).
        assert_eq!(splitmix64(0), 0xE220_A839_7B1D_CDAF);
    }

    #[test]
    fn fnv1a_of_the_empty_name_is_the_offset_basis_and_of_a_is_the_published_value() {
        assert_eq!(fnv1a(""), 0xCBF2_9CE4_8422_2325);
        assert_eq!(fnv1a("a"), 0xAF63_DC4C_8601_EC8C);
    }
}
