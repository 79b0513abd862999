//! Property-based fuzzing of every loader (issue 13): random edits of valid scenario files,
//! dataset files and estimator model files go through the loaders, and edited scenarios through
//! a short `generate`. Each case must end in a valid result or a clear error naming the file,
//! never a panic, and no case may allocate without bound: this test binary's allocator refuses
//! to hold more than [`MEMORY_CAP_BYTES`] at once (an allocation past it aborts the run).
//!
//! Cases per loader: 10,000 by default (what CI runs), or `PATCHFLOW_FUZZ_CASES` for a long
//! local run, e.g. `PATCHFLOW_FUZZ_CASES=1000000 cargo test --release --test fuzz`. The random
//! stream is fixed so CI is repeatable; `PATCHFLOW_FUZZ_SEED=N` draws other cases.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod datasets;
mod hostile;
mod models;
mod mutate;
mod scenarios;

use std::alloc::System;

use cap::Cap;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// Most memory the fuzz binary may hold at once, all tests together: 1 GiB. Every loader bounds
/// what it reads (64 MiB files at most) and the inputs here are small, so a case that needs more
/// is allocating without bound.
const MEMORY_CAP_BYTES: usize = 1 << 30;

#[global_allocator]
static ALLOCATOR: Cap<System> = Cap::new(System, MEMORY_CAP_BYTES);

/// Cases per loader: `PATCHFLOW_FUZZ_CASES`, or `default`.
fn cases(default: u32) -> u32 {
    std::env::var("PATCHFLOW_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// A runner with `cases` cases, a fixed random stream (or `PATCHFLOW_FUZZ_SEED`), no failure
/// files written into the source tree, and a bounded shrink.
fn runner(cases: u32) -> TestRunner {
    let seed: u64 = std::env::var("PATCHFLOW_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(13);
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    let config = Config {
        cases,
        failure_persistence: None,
        max_shrink_iters: 2000,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &key))
}

/// Prints how many cases ran and the most memory held so far (visible with `--nocapture`).
fn report(what: &str, cases: u32, detail: &str) {
    println!(
        "{what}: {cases} cases passed{detail}; peak memory of the fuzz binary so far {:.1} MiB (cap {} MiB)",
        ALLOCATOR.max_allocated() as f64 / (1 << 20) as f64,
        MEMORY_CAP_BYTES >> 20
    );
}

#[test]
fn the_memory_cap_is_in_force() {
    assert_eq!(ALLOCATOR.limit(), MEMORY_CAP_BYTES);
    let v = vec![0u8; 1 << 20];
    assert!(ALLOCATOR.allocated() >= v.len());
}
