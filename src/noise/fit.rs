//! The noise terms of a sensor, fitted to its Allan variance.

// Small dense linear algebra reads best with the indices of its formulas.
#![allow(clippy::needless_range_loop)]

use super::{AllanVariance, Cluster};
use crate::Real;

/// `2 ln 2 / π`: the Allan variance of flicker noise over the square of its bias instability.
pub const FLICKER_FLOOR: f64 = 2.0 * core::f64::consts::LN_2 / core::f64::consts::PI;

/// One point of an Allan variance curve: a cluster time, the variance there, and how many differences it
/// averages (its weight).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Point {
    /// τ (s).
    pub tau: f64,
    /// σ²(τ), the sensor's unit squared.
    pub variance: f64,
    /// The differences of cluster means averaged (for an overlapping estimate, its equivalent degrees of
    /// freedom): the variance's relative variance is taken as `2 / differences`.
    pub differences: f64,
}

/// One term of a [`NoiseFit`]: its coefficient in the Allan variance and that coefficient's standard
/// error, with the density it stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Term {
    /// The coefficient `c ≥ 0` (the density squared: `N²`, `B²` or `K²`).
    pub coefficient: f64,
    /// Its standard error: from the points' covariance under the fitted model when they are an
    /// [`AllanVariance`]'s octaves (which share their samples), from the fit's weights otherwise; inflated
    /// by the misfit when the curve scatters more than that says.
    pub std_error: f64,
}

impl Term {
    /// The density, `√c` (the sensor's unit per √s for white noise and unit·/√s… see [`NoiseFit`]).
    #[must_use]
    pub fn value(&self) -> f64 {
        libm::sqrt(self.coefficient)
    }

    /// The density's interval at `k` standard errors of its coefficient: `(√max(c − k·se, 0), √(c + k·se))`.
    #[must_use]
    pub fn interval(&self, k: f64) -> (f64, f64) {
        (
            libm::sqrt((self.coefficient - k * self.std_error).max(0.0)),
            libm::sqrt(self.coefficient + k * self.std_error),
        )
    }

    /// The curve shows this term: its coefficient is more than two standard errors above zero. A term that
    /// is not identified is bounded from above by [`Term::interval`]'s upper end: the recording was too
    /// short (a random walk) or the term is hidden under the others.
    #[must_use]
    pub fn is_identified(&self) -> bool {
        self.coefficient > 2.0 * self.std_error
    }
}

/// The noise of a sensor at rest, fitted to its Allan variance: `σ²(τ) = N²/τ + (2 ln 2/π) B² + K² τ/3`
/// (IEEE Std 952-1997, Annex C; the same for an accelerometer, in its units).
///
/// | term | gyroscope | accelerometer | on the Allan deviation plot |
/// |---|---|---|---|
/// | `white`, `N` | angle random walk, rad/√s (= rad/s/√Hz; °/√h = 60·°/s/√Hz) | velocity random walk, m/s/√s | the −½ slope; `σ(1 s) = N` |
/// | `instability`, `B` | bias instability, rad/s | bias instability, m/s² | the floor, `σ = 0.664 B` |
/// | `random_walk`, `K` | rate random walk, rad/s/√s | acceleration random walk, m/s²/√s | the +½ slope; `σ(3 s) = K` |
///
/// The three coefficients are fitted at once to every point (not read off one τ each): weighted least
/// squares on the variances, each weighted by its own relative variance `2/differences` at the fitted
/// curve (iterated), with every coefficient kept non-negative (the best of the fits on each subset of the
/// terms). Each term carries its standard error, so a recording too short to show a term says so
/// ([`Term::is_identified`]) instead of inventing it. Fitted to an [`AllanVariance`]
/// ([`NoiseFit::pooled_from`], [`NoiseFit::axis`]), the standard errors count that its octaves share
/// their samples: the weighted fit's covariance `C` sandwiches the points' covariance under the fitted
/// model, `C XᵀW Σ W X C` (docs/noise.md measures how often the ±2 se interval holds the truth).
///
/// ```
/// use quatprop::noise::{AllanVariance, NoiseFit};
/// use quatprop::Vec3;
/// // White noise of 0.01 rad/s per sample at 100 Hz: N = 0.01 · √0.01 = 1e-3 rad/√s.
/// let mut avar = AllanVariance::<f64, 12>::new(0.01)?;
/// let mut x: u64 = 1;
/// for _ in 0..100_000 {
///     // A uniform pseudo-random sample of standard deviation 0.01 (xorshift).
///     let mut u = || { x ^= x << 13; x ^= x >> 7; x ^= x << 17; (x >> 11) as f64 / (1u64 << 53) as f64 };
///     let s = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * (0.01 * 12f64.sqrt());
///     avar.push(s)?;
/// }
/// let fit = NoiseFit::pooled(&avar).unwrap();
/// assert!((fit.white.value() / 1e-3 - 1.0).abs() < 0.02);
/// assert!(!fit.random_walk.is_identified());
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NoiseFit {
    /// The white noise's density `N`.
    pub white: Term,
    /// The bias instability `B` (flicker noise).
    pub instability: Term,
    /// The random walk's density `K`.
    pub random_walk: Term,
    /// The points fitted.
    pub points: u32,
    /// Their shortest and longest τ (s).
    pub tau_range: (f64, f64),
    /// The weighted misfit per degree of freedom: about 1 when the curve is the model plus its own
    /// scatter; much more when the sensor has a term the model lacks (quantization, a filter, a drift).
    pub misfit: f64,
}

/// The model's functions of τ, in the order white, instability, random walk.
fn basis(tau: f64) -> [f64; 3] {
    [1.0 / tau, FLICKER_FLOOR, tau / 3.0]
}

/// Solves the 3 × 3 system `a x = b` by Gaussian elimination with partial pivoting; `None` if singular.
fn solve(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    for col in 0..3 {
        let mut pivot = col;
        for row in col + 1..3 {
            if a[row][col].abs() > a[pivot][col].abs() {
                pivot = row;
            }
        }
        if !(a[pivot][col].abs() > 0.0) {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..3 {
            let f = a[row][col] / a[col][col];
            for k in col..3 {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 3];
    for row in (0..3).rev() {
        let mut s = b[row];
        for k in row + 1..3 {
            s -= a[row][k] * x[k];
        }
        x[row] = s / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The inverse of the 3 × 3 matrix `a`, column by column.
fn inverse(a: [[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let mut inv = [[0.0; 3]; 3];
    for col in 0..3 {
        let mut e = [0.0; 3];
        e[col] = 1.0;
        let x = solve(a, e)?;
        for row in 0..3 {
            inv[row][col] = x[row];
        }
    }
    Some(inv)
}

/// A weighted least-squares fit on the terms of `mask`: coefficients (zero outside the mask), the
/// weighted sum of squared residuals, and the covariance of the coefficients (zero outside the mask).
struct Solution {
    coefficients: [f64; 3],
    residual: f64,
    covariance: [[f64; 3]; 3],
    /// The terms fitted.
    mask: u8,
    /// How many.
    n: usize,
}

/// Rows: `(f(τ), y, weight)` with `weight = 1/var(y)`. Columns scaled to unit weighted norm first (the
/// three functions differ by orders of magnitude); a term outside the mask is an identity row and column
/// of the normal equations, held at zero.
fn fit_subset(rows: &[([f64; 3], f64, f64)], mask: u8) -> Option<Solution> {
    let on = |j: usize| mask & (1 << j) != 0;
    let mut scale = [0.0; 3];
    for (j, sc) in scale.iter_mut().enumerate() {
        if on(j) {
            let s: f64 = rows.iter().map(|(f, _, w)| w * f[j] * f[j]).sum();
            if !(s > 0.0) {
                return None;
            }
            *sc = 1.0 / libm::sqrt(s);
        }
    }
    let mut ata = [[0.0; 3]; 3];
    let mut atb = [0.0; 3];
    for (f, y, w) in rows {
        for i in 0..3 {
            let fi = f[i] * scale[i];
            atb[i] += w * fi * y;
            for k in 0..3 {
                ata[i][k] += w * fi * f[k] * scale[k];
            }
        }
    }
    for j in 0..3 {
        if !on(j) {
            ata[j] = [0.0; 3];
            for row in ata.iter_mut() {
                row[j] = 0.0;
            }
            ata[j][j] = 1.0;
            atb[j] = 0.0;
        }
    }
    let x = solve(ata, atb)?;
    let inv = inverse(ata)?;
    let mut coefficients = [0.0; 3];
    let mut covariance = [[0.0; 3]; 3];
    for i in 0..3 {
        if on(i) {
            coefficients[i] = x[i] * scale[i];
            for k in 0..3 {
                if on(k) {
                    covariance[i][k] = inv[i][k] * scale[i] * scale[k];
                }
            }
        }
    }
    let residual = rows
        .iter()
        .map(|(f, y, w)| {
            let m: f64 = (0..3).map(|j| coefficients[j] * f[j]).sum();
            w * (y - m) * (y - m)
        })
        .sum();
    Some(Solution {
        coefficients,
        residual,
        covariance,
        mask,
        n: (0..3).filter(|&j| on(j)).count(),
    })
}

/// The generalized covariance of the angle `x` (the rate's integral) under the model with coefficients
/// `c = (N², B², K²)`: `Cov(Σ aₚ x(tₚ), Σ b_q x(s_q)) = Σ aₚ b_q G(tₚ − s_q)` for weights that annihilate
/// constants and straight lines (an Allan difference's do). White rate noise makes `x` a Brownian motion,
/// `G = −N² |u| / 2`; a rate random walk makes it an integrated one, `G = K² |u|³ / 12`; flicker noise of
/// Allan variance `(2 ln 2/π) B²` has `G = B² u² ln|u| / (2π)`. Each gives its term of the model's Allan
/// variance through `σ²(τ) = (G(2τ) − 4 G(τ)) / τ²` (the tests check all three).
fn generalized_covariance(c: [f64; 3], u: f64) -> f64 {
    let u = u.abs();
    let flicker = if u > 0.0 {
        c[1] / (2.0 * core::f64::consts::PI) * u * u * libm::log(u)
    } else {
        0.0
    };
    -0.5 * c[0] * u + flicker + c[2] / 12.0 * u * u * u
}

/// The covariance of two Allan differences of cluster means, `d = ȳ₂ − ȳ₁ = (x(t + 2τ) − 2x(t + τ) +
/// x(t)) / τ`: the fine one at `τ_f` starting at `t_f`, the coarse one at `τ_c` starting at 0.
fn difference_covariance(c: [f64; 3], tau_f: f64, t_f: f64, tau_c: f64) -> f64 {
    const A: [f64; 3] = [1.0, -2.0, 1.0];
    let mut s = 0.0;
    for (p, ap) in A.iter().enumerate() {
        for (q, aq) in A.iter().enumerate() {
            s += ap * aq * generalized_covariance(c, t_f + p as f64 * tau_f - q as f64 * tau_c);
        }
    }
    s / (tau_f * tau_c)
}

/// Octaves further apart than this are taken as uncorrelated: their estimates' correlation falls by about
/// `2^(−Δk/2)` where a random walk dominates (0.02 at 12 octaves), `2^(−1.5 Δk)` for white noise; the sum
/// over a pair costs `2^Δk` terms.
const OCTAVE_REACH: u32 = 12;
/// Fine differences beyond the coarse one's span counted on each side.
const TAIL: i64 = 32;

/// The covariance of two octaves' Allan variance estimates (`σ̂² = Σ dᵢ² / (2n)`, non-overlapping, the
/// coarse octave's clusters made of the fine one's) under the model `c`, for Gaussian noise:
/// `Cov(σ̂²_f, σ̂²_c) = Σᵢ Cov(d_fᵢ, d_c)² / (2 n_f)`, the sum over the fine differences around one coarse
/// difference (edges neglected); `n_f` the fine octave's differences (over every axis pooled: the axes'
/// shares of the sum then add up to the same). Points' τ must be a power of two apart.
fn octave_covariance(c: [f64; 3], fine: (f64, f64), coarse: (f64, f64)) -> f64 {
    let ((tau_f, differences_f), (tau_c, _)) = (fine, coarse);
    let ratio = libm::round(tau_c / tau_f);
    if !(ratio >= 1.0) || ratio > f64::from(1_u32 << OCTAVE_REACH) {
        return 0.0;
    }
    let span = 2 * ratio as i64;
    let mut s = 0.0;
    for i in -TAIL..span + TAIL {
        let v = difference_covariance(c, tau_f, i as f64 * tau_f, tau_c);
        s += v * v;
    }
    s / (2.0 * differences_f)
}

/// `M = Σₖ Σₗ wₖ wₗ fₖ fₗᵀ Σₖₗ` over the points `(τ, σ², differences)`, with the rows' weights `wₖ` and
/// functions `fₖ` and the points' covariance `Σ` under the model `c`.
fn sandwich_meat(
    points: &[(f64, f64, f64)],
    rows: &[([f64; 3], f64, f64)],
    c: [f64; 3],
) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for (k, (pk, rk)) in points.iter().zip(rows).enumerate() {
        for (pl, rl) in points.iter().zip(rows).skip(k) {
            let (fine, coarse) = if pk.0 <= pl.0 { (pk, pl) } else { (pl, pk) };
            let cov = octave_covariance(c, (fine.0, fine.2), (coarse.0, coarse.2));
            // Each off-diagonal pair stands for both (k, l) and (l, k).
            let both = if core::ptr::eq(pk, pl) { 1.0 } else { 2.0 };
            let w = rk.2 * rl.2 * cov;
            for i in 0..3 {
                for j in 0..3 {
                    m[i][j] += 0.5 * both * w * (rk.0[i] * rl.0[j] + rl.0[i] * rk.0[j]);
                }
            }
        }
    }
    m
}

/// `C M C`.
fn sandwich(c: &[[f64; 3]; 3], m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut cm = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            cm[i][j] = (0..3).map(|k| c[i][k] * m[k][j]).sum();
        }
    }
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = (0..3).map(|k| cm[i][k] * c[k][j]).sum();
        }
    }
    out
}

/// The most points a fit takes (octaves of a [`AllanVariance`] of up to 64 octaves).
const MAX_POINTS: usize = 64;

impl NoiseFit {
    /// Fits the model to `points` (at most 64 are used, the first ones; a point with no differences, a
    /// non-positive τ or a variance that is not finite and non-negative is skipped).
    ///
    /// Returns `None` with fewer than two usable points.
    ///
    /// The standard errors take the points as independent, each with the relative variance
    /// `2 / differences`. The fits of an [`AllanVariance`] ([`NoiseFit::pooled_from`], [`NoiseFit::axis`])
    /// know more: how its octaves share their samples, so their standard errors count that instead.
    #[must_use]
    pub fn of(points: impl IntoIterator<Item = Point>) -> Option<Self> {
        Self::of_with(points, false)
    }

    /// [`NoiseFit::of`]; with `octaves`, the points are a non-overlapping Allan variance's octaves (each
    /// τ a power of two times the shortest, the same samples under every one), and the coefficients'
    /// covariance is the sandwich `C M C` (`C` the weighted fit's, `M = XᵀW Σ W X`) with `Σ` the points'
    /// covariance under the fitted model ([`octave_covariance`]).
    fn of_with(points: impl IntoIterator<Item = Point>, octaves: bool) -> Option<Self> {
        let mut kept = [(0.0, 0.0, 0.0); MAX_POINTS];
        let mut len = 0;
        for p in points {
            let ok = p.tau > 0.0
                && p.tau.is_finite()
                && p.variance >= 0.0
                && p.variance.is_finite()
                && p.differences >= 1.0
                && p.differences.is_finite();
            if let (true, Some(slot)) = (ok, kept.get_mut(len)) {
                *slot = (p.tau, p.variance, p.differences);
                len += 1;
            }
        }
        let kept = kept.get(..len)?;
        if len < 2 {
            return None;
        }
        // Iteratively reweighted: var(σ̂²) = 2 m² / differences at the current model m (the measured
        // value itself at the start, floored so that a zero variance does not take all the weight).
        let mean: f64 = kept.iter().map(|p| p.1).sum::<f64>() / len as f64;
        let floor = (mean * 1e-12).max(f64::MIN_POSITIVE);
        let mut model = [0.0; MAX_POINTS];
        for (m, p) in model.iter_mut().zip(kept) {
            *m = p.1.max(floor);
        }
        let mut best: Option<Solution> = None;
        for _ in 0..6 {
            let mut rows = [([0.0; 3], 0.0, 0.0); MAX_POINTS];
            for ((row, p), m) in rows.iter_mut().zip(kept).zip(&model) {
                let m = m.max(floor);
                *row = (basis(p.0), p.1, p.2 / (2.0 * m * m));
            }
            let rows = rows.get(..len)?;
            best = (1..8_u8)
                .filter_map(|mask| fit_subset(rows, mask))
                .filter(|s| s.coefficients.iter().all(|&c| c >= 0.0))
                .min_by(|a, b| a.residual.total_cmp(&b.residual));
            let s = best.as_ref()?;
            for (m, p) in model.iter_mut().zip(kept) {
                let f = basis(p.0);
                *m = (0..3).map(|j| s.coefficients[j] * f[j]).sum();
            }
        }
        let s = best?;
        // Standard errors: the active terms' from their own fit; a term held at zero takes the error it
        // would have in the fit of all three (or, if that fit is singular, none can be given: infinite).
        let rows_final = {
            let mut rows = [([0.0; 3], 0.0, 0.0); MAX_POINTS];
            for ((row, p), m) in rows.iter_mut().zip(kept).zip(&model) {
                let m = m.max(floor);
                *row = (basis(p.0), p.1, p.2 / (2.0 * m * m));
            }
            rows
        };
        let rows_final = rows_final.get(..len)?;
        let full = fit_subset(rows_final, 0b111);
        let dof = len.saturating_sub(s.n).max(1) as f64;
        let misfit = s.residual / dof;
        let inflate = misfit.max(1.0);
        // With the octaves' own covariance: the sandwich, on the terms fitted and on all three.
        let meat = octaves.then(|| sandwich_meat(kept, rows_final, s.coefficients));
        let covariance = |sol: &Solution| match &meat {
            Some(m) => sandwich(&sol.covariance, m),
            None => sol.covariance,
        };
        let own_cov = covariance(&s);
        let full_cov = full.as_ref().map(covariance);
        let mut terms = [Term {
            coefficient: 0.0,
            std_error: f64::INFINITY,
        }; 3];
        for (j, term) in terms.iter_mut().enumerate() {
            term.coefficient = s.coefficients[j];
            let own = (s.mask & (1 << j) != 0).then(|| own_cov[j][j]);
            let variance = own.or_else(|| full_cov.map(|f| f[j][j]));
            if let Some(v) = variance.filter(|v| *v >= 0.0) {
                term.std_error = libm::sqrt(v * inflate);
            }
        }
        let (lo, hi) = kept.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
        Some(Self {
            white: terms[0],
            instability: terms[1],
            random_walk: terms[2],
            points: len as u32,
            tau_range: (lo, hi),
            misfit,
        })
    }

    /// Fits one axis (`0, 1, 2` for x, y, z) of `avar`'s clusters with τ ≥ `min_tau` (s; e.g. to skip the
    /// shortest clusters where a sensor's own low-pass filter makes its samples correlated).
    #[must_use]
    pub fn axis<T: Real, const OCTAVES: usize>(
        avar: &AllanVariance<T, OCTAVES>,
        axis: usize,
        min_tau: f64,
    ) -> Option<Self> {
        Self::of_with(
            avar.clusters()
                .filter(|c| c.tau >= min_tau)
                .map(|c: Cluster<T>| Point {
                    tau: c.tau,
                    variance: match axis {
                        0 => c.variance.x,
                        1 => c.variance.y,
                        _ => c.variance.z,
                    }
                    .to_f64(),
                    differences: f64::from(c.differences),
                }),
            true,
        )
    }

    /// Fits the mean of the three axes' variances (a sensor whose axes share one noise: three times the
    /// differences per point), over every cluster.
    #[must_use]
    pub fn pooled<T: Real, const OCTAVES: usize>(avar: &AllanVariance<T, OCTAVES>) -> Option<Self> {
        Self::pooled_from(avar, 0.0)
    }

    /// [`NoiseFit::pooled`] over the clusters with τ ≥ `min_tau` (s).
    #[must_use]
    pub fn pooled_from<T: Real, const OCTAVES: usize>(
        avar: &AllanVariance<T, OCTAVES>,
        min_tau: f64,
    ) -> Option<Self> {
        Self::of_with(
            avar.clusters().filter(|c| c.tau >= min_tau).map(|c| Point {
                tau: c.tau,
                variance: (c.variance.x.to_f64() + c.variance.y.to_f64() + c.variance.z.to_f64())
                    / 3.0,
                differences: 3.0 * f64::from(c.differences),
            }),
            true,
        )
    }

    /// The fitted curve's Allan variance at `tau` (s).
    #[must_use]
    pub fn variance(&self, tau: f64) -> f64 {
        let f = basis(tau);
        self.white.coefficient * f[0]
            + self.instability.coefficient * f[1]
            + self.random_walk.coefficient * f[2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each term's generalized covariance gives its Allan variance: `(G(2τ) − 4 G(τ)) / τ²` is `N²/τ`,
    /// `(2 ln 2/π) B²`, `K² τ/3`; and an Allan difference's variance from [`difference_covariance`] is
    /// twice that.
    #[test]
    fn the_generalized_covariances_give_the_model() {
        for tau in [0.01, 1.0, 300.0] {
            for (j, c) in [[2.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, 5.0]]
                .into_iter()
                .enumerate()
            {
                let g = |u| generalized_covariance(c, u);
                let avar = (g(2.0 * tau) - 4.0 * g(tau)) / (tau * tau);
                let model = c[j] * basis(tau)[j];
                assert!(
                    (avar / model - 1.0).abs() < 1e-9,
                    "{j} {tau}: {avar} {model}"
                );
                let d = difference_covariance(c, tau, 0.0, tau);
                assert!((d / (2.0 * model) - 1.0).abs() < 1e-9, "{j} {tau}: {d}");
            }
        }
    }

    /// White noise: consecutive Allan differences are correlated by −½, so an octave's estimate has the
    /// relative variance `3 / n` (not the `2 / n` of independent differences); the next octave's shares
    /// its samples: correlation `3 / √72 ≈ 0.354` (worked by hand from the clusters' overlaps).
    #[test]
    fn white_noise_octaves_are_correlated_as_worked_by_hand() {
        let c = [1.0, 0.0, 0.0];
        let (tau, n) = (0.5, 1000.0);
        let avar = c[0] / tau;
        let own = octave_covariance(c, (tau, n), (tau, n));
        assert!((own / (avar * avar) - 3.0 / n).abs() < 1e-12, "{own}");
        let next = octave_covariance(c, (tau, n), (2.0 * tau, n / 2.0));
        let next_own = octave_covariance(c, (2.0 * tau, n / 2.0), (2.0 * tau, n / 2.0));
        let corr = next / libm::sqrt(own * next_own);
        assert!((corr - 3.0 / libm::sqrt(72.0)).abs() < 1e-9, "{corr}");
    }
}
