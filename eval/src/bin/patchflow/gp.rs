//! `patchflow gp fit` and `patchflow gp predict`: Gaussian-process regression on any CSV.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_learn::{GpKind, GpModel, GpParams};

use crate::choices::GpChoice;
use crate::csv_table::{Columns, Table};
use crate::output_guard::{Input, OutputKind, check_output};

/// Arguments of `patchflow gp`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: GpCommand,
}

#[derive(Debug, clap::Subcommand)]
enum GpCommand {
    /// Fit a GP to a CSV with a header: all columns but the last are inputs, the last is the target.
    Fit(FitArgs),
    /// Predict with a fitted model at the inputs of a CSV; writes `mean,var,var_y`.
    Predict(PredictArgs),
}

/// Arguments of `patchflow gp fit`.
#[derive(Debug, clap::Args)]
struct FitArgs {
    /// Training CSV.
    #[arg(long)]
    csv: PathBuf,
    /// Model file to write.
    #[arg(long)]
    out: PathBuf,
    /// `full`, `spgp` or `spgp-het`.
    #[arg(long, value_enum, default_value_t = GpChoice::Spgp)]
    kind: GpChoice,
    /// Number of pseudo-inputs.
    #[arg(long, default_value_t = 100)]
    pseudo: usize,
    /// Optimiser iteration limit.
    #[arg(long, default_value_t = 200)]
    iters: usize,
    /// Seed of the initialisation.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Target column name (default: the last column).
    #[arg(long)]
    target: Option<String>,
    /// Comma-separated column names to leave out of the inputs.
    #[arg(long)]
    ignore: Option<String>,
}

/// Arguments of `patchflow gp predict`.
#[derive(Debug, clap::Args)]
struct PredictArgs {
    /// Model file from `gp fit`.
    #[arg(long)]
    model: PathBuf,
    /// CSV with the model's input columns.
    #[arg(long)]
    csv: PathBuf,
    /// Output CSV (default: standard output).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs `patchflow gp ...`.
pub fn run(args: Args) -> anyhow::Result<()> {
    match args.command {
        GpCommand::Fit(a) => fit(a),
        GpCommand::Predict(a) => predict(a),
    }
}

fn fit(a: FitArgs) -> anyhow::Result<()> {
    check_output(&a.out, OutputKind::File, &[Input::new("--csv", &a.csv)])?;
    let kind: GpKind = a.kind.into();
    let ignore: Vec<String> = a
        .ignore
        .iter()
        .flat_map(|s| s.split(','))
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect();
    let table = Table::read(&a.csv, Columns::AllExcept(&ignore))?;
    let cols = table.inputs_and_target(a.target.as_deref())?;
    let params = GpParams::new(kind)
        .pseudo_inputs(a.pseudo)
        .max_iters(a.iters)
        .seed(a.seed);
    let model = params
        .check()?
        .fit_named(&cols.x, &cols.y, &cols.input_names, &cols.target_name)
        .with_context(|| format!("fitting {}", a.csv.display()))?;
    model.save(&a.out)?;
    let r = model.fit_report();
    eprintln!(
        "{kind}: {} iterations, stopped by {}; wrote {}",
        r.iterations,
        r.stop,
        a.out.display()
    );
    let summary = serde_json::json!({
        "kind": kind.name(), "n": r.n, "d": r.d, "m": r.m, "evals": r.evals, "seconds": r.seconds, "nlml": r.nlml,
    });
    println!("{summary}");
    Ok(())
}

fn predict(a: PredictArgs) -> anyhow::Result<()> {
    if let Some(out) = &a.out {
        let inputs = [Input::new("--model", &a.model), Input::new("--csv", &a.csv)];
        check_output(out, OutputKind::File, &inputs)?;
    }
    let model = GpModel::load(&a.model)?;
    let table = Table::read(&a.csv, Columns::Only(model.input_names()))?;
    let x = table.select(model.input_names())?;
    refuse_astronomical_inputs(&x, model.input_names(), &a.csv)?;
    let prediction = model
        .predict(&x)
        .with_context(|| format!("predicting at {}", a.csv.display()))?;
    let broken = (0..prediction.mean.len()).find(|&i| {
        let (m, v, vy) = (
            prediction.mean[i],
            prediction.var_latent[i],
            prediction.var_y[i],
        );
        !(m.is_finite() && v.is_finite() && vy.is_finite() && v > 0.0 && vy > 0.0)
    });
    if let Some(i) = broken {
        anyhow::bail!(
            "{}: data row {}: the GP gives mean {}, variance {} there: the input is too far from the training data for double precision; no prediction written",
            a.csv.display(),
            i + 1,
            prediction.mean[i],
            prediction.var_latent[i]
        );
    }
    let csv = prediction.to_csv();
    match a.out {
        Some(path) => std::fs::write(&path, csv)
            .with_context(|| format!("{}: cannot write", path.display()))?,
        None => print!("{csv}"),
    }
    Ok(())
}

/// Largest input magnitude a GP is asked about: beyond it squared distances overflow (1e100 squared
/// is 1e200, summed over the columns still finite), and the prediction would be meaningless.
const MAX_GP_INPUT: f64 = 1e100;

/// Refuses a test input that is not finite or beyond [`MAX_GP_INPUT`], naming row and column.
fn refuse_astronomical_inputs(
    x: &nalgebra::DMatrix<f64>,
    names: &[String],
    csv: &std::path::Path,
) -> anyhow::Result<()> {
    for (row, values) in x.row_iter().enumerate() {
        if let Some((col, v)) = values
            .iter()
            .enumerate()
            .find(|(_, v)| !v.is_finite() || v.abs() > MAX_GP_INPUT)
        {
            anyhow::bail!(
                "{}: data row {}: column '{}' = {v:e} is beyond ±{MAX_GP_INPUT:e}, where a GP's distances overflow; no prediction written",
                csv.display(),
                row + 1,
                names.get(col).map_or("?", String::as_str)
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gp_fit_then_predict_writes_mean_var_and_var_y_for_every_row() {
        let dir = tempfile::tempdir().expect("temp dir");
        let train = dir.path().join("train.csv");
        let mut text = String::from("x,tag,y\n");
        for i in 0..30 {
            let x = i as f64 * 0.3;
            text.push_str(&format!("{x},t{i},{}\n", x.sin()));
        }
        std::fs::write(&train, text).expect("writes");
        let test = dir.path().join("test.csv");
        std::fs::write(&test, "y,x\n0,1.0\n0,2.5\n").expect("writes");
        let (model, out) = (dir.path().join("m.json"), dir.path().join("p.csv"));
        let fit_args = |ignore: Option<&str>| FitArgs {
            csv: train.clone(),
            out: model.clone(),
            kind: GpChoice::SpgpHet,
            pseudo: 5,
            iters: 20,
            seed: 1,
            target: None,
            ignore: ignore.map(String::from),
        };
        let err = fit(fit_args(None)).expect_err("a text column must be ignored explicitly");
        assert!(format!("{err:#}").contains("train.csv"));
        fit(fit_args(Some("tag"))).expect("fits");
        predict(PredictArgs {
            model: model.clone(),
            csv: test,
            out: Some(out.clone()),
        })
        .expect("predicts");
        let lines: Vec<String> = std::fs::read_to_string(&out)
            .expect("reads")
            .lines()
            .map(String::from)
            .collect();
        assert_eq!(lines[0], "mean,var,var_y");
        assert_eq!(lines.len(), 3);
        let mean: f64 = lines[1]
            .split(',')
            .next()
            .and_then(|v| v.parse().ok())
            .expect("a number");
        assert!((mean - 1f64.sin()).abs() < 0.1, "mean {mean}");
    }

    fn fit_args(csv: PathBuf, out: PathBuf) -> FitArgs {
        FitArgs {
            csv,
            out,
            kind: GpChoice::Spgp,
            pseudo: 4,
            iters: 15,
            seed: 3,
            target: None,
            ignore: None,
        }
    }

    fn write_csv(dir: &std::path::Path, name: &str, rows: usize, huge: bool) -> PathBuf {
        let path = dir.join(name);
        let mut text = String::from("a,b,y\n");
        for i in 0..rows {
            let a = if huge && i == 3 {
                1e300
            } else {
                i as f64 * 0.2
            };
            text.push_str(&format!(
                "{a},{},{}\n",
                (i % 5) as f64,
                (i as f64 * 0.2).cos()
            ));
        }
        std::fs::write(&path, text).expect("writes");
        path
    }

    #[test]
    fn gp_fit_and_predict_refuse_to_write_over_their_input_and_leave_it_intact() {
        let dir = tempfile::tempdir().expect("temp dir");
        let csv = write_csv(dir.path(), "x.csv", 25, false);
        let before = std::fs::read(&csv).expect("reads");
        let err = fit(fit_args(csv.clone(), csv.clone())).expect_err("out is the input");
        assert!(err.to_string().contains("is the input --csv"), "{err}");
        assert_eq!(std::fs::read(&csv).expect("reads"), before);
        let model = dir.path().join("m.json");
        fit(fit_args(csv.clone(), model.clone())).expect("fits");
        let model_bytes = std::fs::read(&model).expect("reads");
        let err = predict(PredictArgs {
            model: model.clone(),
            csv,
            out: Some(model.clone()),
        })
        .expect_err("out is the model");
        assert!(err.to_string().contains("is the input --model"), "{err}");
        assert_eq!(std::fs::read(&model).expect("reads"), model_bytes);
    }

    #[test]
    fn gp_fit_run_twice_writes_byte_identical_model_files() {
        let dir = tempfile::tempdir().expect("temp dir");
        let csv = write_csv(dir.path(), "train.csv", 25, false);
        let (a, b) = (dir.path().join("a.json"), dir.path().join("b.json"));
        fit(fit_args(csv.clone(), a.clone())).expect("fits");
        fit(fit_args(csv, b.clone())).expect("fits");
        assert_eq!(
            std::fs::read(a).expect("reads"),
            std::fs::read(b).expect("reads")
        );
    }

    #[test]
    fn gp_fit_refuses_a_cell_too_large_to_standardise_naming_the_file() {
        let dir = tempfile::tempdir().expect("temp dir");
        let csv = write_csv(dir.path(), "huge.csv", 25, true);
        let out = dir.path().join("m.json");
        let err = fit(fit_args(csv, out.clone())).expect_err("1e300 cell");
        let msg = format!("{err:#}");
        assert!(msg.contains("huge.csv") && msg.contains("'a'"), "{msg}");
        assert!(!out.exists(), "no model file on error");
    }

    #[test]
    fn gp_predict_refuses_inputs_far_beyond_double_precision_instead_of_variance_zero() {
        let dir = tempfile::tempdir().expect("temp dir");
        let csv = write_csv(dir.path(), "train.csv", 25, false);
        let model = dir.path().join("m.json");
        fit(FitArgs {
            kind: GpChoice::Full,
            ..fit_args(csv, model.clone())
        })
        .expect("fits");
        let test = dir.path().join("far.csv");
        std::fs::write(&test, "a,b\n1,1\n1e308,0\n").expect("writes");
        let out = dir.path().join("p.csv");
        let err = predict(PredictArgs {
            model,
            csv: test,
            out: Some(out.clone()),
        })
        .expect_err("1e308 is refused");
        let msg = err.to_string();
        assert!(
            msg.contains("far.csv: data row 2") && msg.contains("'a'"),
            "{msg}"
        );
        assert!(!out.exists());
    }
}
