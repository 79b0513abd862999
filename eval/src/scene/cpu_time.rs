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

/// Seconds this process has run on a CPU since it started, user and system, all threads
/// together including those that have ended (Linux: `/proc/self/stat`, in clock ticks of
/// 1/100 s), or `None` where that is not known. Coarser than [`process_cpu_secs`], but it also
/// counts the threads a stage started and joined, so it measures whole stages.
pub fn process_total_cpu_secs() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) may hold spaces; the fields after its ')' are fixed.
    let rest = text.get(text.rfind(')')? + 1..)?;
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // Fields 14 and 15 of the line (utime, stime) are the 12th and 13th after the name.
    let ticks = |k: usize| fields.get(k)?.parse::<u64>().ok();
    Some((ticks(11)? + ticks(12)?) as f64 / CLOCK_TICKS_PER_SEC)
}

/// Clock ticks per second of `/proc` times (`sysconf(_SC_CLK_TCK)`, 100 on every Linux build
/// in use).
const CLOCK_TICKS_PER_SEC: f64 = 100.0;

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
    fn busy_work_in_a_thread_that_ended_still_counts_in_the_total() {
        let Some(before) = process_total_cpu_secs() else {
            return; // no /proc on this system
        };
        // A fixed amount of work (about 0.2 s of CPU), so a loaded machine only delays it.
        std::thread::spawn(|| {
            let mut x = 1.0f64;
            for _ in 0..10_000_000 {
                x = std::hint::black_box((x * 1.000_001).sin() + 1.0);
            }
        })
        .join()
        .unwrap();
        let after = process_total_cpu_secs().unwrap();
        assert!(after - before >= 0.03, "{before} → {after}");
    }

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
