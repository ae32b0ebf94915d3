//! A recorded motion: the gyro rates of a real IMU trial (an excerpt of BROAD, `lab/data/broad/`, CC BY 4.0)
//! as a scene. The samples are interpolated by a natural cubic spline (twice continuously differentiable,
//! so a fourth-order integrator keeps its order on it), which defines ω(t) at any time and so a stream at any
//! rate; the reference attitude is that ω(t) integrated in f64 by Magnus-4 with Gauss-point samples, with
//! [`RecordedMotion::SUBSTEPS`] substeps per recorded interval, tabulated at the recorded samples and
//! integrated from the nearest one below for any other time. Its own accuracy is measured by halving the
//! substep ([`RecordedMotion::reference_check`]).
//!
//! Data: D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
//! Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0).

use crate::scene::{gauss_step, Scene, Sweep, DEFAULT_SWEEP};
use quatprop::input::GaussPoints;
use quatprop::scheme::Magnus4;
use quatprop::stabilize::Normalize;
use quatprop::{Propagator, Quat, Vec3};
use std::sync::OnceLock;

/// The excerpt (written by `lab/data/broad/make_gyro_excerpt.py`).
const BROAD_07: &str = include_str!("../data/broad/07_fast_rotation_gyro.csv");

/// A recorded rate profile with its spline and its reference.
pub struct RecordedMotion {
    key: &'static str,
    name: &'static str,
    /// Sampling rate of the recording (Hz).
    fs: f64,
    /// The recorded samples (rad/s).
    w: Vec<Vec3<f64>>,
    /// The spline's second derivatives at the samples.
    m: Vec<Vec3<f64>>,
    substeps: usize,
    /// The reference attitude at each recorded sample, built on first use.
    reference: OnceLock<Vec<Quat<f64>>>,
}

impl RecordedMotion {
    /// Magnus-4 substeps per recorded interval of the reference.
    pub const SUBSTEPS: usize = 8;

    /// BROAD trial 07 (undisturbed, fast rotation): 21 s from its first movement sample.
    pub fn broad() -> Self {
        Self::parse(
            "broad07",
            "BROAD trial 07 (fast rotation), recorded rates",
            BROAD_07,
            Self::SUBSTEPS,
        )
        .expect("the committed excerpt parses")
    }

    /// Width σ (s) of the Gaussian low-pass of [`RecordedMotion::broad_low_passed`].
    pub const LOW_PASS_SIGMA: f64 = 0.01;

    /// The same recording low-passed by a zero-phase Gaussian of σ = [`RecordedMotion::LOW_PASS_SIGMA`]
    /// (−3 dB at [`RecordedMotion::low_pass_cutoff`]): the body's motion without the gyro's noise, whose
    /// content up to the recording's Nyquist frequency a spline through the raw samples keeps.
    pub fn broad_low_passed() -> Self {
        let mut m = Self::parse(
            "broad07-lp",
            "BROAD trial 07 (fast rotation), recorded rates low-passed",
            BROAD_07,
            Self::SUBSTEPS,
        )
        .expect("the committed excerpt parses");
        m.w = gaussian_low_pass(&m.w, Self::LOW_PASS_SIGMA * m.fs);
        m.m = natural_spline(&m.w);
        m
    }

    /// The −3 dB frequency (Hz) of the Gaussian low-pass: `|H(f)| = exp(−2π²σ²f²)`.
    pub fn low_pass_cutoff() -> f64 {
        let s = Self::LOW_PASS_SIGMA;
        (0.5 * 2f64.ln() / (2.0 * std::f64::consts::PI.powi(2) * s * s)).sqrt()
    }

    /// Reads an excerpt: `#` lines (one of them `# sampling rate (Hz): F`), a header, then x,y,z per line.
    pub fn parse(
        key: &'static str,
        name: &'static str,
        text: &str,
        substeps: usize,
    ) -> Result<Self, String> {
        let mut fs = None;
        let mut w = Vec::new();
        for line in text.lines() {
            if let Some(c) = line.strip_prefix('#') {
                if let Some(v) = c.trim().strip_prefix("sampling rate (Hz):") {
                    fs = Some(v.trim().parse::<f64>().map_err(|e| format!("{e}"))?);
                }
                continue;
            }
            let f: Vec<&str> = line.split(',').collect();
            if f.len() != 3 || f[0] == "x" {
                continue;
            }
            let v = |i: usize| {
                f[i].trim()
                    .parse::<f64>()
                    .map_err(|e| format!("{line}: {e}"))
            };
            w.push(Vec3::new(v(0)?, v(1)?, v(2)?));
        }
        let fs = fs.ok_or("no sampling rate line")?;
        if w.len() < 4 {
            return Err("fewer than 4 samples".into());
        }
        let m = natural_spline(&w);
        Ok(Self {
            key,
            name,
            fs,
            w,
            m,
            substeps,
            reference: OnceLock::new(),
        })
    }

    /// Seconds the recording covers.
    #[cfg(test)]
    pub fn duration(&self) -> f64 {
        (self.w.len() - 1) as f64 / self.fs
    }

    /// The largest |ω| of the recorded samples (rad/s).
    pub fn peak_rate(&self) -> f64 {
        self.w.iter().map(|w| w.norm()).fold(0.0, f64::max)
    }

    /// The recorded interval holding t and t's offset in it (s).
    fn interval(&self, t: f64) -> (usize, f64) {
        let h = 1.0 / self.fs;
        let k = ((t * self.fs).floor().max(0.0) as usize).min(self.w.len() - 2);
        (k, t - k as f64 * h)
    }

    /// The spline on interval k at offset u (s) from its start.
    fn spline(&self, k: usize, u: f64) -> Vec3<f64> {
        let h = 1.0 / self.fs;
        let (a, b) = ((h - u) / h, u / h);
        let (m0, m1) = (self.m[k], self.m[k + 1]);
        self.w[k] * a
            + self.w[k + 1] * b
            + (m0 * (a * a * a - a) + m1 * (b * b * b - b)) * (1.0 / 6.0)
    }

    /// Integrates the spline over [offset u0, u0 + len] of interval k from q in `n` Magnus-4 steps.
    fn integrate(&self, q: Quat<f64>, k: usize, u0: f64, len: f64, n: usize) -> Quat<f64> {
        let Ok(mut p) = Propagator::new(q, Magnus4, GaussPoints::new(), Normalize) else {
            return Quat::IDENTITY;
        };
        let tau = len / n as f64;
        for j in 0..n {
            let a = u0 + j as f64 * tau;
            let _ = gauss_step(&mut p, |c| self.spline(k, a + c * tau), tau);
        }
        p.attitude()
    }

    fn reference(&self) -> &[Quat<f64>] {
        self.reference.get_or_init(|| {
            let h = 1.0 / self.fs;
            let mut q = Quat::IDENTITY;
            let mut v = Vec::with_capacity(self.w.len());
            v.push(q);
            for k in 0..self.w.len() - 1 {
                q = self.integrate(q, k, 0.0, h, self.substeps);
                v.push(q);
            }
            v
        })
    }

    /// The reference's own accuracy: the largest angle (rad) between this reference and one with half the
    /// substep, over the recorded samples.
    pub fn reference_check(&self) -> f64 {
        let fine = Self {
            key: self.key,
            name: self.name,
            fs: self.fs,
            w: self.w.clone(),
            m: self.m.clone(),
            substeps: 2 * self.substeps,
            reference: OnceLock::new(),
        };
        self.reference()
            .iter()
            .zip(fine.reference())
            .map(|(a, b)| a.angle_to(*b))
            .fold(0.0, f64::max)
    }
}

/// Each sample replaced by the Gaussian-weighted mean of its neighbours within 4σ (σ in samples), the
/// weights renormalized where the window passes an end: zero phase, unit gain at 0 Hz.
fn gaussian_low_pass(w: &[Vec3<f64>], sigma: f64) -> Vec<Vec3<f64>> {
    let reach = (4.0 * sigma).ceil() as isize;
    let kernel: Vec<f64> = (-reach..=reach)
        .map(|j| (-0.5 * (j as f64 / sigma).powi(2)).exp())
        .collect();
    let n = w.len() as isize;
    (0..n)
        .map(|k| {
            let (mut sum, mut weight) = (Vec3::<f64>::ZERO, 0.0);
            for (j, &g) in (-reach..=reach).zip(&kernel) {
                if let Some(x) = usize::try_from(k + j).ok().and_then(|i| w.get(i)) {
                    sum += *x * g;
                    weight += g;
                }
            }
            sum * (1.0 / weight)
        })
        .collect()
}

/// The second derivatives of the natural cubic spline through equally spaced samples (each axis; zero at
/// the ends), up to the factor 1/h² the evaluation applies: `M_{k−1} + 4 M_k + M_{k+1} = 6 (w_{k−1} − 2 w_k
/// + w_{k+1}) / h²` solved by the Thomas algorithm, returned already multiplied by h² (so in rad/s).
fn natural_spline(w: &[Vec3<f64>]) -> Vec<Vec3<f64>> {
    let n = w.len();
    let mut m = vec![Vec3::<f64>::ZERO; n];
    // Forward sweep over the interior unknowns 1..n-1 (diagonal 4, off-diagonals 1).
    let mut c = vec![0.0f64; n];
    let mut d = vec![Vec3::<f64>::ZERO; n];
    for k in 1..n - 1 {
        let rhs = (w[k - 1] - w[k] * 2.0 + w[k + 1]) * 6.0;
        let denom = 4.0 - if k > 1 { c[k - 1] } else { 0.0 };
        c[k] = 1.0 / denom;
        d[k] = (rhs - if k > 1 { d[k - 1] } else { Vec3::ZERO }) * (1.0 / denom);
    }
    for k in (1..n - 1).rev() {
        m[k] = d[k] - m[k + 1] * c[k];
    }
    m
}

// The `Scene` trait's methods, spelled out as in every scene.
impl Scene for RecordedMotion {
    fn key(&self) -> &'static str {
        self.key
    }
    fn name(&self) -> &'static str {
        self.name
    }
    fn sweep(&self) -> Sweep {
        Sweep {
            horizon: 20.37,
            ..DEFAULT_SWEEP
        }
    }
    fn rate(&self, t: f64) -> Vec3<f64> {
        let (k, u) = self.interval(t);
        self.spline(k, u)
    }
    fn attitude(&self, t: f64) -> Quat<f64> {
        let (k, u) = self.interval(t);
        let q = self.reference()[k];
        if u <= 0.0 {
            return q;
        }
        // The partial interval with substeps no longer than the reference's.
        let n = ((u * self.fs * self.substeps as f64).ceil() as usize).max(1);
        self.integrate(q, k, 0.0, u, n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spline goes through the samples, is continuous in value, slope and curvature at them, and has
    /// zero curvature at the ends.
    #[test]
    fn the_spline_interpolates_and_is_twice_differentiable() {
        let r = RecordedMotion::broad();
        let h = 1.0 / r.fs;
        assert_eq!(r.w.len(), 6000);
        assert!((r.fs - 285.714_285_714_285_7).abs() < 1e-9);
        let scale = r.peak_rate();
        for k in [1usize, 17, 2500, 5998] {
            // At the sample: both neighbouring pieces give the sample.
            assert!((r.spline(k, 0.0) - r.w[k]).norm() <= 1e-12 * scale, "{k}");
            assert!((r.spline(k - 1, h) - r.w[k]).norm() <= 1e-12 * scale, "{k}");
            // Slope and curvature from the two sides by differences of the pieces' own polynomials.
            let e = 1e-4 * h;
            let left = (r.spline(k - 1, h) - r.spline(k - 1, h - e)) * (1.0 / e);
            let right = (r.spline(k, e) - r.spline(k, 0.0)) * (1.0 / e);
            let curv = |j: usize, u: f64| {
                (r.spline(j, u + e) - r.spline(j, u) * 2.0 + r.spline(j, u - e)) * (1.0 / (e * e))
            };
            let slope_scale = scale * r.fs;
            assert!(
                (left - right).norm() < 1e-3 * slope_scale,
                "{k}: {left:?} {right:?}"
            );
            let (cl, cr) = (curv(k - 1, h - 2.0 * e), curv(k, 2.0 * e));
            assert!((cl - cr).norm() < 1e-2 * slope_scale * r.fs, "{k}");
        }
        assert_eq!(r.m[0], Vec3::ZERO);
        assert_eq!(r.m[r.w.len() - 1], Vec3::ZERO);
    }

    /// The reference is the spline's attitude: 2 q* ⊗ q' = ω(t) between the samples, and halving its
    /// substep moves it by less than 1e-9 rad over the whole excerpt.
    #[test]
    fn the_reference_follows_the_spline_and_converges() {
        let r = RecordedMotion::broad();
        for &t in &[0.1234, 7.77, 20.01] {
            let d = 1e-6;
            let dq = (r.attitude(t + d) - r.attitude(t - d)) * (0.5 / d);
            let w = r.attitude(t).conjugate() * dq * 2.0;
            let err = (w.vector() - r.rate(t)).norm();
            assert!(err < 1e-5 * r.peak_rate().max(1.0), "{t}: {err:e}");
        }
        let check = r.reference_check();
        assert!(check < 1e-9, "{check:e}");
        assert!(r.duration() > 20.37, "{}", r.duration());
    }

    /// The low-pass keeps a constant and a slow sine, takes out a fast one, and its cut-off is where the
    /// Gaussian's response is 1/√2.
    #[test]
    fn the_low_pass_keeps_the_motion_and_drops_the_noise() {
        let fs = 285.714_285_714_285_7;
        let sigma = RecordedMotion::LOW_PASS_SIGMA * fs;
        let sine = |f: f64| -> Vec<Vec3<f64>> {
            (0..4000)
                .map(|k| {
                    Vec3::new(
                        1.0,
                        (2.0 * std::f64::consts::PI * f * k as f64 / fs).sin(),
                        0.0,
                    )
                })
                .collect()
        };
        let amplitude =
            |v: &[Vec3<f64>]| v[1000..3000].iter().map(|x| x.y.abs()).fold(0.0, f64::max);
        let slow = gaussian_low_pass(&sine(1.0), sigma);
        assert!(slow.iter().all(|x| (x.x - 1.0).abs() < 1e-12));
        assert!(
            (amplitude(&slow) - (-2.0 * (std::f64::consts::PI * 0.01).powi(2)).exp()).abs() < 1e-3
        );
        // 100 Hz: the continuous response is 3e-9; the kernel cut at 4σ leaks at most twice its tail mass,
        // erfc(4/√2) = 6.3e-5.
        let fast = amplitude(&gaussian_low_pass(&sine(100.0), sigma));
        assert!(fast < 6.4e-5, "{fast:e}");
        let fc = RecordedMotion::low_pass_cutoff();
        let at_fc = amplitude(&gaussian_low_pass(&sine(fc), sigma));
        assert!((at_fc - 0.5f64.sqrt()).abs() < 0.01, "{fc} Hz: {at_fc}");
    }
}
