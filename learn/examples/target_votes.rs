//! What each point of the target's cluster says, scan by scan, under thesis 4.4's protocol (the
//! cluster holding most of the target's sliced points, predicted at every one of its points): who
//! the point belongs to (the target, another actor, a static class), its sin/cos prediction and
//! the world heading it votes for (merge.rs's vote), the speed its patch shows along the merged
//! ALL heading and along the true heading, and what its heading patch holds (mean and largest
//! |difference|, the thesis' importance weight of Eq. 3.1; the share of cells at the map prior
//! in the previous and in this sweep). Per scan: the cluster's make-up, the merged ALL / BEST
//! estimates against the truth, and the share of the cluster's surroundings the previous sweep
//! left unobserved (`SweepFeatures::unobserved_before_share`; above `MAX_UNOBSERVED_BEFORE` the
//! cluster gets no estimate) and how many of the cluster's two ends a nearer return hides
//! (`RangeProfile::hidden_ends`; 2: seen through a gap, docs/estimator.md "Stop 46"). A model
//! trained with map patches (the default) is required.
//!
//! On stdout: ALL and BEST RMSE as `evaluate` scores them for the target, and the votes' accuracy
//! per quartile of motion evidence (each scan's points ranked by the mean |difference| of their
//! heading patch).
//!
//! `cargo run --release -p patchflow-learn --example target_votes -- MODEL DATASET SEQUENCE OUT`
//! writes `OUT/points.csv` (one row per point), `OUT/scans.csv` (one row per scan) and
//! `OUT/priors.csv` (each GP's prediction far from its training inputs, i.e. its prior).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;

use patchflow_dataset::{Dataset, wrap_angle_rad};
use patchflow_learn::{
    ClusterMotion, GpPrediction, MotionEstimator, PATCH_LEN, RangeProfile, ScanStream,
    SweepFeatures,
};

type Failure = Box<dyn std::error::Error>;

/// Below this true speed a heading is not scored (`patchflow_eval::MIN_SCORED_SPEED_MPS`).
const MIN_SCORED_SPEED_MPS: f64 = 0.5;

/// Patch rows (difference cells, then reflection cells) of `rows`, each at its position and axis.
fn patch_rows(features: &SweepFeatures, rows: &[([f64; 2], f64)]) -> Vec<f64> {
    let mut x = vec![0.0; rows.len() * PATCH_LEN];
    for (out, &(xy, axis)) in x.chunks_exact_mut(PATCH_LEN).zip(rows) {
        if let Ok(values) = <&mut [f64; PATCH_LEN]>::try_from(out) {
            features.patch_values_at(xy, axis, values);
        }
    }
    x
}

fn error_deg(estimate_rad: f64, truth_rad: f64) -> f64 {
    wrap_angle_rad(estimate_rad - truth_rad).to_degrees()
}

fn rmse(v: &[f64]) -> f64 {
    (v.iter().map(|e| e * e).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

/// Squared errors of one merge rule over the scans.
#[derive(Default)]
struct Score {
    heading_deg: Vec<f64>,
    speed_mps: Vec<f64>,
}

impl Score {
    fn add(&mut self, motion: Option<ClusterMotion>, heading_rad: f64, speed_mps: f64) {
        if let Some(m) = motion {
            if speed_mps >= MIN_SCORED_SPEED_MPS {
                self.heading_deg.push(error_deg(m.heading_rad, heading_rad));
            }
            self.speed_mps.push(m.speed_mps - speed_mps);
        }
    }
}

/// Per quartile of motion evidence: votes, votes within 30° of the truth, votes more than 120°
/// off, and the summed information 1/σ²_sin + 1/σ²_cos.
type Quartiles = [[f64; 4]; 4];

/// One point's row of `points.csv`: its vote and what its patch holds.
fn point_row(
    patch: &[f64],
    prior: f64,
    bearing: f64,
    sin: (f64, f64),
    cos: (f64, f64),
) -> [f64; 11] {
    let (s, c) = bearing.sin_cos();
    let ((ms, vs), (mc, vc)) = (sin, cos);
    // merge.rs's vote: (cos, sin) rotated by the bearing, and its covariance.
    let (vx, vy) = (c * mc - s * ms, s * mc + c * ms);
    let half = PATCH_LEN / 2;
    let (difference, reflection) = patch.split_at(half);
    let at_prior = |v: f64| (v - prior).abs() < 1e-6;
    let diff_abs = difference.iter().map(|d| d.abs()).sum::<f64>() / half as f64;
    let diff_max = difference.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    let unseen_before = difference
        .iter()
        .zip(reflection)
        .filter(|&(d, m)| at_prior(m - d))
        .count() as f64
        / half as f64;
    let unseen_now = reflection.iter().filter(|&&m| at_prior(m)).count() as f64 / half as f64;
    [
        vx,
        vy,
        c * c * vc + s * s * vs,
        s * c * (vc - vs),
        s * s * vc + c * c * vs,
        vy.atan2(vx),
        diff_abs,
        diff_max,
        reflection.iter().sum::<f64>() / half as f64,
        unseen_before,
        unseen_now,
    ]
}

fn main() -> Result<(), Failure> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [model, dataset, name, out] = &args[..] else {
        return Err("usage: target_votes MODEL DATASET SEQUENCE OUT".into());
    };
    let estimator = MotionEstimator::load(&PathBuf::from(model))?;
    let dataset = Dataset::open(&PathBuf::from(dataset))?;
    let sequence = dataset.sequence(name)?;
    let [sin_gp, cos_gp, speed_gp] = estimator.gps();
    let prior = estimator.feature_params().prior;
    let mut priors = String::from("gp,mean,var_y\n");
    for (gp_name, gp) in [("sin", sin_gp), ("cos", cos_gp), ("speed", speed_gp)] {
        let far = gp.predict_rows(&vec![1e3; gp.input_names().len()])?;
        writeln!(priors, "{gp_name},{:.5},{:.5}", far.mean[0], far.var_y[0])?;
    }
    let mut points = String::from(
        "scan,range_m,owner,class,x,y,sin,sin_var,cos,cos_var,vx,vy,cxx,cxy,cyy,vote_deg,\
         vote_err_deg,speed_all,speed_all_var,speed_true,speed_true_var,diff_abs,diff_max,\
         refl_mean,unseen_before,unseen_now\n",
    );
    let mut scans = String::from(
        "scan,range_m,true_deg,true_mps,cluster_points,target_points,other_actor_points,\
         static_points,length_m,all_deg,all_err_deg,all_mps,best_deg,best_err_deg,best_mps,\
         best_votes,target_total,target_clusters,unobserved_before_share,hidden_ends\n",
    );
    let (mut all, mut best, mut quartiles) =
        (Score::default(), Score::default(), Quartiles::default());
    let mut stream = ScanStream::new(&sequence, vec![estimator.feature_params().clone()])?;
    while let Some((index, sweep)) = stream.read_next()? {
        let features = stream.features_of(&sweep)?.remove(0);
        let Some(target) = sweep.target() else {
            continue;
        };
        let [sx, sy] = features.sensor_xy();
        let range_m = (target.centre_m[0] - sx).hypot(target.centre_m[1] - sy);
        let true_heading = target.velocity_mps[1].atan2(target.velocity_mps[0]);
        let true_speed = target.velocity_mps[0].hypot(target.velocity_mps[1]);
        let truth = format!(
            "{index},{range_m:.2},{:.1},{true_speed:.2}",
            true_heading.to_degrees()
        );
        // The oracle's cluster (eval/src/oracle.rs): most of the target's points, ties to the
        // lowest id.
        let mut counts = BTreeMap::<usize, usize>::new();
        for (i, p) in features.points().iter().enumerate() {
            if sweep.labels[p.index].instance() == target.id {
                *counts.entry(features.cluster_of(i)).or_default() += 1;
            }
        }
        let (target_total, target_clusters) = (counts.values().sum::<usize>(), counts.len());
        let cluster = counts
            .into_iter()
            .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)));
        let Some((cluster, _)) = cluster else {
            writeln!(scans, "{truth},0,0,0,0,0,,,,,,,,0,0,")?;
            continue;
        };
        let members = features.clusters().members(cluster);
        let estimate = estimator.estimate_cluster(&features, members)?;
        all.add(estimate.all, true_heading, true_speed);
        best.add(estimate.best, true_heading, true_speed);
        let xy = features.positions_xy(members);
        let heading_rows: Vec<([f64; 2], f64)> =
            xy.iter().map(|&p| (p, features.bearing_at(p))).collect();
        let hx = patch_rows(&features, &heading_rows);
        let (sin, cos) = (sin_gp.predict_rows(&hx)?, cos_gp.predict_rows(&hx)?);
        // Without an ALL heading the speed patches follow the true heading (diagnosis only).
        let all_heading = estimate.all.map_or(true_heading, |a| a.heading_rad);
        let along = |h: f64| -> Result<GpPrediction, Failure> {
            let rows: Vec<([f64; 2], f64)> = xy.iter().map(|&p| (p, h)).collect();
            Ok(speed_gp.predict_rows(&patch_rows(&features, &rows))?)
        };
        let (speed_all, speed_true) = (along(all_heading)?, along(true_heading)?);
        let mut owners = [0usize; 3]; // target, other actors, static
        let mut evidence: Vec<(f64, f64, f64)> = Vec::with_capacity(members.len());
        for (k, &i) in members.iter().enumerate() {
            let label = sweep.labels[features.points()[i].index];
            let owner = match label.instance() {
                0 => "static".to_owned(),
                o if o == target.id => "target".to_owned(),
                o => format!("actor{o}"),
            };
            owners[match owner.as_str() {
                "target" => 0,
                "static" => 2,
                _ => 1,
            }] += 1;
            let row = point_row(
                &hx[k * PATCH_LEN..(k + 1) * PATCH_LEN],
                prior,
                heading_rows[k].1,
                (sin.mean[k], sin.var_y[k]),
                (cos.mean[k], cos.var_y[k]),
            );
            let vote_err = error_deg(row[5], true_heading);
            evidence.push((
                row[6],
                vote_err.abs(),
                1.0 / sin.var_y[k] + 1.0 / cos.var_y[k],
            ));
            write!(
                points,
                "{index},{range_m:.2},{owner},{},{:.3},{:.3}",
                label.semantic(),
                xy[k][0],
                xy[k][1]
            )?;
            write!(
                points,
                ",{:.4},{:.5},{:.4},{:.5}",
                sin.mean[k], sin.var_y[k], cos.mean[k], cos.var_y[k]
            )?;
            write!(
                points,
                ",{:.4},{:.4},{:.5},{:.5},{:.5}",
                row[0], row[1], row[2], row[3], row[4]
            )?;
            write!(points, ",{:.1},{vote_err:.1}", row[5].to_degrees())?;
            write!(
                points,
                ",{:.3},{:.4}",
                speed_all.mean[k], speed_all.var_y[k]
            )?;
            write!(
                points,
                ",{:.3},{:.4}",
                speed_true.mean[k], speed_true.var_y[k]
            )?;
            writeln!(
                points,
                ",{:.4},{:.4},{:.4},{:.3},{:.3}",
                row[6], row[7], row[8], row[9], row[10]
            )?;
        }
        evidence.sort_by(|a, b| a.0.total_cmp(&b.0));
        let n = evidence.len();
        for (q, counts) in quartiles.iter_mut().enumerate() {
            for &(_, err, info) in &evidence[q * n / 4..(q + 1) * n / 4] {
                counts[0] += 1.0;
                counts[1] += f64::from(u8::from(err < 30.0));
                counts[2] += f64::from(u8::from(err > 120.0));
                counts[3] += info;
            }
        }
        let merged = |m: Option<ClusterMotion>| match m {
            Some(m) => format!(
                "{:.1},{:.1},{:.2}",
                m.heading_rad.to_degrees(),
                error_deg(m.heading_rad, true_heading),
                m.speed_mps
            ),
            None => ",,".to_owned(),
        };
        writeln!(
            scans,
            "{truth},{},{},{},{},{:.2},{},{},{},{target_total},{target_clusters},{:.3},{}",
            members.len(),
            owners[0],
            owners[1],
            owners[2],
            features.cluster_shape(cluster).length_m,
            merged(estimate.all),
            merged(estimate.best),
            estimate.best.map_or(0, |b| b.heading_votes),
            features.unobserved_before_share(&xy),
            RangeProfile::of(&features).hidden_ends(&xy),
        )?;
    }
    let out = PathBuf::from(out);
    std::fs::create_dir_all(&out)?;
    std::fs::write(out.join("points.csv"), points)?;
    std::fs::write(out.join("scans.csv"), scans)?;
    std::fs::write(out.join("priors.csv"), priors)?;
    for (rule, score) in [("ALL", &all), ("BEST", &best)] {
        println!(
            "{name} {rule}: heading RMSE {:.1}°, speed RMSE {:.2} m/s, {} scans estimated",
            rmse(&score.heading_deg),
            rmse(&score.speed_mps),
            score.speed_mps.len()
        );
    }
    for (q, [votes, within, opposite, info]) in quartiles.iter().enumerate() {
        let share = |x: f64| x / votes.max(1.0);
        println!(
            "{name} motion-evidence quartile {q}: {votes} votes, {:.2} within 30°, {:.2} over 120° off, \
             information per vote {:.1}",
            share(*within),
            share(*opposite),
            share(*info)
        );
    }
    Ok(())
}
