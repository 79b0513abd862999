//! The report's tables of what each GP map's fit was (issue 25): which GP each map solved (the
//! exact GP or SPGP) and the learned temporal length-scale over the motion map's error, l_t(ε) =
//! a·ε^(−1/b) for DGPOM (eq. 6) and ℓt for GPOM-RD1, by query time, with the range of l_t the
//! window can identify.

use std::fmt::Write as _;

use patchflow_occupancy::SequenceScores;

use super::json::query_time_key;

/// One line per GP method: the solver each map took, by query time.
pub(crate) fn solver_table(md: &mut String, scores: &SequenceScores) {
    let rows: Vec<String> = scores
        .methods
        .iter()
        .filter(|(_, m)| m.solver_per_map.iter().any(Option::is_some))
        .map(|(name, m)| {
            let cells: Vec<&str> = m
                .solver_per_map
                .iter()
                .map(|s| s.as_deref().unwrap_or("–"))
                .collect();
            format!("| `{name}` | {} |", cells.join(" | "))
        })
        .collect();
    if rows.is_empty() {
        return;
    }
    let times: Vec<String> = scores
        .query_secs
        .keys()
        .map(|&t| format!("t = {}", query_time_key(scores, t)))
        .collect();
    let _ = writeln!(
        md,
        "GP solved per map:\n\n| method | {} |\n|---|{}\n{}\n",
        times.join(" | "),
        "---|".repeat(times.len()),
        rows.join("\n")
    );
}

/// The learned temporal length-scales: l_t(ε) of every DGPOM fit at the reported ε, and ℓt of
/// every GPOM-RD1 fit, by query time; `identifiable_secs` is the range of l_t the window can tell
/// apart (the fit is held inside it).
pub(crate) fn temporal_table(
    md: &mut String,
    scores: &SequenceScores,
    identifiable_secs: [f64; 2],
) {
    let times: Vec<String> = scores
        .query_secs
        .keys()
        .map(|&t| format!("t = {}", query_time_key(scores, t)))
        .collect();
    let mut rows = Vec::new();
    for (name, m) in &scores.methods {
        let per_map = &m.temporal_lengthscales_per_map;
        let Some(first) = per_map.iter().find(|l| !l.is_empty()) else {
            continue;
        };
        for (k, &[error_mps, _]) in first.iter().enumerate() {
            let label = match error_mps > 0.0 {
                true => format!("`{name}` l_t at ε = {error_mps} m/s"),
                false => format!("`{name}` ℓt"),
            };
            let cells: Vec<String> = per_map
                .iter()
                .map(|l| l.get(k).map_or("–".into(), |v| format!("{:.2}", v[1])))
                .collect();
            rows.push(format!("| {label} | {} |", cells.join(" | ")));
        }
    }
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        md,
        "Learned temporal length-scale, seconds (DGPOM: l_t(ε) = a·ε^(−1/b), eq. 6, over the motion map's error ε; GPOM-RD1: its time length-scale). A window of four scans 1 s apart identifies l_t only between about {} s and {} s (below, the scans decorrelate completely; above, the covariance across the window hardly changes), so DGPOM's l_t(x) and GPOM-RD1's ℓt are both held inside that range (a smooth tanh squash of the log, never stuck on a bound):\n\n| | {} |\n|---|{}\n{}\n",
        identifiable_secs[0],
        identifiable_secs[1],
        times.join(" | "),
        "---|".repeat(times.len()),
        rows.join("\n")
    );
}
