//! Integration schemes: how one step advances the attitude.
//!
//! | scheme | order (smooth ω) | stages | stability bound `h·|ω|` | norm factor `|R(ix)|²`, `x = h|ω|/2` |
//! |---|---|---|---|---|
//! | [`Euler`] | 1 | 1 | none (≤ 2 admitted) | `1 + x²` |
//! | [`Rk2`] | 2 | 2 | none (≤ 2√2 admitted) | `1 + x⁴/4` |
//! | [`Rk3`] | 3 | 3 | 2√3 ≈ 3.46 | `1 − x⁴/12 + x⁶/36` |
//! | [`Rk4`] | 4 | 4 | 4√2 ≈ 5.66 | `1 − x⁶/72 + x⁸/576` |
//! | [`Rk5`] | 5 | 6 | ≈ 2.00 (see README) | `1 − x⁶/1800 + O(x⁸)` |
//! | [`ExpMap`] | exact (held), 2 (linear), 4 (three samples) | – | none needed | 1 |
//! | [`Magnus4`] | 4 from the Gauss-point rates (`step_gauss`, `step_mid`) | – | none needed | 1 |
//! | [`Cf4`] | 4 from the Gauss-point rates, two exponentials, no cross product | – | none needed | 1 |
//!
//! Each scheme is a zero-sized type, so a firmware that names one links only it; [`Method`] chooses one at
//! run time. The order a step reaches also depends on the input model: with one gyro sample per step, any
//! scheme that sees only the two samples bracketing the step is second order (see [`crate::rates`]).

mod exp_map;
mod explicit_rk;
mod magnus;
pub mod tableau;
mod tableaux;

pub use exp_map::ExpMap;
pub use explicit_rk::held_rate_step_by_stages;
pub use magnus::{Cf4, Magnus4};
pub use tableau::ButcherTableau;
pub use tableaux::{Euler, Rk2, Rk3, Rk4, Rk5};

use crate::rates::RateModel;
use crate::stabilize::Stabilizer;
use crate::{Quat, Real};

/// An integration scheme for `q' = ½ q ⊗ (0, ω) + σ(q) q`.
pub trait Scheme: Copy {
    /// Short name, e.g. `"Rk4"`.
    fn name(&self) -> &'static str;

    /// Classical order on a smooth problem (what the scheme can reach with an exact rate).
    fn order(&self) -> u32;

    /// Largest admitted step angle `h·max|ω|` (rad); steps beyond it are refused with
    /// [`crate::Error::StepAngleBeyondStability`]. Derived from `|R(ix)|²`, see
    /// [`tableau::step_angle_limit`]. Infinite for the exponential map.
    fn step_angle_limit(&self) -> f64;

    /// End of the stability interval on the negative real axis (`h·λ`, `|R(−hλ)| ≤ 1` up to it).
    fn real_axis_limit(&self) -> f64;

    /// Largest Baumgarte `4k·h` the propagator accepts: half of [`Scheme::real_axis_limit`].
    ///
    /// The linear bound alone is not enough. The Baumgarte term is nonlinear (`−4kN(1 + N)`), the norm
    /// settles on the seed's `N∞ ≠ 0`, and the one-step map loses its fixed point before `4kh` reaches the
    /// real-axis limit for some schemes: in propagation (lab `baumgarte_sweep`, |ω| = 1 rad/s, H|ω| from 0.1 to
    /// 2) Rk5 escapes at 0.82–0.96 of the real-axis limit and stops settling at 0.66–0.82 of it; every scheme
    /// settles below half of it. Gains that large correct most of the norm error in one step anyway (the
    /// seed's optimal gains are `4kh` ≈ 0.002–0.05).
    #[inline(always)]
    fn gain_step_limit(&self) -> f64 {
        0.5 * self.real_axis_limit()
    }

    /// `|R(ix)|² − 1` at `x = h|ω|/2`: the per-step relative change of `|q|²` for a held rate with step angle
    /// `h|ω|` (rad) and no stabilization, evaluated from its own polynomial in `x²` (no cancellation).
    fn norm_change(&self, step_angle: f64) -> f64;

    /// Per-step factor `|R(ix)|²` of `|q|²` for a held rate with step angle `h|ω|` (rad), no stabilization.
    fn norm_factor(&self, step_angle: f64) -> f64 {
        1.0 + self.norm_change(step_angle)
    }

    /// The increment `Δ` of one step of length `h` (s) from `q` with the rates of `rates`: the new attitude
    /// is `q + Δ`. Schemes return increments so that the propagator can add them with compensated summation
    /// (see [`crate::accumulate`]). No checks: the propagator validates inputs first.
    fn increment<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T>;

    /// `q + increment(…)`: one unchecked step (the lab calls this to explore beyond the bounds).
    #[inline(always)]
    fn advance<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T> {
        q + self.increment(q, rates, h, stabilizer)
    }
}

/// Any scheme, chosen at run time (the host lab's way; firmware names one type instead).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Method {
    /// [`Euler`].
    Euler,
    /// [`Rk2`].
    Rk2,
    /// [`Rk3`].
    Rk3,
    /// [`Rk4`].
    Rk4,
    /// [`Rk5`].
    Rk5,
    /// [`ExpMap`].
    ExpMap,
    /// [`Magnus4`].
    Magnus4,
    /// [`Cf4`].
    Cf4,
}

impl Method {
    /// Every scheme.
    pub const ALL: [Method; 8] = [
        Method::Euler,
        Method::Rk2,
        Method::Rk3,
        Method::Rk4,
        Method::Rk5,
        Method::ExpMap,
        Method::Magnus4,
        Method::Cf4,
    ];
}

macro_rules! dispatch {
    ($self:ident, $s:ident => $e:expr) => {
        match *$self {
            Method::Euler => {
                let $s = Euler;
                $e
            }
            Method::Rk2 => {
                let $s = Rk2;
                $e
            }
            Method::Rk3 => {
                let $s = Rk3;
                $e
            }
            Method::Rk4 => {
                let $s = Rk4;
                $e
            }
            Method::Rk5 => {
                let $s = Rk5;
                $e
            }
            Method::ExpMap => {
                let $s = ExpMap;
                $e
            }
            Method::Magnus4 => {
                let $s = Magnus4;
                $e
            }
            Method::Cf4 => {
                let $s = Cf4;
                $e
            }
        }
    };
}

impl Scheme for Method {
    fn name(&self) -> &'static str {
        dispatch!(self, s => s.name())
    }
    fn order(&self) -> u32 {
        dispatch!(self, s => s.order())
    }
    fn step_angle_limit(&self) -> f64 {
        dispatch!(self, s => s.step_angle_limit())
    }
    fn real_axis_limit(&self) -> f64 {
        dispatch!(self, s => s.real_axis_limit())
    }
    fn norm_change(&self, step_angle: f64) -> f64 {
        dispatch!(self, s => s.norm_change(step_angle))
    }
    #[inline]
    fn increment<T: Real, R: RateModel<T>, Z: Stabilizer<T>>(
        &self,
        q: Quat<T>,
        rates: &R,
        h: T,
        stabilizer: &Z,
    ) -> Quat<T> {
        dispatch!(self, s => s.increment(q, rates, h, stabilizer))
    }
}
