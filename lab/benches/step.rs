//! One propagator step (`step_linear`, one gyro sample per step) for every scheme × stabilizer in f32 and f64,
//! timed by criterion on the host: `cargo bench -p quatprop-lab --bench step`. Inputs go through
//! `black_box`; the propagator is reused across iterations (a real filter's steady state).

use criterion::{criterion_group, criterion_main, Criterion};
use quatprop::scheme::Method;
use quatprop::stabilize::Policy;
use quatprop::{Propagator, Quat, Real, Vec3};
use std::hint::black_box;

fn policies<T: Real>() -> [(&'static str, Policy<T>); 5] {
    [
        ("Off", Policy::Off),
        ("Normalize", Policy::Normalize),
        ("FirstOrder", Policy::FirstOrder),
        ("Every16", Policy::Every(16)),
        (
            "Baumgarte",
            Policy::Baumgarte {
                k: T::from_f64(0.5),
            },
        ),
    ]
}

fn bench_precision<T: Real>(c: &mut Criterion, precision: &str) {
    let w0 = Vec3::<T>::from_f64(Vec3::new(0.3, -0.2, 1.0));
    let w1 = Vec3::<T>::from_f64(Vec3::new(0.31, -0.19, 0.98));
    let dt = T::from_f64(1e-3);
    let mut group = c.benchmark_group(format!("step_linear_{precision}"));
    for m in Method::ALL {
        for (name, pol) in policies::<T>() {
            let mut p = Propagator::new(Quat::<T>::IDENTITY, m, pol).unwrap();
            group.bench_function(format!("{m:?}/{name}"), |b| {
                b.iter(|| {
                    let _ = black_box(p.step_linear(black_box(w0), black_box(w1), black_box(dt)));
                })
            });
        }
    }
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_precision::<f32>(c, "f32");
    bench_precision::<f64>(c, "f64");
}

criterion_group!(step, benches);
criterion_main!(step);
