//! Keeps the memory an SPGP evaluation frees mapped for the next one. Each evaluation allocates
//! and frees several megabytes of M×B matrices; glibc's malloc returns freed memory at the top of
//! its heap to the system once it exceeds a trim threshold (initially 128 KiB over its 128 KiB mmap
//! threshold), so the next evaluation page-faults every page back in: a quarter of the run time
//! once the products stopped allocating gemm's large packing buffers. glibc raises both
//! thresholds when a block it served by mmap is freed (mallopt(3), "M_MMAP_THRESHOLD"), so one
//! untouched 16 MiB allocation, freed at once, sets them to 16 and 32 MiB for the process. Other
//! allocators ignore it; it costs one mmap/munmap pair and touches no page.

use std::sync::Once;

/// Size of the one-off allocation: above the evaluation's largest transient matrix and below
/// glibc's 32 MiB cap on the dynamic threshold.
const WARMUP_BYTES: usize = 16 << 20;

/// Raises the allocator's thresholds once per process (see the module documentation).
pub(crate) fn keep_freed_memory_mapped() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let block: Vec<u8> = Vec::with_capacity(WARMUP_BYTES);
        drop(std::hint::black_box(block));
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_warmup_can_run_many_times_and_leaves_allocation_working() {
        for _ in 0..3 {
            keep_freed_memory_mapped();
        }
        let v = vec![1.0_f64; 1 << 16];
        assert_eq!(v.iter().sum::<f64>(), 65_536.0);
    }
}
