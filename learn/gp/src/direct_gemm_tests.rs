//! The packing-free products against nalgebra's, over shapes that exercise every edge: row and
//! column counts that are not multiples of the tiles, both layouts of B, triangular A and
//! symmetric results.

use nalgebra::DMatrix;
use pulp::Simd;

use super::*;

fn matrix(rows: usize, cols: usize, seed: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows, cols, |i, j| {
        (((i * 31 + j * 17 + seed * 7) % 23) as f64 - 11.0) * 0.07 + (i as f64 * 0.01)
    })
}

fn close(got: &DMatrix<f64>, want: &DMatrix<f64>) -> bool {
    got.shape() == want.shape() && (got - want).amax() <= 1e-12 * want.amax().max(1.0)
}

const SHAPES: [(usize, usize, usize); 7] = [
    (1, 1, 1),
    (3, 5, 2),
    (8, 8, 8),
    (17, 13, 25),
    (100, 242, 200),
    (100, 100, 13),
    (37, 200, 242),
];

#[test]
fn a_general_product_matches_nalgebra_for_both_layouts_of_b() {
    for (m, k, n) in SHAPES {
        let a = matrix(m, k, 1);
        let b = matrix(k, n, 2);
        let want = &a * &b;
        assert!(
            close(
                &product(Lhs::of(&a), Structure::General, Rhs::of(&b)),
                &want
            ),
            "columns {m}×{k}×{n}"
        );
        let bt = b.transpose();
        let got = product(Lhs::of(&a), Structure::General, Rhs::transpose_of(&bt));
        assert!(close(&got, &want), "rows {m}×{k}×{n}");
    }
}

#[test]
fn a_sub_block_of_a_larger_operand_is_read_through_its_leading_dimension() {
    // Rows 3 .. 3 + 40 of a 50×30 matrix as a 40×30 B, in both layouts.
    let big = matrix(50, 30, 3);
    let a = matrix(21, 40, 4);
    let want = &a * big.rows(3, 40);
    let cols = Rhs::new(&big.as_slice()[3..], (40, 30), 50, Layout::Columns);
    assert!(close(
        &product(Lhs::of(&a), Structure::General, cols),
        &want
    ));
    let bt = big.transpose(); // 30×50: B[p, j] = bt[j, 3 + p]
    let rows = Rhs::new(&bt.as_slice()[3 * 30..], (40, 30), 30, Layout::Rows);
    assert!(close(
        &product(Lhs::of(&a), Structure::General, rows),
        &want
    ));
}

#[test]
fn triangular_products_skip_only_zeros() {
    for m in [1, 7, 16, 23, 100] {
        let full = matrix(m, m, 5);
        let lower = full.lower_triangle();
        let upper = full.upper_triangle();
        let b = matrix(m, 29, 6);
        let got = product(Lhs::of(&lower), Structure::Lower, Rhs::of(&b));
        assert!(close(&got, &(&lower * &b)), "lower {m}");
        let got = product(Lhs::of(&upper), Structure::Upper, Rhs::of(&b));
        assert!(close(&got, &(&upper * &b)), "upper {m}");
    }
}

#[test]
fn a_symmetric_product_is_exactly_symmetric_and_matches_nalgebra() {
    for (m, n) in [(1, 4), (9, 30), (24, 7), (100, 200), (101, 55)] {
        let v = matrix(m, n, 7);
        let w = DMatrix::from_fn(m, n, |i, j| v[(i, j)] * (1.0 + (j % 3) as f64));
        let got = symmetric_product(Lhs::of(&w), Structure::General, Rhs::transpose_of(&v));
        assert!(close(&got, &(&w * v.transpose())), "{m}×{n}");
        assert_eq!(got, got.transpose(), "{m}×{n}");
    }
}

#[test]
fn empty_operands_give_zero_or_empty_results() {
    let a = DMatrix::<f64>::zeros(4, 0);
    let b = DMatrix::<f64>::zeros(0, 3);
    assert_eq!(
        product(Lhs::of(&a), Structure::General, Rhs::of(&b)),
        DMatrix::zeros(4, 3)
    );
    let a = DMatrix::<f64>::zeros(0, 5);
    let b = matrix(5, 2, 1);
    assert_eq!(
        product(Lhs::of(&a), Structure::General, Rhs::of(&b)).shape(),
        (0, 2)
    );
}

/// Every tiling the run-time dispatch may choose (8, 4 or 1 lanes) against nalgebra.
#[test]
fn every_instruction_set_gives_the_same_products() {
    fn check<S: Simd>(simd: S, name: &str) {
        for (m, k, n) in SHAPES {
            let a = matrix(m, k, 1);
            let b = matrix(k, n, 2);
            let want = &a * &b;
            let got = product_with(simd, Lhs::of(&a), Structure::General, Rhs::of(&b));
            assert!(close(&got, &want), "{name} columns {m}×{k}×{n}");
            let bt = b.transpose();
            let got = product_with(
                simd,
                Lhs::of(&a),
                Structure::General,
                Rhs::transpose_of(&bt),
            );
            assert!(close(&got, &want), "{name} rows {m}×{k}×{n}");
        }
        for m in [5, 23, 100] {
            let lower = matrix(m, m, 5).lower_triangle();
            let b = matrix(m, 17, 6);
            let got = product_with(simd, Lhs::of(&lower), Structure::Lower, Rhs::of(&b));
            assert!(close(&got, &(&lower * &b)), "{name} lower {m}");
            let upper = lower.transpose();
            let got = product_with(simd, Lhs::of(&upper), Structure::Upper, Rhs::of(&b));
            assert!(close(&got, &(&upper * &b)), "{name} upper {m}");
        }
    }
    check(pulp::Scalar::new(), "scalar");
    #[cfg(target_arch = "x86_64")]
    {
        if let Some(simd) = pulp::x86::V3::try_new() {
            check(simd, "AVX2");
        }
        if let Some(simd) = pulp::x86::V4::try_new() {
            check(simd, "AVX-512");
        }
    }
}
