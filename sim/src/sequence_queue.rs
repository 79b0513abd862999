//! The sequences of one `generate` run, two at a time when memory allows: a sequence's serial
//! work (building its world, stepping its bodies, handing sweeps to the writer) leaves the cores
//! idle between its ray casts, and a second sequence's casts fill them. Each sequence is
//! generated exactly as alone (its own seed, its own files), so the bytes do not change.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::error::Result;
use crate::memory_budget::MemoryBudget;
use crate::scenario::{Scenario, sweep_memory_bytes};

/// Sequences generated at once when their sweeps fit in memory together.
const SEQUENCES_AT_ONCE: usize = 2;

/// Address space two sequences at once add beyond their sweeps and worlds: the two threads that
/// step them and the second sweep writer, each a stack and an allocator arena (66 MiB, see
/// `memory_budget.rs`).
const EXTRA_BYTES_AT_ONCE: u64 = 3 * (66 << 20);

/// How many sequences to generate at once: two when more than one is to be generated and the
/// two largest sweeps fit in `budget` together with the extra threads, else one.
pub(crate) fn sequences_at_once(scenarios: &[&Scenario], budget: Option<MemoryBudget>) -> usize {
    if scenarios.len() < 2 {
        return 1;
    }
    let mut needs: Vec<u64> = scenarios.iter().map(|s| sweep_memory_bytes(s)).collect();
    needs.sort_unstable_by(|a, b| b.cmp(a));
    let together = needs[..SEQUENCES_AT_ONCE]
        .iter()
        .fold(EXTRA_BYTES_AT_ONCE, |sum, &b| sum.saturating_add(b));
    match budget {
        Some(budget) if together > budget.bytes => 1,
        _ => SEQUENCES_AT_ONCE,
    }
}

/// Runs `generate` on every scenario, `at_once` at a time in scenario order (each worker takes
/// the next one not yet started). After a failure no further scenario starts; the error returned
/// is that of the earliest scenario that failed, as a run one at a time would return it.
pub(crate) fn generate_each(
    scenarios: &[&Scenario],
    at_once: usize,
    generate: &(dyn Fn(&Scenario) -> Result<()> + Sync),
) -> Result<()> {
    if at_once <= 1 {
        return scenarios.iter().try_for_each(|s| generate(s));
    }
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let errors = Mutex::new(Vec::new());
    let worker = || {
        while !failed.load(Ordering::SeqCst) {
            let i = next.fetch_add(1, Ordering::SeqCst);
            let Some(scenario) = scenarios.get(i) else {
                break;
            };
            if let Err(err) = generate(scenario) {
                failed.store(true, Ordering::SeqCst);
                if let Ok(mut errors) = errors.lock() {
                    errors.push((i, err));
                }
            }
        }
    };
    std::thread::scope(|scope| {
        for _ in 0..at_once.min(scenarios.len()) {
            scope.spawn(worker);
        }
    });
    let errors = errors
        .into_inner()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    match errors.into_iter().min_by_key(|(i, _)| *i) {
        Some((_, err)) => Err(err),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::SimError;

    fn situation(name: &str) -> Scenario {
        crate::ScenarioSource::from_argument(std::path::Path::new(name))
            .unwrap()
            .load()
            .unwrap()
    }

    #[test]
    fn two_sequences_go_at_once_only_when_both_sweeps_fit_in_memory() {
        let (a, b) = (situation("situation1"), situation("situation2"));
        let both = [&a, &b];
        assert_eq!(sequences_at_once(&both, None), 2);
        assert_eq!(sequences_at_once(&both[..1], None), 1);
        let one_sweep = sweep_memory_bytes(&a).max(sweep_memory_bytes(&b));
        let tight = MemoryBudget {
            bytes: one_sweep + 1,
            source: "test",
        };
        assert_eq!(sequences_at_once(&both, Some(tight)), 1);
        let roomy = MemoryBudget {
            bytes: u64::MAX,
            source: "test",
        };
        assert_eq!(sequences_at_once(&both, Some(roomy)), 2);
    }

    #[test]
    fn every_scenario_is_generated_once_and_the_earliest_failure_is_returned() {
        let scenarios: Vec<Scenario> = (1..=5)
            .map(|k| situation(&format!("situation{k}")))
            .collect();
        let refs: Vec<&Scenario> = scenarios.iter().collect();
        let done = Mutex::new(Vec::new());
        generate_each(&refs, 2, &|s| {
            done.lock().unwrap().push(s.name.clone());
            Ok(())
        })
        .unwrap();
        let mut done = done.into_inner().unwrap();
        done.sort();
        let names: Vec<String> = scenarios.iter().map(|s| s.name.clone()).collect();
        assert_eq!(done, names);
        let fail = |s: &Scenario| match s.name.as_str() {
            "situation2" | "situation3" => Err(SimError::Options(format!("{} failed", s.name))),
            _ => Ok(()),
        };
        for at_once in [1, 2] {
            let err = generate_each(&refs, at_once, &fail)
                .unwrap_err()
                .to_string();
            assert!(err.contains("situation2"), "{at_once} at once: {err}");
        }
    }
}
