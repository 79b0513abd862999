//! The merge step of a study: every point's file (written by one run or by many shards) read
//! back in sorted order into `study.json`, with `study.md` and one plot per measure beside it.
//! `study.json` is built from the point files alone, so its bytes do not depend on the sharding.

use std::path::{Path, PathBuf};

use crate::error::EvalError;
use crate::report::{create_dir, write_atomic, write_json_atomic};
use crate::study::markdown::study_markdown;
use crate::study::plan::StudyPlan;
use crate::study::plan_stamp::PlanStamp;
use crate::study::plot::plot_study;
use crate::study::point_result::{POINT_BINS, PointResult};
use crate::study::study_report::{PointFile, StudyReport, point_file};

/// The files a merged study wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyFiles {
    /// `OUT/study.json`.
    pub study_json: PathBuf,
    /// `OUT/study.md`.
    pub study_md: PathBuf,
    /// `OUT/plots/study_*.png`.
    pub plots: Vec<PathBuf>,
}

/// Reads every point of `plan` from `out/points/` and writes the study's files into `out`; a
/// missing point is an error naming its file (a shard not yet run), and so is a point run with
/// another plan (another seed, `--quick` or not), naming what differs.
pub fn merge_study(plan: &StudyPlan, out: &Path) -> Result<StudyFiles, EvalError> {
    let stamp = PlanStamp::of(plan);
    let points = plan
        .points
        .iter()
        .map(|p| read_point(&point_file(out, p.index), p.index, &stamp))
        .collect::<Result<Vec<_>, _>>()?;
    let report = StudyReport {
        study: plan.factor.name().to_owned(),
        unit: plan.factor.unit().to_owned(),
        seed: plan.seed,
        samples: plan.samples,
        pseudo_inputs: plan.pseudo_inputs,
        max_iters: plan.max_iters,
        point_bins: POINT_BINS.iter().map(|(l, _)| (*l).to_owned()).collect(),
        points,
    };
    write_study(&report, out)
}

/// Writes `study.json`, `study.md` and the plots of a study into `out`.
pub fn write_study(report: &StudyReport, out: &Path) -> Result<StudyFiles, EvalError> {
    create_dir(out)?;
    let study_json = out.join("study.json");
    write_json_atomic(&study_json, report)?;
    let plots = plot_study(report, &out.join("plots"))?;
    let study_md = out.join("study.md");
    write_atomic(&study_md, study_markdown(report).as_bytes())?;
    Ok(StudyFiles {
        study_json,
        study_md,
        plots,
    })
}

fn read_point(path: &Path, index: usize, stamp: &PlanStamp) -> Result<PointResult, EvalError> {
    let bytes = std::fs::read(path).map_err(|e| EvalError::io(path, e))?;
    let file: PointFile = serde_json::from_slice(&bytes).map_err(|source| EvalError::Json {
        path: path.to_owned(),
        source,
    })?;
    let differences = stamp.differences(&file.plan);
    if !differences.is_empty() {
        return Err(EvalError::BadFile {
            path: path.to_owned(),
            reason: format!(
                "was run with another plan than this merge's ({}); merge with the flags the \
                 shards ran with (`--quick`, `--seed`)",
                differences.join("; ")
            ),
        });
    }
    let point = file.result;
    if point.index != index {
        return Err(EvalError::BadFile {
            path: path.to_owned(),
            reason: format!("holds point {} where point {index} belongs", point.index),
        });
    }
    Ok(point)
}
