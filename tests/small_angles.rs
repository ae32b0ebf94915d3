//! Small steps are not dropped: a step of 1e-9 rad moves the attitude by 1e-9 rad (±1%) in f64, and by what
//! f32 can represent in f32 (peers drop it: nalgebra's f32 `from_scaled_axis` returns the identity below
//! ~2.4e-7 rad, losing Earth rate at 1 kHz).

use quatprop::input::Hold;
use quatprop::scheme::SchemeKind;
use quatprop::stabilize::Normalize;
use quatprop::{GyroSample, Propagator, Quat, Real, Vec3};

fn moved<T: Real>(m: SchemeKind, q0: Quat<T>, angle: f64) -> f64 {
    let mut p = Propagator::new(q0, m, Hold, Normalize).unwrap();
    let start = p.attitude();
    let axis = Vec3::new(0.48, -0.6, 0.64);
    let w = Vec3::<T>::from_f64(axis * angle);
    p.push(GyroSample::new(w), T::ONE).unwrap();
    start.to_f64().angle_to(p.attitude().to_f64())
}

#[test]
fn a_nanoradian_step_moves_the_attitude_by_a_nanoradian() {
    for m in SchemeKind::ALL {
        for angle in [1e-9, 1e-12, 1e-20] {
            let d = moved::<f64>(m, Quat::IDENTITY, angle);
            assert!(
                (d / angle - 1.0).abs() < 1e-2,
                "{m:?} f64 {angle}: moved {d:e}"
            );
            // f32 from the identity: the vector part 5e-10 is representable, so it is kept.
            let d = moved::<f32>(m, Quat::IDENTITY, angle);
            assert!(
                (d / angle - 1.0).abs() < 1e-2,
                "{m:?} f32 {angle}: moved {d:e}"
            );
        }
    }
}

#[test]
fn f32_from_a_general_attitude_moves_by_the_representable_amount() {
    // From a general attitude the components are ~0.5 with an ulp of 2⁻²⁴ ≈ 6e-8: a 1e-9 rad step is below
    // what f32 can represent there and the attitude stays put; a 1e-6 rad step is resolved to within the
    // representation's granularity (one ulp of the components ≈ 6e-8 rad in angle).
    let q0 = Quat::new(0.5_f32, 0.5, -0.5, 0.5);
    for m in SchemeKind::ALL {
        let d = moved::<f32>(m, q0, 1e-9);
        assert!(d <= 2.0 * 6e-8, "{m:?}: {d:e}");
        let d = moved::<f32>(m, q0, 1e-6);
        assert!((d - 1e-6).abs() <= 2.0 * 6e-8, "{m:?}: {d:e}");
    }
}
