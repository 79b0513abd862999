//! `patchflow show`: one sweep's reflection and difference maps with clusters, true boxes and
//! colour keys (`FILE.png`), and beside it the sequence's bird's-eye view (`FILE_scene.png`) and
//! the sweep's point cloud from above (`FILE_cloud.png`), all on world metre axes with a key.

use std::path::PathBuf;

use anyhow::Context;
use patchflow_dataset::Dataset;
use patchflow_eval::{write_map_figure, write_scene_figures};
use patchflow_learn::{EstimatorParams, SweepFeatures};

use crate::output_guard::{Input, OutputKind, check_output};

/// Figure formats `show` writes, by the extension of `--out`.
const FIGURE_EXTENSIONS: [&str; 1] = ["png"];

/// Arguments of `patchflow show`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Dataset folder.
    #[arg(long)]
    pub data: PathBuf,
    /// Sequence name (default: the first one).
    #[arg(long)]
    pub sequence: Option<String>,
    /// Sweep index (must be at least 1: the difference needs the previous sweep).
    #[arg(long, default_value_t = 1)]
    pub scan: usize,
    /// PNG file of the maps; the scene and point-cloud views go beside it (`_scene`, `_cloud`).
    #[arg(long)]
    pub out: PathBuf,
}

/// Runs `patchflow show`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if args.scan == 0 {
        anyhow::bail!("--scan must be at least 1: the difference map needs the previous sweep");
    }
    let extension = args.out.extension().and_then(|e| e.to_str());
    if !extension.is_some_and(|e| FIGURE_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str())) {
        anyhow::bail!(
            "--out {}: unknown figure format {:?}; the file name must end in one of: {}",
            args.out.display(),
            extension.unwrap_or(""),
            FIGURE_EXTENSIONS.map(|e| format!(".{e}")).join(", ")
        );
    }
    let beside = |suffix: &str| {
        let stem = args
            .out
            .file_stem()
            .map_or_else(|| "show".into(), |s| s.to_string_lossy());
        args.out.with_file_name(format!("{stem}_{suffix}.png"))
    };
    let data = [Input::new("--data", &args.data)];
    for out in [args.out.clone(), beside("scene"), beside("cloud")] {
        check_output(&out, OutputKind::File, &data)?;
    }
    if let Some(name) = args.sequence.as_ref().filter(|n| !is_plain_name(n)) {
        anyhow::bail!(
            "--sequence {name:?}: a sequence is named by its folder under sequences/, without '/', '..' or a leading '.'"
        );
    }
    let dataset = Dataset::open(&args.data)?;
    let name = match &args.sequence {
        Some(name) => name.clone(),
        None => dataset
            .sequences()
            .first()
            .map(|s| s.name.clone())
            .with_context(|| format!("{}: no sequence", args.data.display()))?,
    };
    let sequence = dataset.sequence(&name)?;
    if args.scan >= sequence.len() {
        anyhow::bail!(
            "--scan {}: sequence {name} of {} has {} sweeps (0 to {})",
            args.scan,
            args.data.display(),
            sequence.len(),
            sequence.len().saturating_sub(1)
        );
    }
    let prev = sequence.read_sweep(args.scan - 1)?;
    let curr = sequence.read_sweep(args.scan)?;
    // The maps and clusters the default estimator reads (its height slice).
    let features = SweepFeatures::compute(&prev, &curr, &EstimatorParams::default().features)
        .with_context(|| format!("{}: sweep {}", sequence.dir().display(), args.scan))?;
    let title = format!(
        "{name}, sweep {} (t = {:.1} s): {} sliced points in {} clusters",
        args.scan,
        curr.stamp_secs,
        features.len(),
        features.clusters().len()
    );
    // The figure's folder is made as `bench` and `evaluate` make their output folders.
    if let Some(folder) = args.out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder)
            .with_context(|| format!("{}: cannot create the folder", folder.display()))?;
    }
    write_map_figure(&features, &curr, &title, &args.out)?;
    let figures = write_scene_figures(
        &sequence,
        Some(args.scan),
        &beside("scene"),
        &beside("cloud"),
    )?;
    println!(
        "wrote {}, {} and {}",
        args.out.display(),
        figures.birds_eye.display(),
        figures.cloud.display()
    );
    Ok(())
}

/// True for a single folder name: not empty, no separator, not `.`/`..` or hidden.
fn is_plain_name(name: &str) -> bool {
    !name.is_empty() && !name.starts_with('.') && !name.contains(['/', '\\', '\0'])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(data: PathBuf, sequence: Option<&str>, out: PathBuf) -> Args {
        Args {
            data,
            sequence: sequence.map(String::from),
            scan: 1,
            out,
        }
    }

    #[test]
    fn an_unknown_figure_extension_is_refused_listing_the_allowed_ones() {
        let dir = tempfile::tempdir().expect("temp dir");
        let err = run(args(dir.path().join("D"), None, dir.path().join("f.gif")))
            .expect_err("gif is not written");
        let msg = err.to_string();
        assert!(msg.contains("\"gif\"") && msg.contains(".png"), "{msg}");
    }

    #[test]
    fn a_sequence_name_that_climbs_out_of_the_dataset_is_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let data = dir.path().join("D");
        let out = dir.path().join("f.png");
        let err = run(args(data, Some("../../etc"), out)).expect_err("refused");
        assert!(err.to_string().contains("without '/'"), "{err}");
    }

    #[test]
    fn a_figure_inside_the_dataset_is_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let data = dir.path().join("D");
        std::fs::create_dir_all(&data).expect("mkdir");
        let err = run(args(data.clone(), None, data.join("f.png"))).expect_err("refused");
        assert!(
            err.to_string().contains("lies inside the input --data"),
            "{err}"
        );
    }
}
