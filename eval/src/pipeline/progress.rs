//! Progress bars and stage timing for long commands: indicatif bars on stderr (hidden when stderr
//! is not a terminal), progress lines that also reach a log file, and a [`StageTimer`] whose
//! per-stage seconds fill the report's timing table.

use std::io::IsTerminal as _;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

use crate::report::stage_timing::StageTiming;
use crate::scene::cpu_time::process_total_cpu_secs;

/// Records wall-clock and CPU seconds per stage, in the order the stages ran.
///
/// ```
/// use patchflow_eval::progress::StageTimer;
/// let mut timer = StageTimer::new();
/// let answer = timer.time("think", || 6 * 7);
/// assert_eq!(answer, 42);
/// assert_eq!(timer.timings()[0].stage, "think");
/// ```
#[derive(Debug, Clone, Default)]
pub struct StageTimer {
    timings: Vec<StageTiming>,
}

impl StageTimer {
    /// An empty timer.
    pub fn new() -> Self {
        Self::default()
    }

    /// Runs `work`, records its wall and CPU seconds under `stage`, and returns its result.
    pub fn time<T>(&mut self, stage: &str, work: impl FnOnce() -> T) -> T {
        let (start, cpu_start) = (Instant::now(), process_total_cpu_secs());
        let out = work();
        let cpu = cpu_start
            .zip(process_total_cpu_secs())
            .map(|(start, end)| end - start);
        self.record_with_cpu(stage, start.elapsed().as_secs_f64(), cpu);
        out
    }

    /// Records seconds measured elsewhere. A stage recorded twice accumulates.
    pub fn record(&mut self, stage: &str, seconds: f64) {
        self.record_with_cpu(stage, seconds, None);
    }

    /// Records wall and CPU seconds measured elsewhere. A stage recorded twice accumulates.
    pub fn record_with_cpu(&mut self, stage: &str, seconds: f64, cpu_seconds: Option<f64>) {
        match self.timings.iter_mut().find(|t| t.stage == stage) {
            Some(timing) => {
                timing.seconds += seconds;
                timing.cpu_seconds = timing.cpu_seconds.zip(cpu_seconds).map(|(a, b)| a + b);
            }
            None => self.timings.push(StageTiming {
                stage: stage.to_owned(),
                seconds,
                cpu_seconds,
            }),
        }
    }

    /// The stages so far, in first-run order.
    pub fn timings(&self) -> &[StageTiming] {
        &self.timings
    }

    /// Total seconds over all stages.
    pub fn total_seconds(&self) -> f64 {
        self.timings.iter().map(|t| t.seconds).sum()
    }

    /// Hands the timings over (e.g. into `BenchmarkReport::timings`).
    pub fn into_timings(self) -> Vec<StageTiming> {
        self.timings
    }
}

/// Whether stderr is a terminal, i.e. whether the progress bars are drawn.
pub fn stderr_is_terminal() -> bool {
    std::io::stderr().is_terminal()
}

/// Writes one progress line to stderr: seconds since `start`, then `text`. Unlike the bars,
/// these lines reach a log file when stderr is redirected.
pub fn progress_line(start: Instant, text: &str) {
    eprintln!("{}", progress_text(start.elapsed().as_secs_f64(), text));
}

fn progress_text(seconds: f64, text: &str) -> String {
    format!("[{seconds:>7.1} s] {text}")
}

/// Progress as lines when stderr is not a terminal (a log file): one line at every tenth of the
/// work, so a long stage shows it is moving; silent on a terminal, where the bars draw.
#[derive(Debug)]
pub struct ProgressLines {
    label: String,
    start: Instant,
    enabled: bool,
    last_tenth: std::sync::atomic::AtomicUsize,
}

impl ProgressLines {
    /// Lines labelled `label`, timed from now, written only when stderr is not a terminal.
    pub fn new(label: &str) -> Self {
        Self::with_output(label, !stderr_is_terminal())
    }

    fn with_output(label: &str, enabled: bool) -> Self {
        Self {
            label: label.to_owned(),
            start: Instant::now(),
            enabled,
            last_tenth: std::sync::atomic::AtomicUsize::new(0),
        }
    }

    /// Reports `done` of `total` steps; returns the line when one is due (and writes it).
    pub fn update(&self, done: usize, total: usize) -> Option<String> {
        if !self.enabled || total == 0 {
            return None;
        }
        let tenth = (10 * done.min(total)) / total;
        let previous = self
            .last_tenth
            .fetch_max(tenth, std::sync::atomic::Ordering::Relaxed);
        (tenth > previous).then(|| {
            let line = progress_text(
                self.start.elapsed().as_secs_f64(),
                &format!("  {}: {done}/{total}", self.label),
            );
            eprintln!("{line}");
            line
        })
    }
}

/// A progress bar of `len` steps labelled `message`, with elapsed time and ETA.
pub fn progress_bar(len: u64, message: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    let style = ProgressStyle::with_template(
        "{msg:>24} [{elapsed_precise}] {bar:32.cyan/blue} {pos}/{len} (eta {eta})",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ");
    bar.set_style(style);
    bar.set_message(message.to_owned());
    bar
}

/// A spinner for a stage of unknown length labelled `message`.
pub fn spinner(message: &str) -> ProgressBar {
    let bar = ProgressBar::new_spinner();
    bar.set_message(message.to_owned());
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stage_recorded_twice_accumulates_and_keeps_its_place() {
        let mut timer = StageTimer::new();
        timer.record("generate", 1.5);
        timer.record("train", 2.0);
        timer.record("generate", 0.5);
        let names: Vec<&str> = timer.timings().iter().map(|t| t.stage.as_str()).collect();
        assert_eq!(names, ["generate", "train"]);
        assert!((timer.timings()[0].seconds - 2.0).abs() < 1e-12);
        assert!((timer.total_seconds() - 4.0).abs() < 1e-12);
    }

    #[test]
    fn a_progress_line_starts_with_the_elapsed_seconds() {
        assert_eq!(
            progress_text(12.34, "train: started"),
            "[   12.3 s] train: started"
        );
    }

    #[test]
    fn progress_lines_come_once_per_tenth_of_the_work() {
        let lines = ProgressLines::with_output("scans", true);
        let written: Vec<usize> = (1..=100)
            .filter(|&done| lines.update(done, 100).is_some())
            .collect();
        assert_eq!(written, [10, 20, 30, 40, 50, 60, 70, 80, 90, 100]);
        let silent = ProgressLines::with_output("scans", false);
        assert!((1..=100).all(|done| silent.update(done, 100).is_none()));
    }

    #[test]
    fn timing_a_closure_records_a_non_negative_duration() {
        let mut timer = StageTimer::new();
        timer.time("sleep", || {
            std::thread::sleep(std::time::Duration::from_millis(5))
        });
        assert!(timer.timings()[0].seconds >= 0.004);
    }
}
