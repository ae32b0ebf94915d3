//! Target `delta`: `DeltaAngles` with every `ConingKind`, f32 and f64, ExpMap (which applies the update's
//! rotation vector φ itself), Off or Normalize. After every update the rotation it applied,
//! `log(q_before* ⊗ q_after)` measured in f64, equals φ computed here in f64 from the coning table's
//! formulas (written out independently of the library) on the same increments:
//!
//! `|φ_applied − φ_formula| ≤ 1.6·ε·(4 + 16|φ| + 8nS + 24S²) + 64 ε₆₄ (1 + |φ|)`, for `|φ| ≤ 3`, `S ≤ 10`,
//!
//! `S = Σ|Δθᵢ|` (plus the previous increment for OnePlusPrevious), `n` the increments per update. The
//! library forms φ in `T`: the sum rounds by `nεS/2`; the cross term `(Σkᵢ Δθᵢ) × Δθ_n` (weights up to
//! 1375/504 = 2.73, rounded to `T`) by about `(n + 3)·2.73·ε S² ≤ 24εS²`; the exponential and the product
//! `q ⊗ (e − 1)` by `≤ 8ε|φ|` in the rotation, the final addition and normalization by `≤ 4ε`. The log
//! map turns a rotation error into a φ error by at most `(|φ|/2)/sin(|φ|/2) ≤ 1.6` for `|φ| ≤ 3`; the
//! f64 measurement adds `64 ε₆₄ (1 + |φ|)`. Between updates the attitude is bit for bit unchanged, and an
//! update closes exactly every `samples()` accepted increments.

use super::push::assert_unchanged;
use super::{norm64, quat_bits, Bytes, Fz, ANGLE};
use quatprop::input::coning::{ConingCorrection, ConingKind};
use quatprop::input::DeltaAngles;
use quatprop::scheme::ExpMap;
use quatprop::stabilize::StabilizerKind;
use quatprop::{DeltaAngle, Propagator, Quat, Vec3};

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    crate::by_precision(data, check::<f32>, check::<f64>)
}

fn cross(a: Vec3<f64>, b: Vec3<f64>) -> Vec3<f64> {
    Vec3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

/// φ of one update from the table in `input::coning` (f64).
pub fn formula(kind: ConingKind, previous: Option<Vec3<f64>>, d: &[Vec3<f64>]) -> Vec3<f64> {
    let sum = d.iter().fold(Vec3::ZERO, |s, x| s + *x);
    let weighted = |k: &[f64], den: f64| {
        let w = d
            .iter()
            .zip(k)
            .fold(Vec3::ZERO, |s, (x, k)| s + *x * (*k / den));
        cross(w, d[d.len() - 1])
    };
    match kind {
        ConingKind::Uncorrected => sum,
        ConingKind::OnePlusPrevious => match previous {
            Some(p) => d[0] + cross(p, d[0]) * (1.0 / 12.0),
            None => d[0],
        },
        ConingKind::TwoSample => sum + weighted(&[2.0], 3.0),
        ConingKind::ThreeSample => sum + weighted(&[9.0, 27.0], 20.0),
        ConingKind::FourSample => sum + weighted(&[54.0, 92.0, 214.0], 105.0),
        ConingKind::FiveSample => sum + weighted(&[250.0, 525.0, 650.0, 1375.0], 504.0),
    }
}

fn check<T: Fz>(b: &mut Bytes<'_>) {
    let kind = ConingKind::ALL[b.below(6)];
    let z = if b.bool() {
        StabilizerKind::Off
    } else {
        StabilizerKind::Normalize
    };
    let q0 = b.quat::<T>().normalized().unwrap_or(Quat::IDENTITY);
    let Ok(mut p) = Propagator::new(q0, ExpMap, DeltaAngles::new(kind), z) else {
        panic!("a unit start is accepted");
    };
    let n = kind.samples();
    assert!((1..=5).contains(&n));
    let mut pending: Vec<Vec3<T>> = Vec::new();
    let mut previous: Option<Vec3<T>> = None;
    let mut last_dt = T::from_f64(1e-3);
    // Up to 128 rounds while bytes remain, a restart now and then: the loop every target opens alike (the
    // `burst` target's timed one too), each with its own state to restart.
    for _ in 0..128 {
        if b.is_empty() {
            break;
        }
        if b.u8() < 8 {
            p.restart_input();
            pending.clear();
            previous = None;
            continue;
        }
        let d = b.vec::<T>(ANGLE);
        let dt = b.dt(last_dt);
        let before = p;
        if let Err(e) = p.push(DeltaAngle::new(d), dt) {
            assert_unchanged(&before, &p, &e);
            continue;
        }
        last_dt = dt;
        if pending.len() + 1 < n {
            pending.push(d);
            assert_eq!(quat_bits(p.attitude()), quat_bits(before.attitude()));
            assert_eq!(p.steps(), before.steps());
            continue;
        }
        assert_eq!(p.steps(), before.steps() + 1);
        let mut incs: Vec<Vec3<f64>> = pending.iter().map(|x| x.to_f64()).collect();
        incs.push(d.to_f64());
        let prev = previous.map(|x| x.to_f64());
        let phi = formula(kind, prev, &incs);
        previous = Some(d);
        pending.clear();
        let s = incs.iter().map(|x| norm64(*x)).sum::<f64>()
            + prev.map_or(0.0, |x| {
                if kind == ConingKind::OnePlusPrevious {
                    norm64(x)
                } else {
                    0.0
                }
            });
        let np = norm64(phi);
        if !(s <= 10.0 && np <= 3.0) {
            continue;
        }
        let rel = before.attitude().to_f64().conjugate() * p.attitude().to_f64();
        let applied = rel.to_rotation_vector();
        let err = norm64(applied - phi);
        let eps = T::EPS;
        let nf = incs.len() as f64;
        let bound = 1.6 * eps * (4.0 + 16.0 * np + 8.0 * nf * s + 24.0 * s * s)
            + 64.0 * f64::EPSILON * (1.0 + np);
        assert!(
            err <= bound,
            "{} {kind:?}: applied φ {applied:?} vs formula {phi:?}: {err:e} > {bound:e}",
            T::NAME
        );
    }
}
