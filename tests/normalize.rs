//! `Normalize`'s documented rounding (src/stabilize.rs): after one correction with the plain accumulator,
//! `|N| ≤ 4ε` when `‖q‖²` is within a factor of two of 1, and `|N| ≤ (6 + 7(√F − 1)⁺)ε` for any factor `F`
//! (the increment form cancels when the step grew `‖q‖²` a lot). Random quaternions with `‖q‖² = F` over
//! `F ∈ [2⁻²⁰, 2²⁰]`, in f32 and f64; also the case a property test found (Baumgarte over Rk4, a 5.6 rad
//! delta angle: `F = 11.4`, 4.78ε).

mod support;

use quatprop::input::coning::Uncorrected;
use quatprop::input::DeltaAngles;
use quatprop::scheme::{Baumgarte, Rk4};
use quatprop::stabilize::{Normalize, Stabilizer, StabilizerKind};
use quatprop::{DeltaAngle, Propagator, Quat, Real, Vec3};
use support::{normalize_bound_eps, Xorshift};

/// Worst `|N| / bound` over `n` random quaternions in each binade of `F`, and the worst `|N|` in ε
/// for `F ∈ [½, 2]` and outside it.
fn worst<T: Real>(n: u32, eps: f64) -> (f64, f64, f64) {
    let mut rng = Xorshift::new();
    let (mut ratio, mut inside, mut outside) = (0.0_f64, 0.0_f64, 0.0_f64);
    for binade in -20..20 {
        for _ in 0..n {
            let f = 2f64.powf(f64::from(binade) + rng.uniform());
            let c = [(); 4].map(|()| rng.signed());
            let s = (f / c.iter().map(|v| v * v).sum::<f64>()).sqrt();
            let q = Quat::new(c[0] * s, c[1] * s, c[2] * s, c[3] * s);
            let q = Quat::<T>::from_f64(q);
            let f = q.to_f64().norm_squared(); // the factor the rounded q has
            let out = q + Normalize.correction(q, 1).unwrap();
            let e = out.to_f64().norm_error().abs() / eps;
            ratio = ratio.max(e / normalize_bound_eps(f));
            if (0.5..=2.0).contains(&f) {
                inside = inside.max(e);
            } else {
                outside = outside.max(e);
            }
        }
    }
    (ratio, inside, outside)
}

#[test]
fn normalize_stays_within_its_bound_for_every_norm_factor() {
    for (name, (ratio, inside, outside)) in [
        ("f32", worst::<f32>(25_000, f64::from(f32::EPSILON))),
        ("f64", worst::<f64>(25_000, f64::EPSILON)),
    ] {
        println!("{name}: worst |N|/bound {ratio:.3}, |N| ≤ {inside:.2}ε for F in [1/2, 2], {outside:.1}ε outside");
        assert!(ratio <= 1.0, "{name}: |N| reached {ratio} times the bound");
        // The cancellation the bound accounts for is real (a Normalize that no longer cancels should
        // document a tighter bound).
        assert!(
            outside > 100.0,
            "{name}: at most {outside}ε outside [1/2, 2]: tighten the documented bound"
        );
    }
}

#[test]
fn the_property_test_case_baumgarte_rk4_near_its_bound() {
    let q0 = Quat::new(0.152_120_14_f32, -0.987_404_5, -0.820_707_9, -0.260_773_66);
    let angle = Vec3::new(0.134_253_81_f32, 5.020_176, -2.512_219_2); // 5.62 rad of Rk4's 5.66
    let dt = 0.094_590_89;
    let step = |z| {
        let b = Baumgarte::new(Rk4, 1.694_570_8_f32).unwrap();
        let mut p = Propagator::new(q0, b, DeltaAngles::new(Uncorrected), z).unwrap();
        p.push(DeltaAngle::new(angle), dt).unwrap();
        p.attitude().to_f64()
    };
    let f = step(StabilizerKind::Off).norm_squared();
    let n = step(StabilizerKind::Normalize).norm_error().abs() / f64::from(f32::EPSILON);
    println!("F = {f:.3}, |N| = {n:.3}ε");
    assert!(f > 2.0, "F = {f}");
    assert!(n <= normalize_bound_eps(f), "{n}ε after F = {f}");
}
