//! One propagator step (`push` with the linear input model, one gyro sample per step) for every scheme ×
//! stabilizer in f32 and f64, timed by criterion on the host: `cargo bench -p quatprop-lab --bench step`.
//! Samples go through `black_box` and alternate between two rates; the propagator is reused across
//! iterations (a real filter's steady state). Baumgarte wraps the Runge–Kutta schemes only
//! (`scheme::Baumgarte`, stabilizer `Off`).

use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion};
use quatprop::input::Linear;
use quatprop::scheme::{Baumgarte, Euler, Rk2, Rk3, Rk4, Rk5, Scheme, SchemeKind};
use quatprop::stabilize::{Off, Stabilizer, StabilizerKind};
use quatprop::{GyroSample, Propagator, Quat, Real, Vec3};
use std::hint::black_box;

const STABILIZERS: [(&str, StabilizerKind); 4] = [
    ("Off", StabilizerKind::Off),
    ("Normalize", StabilizerKind::Normalize),
    ("FirstOrder", StabilizerKind::FirstOrder),
    ("Every16", StabilizerKind::Every(16)),
];

fn bench_one<T: Real, S: Scheme<T>, Z: Stabilizer>(
    group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: String,
    s: S,
    z: Z,
) {
    let w0 = GyroSample::new(Vec3::<T>::from_f64(Vec3::new(0.3, -0.2, 1.0)));
    let w1 = GyroSample::new(Vec3::<T>::from_f64(Vec3::new(0.31, -0.19, 0.98)));
    let dt = T::from_f64(1e-3);
    let mut p = Propagator::new(Quat::<T>::IDENTITY, s, Linear::new(), z).unwrap();
    let _ = p.push(w0, dt); // starts the linear model
    let mut odd = false;
    group.bench_function(id, |b| {
        b.iter(|| {
            odd = !odd;
            let w = if odd { w1 } else { w0 };
            let _ = black_box(p.push(black_box(w), black_box(dt)));
        })
    });
}

fn bench_precision<T: Real>(c: &mut Criterion, precision: &str) {
    let mut group = c.benchmark_group(format!("push_linear_{precision}"));
    for m in SchemeKind::ALL {
        for (name, z) in STABILIZERS {
            bench_one::<T, _, _>(&mut group, format!("{m:?}/{name}"), m, z);
        }
        let k = T::from_f64(0.5);
        let id = format!("{m:?}/Baumgarte");
        match m {
            SchemeKind::Euler => bench_one(&mut group, id, Baumgarte::new(Euler, k).unwrap(), Off),
            SchemeKind::Rk2 => bench_one(&mut group, id, Baumgarte::new(Rk2, k).unwrap(), Off),
            SchemeKind::Rk3 => bench_one(&mut group, id, Baumgarte::new(Rk3, k).unwrap(), Off),
            SchemeKind::Rk4 => bench_one(&mut group, id, Baumgarte::new(Rk4, k).unwrap(), Off),
            SchemeKind::Rk5 => bench_one(&mut group, id, Baumgarte::new(Rk5, k).unwrap(), Off),
            SchemeKind::ExpMap | SchemeKind::Magnus4 | SchemeKind::Cf4 => {}
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
