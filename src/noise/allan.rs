//! The Allan variance of a 3-axis sensor at rest, computed as the samples arrive.

use crate::exact::two_sum;
use crate::{Error, Real, Vec3};

/// One octave's running sums: cluster sums of `2^k` samples, the differences of consecutive ones.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
struct Octave<T> {
    /// The first half of the cluster being formed (a finished cluster of the octave below).
    half: Option<Vec3<T>>,
    /// The last finished cluster's sum.
    previous: Option<Vec3<T>>,
    /// `Σ (ȳᵢ₊₁ − ȳᵢ)²` over consecutive clusters' means, compensated (Kahan–Babuška: `low` holds what
    /// rounding dropped).
    sum_sq: Vec3<T>,
    low: Vec3<T>,
    /// The differences in `sum_sq`.
    count: u32,
}

impl<T: Real> Octave<T> {
    const EMPTY: Self = Self {
        half: None,
        previous: None,
        sum_sq: Vec3 {
            x: T::ZERO,
            y: T::ZERO,
            z: T::ZERO,
        },
        low: Vec3 {
            x: T::ZERO,
            y: T::ZERO,
            z: T::ZERO,
        },
        count: 0,
    };
}

/// One octave of an [`AllanVariance`]: the cluster time `tau`, the Allan variance on each axis and the
/// differences it averages.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Cluster<T> {
    /// The cluster time τ = `samples · period` (s).
    pub tau: f64,
    /// Samples per cluster, `2^k`.
    pub samples: u32,
    /// The Allan variance `σ²(τ) = ⟨(ȳᵢ₊₁ − ȳᵢ)²⟩ / 2` per axis (the sensor's unit squared: (rad/s)² for a
    /// gyroscope, (m/s²)² for an accelerometer).
    pub variance: Vec3<T>,
    /// The number of differences of consecutive cluster means averaged (`⌊n / 2^k⌋ − 1` for `n` samples):
    /// the estimate's relative standard error is about `√(2 / differences)` for white noise.
    pub differences: u32,
}

/// The non-overlapping Allan variance of a 3-axis sensor at octave-spaced cluster times `τ = 2^k · period`
/// (`k = 0 … OCTAVES − 1`, `OCTAVES ≤ 32`), computed as the samples arrive: no buffer, no allocation, a few operations per
/// sample (the octave `k` works once every `2^k` samples).
///
/// Each octave forms clusters of `2^k` consecutive samples from two clusters of the octave below (so
/// every sum is a pairwise sum, whose rounding grows with `k`, not with the number of samples), and
/// accumulates the squared differences of consecutive cluster means (compensated); the samples are
/// taken relative to the first one, so a large bias costs no precision in the differences. The
/// overlapping estimator (IEEE Std 952, Python's allantools) averages more differences at each τ, but
/// needs the samples of a cluster kept; this one needs `O(OCTAVES)` memory.
///
/// Feed it a recording at rest (a gyroscope in rad/s, an accelerometer in m/s²; any fixed axes) at a
/// fixed `period`, then read the [`clusters`](AllanVariance::clusters) or fit the noise terms with
/// [`NoiseFit::of`](super::NoiseFit::of).
///
/// ```
/// use quatprop::noise::AllanVariance;
/// use quatprop::Vec3;
/// let mut avar = AllanVariance::<f64, 8>::new(0.01)?; // 100 Hz, τ up to 1.28 s
/// for k in 0..1024 {
///     let s = if k % 2 == 0 { 1.0 } else { -1.0 }; // ±1: the clusters of two average to zero
///     avar.push(Vec3::new(s, 0.0, 0.0))?;
/// }
/// let first = avar.clusters().next().unwrap();
/// assert_eq!((first.tau, first.differences), (0.01, 1023));
/// assert_eq!(first.variance.x, 2.0); // ⟨(±2)²⟩ / 2
/// assert_eq!(avar.clusters().nth(1).unwrap().variance.x, 0.0);
/// # Ok::<(), quatprop::Error>(())
/// ```
///
/// (No `serde` derive: serde's arrays stop at 32 elements and `OCTAVES` is any; the [`Cluster`]s it
/// reads out have one.)
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AllanVariance<T, const OCTAVES: usize = 24> {
    period: f64,
    /// The first sample: every sample is taken relative to it.
    origin: Option<Vec3<T>>,
    samples: u64,
    octaves: [Octave<T>; OCTAVES],
}

impl<T: Real, const OCTAVES: usize> AllanVariance<T, OCTAVES> {
    /// An empty estimate for samples `period` seconds apart.
    ///
    /// # Errors
    /// [`Error::NonFiniteStep`] or [`Error::NonPositiveStep`] for a `period` that is not finite and
    /// positive.
    pub fn new(period: f64) -> Result<Self, Error> {
        // A cluster's sample count is a u32: 2^31 at most.
        const { assert!(OCTAVES <= 32, "at most 32 octaves") };
        if !period.is_finite() {
            return Err(Error::NonFiniteStep);
        }
        if !(period > 0.0) {
            return Err(Error::NonPositiveStep);
        }
        Ok(Self {
            period,
            origin: None,
            samples: 0,
            octaves: [Octave::EMPTY; OCTAVES],
        })
    }

    /// The sample period (s).
    #[must_use]
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Samples taken so far.
    #[must_use]
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// Takes the next sample.
    ///
    /// # Errors
    /// [`Error::NonFiniteRate`] for a NaN or infinite component, or a sample so far from the first that
    /// a cluster's sum would overflow; the estimate is then unchanged.
    pub fn push(&mut self, sample: Vec3<T>) -> Result<(), Error> {
        if !sample.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        let origin = self.origin.unwrap_or(sample);
        let mut next = *self;
        next.origin = Some(origin);
        next.samples += 1;
        // The cluster of one sample, then each finished cluster carried one octave up.
        let mut cluster = Some(sample - origin);
        let mut samples = T::ONE;
        for octave in next.octaves.iter_mut() {
            let Some(sum) = cluster.take() else { break };
            if let Some(previous) = octave.previous {
                let d = (sum - previous) * (T::ONE / samples);
                octave.add_square(d);
            }
            octave.previous = Some(sum);
            match octave.half.take() {
                Some(first) => cluster = Some(first + sum),
                None => octave.half = Some(sum),
            }
            samples *= T::TWO;
        }
        if !next.is_finite() {
            return Err(Error::NonFiniteRate);
        }
        *self = next;
        Ok(())
    }

    /// Every octave with at least one difference, shortest τ first.
    pub fn clusters(&self) -> impl Iterator<Item = Cluster<T>> + '_ {
        let half = T::HALF;
        self.octaves
            .iter()
            .enumerate()
            .filter(|(_, o)| o.count > 0)
            .map(move |(k, o)| {
                let n = T::from_f64(f64::from(o.count));
                let samples = 1_u32 << k;
                Cluster {
                    tau: self.period * f64::from(samples),
                    samples,
                    variance: (o.sum_sq + o.low) * (half / n),
                    differences: o.count,
                }
            })
    }

    fn is_finite(&self) -> bool {
        self.octaves.iter().all(|o| {
            o.sum_sq.is_finite()
                && o.low.is_finite()
                && o.half.is_none_or(Vec3::is_finite)
                && o.previous.is_none_or(Vec3::is_finite)
        })
    }
}

impl<T: Real> Octave<T> {
    /// `sum_sq += d²` per axis, compensated.
    fn add_square(&mut self, d: Vec3<T>) {
        let add = |s: &mut T, low: &mut T, v: T| {
            let (hi, lo) = two_sum(*s, v);
            *s = hi;
            *low += lo;
        };
        add(&mut self.sum_sq.x, &mut self.low.x, d.x * d.x);
        add(&mut self.sum_sq.y, &mut self.low.y, d.y * d.y);
        add(&mut self.sum_sq.z, &mut self.low.z, d.z * d.z);
        self.count = self.count.saturating_add(1);
    }
}
