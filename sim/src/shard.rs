//! A share of a job's work (`--shard I/N`): every N-th unit in sorted order, starting at I.

use crate::error::{Result, SimError};

/// Take every `count`-th unit of work starting at `index` (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This worker's index, `0..count`.
    pub index: usize,
    /// Number of workers.
    pub count: usize,
}

impl Shard {
    /// The whole job.
    pub const ALL: Self = Self { index: 0, count: 1 };

    /// Parses `I/N`.
    pub fn parse(text: &str) -> Result<Self> {
        let bad = || {
            SimError::Options(format!(
                "--shard {text:?}: expected I/N with 0 ≤ I < N, e.g. 0/4"
            ))
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count) = (
            i.trim().parse::<usize>().map_err(|_| bad())?,
            n.trim().parse::<usize>().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// True if unit `i` (in sorted order) belongs to this shard.
    pub fn takes(&self, i: usize) -> bool {
        i % self.count == self.index
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_parse_and_partition_the_work() {
        let shard = Shard::parse("1/3").unwrap();
        assert_eq!(
            (0..7).filter(|&i| shard.takes(i)).collect::<Vec<_>>(),
            vec![1, 4]
        );
        assert!(Shard::parse("3/3").is_err());
        assert!(Shard::parse("x").is_err());
        assert!(Shard::parse("0/0").is_err());
    }
}
