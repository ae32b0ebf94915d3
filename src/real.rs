//! The floating-point types the library runs in: a sealed trait implemented for `f32` and `f64`.
//!
//! Every algorithm is generic over [`Real`]. Constants are associated consts, so no conversion runs on the
//! step path; coefficients written as `f64` literals are converted with [`Real::from_f64`], which the
//! compiler folds to a constant.
//!
//! Math backend: `libm` (correctly rounded `sqrt`; `sin`, `cos`, `atan2` within 1 ulp). On
//! `thumbv7em-none-eabihf` `libm::sqrtf` is a software routine, not `vsqrt.f32` (see docs/firmware.md); the
//! step path avoids square roots wherever an algebraic form exists (polynomial RK steps, Taylor branch of
//! the exponential map, first-order normalization).

use core::fmt::{Debug, Display};
use core::marker::PhantomData;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

pub(crate) mod sealed {
    /// The crate's internal floating-point operations. The trait is not nameable outside the crate, so
    /// [`super::Real`] is sealed and these items stay out of the public API.
    pub trait Float: Copy {
        /// `true` where this type has hardware arithmetic (f32 on `eabihf` ARM, f32 and f64 on x86-64 and
        /// aarch64). Chooses how finiteness is checked: a multiply-add probe is cheap with an FPU and costly
        /// in software float, where integer bit tests win.
        const HARDWARE_FLOAT: bool;
        /// Largest squared half-angle `x²` (rad²) for which the exponential map uses its Taylor branch.
        /// Chosen so that the first omitted term (x⁶/720 in cos, x⁶/5040 in sin x / x) is below a quarter
        /// ulp: `f32`: x < 0.1, `f64`: x < 0.005.
        const EXP_TAYLOR_MAX_SQ: Self;
        /// Natural exponential.
        fn exp(self) -> Self;
        /// Sine on the step path (the exponential map's large-angle branch): `f32`:
        /// [`crate::trig::sin_f32`] (`0 ≤ x ≤ 8192`, NaN beyond; no `f64` code linked); `f64`: libm.
        fn sin_step(self) -> Self;
        /// Square root on the step path (the exponential map's large-angle branch): `f32`:
        /// [`crate::trig::sqrt_f32`] (no table, no libm); `f64`: libm.
        fn sqrt_step(self) -> Self;
        /// `sqrt(self² + y²)` without undue overflow or underflow.
        fn hypot(self, y: Self) -> Self;
        /// The larger of two numbers by one comparison (`other` if either is NaN). For validated, finite
        /// values: `f32::max`'s NaN handling costs a call to `fmaxf` on Cortex-M4.
        fn max(self, other: Self) -> Self;
        /// `atan2` of the Euler-angle conversions: `libm`, or `micromath` for `f32` with the `micromath`
        /// feature (max error about 0.002 rad, see its documentation).
        fn atan2_conversion(self, x: Self) -> Self;
        /// `w² + x² + y² + z² − 1` with its own rounding error far below ε (`f32`: in `f64`, where the
        /// squares are exact; `f64`: compensated with `fma`). Telemetry only, never on the step path.
        fn sum_sq_minus_one(w: Self, x: Self, y: Self, z: Self) -> Self;
        /// `Table`'s constants rounded to this type (to nearest, as [`super::Real::from_f64`]), once per
        /// table and type, at compile time: a table of coefficients is written once, in `f64`, where it is
        /// used, and generic code reads it in its own precision with no conversion on its path.
        fn rounded<Table: F64Table<ROWS, COLS>, const ROWS: usize, const COLS: usize>(
        ) -> &'static [[Self; COLS]; ROWS];
        /// Converts an integer (rounds to nearest beyond 2²⁴ for `f32`): one instruction with an FPU.
        fn from_i32(v: i32) -> Self;
        /// Converts to an integer (toward zero, saturating): one instruction with an FPU.
        fn to_i32(self) -> i32;
    }

    /// A table of `f64` constants (`ROWS` × `COLS`) that generic code reads in its own precision through
    /// [`Float::rounded`]. Implemented by a unit type beside the code that owns the table.
    pub trait F64Table<const ROWS: usize, const COLS: usize> {
        /// The table, in `f64`.
        const F64: [[f64; COLS]; ROWS];
    }
}

use sealed::F64Table;

/// The tables of [`F64Table`]s rounded to `T`: an associated const per table and type, so each is rounded
/// once, at compile time.
struct Rounded<T, Table, const ROWS: usize, const COLS: usize>(PhantomData<(T, Table)>);

/// A real number type the propagator computes in: `f32` (what firmware runs) or `f64`.
///
/// Sealed: the algorithms rely on IEEE 754 binary32/binary64 rounding.
pub trait Real:
    sealed::Float
    + Copy
    + Default
    + Debug
    + Display
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + 'static
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 1/2.
    const HALF: Self;
    /// π.
    const PI: Self;
    /// Machine epsilon: the gap between 1 and the next representable number (2⁻²³ or 2⁻⁵²).
    const EPSILON: Self;
    /// Largest finite value.
    const MAX: Self;

    /// Converts an `f64` constant (rounds to nearest for `f32`).
    fn from_f64(v: f64) -> Self;
    /// Widens to `f64` (exact).
    fn to_f64(self) -> f64;
    /// Correctly rounded square root.
    fn sqrt(self) -> Self;
    /// Sine (rad).
    fn sin(self) -> Self;
    /// Cosine (rad).
    fn cos(self) -> Self;
    /// Four-quadrant arctangent of `self / x` (rad, in (−π, π]).
    fn atan2(self, x: Self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// `true` unless NaN or ±∞.
    fn is_finite(self) -> bool;
}

/// Trait methods that pass `self` (and further arguments of type `Self`) to a per-precision function and
/// return its value: `fn sqrt(self) => libm::sqrtf;` is `fn sqrt(self) -> Self { libm::sqrtf(self) }`.
macro_rules! forward {
    ($(fn $name:ident(self $(, $arg:ident)*) => $f:path;)*) => {
        $(
            #[inline(always)]
            fn $name(self $(, $arg: Self)*) -> Self {
                $f(self $(, $arg)*)
            }
        )*
    };
}

macro_rules! impl_real {
    ($t:ty, $abs:path, $sqrt:path, $sqrt_step:path, $sin:path, $sin_step:path, $cos:path, $exp:path, $atan2:path, $hypot:path, $conv_atan2:path, $sum_sq:path, $taylor:expr, $hw:expr) => {
        impl sealed::Float for $t {
            const EXP_TAYLOR_MAX_SQ: Self = $taylor;
            const HARDWARE_FLOAT: bool = $hw;
            forward! {
                fn exp(self) => $exp;
                fn sin_step(self) => $sin_step;
                fn sqrt_step(self) => $sqrt_step;
                fn hypot(self, y) => $hypot;
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                if self > other {
                    self
                } else {
                    other
                }
            }
            #[inline]
            fn atan2_conversion(self, x: Self) -> Self {
                $conv_atan2(self, x)
            }
            #[inline]
            fn sum_sq_minus_one(w: Self, x: Self, y: Self, z: Self) -> Self {
                $sum_sq(w, x, y, z)
            }
            #[inline(always)]
            fn rounded<Table: F64Table<ROWS, COLS>, const ROWS: usize, const COLS: usize>(
            ) -> &'static [[Self; COLS]; ROWS] {
                &Rounded::<$t, Table, ROWS, COLS>::TABLE
            }
            // The integer casts, alike in shape to `Real`'s `from_f64` and `to_f64` below.
            #[inline(always)]
            fn from_i32(v: i32) -> Self {
                v as $t
            }
            #[inline(always)]
            fn to_i32(self) -> i32 {
                self as i32
            }
        }

        impl<Table: F64Table<ROWS, COLS>, const ROWS: usize, const COLS: usize>
            Rounded<$t, Table, ROWS, COLS>
        {
            const TABLE: [[$t; COLS]; ROWS] = {
                let t = Table::F64;
                let mut out = [[0.0; COLS]; ROWS];
                let mut r = 0;
                while r < ROWS {
                    let mut c = 0;
                    while c < COLS {
                        out[r][c] = t[r][c] as $t;
                        c += 1;
                    }
                    r += 1;
                }
                out
            };
        }

        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const TWO: Self = 2.0;
            const HALF: Self = 0.5;
            const PI: Self = core::f64::consts::PI as $t;
            const EPSILON: Self = <$t>::EPSILON;
            const MAX: Self = <$t>::MAX;

            #[inline(always)]
            fn from_f64(v: f64) -> Self {
                v as $t
            }
            #[inline(always)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            // `abs` is not `<$t>::abs`: before Rust 1.85 core has no inherent `abs`, and that path
            // resolves to this trait method itself (unbounded recursion; the MSRV job runs the quick start).
            forward! {
                fn sqrt(self) => $sqrt;
                fn sin(self) => $sin;
                fn cos(self) => $cos;
                fn atan2(self, x) => $atan2;
                fn abs(self) => $abs;
            }
            #[inline(always)]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
        }
    };
}

impl_real!(
    f32,
    libm::fabsf,
    libm::sqrtf,
    crate::trig::sqrt_f32,
    libm::sinf,
    crate::trig::sin_f32,
    libm::cosf,
    libm::expf,
    libm::atan2f,
    libm::hypotf,
    conversion_atan2_f32,
    sum_sq_minus_one_f32,
    1.0e-2,
    cfg!(any(
        target_arch = "x86",
        target_arch = "x86_64",
        target_arch = "aarch64",
        all(target_arch = "arm", target_abi = "eabihf")
    ))
);
impl_real!(
    f64,
    libm::fabs,
    libm::sqrt,
    libm::sqrt,
    libm::sin,
    libm::sin,
    libm::cos,
    libm::exp,
    libm::atan2,
    libm::hypot,
    libm::atan2,
    sum_sq_minus_one_f64,
    2.5e-5,
    cfg!(any(
        target_arch = "x86",
        target_arch = "x86_64",
        target_arch = "aarch64"
    ))
);

/// micromath's `atan2(0, 0)` is NaN (libm's is 0, and the identity's Euler angles need 0): guarded here.
#[cfg(feature = "micromath")]
#[inline]
fn conversion_atan2_f32(y: f32, x: f32) -> f32 {
    if y == 0.0 && x == 0.0 {
        0.0
    } else {
        micromath::F32Ext::atan2(y, x)
    }
}

#[cfg(not(feature = "micromath"))]
#[inline]
fn conversion_atan2_f32(y: f32, x: f32) -> f32 {
    libm::atan2f(y, x)
}

/// Squares of `f32` values are exact in `f64`; the `f64` sum then carries a relative error ≤ 2⁻⁵¹.
#[inline]
fn sum_sq_minus_one_f32(w: f32, x: f32, y: f32, z: f32) -> f32 {
    let (w, x, y, z) = (w as f64, x as f64, y as f64, z as f64);
    ((((w * w - 1.0) + x * x) + y * y) + z * z) as f32
}

/// Each square as an exact pair `p + e = a²` (via `fma`), summed with Neumaier's compensation.
/// A sum of squares that overflows is `+∞` (not the NaN that `∞ − ∞` in the compensation would give).
#[inline]
fn sum_sq_minus_one_f64(w: f64, x: f64, y: f64, z: f64) -> f64 {
    let naive = w * w + x * x + y * y + z * z;
    if !naive.is_finite() {
        return naive;
    }
    let mut sum = -1.0_f64;
    let mut comp = 0.0_f64;
    for a in [w, x, y, z] {
        let p = a * a;
        let e = libm::fma(a, a, -p);
        for term in [p, e] {
            let t = sum + term;
            comp += if sum.abs() >= term.abs() {
                (sum - t) + term
            } else {
                (term - t) + sum
            };
            sum = t;
        }
    }
    sum + comp
}

#[cfg(test)]
mod tests {
    use super::sealed::{F64Table, Float};
    use super::Real;

    /// A table whose entries round differently in `f32` (1/3, 0.1, a subnormal, beyond `f32::MAX`).
    struct Awkward;
    impl F64Table<2, 3> for Awkward {
        const F64: [[f64; 3]; 2] = [[1.0 / 3.0, 0.1, -1.0e-40], [1.0e39, -0.0, 2.5]];
    }

    /// `Float::rounded` is each entry through `Real::from_f64`, bit for bit, in both precisions.
    #[test]
    fn rounded_tables_are_from_f64_of_each_entry() {
        fn check<T: Real>(to_bits: fn(T) -> u64) {
            let t = T::rounded::<Awkward, 2, 3>();
            for (row, row64) in t.iter().zip(Awkward::F64) {
                for (&v, v64) in row.iter().zip(row64) {
                    assert_eq!(to_bits(v), to_bits(T::from_f64(v64)), "{v64:e}");
                }
            }
        }
        check::<f32>(|v| v.to_bits() as u64);
        check::<f64>(f64::to_bits);
    }

    /// `Real::abs` clears the sign bit and nothing else, in both precisions (on Rust < 1.85 an `abs` written
    /// `<f32>::abs(self)` called itself: .ci/msrv runs this with the MSRV toolchain).
    #[test]
    fn abs_clears_the_sign_bit_only() {
        for x in [
            -1.5_f32,
            1.5,
            -0.0,
            0.0,
            -f32::INFINITY,
            -f32::MIN_POSITIVE / 4.0,
            -f32::NAN,
        ] {
            assert_eq!(Real::abs(x).to_bits(), x.to_bits() & 0x7fff_ffff, "{x}");
        }
        for x in [
            -1.5_f64,
            1.5,
            -0.0,
            0.0,
            -f64::INFINITY,
            -f64::MIN_POSITIVE / 4.0,
            -f64::NAN,
        ] {
            assert_eq!(Real::abs(x).to_bits(), x.to_bits() & (u64::MAX >> 1), "{x}");
        }
    }

    #[test]
    fn sum_sq_minus_one_resolves_below_epsilon() {
        // 1 + 2⁻³⁰ is representable in f64; its square minus one is 2⁻²⁹ + 2⁻⁶⁰ exactly.
        let a = 1.0 + 2f64.powi(-30);
        let n = f64::sum_sq_minus_one(a, 0.0, 0.0, 0.0);
        assert_eq!(n, 2f64.powi(-29) + 2f64.powi(-60));
        // A naive sum would return 0 here: 1 + 2⁻⁶⁰ rounds to 1.
        let tiny = 2f64.powi(-30);
        assert_eq!(f64::sum_sq_minus_one(1.0, tiny, 0.0, 0.0), 2f64.powi(-60));
        // Overflow of |q|² is +∞ in both precisions, never NaN.
        assert_eq!(f64::sum_sq_minus_one(1e155, 0.0, 0.0, 0.0), f64::INFINITY);
        assert_eq!(f32::sum_sq_minus_one(1e20, 0.0, 0.0, 0.0), f32::INFINITY);
        let t32 = 2f32.powi(-20);
        assert_eq!(f32::sum_sq_minus_one(1.0, t32, 0.0, 0.0), 2f32.powi(-40));
    }

    #[test]
    fn taylor_threshold_truncation_is_below_quarter_ulp() {
        // First omitted terms at the threshold, relative to the value (cos x ≈ 1, sin x / x ≈ 1).
        for (x2, eps) in [
            (f32::EXP_TAYLOR_MAX_SQ as f64, f32::EPSILON as f64),
            (f64::EXP_TAYLOR_MAX_SQ, f64::EPSILON),
        ] {
            let cos_term = x2 * x2 * x2 / 720.0;
            let sinc_term = x2 * x2 * x2 / 5040.0;
            assert!(
                cos_term < eps / 4.0,
                "cos truncation {cos_term:e} vs eps {eps:e}"
            );
            assert!(sinc_term < eps / 4.0);
        }
    }
}
