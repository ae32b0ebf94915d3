//! The exponential-map family: `q ← q ⊗ exp_q(φ)` with a rotation vector φ built from the step's rate
//! function. The Magnus-4 formula lives here, once ([`magnus4_half_angle`]); the input models only
//! describe their rate function ([`Segment`]).

use super::{Information, Scheme};
use crate::exact::two_sum_vec;
use crate::gauss;
use crate::input::segment::GaussRates;
use crate::input::Segment;
use crate::{Quat, Real, Vec3};

const EXPONENTIAL: Information = Information {
    name: "",
    order: 4,
    step_angle_limit: f64::INFINITY,
    real_axis_limit: f64::INFINITY,
    norm_change_polynomial: [0.0; 7],
};

/// Each exponential scheme's `information()`: [`EXPONENTIAL`] under its name, as a `const fn` (firmware
/// reads it in constants), written once for the three. (Their [`Scheme`] impls share the shape of the
/// trait's signatures; the bodies are each scheme's own.)
macro_rules! exponential_information {
    ($($name:ident),*) => {$(
        impl $name {
            /// What this scheme is: order, stability bounds, norm factor ([`Information`]).
            #[must_use]
            pub const fn information(self) -> Information {
                Information {
                    name: stringify!($name),
                    ..EXPONENTIAL
                }
            }
        }
    )*};
}

exponential_information!(ExpMap, Magnus4, Cf4);

/// Half the fourth-order Magnus rotation vector of a step: `φ/2 = ½∫ω dt + (h²/24) ω(½) × ω'(½)` with
/// `hh = h/2`, i.e. `half_angle(hh) + (hh²/6)·rate_commutator` (Iserles & Nørsett 1999; Blanes, Casas,
/// Oteo, Ros, *Phys. Rep.* 470 (2009), eq. (4.10)). Exact for a held rate (no commutator).
#[inline(always)]
fn magnus4_half_angle<T: Real, G: Segment<T>>(segment: &G, hh: T) -> Vec3<T> {
    let integral = segment.half_angle(hh);
    match segment.rate_commutator() {
        Some(c) => integral + c * (hh * hh * T::from_f64(1.0 / 6.0)),
        None => integral,
    }
}

/// Exact exponential map of the step's Magnus-4 rotation vector, from the input model's own integral of
/// ω and its commutator term:
///
/// - [`crate::input::Hold`]: `φ = hω`, exact for constant rotation at any `h|ω|` (no stability bound; in `f32` up to
///   16384 rad per step, see below).
/// - [`crate::input::Linear`]: `φ = h(ω₀ + ω₁)/2 + (h²/12) ω₀ × ω₁` (second order on sampled data: the
///   trapezoid error in `∫ω`).
/// - [`crate::input::History`], [`crate::input::TwiceRate`], [`crate::input::GaussPoints`]: fourth order.
/// - [`crate::input::DeltaAngles`]: the coning-corrected φ itself.
///
/// Small angles use a Taylor branch that drops nothing (see [`Quat::from_rotation_vector`]). Larger ones
/// (a half angle from 0.1 rad in `f32`, 0.005 rad in `f64`) take a sine: in `f32` a compact one in `f32`
/// arithmetic for half angles up to 8192 rad (within 1 ulp, tested over every `f32` argument; a step beyond
/// it is refused as [`crate::Error::NonFiniteResult`], state unchanged), so that a firmware links no `f64`
/// code and no general argument reduction (flash per scheme: docs/firmware.md); in `f64`, libm's.
///
/// ```
/// use quatprop::{input::Hold, scheme::ExpMap, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// // Exact for a constant rate, even at 3 rad per step.
/// let mut p = Propagator::new(Quat::IDENTITY, ExpMap, Hold, Off)?;
/// p.push(GyroSample::new(Vec3::new(3.0, 0.0, 0.0_f64)), 1.0)?;
/// assert!((p.attitude().x - 1.5_f64.sin()).abs() < 1e-15);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ExpMap;

impl<T: Real> Scheme<T> for ExpMap {
    #[inline(always)]
    fn information(&self) -> Information {
        ExpMap::information(*self)
    }
    #[inline(always)]
    fn increment<G: Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T> {
        // `q ⊗ (e − 1)` with `e = exp_q(φ)`.
        q * Quat::exp_half_minus_one(magnus4_half_angle(segment, h * T::HALF))
    }
    /// `exp_q(φ) − 1` with `φ/2` kept as `hi + lo`: the rounding of the angle integral's final sum and
    /// product, and the commutator term, in `lo`.
    #[inline(always)]
    fn right_factor<G: Segment<T>>(&self, segment: &G, h: T) -> (Quat<T>, Quat<T>) {
        let hh = h * T::HALF;
        let (v, low) = segment.half_angle_split(hh);
        let (v, low) = match segment.rate_commutator() {
            Some(c) => two_sum_vec(v, low + c * (hh * hh * T::from_f64(1.0 / 6.0))),
            None => (v, low),
        };
        Quat::exp_half_minus_one_split(v, low)
    }
}

/// Magnus-4 from the rates at the two Gauss nodes of the step:
/// `q ← q ⊗ exp_q((h/2)(ω₁ + ω₂) + (√3 h²/12) ω₁ × ω₂)`. With [`crate::input::GaussPoints`] it is
/// [`ExpMap`]; with another input it reads that input's rate function at the nodes.
///
/// ```
/// use quatprop::{input::TwiceRate, scheme::Magnus4, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, Magnus4, TwiceRate::new(), Off)?;
/// for k in 0..3 {
///     p.push(GyroSample::new(Vec3::new(0.0, 0.0, 0.1 * k as f64)), 0.1)?; // ω_z = t over 0.2 s
/// }
/// assert!((p.attitude().z - 0.01_f64.sin()).abs() < 1e-15); // ∫ t dt = 0.02 rad
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Magnus4;

impl<T: Real> Scheme<T> for Magnus4 {
    #[inline(always)]
    fn information(&self) -> Information {
        Magnus4::information(*self)
    }
    #[inline(always)]
    fn increment<G: Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T> {
        let at_nodes = GaussRates::sampled(segment);
        ExpMap.increment(q, &at_nodes, h)
    }
    #[inline(always)]
    fn right_factor<G: Segment<T>>(&self, segment: &G, h: T) -> (Quat<T>, Quat<T>) {
        let at_nodes = GaussRates::sampled(segment);
        ExpMap.right_factor(&at_nodes, h)
    }
}

/// Commutator-free fourth order (CF4): `q ← q ⊗ exp_q(h(β₁ω₁ + β₂ω₂)) ⊗ exp_q(h(β₂ω₁ + β₁ω₂))`,
/// `β₁,₂ = ¼ ± √3/6`, ω₁, ω₂ at the Gauss nodes: two exponentials, no cross product
/// (Blanes & Moan, *Appl. Numer. Math.* 56 (2006); Blanes et al., *Phys. Rep.* 470 (2009), eq. (5.8)).
///
/// ```
/// use quatprop::{input::GaussPoints, scheme::Cf4, stabilize::Off, GyroSample, Propagator, Quat, Vec3};
/// let mut p = Propagator::new(Quat::IDENTITY, Cf4, GaussPoints::new(), Off)?;
/// p.push(GyroSample::new(Vec3::new(0.0, 2.0, 0.0_f64)), 0.05)?;
/// p.push(GyroSample::new(Vec3::new(0.0, 2.0, 0.0_f64)), 0.05)?; // 2 rad/s for 0.1 s
/// assert!((p.attitude().y - 0.1_f64.sin()).abs() < 1e-15);
/// # Ok::<(), quatprop::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cf4;

impl<T: Real> Scheme<T> for Cf4 {
    #[inline(always)]
    fn information(&self) -> Information {
        Cf4::information(*self)
    }
    #[inline(always)]
    fn increment<G: Segment<T>>(&self, q: Quat<T>, segment: &G, h: T) -> Quat<T> {
        let (a, b) = (
            segment.rate_at(gauss::NODE_1),
            segment.rate_at(gauss::NODE_2),
        );
        let hh = h * T::HALF;
        let (b1, b2) = (
            T::from_f64(0.25 + gauss::HALF_GAP),
            T::from_f64(0.25 - gauss::HALF_GAP),
        );
        // exp_q(hβ·ω) = exp((0, hh·β·ω)).
        let e1 = Quat::exp_half_minus_one((a * b1 + b * b2) * hh);
        let e2 = Quat::exp_half_minus_one((a * b2 + b * b1) * hh);
        // e₁e₂ − 1 = (e₁ − 1) + (e₂ − 1) + (e₁ − 1)(e₂ − 1): no cancellation.
        q * (e1 + e2 + e1 * e2)
    }
}
