//! The flash floor of a real use: one scheme + one input model + `FirstOrder` in f32, no defmt, no
//! formatting. The scheme is Rk4 unless a `scheme-*` feature picks another, the input model `History`
//! unless `input-hold` or `input-linear` does (for the flash table). Exits 0 if a 1 rad/s yaw over 1000
//! steps of 1 ms lands at 1 rad (quaternion components within 1e-4). With `baseline`: the same loop and
//! exit without quatprop (exits 0), what the flash table subtracts to give the library's share.
//! With `estimator-predict`, also the estimator's predict step every 10th step (`error_state::Step::between`
//! the attitudes 10 ms apart, then `covariance::Ud::<f32, 6>::predict`); with `estimator`, also one scalar
//! `Ud::update` and a correction (`rotate_body` + `correct_bias`) at the end: what the estimator's
//! covariance adds to a firmware's flash. With `calibration-estimator`, the rates go through the front end's
//! `frontend::CalibrationEstimator` (built from constants; `correct` before each push, `update` with the
//! sample and a black-boxed accelerometer after it): what learning the gyro's gain and bias in motion adds.
#![no_std]
#![no_main]
// The baseline names none of the configuration below.
#![cfg_attr(feature = "baseline", allow(unused_imports, dead_code))]

use core::hint::black_box;
use cortex_m_rt::entry;
#[cfg(feature = "estimator-predict")]
use quatprop::covariance::Ud;
#[cfg(feature = "estimator-predict")]
use quatprop::error_state::{GyroNoise, Step};
#[cfg(feature = "calibration-estimator")]
use quatprop::frontend::CalibrationEstimator;
use quatprop::stabilize::FirstOrder;
use quatprop::{input, scheme, GyroSample, Propagator, Quat, Vec3};
use quatprop_firmware::exit::exit;

/// `type $alias` = the type whose feature is enabled (at most one of them), else `$default`.
macro_rules! type_by_feature {
    ($alias:ident, default $default:ty, $($feature:literal => $ty:ty,)*) => {
        $(
            #[cfg(feature = $feature)]
            type $alias = $ty;
        )*
        #[cfg(not(any($(feature = $feature),*)))]
        type $alias = $default;
    };
}

type_by_feature!(I, default input::History<f32>,
    "input-hold" => input::Hold,
    "input-linear" => input::Linear<f32>,
);

type_by_feature!(S, default scheme::Rk4,
    "scheme-euler" => scheme::Euler,
    "scheme-rk2" => scheme::Rk2,
    "scheme-rk3" => scheme::Rk3,
    "scheme-rk5" => scheme::Rk5,
    "scheme-expmap" => scheme::ExpMap,
    "scheme-magnus4" => scheme::Magnus4,
    "scheme-cf4" => scheme::Cf4,
);

#[cfg(feature = "baseline")]
#[entry]
fn main() -> ! {
    let mut sum = 0.0_f32;
    for _ in 0..=1000 {
        let w = black_box(Vec3::new(0.0_f32, 0.0, 1.0));
        sum += black_box(w.z) * black_box(1.0e-3);
    }
    exit(black_box(sum) > 0.0)
}

#[cfg(not(feature = "baseline"))]
#[entry]
fn main() -> ! {
    let ok = match Propagator::new(
        Quat::<f32>::IDENTITY,
        S::default(),
        I::default(),
        FirstOrder,
    ) {
        Ok(mut p) => {
            let mut refused = false;
            #[cfg(feature = "estimator-predict")]
            let (noise, mut ud, mut start) = match (
                GyroNoise::<f32>::from_noise_density_dps(0.0028, 5.0),
                Ud::<f32, 6>::from_diagonal([1.0e-2, 1.0e-2, 1.0e-2, 1.0e-7, 1.0e-7, 1.0e-7]),
            ) {
                (Ok(n), Ok(u)) => (n, u, p.attitude()),
                _ => exit(false),
            };
            #[cfg(feature = "calibration-estimator")]
            let mut cal = match CalibrationEstimator::<f32>::new(1.0e-3, 0.01, 0.0087) {
                Ok(c) => c,
                Err(_) => exit(false),
            };
            // 1001 samples: the first only starts the history.
            for _i in 0..=1000 {
                // black_box: the inputs are data, as from a sensor.
                let w = black_box(Vec3::new(0.0_f32, 0.0, 1.0));
                // With the calibration estimator, the correction learned before the sample (the
                // identity over this second: its start-up takes 3 s), then the sample learned from.
                #[cfg(feature = "calibration-estimator")]
                let s = cal.correct(GyroSample::new(w));
                #[cfg(not(feature = "calibration-estimator"))]
                let s = GyroSample::new(w);
                refused |= p.push(s, black_box(1.0e-3)).is_err();
                #[cfg(feature = "calibration-estimator")]
                if cal
                    .update(
                        w,
                        black_box(Vec3::new(0.0_f32, 0.0, 9.81)),
                        black_box(1.0e-3),
                    )
                    .is_err()
                {
                    refused = true;
                }
                #[cfg(feature = "estimator-predict")]
                if _i % 10 == 0 {
                    let end = p.attitude();
                    match Step::between(start, end, black_box(1.0e-2), &noise) {
                        Ok(step) => {
                            let (phi, q) = step.matrices();
                            refused |= ud.predict(&phi, &q).is_err();
                        }
                        Err(_) => refused = true,
                    }
                    start = end;
                }
            }
            #[cfg(feature = "estimator")]
            {
                // An inclination row; the innovation is data (zero here: the attitude stays exact).
                let h = black_box([0.0_f32, -1.0, 0.0, 0.0, 0.0, 0.0]);
                let innovation = black_box(0.0_f32);
                match ud.update(&h, black_box(1.0e-3)) {
                    Ok(g) => {
                        let k = g.gain.map(|k| k * innovation);
                        refused |= p.rotate_body(Vec3::new(k[0], k[1], k[2])).is_err();
                        refused |= p.correct_bias(Vec3::new(k[3], k[4], k[5])).is_err();
                    }
                    Err(_) => refused = true,
                }
            }
            #[cfg(feature = "estimator-predict")]
            {
                refused |= !ud.variances().iter().all(|v| *v > 0.0 && v.is_finite());
            }
            // 1 rad of yaw: q = (cos ½, 0, 0, sin ½).
            let q = p.attitude();
            !refused
                && p.steps() == 1000
                && (q.w - 0.877_582_6).abs() < 1e-4
                && (q.z - 0.479_425_55).abs() < 1e-4
        }
        Err(_) => false,
    };
    exit(ok)
}
