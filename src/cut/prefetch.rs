//! Software prefetch, for the time-critical cut: a step runs right after the host's other
//! work (the queued MT cut) has evicted the mesh from the caches, and its candidate search
//! walks chains of dependent loads (node → leaf items → tets → vertex positions) where
//! each miss would otherwise be waited for in turn. Asking for the next lines early lets
//! the misses overlap. A hint only: it never changes a result.

/// Asks the CPU to bring the cache line holding `x` (its first byte) into all cache levels.
/// A no-op where no prefetch instruction is wired up.
#[inline(always)]
pub(crate) fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: `_mm_prefetch` needs SSE, which every x86_64 CPU has (it is part of the
    // architecture's baseline, always enabled by the target), and a prefetch never faults
    // nor reads into the program: it is a hint, here given the address of a live
    // reference besides.
    #[allow(unsafe_code)]
    unsafe {
        use core::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>((x as *const T).cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}
