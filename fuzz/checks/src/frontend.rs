//! Target `frontend`: the sensor front end on arbitrary input, f32 and f64.
//!
//! - `CountScale`: any counts; the rate is `count · rad_per_count` bit for bit; `saturated` ⇔ an axis at a
//!   rail (`i16::MIN` or `i16::MAX`); `rad_per_count` is the documented formula rounded once.
//! - `AxisRemap`: every remap is a signed permutation (its matrix has one ±1 per row and column, det +1,
//!   accepted by `from_matrix`); `rotate` is that permutation bit for bit on any vector (NaN included);
//!   `apply` keeps the saturation flag; `Alignment::from(remap)` applies the same.
//! - `Alignment::from_matrix` on arbitrary matrices and on perturbed rotations near the tolerance: no
//!   panic; an independent f64 evaluation of `RᵀR − I` and `det R − 1` (with a slack of its own rounding)
//!   decides every case that is not within rounding of `ROTATION_TOLERANCE`; `Ok` ⇒ within it. `apply`
//!   of an accepted matrix preserves the norm: `RᵀR = I + E`, `|Eᵢⱼ| ≤ tol` gives `‖E‖₂ ≤ 3 tol` and
//!   `|‖Rv‖ − ‖v‖| ≤ 1.5 tol ‖v‖`; the rows' rounding adds `√3 γ₃ √(1 + tol) ‖v‖ ≤ 2.7 ε ‖v‖` and
//!   underflow `6·TINY`.
//! - `FixedBias`: refused iff non-finite; `apply` subtracts bit for bit; `correct_bias(δ)` (δ with NaN,
//!   infinities and huge values among them): `Ok` iff the sum is finite, the offset then moved by δ bit
//!   for bit; `Err` (`NonFiniteRate`) ⇒ unchanged.
//! - `BiasEstimator`: any window (0, 1 to 7 samples, 8 to 64, any `u32`; in samples or in seconds),
//!   period and gate, optional drift, rest drift, noise model, acceleration gate, temperature model and
//!   initial bias ± sigma: each refused exactly as documented, with its error (`InvalidEstimator`;
//!   `NonFiniteRate` for a non-finite initial bias); `new(seconds)` is `from_samples` of the rounded
//!   count. Then arbitrary samples (levels held, with noise within the gate or stepped, and fresh values
//!   with NaN, infinities, huge and saturated ones), accelerations, temperatures and `correct_bias`
//!   calls. `Err` ⇒ the estimator unchanged bit for bit, `NonFiniteRate` for a non-finite rate,
//!   `NonFiniteAux` for a non-finite acceleration or temperature or one whose `bias_at` overflows; `Ok` ⇒
//!   the output is the sample minus `bias_at(temperature)` (`bias()` without one) from before, bit for
//!   bit, the saturation flag kept; `correct` then `learn` gives the same output and state as
//!   `update_with`. The still samples counted here from the documented gate rule (within `gate` of the
//!   estimate, not saturated, the acceleration within the acceleration gate of the window's first):
//!   `bias()`, `is_learned()` and `last_window()` change only on the sample that completes `window` still
//!   samples in a row, never on a saturated one. `bias()` always finite; `variance()` `T::MAX` on every
//!   axis before anything is learned, finite and non-negative after, growing between windows (a drift
//!   whose square overflows is refused; the growth saturates at `T::MAX`); `is_learned()` never reverts;
//!   `last_window()` finite; a slope only with the temperature model, finite. `correct_bias(δ)`: `Err`
//!   (`NonFiniteRate`) ⇒ unchanged; `Ok` ⇒ `bias()` moved by δ bit for bit, the variance and last window
//!   kept. For windows under 8 samples without the temperature model (one block, no flatness or step
//!   test), an independent mirror of the documented estimator (a per-axis scalar Kalman filter measuring
//!   each window's mean with the variance `(gate·2⁻¹³)²`, saturated at `T::MAX`, or the noise model's
//!   `N²/τ`; growth by `drift` unseen and `rest_drift` over a window that agrees; a disagreeing window
//!   confirmed by the next or dropped; a window that overflows undone) gives `bias()`, `variance()`,
//!   `is_learned()`, `last_window()` and every `correct_bias` verdict bit for bit. A `MotionBias` (any
//!   period) fed the outputs with the accelerations and arbitrary `dt`: refused input (typed) leaves it
//!   unchanged, its estimate stays within ±2 °/s, and `at_rest` zeroes it.
//! - `FixedPeriod`: construction errors as documented; with refusals given back by `carry_over`, the
//!   accepted `dt`s sum to `k·period` (k samples) within ½ ulp of the last `dt`, plus one ulp of each `dt`
//!   handed out with a carried interval, plus `4ε²·period` per sample (rounding of the carry and of `lo`)
//!   and two subnormal spacings per sample.
//! - `TickClock`: construction errors as documented; `advance` is `dt` without the commit; an independent
//!   model of the counter (mask, wrapped difference, duplicates and backwards steps refused, gaps counted as
//!   jumps beyond 1.5× the previous interval, restart) agrees on every call; the accepted `dt`s sum to
//!   `ticks · (1/frequency)` within ½ ulp of the longest `dt` since the last restart plus `4ε²·dt` per
//!   sample (and a subnormal spacing per tick, where the period's low part underflows); when the interval
//!   fits in `T`, `dt` is finite, positive and within an eighth of its interval (`ticks · (1/frequency)`)
//!   plus `4ε` of it, `ε·ulp` of the longest `dt` (the carry is split off to half an ulp of itself) and the
//!   subnormal terms: a long gap's carried remainder is spread, never given whole to a short interval.

use super::{assert_same_text, norm64, vec_bits, Bytes, Fz, RATE, SPECIAL, UNIT};
use quatprop::frontend::{
    Alignment, Aux, AxisRemap, BiasEstimator, CountScale, FixedBias, FixedPeriod, MotionBias,
    TickClock, ROTATION_TOLERANCE,
};
use quatprop::noise::GyroNoise;
use quatprop::{Error, GyroSample, Quat, Real, Vec3};

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    crate::by_check_and_precision(data, 7, check::<f32>, check::<f64>)
}

fn check<T: Fz>(b: &mut Bytes<'_>, which: usize) {
    match which {
        0 => count_scale::<T>(b),
        1 => axis_remap::<T>(b),
        2 => alignment::<T>(b),
        3 => fixed_bias::<T>(b),
        4 => bias_estimator::<T>(b),
        5 => fixed_period::<T>(b),
        _ => tick_clock::<T>(b),
    }
}

/// An f64 from the bytes: raw bits, a special value, or one of `plausible`.
pub(crate) fn f64_from(b: &mut Bytes<'_>, plausible: [f64; 4]) -> f64 {
    match b.below(8) {
        0 => f64::from_bits(b.u64()),
        1 => SPECIAL[b.below(16)],
        2 => plausible[b.below(4)] * (1.0 + f64::from(b.u16()) / 65536.0),
        _ => plausible[b.below(4)],
    }
}

fn bits_or_nan<T: Fz>(a: T, b: T) -> bool {
    a.bits() == b.bits() || (a.to_f64().is_nan() && b.to_f64().is_nan())
}

fn count_scale<T: Fz>(b: &mut Bytes<'_>) {
    let by_full_scale = b.bool();
    let x = if by_full_scale {
        f64_from(b, [250.0, 500.0, 1000.0, 2000.0])
    } else {
        f64_from(b, [131.0, 65.5, 32.8, 16.4])
    };
    let (scale, want) = if by_full_scale {
        (
            CountScale::<T>::full_scale_dps(x),
            T::from_f64(x.to_radians() / 32768.0),
        )
    } else {
        (
            CountScale::<T>::sensitivity(x),
            T::from_f64(1f64.to_radians() / x),
        )
    };
    // Refused (`InvalidScale`) exactly when the stated figure or the scale rounded to T is not positive and
    // finite; otherwise the scale is the documented formula rounded once.
    let valid = x > 0.0 && x.is_finite() && want > T::ZERO && want.is_finite();
    let scale = match scale {
        Ok(s) => {
            assert!(valid, "scale {x:e} accepted as {want:?}");
            s
        }
        Err(e) => {
            assert_eq!(e, Error::InvalidScale);
            assert!(!valid, "scale {x:e} refused");
            return;
        }
    };
    let k = scale.rad_per_count();
    assert!(bits_or_nan(k, want), "rad_per_count {k:?} vs {want:?}");
    for _ in 0..16 {
        if b.is_empty() {
            break;
        }
        let mut counts = [0i16; 3];
        for c in &mut counts {
            *c = match b.below(8) {
                0 => i16::MAX,
                1 => i16::MIN,
                2 => i16::MAX - 1,
                3 => i16::MIN + 1,
                _ => b.u16() as i16,
            };
        }
        let s = scale.sample(counts);
        let rail = counts.iter().any(|&c| c == i16::MAX || c == i16::MIN);
        assert_eq!(s.saturated, rail, "{counts:?}");
        let want = counts.map(|c| T::of_i32(i32::from(c)) * k);
        for (got, want) in [s.rate.x, s.rate.y, s.rate.z].into_iter().zip(want) {
            assert!(bits_or_nan(got, want), "{counts:?}: {got:?} vs {want:?}");
        }
    }
}

fn axis_remap<T: Fz>(b: &mut Bytes<'_>) {
    let r = AxisRemap::ALL[b.below(24)];
    let m = r.matrix::<T>();
    let mf = m.map(|row| row.map(|e| e.to_f64()));
    for i in 0..3 {
        let row_nonzero = (0..3).filter(|&j| mf[i][j] != 0.0).count();
        let col_nonzero = (0..3).filter(|&j| mf[j][i] != 0.0).count();
        assert_eq!((row_nonzero, col_nonzero), (1, 1), "{r:?}");
        assert!(mf[i].iter().all(|e| *e == 0.0 || e.abs() == 1.0), "{r:?}");
    }
    assert_eq!(det(&mf), 1.0, "{r:?}");
    assert!(Alignment::from_matrix(m).is_ok(), "{r:?}");
    for _ in 0..8 {
        if b.is_empty() {
            break;
        }
        let v = b.vec::<T>(RATE);
        let s = GyroSample {
            rate: v,
            saturated: b.bool(),
        };
        let out = r.apply(s);
        assert_eq!(out.saturated, s.saturated);
        let comps = [v.x, v.y, v.z];
        let got = [out.rate.x, out.rate.y, out.rate.z];
        for i in 0..3 {
            let j = (0..3).find(|&j| mf[i][j] != 0.0).unwrap_or(0);
            let want = if mf[i][j] < 0.0 { -comps[j] } else { comps[j] };
            assert_eq!(got[i].bits(), want.bits(), "{r:?} row {i}");
        }
        assert_eq!(vec_bits(r.rotate(v)), vec_bits(out.rate));
        let via = Alignment::<T>::from(r).apply(s);
        assert_eq!(vec_bits(via.rate), vec_bits(out.rate));
        assert_eq!(via.saturated, s.saturated);
    }
}

fn det(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// `(deviation, slack)`: the largest of `|(RᵀR − I)ᵢⱼ|` and `|det R − 1|` evaluated here in f64, with
/// the bound of this evaluation's own rounding error at that entry. NaN/∞ entries give an infinite
/// deviation.
fn rotation_deviation(m: &[[f64; 3]; 3]) -> Vec<(f64, f64)> {
    let e = f64::EPSILON;
    let mut out = Vec::with_capacity(10);
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|k| m[k][i] * m[k][j]).sum();
            let mag: f64 = (0..3).map(|k| (m[k][i] * m[k][j]).abs()).sum();
            let target = if i == j { 1.0 } else { 0.0 };
            out.push(((dot - target).abs(), 4.0 * e * (mag + 1.0)));
        }
    }
    let d = det(m);
    let mag = m[0][0].abs() * (m[1][1] * m[2][2]).abs().max((m[1][2] * m[2][1]).abs()) * 2.0
        + m[0][1].abs() * (m[1][0] * m[2][2]).abs().max((m[1][2] * m[2][0]).abs()) * 2.0
        + m[0][2].abs() * (m[1][0] * m[2][1]).abs().max((m[1][1] * m[2][0]).abs()) * 2.0;
    out.push(((d - 1.0).abs(), 8.0 * e * (mag + 1.0)));
    out
}

fn alignment<T: Fz>(b: &mut Bytes<'_>) {
    let m: [[T; 3]; 3] = if b.below(4) == 0 {
        let mut m = [[T::ZERO; 3]; 3];
        for e in m.iter_mut().flatten() {
            *e = b.real(UNIT);
        }
        m
    } else {
        // A rotation, perturbed near the tolerance, maybe mirrored.
        let q = b.quat::<f64>().normalized().unwrap_or(Quat::IDENTITY);
        let mut r = q.to_rotation_matrix();
        let size = 10f64.powi(-(b.below(10) as i32)) * ROTATION_TOLERANCE * 100.0;
        for e in r.iter_mut().flatten() {
            *e += size * f64::from(b.u8() as i8) / 128.0;
        }
        if b.u8() < 16 {
            r[b.below(3)] = r[0].map(|e| -e);
        }
        r.map(|row| row.map(T::from_f64))
    };
    let mf = m.map(|row| row.map(|e| e.to_f64()));
    let tol = ROTATION_TOLERANCE;
    let r = Alignment::from_matrix(m);
    let finite = mf.iter().flatten().all(|e| e.is_finite());
    let dev = rotation_deviation(&mf);
    let clearly_in = finite && dev.iter().all(|&(d, s)| d + s <= tol);
    let clearly_out = !finite || dev.iter().any(|&(d, s)| !(d - s <= tol));
    match r {
        Ok(a) => {
            assert!(!clearly_out, "accepted {mf:?}: {dev:?}");
            assert_eq!(a, Alignment::Matrix(m));
            // The norm is kept (module doc).
            let tol_true = tol + dev.iter().fold(0.0_f64, |a, &(_, s)| a.max(s));
            for _ in 0..4 {
                let v = b.vec::<T>(RATE);
                let nv = norm64(v);
                if !(nv <= T::BIG / 4.0) {
                    continue;
                }
                let out = a.apply(GyroSample::new(v)).rate;
                let no = norm64(out);
                let bound = (1.5 * tol_true * 1.001 + 2.7 * T::EPS + 4.0 * f64::EPSILON) * nv
                    + 6.0 * T::TINY;
                assert!(
                    (no - nv).abs() <= bound,
                    "|Rv| = {no:e}, |v| = {nv:e}, bound {bound:e}, R = {mf:?}"
                );
            }
        }
        Err(e) => {
            assert_eq!(e, Error::NotARotation);
            assert!(!clearly_in, "refused {mf:?}: {dev:?}");
        }
    }
}

fn fixed_bias<T: Fz>(b: &mut Bytes<'_>) {
    let bias = b.vec::<T>(RATE);
    match FixedBias::new(bias) {
        Ok(f) => {
            assert!(bias.is_finite());
            for _ in 0..8 {
                let s = GyroSample {
                    rate: b.vec::<T>(RATE),
                    saturated: b.bool(),
                };
                let out = f.apply(s);
                let want = Vec3::new(s.rate.x - bias.x, s.rate.y - bias.y, s.rate.z - bias.z);
                assert_eq!(vec_bits(out.rate), vec_bits(want));
                assert_eq!(out.saturated, s.saturated);
            }
            let delta = b.vec::<T>(RATE);
            let sum = Vec3::new(bias.x + delta.x, bias.y + delta.y, bias.z + delta.z);
            let mut moved = f;
            match moved.correct_bias(delta) {
                Ok(()) => {
                    assert!(sum.is_finite());
                    assert_eq!(vec_bits(moved.bias()), vec_bits(sum));
                }
                Err(e) => {
                    assert_eq!(e, Error::NonFiniteRate);
                    assert!(!sum.is_finite());
                    assert_eq!(vec_bits(moved.bias()), vec_bits(bias));
                }
            }
        }
        Err(e) => {
            assert_eq!(e, Error::NonFiniteRate);
            assert!(!bias.is_finite());
        }
    }
}

/// `[x, y, z]`: the bias checks compute per axis, independently of `Vec3`'s operators.
fn arr<T: Real>(v: Vec3<T>) -> [T; 3] {
    [v.x, v.y, v.z]
}

fn vec3<T: Real>(a: [T; 3]) -> Vec3<T> {
    Vec3::new(a[0], a[1], a[2])
}

fn finite3<T: Real>(a: [T; 3]) -> bool {
    a.iter().all(|x| x.is_finite())
}

/// Every axis within `gate` (a NaN is not).
fn within<T: Real>(a: [T; 3], gate: T) -> bool {
    a.iter().all(|x| x.abs() <= gate)
}

/// Two vectors equal bit for bit (a NaN equals a NaN).
fn same_vec<T: Fz>(a: Vec3<T>, b: Vec3<T>) -> bool {
    bits_or_nan(a.x, b.x) && bits_or_nan(a.y, b.y) && bits_or_nan(a.z, b.z)
}

/// A count as the library converts it (saturating at 2³¹ − 1).
fn count<T: Fz>(n: u32) -> T {
    T::of_i32(i32::try_from(n).unwrap_or(i32::MAX))
}

/// What a sample did to the current window.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Verdict {
    /// Not still: the window is aborted.
    Aborted,
    /// Still: counted in the window.
    Counted,
    /// Still, and the window's last sample: the only sample that may change the estimate.
    Closed,
}

/// The documented stillness rule, counted here: a sample is still if, minus the bias subtracted from it,
/// it is within `gate` on every axis and not saturated, and (with an acceleration gate) its acceleration,
/// if given, is within that gate of the window's first on every axis. A sample that is not still aborts
/// the window; the `window`-th still sample in a row closes it.

#[derive(Clone, Copy, Debug)]
struct Stillness<T> {
    window: u32,
    gate: T,
    accel_gate: Option<T>,
    count: u32,
    /// The window's first acceleration.
    reference: Option<[T; 3]>,
}

impl<T: Fz> Stillness<T> {
    fn new(window: u32, gate: T, accel_gate: Option<T>) -> Self {
        Self {
            window,
            gate,
            accel_gate,
            count: 0,
            reference: None,
        }
    }

    /// The window restarts (`with_initial`, `correct_bias`).
    fn restart(&mut self) {
        *self = Self::new(self.window, self.gate, self.accel_gate);
    }

    /// One accepted sample: `d` the rate the estimator returned (the sample minus the bias it subtracted).
    fn sample(&mut self, d: [T; 3], saturated: bool, accel: Option<[T; 3]>) -> Verdict {
        if saturated || !within(d, self.gate) {
            self.count = 0;
            self.reference = None;
            return Verdict::Aborted;
        }
        if let (Some(a), Some(r), Some(g)) = (accel, self.reference, self.accel_gate) {
            if !within([a[0] - r[0], a[1] - r[1], a[2] - r[2]], g) {
                self.count = 0;
                self.reference = None;
                return Verdict::Aborted;
            }
        }
        if self.reference.is_none() {
            self.reference = accel;
        }
        self.count += 1;
        if self.count < self.window {
            return Verdict::Counted;
        }
        self.count = 0;
        self.reference = None;
        Verdict::Closed
    }
}

/// `d² > 25 v` on some axis.
fn disagrees<T: Fz>(d: [T; 3], v: [T; 3]) -> bool {
    let k2 = T::of_i32(25);
    (0..3).any(|i| d[i] * d[i] > k2 * v[i])
}

/// `p / (p + r)` per axis (½ if that sum is not positive).
fn gain<T: Fz>(p: [T; 3], r: [T; 3]) -> [T; 3] {
    [0, 1, 2].map(|i| {
        let s = p[i] + r[i];
        if s > T::ZERO {
            p[i] / s
        } else {
            T::HALF
        }
    })
}

/// One still window's measurement of the bias: its mean, the variance of that mean, its mean temperature.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Measured<T> {
    bias: [T; 3],
    variance: [T; 3],
    temperature: Option<T>,
}

impl<T: Fz> Measured<T> {
    fn is_finite(&self) -> bool {
        finite3(self.bias)
            && finite3(self.variance)
            && self.temperature.is_none_or(|t| t.is_finite())
    }
}

/// What the window before showed, for a change of level (the mirror's windows are never tested for
/// steps: a level disagreeing with the estimate waits for the next still window to confirm it).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Link<T> {
    Moving,
    AtEstimate,
    /// A still window that disagreed.
    Candidate(Measured<T>),
}

/// `q²` times `n` periods.
fn walk<T: Fz>(q: T, period: T, n: u32) -> T {
    let g = q * q * period * count::<T>(n);
    if g <= T::MAX {
        g
    } else {
        T::MAX
    }
}

/// The estimator for a window of fewer than 8 samples without the temperature model, written out from its
/// documentation: one block per window, no flatness or step test, so every window that passes the gate is
/// still; its mean is a measurement of the bias with the variance of the noise model's block (`N²/τ`) or
/// else the floor `(gate·2⁻¹³)²` (saturated at `T::MAX`); a scalar Kalman filter per axis on a bias that
/// walks with density `drift` while it is not seen (motion, windows that disagree) and `rest_drift` over
/// a still window that agrees (the variance grows by `q²·period` per sample); a still window that
/// disagrees by more than five standard deviations waits for the next still window to confirm it (their
/// weighted mean adopted) or is dropped. A window whose mean (or temperatures) overflow teaches nothing,
/// and a window that would leave a number infinite is undone.
#[derive(Clone, Copy, Debug)]
struct Mirror<T> {
    window: u32,
    drift: T,
    rest_drift: T,
    period: T,
    measurement: T,
    bias: [T; 3],
    variance: [T; 3],
    since: u32,
    /// Windows taken (an initial bias counts one), and the last window taken.
    learned: u32,
    taken: Option<Measured<T>>,
    /// The mean temperature where the estimate holds: kept without the temperature model too (an
    /// overflowing one undoes the window).
    bias_temperature: Option<T>,
    link: Link<T>,
    sum: [T; 3],
    count: u32,
    temperature_sum: T,
    temperatures: u32,
}

impl<T: Fz> Mirror<T> {
    fn new(window: u32, drift: T, rest_drift: T, period: T, measurement: T) -> Self {
        Self {
            window,
            drift,
            rest_drift,
            period,
            measurement,
            bias: [T::ZERO; 3],
            variance: [T::ZERO; 3],
            since: 0,
            learned: 0,
            taken: None,
            bias_temperature: None,
            link: Link::Moving,
            sum: [T::ZERO; 3],
            count: 0,
            temperature_sum: T::ZERO,
            temperatures: 0,
        }
    }

    /// `variance()`: the last update's, grown by `drift` since; `T::MAX` before the first window.
    fn variance(&self) -> Vec3<T> {
        if self.learned == 0 {
            return Vec3::new(T::MAX, T::MAX, T::MAX);
        }
        let g = walk(self.drift, self.period, self.since);
        vec3(self.variance.map(|v| v + g))
    }

    fn last_window(&self) -> Option<(u32, Vec3<T>, Vec3<T>)> {
        self.taken
            .map(|m| (self.learned, vec3(m.bias), vec3(m.variance)))
    }

    fn restart(&mut self) {
        self.sum = [T::ZERO; 3];
        self.count = 0;
        self.temperature_sum = T::ZERO;
        self.temperatures = 0;
    }

    fn is_finite(&self) -> bool {
        let link = match self.link {
            Link::Candidate(c) => c.is_finite(),
            _ => true,
        };
        finite3(self.bias)
            && finite3(self.variance)
            && self.bias_temperature.is_none_or(|t| t.is_finite())
            && self.taken.is_none_or(|m| m.is_finite())
            && link
    }

    fn initial(&mut self, bias: [T; 3], sigma: T) {
        self.bias = bias;
        self.variance = [sigma * sigma; 3];
        self.since = 0;
        self.learned = 1;
        self.bias_temperature = None;
        self.link = Link::AtEstimate;
        self.restart();
    }

    /// `correct_bias`: `false` if refused.
    fn correct_bias(&mut self, delta: [T; 3]) -> bool {
        if !finite3(delta) {
            return false;
        }
        let mut next = *self;
        next.bias = [0, 1, 2].map(|i| self.bias[i] + delta[i]);
        if let Link::Candidate(c) = &mut next.link {
            c.bias = [0, 1, 2].map(|i| c.bias[i] + delta[i]);
        }
        next.restart();
        if !next.is_finite() {
            return false;
        }
        *self = next;
        true
    }

    fn sample(&mut self, d: [T; 3], still: bool, temperature: Option<T>) {
        self.since = self.since.saturating_add(1);
        if !still {
            self.restart();
            self.link = Link::Moving;
            return;
        }
        for i in 0..3 {
            self.sum[i] += d[i];
        }
        if let Some(t) = temperature {
            self.temperature_sum += t;
            self.temperatures += 1;
        }
        self.count += 1;
        if self.count >= self.window {
            self.close();
            self.restart();
        }
    }

    fn grow(&mut self, g: T) {
        self.variance = self.variance.map(|v| v + g);
    }

    fn close(&mut self) {
        let before = *self;
        let elapsed = self.since;
        self.since = 0;
        // Not seen before the window: `drift`; over the window: `rest_drift` if it agrees, else `drift`.
        let in_window = elapsed.min(self.window);
        let unseen = walk(self.drift, self.period, elapsed.saturating_sub(self.window));
        let seen = walk(self.rest_drift, self.period, in_window);
        let window_unseen = walk(self.drift, self.period, in_window);
        self.grow(unseen);
        let temperature = (self.temperatures > 0)
            .then(|| self.temperature_sum * (T::ONE / count::<T>(self.temperatures)));
        let inv = T::ONE / count::<T>(self.window);
        let m = Measured {
            bias: [0, 1, 2].map(|i| self.bias[i] + self.sum[i] * inv),
            variance: [self.measurement; 3],
            temperature,
        };
        let (mb, r) = (m.bias, m.variance);
        if !(finite3(mb) && temperature.is_none_or(|t| t.is_finite())) {
            self.grow(window_unseen);
            self.link = Link::Moving;
        } else if self.learned == 0 {
            self.bias = mb;
            self.variance = r;
            self.bias_temperature = temperature;
            self.taken = Some(m);
            self.learned += 1;
            self.link = Link::AtEstimate;
        } else {
            let innovation = [0, 1, 2].map(|i| mb[i] - self.bias[i]);
            let predicted = self.variance.map(|v| v + seen);
            let spread = [0, 1, 2].map(|i| predicted[i] + r[i]);
            if !disagrees(innovation, spread) {
                self.variance = predicted;
                let k = gain(self.variance, r);
                self.bias = [0, 1, 2].map(|i| self.bias[i] + k[i] * innovation[i]);
                self.variance = [0, 1, 2].map(|i| (T::ONE - k[i]) * self.variance[i]);
                self.taken = Some(m);
                self.learned = self.learned.saturating_add(1);
                self.link = Link::AtEstimate;
            } else {
                self.grow(window_unseen);
                self.link = match self.link {
                    Link::AtEstimate => Link::Candidate(m),
                    Link::Candidate(c) => {
                        let d = [0, 1, 2].map(|i| mb[i] - c.bias[i]);
                        let s = [0, 1, 2].map(|i| r[i] + c.variance[i]);
                        if disagrees(d, s) {
                            Link::Moving
                        } else {
                            let w = gain(c.variance, r);
                            self.bias = [0, 1, 2].map(|i| c.bias[i] + w[i] * (mb[i] - c.bias[i]));
                            self.variance = [0, 1, 2].map(|i| (T::ONE - w[i]) * c.variance[i]);
                            self.taken = Some(Measured {
                                bias: self.bias,
                                variance: self.variance,
                                temperature,
                            });
                            self.bias_temperature = match (c.temperature, temperature) {
                                (Some(a), Some(b)) => Some(a * T::HALF + b * T::HALF),
                                (a, b) => b.or(a),
                            };
                            self.learned = self.learned.saturating_add(1);
                            Link::AtEstimate
                        }
                    }
                    Link::Moving => Link::Moving,
                };
            }
        }
        if !self.is_finite() {
            *self = before;
            self.link = Link::Moving;
        }
    }
}

/// `BiasEstimator::from_samples`'s conditions: a window of 1 to 2³¹ − 1 samples, a period and a gate
/// finite and positive in `T`.
fn estimator_valid<T: Fz>(window: u32, period: f64, gate: T) -> bool {
    let p = T::from_f64(period);
    (1..=i32::MAX as u32).contains(&window)
        && p > T::ZERO
        && p.is_finite()
        && gate > T::ZERO
        && gate.is_finite()
}

/// A new estimator from the bytes (a window in samples or in seconds), its construction checked: the
/// estimator, its window in samples and its gate; `None` if refused.
fn estimator_config<T: Fz>(b: &mut Bytes<'_>) -> Option<(BiasEstimator<T>, u32, f64, T)> {
    let period = f64_from(b, [1e-3, 1.0 / 1600.0, 2.5e-3, 1e-2]);
    let gate: T = match b.below(4) {
        0 => b.real(UNIT),
        _ => T::from_f64([0.05, 0.01, 0.1, 1e-3][b.below(4)]),
    };
    let (r, window) = if b.below(4) == 0 {
        let seconds = f64_from(b, [4e-3, 8e-3, 1.6e-2, 6.4e-2]);
        let r = BiasEstimator::<T>::new(seconds, period, gate);
        // round(seconds / period) samples, if both are finite and positive and that is 1 to 2³¹ − 1;
        // otherwise refused (window 0 below).
        let positive = |x: f64| x > 0.0 && x.is_finite();
        let n = (seconds / period).round();
        let counted = positive(seconds) && positive(period) && n >= 1.0 && n <= f64::from(i32::MAX);
        let window = if counted { n as u32 } else { 0 };
        if counted {
            let by_count = BiasEstimator::from_samples(window, period, gate);
            assert_same_text(
                &r,
                &by_count,
                &"new(seconds) differs from from_samples(its samples)",
            );
        }
        (r, window)
    } else {
        let window = match b.below(8) {
            0 => b.u32(),
            1 => 0,
            2..=4 => 1 + b.below(7) as u32,
            _ => 8 + b.below(57) as u32,
        };
        (BiasEstimator::from_samples(window, period, gate), window)
    };
    let valid = estimator_valid(window, period, gate);
    match r {
        Ok(e) => {
            assert!(
                valid,
                "window {window}, period {period:e}, gate {gate:?} accepted"
            );
            assert!(!e.is_learned());
            assert_eq!(vec_bits(e.bias()), vec_bits(Vec3::<T>::ZERO));
            assert_eq!(
                vec_bits(e.variance()),
                vec_bits(Vec3::new(T::MAX, T::MAX, T::MAX))
            );
            assert_eq!(e.temperature_slope(), None);
            Some((e, window, period, gate))
        }
        Err(e) => {
            assert_eq!(e, Error::InvalidEstimator);
            assert!(
                !valid,
                "window {window}, period {period:e}, gate {gate:?} refused"
            );
            None
        }
    }
}

/// An option set on a copy: `Ok` ⇒ `valid`; `Err` ⇒ `want`, and `!valid`.
fn option<T: Fz>(
    est: &mut BiasEstimator<T>,
    r: Result<BiasEstimator<T>, Error>,
    valid: bool,
    want: Error,
    what: &str,
) -> bool {
    match r {
        Ok(e) => {
            assert!(valid, "{what} accepted");
            *est = e;
            true
        }
        Err(e) => {
            assert_eq!(e, want, "{what}");
            assert!(!valid, "{what} refused");
            false
        }
    }
}

/// A drift option (`with_drift` or `with_rest_drift`, named `what`) set on half the inputs to a value of
/// `scales`: valid when non-negative with a finite square. Returns the drift in force: the value set if it
/// was accepted, else `default`.
fn drift_option<T: Fz>(
    b: &mut Bytes<'_>,
    est: &mut BiasEstimator<T>,
    (set, what): (DriftSetter<T>, &str),
    default: f64,
    scales: [f64; 4],
) -> T {
    if b.bool() {
        let d: T = b.real(scales);
        let valid = d >= T::ZERO && (d * d).is_finite();
        let r = set(*est, d);
        if option(est, r, valid, Error::InvalidEstimator, what) {
            return d;
        }
    }
    T::from_f64(default)
}

/// `BiasEstimator::with_drift` or `BiasEstimator::with_rest_drift`.
type DriftSetter<T> = fn(BiasEstimator<T>, T) -> Result<BiasEstimator<T>, Error>;

fn bias_estimator<T: Fz>(b: &mut Bytes<'_>) {
    let Some((mut est, window, period, gate)) = estimator_config::<T>(b) else {
        return;
    };
    let period_t = T::from_f64(period);
    let positive = |x: T| x > T::ZERO && x.is_finite();
    let drift = drift_option(
        b,
        &mut est,
        (BiasEstimator::with_drift, "drift"),
        BiasEstimator::<T>::DEFAULT_DRIFT,
        [1e-5, 1e-3, 0.1, 1e3],
    );
    let rest_drift = drift_option(
        b,
        &mut est,
        (BiasEstimator::with_rest_drift, "rest drift"),
        BiasEstimator::<T>::DEFAULT_REST_DRIFT,
        [1e-6, 1e-4, 0.1, 1e3],
    );
    let mut measurement = {
        let s = gate * T::from_f64(1.0 / 8192.0);
        let f = s * s;
        if f.is_finite() {
            f
        } else {
            T::MAX
        }
    };
    if b.bool() {
        let arw: T = b.real([1e-5, 1e-4, 1e-3, 1e-2]);
        let walk: T = if b.bool() {
            b.real([1e-6, 1e-5, 1e-4, 1e3])
        } else {
            T::ZERO
        };
        match GyroNoise::new(arw, walk) {
            Ok(noise) => {
                // `arw²/τ_block`, τ_block the period times the samples per block (the bias walk is not
                // taken: the rest drift is given apart).
                let block = if window >= 8 { window / 8 } else { window };
                let tau = period_t * T::from_f64(f64::from(block));
                let v = arw * arw / tau;
                let r = est.with_noise(&noise);
                if option(&mut est, r, positive(v), Error::InvalidEstimator, "noise") {
                    measurement = v;
                }
            }
            Err(e) => {
                assert_eq!(e, Error::InvalidNoise);
                let ok = |x: T| x >= T::ZERO && x.is_finite();
                assert!(!(ok(arw) && ok(walk)));
            }
        }
    }
    let mut accel_gate = None;
    if b.bool() {
        let g: T = b.real(UNIT);
        let r = est.with_accel_gate(g);
        if option(
            &mut est,
            r,
            positive(g),
            Error::InvalidEstimator,
            "accel gate",
        ) {
            accel_gate = Some(g);
        }
    }
    let mut thermal = false;
    if b.bool() {
        let span: T = b.real(UNIT);
        let r = est.with_temperature_model(span);
        thermal = option(&mut est, r, positive(span), Error::InvalidEstimator, "span");
    }
    let mut mirror = (window < 8 && !thermal)
        .then(|| Mirror::new(window, drift, rest_drift, period_t, measurement));
    if b.u8() < 64 {
        let initial = b.vec::<T>([1e-3, 1e-2, 0.05, 1.0]);
        let sigma: T = b.real([1e-3, 1e-2, 1e-4, 1.0]);
        let r = est.with_initial(initial, sigma);
        let want = if !initial.is_finite() {
            Some(Error::NonFiniteRate)
        } else if !(sigma > T::ZERO && (sigma * sigma).is_finite()) {
            Some(Error::InvalidEstimator)
        } else {
            None
        };
        assert_eq!(r.err(), want, "initial {initial:?} ± {sigma:?}");
        if let Ok(e) = r {
            est = e;
            assert!(est.is_learned());
            assert_eq!(vec_bits(est.bias()), vec_bits(initial));
            let v = sigma * sigma;
            assert_eq!(vec_bits(est.variance()), vec_bits(Vec3::new(v, v, v)));
            if let Some(m) = mirror.as_mut() {
                m.initial(arr(initial), sigma);
            }
        }
    }
    let mut motion = if b.bool() {
        let period = f64_from(b, [1e-3, 1e-2, 2.5e-4, 3.5e-3]);
        match MotionBias::<T>::new(period) {
            Ok(m) => {
                assert!(period > 0.0 && period.is_finite());
                Some(m)
            }
            Err(Error::InvalidEstimator) => {
                // Only a period whose bias growth per sample, 10·10·period/100, overflows T.
                let growth = (0.1 * 100.0_f64) * (0.1 * 100.0) * period / 100.0;
                assert!(period > 0.0 && !(growth.is_finite() && T::from_f64(growth).is_finite()));
                None
            }
            Err(e) => {
                assert!(matches!(e, Error::NonFiniteStep | Error::NonPositiveStep));
                assert!(!(period > 0.0 && period.is_finite()));
                None
            }
        }
    } else {
        None
    };
    let mut still = Stillness::new(window, gate, accel_gate);
    // FUZZ_TRACE=1 prints the configuration and every call (to read a crash input).
    let trace = super::trace();
    if trace {
        eprintln!(
            "{} window {window}, period {period:e}, gate {gate:?}, drift {drift:?}, rest drift {rest_drift:?}, accel gate {accel_gate:?}, thermal {thermal}, mirror {}: {est:?}",
            T::NAME,
            mirror.is_some()
        );
    }
    // What the samples are made of: a level (held, with noise of up to gate/64, or stepped by up to
    // gate/2), an acceleration level and a temperature level; or fresh values from the bytes.
    let mut level = [T::ZERO; 3];
    let mut accel_level = [T::ZERO, T::ZERO, T::from_f64(9.81)];
    let mut temperature_level = T::from_f64(25.0);
    let fraction = |b: &mut Bytes<'_>| T::from_f64(f64::from(b.u8() as i8) / 128.0);
    for _ in 0..1024 {
        if b.is_empty() {
            break;
        }
        let op = b.u8();
        if op == 0xC0 {
            let delta = b.vec::<T>([1e-4, 1e-3, 1e-2, 1.0]);
            if trace {
                eprintln!("correct_bias({delta:?}) on {est:?}");
            }
            correct_bias(&mut est, delta, &mut still, mirror.as_mut());
            continue;
        }
        let rate = match op & 3 {
            0 => {
                level = arr(b.vec::<T>([1e-3, 1e-2, 0.05, 1.0]));
                level
            }
            1 => level,
            2 => {
                let n = gate * T::from_f64(1.0 / 64.0);
                [0, 1, 2].map(|i| level[i] + fraction(b) * n)
            }
            _ => {
                let n = gate * T::HALF;
                level = [0, 1, 2].map(|i| level[i] + fraction(b) * n);
                level
            }
        };
        let accel = match (op >> 2) & 3 {
            0 => None,
            1 => Some(accel_level),
            2 => {
                let n = T::from_f64(0.05);
                Some([0, 1, 2].map(|i| accel_level[i] + fraction(b) * n))
            }
            _ => {
                accel_level = arr(b.vec::<T>([0.1, 1.0, 9.81, 100.0]));
                Some(accel_level)
            }
        };
        let temperature = match (op >> 4) & 3 {
            0 => None,
            1 => Some(temperature_level),
            2 => {
                temperature_level += fraction(b) * T::HALF;
                Some(temperature_level)
            }
            _ => {
                temperature_level = T::from_f64(25.0) + b.real::<T>([0.1, 1.0, 10.0, 100.0]);
                Some(temperature_level)
            }
        };
        let s = GyroSample {
            rate: vec3(rate),
            saturated: op >> 6 == 3,
        };
        let aux = Aux {
            accel: accel.map(vec3),
            temperature,
        };
        let before = est;
        let r = if aux == Aux::NONE {
            est.update(s)
        } else {
            est.update_with(s, aux)
        };
        // update_with is correct, then learn: the same state and output, split as the C API calls them.
        let mut split = before;
        let c = split.correct(s, aux);
        if c != r {
            assert_same_text(&c, &r, &"correct differs from update_with");
        }
        if let Ok(out) = c {
            split.learn(out, aux);
        }
        if split != est {
            assert_same_text(&split, &est, &"correct + learn differ from update_with");
        }
        if !s.rate.is_finite() {
            assert_eq!(r, Err(Error::NonFiniteRate));
            if est != before {
                assert_same_text(&est, &before, &"refused sample changed the estimator");
            }
            continue;
        }
        let aux_finite = accel.is_none_or(finite3) && temperature.is_none_or(|t| t.is_finite());
        if !thermal {
            if let Some(t) = temperature {
                // No line: the estimate itself at any temperature.
                assert_eq!(vec_bits(before.bias_at(t)), vec_bits(before.bias()));
            }
        }
        let used = temperature.map_or(before.bias(), |t| before.bias_at(t));
        if !aux_finite || !used.is_finite() {
            assert_eq!(r, Err(Error::NonFiniteAux));
            if est != before {
                assert_same_text(&est, &before, &"refused aux changed the estimator");
            }
            continue;
        }
        let out = r.expect("a finite sample is taken");
        let want = [0, 1, 2].map(|i| arr(s.rate)[i] - arr(used)[i]);
        assert_eq!(
            vec_bits(out.rate),
            vec_bits(vec3(want)),
            "output: sample − bias before"
        );
        assert_eq!(out.saturated, s.saturated);
        let verdict = still.sample(want, s.saturated, accel);
        let changed = vec_bits(est.bias()) != vec_bits(before.bias());
        if s.saturated {
            assert!(!changed, "learned from a saturated sample");
        }
        if verdict != Verdict::Closed {
            assert!(
                !changed,
                "the estimate changed within a window ({verdict:?}, {still:?})"
            );
            assert_eq!(
                est.is_learned(),
                before.is_learned(),
                "learned within a window"
            );
            assert_same_text(
                &est.last_window(),
                &before.last_window(),
                &"a window taken within a window",
            );
            if est.is_learned() {
                let (v, w) = (arr(est.variance()), arr(before.variance()));
                assert!(
                    (0..3).all(|i| v[i] >= w[i]),
                    "variance {w:?} -> {v:?} within a window"
                );
            }
        }
        if trace {
            eprintln!(
                "{s:?} {aux:?} -> {:?}: {verdict:?}, bias {:?}, variance {:?}",
                out.rate,
                est.bias(),
                est.variance()
            );
        }
        if let Some(m) = mirror.as_mut() {
            m.sample(want, verdict != Verdict::Aborted, temperature);
        }
        invariants(&est, &before, mirror.as_ref(), thermal);
        if let (Some(m), Some(a)) = (motion.as_mut(), accel) {
            let dt: T = b.real(UNIT);
            following(m, out.rate, vec3(a), dt, changed);
        }
    }
}

/// `correct_bias(delta)`: refused (typed) ⇒ unchanged; accepted ⇒ the estimate moved by `delta` bit for
/// bit, its variance kept, the window restarted; as the mirror says.
fn correct_bias<T: Fz>(
    est: &mut BiasEstimator<T>,
    delta: Vec3<T>,
    still: &mut Stillness<T>,
    mirror: Option<&mut Mirror<T>>,
) {
    let before = *est;
    let r = est.correct_bias(delta);
    let predicted = mirror.map(|m| m.correct_bias(arr(delta)));
    match r {
        Ok(()) => {
            assert!(delta.is_finite());
            let want = [0, 1, 2].map(|i| arr(before.bias())[i] + arr(delta)[i]);
            assert_eq!(
                vec_bits(est.bias()),
                vec_bits(vec3(want)),
                "bias moved by {delta:?}"
            );
            assert!(finite3(want));
            assert!(same_vec(est.variance(), before.variance()));
            assert_eq!(est.is_learned(), before.is_learned());
            assert_same_text(&est.last_window(), &before.last_window(), &"last window");
            assert_ne!(predicted, Some(false), "correct_bias accepted");
            still.restart();
        }
        Err(e) => {
            assert_eq!(e, Error::NonFiniteRate);
            if *est != before {
                assert_same_text(est, &before, &"refused correction changed the estimator");
            }
            // Refused for a non-finite delta or moved estimate, or a waiting level or a sum of the bias(T)
            // line (`weight·δ`) that overflows: the mirror (no line) tells exactly.
            assert_ne!(predicted, Some(true), "correct_bias refused");
        }
    }
}

/// What holds after every sample: the estimate finite; the variance `T::MAX` before anything is learned,
/// finite and non-negative after; learned stays learned; a slope only
/// with the temperature model, and finite; and the mirror's estimate and variance bit for bit.
fn invariants<T: Fz>(
    est: &BiasEstimator<T>,
    before: &BiasEstimator<T>,
    mirror: Option<&Mirror<T>>,
    thermal: bool,
) {
    assert!(est.bias().is_finite(), "{est:?}");
    let v = est.variance();
    if est.is_learned() {
        assert!(
            arr(v).iter().all(|&x| x >= T::ZERO && x.is_finite()),
            "variance {v:?}"
        );
    } else {
        assert_eq!(vec_bits(v), vec_bits(Vec3::new(T::MAX, T::MAX, T::MAX)));
    }
    assert!(
        est.is_learned() || !before.is_learned(),
        "forgot what it learned"
    );
    // The last window taken: a finite mean with a finite, non-negative variance, counted from 1 (an
    // initial bias counts one).
    if let Some((n, b, v)) = est.last_window() {
        assert!(est.is_learned() && n >= 1, "{n}");
        assert!(
            b.is_finite() && arr(v).iter().all(|&x| x >= T::ZERO && x.is_finite()),
            "{b:?} {v:?}"
        );
    }
    if let Some(slope) = est.temperature_slope() {
        assert!(thermal && slope.is_finite(), "slope {slope:?}");
    }
    if let Some(m) = mirror {
        assert_eq!(vec_bits(est.bias()), vec_bits(vec3(m.bias)), "{m:?}");
        assert!(same_vec(v, m.variance()), "variance {v:?}, {m:?}, {est:?}");
        assert_eq!(est.is_learned(), m.learned > 0, "{m:?}");
        assert_same_text(&est.last_window(), &m.last_window(), &"last window");
    }
}

/// A `MotionBias` fed the estimator's output with the acceleration over an arbitrary `dt`: refused input
/// (typed) leaves it unchanged; otherwise its estimate stays finite and within its ±2 °/s clip; `at_rest`
/// (called when the rest estimate changed) zeroes it.
fn following<T: Fz>(m: &mut MotionBias<T>, rate: Vec3<T>, accel: Vec3<T>, dt: T, rest: bool) {
    let kept = *m;
    match m.update(rate, accel, dt) {
        Ok(()) => {
            let c = T::from_f64(2.0_f64.to_radians());
            let r = m.bias();
            assert!(r.x.abs() <= c && r.y.abs() <= c && r.z.abs() <= c, "{m:?}");
        }
        Err(e) => {
            assert!(matches!(
                e,
                Error::NonFiniteRate
                    | Error::NonFiniteAux
                    | Error::NonFiniteStep
                    | Error::NonPositiveStep
                    | Error::NonFiniteResult
            ));
            assert_same_text(m, &kept, &"refused input changed the motion bias");
        }
    }
    if rest {
        m.at_rest();
        assert_eq!(vec_bits(m.bias()), vec_bits(Vec3::<T>::ZERO));
    }
}

/// The error `FixedPeriod::new` / `TickClock::new` must give for a period (s), if any.
fn period_error<T: Fz>(period: f64) -> Option<Error> {
    if !period.is_finite() {
        Some(Error::NonFiniteStep)
    } else if !(period > 0.0) {
        Some(Error::NonPositiveStep)
    } else {
        let hi = T::from_f64(period);
        if hi > T::ZERO && hi.is_finite() {
            None
        } else {
            Some(Error::NonPositiveStep)
        }
    }
}

const PERIODS: [f64; 4] = [1e-3, 1.0 / 1600.0, 1.0 / 3e3, 2.5e-4];

/// A fixed period from the bytes, its construction checked; `None` if refused.
pub fn period_config<T: Fz>(b: &mut Bytes<'_>) -> Option<(FixedPeriod<T>, f64)> {
    let period = f64_from(b, PERIODS);
    let r = FixedPeriod::<T>::new(period);
    assert_eq!(r.err(), period_error::<T>(period), "period {period:e}");
    let p = r.ok()?;
    assert_eq!(p.period().bits(), T::from_f64(period).bits());
    Some((p, period))
}

/// A clock from the bytes (frequency, counter width), its construction checked; `None` if refused.
pub fn clock_config<T: Fz>(b: &mut Bytes<'_>) -> Option<(TickClock<T>, f64, u32)> {
    let frequency = f64_from(b, [1e6, 32e3, 1e3, 19.2e6]);
    let bits = match b.below(4) {
        0 => 16,
        1 => 32,
        2 => b.below(34) as u32,
        _ => 1 + b.below(32) as u32,
    };
    let r = TickClock::<T>::new(frequency, bits);
    let want = if !(1..=32).contains(&bits) {
        Some(Error::InvalidClock)
    } else if !frequency.is_finite() {
        Some(Error::NonFiniteStep)
    } else if !(frequency > 0.0) {
        Some(Error::NonPositiveStep)
    } else {
        period_error::<T>(1.0 / frequency)
    };
    // A tick so long that the exact product's split (factor 2^27 + 1) overflows T may be refused as not
    // finite (the fix of `tick_clock_gives_a_finite_dt_for_a_huge_period`) or accepted (before it).
    let split_overflows = T::from_f64(1.0 / frequency).to_f64() * 134_217_729.0 > T::BIG;
    if want.is_none() && split_overflows && r.is_err() {
        assert_eq!(
            r.err(),
            Some(Error::NonFiniteStep),
            "clock {frequency:e} Hz"
        );
    } else {
        assert_eq!(r.err(), want, "clock {frequency:e} Hz, {bits} bits");
    }
    Some((r.ok()?, frequency, bits))
}

/// A double-double accumulator (TwoSum), exact enough for sums of a few thousand f64 terms.
#[derive(Clone, Copy, Default)]
struct Exact {
    hi: f64,
    lo: f64,
}

impl Exact {
    fn add(&mut self, x: f64) {
        let s = self.hi + x;
        let bb = s - self.hi;
        let e = (self.hi - (s - bb)) + (x - bb);
        self.hi = s;
        self.lo += e;
    }
    /// `self − n·p` with `n·p` exact (its FMA remainder).
    fn minus_product(&self, n: f64, p: f64) -> f64 {
        let prod = n * p;
        let rem = n.mul_add(p, -prod);
        (self.hi - prod) + (self.lo - rem)
    }
}

fn fixed_period<T: Fz>(b: &mut Bytes<'_>) {
    let Some((mut p, period)) = period_config::<T>(b) else {
        return;
    };
    let eps = T::EPS;
    let mut accepted = Exact::default();
    let mut k = 0.0_f64; // samples (next_dt calls)
    let mut carried = 0.0_f64; // the bound's share from dts handed out with a carried interval
    let mut carry_pending = false;
    for _ in 0..512 {
        if b.is_empty() {
            break;
        }
        let byte = b.u8();
        for call in 0..2 {
            let dt = p.next_dt();
            k += 1.0;
            let dtf = dt.to_f64();
            if carry_pending {
                carried += T::ulp(dtf);
            }
            // A refused sample one time in eight: its dt is given back.
            let refused = (byte >> (4 * call)) & 7 == 0;
            if refused {
                let before = dtf;
                p.carry_over(dt);
                // The carry's own rounding when it absorbs the dt.
                carried += T::ulp(before);
                carry_pending = true;
                continue;
            }
            carry_pending = false;
            if !(period * (k + 2.0) < T::BIG / 4.0) {
                return;
            }
            assert!(dt > T::ZERO && dt.is_finite(), "dt {dtf:e}");
            accepted.add(dtf);
            let err = accepted.minus_product(k, period).abs();
            let bound =
                0.5 * T::ulp(dtf) + carried + k * (4.0 * eps * eps * period + 2.0 * T::TINY);
            assert!(
                err <= bound,
                "{}: after {k} samples of {period:e} s, sum of dts off by {err:e} > {bound:e}",
                T::NAME
            );
        }
    }
}

fn tick_clock<T: Fz>(b: &mut Bytes<'_>) {
    let Some((mut clock, frequency, bits)) = clock_config::<T>(b) else {
        return;
    };
    let eps = T::EPS;
    let period = 1.0 / frequency;
    let mask: u32 = if bits == 32 {
        u32::MAX
    } else {
        (1u32 << bits) - 1
    };
    let mut last: Option<u32> = None;
    let mut previous_ticks: u32 = 0;
    let mut gaps: u32 = 0;
    let mut ticks_total = 0.0_f64;
    let mut sum = Exact::default();
    let mut small = 0.0_f64; // the 4ε²·dt and subnormal terms of the bound
    let mut max_dt = 0.0_f64;
    let mut t = b.u32();
    let step = u32::from(b.u16()).max(1);
    for _ in 0..256 {
        if b.is_empty() {
            break;
        }
        let op = b.below(32);
        if op == 0 {
            clock.restart();
            last = None;
            previous_ticks = 0;
            ticks_total = 0.0;
            sum = Exact::default();
            small = 0.0;
            max_dt = 0.0;
            continue;
        }
        t = match op {
            1..=19 => t.wrapping_add(step),
            20 | 21 => t,
            22 | 23 => t.wrapping_sub(u32::from(b.u8())),
            24..=27 => t.wrapping_add(step.wrapping_mul(2 + b.below(8) as u32)),
            28 | 29 => t.wrapping_add(b.u32()),
            _ => b.u32(),
        };
        let before = clock;
        let advanced = clock.advance(t);
        // Debug text throughout: an overflowed product (a period near T::MAX) gives a NaN dt and carry.
        // `advance(&self)` cannot change the clock (a shared borrow of a `Copy` type without interior
        // mutability); a refused `dt` is checked against `before` below.
        let r = clock.dt(t);
        let same_bits = match (r, advanced) {
            (Ok(Some(x)), Ok((_, Some(y)))) => x.bits() == y.bits(),
            (Ok(None), Ok((_, None))) => true,
            _ => false,
        };
        // Equal bits are equal text; otherwise the text decides (a NaN equals a NaN).
        if !same_bits {
            assert_same_text(&r, &advanced.map(|(_, dt)| dt), &"dt vs advance");
        }
        if let Ok((next, _)) = advanced {
            assert_same_text(&clock, &next, &"dt committed another clock");
        }
        let stamp = t & mask;
        let Some(prev) = last else {
            assert_eq!(r, Ok(None), "first timestamp");
            last = Some(stamp);
            continue;
        };
        let ticks = stamp.wrapping_sub(prev) & mask;
        if ticks == 0 || ticks > mask / 2 {
            assert_eq!(
                r,
                Err(Error::TimestampNotIncreasing),
                "{prev} -> {stamp} ({bits} bits)"
            );
            assert_same_text(&clock, &before, &"refused timestamp changed the clock");
            continue;
        }
        let dt = match r {
            Ok(Some(dt)) => dt,
            other => panic!("{prev} -> {stamp} ({bits} bits): {other:?}"),
        };
        if previous_ticks != 0 && u64::from(ticks) * 2 > u64::from(previous_ticks) * 3 {
            gaps = gaps.saturating_add(1);
        }
        previous_ticks = ticks;
        last = Some(stamp);
        assert_eq!(clock.gaps(), gaps);
        ticks_total += f64::from(ticks);
        if !(ticks_total * period < T::BIG / 4.0) {
            return;
        }
        let dtf = dt.to_f64();
        // Positive (fixed: tests/fuzz_regressions.rs, `tick_clock_dt_is_positive_after_a_long_gap`) and
        // within an eighth of its own interval: the carry goes in up to ⅛ of `n·hi` (exactly split off, to
        // half an ulp of the carry, itself within half an ulp of the longest dt); `n·hi + n·lo` is the
        // interval to a few ε, and the period's low part may underflow (a subnormal spacing per tick).
        let interval = f64::from(ticks) * period;
        let spread = (0.125 + 4.0 * eps) * interval
            + eps * T::ulp(max_dt)
            + 4.0 * T::TINY
            + f64::from(ticks) * T::TINY;
        assert!(
            dt > T::ZERO && dt.is_finite() && (dtf - interval).abs() <= spread,
            "{}: dt {dtf:e} for {ticks} ticks of {period:e} s (allowed {interval:e} ± {spread:e})",
            T::NAME
        );
        sum.add(dtf);
        // Below the normal range the period's low part `lo` underflows: up to half a subnormal spacing
        // per tick is lost (TwoProduct's exactness needs no underflow in the low part).
        small += 4.0 * eps * eps * dtf + 4.0 * T::TINY + f64::from(ticks) * T::TINY;
        let err = sum.minus_product(ticks_total, period).abs();
        // The carried remainder is at most half an ulp of a dt handed out since the restart (the longest
        // one: a fix may drain a long gap's remainder over several samples instead of the next one).
        max_dt = max_dt.max(dtf);
        let bound = 0.5 * T::ulp(max_dt) + small;
        assert!(
            err <= bound,
            "{}: after {ticks_total} ticks of {period:e} s ({bits} bits), sum of dts off by {err:e} > {bound:e}",
            T::NAME
        );
    }
}
