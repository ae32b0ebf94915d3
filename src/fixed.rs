//! Fixed point for cores without an FPU (Cortex-M0/M0+, Cortex-M3): the recommended configuration
//! (ExpMap + History + FirstOrder) on raw gyro counts in integer arithmetic, with a Q30 attitude.
//!
//! On such a core every `f32` operation is a call into software floating point: the recommended `f32`
//! step costs about 12 500 instructions on a Cortex-M0 and 7 300 on a Cortex-M3 (docs/firmware.md), a
//! quarter of a 48 MHz M0 at 1 kHz. [`Q30Propagator`] takes the gyro's `i16` counts at a fixed period and
//! does the same step in integers:
//!
//! - the sample history's weights on the counts are exact integers (the cubic's mean rate is
//!   `(24ω_k + 9Δ₃ + 4Δ₂ − Δ₁)/24`, its rate at mid-step `(16ω_k + 4Δ₂ − Δ₁)/16`), with the same start-up
//!   and start correction as [`crate::input::History`];
//! - the half angle (rad, Q31) is the exact integer sum times one constant `period · rad_per_count / 48`
//!   held as a 31-bit mantissa and a shift, so the only roundings of the step are the final shifts;
//! - the second Magnus term from the exact integer cross product `(16ω(½)) × Δ₃` (i64);
//! - the exponential map by its Taylor series to `|v|⁶` (exact to 1 unit of Q30 for half angles up to ¼
//!   rad; a step beyond 0.5 rad is refused), the product `q ⊗ (exp(v) − 1)` with 64-bit sums rounded once
//!   per component, and the first-order norm correction.
//!
//! Every shift rounds to nearest (truncation would bias every step the same way: a drift of half a unit of
//! Q31 per step), and what the roundings of the half angle and of the attitude leave out is carried to the
//! next step. The attitude is Q30: a unit of 2⁻³⁰ = 9.3·10⁻¹⁰, 128 times finer than an `f32`'s ε. Its
//! error is measured the way `f32`'s is, against an `f64` propagator fed the same samples (`tests/fixed.rs`,
//! docs/own_error.md): 2.8·10⁻⁹ rad after 200 s of a random motion at 1 kHz (f32: 1.8·10⁻⁵). What still
//! repeats step after step on a steady rate is the rounding of `sinc|v| − 1 ≈ −|v|²/6` to Q31, which for
//! small steps is a few tens of units: a relative error of a few 10⁻¹⁰ in each step's angle (2.4·10⁻⁷ rad
//! after 1000 rad of turning).
//!
//! Conventions as everywhere: Hamilton product, scalar first, body-frame rates, the attitude turns body
//! vectors into the reference frame.
//!
//! ```
//! use quatprop::fixed::Q30Propagator;
//! use quatprop::Quat;
//! // ±2000 °/s on 16 bits (16.4 counts per °/s) at 1 kHz.
//! let rad_per_count = (1.0 / 16.4_f32).to_radians();
//! let mut p = Q30Propagator::new(Quat::IDENTITY, rad_per_count, 1.0e-3)?;
//! for _ in 0..1001 {
//!     p.push([0, 0, 1640])?; // 100 °/s about z
//! }
//! let yaw = 2.0 * p.attitude().z.atan2(p.attitude().w);
//! assert!((yaw.to_degrees() - 100.0).abs() < 1e-3); // 1000 intervals of 1 ms
//! # Ok::<(), quatprop::Error>(())
//! ```

use crate::propagator::{checked_unit, Refused};
use crate::{Error, Quat, Real};

/// One in Q30.
const ONE_Q30: i64 = 1 << 30;

/// The largest half angle `|v|` of a step (rad): ¼, a step angle of 0.5 rad, where the Taylor series of the
/// exponential map, cut after `|v|⁶`, is still exact to a unit of Q30.
const MAX_HALF_ANGLE: f64 = 0.25;

/// A positive constant as `(mantissa + extra · 2⁻³¹) · 2⁻shift`: `extra` carries the mantissa's rounding
/// (the next 31 bits; zero where a single word is precise enough).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Scale {
    mantissa: i64,
    extra: i64,
    shift: u32,
}

impl Scale {
    /// `value` with a mantissa in `[2^(bits−1), 2^bits)` and a shift in 1..=62; `None` if that shift is out
    /// of range (or `value` is not finite and positive).
    fn new(value: f64, bits: u32) -> Option<Self> {
        if !(value > 0.0 && value < f64::INFINITY) {
            return None;
        }
        let (low, high) = (
            f64::from(1u32 << (bits - 1)),
            f64::from(1u32 << (bits - 1)) * 2.0,
        );
        let mut m = value;
        let mut shift: i32 = 0;
        // Bounded: a finite positive f64 is within 2^±1075.
        while m < low && shift < 2000 {
            m *= 2.0;
            shift += 1;
        }
        while m >= high && shift > -2000 {
            m *= 0.5;
            shift -= 1;
        }
        let shift = u32::try_from(shift).ok().filter(|s| (1..=62).contains(s))?;
        let mantissa = libm::rint(m);
        Some(Self {
            mantissa: mantissa as i64,
            extra: libm::rint((m - mantissa) * 2_147_483_648.0) as i64,
            shift,
        })
    }

    /// `round(x · mantissa · 2⁻shift)`; `x · mantissa` must fit an i64 (the callers' bounds; the
    /// rounding is carried by [`Q30Propagator`]).
    #[inline(always)]
    fn apply(self, x: i64) -> i64 {
        shr_round(x.wrapping_mul(self.mantissa), self.shift)
    }
}

/// `x / 2^s` rounded to nearest (ties up), for `s` in 1..=62.
#[inline(always)]
fn shr_round(x: i64, s: u32) -> i64 {
    x.wrapping_add(1_i64.wrapping_shl(s.wrapping_sub(1)))
        .wrapping_shr(s)
}

/// `a · b` for operands that fit an i32 (the callers' bounds), as a 32 × 32 → 64-bit multiply.
///
/// On Thumb-1-only cores (ARMv6-M: Cortex-M0/M0+/M1, told apart by their lack of 32-bit atomic
/// read-modify-write, the one `cfg` that marks them) there is no such instruction, and an i64 product is a
/// call to the general 64 × 64-bit `__aeabi_lmul`; four 16 × 16-bit products inline cost about half.
#[inline(always)]
fn wide(a: i64, b: i64) -> i64 {
    let (a, b) = (a as i32, b as i32);
    if cfg!(all(target_arch = "arm", not(target_has_atomic = "32"))) {
        wide_by_halves(a, b)
    } else {
        i64::from(a) * i64::from(b)
    }
}

/// `a · b` from four 16 × 16-bit products (exact for every pair of i32).
#[inline(always)]
fn wide_by_halves(a: i32, b: i32) -> i64 {
    // a = ah·2¹⁶ + al, al in [0, 2¹⁶): |ah·bh| ≤ 2³⁰, |ah·bl| < 2³¹, al·bl < 2³² unsigned.
    let (ah, al) = (a >> 16, a & 0xffff);
    let (bh, bl) = (b >> 16, b & 0xffff);
    let high = i64::from(ah * bh) << 32;
    let middle = (i64::from(ah * bl) + i64::from(al * bh)) << 16;
    high + middle + i64::from((al as u32) * (bl as u32))
}

/// `a · b / 2³¹` rounded, for Q31/Q30 operands that fit an i32.
#[inline(always)]
fn mul_q31(a: i64, b: i64) -> i64 {
    shr_round(wide(a, b), 31)
}

/// The recommended step (ExpMap + History + FirstOrder) in fixed point: raw `i16` gyro counts at a fixed
/// period in, a Q30 attitude out. See the [module](self) for the arithmetic; every operation is an
/// integer one, so a core without an FPU runs it without software floating point (construction and
/// [`Q30Propagator::attitude`] convert once).
///
/// The counts are body-frame rates: apply the axis remap (a permutation with signs is exact on counts)
/// and subtract the bias upstream. A count at `i16::MIN` or `i16::MAX` is integrated and counted as
/// saturated ([`Q30Propagator::saturated_samples`]), as [`crate::frontend::CountScale`] does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Q30Propagator {
    /// The attitude `[w, x, y, z]`, Q30.
    q: [i32; 4],
    /// What rounding the last increments to Q30 left out, in units of 2⁻⁶¹ (below 2³⁰ in magnitude): added
    /// to the next increment before it is rounded, so the roundings do not accumulate (compensated
    /// summation).
    low: [i32; 4],
    /// What rounding the last half angle to Q31 left out, in units of `2^−(31 + angle.shift)` (below
    /// `2^(angle.shift − 1)` in magnitude): added before the next one is rounded, so a steady rate's
    /// rounding does not accumulate into a scale error.
    angle_low: [i64; 3],
    /// The newest sample (counts).
    w: [i32; 3],
    /// `[Δ₁, Δ₂]`, the differences of the kept samples (counts; the last `kept − 1` are valid).
    d: [[i32; 3]; 2],
    /// Samples kept (0 to 3).
    kept: u8,
    /// Half angle (Q31) per unit of the mean rate ×24: `period · rad_per_count / 48`.
    angle: Scale,
    /// Second Magnus term per unit of `(16ω(½)) × Δ₃`, `(period · rad_per_count)² / 384`, in units of the
    /// half angle's exact sum (its shift relative to `angle`'s).
    commutator: Scale,
    steps: u64,
    saturated: u64,
}

/// The components of `q ⊗ e` as Q61 sums (Hamilton product, scalar first); `e`'s components fit an i32.
#[inline(always)]
fn product_q61(q: [i32; 4], e: [i64; 4]) -> [i64; 4] {
    let [qw, qx, qy, qz] = q.map(i64::from);
    let [ew, ex, ey, ez] = e;
    [
        wide(qw, ew) - wide(qx, ex) - wide(qy, ey) - wide(qz, ez),
        wide(qw, ex) + wide(qx, ew) + wide(qy, ez) - wide(qz, ey),
        wide(qw, ey) - wide(qx, ez) + wide(qy, ew) + wide(qz, ex),
        wide(qw, ez) + wide(qx, ey) - wide(qy, ex) + wide(qz, ew),
    ]
}

impl Q30Propagator {
    /// A propagator from attitude `q0` (normalized here) for a gyro of `rad_per_count` (rad/s per count)
    /// sampled every `period` seconds.
    ///
    /// # Errors
    /// - [`Error::NonFiniteQuaternion`] or [`Error::ZeroQuaternion`] for `q0`;
    /// - [`Error::NonFiniteStep`] / [`Error::NonPositiveStep`] for `period`;
    /// - [`Error::InvalidScale`]: `rad_per_count` is not finite and positive, or `period · rad_per_count`
    ///   is outside what the integer step represents (one count over one period must turn by less than
    ///   2⁻⁶ rad and more than 2⁻⁴⁰ rad: from a ±2000 °/s gyro at 1 MHz to a ±250 °/s one at 1 Hz).
    pub fn new<T: Real>(q0: Quat<T>, rad_per_count: T, period: T) -> Result<Self, Error> {
        let q0 = checked_unit(q0)?;
        let (s, h) = (rad_per_count.to_f64(), period.to_f64());
        if !h.is_finite() {
            return Err(Error::NonFiniteStep);
        }
        if !(h > 0.0) {
            return Err(Error::NonPositiveStep);
        }
        if !(s > 0.0 && s < f64::INFINITY) {
            return Err(Error::InvalidScale);
        }
        let per_count = s * h;
        if !(per_count < 1.0 / 64.0 && per_count > 1.0 / 1_099_511_627_776.0) {
            return Err(Error::InvalidScale);
        }
        // Half angle per unit of the ×24 mean: s·h/48, in Q31. The ×24 sums are below 2²¹ and the
        // mantissa at most 2³⁰ (an i32: a 32 × 32-bit product). Its rounding (2⁻³⁰ relative) would be a
        // scale error, an angle short or long by that fraction of every turn: the next 31 bits (`extra`)
        // take it to f64's precision.
        let angle =
            Scale::new(per_count / 48.0 * 2_147_483_648.0, 30).ok_or(Error::InvalidScale)?;
        // ¼·(s·h)²/(6·16), in units of the half angle's exact sum (2^−(31 + angle.shift)): the cross
        // product (16ω(½)) × Δ₃ is below 2³⁸ and the mantissa below 2²⁴ (a relative 2⁻²⁴ on a term that
        // is itself O(h²) of the step). The term is below 2⁻⁹ of the first per count, so its shift is at
        // least 1; below 2⁻⁶² · 2²³ it rounds to zero for any cross product, and the scale is zero.
        let commutator = Scale::new(per_count * per_count / 384.0 * 2_147_483_648.0, 24)
            .and_then(|c| {
                Some(Scale {
                    mantissa: c.mantissa,
                    extra: 0,
                    shift: c.shift.checked_sub(angle.shift).filter(|&s| s >= 1)?,
                })
            })
            .unwrap_or(Scale {
                mantissa: 0,
                extra: 0,
                shift: 1,
            });
        let to_q30 = |v: T| libm::rint(v.to_f64() * ONE_Q30 as f64) as i32;
        Ok(Self {
            q: [to_q30(q0.w), to_q30(q0.x), to_q30(q0.y), to_q30(q0.z)],
            low: [0; 4],
            angle_low: [0; 3],
            w: [0; 3],
            d: [[0; 3]; 2],
            kept: 0,
            angle,
            commutator,
            steps: 0,
            saturated: 0,
        })
    }

    /// Takes the next sample: raw counts `[x, y, z]` (body axes), one period after the previous one. The
    /// first sample after [`Q30Propagator::new`] or [`Q30Propagator::restart_input`] only starts the
    /// history; each later one closes a step.
    ///
    /// # Errors
    /// [`Error::StepAngleBeyondStability`] if the step would turn by more than 0.5 rad (beyond any gyro's
    /// range at the periods [`Q30Propagator::new`] accepts unless the period is long); the propagator is
    /// then unchanged and the sample not taken.
    #[inline]
    pub fn push(&mut self, counts: [i16; 3]) -> Result<(), Error> {
        let w = counts.map(i32::from);
        let c = self.w;
        let d3: [i32; 3] = core::array::from_fn(|i| w[i] - c[i]);
        let [d1, d2] = self.d;
        if self.kept > 0 {
            // Mean rate ×24 and rate at mid-step ×16 of the linear (1 kept), quadratic with the start
            // correction (2) or cubic (3) step; exact in i32 (|·| < 2²¹).
            let (m24, mid16): ([i32; 3], [i32; 3]) = match self.kept {
                1 => (
                    core::array::from_fn(|i| 24 * c[i] + 12 * d3[i]),
                    core::array::from_fn(|i| 16 * c[i]),
                ),
                2 => (
                    core::array::from_fn(|i| 24 * c[i] + 8 * d3[i] + 4 * d2[i]),
                    core::array::from_fn(|i| 16 * c[i] + 4 * d2[i]),
                ),
                _ => (
                    core::array::from_fn(|i| 24 * c[i] + 9 * d3[i] + 4 * d2[i] - d1[i]),
                    core::array::from_fn(|i| 16 * c[i] + 4 * d2[i] - d1[i]),
                ),
            };
            self.step(m24, mid16, d3)?;
        }
        if counts.iter().any(|&k| k == i16::MAX || k == i16::MIN) {
            self.saturated = self.saturated.wrapping_add(1);
        }
        self.d = [d2, d3];
        self.w = w;
        self.kept = (self.kept + 1).min(3);
        Ok(())
    }

    /// Pushes a FIFO burst; at the first refused sample it stops and returns its index and error, the
    /// propagator as it was after the last accepted sample.
    ///
    /// # Errors
    /// As [`Q30Propagator::push`], with the sample's index ([`Refused`]).
    pub fn push_burst(&mut self, samples: &[[i16; 3]]) -> Result<usize, Refused> {
        for (index, s) in samples.iter().enumerate() {
            self.push(*s).map_err(|error| Refused { index, error })?;
        }
        Ok(samples.len())
    }

    /// The step from the mean rate ×24, the rate at mid-step ×16 and Δ₃ (counts); commits the attitude.
    #[inline(always)]
    fn step(&mut self, m24: [i32; 3], mid16: [i32; 3], d3: [i32; 3]) -> Result<(), Error> {
        let [a, b] = [mid16.map(i64::from), d3.map(i64::from)];
        // (16ω(½)) × Δ₃, exact (|·| < 2³⁸).
        let cross = [
            wide(a[1], b[2]) - wide(a[2], b[1]),
            wide(a[2], b[0]) - wide(a[0], b[2]),
            wide(a[0], b[1]) - wide(a[1], b[0]),
        ];
        // The half angle v (Q31): ½∫ω plus the second Magnus term, summed in units of 2^−(31 + shift) with
        // what the last rounding left out, then rounded once.
        let mut v = [0_i64; 3];
        let mut angle_low = [0_i64; 3];
        for i in 0..3 {
            let m = i64::from(m24[i]);
            let exact = wide(m, self.angle.mantissa)
                .wrapping_add(shr_round(wide(m, self.angle.extra), 31))
                .wrapping_add(self.commutator.apply(cross[i]))
                .wrapping_add(self.angle_low[i]);
            let rounded = shr_round(exact, self.angle.shift);
            angle_low[i] = exact.wrapping_sub(rounded.wrapping_shl(self.angle.shift));
            v[i] = rounded;
        }
        // |v|² (Q31), once every |v_i| is below ½ (2³⁰): then it fits.
        const LIMIT: i64 = ((MAX_HALF_ANGLE * MAX_HALF_ANGLE) * 2_147_483_648.0) as i64;
        let refused = |v: [i64; 3]| {
            let norm = libm::sqrt(v.iter().map(|&x| (x as f64) * (x as f64)).sum::<f64>());
            Error::StepAngleBeyondStability {
                step_angle: 2.0 * norm / 2_147_483_648.0,
                limit: 2.0 * MAX_HALF_ANGLE,
            }
        };
        if v.iter().any(|x| !(-(1 << 30)..1 << 30).contains(x)) {
            return Err(refused(v));
        }
        // |v|², exact in Q62 (< 3·2⁶⁰), and rounded to Q31 for the Taylor series' higher terms.
        let t62 = wide(v[0], v[0]) + wide(v[1], v[1]) + wide(v[2], v[2]);
        let t = shr_round(t62, 31);
        if t > LIMIT {
            return Err(refused(v));
        }
        // exp((0, v)) − 1 = (cos|v| − 1, sinc|v|·v), Taylor in t = |v|² (Horner, Q31 coefficients):
        // cos − 1 = −t/2 + t²/24 − t³/720, sinc − 1 = −t/6 + t²/120 − t³/5040.
        const C24: i64 = (2_147_483_648.0 / 24.0 + 0.5) as i64;
        const C720: i64 = (2_147_483_648.0 / 720.0 + 0.5) as i64;
        const C6: i64 = (2_147_483_648.0 / 6.0 + 0.5) as i64;
        const C120: i64 = (2_147_483_648.0 / 120.0 + 0.5) as i64;
        const C5040: i64 = (2_147_483_648.0 / 5040.0 + 0.5) as i64;
        // cos − 1 in Q62: the leading −t/2 exact (a rounded Q31 value would be off by the same fraction of
        // a unit every step of a steady rate: a drift), the rest in Q31; split as hi·2³¹ + lo.
        let cos_minus_one = -(t62 >> 1) + (mul_q31(t, mul_q31(t, C24 - mul_q31(t, C720))) << 31);
        let (ew_hi, ew_lo) = {
            let hi = shr_round(cos_minus_one, 31);
            (hi, cos_minus_one - (hi << 31))
        };
        let sinc_minus_one = mul_q31(t, mul_q31(t, C120 - mul_q31(t, C5040)) - C6);
        // q ⊗ (exp(v) − 1) in Q61 = (cos − 1)·q + q ⊗ (0, v) + (sinc − 1)·(q ⊗ (0, v)): the first two
        // exact products, the third (below 2⁻⁷ of the second) from the second rounded to Q31. Rounding
        // e = sinc·v to Q31 first would lose the same fraction of a unit every step of a steady rate.
        let pv = product_q61(self.q, [0, v[0], v[1], v[2]]);
        let inc: [i64; 4] = core::array::from_fn(|i| {
            let qi = i64::from(self.q[i]);
            wide(qi, ew_hi)
                + shr_round(wide(qi, ew_lo), 31)
                + pv[i]
                + shr_round(wide(shr_round(pv[i], 30), sinc_minus_one), 1)
        });
        // q + q ⊗ (exp(v) − 1) in Q61 with what the last rounding left out, rounded to Q30 for the norm.
        let sum: [i64; 4] = core::array::from_fn(|i| {
            (i64::from(self.q[i]) << 31) + inc[i] + i64::from(self.low[i])
        });
        let advanced: [i64; 4] = core::array::from_fn(|i| shr_round(sum[i], 31));
        // FirstOrder: q ← q − q·N/2, N = |q|² − 1 (Q60 sum, Q30 N). The correction q·N/2 is exact in Q61
        // (Q30 · Q30 = Q60, halved), so it joins the sum before the one rounding: a correction rounded on
        // its own would lose the same fraction of a unit step after step on a steady rotation (a drift).
        let n60 = advanced.iter().map(|&x| wide(x, x)).sum::<i64>() - (1 << 60);
        let n30 = shr_round(n60, 30);
        let mut low = [0_i32; 4];
        let mut corrected = [0_i64; 4];
        for i in 0..4 {
            let total = sum[i] - wide(advanced[i], n30);
            corrected[i] = shr_round(total, 31);
            // |total − rounded·2³¹| ≤ 2³⁰: fits an i32.
            low[i] = (total - (corrected[i] << 31)) as i32;
        }
        // |q_i| ≤ 1 + O(2⁻³⁰) < 2: each fits an i32 in Q30 (2³¹ is 2.0).
        let mut q = [0_i32; 4];
        for (out, &x) in q.iter_mut().zip(&corrected) {
            *out = i32::try_from(x).map_err(|_| Error::NonFiniteResult)?;
        }
        self.q = q;
        self.low = low;
        self.angle_low = angle_low;
        self.steps = self.steps.wrapping_add(1);
        Ok(())
    }

    /// Forgets the kept samples (after a gap in the data): the next sample starts the history afresh.
    pub fn restart_input(&mut self) {
        self.kept = 0;
    }

    /// The attitude as `f32` (body to reference; Hamilton, scalar first): the Q30 components / 2³⁰.
    #[must_use]
    pub fn attitude(&self) -> Quat<f32> {
        let f = |x: i32| x as f32 * (1.0 / ONE_Q30 as f32);
        Quat::new(f(self.q[0]), f(self.q[1]), f(self.q[2]), f(self.q[3]))
    }

    /// The attitude as `f64` (exact: every Q30 value is an `f64`).
    #[must_use]
    pub fn attitude_f64(&self) -> Quat<f64> {
        let f = |x: i32| f64::from(x) / ONE_Q30 as f64;
        Quat::new(f(self.q[0]), f(self.q[1]), f(self.q[2]), f(self.q[3]))
    }

    /// The attitude `[w, x, y, z]` in Q30 (1.0 = 2³⁰).
    #[must_use]
    pub fn attitude_q30(&self) -> [i32; 4] {
        self.q
    }

    /// Steps taken.
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Saturated samples accepted so far.
    #[must_use]
    pub fn saturated_samples(&self) -> u64 {
        self.saturated
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_product_by_halves_is_the_product() {
        let edges = [
            i32::MIN,
            i32::MIN + 1,
            -65537,
            -65536,
            -65535,
            -1,
            0,
            1,
            65535,
            65536,
            i32::MAX,
        ];
        for &a in &edges {
            for &b in &edges {
                assert_eq!(wide_by_halves(a, b), i64::from(a) * i64::from(b), "{a} {b}");
            }
        }
        // A deterministic spread of the rest (xorshift).
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let (a, b) = (x as i32, (x >> 32) as i32);
            assert_eq!(wide_by_halves(a, b), i64::from(a) * i64::from(b), "{a} {b}");
        }
    }
}
