//! CPU time of this process, all threads together, and the machine's load, where the system
//! reports them (Linux:
//! `/proc/self/task/*/schedstat`, nanoseconds on a CPU). On a machine shared with other work a
//! scan's wall time grows with the load, its CPU time hardly: CPU time over the cores is the
//! latency the scan would have on idle cores with perfect parallelism, a floor for the wall time.

/// Seconds this process's live threads have run on a CPU, or `None` where that is not known.
pub fn process_cpu_secs() -> Option<f64> {
    let mut nanos: u64 = 0;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let text = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        nanos += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(nanos as f64 * 1e-9)
}

/// The system's 1-minute load average (runnable tasks), where the system reports it (Linux:
/// `/proc/loadavg`).
pub fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn busy_work_advances_the_cpu_clock_where_there_is_one() {
        let Some(before) = process_cpu_secs() else {
            return; // no per-thread CPU clock on this system
        };
        let mut x = 1.0f64;
        let start = std::time::Instant::now();
        while start.elapsed().as_secs_f64() < 0.05 {
            x = (x * 1.000_001).sin() + 1.0;
        }
        std::hint::black_box(x);
        let after = process_cpu_secs().unwrap();
        assert!(after > before, "{before} → {after}");
    }
}
