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
    /// Its standard error (from the fit's weights, inflated by the misfit when the curve scatters more
    /// than its own counts say).
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
/// ([`Term::is_identified`]) instead of inventing it.
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

/// The most points a fit takes (octaves of a [`AllanVariance`] of up to 64 octaves).
const MAX_POINTS: usize = 64;

impl NoiseFit {
    /// Fits the model to `points` (at most 64 are used, the first ones; a point with no differences, a
    /// non-positive τ or a variance that is not finite and non-negative is skipped).
    ///
    /// Returns `None` with fewer than two usable points.
    #[must_use]
    pub fn of(points: impl IntoIterator<Item = Point>) -> Option<Self> {
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
        let full = fit_subset(rows_final.get(..len)?, 0b111);
        let dof = len.saturating_sub(s.n).max(1) as f64;
        let misfit = s.residual / dof;
        let inflate = misfit.max(1.0);
        let mut terms = [Term {
            coefficient: 0.0,
            std_error: f64::INFINITY,
        }; 3];
        for (j, term) in terms.iter_mut().enumerate() {
            term.coefficient = s.coefficients[j];
            let own = (s.mask & (1 << j) != 0).then(|| s.covariance[j][j]);
            let variance = own.or_else(|| full.as_ref().map(|f| f.covariance[j][j]));
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
        Self::of(
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
        Self::of(avar.clusters().filter(|c| c.tau >= min_tau).map(|c| Point {
            tau: c.tau,
            variance: (c.variance.x.to_f64() + c.variance.y.to_f64() + c.variance.z.to_f64()) / 3.0,
            differences: 3.0 * f64::from(c.differences),
        }))
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
