//! `patchflow bench`: the main job on embedded defaults, run by the library's benchmark driver
//! ([`patchflow_eval::run_bench`]); this command only picks the plan and prints.

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::output_guard::{OutputKind, check_output};
use patchflow_eval::{BenchPlan, Method, MethodMetrics, SeedSpread, run_bench};

/// Arguments of `patchflow bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder.
    #[arg(long, default_value = "results/bench")]
    pub out: PathBuf,
    /// A smaller run for a quick look, under 2 minutes on 2 cores: the five situations without
    /// the dense scene, the last third of every training track's sweeps, SPGP-HET only, fewer
    /// samples, pseudo-inputs and folds, one training seed, a shorter realism study and fewer
    /// occupancy query times.
    #[arg(long)]
    pub quick: bool,
    /// Training seeds (7, 8, …): the report gives each headline figure's mean ± std over them
    /// [default: 3, with --quick 1].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=20))]
    pub seeds: Option<u64>,
    /// Keep the generated datasets under OUT/data (about 7 GB) instead of deleting each once used.
    #[arg(long)]
    pub keep_data: bool,
}

/// Runs `patchflow bench`.
pub fn run(args: Args) -> anyhow::Result<()> {
    check_output(&args.out, OutputKind::Folder, &[])?;
    let mut plan = if args.quick {
        BenchPlan::quick()
    } else {
        BenchPlan::full()
    };
    if let Some(seeds) = args.seeds {
        plan.seeds = seeds as usize;
    }
    plan.keep_data = args.keep_data;
    // Every stage's start and end is printed to stderr by the driver.
    let outcome = run_bench(&plan, &args.out, &|_| {})?;
    print_headline(&outcome.situation_metrics, &outcome.spread);
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
/// the GPs' as mean ± std over the training seeds when there are several, from the scores the
/// report files were written with.
fn print_headline(situations: &[(String, BTreeMap<Method, MethodMetrics>)], spread: &SeedSpread) {
    // The headline methods the run has (`--quick` trains SPGP-HET only).
    let methods: Vec<Method> = [Method::SpgpHetAll, Method::SpgpAll, Method::Kf, Method::Icp]
        .into_iter()
        .filter(|m| {
            situations
                .iter()
                .any(|(_, metrics)| metrics.contains_key(m))
        })
        .collect();
    let row =
        |cell: &dyn Fn(Method) -> String| methods.iter().map(|&m| cell(m)).collect::<String>();
    println!("\n{:<12} {}", "situation", row(&|m| format!("{m:>40}")));
    println!(
        "{:<12} {}",
        "",
        row(&|_| format!("{:>40}", "heading° / speed m/s / cov"))
    );
    for (name, metrics) in situations {
        let spread_of = |m: &Method| {
            let (_, methods) = spread.situations.iter().find(|(n, _)| n == name)?;
            methods.get(m).filter(|s| s.heading_rmse_deg.std.is_some())
        };
        let cells = row(&|m| match (spread_of(&m), metrics.get(&m)) {
            (Some(s), _) => format!(
                "{:>40}",
                format!(
                    "{} / {} / {}",
                    s.heading_rmse_deg.cell(1),
                    s.speed_rmse_mps.cell(2),
                    s.coverage.cell(2)
                )
            ),
            (None, Some(x)) => format!(
                "{:>40}",
                format!(
                    "{} / {} / {:.2}",
                    x.heading_rmse_deg.map_or("-".into(), |v| format!("{v:.1}")),
                    x.speed_rmse_mps.map_or("-".into(), |v| format!("{v:.2}")),
                    x.coverage
                )
            ),
            (None, None) => format!("{:>40}", "-"),
        });
        println!("{:<12} {}", name, cells);
    }
}
