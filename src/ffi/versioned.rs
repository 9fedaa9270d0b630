//! Structs that may grow: the `struct_size` convention.
//!
//! Every struct passed by pointer whose fields may be added to (statistics out, written
//! by [`VersionedOut`]; option structs in, read by [`read_optional`]) starts with `size_t struct_size`, which the
//! caller sets to `sizeof` the struct as *its* header declares it. Fields are only ever
//! appended within a major version. The library reads or writes only the bytes within
//! `struct_size`, so a program compiled against an older header keeps working with a newer
//! library: statistics it does not know are not written, options it does not know keep
//! their defaults. A `struct_size` below the struct's first published version, or above
//! what this library knows (a program compiled against a newer header than the library it
//! runs with), is refused with `MTCUT_STATUS_INVALID_ARGUMENT`.

use super::guard::Out;
use super::status::{Failure, FfiResult};

/// A `#[repr(C)]` struct whose first field is `struct_size: usize`.
///
/// # Safety
/// Implementors must be `#[repr(C)]` with `struct_size: usize` as their first field, and
/// `FIRST_SIZE` must not exceed `size_of::<Self>()`. Structs read from C
/// ([`read_optional`]) must accept any bit pattern in their fields (numbers, raw and
/// nullable function pointers: no `bool`, no Rust enum, no reference).
pub(crate) unsafe trait Versioned: Copy {
    /// The C name, for messages.
    const NAME: &'static str;
    /// The end of the last field of the struct's first published version: the smallest
    /// `struct_size` accepted.
    const FIRST_SIZE: usize;
}

/// Checks `out`'s `struct_size` now (before any work), so that the write later cannot fail.
pub(crate) struct VersionedOut<T> {
    out: Out<T>,
    size: usize,
}

impl<T: Versioned> VersionedOut<T> {
    pub fn new(out: Out<T>) -> FfiResult<VersionedOut<T>> {
        // SAFETY: `out` is checked non-NULL and aligned for T; the caller initialised its
        // first field.
        let size = unsafe { checked_size(out.as_ptr()) }?;
        Ok(VersionedOut { out, size })
    }

    /// Writes the fields of `value` that lie within the caller's `struct_size`, leaving
    /// `struct_size` itself and everything beyond untouched.
    pub fn write(self, value: T) {
        let skip = size_of::<usize>();
        let src = (&value as *const T).cast::<u8>();
        let dst = self.out.as_ptr().cast::<u8>();
        // SAFETY: both point to a T; `skip..size` lies within size_of::<T>() (checked in
        // `new`), and the caller's struct is writable for `size` bytes.
        unsafe { std::ptr::copy_nonoverlapping(src.add(skip), dst.add(skip), self.size - skip) };
    }
}

/// The caller's `struct_size` at `p`, checked against what this library knows of `T`.
///
/// # Safety
/// `p` must be non-NULL and aligned (checked by the caller), pointing to a `T` whose first
/// field the caller initialised.
unsafe fn checked_size<T: Versioned>(p: *const T) -> FfiResult<usize> {
    // SAFETY: the caller's contract; the first field is a usize (the trait's contract).
    let size = unsafe { p.cast::<usize>().read() };
    if !(T::FIRST_SIZE..=size_of::<T>()).contains(&size) {
        return Err(Failure::invalid(format!(
            "{}.struct_size is {size}; this library accepts {} to {} (set it to \
             sizeof({}) before the call)",
            T::NAME,
            T::FIRST_SIZE,
            size_of::<T>(),
            T::NAME
        )));
    }
    Ok(size)
}

/// Reads an options struct the caller may pass as NULL: `defaults` when NULL, else the
/// caller's fields within its `struct_size` over `defaults` (fields a program compiled
/// against an older header does not know keep their default; `struct_size` stays the
/// one of `defaults`).
///
/// # Safety
/// A non-NULL `p` must point to a readable `T` of at least its `struct_size` bytes.
pub(crate) unsafe fn read_optional<T: Versioned>(
    p: *const T,
    arg: &str,
    defaults: T,
) -> FfiResult<T> {
    if p.is_null() {
        return Ok(defaults);
    }
    // SAFETY: forwarded contract (non-NULL here; alignment checked by `deref`).
    unsafe { super::guard::deref(p, arg) }?;
    // SAFETY: non-NULL and aligned (just checked).
    let size = unsafe { checked_size(p) }?;
    let mut value = defaults;
    let skip = size_of::<usize>();
    // SAFETY: `skip..size` lies within size_of::<T>() (checked), the caller's struct is
    // readable for `size` bytes (its contract), and `value` is a local T. Copying bytes
    // (padding included) is untyped; the fields of `T` accept any bit pattern (the trait's
    // contract), so the result is a valid T.
    unsafe {
        std::ptr::copy_nonoverlapping(
            p.cast::<u8>().add(skip),
            (&mut value as *mut T).cast::<u8>().add(skip),
            size - skip,
        )
    };
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::MTCUT_STATUS_INVALID_ARGUMENT;
    use std::mem::offset_of;

    /// Version 2 of a struct whose version 1 ended after `a`.
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[repr(C)]
    struct Stats {
        struct_size: usize,
        a: f64,
        b: u32,
    }

    unsafe impl Versioned for Stats {
        const NAME: &'static str = "stats";
        const FIRST_SIZE: usize = offset_of!(Stats, a) + size_of::<f64>();
    }

    fn write(caller: &mut Stats) -> FfiResult<()> {
        let out = unsafe { Out::new(caller as *mut Stats, "stats") }?;
        VersionedOut::new(out)?.write(Stats {
            struct_size: 0,
            a: 1.5,
            b: 7,
        });
        Ok(())
    }

    #[test]
    fn an_older_caller_gets_only_the_fields_it_knows() {
        let v1_size = offset_of!(Stats, b);
        let mut old = Stats {
            struct_size: v1_size,
            a: 0.0,
            b: 99,
        };
        write(&mut old).unwrap();
        assert_eq!((old.struct_size, old.a, old.b), (v1_size, 1.5, 99));
        let mut new = Stats {
            struct_size: size_of::<Stats>(),
            a: 0.0,
            b: 0,
        };
        write(&mut new).unwrap();
        assert_eq!((new.a, new.b), (1.5, 7));
    }

    #[test]
    fn unknown_sizes_are_refused_untouched() {
        for size in [0, Stats::FIRST_SIZE - 1, size_of::<Stats>() + 8] {
            let mut s = Stats {
                struct_size: size,
                a: -1.0,
                b: 3,
            };
            let err = write(&mut s).unwrap_err();
            assert_eq!(err.status, MTCUT_STATUS_INVALID_ARGUMENT);
            assert!(err.message.contains("sizeof(stats)"), "{}", err.message);
            assert_eq!((s.struct_size, s.a, s.b), (size, -1.0, 3));
        }
    }
}
