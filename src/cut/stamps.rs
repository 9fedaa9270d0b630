//! Marks per index that a new pass clears for free: an index is marked in the current pass
//! when its stamp equals the pass's epoch, so starting a pass only moves the epoch on. The
//! MT cut's per-vertex pieces and the copy planning's small hash tables use it, so nothing
//! is cleared in proportion to the mesh per cut. (The per-vertex state cache and edge and
//! face lists keep their epoch next to their data instead: one cache miss per vertex.)

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
