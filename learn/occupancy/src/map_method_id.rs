//! The name of each map method as a type: reports, tables and `occupancy.json` key their rows by
//! it, so a method is matched by value, never by a string that may be misspelt.

use std::fmt;

use serde::{Serialize, Serializer};

/// One occupancy map method. The derived order is the names' alphabetical order, so maps keyed
/// by it keep the order (and the bytes) maps keyed by the names had.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum MapMethodId {
    /// DGPOM: a motion-adapted kernel with a learned velocity field.
    Dgpom,
    /// GPOM in R^D (space only).
    GpomRd,
    /// GPOM in R^{D+1} (space and time).
    GpomRd1,
    /// The occupancy grid.
    Grid,
}

impl MapMethodId {
    /// Every method, in the paper's table order (DGPOM, GPOM ℜ^D, GPOM ℜ^{D+1}), then the grid.
    pub const ALL: [Self; 4] = [Self::Dgpom, Self::GpomRd, Self::GpomRd1, Self::Grid];

    /// The method's name in reports (`DGPOM`, `GPOM-RD`, `GPOM-RD1`, `GRID`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Dgpom => "DGPOM",
            Self::GpomRd => "GPOM-RD",
            Self::GpomRd1 => "GPOM-RD1",
            Self::Grid => "GRID",
        }
    }
}

impl fmt::Display for MapMethodId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

impl Serialize for MapMethodId {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_derived_order_is_the_alphabetical_order_of_the_names() {
        let mut by_name = MapMethodId::ALL;
        by_name.sort_by_key(|m| m.name());
        let mut by_value = MapMethodId::ALL;
        by_value.sort();
        assert_eq!(by_name, by_value);
    }

    #[test]
    fn every_method_has_its_own_name() {
        let mut names: Vec<&str> = MapMethodId::ALL.iter().map(|m| m.name()).collect();
        names.dedup();
        assert_eq!(names.len(), MapMethodId::ALL.len());
    }
}
