//! Explicit Runge–Kutta tableaux as `const` data, and what follows from them at compile time.
//!
//! For the kinematic equation with a held rate, `(h·½Ω)² = −x² I` with `x = h|ω|/2`, so one step is exactly
//! `q ← R(h·½Ω) q` where `R(z) = Σ r_m z^m` is the tableau's stability polynomial, `r_0 = 1`,
//! `r_m = bᵀ A^(m−1) 𝟙`. Everything about norm behaviour and stability follows from `R`:
//! `|q_{n+1}|² = |R(ix)|² |q_n|²`. This module computes `R`, `|R(ix)|²` and both stability bounds from the
//! tableau in `const fn`s, so the numbers in the docs and the checks in the propagator cannot disagree with
//! the coefficients.

/// The most stages any tableau in the crate has.
pub(crate) const MAX_STAGES: usize = 6;

/// An explicit Butcher tableau with exact coefficients (written as fractions of integers). Crate-private
/// (the trait is not nameable outside the crate): each tableau is a [`super::Scheme`] through the one
/// explicit Runge–Kutta engine, and its analysis data is public as [`super::Information`].
pub trait ButcherTableau: Copy + Default {
    /// Short name, e.g. `"Rk4"`.
    const NAME: &'static str;
    /// Classical order of the method.
    const ORDER: u32;
    /// Number of stages `s ≤ MAX_STAGES`.
    const STAGES: usize;
    /// Nodes `c_i` (unused entries zero).
    const C: [f64; MAX_STAGES];
    /// Strictly lower-triangular coupling matrix `a_ij` (unused entries zero).
    const A: [[f64; MAX_STAGES]; MAX_STAGES];
    /// Weights `b_i` (unused entries zero).
    const B: [f64; MAX_STAGES];

    /// Coefficients `r_0 … r_s` of the stability polynomial `R(z)`.
    /// `r_m = 1/m!` exactly for `m ≤ ORDER` (the order conditions imply it; the tests check the tableau
    /// agrees to rounding); higher coefficients are `bᵀ A^(m−1) 𝟙` computed from the tableau.
    const STABILITY_POLYNOMIAL: [f64; MAX_STAGES + 1] = exact_low_order(
        stability_polynomial(&Self::A, &Self::B, Self::STAGES),
        Self::ORDER,
    );
    /// Coefficients of `|R(ix)|² − 1` as a polynomial in `x²`, see [`norm_factor_deviation`].
    const NORM_CHANGE_POLYNOMIAL: [f64; MAX_STAGES + 1] =
        norm_factor_deviation(&Self::STABILITY_POLYNOMIAL);
    /// Largest admitted step angle `h·|ω|` (rad), see [`step_angle_limit`].
    const STEP_ANGLE_LIMIT: f64 = step_angle_limit(&Self::STABILITY_POLYNOMIAL);
    /// Largest `h·λ` with `|R(−hλ)| ≤ 1` on the negative real axis, see [`real_axis_limit`].
    const REAL_AXIS_LIMIT: f64 = real_axis_limit(&Self::STABILITY_POLYNOMIAL);
    /// Everything above as the public record.
    const INFORMATION: super::Information = super::Information {
        name: Self::NAME,
        order: Self::ORDER,
        step_angle_limit: Self::STEP_ANGLE_LIMIT,
        real_axis_limit: Self::REAL_AXIS_LIMIT,
        norm_change_polynomial: Self::NORM_CHANGE_POLYNOMIAL,
    };
}

/// `r_0 = 1`, `r_m = bᵀ A^(m−1) 𝟙` for `m = 1 … s` (zero beyond `s`).
pub(crate) const fn stability_polynomial(
    a: &[[f64; MAX_STAGES]; MAX_STAGES],
    b: &[f64; MAX_STAGES],
    stages: usize,
) -> [f64; MAX_STAGES + 1] {
    let mut r = [0.0; MAX_STAGES + 1];
    r[0] = 1.0;
    let mut v = [0.0; MAX_STAGES];
    let mut i = 0;
    while i < stages {
        v[i] = 1.0;
        i += 1;
    }
    let mut m = 1;
    while m <= stages {
        let mut dot = 0.0;
        let mut i = 0;
        while i < stages {
            dot += b[i] * v[i];
            i += 1;
        }
        r[m] = dot;
        // v ← A v
        let mut next = [0.0; MAX_STAGES];
        let mut i = 0;
        while i < stages {
            let mut j = 0;
            while j < stages {
                next[i] += a[i][j] * v[j];
                j += 1;
            }
            i += 1;
        }
        v = next;
        m += 1;
    }
    r
}

/// Replaces `r_0 … r_order` by the exact `1/m!` that the order conditions imply, so the polynomial carries
/// no rounding of the tableau's fractions (RK3's `Σb` is 0.9999999999999999 in binary).
pub(crate) const fn exact_low_order(
    mut r: [f64; MAX_STAGES + 1],
    order: u32,
) -> [f64; MAX_STAGES + 1] {
    let mut m = 0;
    let mut factorial = 1.0;
    while m <= order as usize && m <= MAX_STAGES {
        if m > 0 {
            factorial *= m as f64;
        }
        r[m] = 1.0 / factorial;
        m += 1;
    }
    r
}

/// The held-rate step as `q ← q ⊗ (C(x²), S(x²)·v)` with `v = h ω/2`, `x² = |v|²`:
/// `C(s) = Σ_j r_{2j} (−s)^j` and `S(s) = Σ_j r_{2j+1} (−s)^j`. Returns `(C, S)` coefficient lists.
pub(crate) const fn rotation_polynomials(
    r: &[f64; MAX_STAGES + 1],
) -> ([f64; MAX_STAGES / 2 + 1], [f64; MAX_STAGES / 2 + 1]) {
    let mut c = [0.0; MAX_STAGES / 2 + 1];
    let mut s = [0.0; MAX_STAGES / 2 + 1];
    let mut m = 0;
    while m <= MAX_STAGES {
        let j = m / 2;
        let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
        if m % 2 == 0 {
            c[j] = sign * r[m];
        } else {
            s[j] = sign * r[m];
        }
        m += 1;
    }
    (c, s)
}

/// Evaluates a polynomial with coefficients `p` (constant first) at `s`.
pub(crate) const fn poly_eval<const N: usize>(p: &[f64; N], s: f64) -> f64 {
    let mut acc = 0.0;
    let mut i = N;
    while i > 0 {
        i -= 1;
        acc = acc * s + p[i];
    }
    acc
}

/// The per-step norm factor `|R(ix)|² = C(x²)² + x² S(x²)²` at `x = h|ω|/2`:
/// with the rate held and no stabilization, `|q_{n+1}|² = |R(ix)|² · |q_n|²` exactly.
pub(crate) const fn norm_factor(r: &[f64; MAX_STAGES + 1], x: f64) -> f64 {
    let (c, s) = rotation_polynomials(r);
    let s2 = x * x;
    let cv = poly_eval(&c, s2);
    let sv = poly_eval(&s, s2);
    cv * cv + s2 * sv * sv
}

/// Coefficients of `|R(ix)|² − 1` as a polynomial in `s = x²` (degree ≤ MAX_STAGES).
pub(crate) const fn norm_factor_deviation(r: &[f64; MAX_STAGES + 1]) -> [f64; MAX_STAGES + 1] {
    let (c, s) = rotation_polynomials(r);
    let mut p = [0.0; MAX_STAGES + 1];
    let n = MAX_STAGES / 2 + 1;
    let mut i = 0;
    while i < n {
        let mut j = 0;
        while j < n {
            if i + j <= MAX_STAGES {
                p[i + j] += c[i] * c[j];
            }
            if i + j < MAX_STAGES {
                p[i + j + 1] += s[i] * s[j];
            }
            j += 1;
        }
        i += 1;
    }
    p[0] -= 1.0;
    p
}

/// `true` if `|R(ix)|² < 1` for small `x > 0`: the lowest non-vanishing coefficient of `|R(ix)|² − 1`
/// is negative (the method loses norm, like the seed's RK4), `false` if it gains norm (Euler, RK2).
pub(crate) const fn dissipative_near_zero(r: &[f64; MAX_STAGES + 1]) -> bool {
    let p = norm_factor_deviation(r);
    let mut i = 1;
    while i <= MAX_STAGES {
        // Exact fractions give exact zeros up to a few ulp of the coefficient arithmetic.
        if p[i] > 1e-13 {
            return false;
        }
        if p[i] < -1e-13 {
            return true;
        }
        i += 1;
    }
    true
}

/// The largest admitted step angle `h|ω|` (rad) for a tableau with stability polynomial `r`.
///
/// - Methods that are dissipative near zero (RK3, RK4, the Dormand–Prince RK5) have an interval of stability
///   on the imaginary axis: the bound is its end, the first `x > 0` with `|R(ix)|² = 1`, as `h|ω| = 2x`.
/// - Methods with `|R(ix)|² > 1` for every `x > 0` (Euler: 1 + x², RK2: 1 + x⁴/4) have no such interval;
///   every step amplifies `|q|`. For them the bound is where one step would double `|q|²`
///   (`|R(ix)|² = 2`): Euler `h|ω| ≤ 2`, RK2 `h|ω| ≤ 2√2`. Use them with a normalizing stabilizer.
pub(crate) const fn step_angle_limit(r: &[f64; MAX_STAGES + 1]) -> f64 {
    let level = if dissipative_near_zero(r) { 1.0 } else { 2.0 };
    // Scan x upward past the region where |R|² − level is of one sign, then bisect the crossing.
    let start = 1e-3;
    let step = 1e-3;
    let mut lo = start;
    let mut k = 0;
    while k < 20_000 {
        let hi = lo + step;
        if norm_factor(r, hi) > level {
            // Bisect [lo, hi].
            let mut a = lo;
            let mut b = hi;
            let mut it = 0;
            while it < 60 {
                let m = 0.5 * (a + b);
                if norm_factor(r, m) > level {
                    b = m;
                } else {
                    a = m;
                }
                it += 1;
            }
            return 2.0 * a;
        }
        lo = hi;
        k += 1;
    }
    f64::INFINITY
}

/// The end of the stability interval on the negative real axis: the largest `y` with `|R(−t)| ≤ 1`
/// for all `t ∈ [0, y]` (Euler and RK2: 2, RK3: 2.51, RK4: 2.79). Baumgarte's term linearizes to
/// `N' = −4kN`, an eigenvalue `−4k` of the norm direction, so `4 k h` must stay below this bound.
pub(crate) const fn real_axis_limit(r: &[f64; MAX_STAGES + 1]) -> f64 {
    let step = 1e-3;
    let mut lo = 0.0;
    let mut k = 0;
    while k < 20_000 {
        let hi = lo + step;
        let v = poly_eval(r, -hi);
        if v > 1.0 || v < -1.0 {
            let mut a = lo;
            let mut b = hi;
            let mut it = 0;
            while it < 60 {
                let m = 0.5 * (a + b);
                let v = poly_eval(r, -m);
                if v > 1.0 || v < -1.0 {
                    b = m;
                } else {
                    a = m;
                }
                it += 1;
            }
            return a;
        }
        lo = hi;
        k += 1;
    }
    f64::INFINITY
}
