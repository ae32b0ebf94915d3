//! The one explicit Runge–Kutta engine: every [`ButcherTableau`] is a [`Scheme`] through it.
//!
//! The engine integrates `q' = ½ g(c, q)` with `g = q ⊗ (0, ω(c)) + s(q) q` (the seed's eq. (7) with
//! `s = −4kN` for Baumgarte, `s = 0` otherwise), so it works with the half step `hh = h/2` and raw rates:
//! no stage rescales anything.
//!
//! Two paths, both defined by the tableau alone:
//! - Rate held over the step and no right-hand-side stabilizer: the step is exactly `q ← R(h·½Ω) q`, and
//!   since `(h·½Ω)² = −x² I` this is one quaternion product `q ⊗ (C(x²), S(x²)·hω/2)` with the polynomials
//!   `C`, `S` read off the stability polynomial at compile time. No square root, no trigonometry.
//! - Otherwise (a varying rate, or Baumgarte's nonlinear term): the stages, unrolled by a macro so that every
//!   node and coefficient is a literal at any optimization level and the tableau's zeros cost nothing.
//!
//! In exact arithmetic both paths give the same result for a held rate (a test checks it to rounding).

use super::tableau::{rotation_polynomials, ButcherTableau, MAX_STAGES};
use super::Scheme;
use crate::rates::RateModel;
use crate::stabilize::Stabilizer;
use crate::{Quat, Real, Vec3};

/// Compile-time data derived from a tableau for the held-rate path.
trait HeldRatePolynomials: ButcherTableau {
    /// `(C(s) − 1)/s = Σ_{j≥1} r_{2j} (−1)^j s^{j−1}`: the scalar part of the increment, without the 1 that
    /// would cancel (C(0) = r₀ = 1).
    const C_MINUS_ONE_OVER_S: [f64; MAX_STAGES / 2 + 1] =
        shift_down(rotation_polynomials(&Self::STABILITY_POLYNOMIAL).0);
    /// `S(s) = Σ_j r_{2j+1} (−s)^j`.
    const S_POLY: [f64; MAX_STAGES / 2 + 1] = rotation_polynomials(&Self::STABILITY_POLYNOMIAL).1;
}
impl<Tab: ButcherTableau> HeldRatePolynomials for Tab {}

/// Drops the constant coefficient and divides by `s`: `[p₀, p₁, p₂, …] → [p₁, p₂, …, 0]`.
const fn shift_down<const N: usize>(p: [f64; N]) -> [f64; N] {
    let mut out = [0.0; N];
    let mut i = 1;
    while i < N {
        out[i - 1] = p[i];
        i += 1;
    }
    out
}

/// `true` if every coefficient is zero (then the polynomial term is skipped at compile time).
const fn all_zero<const N: usize>(p: &[f64; N]) -> bool {
    let mut i = 0;
    while i < N {
        if p[i] != 0.0 {
            return false;
        }
        i += 1;
    }
    true
}

/// Horner evaluation in `T`, starting at the highest non-zero coefficient (folded at compile time), so a
/// zero coefficient costs nothing and a leading 1 costs no multiplication.
#[inline(always)]
fn horner<T: Real, const N: usize>(p: &[f64; N], s: T) -> T {
    let mut top = N;
    while top > 0 && p[top - 1] == 0.0 {
        top -= 1;
    }
    if top == 0 {
        return T::ZERO;
    }
    let mut acc = T::from_f64(p[top - 1]);
    let mut i = top - 1;
    while i > 0 {
        i -= 1;
        acc = acc * s + T::from_f64(p[i]);
    }
    acc
}

/// The held-rate increment `q ⊗ (C(x²) − 1, S(x²)·v)` with `v = hω/2`, `x² = |v|²`.
#[inline(always)]
fn held_rate_increment<T: Real, Tab: ButcherTableau>(q: Quat<T>, v: Vec3<T>) -> Quat<T> {
    let vector = q.mul_pure(v * horner(&Tab::S_POLY, v.norm_squared()));
    if all_zero(&Tab::C_MINUS_ONE_OVER_S) {
        return vector; // Euler: C = 1
    }
    let s = v.norm_squared();
    q * (s * horner(&Tab::C_MINUS_ONE_OVER_S, s)) + vector
}

/// Adds `coef·k` to an optional running sum, skipping a zero coefficient (a literal after unrolling).
#[inline(always)]
fn accumulate<T: Real>(acc: Option<Quat<T>>, coef: f64, k: Quat<T>) -> Option<Quat<T>> {
    if coef == 0.0 {
        return acc;
    }
    let term = k * T::from_f64(coef);
    Some(match acc {
        None => term,
        Some(s) => s + term,
    })
}

/// `Σ_{j<n} coef_j · k_j`, `None` if all coefficients are zero. Unrolled over the six possible stages.
#[inline(always)]
fn weighted_sum<T: Real>(
    coef: &[f64; MAX_STAGES],
    k: &[Quat<T>; MAX_STAGES],
    n: usize,
) -> Option<Quat<T>> {
    let mut acc = None;
    macro_rules! terms {
        ($($j:literal)*) => {$(
            if $j < n {
                acc = accumulate(acc, coef[$j], k[$j]);
            }
        )*};
    }
    terms!(0 1 2 3 4 5);
    acc
}

/// The increment of one explicit RK step of `q' = ½ g(c, q)` over `h = 2·hh` with the tableau's stages.
#[inline(always)]
pub(crate) fn stage_increment<T: Real, Tab: ButcherTableau, G: Fn(f64, Quat<T>) -> Quat<T>>(
    q: Quat<T>,
    hh: T,
    g: G,
) -> Quat<T> {
    let mut k = [Quat::<T>::ZERO; MAX_STAGES];
    macro_rules! stages {
        ($($i:literal)*) => {$(
            if $i < Tab::STAGES {
                let y = match weighted_sum(&Tab::A[$i], &k, $i) {
                    Some(s) => q + s * hh,
                    None => q,
                };
                k[$i] = g(Tab::C[$i], y);
            }
        )*};
    }
    stages!(0 1 2 3 4 5);
    match weighted_sum(&Tab::B, &k, Tab::STAGES) {
        Some(s) => s * hh,
        None => Quat::ZERO,
    }
}

impl<Tab: ButcherTableau> Scheme for Tab {
    #[inline(always)]
    fn name(&self) -> &'static str {
        Tab::NAME
    }
    #[inline(always)]
    fn order(&self) -> u32 {
        Tab::ORDER
    }
    #[inline(always)]
    fn step_angle_limit(&self) -> f64 {
        Tab::STEP_ANGLE_LIMIT
    }
    #[inline(always)]
    fn real_axis_limit(&self) -> f64 {
        Tab::REAL_AXIS_LIMIT
    }
    fn norm_change(&self, step_angle: f64) -> f64 {
        let x = 0.5 * step_angle;
        super::tableau::poly_eval(&Tab::NORM_CHANGE_POLYNOMIAL, x * x)
    }

    #[inline(always)]
    fn increment<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T> {
        let hh = h * T::HALF;
        if !stabilizer.has_rhs_term() {
            if let Some(w) = rates.held_rate() {
                return held_rate_increment::<T, Tab>(q, w * hh);
            }
            return stage_increment::<T, Tab, _>(q, hh, |c, y| y.mul_pure(rates.rate_at(c)));
        }
        stage_increment::<T, Tab, _>(q, hh, |c, y| {
            y.mul_pure(rates.rate_at(c)) + y * stabilizer.rhs_scalar(y)
        })
    }
}

/// The held-rate step evaluated through the stages instead of the polynomial (for tests and the lab:
/// both must agree to rounding).
#[must_use]
pub fn held_rate_step_by_stages<T: Real, Tab: ButcherTableau>(
    q: Quat<T>,
    w: Vec3<T>,
    h: T,
) -> Quat<T> {
    q + stage_increment::<T, Tab, _>(q, h * T::HALF, |_, y| y.mul_pure(w))
}
