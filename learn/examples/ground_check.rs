//! How well the per-sweep ground estimate finds the true ground of a generated dataset, and what
//! it changes in the height slice: for every `STEP`-th sweep of every sequence, the height of each
//! ground-labelled return (road, parking, sidewalk, other ground, terrain) above the estimated
//! ground and above the flat z = 0, within the map window; how many returns of the ground, of
//! actors and of everything else fall in the 0.5-1.0 m slice above each ground; and how well
//! each slice picks the actor returns that truly lie 0.5-1.0 m above the bottom of their truth
//! box (the ground they stand on).
//!
//! `cargo run --release -p patchflow-learn --example ground_check -- DATASET [STEP] [OUT_DIR]`
//!
//! Points go to the world frame with the ego's own pose estimate (`poses_estimated.txt`) where
//! the sequence has one, as perception does, else with the true pose. Writes `ground_check.json`
//! and `ground_check.md` into `OUT_DIR` (default: the current directory) and prints the table.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use nalgebra::{Matrix3, Rotation3, Translation3, UnitQuaternion};
use patchflow_dataset::{Dataset, Pose, Sweep};
use patchflow_learn::{FeatureParams, GroundGrid, GroundMode, HeightSlice};

type Failure = Box<dyn std::error::Error>;

/// SemanticKITTI ground classes: road, parking, sidewalk, other ground, terrain.
const GROUND_CLASSES: [(u16, &str); 5] = [
    (40, "road"),
    (44, "parking"),
    (48, "sidewalk"),
    (49, "other ground"),
    (72, "terrain"),
];

#[derive(Default)]
struct Tally {
    /// Per ground class: |height above the estimated ground| and |height above z = 0|.
    estimated_m: BTreeMap<&'static str, Vec<f64>>,
    flat_m: BTreeMap<&'static str, Vec<f64>>,
    /// Returns in the slice above [estimated, flat] ground: ground, actors, the rest.
    in_slice: BTreeMap<&'static str, [u64; 2]>,
    /// Actor returns against their truth box, above [estimated, flat] ground: in the slice and
    /// truly 0.5-1.0 m above the box bottom, in the slice but not, truly but not in the slice.
    actors: BTreeMap<&'static str, [u64; 2]>,
    estimate_ms: Vec<f64>,
    sweeps: usize,
}

fn main() -> Result<(), Failure> {
    let mut args = std::env::args().skip(1);
    let root = PathBuf::from(
        args.next()
            .ok_or("usage: ground_check DATASET [STEP] [OUT]")?,
    );
    let step: usize = args.next().map_or(Ok(5), |s| s.parse())?;
    let out = PathBuf::from(args.next().unwrap_or_else(|| ".".to_owned()));
    let dataset = Dataset::open(&root)?;
    let params = FeatureParams::default();
    let flat = FeatureParams {
        ground: GroundMode::Flat,
        ..params.clone()
    };
    let mut tally = Tally::default();
    let mut pose_source = "poses.txt";
    for info in dataset.sequences() {
        let reader = dataset.sequence(&info.name)?;
        let estimated = read_poses(&reader.dir().join("poses_estimated.txt"))?;
        if estimated.is_some() {
            pose_source = "poses_estimated.txt";
        }
        eprintln!("{}: {} sweeps, every {step}th", info.name, reader.len());
        for t in (0..reader.len()).step_by(step.max(1)) {
            let mut sweep = reader.read_sweep(t)?;
            if let Some(poses) = &estimated {
                sweep.world_from_sensor = poses[t];
            }
            check_sweep(&sweep, &params, &flat, &mut tally)?;
        }
    }
    let (json, markdown) = report(&tally, &root, step, pose_source);
    std::fs::create_dir_all(&out)?;
    std::fs::write(out.join("ground_check.json"), json)?;
    std::fs::write(out.join("ground_check.md"), &markdown)?;
    println!("{markdown}");
    Ok(())
}

fn check_sweep(
    sweep: &Sweep,
    params: &FeatureParams,
    flat: &FeatureParams,
    tally: &mut Tally,
) -> Result<(), Failure> {
    let started = Instant::now();
    let ground = GroundGrid::estimate(sweep, params.half_extent_m)?;
    tally
        .estimate_ms
        .push(started.elapsed().as_secs_f64() * 1e3);
    tally.sweeps += 1;
    let sensor = sweep.world_from_sensor.translation.vector;
    let inside = |x: f64, y: f64| {
        (x - sensor.x).abs() < params.half_extent_m && (y - sensor.y).abs() < params.half_extent_m
    };
    for i in 0..sweep.len() {
        let p = sweep.point_in_world(i);
        let semantic = sweep.labels[i].semantic();
        let Some(&(_, class)) = GROUND_CLASSES.iter().find(|(id, _)| *id == semantic) else {
            continue;
        };
        if inside(p.x, p.y) {
            let above = p.z - ground.ground_z_m(p.x, p.y);
            tally
                .estimated_m
                .entry(class)
                .or_default()
                .push(above.abs());
            tally.flat_m.entry(class).or_default().push(p.z.abs());
        }
    }
    // Actor returns whose height above their truth box's bottom lies in the slice.
    let truly: BTreeMap<usize, bool> = (0..sweep.len())
        .filter_map(|i| {
            let id = sweep.labels[i].instance();
            let object = sweep.objects.iter().find(|o| o.id == id && id != 0)?;
            let p = sweep.point_in_world(i);
            let above = p.z - (object.centre_m[2] - object.size_m[2] / 2.0);
            inside(p.x, p.y).then_some((
                i,
                (params.slice_min_m..=params.slice_max_m).contains(&above),
            ))
        })
        .collect();
    for (k, slice) in [
        HeightSlice::cut_above(sweep, &ground, params)?,
        HeightSlice::cut(sweep, flat)?,
    ]
    .iter()
    .enumerate()
    {
        let sliced: std::collections::BTreeSet<usize> =
            slice.points.iter().map(|p| p.index).collect();
        for (i, &truth) in &truly {
            let kind = match (sliced.contains(i), truth) {
                (true, true) => "in the slice, truly",
                (true, false) => "in the slice, truly not",
                (false, true) => "missed",
                (false, false) => continue,
            };
            tally.actors.entry(kind).or_default()[k] += 1;
        }
        for point in slice.points.iter().filter(|p| inside(p.x_m, p.y_m)) {
            let label = sweep.labels[point.index];
            let kind = if GROUND_CLASSES.iter().any(|(id, _)| *id == label.semantic()) {
                "ground"
            } else if label.instance() != 0 {
                "actors"
            } else {
                "other"
            };
            tally.in_slice.entry(kind).or_default()[k] += 1;
        }
    }
    Ok(())
}

/// The poses of a KITTI pose file, if it exists.
fn read_poses(path: &Path) -> Result<Option<Vec<Pose>>, Failure> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Ok(None);
    };
    let mut poses = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()?;
        if v.len() != 12 {
            return Err(format!("{}: a pose line has {} values", path.display(), v.len()).into());
        }
        let m = Matrix3::new(v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10]);
        let rotation = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix(&m));
        poses.push(Pose::from_parts(
            Translation3::new(v[3], v[7], v[11]),
            rotation,
        ));
    }
    Ok(Some(poses))
}

/// Quantile `q` of unsorted values (0 if none).
fn quantile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    values[((values.len() - 1) as f64 * q).round() as usize]
}

fn report(tally: &Tally, root: &Path, step: usize, pose_source: &str) -> (String, String) {
    let mut md = format!(
        "Ground check of `{}` (every {step}th sweep, {} sweeps, world frame from `{pose_source}`)\n\n\
         | class | returns | estimated: median / p90 / p99 (m) | flat z = 0: median / p90 / p99 (m) |\n|---|---|---|---|\n",
        root.display(),
        tally.sweeps
    );
    let mut classes = serde_json::Map::new();
    for (class, estimated) in &tally.estimated_m {
        let (mut e, mut f) = (estimated.clone(), tally.flat_m[class].clone());
        let qs = |v: &mut Vec<f64>| [0.5, 0.9, 0.99].map(|q| quantile(v, q));
        let (qe, qf) = (qs(&mut e), qs(&mut f));
        md += &format!(
            "| {class} | {} | {:.3} / {:.3} / {:.3} | {:.3} / {:.3} / {:.3} |\n",
            e.len(),
            qe[0],
            qe[1],
            qe[2],
            qf[0],
            qf[1],
            qf[2]
        );
        classes.insert(
            (*class).to_owned(),
            serde_json::json!({"returns": e.len(), "estimated_m": qe, "flat_m": qf}),
        );
    }
    md += "\n| returns in the slice | above the estimated ground | above z = 0 |\n|---|---|---|\n";
    for (kind, [e, f]) in &tally.in_slice {
        md += &format!("| {kind} | {e} | {f} |\n");
    }
    md += "\n| actor returns vs. 0.5-1.0 m above their truth box bottom | above the estimated ground | above z = 0 |\n|---|---|---|\n";
    for (kind, [e, f]) in &tally.actors {
        md += &format!("| {kind} | {e} | {f} |\n");
    }
    let mut ms = tally.estimate_ms.clone();
    let timing = [0.5, 0.9].map(|q| quantile(&mut ms, q));
    md += &format!(
        "\nGround estimate per sweep: median {:.2} ms, p90 {:.2} ms (wall time, one thread).\n",
        timing[0], timing[1]
    );
    let json = serde_json::json!({
        "dataset": root.display().to_string(),
        "step": step,
        "sweeps": tally.sweeps,
        "pose_source": pose_source,
        "quantiles": [0.5, 0.9, 0.99],
        "classes": classes,
        "in_slice_estimated_flat": tally.in_slice,
        "actor_returns_estimated_flat": tally.actors,
        "estimate_ms_median_p90": timing,
    });
    (format!("{json:#}\n"), md)
}
