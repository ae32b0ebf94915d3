//! The sine and the square root of the exponential map's large-angle branch in `f32`, in `f32` arithmetic
//! only ([`sin_f32`], [`sqrt_f32`]).
//!
//! libm's `sinf` reduces any argument (Payne–Hanek, for up to 2¹²⁸ rad) and evaluates its kernels in
//! `f64`: on a Cortex-M4F that links software `f64` arithmetic and tables, about 8 KiB of flash for a
//! branch that only steps beyond 0.2 rad take. The step path needs far less: [`sin_f32`] covers
//! `0 ≤ x ≤` [`SIN_F32_MAX`] (a half rotation angle of 8192 rad, a step of 16384 rad) and returns NaN
//! beyond, which the propagator refuses as [`crate::Error::NonFiniteResult`] with its state unchanged.
//!
//! Method: `x = j·π/2 + r` with `j` the nearest integer of `x·2/π`, `r` by Cody–Waite with π/2 split in
//! four parts (the first three short enough that `j·part` is exact for `j < 2¹³`) and `r` kept as a
//! float-float pair (TwoSum, [`crate::exact::two_sum`]), then the Taylor
//! polynomials of sin and cos on `|r| ≤ π/4` (to r¹¹ and r¹⁰), chosen by `j mod 4`.
//! Error, measured over every `f32` in `[0.05, 8192]` by the test below: at most 1 ulp of the result
//! (0.977 measured) where `|sin x| ≥ 2⁻⁵`, and at most 6e-8 absolute (5.8e-8 measured) everywhere (where
//! `sin x` is small the reduction's absolute error, not the result's ulp, is what is left; against the
//! attitude's unit norm both are far below its ulp, 6e-8).

use crate::exact::{two_product, two_sum};

/// Largest argument (rad) of [`sin_f32`]; beyond it the result is NaN.
pub(crate) const SIN_F32_MAX: f32 = 8192.0;

/// Error bound of [`sin_f32`] in ulp of the result where `|sin x| ≥ 2⁻⁵` (exhaustive test).
#[cfg(test)]
const SIN_F32_MAX_ULP: f64 = 1.0;

/// Absolute error bound of [`sin_f32`] over its whole range (exhaustive test).
#[cfg(test)]
const SIN_F32_MAX_ABS: f64 = 6.0e-8;

const FRAC_2_PI: f32 = core::f32::consts::FRAC_2_PI;
/// π/2 = P1 + P2 + P3 + P4 (+ 8.3e-20): P1 has 8 significant bits, P2 and P3 11 each, so `j·P1`, `j·P2`
/// and `j·P3` are exact for `j < 2¹³`; only `j·P4` (≤ 1.4e-8) rounds.
const P1: f32 = 1.570_312_5;
const P2: f32 = 2029.0 / 4_194_304.0; // 2029·2⁻²²
const P3: f32 = 1297.0 / 17_179_869_184.0; // 1297·2⁻³⁴
const P4: f32 = 2.563_344e-12;

/// `sin x` for `0 ≤ x ≤ SIN_F32_MAX`; NaN for any other `x` (negative, beyond, NaN).
#[inline(never)]
pub(crate) fn sin_f32(x: f32) -> f32 {
    if !(0.0..=SIN_F32_MAX).contains(&x) {
        return f32::NAN;
    }
    // x·2/π ≤ 5215.2: the cast is exact and in range.
    let j = (x * FRAC_2_PI + 0.5) as u32;
    let jf = j as f32;
    // r = x − j·π/2 as r_hi + r_lo (absolute error below 1e-14): x − j·P1 is exact (Sterbenz), the
    // next two subtractions are exact through TwoSum, and the rounded tail goes into r_lo.
    let t = x - jf * P1;
    let (a, ea) = two_sum(t, -(jf * P2));
    let (b, eb) = two_sum(a, -(jf * P3));
    let r = b - jf * P4;
    let r_lo = ((b - r) - jf * P4) + (ea + eb);
    let z = r * r;
    // Taylor series to r¹¹ and r¹⁰: on |r| ≤ π/4 the first omitted terms are below 1e-11, far under half an
    // ulp; every coefficient's own rounding (2⁻²⁴ relative) scales a term at most 0.1 of the result.
    // sin(r + r_lo) = sin r + r_lo·cos r, cos(r + r_lo) = cos r − r_lo·sin r, to first order in r_lo.
    let sin_tail = z
        * (-1.0 / 6.0
            + z * (1.0 / 120.0
                + z * (-1.0 / 5040.0 + z * (1.0 / 362_880.0 + z * (-1.0 / 39_916_800.0)))));
    let sin_r = r + (r_lo + r * sin_tail);
    // 1 − z/2 = w + w_lo exactly (Sterbenz: 1 − w and z/2 are within a factor 2 of each other).
    let w = 1.0 - 0.5 * z;
    let w_lo = (1.0 - w) - 0.5 * z;
    let cos_tail =
        z * z * (1.0 / 24.0 + z * (-1.0 / 720.0 + z * (1.0 / 40_320.0 + z * (-1.0 / 3_628_800.0))));
    let cos_r = w + ((cos_tail - r * r_lo) + w_lo);
    match j & 3 {
        0 => sin_r,
        1 => cos_r,
        2 => -sin_r,
        _ => -cos_r,
    }
}

/// `√x` correctly rounded for `2⁻¹²⁰ ≤ x ≤ 2¹²⁶` (tested exhaustively over the step path's range, see
/// below); `0` for `0`, `∞` for `∞`, NaN for a negative, subnormal or NaN `x` (not exact in the few binades
/// at either end of the normal range: `x/2` or the square's error lose bits, or the square overflows).
///
/// libm's `sqrtf` is a bit-by-bit software root with a 256-byte table (about 480 bytes of flash on a
/// Cortex-M4F, whose `vsqrt.f32` libm does not use and `forbid(unsafe_code)` cannot reach). This one: an
/// estimate of `1/√x` from the exponent and the leading mantissa bits (the bit pattern halved and
/// subtracted from a constant; 3.5% relative error), three Newton steps `y ← y(3/2 − x y²/2)` (3.5% →
/// 2e-3 → 5e-6 → f32's rounding), `s = x·y` (within a few ulp), and one Newton step on the root with the
/// exact residual `x − s²` (TwoProduct): `s + (x − s²)·y/2`. With two steps on `1/√x` instead of three,
/// `s` is 5e-6 off and the last step leaves an error large enough to round some near-ties the wrong way.
/// Every step scales exactly with `x → 4x` (the estimate halves, the rest is homogeneous), so what holds
/// over two binades holds everywhere in range.
#[inline(never)]
pub(crate) fn sqrt_f32(x: f32) -> f32 {
    if !(f32::MIN_POSITIVE..=f32::MAX).contains(&x) {
        return if x == 0.0 || x == f32::INFINITY {
            x
        } else {
            f32::NAN
        };
    }
    let h = 0.5 * x;
    let mut y = f32::from_bits(0x5f37_5a86 - (x.to_bits() >> 1));
    y = y * (1.5 - h * y * y);
    y = y * (1.5 - h * y * y);
    y = y * (1.5 - h * y * y);
    let s = x * y;
    // x − p is exact (Sterbenz: p is within a few ulp of x); e is the square's rounding.
    let (p, e) = two_product(s, s);
    s + ((x - p) - e) * (0.5 * y)
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::{eprintln, vec::Vec};

    fn ulp_f32(v: f64) -> f64 {
        // The spacing of f32 at |v| (normal range).
        let e = v.abs().log2().floor() as i32;
        2f64.powi(e - 23)
    }

    /// Every f32 in [0.05, 8192] (the step path's half angles and their halves): within the stated bounds.
    #[test]
    fn sin_f32_is_within_its_bounds_for_every_argument_in_range() {
        let (lo, hi) = (0.05f32.to_bits(), SIN_F32_MAX.to_bits());
        let (mut max_ulp, mut max_abs, mut at) = (0.0f64, 0.0f64, 0.0f32);
        for bits in lo..=hi {
            let x = f32::from_bits(bits);
            let exact = libm::sin(f64::from(x));
            let got = f64::from(sin_f32(x));
            let abs = (got - exact).abs();
            max_abs = max_abs.max(abs);
            if exact.abs() >= 1.0 / 32.0 {
                let u = abs / ulp_f32(exact);
                if u > max_ulp {
                    (max_ulp, at) = (u, x);
                }
            }
        }
        eprintln!("sin_f32: max {max_ulp:.3} ulp (at {at}), max abs {max_abs:.3e}");
        assert!(max_ulp <= SIN_F32_MAX_ULP, "{max_ulp} ulp at {at}");
        assert!(max_abs <= SIN_F32_MAX_ABS, "{max_abs:e}");
    }

    /// Every f32 in [0.01, 2²⁸] (the large-angle branch's |v|² from the Taylor threshold up to where
    /// `sin_f32` refuses), and the ends of the range: correctly rounded. (The f64 root rounded to f32 is
    /// the correctly rounded f32 root: 53 ≥ 2·24 + 2 makes the double rounding innocuous.)
    #[test]
    fn sqrt_f32_is_correctly_rounded_for_every_argument_in_range() {
        let (lo, hi) = (0.01f32.to_bits(), 2f32.powi(28).to_bits());
        let extremes = [
            2f32.powi(-120),
            1.5 * 2f32.powi(-120),
            2f32.powi(126),
            1.99 * 2f32.powi(125),
        ];
        let wrong: Vec<f32> = (lo..=hi)
            .map(f32::from_bits)
            .chain(extremes)
            .filter(|&x| sqrt_f32(x) != libm::sqrt(f64::from(x)) as f32)
            .take(5)
            .collect();
        assert!(wrong.is_empty(), "not correctly rounded at {wrong:?}");
    }

    #[test]
    fn sqrt_f32_handles_what_is_not_a_normal_positive_number() {
        assert_eq!(sqrt_f32(0.0), 0.0);
        assert_eq!(sqrt_f32(f32::INFINITY), f32::INFINITY);
        for x in [
            -1.0,
            -f32::MIN_POSITIVE,
            f32::MIN_POSITIVE / 2.0,
            f32::NAN,
            f32::NEG_INFINITY,
        ] {
            assert!(sqrt_f32(x).is_nan(), "{x}");
        }
    }

    #[test]
    fn sin_f32_refuses_what_it_does_not_cover() {
        for x in [-1.0, -f32::MIN_POSITIVE, 8192.001, f32::INFINITY, f32::NAN] {
            assert!(sin_f32(x).is_nan(), "{x}");
        }
        assert_eq!(sin_f32(0.0), 0.0);
        assert!(sin_f32(SIN_F32_MAX).is_finite());
    }
}
