//! `patchflow occupancy`: occupancy maps of every planar scanner's sequence in a dataset (the
//! DGPOM paper's protocol: query times t = 3 … 9, each map from the scan then and the three before),
//! scored by ROC AUC against exact truth; writes `occupancy.json`, `occupancy.md` and
//! `plots/occupancy_*.png`.

use std::path::PathBuf;

use patchflow_dataset::Dataset;
use patchflow_eval::{
    OccupancyReport, evaluate_occupancy, occupancy_methods, occupancy_notes, occupancy_sequences,
    progress_bar, write_occupancy_report,
};
use patchflow_occupancy::{OccupancyParams, OccupancySequence};

/// Arguments of `patchflow occupancy`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder holding planar-scanner sequences (e.g. `generate dgpom_tjunction`).
    #[arg(long)]
    pub data: PathBuf,
    /// Report folder to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Seed of the free-space samples drawn along the beams.
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
}

/// Runs `patchflow occupancy`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let dataset = Dataset::open(&args.data)?;
    let report = occupancy_with_bar(&dataset, args.seed)?;
    let files = write_occupancy_report(&report, &args.out)?;
    print_table(&report);
    println!(
        "wrote {} and {} plots",
        files.markdown.display(),
        files.plots.len()
    );
    Ok(())
}

/// Scores every method on the dataset's planar sequences with a progress bar over the maps;
/// `bench` uses it too.
pub fn occupancy_with_bar(dataset: &Dataset, seed: u64) -> anyhow::Result<OccupancyReport> {
    let params = OccupancyParams::default();
    let methods_per_scenario = occupancy_methods(seed).len();
    let maps =
        occupancy_sequences(dataset)?.len() * params.query_scans.len() * methods_per_scenario;
    let bar = progress_bar(maps as u64, "occupancy maps");
    let methods_for =
        |_: &OccupancySequence, _: Option<&OccupancySequence>| Ok(occupancy_methods(seed));
    let report = evaluate_occupancy(dataset, &methods_for, &params, seed, &|_, _, _| bar.inc(1));
    bar.finish_and_clear();
    let mut report = report?;
    report.notes = occupancy_notes(&params);
    Ok(report)
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
                "  {method:>9}  AUC {}  {:.3} s/map, {:.0} training points",
                aucs.join(" "),
                m.mean_seconds_per_map(),
                m.mean_training_points()
            );
        }
    }
}
