//! The whole-scene sections of `report.md`: every moving object by class, range and points, the
//! scene-flow tables with each metric's definition and source, and the object EPE plots.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::methods::method::Method;
use crate::report::files::fmt_opt;
use crate::report::scores::ReportScores;
use crate::scene::objects::{MIN_OBJECT_POINTS, ObjectGroup, ObjectMetrics};
use crate::scene::scene_flow::SceneFlowMetrics;

/// Writes the whole-scene sections (nothing if no sequence was evaluated as a whole scene).
pub(crate) fn scene_sections(md: &mut String, scores: &ReportScores) {
    if scores.scenes.is_empty() {
        return;
    }
    // Writing to a String cannot fail, so the `fmt::Result`s below are ignored.
    let _ = writeln!(md, "## Whole scene: every object, every point\n");
    let _ = writeln!(
        md,
        "Every sequence is replayed scan by scan, in order, as a car would run it. The clusters of \
         a scan that can be one road user (at most 12 m long) are the object hypotheses (thesis \
         3.1, step 1), and every method estimates each of them: the GP estimators once per \
         occupied 0.1 m map cell (the points of a cell share the prediction at their mean), the \
         baselines from the clusters' points. Longer clusters (building fronts, walls) stand still \
         for every method. `KF` and `ICP` take from ground truth which cluster holds which actor, \
         as in the thesis, so they leave clusters without an actor (parked cars, the static world) \
         standing; `KF-AUTO` and `ICP-AUTO` associate every cluster themselves. `-POINT` moves each \
         point with its own predicted heading and speed; `ZERO-FLOW` moves nothing. The per-target \
         tables above follow the thesis' protocol instead: the target's cluster, picked from \
         ground truth, predicted at every one of its points.\n"
    );
    objects_section(md, &scores.objects);
    flow_section(md, scores);
}

fn objects_section(md: &mut String, groups: &[(ObjectGroup, BTreeMap<Method, ObjectMetrics>)]) {
    let _ = writeln!(md, "### Every moving object\n");
    let _ = writeln!(
        md,
        "An actor is scored at a scan when at least {MIN_OBJECT_POINTS} of its points lie in the \
         height slice inside the map window; its cluster is the one holding most of them. Cells: \
         heading RMSE (°) / speed RMSE (m/s), scored as for the target (heading only above 0.5 \
         m/s; `ZERO-FLOW` has no heading), over all sequences; the header gives the object scans \
         of each group. `standing` holds the actors slower than 0.5 m/s (speed RMSE only).\n"
    );
    type Wanted = fn(ObjectGroup) -> bool;
    let tables: [(&str, Wanted); 3] = [
        ("By class", |g| {
            matches!(
                g,
                ObjectGroup::Moving | ObjectGroup::Class(_) | ObjectGroup::Standing
            )
        }),
        ("By range", |g| matches!(g, ObjectGroup::Range(_))),
        ("By the object's points in the height slice", |g| {
            matches!(g, ObjectGroup::Points(_))
        }),
    ];
    for (title, wanted) in tables {
        let chosen: Vec<&(ObjectGroup, BTreeMap<Method, ObjectMetrics>)> =
            groups.iter().filter(|(g, _)| wanted(*g)).collect();
        object_table(md, title, &chosen, Method::is_per_cluster, |m| {
            format!(
                "{} / {}",
                fmt_opt(m.motion.heading_rmse_deg, 1),
                fmt_opt(m.motion.speed_rmse_mps, 2)
            )
        });
    }
    let classes: Vec<&(ObjectGroup, BTreeMap<Method, ObjectMetrics>)> = groups
        .iter()
        .filter(|(g, _)| matches!(g, ObjectGroup::Moving | ObjectGroup::Class(_)))
        .collect();
    let _ = writeln!(
        md,
        "Mean point EPE: the mean end-point error of the object's sliced points over the sweep \
         interval, for every method including the per-point GP flows. Coverage: share of object \
         scans with an estimate (per-cluster methods only).\n"
    );
    object_table(
        md,
        "Coverage / mean point EPE (m per sweep) by class",
        &classes,
        |_| true,
        |m| {
            let coverage = if m.motion.estimated_scans > 0 || m.motion.coverage > 0.0 {
                format!("{:.2}", m.motion.coverage)
            } else {
                "–".into()
            };
            format!("{coverage} / {}", fmt_opt(m.point_epe_m, 3))
        },
    );
    let _ = writeln!(
        md,
        "![point EPE by range](plots/objects_epe_by_range.png)\n\n*Mean point EPE of the moving \
         objects by their range.*\n\n![point EPE by points](plots/objects_epe_by_points.png)\n\n\
         *Mean point EPE of the moving objects by their number of sliced points.*\n"
    );
}

fn object_table(
    md: &mut String,
    title: &str,
    groups: &[&(ObjectGroup, BTreeMap<Method, ObjectMetrics>)],
    shown: fn(Method) -> bool,
    cell: impl Fn(&ObjectMetrics) -> String,
) {
    if groups.is_empty() {
        return;
    }
    let _ = writeln!(md, "#### {title}\n");
    let _ = write!(md, "| Method |");
    for (group, methods) in groups {
        let n = methods.values().next().map_or(0, |m| m.object_scans);
        let _ = write!(md, " {} ({n}) |", group.label());
    }
    let _ = writeln!(md, "\n|---|{}", "---|".repeat(groups.len()));
    let methods: std::collections::BTreeSet<Method> = groups
        .iter()
        .flat_map(|(_, m)| m.keys().copied())
        .filter(|m| shown(*m))
        .collect();
    for method in methods {
        let _ = write!(md, "| {} |", method.label());
        for (_, scores) in groups {
            let _ = write!(md, " {} |", scores.get(&method).map_or("–".into(), &cell));
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(md);
}

fn flow_section(md: &mut String, scores: &ReportScores) {
    let _ = writeln!(md, "### Scene flow\n");
    let _ = writeln!(
        md,
        "Every height-sliced point inside the map window (what every method sees) is scored: its \
         predicted displacement over the sweep interval against the dataset's exact per-point \
         velocity times the interval. The frame does not matter for these norms. Definitions:\n\n\
         - **EPE3D**: mean ‖d̂ − d‖ (m). **AccStrict**: share with EPE < 0.05 m or EPE/‖d‖ < 5 %. \
         **AccRelax**: the same at 0.1 m / 10 %. **Outliers**: EPE > 0.3 m or EPE/‖d‖ > 10 %; a \
         standing point with any error counts. After FlowNet3D (Liu et al. 2019) as coded in \
         NSFP's `scene_flow_metrics` (`Lilac-Lee/Neural_Scene_Flow_Prior:utils.py`).\n\
         - **Three-way EPE** (Argoverse 2, `argoverse/av2-api`, `evaluation/scene_flow`): the mean \
         of the EPE on foreground-dynamic, foreground-static and background-static points; \
         foreground are road users (cars, trucks, pedestrians, cyclists, parked or moving), \
         dynamic means faster than 0.5 m/s; moving background is left out.\n\
         - **Normalised dynamic EPE** (bucketed EPE, Khatri, Vedder et al. 2024, \
         `kylevedder/BucketedSceneFlowEval`): per class, points are binned by true displacement \
         per sweep (edges 0, 1/49, …, 1 m, then ∞); each bucket but the first scores its mean EPE \
         divided by its mean true displacement; the classes' means over their buckets are \
         averaged. Zero flow scores exactly 1, a perfect method 0. The first bucket's raw EPE is \
         the *static* score.\n\
         - **Moving IoU** (SemanticKITTI moving-object segmentation, LiDAR-MOS, Chen et al. \
         2021): each method's displacement read as moving (faster than 0.5 m/s) or static per \
         point; the IoU of the moving class, TP / (TP + FP + FN).\n\n\
         Rows are ranked by three-way EPE. **`KF` and `ICP` are oracle upper bounds**: they take \
         the association of points to objects from the ground-truth labels, which for scene flow \
         is a perfect moving/static segmentation handed to them; they are listed below the \
         ranking, not in it. Every other method associates by itself: `KF-AUTO` and `ICP-AUTO` \
         (thesis 3.2 with their own association), `GP-KF` (KF-AUTO's tracker measuring the GP's \
         merged heading and speed as a velocity, thesis 3.1.4, and, in place of its centroid, the \
         visible end of a moving object one of whose ends is hidden, or the centre of a box \
         aligned with its heading where it shows whole), `GP-ICP` (ICP-AUTO started from \
         the GP's motion), and the `+MOS` read-outs (the GP's ALL estimate where the learned \
         moving classifier says the cluster moves, zero flow where it says static; GP-KF and \
         GP-ICP take the same decision here). In the per-target tables GP-KF and GP-ICP run \
         without it, as KF-AUTO and ICP-AUTO do (thesis 4.4: the target is the moving car the \
         situation names); there a `+MOS` row's static decision is speed 0 facing the GP's \
         heading: a zero velocity has no direction, and scoring it as the world's +x axis would \
         make the heading error depend on how the world is turned.\n"
    );
    if scores.scenes.len() > 1 {
        flow_table(md, "All sequences", &scores.pooled_flow);
    }
    for scene in &scores.scenes {
        let title = format!("{} ({} scans)", scene.name, scene.scans);
        flow_table(md, &title, &scene.scene_flow);
    }
}

fn flow_table(md: &mut String, title: &str, methods: &BTreeMap<Method, SceneFlowMetrics>) {
    let points = methods.values().next().map_or(0, |m| m.points);
    let _ = writeln!(md, "#### {title}, {points} points\n");
    let _ = writeln!(
        md,
        "| rank | Method | EPE3D (m) | AccStrict | AccRelax | Outliers | EPE FG dynamic | EPE FG static | EPE BG static | three-way EPE (m) | normalised dynamic EPE | static bucket EPE (m) | moving IoU |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for (rank, (method, m)) in ranked(methods).into_iter().enumerate() {
        let rank = if method.is_oracle() {
            "–".to_owned()
        } else {
            (rank + 1).to_string()
        };
        let _ = writeln!(
            md,
            "| {rank} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            method.label(),
            fmt_opt(m.epe3d_m, 4),
            fmt_opt(m.acc_strict, 3),
            fmt_opt(m.acc_relax, 3),
            fmt_opt(m.outliers, 3),
            fmt_opt(m.epe_fg_dynamic_m, 3),
            fmt_opt(m.epe_fg_static_m, 3),
            fmt_opt(m.epe_bg_static_m, 4),
            fmt_opt(m.epe_threeway_m, 3),
            fmt_opt(m.normalised_dynamic_epe, 3),
            fmt_opt(m.bucketed_static_epe_m, 4),
            fmt_opt(m.moving_iou, 3),
        );
    }
    let _ = writeln!(md);
}

/// The methods ranked by three-way EPE, best first (ties and missing scores in method order),
/// the oracle upper bounds after them: they read the association from the truth.
fn ranked(methods: &BTreeMap<Method, SceneFlowMetrics>) -> Vec<(Method, SceneFlowMetrics)> {
    let mut rows: Vec<(Method, SceneFlowMetrics)> = methods.iter().map(|(m, s)| (*m, *s)).collect();
    rows.sort_by(|(a, x), (b, y)| {
        let key = |s: &SceneFlowMetrics| s.epe_threeway_m.unwrap_or(f64::INFINITY);
        a.is_oracle()
            .cmp(&b.is_oracle())
            .then(key(x).total_cmp(&key(y)))
            .then(a.cmp(b))
    });
    rows
}
