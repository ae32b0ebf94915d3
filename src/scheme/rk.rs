//! The one explicit Runge–Kutta engine: every [`ButcherTableau`] is a [`Scheme`] through it.
//!
//! The engine integrates `q' = ½ g(c, q)` with `g = q ⊗ (0, ω(c))`, or with [`super::Baumgarte`]'s
//! right-hand side `g = q ⊗ (0, ω(c)) + s(q) q` (the seed's eq. (7), `s = −4kN`), so it works with the half
//! step `hh = h/2` and raw rates: no stage rescales anything.
//!
//! Two paths, both defined by the tableau alone:
//! - Rate held over the step (plain right-hand side): the step is exactly `q ← R(h·½Ω) q`, and
//!   since `(h·½Ω)² = −x² I` this is one quaternion product `q ⊗ (C(x²), S(x²)·hω/2)` with the polynomials
//!   `C`, `S` read off the stability polynomial at compile time. No square root, no trigonometry.
//! - Otherwise (a varying rate, or Baumgarte's nonlinear term): the stages, unrolled by a macro so that every
//!   node and coefficient is a literal at any optimization level and the tableau's zeros cost nothing.
//!
//! In exact arithmetic both paths give the same result for a held rate (a test checks it to rounding).

use super::tableau::{rotation_polynomials, ButcherTableau, MAX_STAGES};
use super::{Information, Scheme};
use crate::input::Segment;
use crate::{Quat, Real, Vec3};

/// The explicit Runge–Kutta schemes ([`super::Euler`] … [`super::Rk5`]): the schemes [`super::Baumgarte`]
/// can wrap. Sealed: implemented by every tableau of the crate.
pub trait RungeKutta: ButcherTableau {}
impl<Tab: ButcherTableau> RungeKutta for Tab {}

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

impl<T: Real, Tab: ButcherTableau> Scheme<T> for Tab {
    #[inline(always)]
    fn information(&self) -> Information {
        Tab::INFORMATION
    }

    #[inline(always)]
    fn increment<G: Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T> {
        let hh = h * T::HALF;
        if let Some(w) = segment.held_rate() {
            return held_rate_increment::<T, Tab>(q, w * hh);
        }
        stage_increment::<T, Tab, _>(q, hh, |c, y| y.mul_pure(segment.rate_at(c)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scheme::{Euler, Rk2, Rk3, Rk4, Rk5};

    /// The held-rate polynomial shortcut and the stages agree to rounding for every tableau.
    #[test]
    fn held_rate_polynomial_matches_the_stages() {
        fn check<Tab: ButcherTableau>() {
            let q = Quat::new(0.9_f64, 0.1, -0.3, 0.2);
            let w = Vec3::new(0.7, -1.3, 2.1);
            for hw in [1e-3, 0.05, 0.3, 0.9] {
                let hh = hw * 0.5;
                let by_poly = q + held_rate_increment::<f64, Tab>(q, w * hh);
                let by_stages = q + stage_increment::<f64, Tab, _>(q, hh, |_, y| y.mul_pure(w));
                let d = (by_poly - by_stages).dot(by_poly - by_stages).sqrt();
                assert!(d <= 8.0 * f64::EPSILON, "{} h={hw}: {d:e}", Tab::NAME);
                // And the polynomial path is not trivially the identity.
                assert!((by_poly - q).dot(by_poly - q).sqrt() > 0.1 * hw);
            }
        }
        check::<Euler>();
        check::<Rk2>();
        check::<Rk3>();
        check::<Rk4>();
        check::<Rk5>();
    }
}
