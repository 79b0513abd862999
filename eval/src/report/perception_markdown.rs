//! The perception section of `report.md`: per sequence the whole-scan time (median and worst),
//! and every stage over all scans (SPEC §8: a whole scan under 100 ms on 2 cores).

use std::fmt::Write as _;

use crate::report::perception_summary::PerceptionSummary;

/// Writes the perception section (nothing without timed scans).
pub(crate) fn perception_section(md: &mut String, summaries: &[PerceptionSummary]) {
    let Some(all) = summaries.last().filter(|a| a.scans > 0) else {
        return;
    };
    let ms = |s: f64| s * 1e3;
    // Writing to a String cannot fail, so the `fmt::Result`s below are ignored.
    let _ = writeln!(md, "## Perception per scan\n");
    let _ = writeln!(
        md,
        "Scans run one after the other, in order, each using every core; its wall time is its \
         latency. The whole scan is the height slice of the new sweep, reflection and difference \
         maps beside the clusters, then per estimator the object hypotheses with their map cells, \
         patches, GP predictions and merging, for every hypothesis (SPEC §8: under 100 ms on 2 \
         cores, the sensor's 10 Hz). The thesis-protocol estimate of the target from all its \
         points (the per-target tables) is timed apart; it is not part of the whole scan. Times \
         in ms, median / worst scan. The CPU column adds up the time every thread of the whole \
         scan spent on a CPU: on a machine shared with other work the wall times grow with its \
         load, the CPU time hardly, and CPU time over the cores is the scan's latency on idle \
         cores with perfect parallelism.\n"
    );
    let _ = writeln!(
        md,
        "| Sequence | scans | whole scan, {} estimators | its CPU time | one estimator | map-cell samples / hypothesis points (median) | baselines | target from all its points (mean points) |\n|---|---|---|---|---|---|---|---|",
        all.estimators
    );
    for s in summaries {
        let target = match s.mean_target_points {
            Some(points) => format!(
                "{:.1} / {:.1} ({points:.0})",
                ms(s.target.median_secs),
                ms(s.target.worst_secs)
            ),
            None => "–".into(),
        };
        let cpu = s.whole_scan_cpu.map_or("–".into(), |c| {
            format!("{:.1} / {:.1}", ms(c.median_secs), ms(c.worst_secs))
        });
        let _ = writeln!(
            md,
            "| {} | {} | {:.1} / {:.1} | {cpu} | {:.1} / {:.1} | {:.0} / {:.0} | {:.1} / {:.1} | {target} |",
            s.name,
            s.scans,
            ms(s.whole_scan().median_secs),
            ms(s.whole_scan().worst_secs),
            ms(s.one_estimator.median_secs),
            ms(s.one_estimator.worst_secs),
            s.median_samples,
            s.median_points,
            ms(s.baselines.median_secs),
            ms(s.baselines.worst_secs),
        );
    }
    let _ = writeln!(
        md,
        "\n#### Stages over all {} scans (estimator stages summed over the estimators)\n\n| Stage | median (ms) | worst (ms) |\n|---|---|---|",
        all.scans
    );
    for (stage, spread) in &all.stages {
        let _ = writeln!(
            md,
            "| {stage} | {:.1} | {:.1} |",
            ms(spread.median_secs),
            ms(spread.worst_secs)
        );
    }
    let learned = [
        ("moving classifier (segmentation)", all.segmentation),
        ("GP-KF, every cluster", all.gp_kf),
        ("GP-ICP, the hypotheses", all.gp_icp),
        (
            "whole learned scan: one estimator, segmentation, GP-KF, GP-ICP",
            all.learned_scan,
        ),
    ];
    let cpu = all
        .learned_scan_cpu
        .map(|c| ("whole learned scan, its CPU time (all threads)", c));
    for (stage, spread) in learned.into_iter().chain(cpu) {
        let _ = writeln!(
            md,
            "| {stage} | {:.1} | {:.1} |",
            ms(spread.median_secs),
            ms(spread.worst_secs)
        );
    }
    let _ = writeln!(
        md,
        "\nThe whole learned scan (issue 27) is the scan with one estimator (features, its step), \
         the moving classifier with the change evidence it reads, GP-KF and GP-ICP; its bar is \
         100 ms median and 150 ms worst on 2 idle cores, where its CPU time over 2 is the \
         latency with perfect parallelism."
    );
    let _ = writeln!(md);
}
