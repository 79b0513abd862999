//! Large buffers kept between sweeps, a few of every length, so that the next sweep's maps and
//! beam counts cost neither fresh pages nor the allocator's zeroing.
//!
//! A sweep pair's maps take 5 MB per map on the 0.10 m window and 1.3 MB on the patches' 0.20 m
//! window, its beam counts half that; several sweep pairs are in flight at once (one per thread,
//! several priors per pair in the training sampler, the 0.5 s look-back of the moving
//! classifier's change evidence). A buffer the allocator hands back to the system comes back as
//! fresh pages, one page fault per 4 KB: pools of 8 buffers of any length cost the default
//! `bench` 12 million page faults and 35 s (docs/speed.md, "Issue 24's time targets: stop 47").

use std::sync::Mutex;

/// Buffers kept per length at most: more than the sweep pairs in flight ever hold.
const PER_LENGTH: usize = 16;
/// Bytes one pool keeps at most, whatever the lengths.
const MAX_BYTES: usize = 192 << 20;

/// A pool of buffers of element type `T`, handed out by exact length.
#[derive(Debug)]
pub(crate) struct BufferPool<T> {
    buffers: Mutex<Vec<Vec<T>>>,
}

impl<T> BufferPool<T> {
    /// An empty pool (usable in a `static`).
    pub(crate) const fn new() -> Self {
        Self {
            buffers: Mutex::new(Vec::new()),
        }
    }

    /// A pooled buffer of exactly `len` elements, whatever it holds, or `None`.
    pub(crate) fn take(&self, len: usize) -> Option<Vec<T>> {
        let mut pool = self.buffers.lock().ok()?;
        let k = pool.iter().position(|b| b.len() == len)?;
        Some(pool.swap_remove(k))
    }

    /// Keeps `buffer` for a later [`Self::take`] unless the pool holds enough of its length or
    /// of bytes; otherwise it is freed.
    pub(crate) fn give(&self, buffer: Vec<T>) {
        let Ok(mut pool) = self.buffers.lock() else {
            return;
        };
        let size = std::mem::size_of::<T>();
        let same = pool.iter().filter(|b| b.len() == buffer.len()).count();
        let bytes: usize = pool.iter().map(|b| b.len() * size).sum();
        if same < PER_LENGTH && bytes + buffer.len() * size <= MAX_BYTES {
            pool.push(buffer);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_buffer_given_back_is_taken_again_by_its_length_only() {
        let pool = BufferPool::<f64>::new();
        pool.give(vec![1.0; 10]);
        pool.give(vec![2.0; 20]);
        assert_eq!(pool.take(30), None);
        assert_eq!(pool.take(20), Some(vec![2.0; 20]));
        assert_eq!(pool.take(10), Some(vec![1.0; 10]));
        assert_eq!(pool.take(10), None);
    }

    #[test]
    fn buffers_of_one_length_do_not_crowd_out_another_length() {
        let pool = BufferPool::<f32>::new();
        for _ in 0..PER_LENGTH + 4 {
            pool.give(vec![0.0; 8]);
        }
        pool.give(vec![0.0; 9]);
        assert!(pool.take(9).is_some(), "the other length was kept");
        let kept = std::iter::from_fn(|| pool.take(8)).count();
        assert_eq!(kept, PER_LENGTH);
    }

    #[test]
    fn the_pool_keeps_no_more_than_its_byte_limit() {
        let pool = BufferPool::<u8>::new();
        let len = MAX_BYTES / 3 + 1;
        for _ in 0..3 {
            pool.give(vec![0; len]);
        }
        let kept = std::iter::from_fn(|| pool.take(len)).count();
        assert_eq!(kept, 2);
    }
}
