//! `step-loop <scheme> <stabilizer> <f32|f64> <steps>`: runs `step_linear` `steps` times; used by
//! `lab/callgrind.sh` to count instructions per step (callgrind totals at N and 2N steps, differenced).
use quatprop::scheme::Method;
use quatprop::stabilize::Policy;
use quatprop::{Propagator, Quat, Real, Vec3};
use std::hint::black_box;

fn run<T: Real>(m: Method, pol: Policy<T>, steps: u64) {
    let mut p = Propagator::new(Quat::<T>::IDENTITY, m, pol).expect("valid configuration");
    let w0 = Vec3::<T>::from_f64(Vec3::new(0.3, -0.2, 1.0));
    let w1 = Vec3::<T>::from_f64(Vec3::new(0.31, -0.19, 0.98));
    let dt = T::from_f64(1e-3);
    for _ in 0..steps {
        let _ = black_box(p.step_linear(black_box(w0), black_box(w1), black_box(dt)));
    }
    black_box(p.attitude());
}

fn policy<T: Real>(s: &str) -> Option<Policy<T>> {
    Some(match s {
        "Off" => Policy::Off,
        "Normalize" => Policy::Normalize,
        "FirstOrder" => Policy::FirstOrder,
        "Every16" => Policy::Every(16),
        "Baumgarte" => Policy::Baumgarte {
            k: T::from_f64(0.5),
        },
        _ => return None,
    })
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
    let m = Method::ALL
        .into_iter()
        .find(|m| format!("{m:?}") == a[0])
        .unwrap_or_else(|| usage());
    let steps: u64 = a[3].parse().unwrap_or_else(|_| usage());
    match a[2].as_str() {
        "f32" => run::<f32>(m, policy(&a[1]).unwrap_or_else(|| usage()), steps),
        "f64" => run::<f64>(m, policy(&a[1]).unwrap_or_else(|| usage()), steps),
        _ => usage(),
    }
}
