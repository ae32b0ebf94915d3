//! Error-free transformations in plain floating-point arithmetic (no FMA): Knuth's TwoSum and Dekker's
//! TwoProduct with Veltkamp's splitting (Dekker 1971; Joldes, Muller, Popescu 2017). Exact for finite
//! operands whose results do not overflow (TwoProduct also needs no underflow in the low part).

use crate::Real;

/// `(s, e)` with `s = fl(a + b)` and `a + b = s + e` exactly.
#[inline(always)]
pub(crate) fn two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// Veltkamp's split `a = hi + lo` with `hi` holding the upper half of the significand.
#[inline(always)]
fn split<T: Real>(a: T) -> (T, T) {
    // 2^⌈p/2⌉ + 1: 4097 for f32 (p = 24), 134217729 for f64 (p = 53).
    let factor = if T::EPSILON > T::from_f64(1e-10) {
        T::from_f64(4097.0)
    } else {
        T::from_f64(134_217_729.0)
    };
    let c = factor * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `(p, e)` with `p = fl(a·b)` and `a·b = p + e` exactly (Dekker's TwoProduct, 17 flops).
#[inline(always)]
pub(crate) fn two_product<T: Real>(a: T, b: T) -> (T, T) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    (p, e)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift) for operands over many binades.
    fn operands(n: usize) -> impl Iterator<Item = (f32, f32)> {
        let mut s = 0x9E37_79B9_7F4A_7C15_u64;
        core::iter::repeat_with(move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let a = f32::from_bits(((s as u32) & 0x007F_FFFF) | 0x3F80_0000)
                * 2f32.powi((s >> 40) as i32 % 24 - 12);
            let b = f32::from_bits(((s >> 32) as u32 & 0x007F_FFFF) | 0x3F80_0000)
                * 2f32.powi((s >> 50) as i32 % 24 - 12);
            (if s & 1 == 0 { a } else { -a }, b)
        })
        .take(n)
    }

    #[test]
    fn two_product_is_exact_in_f32_without_fma() {
        // f32 products are exact in f64 (48-bit significands), so the check is exact.
        for (a, b) in operands(200_000) {
            let (p, e) = two_product(a, b);
            assert_eq!(p as f64 + e as f64, a as f64 * b as f64, "{a:e} * {b:e}");
        }
    }

    #[test]
    fn two_sum_is_exact_in_f32() {
        for (a, b) in operands(200_000) {
            let (s, e) = two_sum(a, b);
            assert_eq!(s as f64 + e as f64, a as f64 + b as f64, "{a:e} + {b:e}");
        }
    }
}
