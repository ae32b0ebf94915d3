//! `step-loop <scheme> <stabilizer> <f32|f64> <steps>`: pushes `steps` gyro samples into a propagator with
//! the linear input model (one step per sample, the samples alternating between two rates); used by
//! `lab/callgrind.sh` to count instructions per step (callgrind totals at N and 2N steps, differenced).
//! Scheme and stabilizer are the library's run-time enums (`SchemeKind`, `StabilizerKind`); Baumgarte wraps a
//! Runge–Kutta scheme (`scheme::Baumgarte`, stabilizer `Off`) and exits with status 3 for the others.
use quatprop::input::Linear;
use quatprop::scheme::{Baumgarte, Euler, Rk2, Rk3, Rk4, Rk5, Scheme, SchemeKind};
use quatprop::stabilize::{Off, Stabilizer, StabilizerKind};
use quatprop::{GyroSample, Propagator, Quat, Real, Vec3};
use std::hint::black_box;

fn run<T: Real, S: Scheme<T>, Z: Stabilizer>(s: S, z: Z, steps: u64) {
    let mut p =
        Propagator::new(Quat::<T>::IDENTITY, s, Linear::new(), z).expect("valid configuration");
    let w0 = GyroSample::new(Vec3::<T>::from_f64(Vec3::new(0.3, -0.2, 1.0)));
    let w1 = GyroSample::new(Vec3::<T>::from_f64(Vec3::new(0.31, -0.19, 0.98)));
    let dt = T::from_f64(1e-3);
    // The first sample only starts the linear model.
    let _ = p.push(w0, dt);
    for i in 0..steps {
        let w = if i % 2 == 0 { w1 } else { w0 };
        let _ = black_box(p.push(black_box(w), black_box(dt)));
    }
    black_box(p.attitude());
}

const GAIN: &str = "k = 0.5 is a valid gain";

fn stabilizer(s: &str) -> Option<StabilizerKind> {
    Some(match s {
        "Off" => StabilizerKind::Off,
        "Normalize" => StabilizerKind::Normalize,
        "FirstOrder" => StabilizerKind::FirstOrder,
        "Every16" => StabilizerKind::Every(16),
        _ => return None,
    })
}

fn run_in<T: Real>(m: SchemeKind, stab: &str, steps: u64) {
    if stab == "Baumgarte" {
        let k = T::from_f64(0.5);
        match m {
            SchemeKind::Euler => run::<T, _, _>(Baumgarte::new(Euler, k).expect(GAIN), Off, steps),
            SchemeKind::Rk2 => run::<T, _, _>(Baumgarte::new(Rk2, k).expect(GAIN), Off, steps),
            SchemeKind::Rk3 => run::<T, _, _>(Baumgarte::new(Rk3, k).expect(GAIN), Off, steps),
            SchemeKind::Rk4 => run::<T, _, _>(Baumgarte::new(Rk4, k).expect(GAIN), Off, steps),
            SchemeKind::Rk5 => run::<T, _, _>(Baumgarte::new(Rk5, k).expect(GAIN), Off, steps),
            SchemeKind::ExpMap | SchemeKind::Magnus4 | SchemeKind::Cf4 => {
                eprintln!("no such configuration: Baumgarte wraps the Runge-Kutta schemes only");
                std::process::exit(3)
            }
        }
    } else {
        run::<T, _, _>(m, stabilizer(stab).unwrap_or_else(|| usage()), steps)
    }
}

fn usage() -> ! {
    eprintln!(
        "usage: step-loop <Euler|Rk2|Rk3|Rk4|Rk5|ExpMap|Magnus4|Cf4> \
         <Off|Normalize|FirstOrder|Every16|Baumgarte> <f32|f64> <steps>"
    );
    std::process::exit(2)
}

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    if a.len() != 4 {
        usage()
    }
    let m = SchemeKind::ALL
        .into_iter()
        .find(|m| format!("{m:?}") == a[0])
        .unwrap_or_else(|| usage());
    let steps: u64 = a[3].parse().unwrap_or_else(|_| usage());
    match a[2].as_str() {
        "f32" => run_in::<f32>(m, &a[1], steps),
        "f64" => run_in::<f64>(m, &a[1], steps),
        _ => usage(),
    }
}
