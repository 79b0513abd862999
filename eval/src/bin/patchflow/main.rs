//! The `patchflow` command: one subcommand per job of SPEC §7. Each subcommand parses its
//! arguments, calls one library function and prints; no algorithm lives here.

mod bench;
mod check;
mod choices;
mod common;
mod csv_table;
mod cv;
mod evaluate;
mod features;
mod flow;
mod generate;
mod gp;
mod occupancy;
mod output_guard;
mod score;
mod show;
mod study;
mod train;

use clap::{Parser, Subcommand};

/// Simulated lidar traffic, difference-map patches and sparse heteroscedastic GPs for motion estimation.
#[derive(Debug, Parser)]
#[command(name = "patchflow", version, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Simulate scenarios and write a labelled dataset (SemanticKITTI layout plus motion truth).
    Generate(generate::Args),
    /// Extract importance-sampled patch or Gabor features with motion targets to a CSV.
    Features(features::Args),
    /// Draw one sweep's reflection and difference maps with clusters and true boxes to a PNG.
    Show(show::Args),
    /// Train the motion estimator (heading and speed GPs) on a dataset.
    Train(train::Args),
    /// Run every method on the five situations of a dataset and write metrics, tables and plots.
    Evaluate(evaluate::Args),
    /// K-fold cross-validation tables after thesis Tables 4.1 to 4.4.
    Cv(cv::Args),
    /// Export a trained estimator's per-point scene flow beside a dataset's layout.
    Flow(flow::Args),
    /// Score prediction folders of any method (the layout `flow` writes) beside the built-in methods.
    Score(score::Args),
    /// The main job: generate, train, cross-validate and evaluate on embedded defaults.
    Bench(bench::Args),
    /// A study: one factor (realism rung, lidar rate, channels, patch-map cell size) varied, every method scored at each point.
    Study(study::Args),
    /// Occupancy maps (grid, GPOM) of planar-scanner sequences, scored by ROC AUC against exact truth.
    Occupancy(occupancy::Args),
    /// Read trained models on targets of your own scenarios over several world draws, against the bar.
    Check(check::Args),
    /// Gaussian-process regression on any CSV.
    Gp(gp::Args),
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Generate(args) => generate::run(args),
        Command::Features(args) => features::run(args),
        Command::Show(args) => show::run(args),
        Command::Train(args) => train::run(args),
        Command::Evaluate(args) => evaluate::run(args),
        Command::Cv(args) => cv::run(args),
        Command::Flow(args) => flow::run(args),
        Command::Score(args) => score::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Study(args) => study::run(args),
        Command::Occupancy(args) => occupancy::run(args),
        Command::Check(args) => check::run(args),
        Command::Gp(args) => gp::run(args),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {}", error_chain(&err));
            std::process::ExitCode::FAILURE
        }
    }
}

/// The error and its causes joined by ": ", leaving out a cause whose text the message already
/// holds (library errors include their I/O cause in their own text, so `{:#}` would repeat it).
fn error_chain(err: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    message
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cause_already_in_the_message_is_printed_once() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "No such file");
        let err = anyhow::Error::new(io)
            .context("data.csv: No such file")
            .context("reading the table");
        assert_eq!(
            error_chain(&err),
            "reading the table: data.csv: No such file"
        );
    }
}
