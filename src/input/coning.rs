//! Coning corrections for delta-angle input ([`super::DeltaAngles`]): from the angle increments
//! `Δθᵢ = ∫ ω dt` (rad) over the gyro sample intervals of one update to the update's rotation vector `φ`,
//! then `q ← q ⊗ exp_q(φ)`.
//!
//! Summing the increments ignores the non-commutativity of rotation: under coning motion (the rate vector
//! itself rotating) the attitude drifts about the cone axis. The cross-product corrections below remove that
//! drift to a given order (Ignagni, J. Guidance 13(2), 1990; Savage, *Strapdown Analytics*, §7):
//!
//! | correction | increments per update | φ | coning drift, small α (rad/s) |
//! |---|---|---|---|
//! | [`Uncorrected`] | 1 | `Δθ` | `α²Ω (ΩT)²/12` |
//! | [`OnePlusPrevious`] | 1 (+ the previous update's) | `Δθ_k + (1/12) Δθ_{k−1} × Δθ_k` | `α²Ω (Ωh)⁴/60` |
//! | [`TwoSample`] | 2 | `ΣΔθ + (2/3) Δθ₁ × Δθ₂` | `α²Ω (ΩT)⁴/960` |
//! | [`ThreeSample`] | 3 | `ΣΔθ + (9/20 Δθ₁ + 27/20 Δθ₂) × Δθ₃` | `α²Ω (ΩT)⁶/204120` |
//! | [`FourSample`] | 4 | `ΣΔθ + (54 Δθ₁ + 92 Δθ₂ + 214 Δθ₃)/105 × Δθ₄` | `α²Ω (ΩT)⁸/(…)`, see `tests/coning.rs` |
//! | [`FiveSample`] | 5 | `ΣΔθ + (250 Δθ₁ + 525 Δθ₂ + 650 Δθ₃ + 1375 Δθ₄)/504 × Δθ₅` | `α²Ω (ΩT)¹⁰/(…)` |
//!
//! `T` is the update interval, `h` the sample interval, `Ω` the coning frequency, `α` the cone half-angle.
//! The drift coefficients are checked against propagation on the exact coning motion in `tests/coning.rs`.

use crate::dispatch::dispatch;
use crate::exact::two_sum_vec;
use crate::{Real, Vec3};

/// A coning correction: the update's rotation vector from its angle increments.
pub trait ConingCorrection: Copy {
    /// Short name.
    fn name(&self) -> &'static str;
    /// Increments per update (1 to 5).
    fn samples(&self) -> usize;
    /// `φ` (rad) from this update's increments and the previous update's last increment (if any).
    /// `increments` has the length [`ConingCorrection::samples`] asks for (the input model gathers them).
    fn rotation_vector<T: Real>(
        &self,
        previous: Option<Vec3<T>>,
        increments: &[Vec3<T>],
    ) -> Vec3<T>;

    /// [`ConingCorrection::rotation_vector`] as an unevaluated sum `hi + lo` (rad): `hi` is its value bit for
    /// bit, `lo` the rounding of the increments' sum and of adding the correction term (TwoSum), which
    /// [`crate::accumulate::FloatFloat`] carries. By default no low part; every correction here
    /// keeps it.
    #[inline(always)]
    #[doc(hidden)]
    fn rotation_vector_split<T: Real>(
        &self,
        previous: Option<Vec3<T>>,
        increments: &[Vec3<T>],
    ) -> (Vec3<T>, Vec3<T>) {
        (self.rotation_vector(previous, increments), Vec3::ZERO)
    }
}

fn sum<T: Real>(increments: &[Vec3<T>]) -> Vec3<T> {
    let mut s = Vec3::ZERO;
    for d in increments {
        s += *d;
    }
    s
}

/// [`sum`] with its rounding error: the same high part, bit for bit, and the sum of every addition's error
/// (TwoSum; the errors' own sum rounds far below the high part's ulp).
#[inline(always)]
fn sum_split<T: Real>(increments: &[Vec3<T>]) -> (Vec3<T>, Vec3<T>) {
    let mut s = Vec3::ZERO;
    let mut e = Vec3::ZERO;
    for d in increments {
        let (t, r) = two_sum_vec(s, *d);
        s = t;
        e += r;
    }
    (s, e)
}

/// `φ = ΣΔθ + (Σ_{i<N} kᵢ Δθᵢ) × Δθ_N`: the compressed N-sample form with coefficients `k` (over `den`).
/// Panic-free for any slice (empty: zero).
fn compressed<T: Real>(increments: &[Vec3<T>], k: &[f64], den: f64) -> Vec3<T> {
    let Some((last, rest)) = increments.split_last() else {
        return Vec3::ZERO;
    };
    let mut weighted = Vec3::ZERO;
    for (d, &ki) in rest.iter().zip(k) {
        weighted += *d * T::from_f64(ki / den);
    }
    sum(increments) + weighted.cross(*last)
}

/// The cross-product term of [`compressed`], `(Σ_{i<N} kᵢ Δθᵢ) × Δθ_N` (zero for an empty slice), for
/// the split form only. `compressed` keeps its own copy of these lines on purpose: written as
/// `sum + compressed_term(…)` it measured 10 to 19 more M4F instructions per delta-angle step
/// (firmware `bench`, Plain and Kahan).
#[inline(always)]
fn compressed_term<T: Real>(increments: &[Vec3<T>], k: &[f64], den: f64) -> Vec3<T> {
    let Some((last, rest)) = increments.split_last() else {
        return Vec3::ZERO;
    };
    let mut weighted = Vec3::ZERO;
    for (d, &ki) in rest.iter().zip(k) {
        weighted += *d * T::from_f64(ki / den);
    }
    weighted.cross(*last)
}

/// [`compressed`] as `hi + lo` ([`ConingCorrection::rotation_vector_split`]).
#[inline(always)]
fn compressed_split<T: Real>(increments: &[Vec3<T>], k: &[f64], den: f64) -> (Vec3<T>, Vec3<T>) {
    let (s, e) = sum_split(increments);
    let (hi, r) = two_sum_vec(s, compressed_term(increments, k, den));
    (hi, e + r)
}

/// A coning correction's type, written once for all six: the unit struct (with the doc comments given) and
/// its [`ConingCorrection`] impl from the increments it takes and its two bodies, `rotation_vector` and
/// `rotation_vector_split`, over the names given for the previous update's increment and this update's.
macro_rules! correction {
    (
        $(#[doc = $doc:expr])*
        $name:ident, samples: $n:expr,
        |$previous:pat_param, $increments:ident| $value:expr,
        split: $split:expr $(,)?
    ) => {
        $(#[doc = $doc])*
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        pub struct $name;

        impl ConingCorrection for $name {
            fn name(&self) -> &'static str {
                stringify!($name)
            }
            fn samples(&self) -> usize {
                $n
            }
            #[inline]
            fn rotation_vector<T: Real>(&self, $previous: Option<Vec3<T>>, $increments: &[Vec3<T>]) -> Vec3<T> {
                $value
            }
            #[inline(always)]
            fn rotation_vector_split<T: Real>(&self, $previous: Option<Vec3<T>>, $increments: &[Vec3<T>]) -> (Vec3<T>, Vec3<T>) {
                $split
            }
        }
    };
}

correction!(
    /// No correction: `φ = Δθ`, one increment per update (the coning drift of the table above).
    Uncorrected, samples: 1,
    |_previous, increments| sum(increments),
    split: sum_split(increments),
);

correction!(
    /// One increment per update plus the previous update's: `φ = Δθ_k + (1/12) Δθ_{k−1} × Δθ_k`
    /// (PX4, KF-GINS). The first update, with no previous increment, is uncorrected.
    OnePlusPrevious, samples: 1,
    |previous, increments| match (increments.first(), previous) {
        (None, _) => Vec3::ZERO,
        (Some(&d), Some(p)) => d + p.cross(d) * T::from_f64(1.0 / 12.0),
        (Some(&d), None) => d,
    },
    split: match (increments.first(), previous) {
        (None, _) => (Vec3::ZERO, Vec3::ZERO),
        (Some(&d), Some(p)) => two_sum_vec(d, p.cross(d) * T::from_f64(1.0 / 12.0)),
        (Some(&d), None) => (d, Vec3::ZERO),
    },
);

correction!(
    /// Two increments per update: `φ = Δθ₁ + Δθ₂ + (2/3) Δθ₁ × Δθ₂`.
    TwoSample, samples: 2,
    |_previous, increments| compressed(increments, &[2.0], 3.0),
    split: compressed_split(increments, &[2.0], 3.0),
);

correction!(
    /// Three increments per update, coning-optimal: `φ = ΣΔθ + (9/20 Δθ₁ + 27/20 Δθ₂) × Δθ₃`.
    ThreeSample, samples: 3,
    |_previous, increments| compressed(increments, &[9.0, 27.0], 20.0),
    split: compressed_split(increments, &[9.0, 27.0], 20.0),
);

correction!(
    /// Four increments per update: `φ = ΣΔθ + (54 Δθ₁ + 92 Δθ₂ + 214 Δθ₃)/105 × Δθ₄`.
    FourSample, samples: 4,
    |_previous, increments| compressed(increments, &[54.0, 92.0, 214.0], 105.0),
    split: compressed_split(increments, &[54.0, 92.0, 214.0], 105.0),
);

correction!(
    /// Five increments per update: `φ = ΣΔθ + (250 Δθ₁ + 525 Δθ₂ + 650 Δθ₃ + 1375 Δθ₄)/504 × Δθ₅`.
    FiveSample, samples: 5,
    |_previous, increments| compressed(increments, &[250.0, 525.0, 650.0, 1375.0], 504.0),
    split: compressed_split(increments, &[250.0, 525.0, 650.0, 1375.0], 504.0),
);

/// Any coning correction, chosen at run time (the host lab's way; firmware names one type instead).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ConingKind {
    /// [`Uncorrected`].
    Uncorrected,
    /// [`OnePlusPrevious`].
    OnePlusPrevious,
    /// [`TwoSample`].
    TwoSample,
    /// [`ThreeSample`].
    ThreeSample,
    /// [`FourSample`].
    FourSample,
    /// [`FiveSample`].
    FiveSample,
}

impl ConingKind {
    /// Every correction.
    pub const ALL: [ConingKind; 6] = [
        ConingKind::Uncorrected,
        ConingKind::OnePlusPrevious,
        ConingKind::TwoSample,
        ConingKind::ThreeSample,
        ConingKind::FourSample,
        ConingKind::FiveSample,
    ];
}

macro_rules! each {
    ($self:ident, $c:ident => $e:expr) => {
        dispatch!(*$self;
            ConingKind::Uncorrected => Uncorrected,
            ConingKind::OnePlusPrevious => OnePlusPrevious,
            ConingKind::TwoSample => TwoSample,
            ConingKind::ThreeSample => ThreeSample,
            ConingKind::FourSample => FourSample,
            ConingKind::FiveSample => FiveSample;
            $c => $e)
    };
}

impl ConingCorrection for ConingKind {
    fn name(&self) -> &'static str {
        each!(self, c => c.name())
    }
    fn samples(&self) -> usize {
        each!(self, c => c.samples())
    }
    #[inline]
    fn rotation_vector<T: Real>(
        &self,
        previous: Option<Vec3<T>>,
        increments: &[Vec3<T>],
    ) -> Vec3<T> {
        each!(self, c => c.rotation_vector(previous, increments))
    }
    #[inline(always)]
    fn rotation_vector_split<T: Real>(
        &self,
        previous: Option<Vec3<T>>,
        increments: &[Vec3<T>],
    ) -> (Vec3<T>, Vec3<T>) {
        each!(self, c => c.rotation_vector_split(previous, increments))
    }
}
