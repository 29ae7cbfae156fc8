//! An indexed 4-ary min-heap of vertices keyed by error: at most one entry per vertex,
//! updated in place when a vertex's error changes. The lazy `BinaryHeap` with stale
//! entries it replaces spent nearly half of a large decimation popping dead entries; four
//! children per node (one cache line of entries) halve the depth a pop sifts through.

const ABSENT: u32 = u32::MAX;

/// Children per node.
const ARITY: usize = 4;

fn parent(i: usize) -> usize {
    (i - 1) / ARITY
}

/// Strict order on entries: by key, then by vertex, so equal keys pop in a fixed order
/// whatever sequence of updates built the heap.
fn less(a: (f64, u32), b: (f64, u32)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

/// Min-heap of `(key, vertex)` with `O(log n)` insert, update, remove and pop.
#[derive(Debug, Clone)]
pub struct VertexQueue {
    heap: Vec<(f64, u32)>,
    /// Heap slot of each vertex, `ABSENT` when not queued.
    slot: Vec<u32>,
}

impl VertexQueue {
    pub fn new(vertex_count: usize) -> Self {
        Self {
            heap: Vec::with_capacity(vertex_count),
            slot: vec![ABSENT; vertex_count],
        }
    }

    /// A queue of `entries` (distinct vertices below `vertex_count`), built bottom-up in
    /// linear time.
    pub fn from_entries(vertex_count: usize, entries: Vec<(f64, u32)>) -> Self {
        let mut q = Self {
            heap: entries,
            slot: vec![ABSENT; vertex_count],
        };
        for (i, &(_, v)) in q.heap.iter().enumerate() {
            q.slot[v as usize] = i as u32;
        }
        for i in (0..q.heap.len().div_ceil(ARITY)).rev() {
            q.sift_down(i);
        }
        q
    }

    pub fn len(&self) -> usize {
        self.heap.len()
    }

    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }

    /// Queues `v` with `key`, or moves it to `key` if already queued.
    pub fn set(&mut self, v: u32, key: f64) {
        match self.slot[v as usize] {
            ABSENT => {
                self.heap.push((key, v));
                let i = self.heap.len() - 1;
                self.slot[v as usize] = i as u32;
                self.sift_up(i);
            }
            s => {
                let i = s as usize;
                let old = self.heap[i];
                self.heap[i].0 = key;
                if less(self.heap[i], old) {
                    self.sift_up(i);
                } else {
                    self.sift_down(i);
                }
            }
        }
    }

    /// Takes `v` out of the queue if it is there.
    pub fn remove(&mut self, v: u32) {
        let s = self.slot[v as usize];
        if s == ABSENT {
            return;
        }
        let i = s as usize;
        self.slot[v as usize] = ABSENT;
        let last = self.heap.len() - 1;
        if i != last {
            self.heap.swap(i, last);
            self.heap.pop();
            self.slot[self.heap[i].1 as usize] = i as u32;
            let parent_greater = i > 0 && less(self.heap[i], self.heap[parent(i)]);
            if parent_greater {
                self.sift_up(i);
            } else {
                self.sift_down(i);
            }
        } else {
            self.heap.pop();
        }
    }

    /// The smallest entry, without taking it.
    pub fn peek(&self) -> Option<(f64, u32)> {
        self.heap.first().copied()
    }

    /// Takes the smallest entry.
    pub fn pop(&mut self) -> Option<(f64, u32)> {
        let top = self.peek()?;
        self.remove(top.1);
        Some(top)
    }

    fn sift_up(&mut self, mut i: usize) {
        let item = self.heap[i];
        while i > 0 {
            let up = parent(i);
            if !less(item, self.heap[up]) {
                break;
            }
            self.heap[i] = self.heap[up];
            self.slot[self.heap[i].1 as usize] = i as u32;
            i = up;
        }
        self.heap[i] = item;
        self.slot[item.1 as usize] = i as u32;
    }

    fn sift_down(&mut self, mut i: usize) {
        let item = self.heap[i];
        let n = self.heap.len();
        loop {
            let first = ARITY * i + 1;
            if first >= n {
                break;
            }
            let mut child = first;
            for c in first + 1..(first + ARITY).min(n) {
                if less(self.heap[c], self.heap[child]) {
                    child = c;
                }
            }
            if !less(self.heap[child], item) {
                break;
            }
            self.heap[i] = self.heap[child];
            self.slot[self.heap[i].1 as usize] = i as u32;
            i = child;
        }
        self.heap[i] = item;
        self.slot[item.1 as usize] = i as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pops_in_key_order_after_updates_and_removals() {
        let mut q = VertexQueue::new(10);
        for (v, k) in [(0, 5.0), (1, 3.0), (2, 8.0), (3, 1.0), (4, 9.0), (5, 4.0)] {
            q.set(v, k);
        }
        q.set(2, 0.5); // decrease
        q.set(3, 7.0); // increase
        q.remove(5);
        q.remove(9); // absent: no-op
        let order: Vec<u32> = std::iter::from_fn(|| q.pop().map(|(_, v)| v)).collect();
        assert_eq!(order, vec![2, 1, 0, 3, 4]);
        assert!(q.is_empty());
    }

    #[test]
    fn built_from_entries_pops_in_order_and_stays_updatable() {
        let keys = [7.0, 1.0, 4.0, 4.0, 9.0, 0.5, 3.0];
        let entries = keys
            .iter()
            .enumerate()
            .map(|(v, &k)| (k, v as u32))
            .collect();
        let mut q = VertexQueue::from_entries(10, entries);
        q.set(4, 0.1);
        q.remove(0);
        let order: Vec<u32> = std::iter::from_fn(|| q.pop().map(|(_, v)| v)).collect();
        assert_eq!(order, vec![4, 5, 1, 6, 2, 3]);
    }

    #[test]
    fn matches_a_sorted_reference_under_random_operations() {
        let mut q = VertexQueue::new(64);
        let mut reference: Vec<Option<f64>> = vec![None; 64];
        let mut state = 0x9e3779b97f4a7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..5000 {
            let v = (next() % 64) as u32;
            match next() % 4 {
                0 => {
                    q.remove(v);
                    reference[v as usize] = None;
                }
                3 => {
                    let got = q.pop();
                    let want = reference
                        .iter()
                        .enumerate()
                        .filter_map(|(i, k)| k.map(|k| (k, i as u32)))
                        .min_by(|a, b| a.0.total_cmp(&b.0));
                    assert_eq!(got.map(|g| g.0), want.map(|w| w.0));
                    if let Some((_, u)) = got {
                        reference[u as usize] = None;
                    }
                }
                _ => {
                    let k = (next() % 1000) as f64;
                    q.set(v, k);
                    reference[v as usize] = Some(k);
                }
            }
            assert_eq!(q.len(), reference.iter().flatten().count());
        }
    }
}
