//! Running independent maps side by side (issue 25: the occupancy stage on 2 cores): every map
//! of a sequence (query time × method) is a job, the jobs are taken in the given order (costliest
//! first) by one worker per core, and each job runs alone on its worker's thread, its GP's own
//! parallel parts included (a one-thread pool), so a map's wall and CPU seconds are its own and
//! its result does not depend on the number of workers. Before, the maps ran one after the other
//! with the GP splitting its products over the cores, which kept both cores busy only part of
//! the time.

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// A job's result with its wall and CPU seconds (`None` where the system does not report the
/// thread's CPU time).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Timed<T> {
    /// What the job returned.
    pub value: T,
    /// Wall-clock seconds of the job.
    pub wall_secs: f64,
    /// CPU seconds of the job's thread.
    pub cpu_secs: Option<f64>,
}

/// Seconds the calling thread has run on a CPU (Linux: `/proc/thread-self/schedstat`,
/// nanoseconds), or `None` where that is not known.
pub(crate) fn thread_cpu_secs() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let nanos: u64 = text.split_whitespace().next()?.parse().ok()?;
    Some(nanos as f64 * 1e-9)
}

/// Runs `job(0) … job(jobs − 1)` on up to `workers` threads (at least one), each job alone on
/// its thread; results in job order.
pub(crate) fn run_jobs<T: Send>(
    jobs: usize,
    workers: usize,
    job: &(dyn Fn(usize) -> T + Sync),
) -> Vec<Timed<T>> {
    let next = AtomicUsize::new(0);
    let done: Mutex<Vec<(usize, Timed<T>)>> = Mutex::new(Vec::with_capacity(jobs));
    let worker = || {
        // The job's own parallel parts (rayon::join in the GP) run on this one thread.
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().ok();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            if i >= jobs {
                break;
            }
            let timed = || {
                let (wall, cpu) = (Instant::now(), thread_cpu_secs());
                let value = job(i);
                let cpu_secs = thread_cpu_secs().zip(cpu).map(|(b, a)| b - a);
                Timed {
                    value,
                    wall_secs: wall.elapsed().as_secs_f64(),
                    cpu_secs,
                }
            };
            let result = match &pool {
                Some(pool) => pool.install(timed),
                None => timed(),
            };
            if let Ok(mut done) = done.lock() {
                done.push((i, result));
            }
        }
    };
    let workers = workers.clamp(1, jobs.max(1));
    std::thread::scope(|scope| {
        for _ in 1..workers {
            scope.spawn(worker);
        }
        worker();
    });
    let mut done = done
        .into_inner()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, t)| t).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn busy(rounds: u64) -> f64 {
        let mut x = 1.0f64;
        for _ in 0..rounds {
            x = std::hint::black_box((x * 1.000_001).sin() + 1.0);
        }
        x
    }

    #[test]
    fn results_come_back_in_job_order_whatever_the_number_of_workers() {
        let job = |i: usize| (i * i, busy(1_000 * (7 - i as u64 % 7)));
        let one: Vec<_> = run_jobs(13, 1, &job).into_iter().map(|t| t.value).collect();
        for workers in [2, 3, 8] {
            let many: Vec<_> = run_jobs(13, workers, &job)
                .into_iter()
                .map(|t| t.value)
                .collect();
            assert_eq!(many, one, "{workers} workers");
        }
        assert_eq!(one.iter().map(|v| v.0).collect::<Vec<_>>()[12], 144);
        assert!(run_jobs(0, 2, &job).is_empty());
    }

    #[test]
    fn a_jobs_inner_parallel_work_stays_on_its_thread_and_counts_in_its_cpu_seconds() {
        // Inside a job rayon sees one thread: the GP's rayon::join halves run on the job's own,
        // so the job's thread CPU time holds all of its work. Checked by where the halves run,
        // not by comparing CPU times, which a loaded machine makes noisy.
        let threads = run_jobs(3, 2, &|_| rayon::current_num_threads());
        assert!(threads.iter().all(|t| t.value == 1));
        let half = || (std::thread::current().id(), busy(200_000));
        for t in run_jobs(4, 2, &|_| {
            let own = std::thread::current().id();
            let ((a, _), (b, _)) = rayon::join(half, half);
            (own, a, b)
        }) {
            let (own, a, b) = t.value;
            assert!(a == own && b == own, "a half ran on another thread");
            // One thread cannot spend more CPU than wall time (5 ms for the clocks' granularity).
            if let Some(cpu) = t.cpu_secs {
                assert!(cpu <= t.wall_secs + 0.005, "cpu {cpu} wall {}", t.wall_secs);
            }
        }
    }
}
