//! The closed-form transition and process noise of one interval (see the module documentation).

use super::GyroNoise;
use crate::real::sealed::F64Table;
use crate::{Error, Quat, Real, Vec3};

/// A 3 × 3 matrix by rows.
type M3<T> = [[T; 3]; 3];

/// The error-state transition `Φ` of an interval: `Φθθ` ([`Transition::attitude`]), `Φθb`
/// ([`Transition::bias`]); the bias rows are `(0, I)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Transition<T> {
    /// `Φθθ = exp(−[φ×])`: how an attitude error at the start appears at the end (the interval's
    /// rotation, transposed: body axes at the start to body axes at the end).
    pub attitude: M3<T>,
    /// `Φθb`: how a bias error accumulates into attitude error over the interval (s).
    pub bias: M3<T>,
}

// `Transition` and `ProcessNoise` are plain data with the same derives and alike field lists (one
// block per matrix of the error state): alike in shape, each its own.
/// The process noise `Q` accumulated over an interval (symmetric): `Qθθ` (rad²), `Qθb` (rad²/s) and
/// `Qbb = bias · I` ((rad/s)²).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ProcessNoise<T> {
    /// `Qθθ` (symmetric).
    pub attitude: M3<T>,
    /// `Qθb`; the lower-left block is its transpose.
    pub cross: M3<T>,
    /// The diagonal of `Qbb = σ_b² Δt I`.
    pub bias: T,
}

/// One predict step of the error state `(δθ, δb)`: its transition and its process noise (see the
/// [module documentation](super) for the model and the formulas).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Step<T> {
    /// `Φ`.
    pub transition: Transition<T>,
    /// `Q`.
    pub noise: ProcessNoise<T>,
}

/// The largest rotation (rad) of one interval in f32: the step path's sine (`Float::sin_step`) covers
/// `0 ≤ x ≤ 8192`.
const SINE_LIMIT: f64 = 8192.0;

/// The closed form's coefficients of `x = |φ|`: `sin x/x`, `(1 − cos x)/x²`, `(x − sin x)/x³`,
/// `(x²/2 − 1 + cos x)/x⁴` and `(x³/3 + 2 sin x − 2x)/x⁵`.
struct Coefficients<T> {
    s1: T,
    c1: T,
    c2: T,
    c3: T,
    c4: T,
}

/// Below this `x²` the coefficients are their Taylor series (`x ≤ 2`: the closed forms lose at most one
/// digit to cancellation beyond it).
const SERIES_MAX_SQ: f64 = 4.0;
/// Terms of each series: the last term of the slowest (`sin x / x` at `x = 2`) is `2²⁶/27!`, 6e-21.
const SERIES_TERMS: usize = 14;

/// The five series' coefficients as a table each type rounds once, at compile time (`Float::rounded`).
struct StepSeries;

impl F64Table<5, SERIES_TERMS> for StepSeries {
    const F64: [[f64; SERIES_TERMS]; 5] = STEP_SERIES;
}

/// The coefficients `m (−1)ᵏ / (2k + p)!` of the five series, `(p, m)` = (1, 1), (2, 1), (3, 1), (4, 1),
/// (5, 2), computed at compile time.
const STEP_SERIES: [[f64; SERIES_TERMS]; 5] = {
    let mut out = [[0.0; SERIES_TERMS]; 5];
    let mut f = 0;
    while f < 5 {
        let p = f as u32 + 1;
        let m = if f == 4 { 2.0 } else { 1.0 };
        // (2k + p)! for k = 0, then the ratio (2k + p − 1)(2k + p) per term.
        let mut factorial = 1.0;
        let mut i = 2;
        while i <= p {
            factorial *= i as f64;
            i += 1;
        }
        let mut term = m / factorial;
        let mut k = 0;
        while k < SERIES_TERMS {
            out[f][k] = term;
            let next = 2 * (k as u32 + 1) + p;
            term = -term / (((next - 1) * next) as f64);
            k += 1;
        }
        f += 1;
    }
    out
};

/// `Σₖ cₖ x²ᵏ` by Horner's rule.
#[inline]
fn series<T: Real>(x2: T, c: &[T; SERIES_TERMS]) -> T {
    c.iter().rev().fold(T::ZERO, |acc, &ck| acc * x2 + ck)
}

impl<T: Real> Coefficients<T> {
    fn of(x2: T) -> Self {
        if x2 <= T::from_f64(SERIES_MAX_SQ) {
            let [s1, c1, c2, c3, c4] = T::rounded::<StepSeries, 5, SERIES_TERMS>();
            Self {
                s1: series(x2, s1),
                c1: series(x2, c1),
                c2: series(x2, c2),
                c3: series(x2, c3),
                c4: series(x2, c4),
            }
        } else {
            // The step path's sine and square root (f32: no libm, no f64 code; NaN beyond 8192 rad,
            // which `held_rate` refuses).
            let x = x2.sqrt_step();
            let (s, h) = (x.sin_step(), (x * T::HALF).sin_step());
            let one_minus_cos = T::TWO * h * h;
            let x3 = x2 * x;
            Self {
                s1: s / x,
                c1: one_minus_cos / x2,
                c2: (x - s) / x3,
                c3: (x2 * T::HALF - one_minus_cos) / (x2 * x2),
                c4: (x3 * T::from_f64(1.0 / 3.0) + T::TWO * (s - x)) / (x3 * x2),
            }
        }
    }
}

/// `a I + b U + c φφᵀ` for `U = [φ×]` (`U² = φφᵀ − |φ|² I`: a `U²` term is folded into `a` by the
/// caller, in a form without cancellation where the sign matters).
#[inline]
fn poly<T: Real>(phi: Vec3<T>, a: T, b: T, c: T) -> M3<T> {
    let v = [phi.x, phi.y, phi.z];
    // [φ×] by rows: (0, −z, y), (z, 0, −x), (−y, x, 0).
    let u = [
        [T::ZERO, -phi.z, phi.y],
        [phi.z, T::ZERO, -phi.x],
        [-phi.y, phi.x, T::ZERO],
    ];
    let mut m = [[T::ZERO; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().enumerate() {
            let diagonal = if i == j { a } else { T::ZERO };
            *e = diagonal + b * u[i][j] + c * (v[i] * v[j]);
        }
    }
    m
}

impl<T: Real> Step<T> {
    /// The step of an interval of `dt` seconds in which the body turned by the rotation vector `phi`
    /// (body frame, rad), the rate held at `phi/dt`, with the gyro's `noise`.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite `phi`; [`Error::NonFiniteStep`] or
    /// [`Error::NonPositiveStep`] for `dt`; [`Error::StepAngleBeyondStability`] in f32 for `|phi|` beyond
    /// 8192 rad (the step path's sine: no libm sine is linked); [`Error::NonFiniteResult`] if the noise
    /// overflows.
    pub fn held_rate(phi: Vec3<T>, dt: T, noise: &GyroNoise<T>) -> Result<Self, Error> {
        if !phi.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        if !(dt > T::ZERO && dt <= T::MAX) {
            return Err(if dt.is_finite() {
                Error::NonPositiveStep
            } else {
                Error::NonFiniteStep
            });
        }
        let x2 = phi.norm_squared();
        let k = Coefficients::of(x2);
        let (g2, b2) = (
            noise.arw() * noise.arw(),
            noise.bias_walk() * noise.bias_walk(),
        );
        let dt2 = dt * dt;
        // I − s₁U + c₁U² = (1 − c₁x²) I − s₁U + c₁φφᵀ (1 − c₁x² = cos x).
        let attitude = poly(phi, T::ONE - k.c1 * x2, -k.s1, k.c1);
        // −Δt (I − c₁U + c₂U²) = −Δt (s₁ I − c₁U + c₂φφᵀ) (1 − c₂x² = sin x / x).
        let bias = poly(phi, -(dt * k.s1), dt * k.c1, -(dt * k.c2));
        // I/3 + c₄U² = 2c₂ I + c₄φφᵀ (1/3 − c₄x² = 2(x − sin x)/x³ exactly): both terms non-negative, so
        // the diagonal of Qθθ is, in any rounding.
        let b2dt3 = b2 * dt2 * dt;
        let q_attitude = poly(
            phi,
            g2 * dt + b2dt3 * (T::TWO * k.c2),
            T::ZERO,
            b2dt3 * k.c4,
        );
        let b2dt2 = b2 * dt2;
        // −σ_b²Δt² (I/2 − c₂U + c₃U²) = −σ_b²Δt² (c₁ I − c₂U + c₃φφᵀ) (½ − c₃x² = (1 − cos x)/x²).
        let cross = poly(phi, -(b2dt2 * k.c1), b2dt2 * k.c2, -(b2dt2 * k.c3));
        let step = Self {
            transition: Transition { attitude, bias },
            noise: ProcessNoise {
                attitude: q_attitude,
                cross,
                bias: b2 * dt,
            },
        };
        if step.is_finite() {
            return Ok(step);
        }
        // The angle the sine was given, compared as it is reported: `|φ|²` just above 8192² can have a
        // square root of exactly 8192 in f32, which the sine covers (the step then failed for another
        // reason, e.g. an overflowing noise).
        let angle = x2.sqrt_step();
        if T::EPSILON > T::from_f64(1e-10) && angle > T::from_f64(SINE_LIMIT) {
            Err(Error::StepAngleBeyondStability {
                step_angle: angle.to_f64(),
                limit: SINE_LIMIT,
            })
        } else {
            Err(Error::NonFiniteResult)
        }
    }

    /// The step of the interval between the propagator's attitudes `start` and `end`, `dt` seconds
    /// apart (e.g. `n` steps of a fixed period): [`Step::held_rate`] with `φ = log(start⁻¹ ⊗ end)`, the
    /// rotation the propagator actually took (its input model's, exactly), `|φ| ≤ π`. The covariance can
    /// thus be propagated once every `n` attitude steps, from two attitudes kept by the caller.
    ///
    /// # Errors
    /// [`Error::NonFiniteQuaternion`] or [`Error::ZeroQuaternion`] for an attitude; otherwise as
    /// [`Step::held_rate`].
    pub fn between(
        start: Quat<T>,
        end: Quat<T>,
        dt: T,
        noise: &GyroNoise<T>,
    ) -> Result<Self, Error> {
        let (Some(a), Some(b)) = (unit(start)?, unit(end)?) else {
            return Err(Error::ZeroQuaternion);
        };
        Self::held_rate((a.conjugate() * b).to_rotation_vector(), dt, noise)
    }

    /// `Φ` and `Q` as 6 × 6 matrices over `(δθ, δb)`.
    #[must_use]
    pub fn matrices(&self) -> ([[T; 6]; 6], [[T; 6]; 6]) {
        let mut phi = [[T::ZERO; 6]; 6];
        let mut q = [[T::ZERO; 6]; 6];
        let (t, n) = (&self.transition, &self.noise);
        for i in 0..3 {
            for j in 0..3 {
                phi[i][j] = t.attitude[i][j];
                phi[i][j + 3] = t.bias[i][j];
                q[i][j] = n.attitude[i][j];
                q[i][j + 3] = n.cross[i][j];
                q[j + 3][i] = n.cross[i][j];
            }
            phi[i + 3][i + 3] = T::ONE;
            q[i + 3][i + 3] = n.bias;
        }
        (phi, q)
    }

    fn is_finite(&self) -> bool {
        let m = |m: &M3<T>| m.iter().flatten().all(|v| v.is_finite());
        m(&self.transition.attitude)
            && m(&self.transition.bias)
            && m(&self.noise.attitude)
            && m(&self.noise.cross)
            && self.noise.bias.is_finite()
    }
}

/// `q` normalized (`None` if zero), refused if not finite.
fn unit<T: Real>(q: Quat<T>) -> Result<Option<Quat<T>>, Error> {
    if q.is_finite() {
        Ok(q.normalized())
    } else {
        Err(Error::NonFiniteQuaternion)
    }
}
