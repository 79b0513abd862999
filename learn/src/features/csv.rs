//! The features CSV of `patchflow features`: feature columns, then the sample's identity,
//! weight and targets.

use std::fmt::Write as _;
use std::path::Path;

use crate::Result;
use crate::features::sample_set::SampleSet;

/// Which of a sample's two feature vectors goes into the CSV.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Alignment {
    /// The patch aligned to the observation bearing (heading GPs).
    #[default]
    Bearing,
    /// The patch aligned to the true heading plus the training alignment error
    /// (`FeatureParams::speed_jitter_deg`; speed GP).
    Heading,
}

/// Trailing columns after the features, in order.
pub const META_COLUMNS: [&str; 9] = [
    "sequence", "scan", "actor", "weight", "bearing", "sin_rel", "cos_rel", "heading", "speed",
];

impl SampleSet {
    /// The CSV text: a header (`d_r_c`/`m_r_c` or `g00`…`g15`, then `META_COLUMNS`) and one
    /// row per sample; angles in radians, speed in m/s, numbers in shortest round-trip form.
    pub fn to_csv(&self, align: Alignment) -> String {
        let mut out = self.feature_names().join(",");
        out.push(',');
        out.push_str(&META_COLUMNS.join(","));
        out.push('\n');
        for s in &self.samples {
            let features = match align {
                Alignment::Bearing => &s.heading_features,
                Alignment::Heading => &s.speed_features,
            };
            for v in features {
                let _ = write!(out, "{v},");
            }
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{}",
                quote(&s.sequence),
                s.scan,
                s.actor,
                s.weight,
                s.bearing_rad,
                s.sin_rel,
                s.cos_rel,
                s.heading_rad,
                s.speed_mps
            );
        }
        out
    }

    /// Writes [`Self::to_csv`] to `path` atomically.
    pub fn write_csv(&self, path: &Path, align: Alignment) -> Result<()> {
        // The dataset crate's error names the file.
        Ok(patchflow_dataset::write_atomic(
            path,
            self.to_csv(align).as_bytes(),
        )?)
    }
}

/// A CSV field, quoted if it holds a comma, quote or line break.
fn quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::sample_set::tests::write_dataset;
    use crate::{FeatureKind, FeatureParams};
    use patchflow_dataset::Dataset;

    #[test]
    fn the_csv_has_one_row_per_sample_and_the_documented_columns() {
        let dir = tempfile::tempdir().unwrap();
        write_dataset(dir.path(), 2);
        let dataset = Dataset::open(dir.path()).unwrap();
        let set = SampleSet::collect(
            &dataset,
            &FeatureParams::default(),
            FeatureKind::Patch,
            25,
            1,
        )
        .unwrap();
        let path = dir.path().join("features.csv");
        set.write_csv(&path, Alignment::Heading).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 1 + set.samples.len());
        let header: Vec<&str> = lines[0].split(',').collect();
        assert_eq!(header.len(), 242 + 9);
        assert_eq!(
            (header[0], header[121], header[241]),
            ("d_0_0", "m_0_0", "m_10_10")
        );
        assert_eq!(header[242..], META_COLUMNS);
        let row: Vec<&str> = lines[1].split(',').collect();
        assert_eq!(row.len(), header.len());
        let s = &set.samples[0];
        assert_eq!(row[0].parse::<f64>().unwrap(), s.speed_features[0]);
        assert_eq!(row[242], "synthetic");
        assert_eq!(row[250].parse::<f64>().unwrap(), s.speed_mps);
    }

    #[test]
    fn a_csv_in_a_missing_folder_is_an_error_naming_it() {
        let set = SampleSet {
            kind: FeatureKind::Gabor,
            features: crate::FeatureParams::default(),
            pool_size: 0,
            samples: Vec::new(),
        };
        let path = Path::new("/nonexistent-folder/features.csv");
        let err = set.write_csv(path, Alignment::Bearing).unwrap_err();
        assert!(err.to_string().contains("nonexistent-folder"), "{err}");
    }

    #[test]
    fn fields_with_commas_are_quoted() {
        assert_eq!(quote("a,b"), "\"a,b\"");
        assert_eq!(quote("plain"), "plain");
    }
}
