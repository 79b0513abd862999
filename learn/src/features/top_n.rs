//! The `n` best items of a stream (the streaming half of the Efraimidis–Spirakis draw, thesis
//! 3.1.2): a bounded min-heap, mergeable, so per-thread lists combine into the list of the whole.

use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

/// The `n` items with the largest keys seen so far (keys must be distinct: break ties in the
/// key, e.g. by the item's position). Merging two is keeping the `n` largest of both, so the
/// result is the same however a stream was split.
#[derive(Debug)]
pub(crate) struct TopN<K: Ord, T> {
    n: usize,
    /// Min-heap: the top is the smallest kept key.
    heap: BinaryHeap<Reverse<Keyed<K, T>>>,
}

/// An item ordered by its key alone.
#[derive(Debug)]
struct Keyed<K, T>(K, T);

impl<K: Ord, T> PartialEq for Keyed<K, T> {
    fn eq(&self, other: &Self) -> bool {
        self.0 == other.0
    }
}

impl<K: Ord, T> Eq for Keyed<K, T> {}

impl<K: Ord, T> PartialOrd for Keyed<K, T> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<K: Ord, T> Ord for Keyed<K, T> {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.cmp(&other.0)
    }
}

impl<K: Ord, T> TopN<K, T> {
    /// Keeps at most `n` items.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            heap: BinaryHeap::new(),
        }
    }

    /// True if an item with this key would be kept now (check before building a costly item).
    pub(crate) fn accepts(&self, key: &K) -> bool {
        self.heap.len() < self.n || self.heap.peek().is_some_and(|worst| *key > worst.0.0)
    }

    /// Offers an item; it is kept if its key is among the `n` largest so far.
    pub(crate) fn push(&mut self, key: K, item: T) {
        if !self.accepts(&key) {
            return;
        }
        self.heap.push(Reverse(Keyed(key, item)));
        if self.heap.len() > self.n {
            self.heap.pop();
        }
    }

    /// The `n` largest of both.
    pub(crate) fn merge(self, other: Self) -> Self {
        let (mut big, small) = if self.heap.len() >= other.heap.len() {
            (self, other)
        } else {
            (other, self)
        };
        for Reverse(Keyed(key, item)) in small.heap {
            big.push(key, item);
        }
        big
    }

    /// The kept items with their keys, in no particular order.
    pub(crate) fn into_items(self) -> impl Iterator<Item = (K, T)> {
        self.heap.into_iter().map(|Reverse(Keyed(k, t))| (k, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_split_and_merged_stream_keeps_the_same_items_as_one_stream() {
        let keys: Vec<u64> = (0..500).map(|i| (i * 7919) % 1009).collect();
        let mut one = TopN::new(37);
        let mut parts: Vec<TopN<u64, usize>> = (0..4).map(|_| TopN::new(37)).collect();
        for (i, &k) in keys.iter().enumerate() {
            one.push(k, i);
            parts[i % 4].push(k, i);
        }
        let merged = parts.into_iter().reduce(TopN::merge).unwrap();
        let sorted = |t: TopN<u64, usize>| {
            let mut v: Vec<_> = t.into_items().collect();
            v.sort_unstable();
            v
        };
        assert_eq!(sorted(one), sorted(merged));
    }
}
