//! Typed values from the bytes of a `DataArray`: every VTK scalar type, either byte order,
//! converted in parallel to what the mesh stores (f64 coordinates and attributes, u32
//! vertex indices). ASCII data is first parsed into the same bytes binary data has, so the
//! conversions exist once.

use super::format::{ByteOrder, Scalar};
use crate::geom::DVec3;
use rayon::prelude::*;

/// A VTK scalar type as a Rust primitive.
trait Prim: Copy + Send + Sync {
    const SIZE: usize;
    fn read(c: &[u8], order: ByteOrder) -> Self;
    fn to_f64(self) -> f64;
    /// The value as an integer, `None` for a float that is not a whole number.
    fn to_i128(self) -> Option<i128>;
}

macro_rules! prim_int {
    ($($t:ty),*) => {$(
        impl Prim for $t {
            const SIZE: usize = std::mem::size_of::<$t>();
            #[inline]
            fn read(c: &[u8], order: ByteOrder) -> Self {
                let a = <[u8; std::mem::size_of::<$t>()]>::try_from(c).unwrap_or_default();
                match order {
                    ByteOrder::Little => <$t>::from_le_bytes(a),
                    ByteOrder::Big => <$t>::from_be_bytes(a),
                }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn to_i128(self) -> Option<i128> {
                Some(self as i128)
            }
        }
    )*};
}
prim_int!(i8, u8, i16, u16, i32, u32, i64, u64);

macro_rules! prim_float {
    ($($t:ty),*) => {$(
        impl Prim for $t {
            const SIZE: usize = std::mem::size_of::<$t>();
            #[inline]
            fn read(c: &[u8], order: ByteOrder) -> Self {
                let a = <[u8; std::mem::size_of::<$t>()]>::try_from(c).unwrap_or_default();
                match order {
                    ByteOrder::Little => <$t>::from_le_bytes(a),
                    ByteOrder::Big => <$t>::from_be_bytes(a),
                }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn to_i128(self) -> Option<i128> {
                (self.fract() == 0.0 && self.abs() < 1e30).then_some(self as i128)
            }
        }
    )*};
}
prim_float!(f32, f64);

/// Runs `$body` with `$t` bound to the primitive of `$scalar`.
macro_rules! with_prim {
    ($scalar:expr, $t:ident => $body:expr) => {
        match $scalar {
            Scalar::I8 => {
                type $t = i8;
                $body
            }
            Scalar::U8 => {
                type $t = u8;
                $body
            }
            Scalar::I16 => {
                type $t = i16;
                $body
            }
            Scalar::U16 => {
                type $t = u16;
                $body
            }
            Scalar::I32 => {
                type $t = i32;
                $body
            }
            Scalar::U32 => {
                type $t = u32;
                $body
            }
            Scalar::I64 => {
                type $t = i64;
                $body
            }
            Scalar::U64 => {
                type $t = u64;
                $body
            }
            Scalar::F32 => {
                type $t = f32;
                $body
            }
            Scalar::F64 => {
                type $t = f64;
                $body
            }
        }
    };
}

/// Values below this many are converted on one thread (spawning costs more).
const PARALLEL_MIN: usize = 1 << 16;

fn map_values<T: Prim, R: Send>(
    bytes: &[u8],
    order: ByteOrder,
    f: impl Fn(T) -> R + Sync + Send,
) -> Vec<R> {
    if bytes.len() / T::SIZE < PARALLEL_MIN {
        bytes
            .chunks_exact(T::SIZE)
            .map(|c| f(T::read(c, order)))
            .collect()
    } else {
        bytes
            .par_chunks_exact(T::SIZE)
            .map(|c| f(T::read(c, order)))
            .collect()
    }
}

/// All values as f64 (exact for every type except 64-bit integers beyond 2^53).
pub fn to_f64(bytes: &[u8], scalar: Scalar, order: ByteOrder) -> Vec<f64> {
    with_prim!(scalar, T => map_values::<T, f64>(bytes, order, |v| v.to_f64()))
}

/// Groups of `K` values as indices below `bound` (< u32::MAX): tetrahedra from a
/// connectivity array. On failure, the position of the first value that is not a valid
/// index, and that value as text.
pub fn to_index_groups<const K: usize>(
    bytes: &[u8],
    scalar: Scalar,
    order: ByteOrder,
    bound: usize,
) -> Result<Vec<[u32; K]>, (usize, String)> {
    fn index<T: Prim>(c: &[u8], order: ByteOrder, bound: usize) -> u32 {
        match T::read(c, order).to_i128() {
            Some(i) if i >= 0 && (i as u128) < bound as u128 => i as u32,
            _ => u32::MAX,
        }
    }
    let out: Vec<[u32; K]> = with_prim!(scalar, T => {
        let group = |g: &[u8]| -> [u32; K] {
            std::array::from_fn(|k| index::<T>(&g[k * T::SIZE..(k + 1) * T::SIZE], order, bound))
        };
        if bytes.len() / T::SIZE < PARALLEL_MIN {
            bytes.chunks_exact(K * T::SIZE).map(group).collect()
        } else {
            bytes.par_chunks_exact(K * T::SIZE).map(group).collect()
        }
    });
    match out.par_iter().position_first(|g| g.contains(&u32::MAX)) {
        None => Ok(out),
        Some(g) => {
            let k = K * g + out[g].iter().position(|&i| i == u32::MAX).unwrap_or(0);
            let c = &bytes[k * scalar.size()..(k + 1) * scalar.size()];
            let text = with_prim!(scalar, T => format!("{}", T::read(c, order).to_f64()));
            Err((k, text))
        }
    }
}

/// Points: groups of three values as positions.
pub fn to_points(bytes: &[u8], scalar: Scalar, order: ByteOrder) -> Vec<DVec3> {
    with_prim!(scalar, T => {
        let point = |g: &[u8]| {
            DVec3::new(
                T::read(&g[..T::SIZE], order).to_f64(),
                T::read(&g[T::SIZE..2 * T::SIZE], order).to_f64(),
                T::read(&g[2 * T::SIZE..], order).to_f64(),
            )
        };
        if bytes.len() / T::SIZE < PARALLEL_MIN {
            bytes.chunks_exact(3 * T::SIZE).map(point).collect()
        } else {
            bytes.par_chunks_exact(3 * T::SIZE).map(point).collect()
        }
    })
}

/// The value at `k` as an integer, if it is one (for checking cell types and offsets).
pub fn integer_at(bytes: &[u8], scalar: Scalar, order: ByteOrder, k: usize) -> Option<i128> {
    let s = scalar.size();
    let c = bytes.get(k * s..(k + 1) * s)?;
    with_prim!(scalar, T => T::read(c, order).to_i128())
}

/// The first position `k` where the value is not the integer `expect(k)`.
pub fn first_mismatch(
    bytes: &[u8],
    scalar: Scalar,
    order: ByteOrder,
    expect: impl Fn(usize) -> i128 + Sync,
) -> Option<usize> {
    with_prim!(scalar, T => {
        // Blocks of values, each scanned sequentially: per-value parallel overhead would
        // cost more than the comparison.
        let block = 1 << 14;
        bytes
            .par_chunks(block * T::SIZE)
            .enumerate()
            .find_map_first(|(b, chunk)| {
                chunk
                    .chunks_exact(T::SIZE)
                    .enumerate()
                    .position(|(k, c)| T::read(c, order).to_i128() != Some(expect(b * block + k)))
                    .map(|k| b * block + k)
            })
    })
}

/// Parses ASCII data of type `scalar` into bytes in `order`; errors name the value's
/// position (0-based) and text. Floats accept `nan` and `inf` in any case.
pub fn parse_ascii(
    text: &[u8],
    scalar: Scalar,
    order: ByteOrder,
) -> Result<Vec<u8>, (usize, String)> {
    let mut out = Vec::with_capacity(text.len());
    let tokens = text
        .split(|c| c.is_ascii_whitespace())
        .filter(|t| !t.is_empty());
    for (k, tok) in tokens.enumerate() {
        let s =
            std::str::from_utf8(tok).map_err(|_| (k, String::from_utf8_lossy(tok).into_owned()))?;
        let bad = || (k, s.to_string());
        macro_rules! push {
            ($t:ty) => {{
                let v = s.parse::<$t>().map_err(|_| bad())?;
                match order {
                    ByteOrder::Little => out.extend_from_slice(&v.to_le_bytes()),
                    ByteOrder::Big => out.extend_from_slice(&v.to_be_bytes()),
                }
            }};
        }
        match scalar {
            Scalar::I8 => push!(i8),
            Scalar::U8 => push!(u8),
            Scalar::I16 => push!(i16),
            Scalar::U16 => push!(u16),
            Scalar::I32 => push!(i32),
            Scalar::U32 => push!(u32),
            Scalar::I64 => push!(i64),
            Scalar::U64 => push!(u64),
            // Float32 text is parsed as f32, so it gives the value VTK holds, not a nearby
            // f64 (VTK writes Float32 values with 9 digits).
            Scalar::F32 => push!(f32),
            Scalar::F64 => push!(f64),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_type_and_order_converts() {
        let v: i32 = -7;
        assert_eq!(
            to_f64(&v.to_be_bytes(), Scalar::I32, ByteOrder::Big),
            vec![-7.0]
        );
        assert_eq!(
            to_f64(&0.1f32.to_le_bytes(), Scalar::F32, ByteOrder::Little),
            vec![0.1f32 as f64]
        );
        let ids: Vec<u8> = [3u16, 9].iter().flat_map(|x| x.to_le_bytes()).collect();
        assert_eq!(
            to_index_groups::<2>(&ids, Scalar::U16, ByteOrder::Little, 10),
            Ok(vec![[3, 9]])
        );
        assert_eq!(
            to_index_groups::<2>(&ids, Scalar::U16, ByteOrder::Little, 9),
            Err((1, "9".to_string()))
        );
        let neg = (-1i64).to_le_bytes();
        assert!(to_index_groups::<1>(&neg, Scalar::I64, ByteOrder::Little, 9).is_err());
        let p: Vec<u8> = [1.5f64, -2.0, 3.0]
            .iter()
            .flat_map(|x| x.to_be_bytes())
            .collect();
        assert_eq!(
            to_points(&p, Scalar::F64, ByteOrder::Big),
            vec![DVec3::new(1.5, -2.0, 3.0)]
        );
    }

    #[test]
    fn ascii_parses_to_the_declared_type() {
        let b = parse_ascii(b" 0.1\n nan -inf ", Scalar::F32, ByteOrder::Little).unwrap();
        let v = to_f64(&b, Scalar::F32, ByteOrder::Little);
        assert_eq!(v[0], 0.1f32 as f64);
        assert!(v[1].is_nan() && v[2] == f64::NEG_INFINITY);
        assert_eq!(
            parse_ascii(b"1 2 x", Scalar::I32, ByteOrder::Little),
            Err((2, "x".to_string()))
        );
        assert!(parse_ascii(b"300", Scalar::U8, ByteOrder::Big).is_err());
    }
}
