//! A covariance kept as `P = U D Uᵀ` (`U` unit upper triangular, `D` diagonal and non-negative): symmetric
//! and positive semi-definite by construction, in `f32` as in `f64`, over any number of steps.
//!
//! The predict step is Thornton's (modified weighted Gram–Schmidt on `[Φ U | G]`, with `Q = G D_Q Gᵀ`
//! factored the same way); the update is Bierman's, one scalar measurement at a time (G. J. Bierman,
//! *Factorization Methods for Discrete Sequential Estimation*, 1977, §V and §VI; C. L. Thornton, G. J.
//! Bierman, *Gram–Schmidt algorithms for covariance propagation*, 1975). Neither forms `P`: no rounding can
//! make it asymmetric, and every `D` entry is a sum of non-negative terms (predict) or a non-negative one
//! scaled by a ratio in `(0, 1]` (update), so no eigenvalue goes negative — the property that `P ← ΦPΦᵀ +
//! Q` and `P ← (I − KH)P` lose in `f32` over a long run, and that symmetrizing and clamping only patch
//! (docs/covariance.md measures all three forms against an `f64` reference).
//!
//! ```
//! use quatprop::covariance::Ud;
//! use quatprop::error_state::{GyroNoise, Step};
//! use quatprop::Vec3;
//! // (δθ, δb): 0.1 rad and 0.01 rad/s standard deviations.
//! let mut p = Ud::<f32, 6>::from_diagonal([1e-2, 1e-2, 1e-2, 1e-4, 1e-4, 1e-4])?;
//! let noise = GyroNoise::from_datasheet(0.2, 5.0)?;
//! let step = Step::held_rate(Vec3::new(0.0, 0.0, 0.01), 0.01, &noise)?;
//! let (phi, q) = step.matrices();
//! p.predict(&phi, &q)?;
//! // Observe δθ_x with a variance of 1e-4 rad²: its variance falls to about 1e-4.
//! let gain = p.update(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0], 1e-4)?;
//! assert!((p.variances()[0] - 0.99e-4).abs() < 1e-6);
//! assert!((gain.gain[0] - 0.99).abs() < 1e-4);
//! # Ok::<(), quatprop::Error>(())
//! ```

// Matrix algorithms read clearest with the indices of their formulas.
#![allow(clippy::needless_range_loop)]

use crate::exact::{two_product, two_sum};
use crate::{Error, Real};

/// A covariance of `N` states as `U D Uᵀ` ([module documentation](self)). Small and `Copy`; no
/// allocation, no panic. On any error the factors are unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ud<T, const N: usize> {
    /// Unit upper triangular by rows (the strict lower triangle is zero; the diagonal is one).
    u: [[T; N]; N],
    /// The diagonal of `D`, non-negative.
    d: [T; N],
    /// What [`Ud::predict_compensated`] carries below `d`'s rounding (`D = d + d_low`); zero otherwise.
    d_low: [T; N],
}

/// What a scalar update returns ([`Ud::update`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gain<T, const N: usize> {
    /// The Kalman gain `K = P hᵀ / (h P hᵀ + r)`: the state moves by `K` times the innovation.
    pub gain: [T; N],
    /// The innovation's variance `h P hᵀ + r` (the prior `P`): the normalized innovation squared is
    /// `innovation² / innovation_variance`.
    pub innovation_variance: T,
}

impl<T: Real, const N: usize> Ud<T, N> {
    /// A diagonal covariance (`U = I`, `D` = `variances`).
    ///
    /// # Errors
    /// [`Error::InvalidCovariance`] for a negative, NaN or infinite variance.
    pub fn from_diagonal(variances: [T; N]) -> Result<Self, Error> {
        if !variances.iter().all(|&v| v >= T::ZERO && v.is_finite()) {
            return Err(Error::InvalidCovariance);
        }
        Ok(Self {
            u: identity(),
            d: variances,
            d_low: [T::ZERO; N],
        })
    }

    /// The factors of a symmetric positive semi-definite `p`.
    ///
    /// # Errors
    /// [`Error::InvalidCovariance`] if an entry is not finite, `p` is not symmetric (beyond 16 ε relative
    /// to its diagonal), or it is not positive semi-definite (a pivot below zero by more than `N` ε of
    /// its diagonal entry; one within that is taken as zero).
    pub fn from_matrix(p: &[[T; N]; N]) -> Result<Self, Error> {
        let eps = T::EPSILON;
        for i in 0..N {
            for j in 0..N {
                let (a, b) = (p[i][j], p[j][i]);
                if !a.is_finite() {
                    return Err(Error::InvalidCovariance);
                }
                let scale = (p[i][i] * p[j][j]).abs().sqrt();
                if (a - b).abs() > T::from_i32(16) * eps * scale {
                    return Err(Error::InvalidCovariance);
                }
            }
        }
        let (u, d) = factor(p, |pivot, diagonal| {
            if pivot >= T::ZERO {
                Some(pivot)
            } else if -pivot <= T::from_i32(N as i32) * eps * diagonal {
                Some(T::ZERO)
            } else {
                None
            }
        })
        .ok_or(Error::InvalidCovariance)?;
        Ok(Self {
            u,
            d,
            d_low: [T::ZERO; N],
        })
    }

    /// `P ← Φ P Φᵀ + Q` (Thornton): `q` symmetric positive semi-definite (its upper triangle is read;
    /// a pivot of its factorization that rounds below zero is taken as zero).
    ///
    /// # Errors
    /// [`Error::InvalidCovariance`] if `phi` or `q` has a non-finite entry, or the result overflows.
    pub fn predict(&mut self, phi: &[[T; N]; N], q: &[[T; N]; N]) -> Result<(), Error> {
        self.thornton::<false>(phi, q)
    }

    /// [`Ud::predict`] with `D` carried to twice the working precision: each `d_j` is summed from exact
    /// products (Dekker's TwoProduct, Knuth's TwoSum) and its rounding kept for the next step.
    ///
    /// Why: a variance that nothing observes (the heading of an inclination-only filter on a still or
    /// slowly turning body) grows by a `Q` far below its own ulp at each step — in f32, the angle random
    /// walk of a MEMS gyro over 10 ms is 1e-8 of a 5° heading variance, under half an ulp — and a plain sum
    /// drops every such increment (`tests/covariance.rs`: 10⁶ steps of 1e-11 on 1e-2, plain 1.0e-3 low,
    /// compensated 6e-8). About twice the time of [`Ud::predict`] (docs/covariance.md, docs/firmware.md);
    /// [`Ud::update`] keeps the carried part consistent.
    ///
    /// What it does not do: on a body that tumbles, the unobserved direction moves through the states at
    /// every step and its growth is lost in the rounding of `U` and of the reduced rows as well, which this
    /// does not carry; over 10⁸ steps at 1 kHz the f32 heading variance ended about 15 % below f64's either
    /// way (docs/covariance.md). There, propagate the covariance less often (larger increments) or keep it
    /// in f64.
    ///
    /// # Errors
    /// As [`Ud::predict`]; also when an exact product overflows (entries beyond about `MAX/4097`).
    pub fn predict_compensated(&mut self, phi: &[[T; N]; N], q: &[[T; N]; N]) -> Result<(), Error> {
        self.thornton::<true>(phi, q)
    }

    /// Thornton's modified weighted Gram–Schmidt; `CARRY`: `d` summed exactly and its low part kept.
    fn thornton<const CARRY: bool>(
        &mut self,
        phi: &[[T; N]; N],
        q: &[[T; N]; N],
    ) -> Result<(), Error> {
        let finite = |m: &[[T; N]; N]| m.iter().flatten().all(|v| v.is_finite());
        if !finite(phi) || !finite(q) {
            return Err(Error::InvalidCovariance);
        }
        // Q = G D_Q Gᵀ.
        let (g, dq) =
            factor(q, |pivot, _| Some(pivot.max(T::ZERO))).ok_or(Error::InvalidCovariance)?;
        // W = [Φ U | G], weights [D | D_Q]; rows are reduced from the last.
        let mut a = [[T::ZERO; N]; N];
        for (i, row) in a.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().enumerate() {
                // U is upper triangular: (ΦU)_ij = Σ_{k ≤ j} Φ_ik U_kj.
                let mut s = T::ZERO;
                for k in 0..=j {
                    s += phi[i][k] * self.u[k][j];
                }
                *e = s;
            }
        }
        let mut b = g;
        let mut u = identity();
        let mut d = [T::ZERO; N];
        let mut d_low = [T::ZERO; N];
        for j in (0..N).rev() {
            // d_j = |w_j|² in the weighted norm.
            let mut dj = T::ZERO;
            let mut wa = [T::ZERO; N];
            let mut wb = [T::ZERO; N];
            for k in 0..N {
                wa[k] = self.d[k] * a[j][k];
                wb[k] = dq[k] * b[j][k];
                dj += a[j][k] * wa[k] + b[j][k] * wb[k];
            }
            if CARRY {
                let (hi, lo) = carried_norm(&a[j], &self.d, &self.d_low, &b[j], &dq);
                dj = hi;
                d_low[j] = lo;
            }
            d[j] = dj;
            if dj > T::ZERO {
                let inv = T::ONE / dj;
                for i in 0..j {
                    let mut s = T::ZERO;
                    for k in 0..N {
                        s += a[i][k] * wa[k] + b[i][k] * wb[k];
                    }
                    let uij = s * inv;
                    u[i][j] = uij;
                    for k in 0..N {
                        a[i][k] -= uij * a[j][k];
                        b[i][k] -= uij * b[j][k];
                    }
                }
            }
        }
        let all = |v: &[T]| v.iter().all(|x| x.is_finite());
        if !(all(&d) && all(&d_low) && u.iter().all(|r| all(r))) {
            return Err(Error::InvalidCovariance);
        }
        self.u = u;
        self.d = d;
        self.d_low = d_low;
        Ok(())
    }

    /// Bierman's update with one scalar measurement `z = h·x + v`, `v` of variance `variance`: the
    /// factors become those of `(I − K h) P`, and the gain `K` is returned. Apply it as `x ← x + K (z −
    /// h·x)`, with `x` the error state as corrected by the measurements before this one.
    ///
    /// # Errors
    /// [`Error::InvalidNoise`] if `variance` is not positive and finite; [`Error::InvalidCovariance`] if
    /// `h` has a non-finite entry or the result overflows.
    pub fn update(&mut self, h: &[T; N], variance: T) -> Result<Gain<T, N>, Error> {
        if !(variance > T::ZERO && variance.is_finite()) {
            return Err(Error::InvalidNoise);
        }
        if !h.iter().all(|v| v.is_finite()) {
            return Err(Error::InvalidCovariance);
        }
        let mut u = self.u;
        let mut d = self.d;
        let mut d_low = self.d_low;
        // f = Uᵀ h, v = D f.
        let mut f = [T::ZERO; N];
        for (j, fj) in f.iter_mut().enumerate() {
            let mut s = h[j];
            for i in 0..j {
                s += u[i][j] * h[i];
            }
            *fj = s;
        }
        let mut v = [T::ZERO; N];
        for j in 0..N {
            v[j] = d[j] * f[j];
        }
        let mut b = [T::ZERO; N];
        let mut alpha = variance;
        for j in 0..N {
            let beta = alpha;
            alpha += f[j] * v[j];
            let lambda = -f[j] / beta;
            let ratio = beta / alpha;
            d[j] *= ratio;
            d_low[j] *= ratio;
            for i in 0..j {
                let uij = u[i][j];
                u[i][j] = uij + b[i] * lambda;
                b[i] += uij * v[j];
            }
            b[j] = v[j];
        }
        let inv = T::ONE / alpha;
        let mut gain = [T::ZERO; N];
        for (k, bk) in gain.iter_mut().zip(b) {
            *k = bk * inv;
        }
        let finite = alpha.is_finite()
            && gain.iter().all(|v| v.is_finite())
            && d.iter().all(|v| v.is_finite())
            && u.iter().flatten().all(|v| v.is_finite());
        if !finite {
            return Err(Error::InvalidCovariance);
        }
        self.u = u;
        self.d = d;
        self.d_low = d_low;
        Ok(Gain {
            gain,
            innovation_variance: alpha,
        })
    }

    /// `P = U D Uᵀ` (symmetric by construction: each entry is formed once and mirrored).
    #[must_use]
    pub fn matrix(&self) -> [[T; N]; N] {
        let mut p = [[T::ZERO; N]; N];
        for i in 0..N {
            for j in i..N {
                // Σ_{k ≥ j} U_ik D_k U_jk (U upper triangular).
                let mut s = T::ZERO;
                for k in j..N {
                    s += self.u[i][k] * self.d[k] * self.u[j][k];
                }
                p[i][j] = s;
                p[j][i] = s;
            }
        }
        p
    }

    /// The diagonal of `P`: each state's variance.
    #[must_use]
    pub fn variances(&self) -> [T; N] {
        let mut out = [T::ZERO; N];
        for (i, o) in out.iter_mut().enumerate() {
            let mut s = T::ZERO;
            for k in i..N {
                s += self.u[i][k] * self.u[i][k] * self.d[k];
            }
            *o = s;
        }
        out
    }

    /// The factor `U` (unit upper triangular, by rows).
    #[must_use]
    pub fn u(&self) -> [[T; N]; N] {
        self.u
    }

    /// The diagonal of `D` (non-negative).
    #[must_use]
    pub fn d(&self) -> [T; N] {
        self.d
    }
}

/// `Σₖ a_k² (d_k + l_k) + b_k² q_k` as `hi + lo`, the products exact (TwoProduct) and summed with TwoSum;
/// what stays rounded (`a_k²`'s low part times `d_k`, `l_k` and `q_k`'s products with the squares' low
/// parts) is below the result's ulp squared.
fn carried_norm<T: Real, const N: usize>(
    a: &[T; N],
    d: &[T; N],
    l: &[T; N],
    b: &[T; N],
    q: &[T; N],
) -> (T, T) {
    let (mut s, mut c) = (T::ZERO, T::ZERO);
    let mut add = |x: T, w: T, w_low: T| {
        let (x2, x2_low) = two_product(x, x);
        let (p, p_low) = two_product(w, x2);
        let (t, e) = two_sum(s, p);
        s = t;
        c += e + (p_low + w * x2_low + w_low * x2);
    };
    for k in 0..N {
        add(a[k], d[k], l[k]);
        add(b[k], q[k], T::ZERO);
    }
    two_sum(s, c)
}

fn identity<T: Real, const N: usize>() -> [[T; N]; N] {
    let mut u = [[T::ZERO; N]; N];
    for (i, row) in u.iter_mut().enumerate() {
        row[i] = T::ONE;
    }
    u
}

/// `p = U D Uᵀ` from `p`'s upper triangle, from the last column back; `pivot(value, p_jj)` decides what a
/// pivot becomes (`None`: refuse). A zero pivot leaves its column of `U` at the unit vector.
#[allow(clippy::type_complexity)]
fn factor<T: Real, const N: usize>(
    p: &[[T; N]; N],
    pivot: impl Fn(T, T) -> Option<T>,
) -> Option<([[T; N]; N], [T; N])> {
    let mut u = identity::<T, N>();
    let mut d = [T::ZERO; N];
    for j in (0..N).rev() {
        let mut s = p[j][j];
        for k in j + 1..N {
            s -= u[j][k] * u[j][k] * d[k];
        }
        let dj = pivot(s, p[j][j].abs())?;
        d[j] = dj;
        if dj > T::ZERO {
            let inv = T::ONE / dj;
            for i in 0..j {
                let mut s = p[i][j];
                for k in j + 1..N {
                    s -= u[i][k] * u[j][k] * d[k];
                }
                u[i][j] = s * inv;
            }
        }
    }
    Some((u, d))
}
