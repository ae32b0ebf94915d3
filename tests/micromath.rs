//! With the `micromath` feature the f32 Euler conversions use micromath's `atan2`. Its documented max error
//! is about 0.002 rad; this measures what the conversions actually lose. Run:
//! `cargo test --features micromath --test micromath -- --nocapture`.
#![cfg(feature = "micromath")]

use quatprop::{EulerZxz, EulerZyx, Quat};

#[test]
fn micromath_euler_error_is_within_its_documented_bound() {
    let mut worst_zyx: f64 = 0.0;
    let mut worst_zxz: f64 = 0.0;
    for i in 0..60 {
        for j in 0..30 {
            let a = -3.1 + 0.105 * i as f64;
            let b = -1.5 + 0.1 * j as f64;
            let e = EulerZyx {
                yaw: a as f32,
                pitch: b as f32,
                roll: (0.7 * a) as f32,
            };
            let q = Quat::from_euler_zyx(e);
            let back = Quat::from_euler_zyx(q.to_euler_zyx());
            worst_zyx = worst_zyx.max(q.to_f64().angle_to(back.to_f64()));
            let z = EulerZxz {
                psi: a as f32,
                theta: (b + 1.55) as f32,
                phi: (-0.4 * a) as f32,
            };
            let q = Quat::from_euler_zxz(z);
            let back = Quat::from_euler_zxz(q.to_euler_zxz());
            worst_zxz = worst_zxz.max(q.to_f64().angle_to(back.to_f64()));
        }
    }
    println!("micromath atan2: worst rotation error after an Euler round trip: zyx {worst_zyx:.2e} rad, zxz {worst_zxz:.2e} rad");
    // Two atan2 calls per outer angle, each ≤ 0.002 rad (half angles doubled): ≤ 0.008 rad in rotation.
    assert!(worst_zyx <= 0.008 && worst_zxz <= 0.008);
    // And visibly coarser than libm (which lands within 16 ε), so the feature really switches.
    assert!(worst_zyx > 1e-5);
}
