//! Marks per index that a new pass clears for free: an index is marked in the current pass
//! when its stamp equals the pass's epoch, so starting a pass only moves the epoch on. The
//! cut's per-vertex scratch (state caches, edge and face lists, link slots, pieces) and its
//! small hash tables use it, so nothing is cleared in proportion to the mesh per cut.

#[derive(Clone, Debug, Default)]
pub(crate) struct Stamps {
    epoch: u32,
    stamp: Vec<u32>,
}

impl Stamps {
    /// Starts a pass: nothing is marked.
    pub fn begin(&mut self) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            // Wrapped after 4 billion passes: old stamps could collide, start afresh.
            self.stamp.fill(0);
            self.epoch = 1;
        }
    }

    /// How many indices can be marked.
    pub fn len(&self) -> usize {
        self.stamp.len()
    }

    /// Room for `n` indices (new ones unmarked).
    pub fn resize(&mut self, n: usize) {
        self.stamp.resize(n, 0);
    }

    /// Marks `i`; whether it was unmarked in this pass.
    #[inline]
    pub fn mark(&mut self, i: usize) -> bool {
        if self.stamp[i] == self.epoch {
            return false;
        }
        self.stamp[i] = self.epoch;
        true
    }
}
