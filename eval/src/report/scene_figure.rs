//! Pictures of a scene, so a reader sees what the target did: a bird's-eye view of the whole
//! sequence (static structures, the ego path, every actor's path with the target highlighted,
//! range rings around the ego car at the chosen sweep) and a top-down view of that sweep's point
//! cloud coloured by class, moving points by their true flow direction (`report/cloud_view.rs`).
//! Both in the world frame, metres on equal axes, with a title and a key beside the picture.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use patchflow_dataset::{ObjectTruth, SequenceReader};
use plotters::prelude::*;

use crate::error::EvalError;
use crate::report::birds_eye::draw_birds_eye;
use crate::report::cloud_view::draw_cloud;
use crate::report::font::{FONT, ensure_font};
use crate::report::png_file::PngFile;
use crate::report::world_chart::{ActorPath, Area, DrawResult, RINGS_M, WorldChart};

/// Canvas of a scene figure: the square picture and the key panel.
pub(crate) const SCENE_PX: (u32, u32) = (1100, 860);
/// Width of the key panel.
pub(crate) const KEY_PX: u32 = 250;
/// The two figures of one sequence written by [`write_scene_figures`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneFigures {
    /// Bird's-eye view of the sequence (the report's `<name>_scene.png`).
    pub birds_eye: PathBuf,
    /// The chosen sweep's points from above (the report's `<name>_cloud.png`).
    pub cloud: PathBuf,
    /// The sweep both figures show.
    pub sweep: usize,
}

/// Writes the bird's-eye view of a sequence to `birds_eye` and the point cloud to `cloud`, at
/// `sweep` or (none given) at the sweep where the target, or else any moving actor, shows the
/// most points.
pub fn write_scene_figures(
    sequence: &SequenceReader,
    sweep: Option<usize>,
    birds_eye: &Path,
    cloud: &Path,
) -> Result<SceneFigures, EvalError> {
    let name = sequence.info().name.clone();
    // The actors of every sweep from its object truth alone (SPEC §4 `objects/NNNNNN.json`);
    // only the sweep shown is read whole.
    let objects: Vec<Vec<ObjectTruth>> = (0..sequence.len())
        .map(|i| read_objects(sequence.dir(), i))
        .collect::<Result<_, _>>()?;
    let chosen = match sweep {
        Some(i) if i < objects.len() => i,
        Some(i) => {
            return Err(EvalError::BadParameter {
                name: "sweep",
                reason: format!("{name} has {} sweeps, no sweep {i}", objects.len()),
            });
        }
        None => busiest_sweep(&objects),
    };
    if objects.is_empty() {
        return Err(EvalError::BadResult {
            situation: name,
            reason: "the sequence has no sweep".into(),
        });
    }
    let shown = sequence.read_sweep(chosen)?;
    let structures = sequence.static_obstacles()?;
    let figures = SceneFigures {
        birds_eye: birds_eye.to_owned(),
        cloud: cloud.to_owned(),
        sweep: chosen,
    };
    let paths = actor_paths(&objects);
    let ego: Vec<(f64, f64)> = sequence
        .poses()
        .iter()
        .map(|p| (p.translation.x, p.translation.y))
        .collect();
    let view = View::around(
        ego.iter()
            .chain(paths.values().flat_map(|p| p.points.iter())),
    );
    let title = format!(
        "{name}: bird's-eye view of {} sweeps (boxes and rings at sweep {chosen}, t = {:.1} s)",
        objects.len(),
        shown.stamp_secs
    );
    draw_figure(&figures.birds_eye, &title, &view, |chart, key| {
        draw_birds_eye(chart, key, &structures, &ego, &paths, &shown)
    })?;
    let ego_xy = (
        shown.world_from_sensor.translation.x,
        shown.world_from_sensor.translation.y,
    );
    let cloud_view = View::square((ego_xy.0, ego_xy.1), RINGS_M[2] + 10.0);
    let title = format!("{name}: sweep {chosen} from above, points by class and flow direction");
    draw_figure(&figures.cloud, &title, &cloud_view, |chart, key| {
        draw_cloud(chart, key, &shown, &structures)
    })?;
    Ok(figures)
}

/// Writes the scene figures of the named sequences of `dataset` into `dir` (in parallel);
/// sequence name → the sweep shown, for [`crate::BenchmarkReport::scene_figures`].
pub fn write_dataset_scene_figures(
    dataset: &patchflow_dataset::Dataset,
    names: &[String],
    dir: &Path,
) -> Result<BTreeMap<String, usize>, EvalError> {
    use rayon::prelude::*;
    crate::report::create_dir(dir)?;
    names
        .par_iter()
        .map(|name| {
            let (birds_eye, cloud) = (
                dir.join(format!("{name}_scene.png")),
                dir.join(format!("{name}_cloud.png")),
            );
            let figures = write_scene_figures(&dataset.sequence(name)?, None, &birds_eye, &cloud)?;
            Ok((name.clone(), figures.sweep))
        })
        .collect()
}

/// The object truth of sweep `index` of the sequence in `dir`.
fn read_objects(dir: &Path, index: usize) -> Result<Vec<ObjectTruth>, EvalError> {
    let path = dir.join("objects").join(format!("{index:06}.json"));
    let bytes = std::fs::read(&path).map_err(|e| EvalError::io(&path, e))?;
    serde_json::from_slice(&bytes).map_err(|source| EvalError::Json { path, source })
}

/// The sweep where the target (or else any moving actor) has the most points.
fn busiest_sweep(objects: &[Vec<ObjectTruth>]) -> usize {
    let points = |objects: &Vec<ObjectTruth>| {
        let target = objects.iter().find(|o| o.target).map(|t| t.point_count);
        target.unwrap_or_else(|| {
            objects
                .iter()
                .filter(|o| o.moving)
                .map(|o| o.point_count)
                .sum()
        })
    };
    let best = objects
        .iter()
        .enumerate()
        .max_by_key(|(i, o)| (points(o), usize::MAX - i));
    best.map_or(0, |(i, _)| i)
}

fn actor_paths(objects: &[Vec<ObjectTruth>]) -> BTreeMap<u16, ActorPath> {
    let mut paths: BTreeMap<u16, ActorPath> = BTreeMap::new();
    for sweep in objects {
        for o in sweep {
            let path = paths.entry(o.id).or_insert(ActorPath {
                target: o.target,
                points: Vec::new(),
            });
            path.points.push((o.centre_m[0], o.centre_m[1]));
        }
    }
    paths
}

/// A square window of the world, metres.
pub(crate) struct View {
    /// World x range, metres.
    pub x: std::ops::Range<f64>,
    /// World y range, metres.
    pub y: std::ops::Range<f64>,
}

impl View {
    /// The square around `points` with a margin.
    fn around<'a>(points: impl Iterator<Item = &'a (f64, f64)>) -> Self {
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for &(x, y) in points {
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        }
        if !lo.0.is_finite() {
            return Self::square((0.0, 0.0), 50.0);
        }
        let half = ((hi.0 - lo.0).max(hi.1 - lo.1) / 2.0 + 15.0).max(RINGS_M[2] + 5.0);
        Self::square(((lo.0 + hi.0) / 2.0, (lo.1 + hi.1) / 2.0), half)
    }

    /// The square of half-width `half` around `centre`.
    pub(crate) fn square(centre: (f64, f64), half: f64) -> Self {
        Self {
            x: centre.0 - half..centre.0 + half,
            y: centre.1 - half..centre.1 + half,
        }
    }
}

/// A titled figure: a square chart in world metres and a key panel, filled by `fill`.
pub(crate) fn draw_figure(
    path: &Path,
    title: &str,
    view: &View,
    fill: impl FnOnce(&mut WorldChart<'_>, &Area<'_>) -> DrawResult,
) -> Result<(), EvalError> {
    ensure_font(path)?;
    let plot_err = |e: &dyn std::fmt::Display| EvalError::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    };
    let png = PngFile::new(path);
    let png_path = png.drawing_path().to_path_buf();
    let root = BitMapBackend::new(&png_path, SCENE_PX).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_err(&e))?;
    let root = root.titled(title, (FONT, 20)).map_err(|e| plot_err(&e))?;
    let (left, key) = root.split_horizontally(SCENE_PX.0 - KEY_PX);
    let mut chart = ChartBuilder::on(&left)
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(view.x.clone(), view.y.clone())
        .map_err(|e| plot_err(&e))?;
    chart
        .configure_mesh()
        .x_desc("x (m, world frame)")
        .y_desc("y (m, world frame)")
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .light_line_style(RGBColor(250, 250, 250))
        .draw()
        .map_err(|e| plot_err(&e))?;
    fill(&mut chart, &key).map_err(|e| plot_err(&e))?;
    root.present().map_err(|e| plot_err(&e))?;
    png.commit()
}
