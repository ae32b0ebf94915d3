//! `step-loop <scheme> <stabilizer> <f32|f64> <steps>`: pushes `steps` gyro samples into a propagator with
//! the linear input model (one step per sample, the samples alternating between two rates); used by
//! `lab/callgrind.sh` to count instructions per step (callgrind totals at N and 2N steps, differenced).
//! Every configuration is monomorphized (the scheme and stabilizer types a firmware names, as in the lab's
//! studies); Baumgarte wraps a Runge–Kutta scheme (`scheme::Baumgarte`, stabilizer `Off`) and exits with
//! status 3 for the others.
use quatprop::input::Linear;
use quatprop::scheme::{
    Baumgarte, Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, Scheme, SchemeKind,
};
use quatprop::stabilize::{Every, FirstOrder, Normalize, Off, Stabilizer};
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

/// Every configuration monomorphized (the zero-sized types a firmware names), as in the lab's studies.
fn run_in<T: Real>(m: SchemeKind, stab: &str, steps: u64) {
    macro_rules! post_step {
        ($s:expr) => {
            match stab {
                "Off" => run::<T, _, _>($s, Off, steps),
                "Normalize" => run::<T, _, _>($s, Normalize, steps),
                "FirstOrder" => run::<T, _, _>($s, FirstOrder, steps),
                "Every16" => run::<T, _, _>($s, Every(16), steps),
                _ => usage(),
            }
        };
    }
    macro_rules! rk {
        ($s:expr) => {
            if stab == "Baumgarte" {
                let b = Baumgarte::new($s, T::from_f64(0.5)).expect("k = 0.5 is a valid gain");
                run::<T, _, _>(b, Off, steps)
            } else {
                post_step!($s)
            }
        };
    }
    macro_rules! exp {
        ($s:expr) => {
            if stab == "Baumgarte" {
                eprintln!("no such configuration: Baumgarte wraps the Runge-Kutta schemes only");
                std::process::exit(3)
            } else {
                post_step!($s)
            }
        };
    }
    match m {
        SchemeKind::Euler => rk!(Euler),
        SchemeKind::Rk2 => rk!(Rk2),
        SchemeKind::Rk3 => rk!(Rk3),
        SchemeKind::Rk4 => rk!(Rk4),
        SchemeKind::Rk5 => rk!(Rk5),
        SchemeKind::ExpMap => exp!(ExpMap),
        SchemeKind::Magnus4 => exp!(Magnus4),
        SchemeKind::Cf4 => exp!(Cf4),
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
