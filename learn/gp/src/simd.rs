//! Elementwise loops compiled for the widest vector instructions the CPU has: AVX-512 or AVX2 + FMA
//! when present (detected at run time through `pulp`, safely), the baseline SSE2 otherwise. The
//! loops stay plain Rust: every path performs the same operations in the same order (the
//! compiler never fuses a multiply and an add on its own), so the results are bit-identical
//! whichever instruction set runs them; only the number of lanes per instruction changes.

/// Runs `f` compiled for the best instruction set of this CPU. Pass an `#[inline(always)]`
/// closure and call only `#[inline(always)]` helpers from it, or the compiler may keep the body
/// (or the helper) in a baseline copy.
#[inline(always)]
pub(crate) fn vectorised<R>(f: impl FnOnce() -> R) -> R {
    pulp::Arch::new().dispatch(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vectorised_loop_gives_the_bits_of_the_plain_one() {
        let x: Vec<f64> = (0..1003).map(|i| (i as f64 * 0.37).sin() * 3.0).collect();
        let plain: Vec<f64> = x.iter().map(|v| v * v * 0.5 + v / 3.0).collect();
        let fast = vectorised(
            #[inline(always)]
            || {
                x.iter()
                    .map(|v| v * v * 0.5 + v / 3.0)
                    .collect::<Vec<f64>>()
            },
        );
        assert_eq!(plain, fast);
    }
}
