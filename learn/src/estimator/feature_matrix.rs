//! GP inputs from feature rows: the one place where rows of patch values or Gabor responses
//! become the N × D matrix the GPs read (training, prediction and cross-validation).

use nalgebra::DMatrix;

use crate::{LearnError, Result};

/// Stacks feature rows into an N × D matrix, checking every row's length.
pub fn rows_to_matrix<'a>(
    rows: impl ExactSizeIterator<Item = &'a [f64]>,
    d: usize,
) -> Result<DMatrix<f64>> {
    let n = rows.len();
    let mut x = DMatrix::zeros(n, d);
    for (r, row) in rows.enumerate() {
        if row.len() != d {
            return Err(LearnError::degenerate_data(format!(
                "feature row {r} has {} values, expected {d}",
                row.len()
            )));
        }
        for (c, v) in row.iter().enumerate() {
            x[(r, c)] = *v;
        }
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_become_matrix_rows_and_a_short_row_is_an_error() {
        let rows = [vec![1.0, 2.0], vec![3.0, 4.0]];
        let x = rows_to_matrix(rows.iter().map(Vec::as_slice), 2).unwrap();
        assert_eq!(x, DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 3.0, 4.0]));
        let short = [vec![1.0]];
        assert!(rows_to_matrix(short.iter().map(Vec::as_slice), 2).is_err());
    }
}
