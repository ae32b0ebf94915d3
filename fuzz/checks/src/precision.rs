//! Targets `precision` and `kahan`: the same well-conditioned samples (f32 values, widened exactly) into an
//! f32 propagator and an f64 one with the same scheme, stabilizer and input model; after every push their
//! attitudes are within a derived bound of each other (angle measured in f64).
//!
//! Well-conditioned: a start with components `i16/32768`; rates `|ωᵢ| ≤ 10` rad/s (delta angles
//! `|Δθᵢ| ≤ 0.05` rad); `dt` a fixed base in [1e-4, 1e-2] s, now and then doubled or halved (exact in both
//! precisions, so History's spacing test decides the same way). Every step is then far inside every
//! scheme's stability bound and both propagators accept every sample. In exact arithmetic both compute the
//! same attitudes; only rounding separates them. Per step, with θ the mirror's bound on the step angle
//! ([`super::model::Schedule::step_angle`]):
//! - the increment is formed with a relative error of a few ε of its size θ/2 (the rotation vector or the
//!   Runge–Kutta stages, the product with q): at most `64εθ` of rotation;
//! - `precision` (Plain): adding the increment rounds each component by ½ ulp and the stabilizer's scaling
//!   rounds again: `4ε` of rotation per step; `kahan` (f32 `Kahan` against an f64 `Plain` state): the
//!   compensated sum keeps those roundings (Kahan: error ≤ 2u|q| + O(nu²)), and the stabilizers'
//!   corrections are radial (q times a scalar), so only the final representation, `4ε`, is added once.
//!
//! The start's normalization differs by `2ε`; the f64 state's own rounding is bounded the same way with
//! ε₆₄ (`8ε₆₄` per step). Bounds: `precision`: `2ε + Σ(4ε + 64εθₖ) + 8kε₆₄`; `kahan`:
//! `6ε + Σ 64εθₖ + 8kε₆₄`, ε = 2⁻²³. Over 256 steps of 1 mrad the Kahan bound is 22ε while a plain f32
//! state may drift by 2ε per step (512ε): the check tells the two apart.

use super::model::Model;
use super::{angle64, norm64, Bytes};
use quatprop::accumulate::{Accumulator, Kahan, Plain};
use quatprop::input::coning::ConingKind;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, Linear, TwiceRate};
use quatprop::scheme::SchemeKind;
use quatprop::stabilize::StabilizerKind;
use quatprop::{Propagator, Quat, Vec3};
use std::fmt::Debug;

/// Decodes and checks one input of the `precision` target.
pub fn run(data: &[u8]) {
    run_with(data, false)
}

/// Decodes and checks one input; `kahan`: the f32 state is compensated.
pub fn run_with(data: &[u8], kahan: bool) {
    let mut b = Bytes::new(data);
    let s = SchemeKind::ALL[b.below(8)];
    let z = match b.below(4) {
        0 => StabilizerKind::Off,
        1 => StabilizerKind::Normalize,
        2 => StabilizerKind::FirstOrder,
        _ => StabilizerKind::Every(1 + b.below(8) as u32),
    };
    let input = b.below(11);
    let c = [b.u16(), b.u16(), b.u16(), b.u16()].map(|x| f32::from(x as i16) / 32768.0);
    let q0 = if c.iter().all(|x| *x == 0.0) {
        Quat::IDENTITY
    } else {
        Quat::new(c[0], c[1], c[2], c[3])
    };
    let base = 1e-4 + (f32::from(b.u16()) / 65536.0) * (1e-2 - 1e-4);
    let cfg = Cfg {
        s,
        z,
        q0,
        base,
        kahan,
    };
    match input {
        0 => pair(&mut b, cfg, Hold, Hold),
        1 => pair(&mut b, cfg, Linear::new(), Linear::new()),
        2 => pair(&mut b, cfg, History::new(), History::new()),
        3 => pair(&mut b, cfg, TwiceRate::new(), TwiceRate::new()),
        4 => pair(&mut b, cfg, GaussPoints::new(), GaussPoints::new()),
        n => {
            let k = ConingKind::ALL[(n - 5) % 6];
            pair(&mut b, cfg, DeltaAngles::new(k), DeltaAngles::new(k))
        }
    }
}

#[derive(Clone, Copy)]
struct Cfg {
    s: SchemeKind,
    z: StabilizerKind,
    q0: Quat<f32>,
    base: f32,
    kahan: bool,
}

fn pair<I32: Model<f32>, I64: Model<f64>>(b: &mut Bytes<'_>, cfg: Cfg, i32: I32, i64: I64) {
    let a = Propagator::new(cfg.q0, cfg.s, i32, cfg.z).expect("a valid start");
    let c = Propagator::new(cfg.q0.to_f64(), cfg.s, i64, cfg.z).expect("a valid start");
    if cfg.kahan {
        drive(b, cfg, a.with_accumulator(Kahan::new()), c)
    } else {
        drive(b, cfg, a, c)
    }
}

fn drive<I32: Model<f32>, I64: Model<f64>, A: Accumulator<f32> + Debug + PartialEq>(
    b: &mut Bytes<'_>,
    cfg: Cfg,
    mut a: Propagator<f32, SchemeKind, I32, StabilizerKind, A>,
    mut c: Propagator<f64, SchemeKind, I64, StabilizerKind, Plain>,
) {
    let eps = f64::from(f32::EPSILON);
    let e64 = f64::EPSILON;
    let mut schedule = a.input().schedule();
    let delta = matches!(schedule.kind(), super::model::Kind::Delta(_));
    let scale = if delta { 0.05 } else { 10.0 };
    let mut bound = if cfg.kahan { 6.0 * eps } else { 2.0 * eps };
    let steps = if cfg.kahan { 256 } else { 32 };
    let d0 = angle64(a.attitude().to_f64(), c.attitude());
    assert!(d0 <= 2.0 * eps + 4.0 * e64, "start: {d0:e}");
    for _ in 0..steps {
        if b.is_empty() {
            break;
        }
        let tag = b.u8();
        let mag = if cfg.kahan {
            [1e-3, 0.01, 0.1, 1.0][usize::from(tag % 4)]
        } else {
            1.0
        };
        let mut comp = || f32::from(b.u16() as i16) / 32768.0 * scale * mag as f32;
        let v = Vec3::new(comp(), comp(), comp());
        let dt = match tag >> 5 {
            0 => cfg.base * 2.0,
            1 => cfg.base * 0.5,
            _ => cfg.base,
        };
        let closes = schedule.closes();
        let theta = schedule.step_angle(norm64(v), f64::from(dt));
        let ra = a.push(I32::sample(v, false), dt);
        let rc = c.push(I64::sample(v.to_f64(), false), f64::from(dt));
        assert!(
            ra.is_ok() && rc.is_ok(),
            "{:?} {:?}: {ra:?} {rc:?} for {v:?} over {dt:e}",
            cfg.s,
            schedule.kind()
        );
        schedule.accept(norm64(v), f64::from(dt));
        assert_eq!(a.steps(), c.steps());
        if closes {
            bound += 64.0 * eps * theta + 8.0 * e64;
            if !cfg.kahan {
                bound += 4.0 * eps;
            }
        }
        let d = angle64(a.attitude().to_f64(), c.attitude());
        assert!(
            d <= bound,
            "{:?} {:?} {:?} kahan {}: f32 and f64 states {d:e} rad apart after {} steps, bound {bound:e}",
            cfg.s,
            cfg.z,
            schedule.kind(),
            cfg.kahan,
            a.steps()
        );
    }
}
