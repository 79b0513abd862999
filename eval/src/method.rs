//! Method names of the benchmark (SPEC §6) and their canonical order in tables and plots.

/// Every method the benchmark knows, in table order: the four GP variants (thesis Table 4.5),
/// the oracle-association baselines, then the self-associating baselines.
pub const CANONICAL_METHODS: [&str; 8] = [
    "SPGP-ALL",
    "SPGP-BEST",
    "SPGP-HET-ALL",
    "SPGP-HET-BEST",
    "KF",
    "ICP",
    "KF-AUTO",
    "ICP-AUTO",
];

/// Orders method names: canonical ones first in canonical order, any others after them
/// alphabetically. Duplicates are dropped.
pub fn ordered_methods<'a>(names: impl IntoIterator<Item = &'a str>) -> Vec<String> {
    let mut names: Vec<&str> = names.into_iter().collect();
    names.sort_by_key(|name| {
        let rank = CANONICAL_METHODS
            .iter()
            .position(|c| c == name)
            .unwrap_or(CANONICAL_METHODS.len());
        (rank, *name)
    });
    names.dedup();
    names.into_iter().map(str::to_owned).collect()
}

/// Index of a method in [`CANONICAL_METHODS`] (for stable colours); unknown names hash to a slot after them.
pub fn method_slot(name: &str) -> usize {
    CANONICAL_METHODS
        .iter()
        .position(|c| *c == name)
        .unwrap_or_else(|| {
            CANONICAL_METHODS.len() + name.bytes().map(usize::from).sum::<usize>() % 4
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn methods_are_ordered_canonically_with_unknown_names_last() {
        let ordered = ordered_methods(["ICP-AUTO", "zeta", "KF", "SPGP-ALL", "ICP", "alpha", "KF"]);
        assert_eq!(
            ordered,
            ["SPGP-ALL", "KF", "ICP", "ICP-AUTO", "alpha", "zeta"]
        );
    }
}
