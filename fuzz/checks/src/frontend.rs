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
//! - `FixedBias`: refused iff non-finite; `apply` subtracts bit for bit.
//! - `BiasEstimator`: any window, gate and memory (refused as documented), optional initial bias, then
//!   arbitrary samples with NaN and saturated ones: `Err` ⇒ unchanged; `Ok` ⇒ output = sample − bias
//!   before it, and a saturated sample never changes the estimate. With changes switched off
//!   (`with_change(MAX)`) the estimate follows an independent implementation of the documented rule
//!   (stillness windows, running mean over `memory` windows; a window whose mean overflows teaches
//!   nothing) bit for bit. With changes on, and optionally an
//!   acceleration gate and the temperature model fed arbitrary accelerations and temperatures (NaN and
//!   infinities among them): a NaN or infinite one is refused as `NonFiniteAux` with the estimator
//!   unchanged; otherwise the output is the sample minus `bias_at(temperature)` from before, bit for bit,
//!   and the estimate stays finite; `correct` then `learn` gives the same output and state. A `MotionBias` (any period) fed those outputs with the accelerations
//!   and arbitrary `dt`: refused input (typed) leaves it unchanged, its estimate stays within ±2 °/s, and
//!   `at_rest` zeroes it.
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
use quatprop::{Error, GyroSample, Quat, Vec3};

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    let mut b = Bytes::new(data);
    let which = b.below(7);
    if b.bool() {
        check::<f32>(&mut b, which)
    } else {
        check::<f64>(&mut b, which)
    }
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
fn f64_from(b: &mut Bytes<'_>, plausible: [f64; 4]) -> f64 {
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
        }
        Err(e) => {
            assert_eq!(e, Error::NonFiniteRate);
            assert!(!bias.is_finite());
        }
    }
}

/// The documented bias estimator, written out independently.
#[derive(Clone, Copy, Debug)]
struct Mirror<T> {
    window: u32,
    gate: T,
    memory: u32,
    bias: Vec3<T>,
    sum: Vec3<T>,
    count: u32,
    learned: u32,
}

fn bias_estimator<T: Fz>(b: &mut Bytes<'_>) {
    let window = match b.below(4) {
        0 => u32::from(b.u8() % 3),
        _ => 1 + b.below(8) as u32,
    };
    let gate: T = match b.below(4) {
        0 => b.real(UNIT),
        _ => T::from_f64([0.05, 0.01, 0.1, 1e-3][b.below(4)]),
    };
    let memory = match b.below(4) {
        0 => u32::from(b.u8() % 3),
        _ => 1 + b.below(4) as u32,
    };
    let default_memory = b.bool();
    let r = if default_memory {
        BiasEstimator::from_samples(window, gate, 64)
    } else {
        BiasEstimator::from_samples(window, gate, memory)
    };
    let memory = if default_memory { 64 } else { memory };
    let valid = window > 0 && memory > 0 && gate > T::ZERO && gate.is_finite();
    let follow = b.bool();
    let mut est = match r.and_then(|e| if follow { Ok(e) } else { e.with_change(T::MAX) }) {
        Ok(e) => {
            assert!(valid);
            e
        }
        Err(e) => {
            assert_eq!(e, Error::InvalidEstimator);
            assert!(!valid);
            return;
        }
    };
    let mut m = Mirror {
        window,
        gate,
        memory,
        bias: Vec3::ZERO,
        sum: Vec3::ZERO,
        count: 0,
        learned: 0,
    };
    if b.u8() < 64 {
        let initial = b.vec::<T>([1e-3, 1e-2, 0.05, 1.0]);
        match est.with_initial(initial) {
            Ok(e) => {
                assert!(initial.is_finite());
                est = e;
                m.bias = initial;
                m.learned = 1;
            }
            Err(e) => {
                assert_eq!(e, Error::NonFiniteRate);
                assert!(!initial.is_finite());
            }
        }
    }
    assert_eq!(vec_bits(est.bias()), vec_bits(m.bias));
    if follow {
        following(b, est);
        return;
    }
    for _ in 0..256 {
        if b.is_empty() {
            break;
        }
        let s = GyroSample {
            rate: b.vec::<T>([1e-3, 1e-2, 0.05, 1.0]),
            saturated: b.u8() < 32,
        };
        let before = est;
        let r = est.update(s);
        if !s.rate.is_finite() {
            assert_eq!(r, Err(Error::NonFiniteRate));
            assert!(est == before);
            super::assert_same_text(&est, &before, &"refused sample changed the estimator");
            continue;
        }
        let out = r.expect("a finite sample is taken");
        let d = Vec3::new(
            s.rate.x - m.bias.x,
            s.rate.y - m.bias.y,
            s.rate.z - m.bias.z,
        );
        assert_eq!(vec_bits(out.rate), vec_bits(d));
        assert_eq!(out.saturated, s.saturated);
        let g = m.gate;
        let still = !s.saturated && d.x.abs() <= g && d.y.abs() <= g && d.z.abs() <= g;
        if still {
            m.sum = Vec3::new(m.sum.x + d.x, m.sum.y + d.y, m.sum.z + d.z);
            m.count += 1;
            if m.count >= m.window {
                // A window whose mean (added to the estimate) overflows teaches nothing.
                let w = T::ONE / T::of_i32(m.window as i32);
                let probe = Vec3::new(
                    m.bias.x + m.sum.x * w,
                    m.bias.y + m.sum.y * w,
                    m.bias.z + m.sum.z * w,
                );
                if probe.is_finite() {
                    m.learned = (m.learned + 1).min(m.memory);
                    let n = T::of_i32(m.window as i32) * T::of_i32(m.learned as i32);
                    let inv = T::ONE / n;
                    m.bias = Vec3::new(
                        m.bias.x + m.sum.x * inv,
                        m.bias.y + m.sum.y * inv,
                        m.bias.z + m.sum.z * inv,
                    );
                }
                m.sum = Vec3::ZERO;
                m.count = 0;
            }
        } else {
            m.sum = Vec3::ZERO;
            m.count = 0;
        }
        if s.saturated {
            assert_eq!(
                vec_bits(est.bias()),
                vec_bits(before.bias()),
                "learned from a saturated sample"
            );
        }
        assert_eq!(vec_bits(est.bias()), vec_bits(m.bias), "{m:?}");
        assert_eq!(est.is_learned(), m.learned > 0);
    }
}

/// The estimator with changes followed, optionally an acceleration gate and the temperature model, fed
/// arbitrary samples, accelerations and temperatures: the invariants that hold whatever it learns.
fn following<T: Fz>(b: &mut Bytes<'_>, mut est: BiasEstimator<T>) {
    let period = f64_from(b, [1e-3, 1e-2, 2.5e-4, 3.5e-3]);
    let mut motion = match MotionBias::<T>::new(period) {
        Ok(m) => {
            assert!(period > 0.0 && period.is_finite());
            Some(m)
        }
        Err(e) => {
            assert!(matches!(e, Error::NonFiniteStep | Error::NonPositiveStep));
            assert!(!(period > 0.0 && period.is_finite()));
            None
        }
    };
    if b.bool() {
        let gate: T = b.real(UNIT);
        let r = est.with_accel_gate(gate);
        match r {
            Ok(e) => est = e,
            Err(e) => {
                assert_eq!(e, Error::InvalidEstimator);
                assert!(!(gate > T::ZERO && gate.is_finite()));
            }
        }
    }
    if b.bool() {
        let span: T = b.real(UNIT);
        match est.with_temperature_model(span) {
            Ok(e) => est = e,
            Err(e) => {
                assert_eq!(e, Error::InvalidEstimator);
                assert!(!(span > T::ZERO && span.is_finite()));
            }
        }
    }
    for _ in 0..256 {
        if b.is_empty() {
            break;
        }
        let s = GyroSample {
            rate: b.vec::<T>([1e-3, 1e-2, 0.05, 1.0]),
            saturated: b.u8() < 32,
        };
        let accel = b.bool().then(|| b.vec::<T>([0.1, 1.0, 9.81, 100.0]));
        let temperature = b
            .bool()
            .then(|| T::from_f64(25.0) + b.real::<T>([0.1, 1.0, 10.0, 100.0]));
        let aux = Aux { accel, temperature };
        let before = est;
        let r = est.update_with(s, aux);
        // update_with is correct, then learn: the same state and output, split as the C API calls them.
        let mut split = before;
        let c = split.correct(s, aux);
        assert_eq!(format!("{c:?}"), format!("{r:?}"));
        if let Ok(out) = c {
            split.learn(out, aux);
        }
        assert_same_text(&split, &est, &"correct + learn differ from update_with");
        if !s.rate.is_finite() {
            assert_eq!(r, Err(Error::NonFiniteRate));
            assert_same_text(&est, &before, &"refused sample changed the estimator");
            continue;
        }
        let aux_finite =
            accel.is_none_or(|a| a.is_finite()) && temperature.is_none_or(|t| t.is_finite());
        let used = temperature.map_or(before.bias(), |t| before.bias_at(t));
        if !aux_finite || !used.is_finite() {
            assert_eq!(r, Err(Error::NonFiniteAux));
            assert_same_text(&est, &before, &"refused aux changed the estimator");
            continue;
        }
        let out = r.expect("a finite sample is taken");
        let d = Vec3::new(s.rate.x - used.x, s.rate.y - used.y, s.rate.z - used.z);
        assert_eq!(vec_bits(out.rate), vec_bits(d));
        assert_eq!(out.saturated, s.saturated);
        if s.saturated {
            assert_eq!(
                vec_bits(est.bias()),
                vec_bits(before.bias()),
                "learned from a saturated sample"
            );
        }
        assert!(est.bias().is_finite(), "{est:?}");
        assert!(
            est.is_learned() || !before.is_learned(),
            "forgot what it learned"
        );
        // The residual in motion on the corrected rate: refused input leaves it unchanged; otherwise its
        // estimate stays finite and within its ±2 °/s clip.
        if let (Some(m), Some(a)) = (motion.as_mut(), accel) {
            let dt: T = b.real(UNIT);
            let kept = *m;
            match m.update(out.rate, a, dt) {
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
            if est.bias() != before.bias() {
                m.at_rest();
                assert_eq!(vec_bits(m.bias()), vec_bits(Vec3::<T>::ZERO));
            }
        }
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
