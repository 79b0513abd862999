//! `tables.csv`: one row per situation × method with every metric (empty cell = no value).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::method::Method;
use crate::metrics::MethodMetrics;

/// Header of `tables.csv`.
pub(crate) const CSV_HEADER: &str = "situation,method,scans,estimated_scans,heading_scored_scans,\
heading_rmse_deg,heading_me_deg,speed_rmse_mps,speed_me_mps,coverage,epe_mps";

/// The text of `tables.csv` for situations in report order (name, scans, method → metrics).
pub(crate) fn tables_csv(
    situations: &[(String, usize, BTreeMap<Method, MethodMetrics>)],
) -> String {
    let cell = |v: Option<f64>| {
        v.filter(|v| v.is_finite())
            .map(|v| format!("{v:.6}"))
            .unwrap_or_default()
    };
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for (name, scans, metrics) in situations {
        for (method, m) in metrics {
            // Writing to a String cannot fail.
            let _ = writeln!(
                out,
                "{name},{method},{scans},{},{},{},{},{},{},{},{}",
                m.estimated_scans,
                m.heading_scored_scans,
                cell(m.heading_rmse_deg),
                cell(m.heading_me_deg),
                cell(m.speed_rmse_mps),
                cell(m.speed_me_mps),
                cell(Some(m.coverage)),
                cell(m.epe_mps),
            );
        }
    }
    out
}
