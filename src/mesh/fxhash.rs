//! A small fast hasher for keys the library makes itself (vertex, tet and fragment ids,
//! faces, coordinate bit patterns): one multiply-rotate per word. The default SipHash is
//! built to resist keys an attacker chooses, which these are not, and costs several times
//! more: it was a sixth of an MT cut's time on a 1M-tet model, and a tenth of a small
//! plain-mesh cut's.

use std::hash::{BuildHasherDefault, Hasher};

#[derive(Default, Clone, Copy)]
pub(crate) struct FxHasher(u64);

/// `HashMap<K, V, FxBuild>` / `HashSet<K, FxBuild>`; make them with `Default::default()`
/// or `with_capacity_and_hasher(n, FxBuild::default())`.
pub(crate) type FxBuild = BuildHasherDefault<FxHasher>;

impl FxHasher {
    #[inline]
    fn add(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

impl Hasher for FxHasher {
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut w = [0u8; 8];
            w[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(w));
        }
    }

    #[inline]
    fn write_u32(&mut self, x: u32) {
        self.add(x as u64);
    }

    #[inline]
    fn write_u64(&mut self, x: u64) {
        self.add(x);
    }

    #[inline]
    fn write_usize(&mut self, x: usize) {
        self.add(x as u64);
    }
}
