//! `checks.md`: how many readings of each method are within the bar, over all checks and per
//! check, with the median errors beside the counts.

use crate::check::check_report::{CheckReport, CheckTally};
use crate::report::fmt_opt;

impl CheckReport {
    /// The Markdown report.
    pub fn markdown(&self) -> String {
        let mut md = String::from("# Target checks\n\n");
        let worlds: Vec<String> = self.worlds.iter().map(u64::to_string).collect();
        let models: Vec<String> = self
            .models
            .iter()
            .map(|m| format!("`{}` ({}, training seed {})", m.file, m.gp, m.seed))
            .collect();
        let realism = match &self.realism {
            Some(rung) => format!("every check on the `{rung}` rung"),
            None => "each check on its file's own realism rung (`urban` if it names none)".into(),
        };
        md.push_str(&format!(
            "{}, each simulated once per world seed ({}: `patchflow generate --seed W`), \
             {realism}, read with {}: {}. A reading is one method on one check's target \
             in one world with one model; it is within the bar when its heading RMSE is under \
             {}° and its speed RMSE under {} m/s (thesis 4.4's target protocol; a method that \
             gave no estimate is a miss). The baselines do not learn: each world's KF-AUTO and \
             ICP-AUTO reading (on the clusters of the first model's height slice) counts once \
             per model. Every reading is in `checks.csv`.\n\n",
            count(self.checks.len(), "check"),
            worlds.join(", "),
            count(self.models.len(), "model"),
            models.join(", "),
            self.bar.heading_rmse_deg,
            self.bar.speed_rmse_mps,
        ));
        md.push_str("## Readings within the bar\n\n");
        md.push_str(
            "| method | within the bar | readings | median heading RMSE (°) | median speed RMSE \
             (m/s) |\n|---|---|---|---|---|\n",
        );
        for t in &self.methods {
            md.push_str(&format!(
                "| {} | {} | {} | {} | {} |\n",
                t.method,
                t.within,
                t.readings,
                fmt_opt(t.median_heading_rmse_deg, 1),
                fmt_opt(t.median_speed_rmse_mps, 2)
            ));
        }
        md.push_str(
            "\n## Per check\n\nReadings within the bar of each check (median heading RMSE ° / \
             speed RMSE m/s over its readings).\n\n",
        );
        let methods: Vec<&str> = self.methods.iter().map(|t| t.method.as_str()).collect();
        md.push_str(&format!("| check | {} |\n", methods.join(" | ")));
        md.push_str(&format!("|---|{}\n", "---|".repeat(methods.len())));
        for check in &self.checks {
            let cells: Vec<String> = methods
                .iter()
                .map(|m| {
                    self.per_check
                        .iter()
                        .find(|t| &t.check == check && t.method == *m)
                        .map_or_else(|| "–".to_owned(), cell)
                })
                .collect();
            md.push_str(&format!("| {check} | {} |\n", cells.join(" | ")));
        }
        md
    }
}

/// `1 check`, `3 checks`.
fn count(n: usize, noun: &str) -> String {
    match n {
        1 => format!("1 {noun}"),
        _ => format!("{n} {noun}s"),
    }
}

/// `within of readings (heading / speed)`.
fn cell(t: &CheckTally) -> String {
    format!(
        "{} of {} ({} / {})",
        t.within,
        t.readings,
        fmt_opt(t.median_heading_rmse_deg, 1),
        fmt_opt(t.median_speed_rmse_mps, 2)
    )
}
