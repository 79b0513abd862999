//! `patchflow occupancy`: occupancy maps of every planar scanner's sequence in a dataset (the
//! DGPOM paper's protocol: query times t = 3 … 9, each map from the scan then and the three before),
//! scored by ROC AUC against exact truth; writes `occupancy.json`, `occupancy.md` and
//! `plots/occupancy_*.png`.

use patchflow_dataset::Dataset;
use patchflow_eval::stages::occupancy_with_bar;
use patchflow_eval::{OccupancyReport, write_occupancy_report};
use patchflow_occupancy::{AheadParams, OccupancyParams};

use crate::common::DataAndReport;

/// Arguments of `patchflow occupancy`.
#[derive(Debug, clap::Args)]
#[command(mut_arg("data", |a| a.help(
    "Dataset folder holding planar-scanner sequences (e.g. `generate dgpom_tjunction`)"
)))]
pub struct Args {
    #[command(flatten)]
    pub io: DataAndReport,
    /// Seed of the free-space samples drawn along the beams.
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
}

/// Runs `patchflow occupancy`.
pub fn run(args: Args) -> anyhow::Result<()> {
    args.io.check_output(&[])?;
    let dataset = Dataset::open(&args.io.data)?;
    let report = occupancy_with_bar(
        &dataset,
        args.seed,
        &OccupancyParams::default(),
        &AheadParams::default(),
    )?;
    let files = write_occupancy_report(&report, &args.io.out)?;
    print_table(&report);
    println!(
        "wrote {} and {} plots",
        files.markdown.display(),
        files.plots.len()
    );
    Ok(())
}

/// One line per scenario and method: AUC at each query time and seconds per map.
pub fn print_table(report: &OccupancyReport) {
    for scores in &report.scenarios {
        println!("{}:", scores.name);
        for (method, m) in &scores.methods {
            let aucs: Vec<String> = m
                .auc_by_query_scan
                .values()
                .map(|a| a.map_or("  –   ".into(), |v| format!("{v:.4}")))
                .collect();
            println!(
                "  {method:>9}  AUC {}  {:.3} s/map, {:.0} training points ({:.0} drawn)",
                aucs.join(" "),
                m.mean_seconds_per_map(),
                m.mean_training_points(),
                m.mean_drawn_points()
            );
        }
    }
}
