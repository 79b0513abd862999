//! `patchflow bench`: the main job on embedded defaults, run by the library's benchmark driver
//! ([`patchflow_eval::run_bench`]); this command only picks the plan and prints.

use std::collections::BTreeMap;
use std::path::PathBuf;

use patchflow_eval::{BenchPlan, Method, MethodMetrics, run_bench};

/// Arguments of `patchflow bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder.
    #[arg(long, default_value = "results/bench")]
    pub out: PathBuf,
    /// A smaller run (three training tracks, fewer samples, pseudo-inputs and folds) for a quick look.
    #[arg(long)]
    pub quick: bool,
}

/// Runs `patchflow bench`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let plan = if args.quick {
        BenchPlan::quick()
    } else {
        BenchPlan::full()
    };
    let outcome = run_bench(&plan, &args.out, &|t| {
        println!("{:>28}: {:7.1} s", t.stage, t.seconds);
    })?;
    print_headline(&outcome.situation_metrics);
    if let Some(occupancy) = &outcome.occupancy {
        crate::occupancy::print_table(occupancy);
    }
    if let Some(all) = outcome.perception.last() {
        println!("\nperception: {}", all.line());
    }
    println!("report: {}", outcome.files.report_md.display());
    Ok(())
}

/// Prints one line per situation: heading and speed RMSE and coverage of the headline methods,
/// from the scores the report files were written with.
fn print_headline(situations: &[(String, BTreeMap<Method, MethodMetrics>)]) {
    let methods = [Method::SpgpHetAll, Method::SpgpAll, Method::Kf, Method::Icp];
    println!(
        "\n{:<12} {}",
        "situation",
        methods.map(|m| format!("{m:>28}")).join("")
    );
    println!(
        "{:<12} {}",
        "",
        methods
            .map(|_| format!("{:>28}", "heading° / speed m/s / cov"))
            .join("")
    );
    for (name, metrics) in situations {
        let cells = methods.map(|m| match metrics.get(&m) {
            Some(x) => format!(
                "{:>28}",
                format!(
                    "{} / {} / {:.2}",
                    x.heading_rmse_deg.map_or("-".into(), |v| format!("{v:.1}")),
                    x.speed_rmse_mps.map_or("-".into(), |v| format!("{v:.2}")),
                    x.coverage
                )
            ),
            None => format!("{:>28}", "-"),
        });
        println!("{:<12} {}", name, cells.join(""));
    }
}
