//! A small, strict CSV reader for `patchflow gp`: one header line, comma-separated numeric cells,
//! no quoting. Every problem is an error naming the file and the 1-based line; a first line of
//! numbers is refused as a header, so a file without one never loses its first row silently.

use std::path::{Path, PathBuf};

use anyhow::{Result, anyhow};
use nalgebra::{DMatrix, DVector};

/// Which header columns to read.
#[derive(Debug, Clone, Copy)]
pub enum Columns<'a> {
    /// Every column except these (which may hold anything, e.g. text).
    AllExcept(&'a [String]),
    /// Exactly these columns (all must be present); others are not parsed.
    Only(&'a [String]),
}

/// A table split into inputs and target, with their column names.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainingColumns {
    /// Inputs, one sample per row (N×D).
    pub x: DMatrix<f64>,
    /// Targets (N).
    pub y: DVector<f64>,
    /// Names of the input columns, in order.
    pub input_names: Vec<String>,
    /// Name of the target column.
    pub target_name: String,
}

/// The numeric columns read from a CSV file.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The file read.
    pub path: PathBuf,
    /// Names of the columns kept, in file order.
    pub columns: Vec<String>,
    /// One row per data line, one column per kept column.
    pub values: DMatrix<f64>,
}

impl Table {
    /// Reads the selected columns of `path`.
    pub fn read(path: &Path, select: Columns<'_>) -> Result<Self> {
        patchflow_dataset::check_input_file(path)?;
        let text = std::fs::read_to_string(path)
            .map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))?;
        let err =
            |line: usize, reason: String| anyhow!("{}: line {line}: {reason}", path.display());
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim_end_matches('\r')));
        let Some((_, header)) = lines.next() else {
            return Err(err(1, "empty file: expected a header line".into()));
        };
        let header: Vec<String> = split(header.trim_start_matches('\u{feff}'), 1, &err)?;
        if header.iter().all(|name| name.parse::<f64>().is_ok()) {
            return Err(err(
                1,
                format!(
                    "'{}' is a row of numbers, not a header; the first line must name the columns \
                     (e.g. x1,x2,y)",
                    header.join(",")
                ),
            ));
        }
        for (i, name) in header.iter().enumerate() {
            if name.is_empty() {
                return Err(err(1, format!("column {} has an empty name", i + 1)));
            }
            if header[..i].contains(name) {
                return Err(err(1, format!("column '{name}' appears twice")));
            }
        }
        let listed = match select {
            Columns::AllExcept(names) | Columns::Only(names) => names,
        };
        if let Some(missing) = listed.iter().find(|n| !header.contains(n)) {
            return Err(err(1, format!("column '{missing}' is not in the header")));
        }
        let keep: Vec<usize> = (0..header.len())
            .filter(|&i| match select {
                Columns::AllExcept(skip) => !skip.contains(&header[i]),
                Columns::Only(only) => only.contains(&header[i]),
            })
            .collect();
        let mut values = Vec::new();
        let mut rows = 0;
        for (line_no, line) in lines {
            if line.trim().is_empty() {
                continue;
            }
            let cells = split(line, line_no, &err)?;
            if cells.len() != header.len() {
                return Err(err(
                    line_no,
                    format!("{} cells, but the header has {}", cells.len(), header.len()),
                ));
            }
            for &c in &keep {
                values.push(parse_cell(&cells[c], &header[c]).map_err(|why| err(line_no, why))?);
            }
            rows += 1;
        }
        if rows == 0 {
            return Err(err(1, "no data rows after the header".into()));
        }
        Ok(Self {
            path: path.to_path_buf(),
            columns: keep.iter().map(|&c| header[c].clone()).collect(),
            values: DMatrix::from_row_slice(rows, keep.len(), &values),
        })
    }

    /// Index of the column `name`.
    pub fn column_index(&self, name: &str) -> Result<usize> {
        self.columns.iter().position(|c| c == name).ok_or_else(|| {
            anyhow!(
                "{}: line 1: column '{name}' is not among the numeric columns read",
                self.path.display()
            )
        })
    }

    /// Splits into inputs (every other column) and the target (`target`, or the last column).
    pub fn inputs_and_target(&self, target: Option<&str>) -> Result<TrainingColumns> {
        let t = match target {
            Some(name) => self.column_index(name)?,
            None => self.columns.len().checked_sub(1).ok_or_else(|| {
                anyhow!("{}: line 1: no numeric columns left", self.path.display())
            })?,
        };
        let inputs: Vec<usize> = (0..self.columns.len()).filter(|&c| c != t).collect();
        if inputs.is_empty() {
            return Err(anyhow!(
                "{}: line 1: no input columns besides the target",
                self.path.display()
            ));
        }
        Ok(TrainingColumns {
            x: self.select_indices(&inputs),
            y: self.values.column(t).into_owned(),
            input_names: inputs.iter().map(|&c| self.columns[c].clone()).collect(),
            target_name: self.columns[t].clone(),
        })
    }

    /// The named columns, in the order given.
    pub fn select(&self, names: &[String]) -> Result<DMatrix<f64>> {
        let idx = names
            .iter()
            .map(|n| self.column_index(n))
            .collect::<Result<Vec<_>>>()?;
        Ok(self.select_indices(&idx))
    }

    fn select_indices(&self, idx: &[usize]) -> DMatrix<f64> {
        DMatrix::from_fn(self.values.nrows(), idx.len(), |i, j| {
            self.values[(i, idx[j])]
        })
    }
}

fn split(
    line: &str,
    line_no: usize,
    err: &impl Fn(usize, String) -> anyhow::Error,
) -> Result<Vec<String>> {
    if line.contains('"') {
        return Err(err(line_no, "quoted fields are not supported".into()));
    }
    Ok(line.split(',').map(|c| c.trim().to_string()).collect())
}

fn parse_cell(cell: &str, column: &str) -> std::result::Result<f64, String> {
    match cell.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!(
            "column '{column}': '{cell}' is not a finite number"
        )),
        Err(_) if cell.is_empty() => Err(format!("column '{column}' is empty")),
        Err(_) => Err(format!(
            "column '{column}': '{cell}' is not a number (leave the column out with --ignore {column})"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(text: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("data.csv");
        std::fs::write(&path, text).expect("writes");
        (dir, path)
    }

    #[test]
    fn a_csv_splits_into_inputs_and_the_last_or_named_target() {
        let (_dir, path) = write("a, b ,label,y\n1,2,car,3\n4,5,bus,6\n\n");
        let ignore = vec!["label".to_string()];
        let t = Table::read(&path, Columns::AllExcept(&ignore)).expect("reads");
        let cols = t.inputs_and_target(None).expect("splits");
        assert_eq!(cols.input_names, vec!["a".to_string(), "b".to_string()]);
        assert_eq!(cols.target_name, "y");
        assert_eq!(cols.x, DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 4.0, 5.0]));
        assert_eq!(cols.y, DVector::from_vec(vec![3.0, 6.0]));
        let by_name = t.inputs_and_target(Some("a")).expect("splits");
        assert_eq!(by_name.y, DVector::from_vec(vec![1.0, 4.0]));
        let all: Vec<String> = ["a", "b", "label", "y"].map(String::from).to_vec();
        let empty = Table::read(&path, Columns::AllExcept(&all)).expect("reads");
        assert!(empty.inputs_and_target(None).is_err());
    }

    fn error_of(text: &str, ignore: &[String]) -> String {
        let (_dir, path) = write(text);
        let err = Table::read(&path, Columns::AllExcept(ignore)).expect_err("must fail");
        let msg = err.to_string();
        assert!(msg.contains("data.csv"), "no file name in: {msg}");
        msg
    }

    #[test]
    fn bad_cells_and_shapes_are_errors_with_file_and_line() {
        assert!(error_of("a,y\n1,2\n3,nan\n", &[]).contains("line 3"));
        assert!(error_of("a,label,y\n1,car,2\n", &[]).contains("--ignore label"));
        assert!(error_of("a,y\n1,2\n3\n", &[]).contains("line 3"));
        assert!(error_of("a,y\n\"1\",2\n", &[]).contains("quoted"));
        assert!(error_of("a,a\n1,2\n", &[]).contains("twice"));
        assert!(error_of("a,y\n", &[]).contains("no data rows"));
        assert!(error_of("", &[]).contains("empty file"));
        assert!(error_of("a,y\n1,2\n", &["zz".to_string()]).contains("'zz'"));
    }

    #[test]
    fn a_csv_without_a_header_is_an_error_instead_of_losing_its_first_row() {
        let msg = error_of("1.5,2\n3,4\n5,6\n", &[]);
        assert!(
            msg.contains("line 1") && msg.contains("not a header"),
            "{msg}"
        );
        // A header may still have some numeric-looking names.
        let (_dir, path) = write("x,2019,y\n1,2,3\n");
        assert!(Table::read(&path, Columns::AllExcept(&[])).is_ok());
    }

    #[test]
    fn only_the_requested_columns_are_parsed() {
        let (_dir, path) = write("note,b,a\nhello,2,1\n");
        let want = vec!["a".to_string(), "b".to_string()];
        let t = Table::read(&path, Columns::Only(&want)).expect("reads");
        assert_eq!(
            t.select(&want).expect("selects"),
            DMatrix::from_row_slice(1, 2, &[1.0, 2.0])
        );
    }
}
