//! `tables.csv`: one row per sequence × method with every metric: the per-target columns
//! (thesis 4.4), the scene-flow columns, and the scores on the sequence's moving objects. An
//! empty cell means no value (a method outside the per-target tables, or nothing scored).

use std::collections::BTreeSet;
use std::fmt::Write as _;

use crate::methods::method::Method;
use crate::report::scores::ReportScores;

/// Header of `tables.csv`.
pub(crate) const CSV_HEADER: &str = "situation,method,scans,estimated_scans,heading_scored_scans,\
heading_rmse_deg,heading_me_deg,speed_rmse_mps,speed_me_mps,coverage,epe_mps,\
flow_points,epe3d_m,acc_strict,acc_relax,outliers,epe_fg_dynamic_m,epe_fg_static_m,\
epe_bg_static_m,epe_threeway_m,normalised_dynamic_epe,bucketed_static_epe_m,\
object_scans,object_heading_rmse_deg,object_speed_rmse_mps,object_coverage,object_epe_mps,\
object_point_epe_m";

/// The text of `tables.csv`: situations with a target first (report order), then the other
/// sequences; methods in canonical order.
pub(crate) fn tables_csv(scores: &ReportScores) -> String {
    let cell = |v: Option<f64>| {
        v.filter(|v| v.is_finite())
            .map(|v| format!("{v:.6}"))
            .unwrap_or_default()
    };
    let mut names: Vec<&str> = scores.situations.iter().map(|s| s.0.as_str()).collect();
    for scene in &scores.scenes {
        if !names.contains(&scene.name.as_str()) {
            names.push(&scene.name);
        }
    }
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for name in names {
        let target = scores.situations.iter().find(|s| s.0 == name);
        let scene = scores.scenes.iter().find(|s| s.name == name);
        let scans = target.map(|t| t.1).or(scene.map(|s| s.scans)).unwrap_or(0);
        let methods: BTreeSet<Method> = target
            .into_iter()
            .flat_map(|t| t.2.keys())
            .chain(scene.into_iter().flat_map(|s| s.scene_flow.keys()))
            .copied()
            .collect();
        for method in methods {
            let m = target.and_then(|t| t.2.get(&method));
            let f = scene.and_then(|s| s.scene_flow.get(&method));
            let o = scene.and_then(|s| s.objects.get(&method));
            let count = |v: Option<usize>| v.map(|v| v.to_string()).unwrap_or_default();
            // Writing to a String cannot fail.
            let _ = writeln!(
                out,
                "{name},{method},{scans},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                count(m.map(|m| m.estimated_scans)),
                count(m.map(|m| m.heading_scored_scans)),
                cell(m.and_then(|m| m.heading_rmse_deg)),
                cell(m.and_then(|m| m.heading_me_deg)),
                cell(m.and_then(|m| m.speed_rmse_mps)),
                cell(m.and_then(|m| m.speed_me_mps)),
                cell(m.map(|m| m.coverage)),
                cell(m.and_then(|m| m.epe_mps)),
                count(f.map(|f| f.points as usize)),
                cell(f.and_then(|f| f.epe3d_m)),
                cell(f.and_then(|f| f.acc_strict)),
                cell(f.and_then(|f| f.acc_relax)),
                cell(f.and_then(|f| f.outliers)),
                cell(f.and_then(|f| f.epe_fg_dynamic_m)),
                cell(f.and_then(|f| f.epe_fg_static_m)),
                cell(f.and_then(|f| f.epe_bg_static_m)),
                cell(f.and_then(|f| f.epe_threeway_m)),
                cell(f.and_then(|f| f.normalised_dynamic_epe)),
                cell(f.and_then(|f| f.bucketed_static_epe_m)),
                count(o.map(|o| o.object_scans)),
                cell(o.and_then(|o| o.motion.heading_rmse_deg)),
                cell(o.and_then(|o| o.motion.speed_rmse_mps)),
                cell(o.map(|o| o.motion.coverage)),
                cell(o.and_then(|o| o.motion.epe_mps)),
                cell(o.and_then(|o| o.point_epe_m)),
            );
        }
    }
    out
}
