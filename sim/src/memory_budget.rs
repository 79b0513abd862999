//! How much memory this process may still use: the tightest of the machine's `MemAvailable`, the
//! process's address-space limit (`ulimit -v`, `prlimit --as`, what Slurm and batch systems set)
//! less what it already maps, and its cgroup's limit (v2 `memory.max`, v1
//! `memory.limit_in_bytes`) less what the group already uses. A run refused up front by this
//! budget gets a message naming the limit; one that only met the limit mid-run would abort.

use crate::error::{Result, SimError};
use crate::scenario::{Scenario, gigabytes, sweep_memory_bytes};

/// Refuses a scenario whose sweep needs more memory than this process may use: the tightest
/// of the machine's available memory, the process's address-space limit and its cgroup's.
pub(crate) fn check_memory(scenario: &Scenario) -> Result<()> {
    check_memory_within(scenario, memory_budget())
}

/// [`check_memory`] against a given budget.
pub(crate) fn check_memory_within(scenario: &Scenario, budget: Option<MemoryBudget>) -> Result<()> {
    let needed = sweep_memory_bytes(scenario);
    match budget {
        Some(budget) if needed > budget.bytes => Err(SimError::Options(format!(
            "scenario {:?}: one sweep of {} × {} rays and the world it is cast into need about {} of memory, but {} leaves {}",
            scenario.name,
            scenario.lidar.channels,
            scenario.lidar.azimuth_steps,
            gigabytes(needed),
            budget.source,
            gigabytes(budget.bytes)
        ))),
        _ => Ok(()),
    }
}

/// Address space each worker thread takes beyond what it allocates: its stack (2 MiB) and the
/// C allocator's arena, which reserves 64 MiB of address space (not of memory) on first use.
/// Under `ulimit -v` these count: a run that fit the sweep alone aborted between 330 and 370 MB.
const RESERVED_BYTES_PER_THREAD: u64 = 66 << 20;

/// A memory budget and the limit that set it, for messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryBudget {
    /// Bytes this process may still allocate.
    pub bytes: u64,
    /// Which limit is the tightest, in words.
    pub source: &'static str,
}

/// The budget on this machine, `None` where no limit can be read (not Linux).
pub fn memory_budget() -> Option<MemoryBudget> {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let status = read("/proc/self/status");
    let mapped = status.as_deref().and_then(|s| kib_field(s, "VmSize:"));
    tightest([
        read("/proc/meminfo")
            .and_then(|t| kib_field(&t, "MemAvailable:"))
            .map(|b| (b, "the machine's available memory (MemAvailable)")),
        read("/proc/self/limits")
            .and_then(|t| address_space_limit(&t))
            .map(|limit| {
                let threads = rayon::current_num_threads() as u64 + 1; // + the sweep writer
                let left = limit
                    .saturating_sub(mapped.unwrap_or(0))
                    .saturating_sub(threads.saturating_mul(RESERVED_BYTES_PER_THREAD));
                (
                    left,
                    "the process's address-space limit (ulimit -v / prlimit --as), less what it \
                     maps and its threads reserve",
                )
            }),
        cgroup_left(
            read("/sys/fs/cgroup/memory.max"),
            read("/sys/fs/cgroup/memory.current"),
        )
        .map(|b| (b, "the cgroup's memory limit (memory.max)")),
        cgroup_left(
            read("/sys/fs/cgroup/memory/memory.limit_in_bytes"),
            read("/sys/fs/cgroup/memory/memory.usage_in_bytes"),
        )
        .map(|b| (b, "the cgroup's memory limit (memory.limit_in_bytes)")),
    ])
}

/// The smallest of the limits that could be read.
pub(crate) fn tightest<const N: usize>(
    limits: [Option<(u64, &'static str)>; N],
) -> Option<MemoryBudget> {
    limits
        .into_iter()
        .flatten()
        .min_by_key(|(bytes, _)| *bytes)
        .map(|(bytes, source)| MemoryBudget { bytes, source })
}

/// A `Name:   123 kB` field of `/proc/meminfo` or `/proc/self/status`, in bytes.
pub(crate) fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

/// The soft `Max address space` of `/proc/self/limits`, `None` if unlimited.
pub(crate) fn address_space_limit(limits: &str) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line.trim_start_matches("Max address space")
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// A cgroup's limit less its usage; `None` without a limit (`max`, or v1's huge sentinel).
pub(crate) fn cgroup_left(limit: Option<String>, usage: Option<String>) -> Option<u64> {
    let limit: u64 = limit?.trim().parse().ok()?;
    if limit >= 1 << 60 {
        return None;
    }
    let used: u64 = usage.and_then(|u| u.trim().parse().ok()).unwrap_or(0);
    Some(limit.saturating_sub(used))
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: &str = "Limit                     Soft Limit           Hard Limit           Units\n\
        Max stack size            8388608              unlimited            bytes\n\
        Max address space         2147483648           unlimited            bytes\n";

    #[test]
    fn the_address_space_limit_is_read_and_unlimited_is_none() {
        assert_eq!(address_space_limit(LIMITS), Some(2 << 30));
        let unlimited = LIMITS.replace("2147483648          ", "unlimited           ");
        assert_eq!(address_space_limit(&unlimited), None);
    }

    #[test]
    fn the_tightest_limit_wins_and_names_itself() {
        let budget = tightest([
            Some((8 << 30, "memavailable")),
            Some((1 << 30, "rlimit")),
            None,
            Some((4 << 30, "cgroup")),
        ])
        .unwrap();
        assert_eq!(
            budget,
            MemoryBudget {
                bytes: 1 << 30,
                source: "rlimit"
            }
        );
    }

    #[test]
    fn a_cgroup_without_a_limit_gives_none_and_one_with_a_limit_its_headroom() {
        assert_eq!(cgroup_left(Some("max\n".into()), Some("100".into())), None);
        assert_eq!(cgroup_left(Some("9223372036854771712".into()), None), None);
        assert_eq!(
            cgroup_left(Some("1000\n".into()), Some("300\n".into())),
            Some(700)
        );
    }

    #[test]
    fn meminfo_fields_are_read_in_bytes() {
        let text = "MemTotal:  100 kB\nMemAvailable:   50 kB\n";
        assert_eq!(kib_field(text, "MemAvailable:"), Some(50 * 1024));
    }

    #[test]
    fn a_sweep_over_a_process_limit_is_refused_naming_the_limit() {
        let scenario = crate::ScenarioSource::from_argument(std::path::Path::new("situation1"))
            .unwrap()
            .load()
            .unwrap();
        let budget = MemoryBudget {
            bytes: 1 << 20,
            source: "the process's address-space limit (ulimit -v / prlimit --as)",
        };
        let err = check_memory_within(&scenario, Some(budget))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("address-space limit") && err.contains("rays"),
            "{err}"
        );
        let roomy = MemoryBudget {
            bytes: u64::MAX,
            source: "x",
        };
        assert!(check_memory_within(&scenario, Some(roomy)).is_ok());
    }
}
