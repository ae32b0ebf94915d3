//! The rate functions the built-in input models hand to the schemes: each model's
//! [`InputModel::Segment`](super::InputModel::Segment), named here so that a propagator's type can be
//! written out. They are built by their input models only; a custom input model brings its own [`Segment`]
//! (see [`crate::input`]).

use super::Segment;
use crate::exact::{two_product_vec, two_sum_vec};
use crate::gauss;
use crate::{Real, Vec3};
use core::marker::PhantomData;

/// `(a + b)·k` as `hi + lo`: the sum's and the product's roundings kept (the rounding of `lo` itself and
/// of `e·k` aside).
#[inline(always)]
fn sum_times_split<T: Real>(a: Vec3<T>, b: Vec3<T>, k: T) -> (Vec3<T>, Vec3<T>) {
    let (s, e) = two_sum_vec(a, b);
    let (p, pe) = two_product_vec(s, k);
    (p, pe + e * k)
}

/// ω constant over the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeldRate<T>(pub(crate) Vec3<T>);

impl<T: Real> Segment<T> for HeldRate<T> {
    #[inline(always)]
    fn rate_at(&self, _c: f64) -> Vec3<T> {
        self.0
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        Some(self.0)
    }
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        self.0 * hh
    }
    #[inline(always)]
    fn half_angle_split(&self, hh: T) -> (Vec3<T>, Vec3<T>) {
        two_product_vec(self.0, hh)
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.0 * h).norm_squared()
    }
}

/// ω (rad/s, body axes) linear in time through its values at two nodes of the step (fractions of it,
/// symmetric about ½): `first` at [`Nodes::FIRST`], `second` at [`Nodes::SECOND`], linear between and
/// beyond them. Both
/// [`LinearRate`] (the step's ends) and [`GaussRates`] (its Gauss–Legendre nodes) are this segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoNodeRate<T, N> {
    pub(crate) first: Vec3<T>,
    pub(crate) second: Vec3<T>,
    nodes: PhantomData<N>,
}

impl<T, N> TwoNodeRate<T, N> {
    /// The rates at the first and the second node (rad/s).
    #[inline(always)]
    pub(crate) const fn new(first: Vec3<T>, second: Vec3<T>) -> Self {
        Self {
            first,
            second,
            nodes: PhantomData,
        }
    }
}

impl<T: Real, N: Nodes> TwoNodeRate<T, N> {
    /// `segment`'s rates at the two nodes: the linear rate through them.
    #[inline(always)]
    pub(crate) fn sampled<G: Segment<T>>(segment: &G) -> Self {
        Self::new(segment.rate_at(N::FIRST), segment.rate_at(N::SECOND))
    }
}

/// Where a [`TwoNodeRate`]'s two values sit in the step (fractions of it, symmetric about ½: the
/// segment's half-angle rule needs the symmetry). Sealed: [`Ends`] and [`GaussNodes`] are the nodes.
pub trait Nodes: Copy + sealed::Sealed {
    /// The first node (fraction of the step).
    const FIRST: f64;
    /// The second node (fraction of the step).
    const SECOND: f64;
    /// `1/(SECOND − FIRST)`: turns the difference of the two node values into a slope per unit step.
    const INV_GAP: f64;
}

/// The step's start and end: `ω` linear from its value at the start to its value at the end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ends;

impl sealed::Sealed for Ends {}
impl Nodes for Ends {
    const FIRST: f64 = 0.0;
    const SECOND: f64 = 1.0;
    const INV_GAP: f64 = 1.0;
}

/// The two Gauss–Legendre nodes of the step, `½ ∓ √3/6`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GaussNodes;

impl sealed::Sealed for GaussNodes {}
impl Nodes for GaussNodes {
    const FIRST: f64 = gauss::NODE_1;
    const SECOND: f64 = gauss::NODE_2;
    const INV_GAP: f64 = gauss::INV_GAP;
}

mod sealed {
    /// Keeps [`super::Nodes`] to this crate's two sets of nodes.
    pub trait Sealed {}
}

/// ω linear from its value at the start to its value at the end of the step.
pub type LinearRate<T> = TwoNodeRate<T, Ends>;

/// Rates at the two Gauss–Legendre nodes of the step; linear between (and beyond) them.
pub type GaussRates<T> = TwoNodeRate<T, GaussNodes>;

impl<T: Real, N: Nodes> Segment<T> for TwoNodeRate<T, N> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        if c == N::FIRST {
            self.first
        } else if c == N::SECOND {
            self.second
        } else {
            let f = (c - N::FIRST) * N::INV_GAP;
            self.first + (self.second - self.first) * T::from_f64(f)
        }
    }
    /// The two-node rule (the trapezoid at the ends, the Gauss rule at the Gauss nodes), exact for a
    /// linear rate: `½∫ω = (hh/2)(ω₁ + ω₂)`.
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        (self.first + self.second) * (hh * T::HALF)
    }
    #[inline(always)]
    fn half_angle_split(&self, hh: T) -> (Vec3<T>, Vec3<T>) {
        sum_times_split(self.first, self.second, hh * T::HALF)
    }
    /// `ω(½) × ω'(½) = ½(ω₁ + ω₂) × (ω₂ − ω₁)/gap = ω₁ × ω₂ / gap` exactly for a linear rate (`gap` 1
    /// at the ends, `1/√3` at the Gauss nodes).
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        Some(self.first.cross(self.second) * T::from_f64(N::INV_GAP))
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.first * h)
            .norm_squared()
            .max((self.second * h).norm_squared())
    }
}

/// ω quadratic through samples at the start, the middle and the end of the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadraticRate<T> {
    pub(crate) w0: Vec3<T>,
    pub(crate) wm: Vec3<T>,
    pub(crate) w1: Vec3<T>,
}

impl<T: Real> Segment<T> for QuadraticRate<T> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        if c == 0.0 {
            self.w0
        } else if c == 0.5 {
            self.wm
        } else if c == 1.0 {
            self.w1
        } else {
            // Lagrange basis on the nodes 0, ½, 1 (constants: c is a tableau node).
            let l0 = 2.0 * (c - 0.5) * (c - 1.0);
            let lm = -4.0 * c * (c - 1.0);
            let l1 = 2.0 * c * (c - 0.5);
            self.w0 * T::from_f64(l0) + self.wm * T::from_f64(lm) + self.w1 * T::from_f64(l1)
        }
    }
    /// Simpson: `½∫ω = (hh/6)(ω₀ + 4ω_m + ω₁)`.
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        (self.w0 + self.wm * T::from_f64(4.0) + self.w1) * (hh * T::from_f64(1.0 / 6.0))
    }
    /// `ω₀ × ω₁`: differs from `ω(½) × ω'(½)` by O(h³).
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        Some(self.w0.cross(self.w1))
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        (self.w0 * h)
            .norm_squared()
            .max((self.wm * h).norm_squared())
            .max((self.w1 * h).norm_squared())
    }
}

/// `4Δ₂ − Δ₁`: the earlier samples' part of the cubic's mean rate over the step (`/24`) and of its rate
/// at the middle (`/16`), computed once for both.
#[inline(always)]
fn earlier<T: Real>(d1: Vec3<T>, d2: Vec3<T>) -> Vec3<T> {
    d2 * T::from_f64(4.0) - d1
}

/// The equally spaced history's mean rate over the step as `ω_k + correction`: the correction for the
/// cubic (`count` 4) and the quadratic step (3), `None` for the linear step (2), which has no `ω_k` term.
/// The quadratic step also carries the start correction (see [`HistoryRate`]): `(2Δ₃ + Δ₂)/6` instead of
/// the quadratic's own `(5Δ₃ + Δ₂)/12`, so that the linear step before it and this one together integrate
/// Simpson's rule over both intervals.
#[inline(always)]
fn uniform_correction<T: Real>(ends: [Vec3<T>; 2], d: [Vec3<T>; 2], count: u8) -> Option<Vec3<T>> {
    let [w2, w3] = ends;
    let [d1, d2] = d;
    let d3 = w3 - w2;
    match count {
        4 => Some((d3 * T::from_f64(9.0) + earlier(d1, d2)) * T::from_f64(1.0 / 24.0)),
        3 => Some((d3 * T::TWO + d2) * T::from_f64(1.0 / 6.0)),
        _ => None,
    }
}

/// ω from the sample history: the polynomial through the last 2, 3 or 4 samples
/// ω_{k−2}, ω_{k−1}, ω_k, ω_{k+1} on the last interval `[t_k, t_{k+1}]`.
///
/// `Uniform`: equally spaced samples, held as the interval's ends and the backward differences
/// `Δ₁ = ω_{k−1} − ω_{k−2}`, `Δ₂ = ω_k − ω_{k−1}` (with `Δ₃ = ω_{k+1} − ω_k`), the weights constants.
/// `Newton`: samples at their true times (jittered timestamps), the Newton form
/// `p(c) = ω_k + (ω_{k+1} − ω_k)c + d₂ c(c − 1) + d₃ c(c − 1)(c + r)` in units of the step, with the
/// divided differences `d₂`, `d₃` and `r = (t_k − t_{k−1})/h`.
///
/// **The start correction.** The history's first step (after a cold start or a gap) is linear over
/// `[t_{k−1}, t_k]`, the trapezoid rule, which errs by `−(r h)³ω''/12`: O(h³), one order short, and over a
/// horizon it would set the order of the whole run. The quadratic step that follows (three samples) knows
/// ω'' and carries the correction: its rate function is the quadratic plus `r³d₂ c(c − 1)` (zero at both
/// ends, so the samples stay exact at their nodes), whose integral over the step, `−r³d₂/6`, is the
/// trapezoid's error over the interval before. Moved from `t_k` to the end of this step it commutes with
/// the step's rotation to O(h⁴), so from the third sample on the attitude is fourth order over any horizon,
/// with no latency (the linear step's own attitude, one sample long, is third order). In both forms this
/// is the quadratic's `d₂` times `1 + r³` (equal spacing: `r = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HistoryRate<T> {
    /// Equally spaced samples.
    Uniform {
        /// ω_k and ω_{k+1}.
        ends: [Vec3<T>; 2],
        /// `[Δ₁, Δ₂]`; the ones the count leaves out are unused.
        d: [Vec3<T>; 2],
        /// 2, 3 or 4 samples.
        count: u8,
    },
    /// Samples at their true times.
    Newton {
        /// ω_k and ω_{k+1}.
        ends: [Vec3<T>; 2],
        /// Second and third divided differences (per unit step²  and step³; zero with fewer samples).
        d2: Vec3<T>,
        /// See `d2`.
        d3: Vec3<T>,
        /// `(t_k − t_{k−1})/h`.
        r: T,
    },
}

impl<T: Real> HistoryRate<T> {
    /// The Newton form through the samples ending at `ends = [ω_k, ω_{k+1}]` with the backward differences
    /// `d = [Δ₁, Δ₂]` before them, whose spacings relative to the step are `r1 = (t_k − t_{k−1})/h` and
    /// `r2 = (t_{k−1} − t_{k−2})/h`.
    #[inline]
    pub(crate) fn newton(ends: [Vec3<T>; 2], d: [Vec3<T>; 2], count: u8, r1: T, r2: T) -> Self {
        let [w2, w3] = ends;
        let [dd1, dd2] = d;
        let d1 = w3 - w2;
        let (d2, d3) = match count {
            4 => {
                let d12 = dd2 * (T::ONE / r1);
                let d01 = dd1 * (T::ONE / r2);
                let d2 = (d1 - d12) * (T::ONE / (T::ONE + r1));
                let d012 = (d12 - d01) * (T::ONE / (r1 + r2));
                (d2, (d2 - d012) * (T::ONE / (T::ONE + r1 + r2)))
            }
            // With the start correction: d₂·(1 + r³).
            3 => {
                let d12 = dd2 * (T::ONE / r1);
                let start = T::ONE + r1 * r1 * r1;
                ((d1 - d12) * (start / (T::ONE + r1)), Vec3::ZERO)
            }
            _ => (Vec3::ZERO, Vec3::ZERO),
        };
        HistoryRate::Newton {
            ends: [w2, w3],
            d2,
            d3,
            r: r1,
        }
    }

    /// The weights of `[Δ₁, Δ₂, Δ₃]` in `ω(c) = ω_k + Σ weight·Δ` for equally spaced samples (the
    /// Newton form on the nodes 0, 1, −1, −2: `cΔ₃ + c(c−1)/2·(Δ₃ − Δ₂) + c(c−1)(c+1)/6·(Δ₃ − 2Δ₂ + Δ₁)`,
    /// the terms the count allows; the quadratic step's second difference doubled by the start
    /// correction).
    #[inline(always)]
    fn weights(count: u8, c: f64) -> [f64; 3] {
        let quadratic = c * (c - 1.0) / 2.0;
        let cubic = c * (c - 1.0) * (c + 1.0) / 6.0;
        match count {
            4 => [cubic, -quadratic - 2.0 * cubic, c + quadratic + cubic],
            3 => [0.0, -2.0 * quadratic, c + 2.0 * quadratic],
            _ => [0.0, 0.0, c],
        }
    }
}

impl<T: Real> Segment<T> for HistoryRate<T> {
    #[inline(always)]
    fn rate_at(&self, c: f64) -> Vec3<T> {
        match self {
            HistoryRate::Uniform { ends, d, count } => {
                let [w2, w3] = *ends;
                if c == 0.0 {
                    w2
                } else if c == 1.0 {
                    w3
                } else {
                    let [d1, d2] = *d;
                    let mut s = w2;
                    for (d, k) in [d1, d2, w3 - w2].into_iter().zip(Self::weights(*count, c)) {
                        if k != 0.0 {
                            s += d * T::from_f64(k);
                        }
                    }
                    s
                }
            }
            HistoryRate::Newton { ends, d2, d3, r } => {
                let [w2, w3] = *ends;
                let cc = T::from_f64(c);
                let b = T::from_f64(c * (c - 1.0));
                w2 + (w3 - w2) * cc + *d2 * b + *d3 * (b * (cc + *r))
            }
        }
    }
    /// `½∫ω dt` written on the differences of the samples, so a constant rate integrates exactly:
    /// cubic `ω_k + (9Δ₃ + 4Δ₂ − Δ₁)/24` (Adams–Moulton's (1, −5, 19, 9)/24), quadratic with the start
    /// correction `ω_k + (2Δ₃ + Δ₂)/6`, linear `(ω_k + ω_{k+1})/2`. Newton form:
    /// `∫₀¹ p = ω_k + Δ₃/2 − d₂/6 − d₃(1/12 + r/6)`.
    #[inline(always)]
    fn half_angle(&self, hh: T) -> Vec3<T> {
        match self {
            HistoryRate::Uniform { ends, d, count } => {
                let [w2, w3] = *ends;
                match uniform_correction(*ends, *d, *count) {
                    Some(correction) => (w2 + correction) * hh,
                    None => (w2 + w3) * (hh * T::HALF),
                }
            }
            HistoryRate::Newton { ends, d2, d3, r } => {
                let [w2, w3] = *ends;
                let k3 = T::from_f64(1.0 / 12.0) + *r * T::from_f64(1.0 / 6.0);
                let mean = w2 + (w3 - w2) * T::HALF - *d2 * T::from_f64(1.0 / 6.0) - *d3 * k3;
                mean * hh
            }
        }
    }
    /// The mean rate as `ω_k + correction` with that sum's rounding kept, times `hh` with TwoProduct
    /// (the correction, a small difference of samples, rounds plainly).
    #[inline(always)]
    fn half_angle_split(&self, hh: T) -> (Vec3<T>, Vec3<T>) {
        let (w2, correction) = match self {
            HistoryRate::Uniform { ends, d, count } => {
                let [w2, w3] = *ends;
                match uniform_correction(*ends, *d, *count) {
                    Some(correction) => (w2, correction),
                    None => return sum_times_split(w2, w3, hh * T::HALF),
                }
            }
            HistoryRate::Newton { ends, d2, d3, r } => {
                let [w2, w3] = *ends;
                let k3 = T::from_f64(1.0 / 12.0) + *r * T::from_f64(1.0 / 6.0);
                (
                    w2,
                    (w3 - w2) * T::HALF - *d2 * T::from_f64(1.0 / 6.0) - *d3 * k3,
                )
            }
        };
        let (mean, e) = two_sum_vec(w2, correction);
        let (p, pe) = two_product_vec(mean, hh);
        (p, pe + e * hh)
    }
    /// `ω(½) × (ω_{k+1} − ω_k)`: uniform, ω(½) from the interpolant, `ω_k + (5/16)Δ₃ + (4Δ₂ − Δ₁)/16`
    /// (cubic; quadratic with the start correction `ω_k + (Δ₃ + Δ₂)/4`), whose `Δ₃` term drops out of the cross product with
    /// `Δ₃` (and `4Δ₂ − Δ₁` is the mean rate's too); Newton, ω(½) ≈ (ω_k + ω_{k+1})/2, which makes it
    /// `ω_k × ω_{k+1}` (the O(h²) difference costs O(h⁵) per step). `ω_{k+1} − ω_k` is `ω'(½)` to O(h³).
    #[inline(always)]
    fn rate_commutator(&self) -> Option<Vec3<T>> {
        match self {
            HistoryRate::Uniform { ends, d, count } => {
                let [w2, w3] = *ends;
                let [d1, d2] = *d;
                let mid = match count {
                    4 => w2 + earlier(d1, d2) * T::from_f64(1.0 / 16.0),
                    3 => w2 + d2 * T::from_f64(0.25),
                    _ => w2,
                };
                Some(mid.cross(w3 - w2))
            }
            HistoryRate::Newton { ends, .. } => Some(ends[0].cross(ends[1])),
        }
    }
    /// The two samples that bound the step: every earlier sample bounded a step of its own and was checked
    /// there (the start-up sample, which closes no step, is `w_k` of the next), at a spacing within
    /// 2⁻²⁰ (relative) of this one for the constant weights.
    #[inline(always)]
    fn max_step_angle_squared(&self, h: T) -> T {
        let [w2, w3] = match self {
            HistoryRate::Uniform { ends, .. } | HistoryRate::Newton { ends, .. } => *ends,
        };
        (w2 * h).norm_squared().max((w3 * h).norm_squared())
    }
}

/// The step's rotation vector φ (rad) given directly (delta angles after a coning correction). Runge–Kutta
/// schemes see the constant rate `φ/h`; the exponential map applies φ exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationVector<T> {
    pub(crate) phi: Vec3<T>,
    pub(crate) h: T,
    /// The rounding of `phi` (TwoSum over the increments and the correction term): `φ = phi + low`; zero
    /// unless the accumulator carries low parts ([`crate::input::InputModel::accept_split`]).
    pub(crate) low: Vec3<T>,
}

impl<T: Real> Segment<T> for RotationVector<T> {
    #[inline(always)]
    fn rate_at(&self, _c: f64) -> Vec3<T> {
        self.phi * (T::ONE / self.h)
    }
    #[inline(always)]
    fn held_rate(&self) -> Option<Vec3<T>> {
        Some(self.phi * (T::ONE / self.h))
    }
    #[inline(always)]
    fn half_angle(&self, _hh: T) -> Vec3<T> {
        self.phi * T::HALF
    }
    /// Halving is exact: the low part is the rotation vector's own.
    #[inline(always)]
    fn half_angle_split(&self, _hh: T) -> (Vec3<T>, Vec3<T>) {
        (self.phi * T::HALF, self.low * T::HALF)
    }
    #[inline(always)]
    fn max_step_angle_squared(&self, _h: T) -> T {
        self.phi.norm_squared()
    }
}
