//! One propagator step (`push` with the linear input model, one gyro sample per step) for every scheme ×
//! stabilizer in f32 and f64, timed by criterion on the host: `cargo bench -p quatprop-lab --bench step`.
//! Samples go through `black_box` and alternate between two rates; the propagator is reused across
//! iterations (a real filter's steady state). Baumgarte wraps the Runge–Kutta schemes only
//! (`scheme::Baumgarte`, stabilizer `Off`).

use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion};
use quatprop::input::Linear;
use quatprop::scheme::{Baumgarte, Cf4, Euler, ExpMap, Magnus4, Rk2, Rk3, Rk4, Rk5, Scheme};
use quatprop::stabilize::{Every, FirstOrder, Normalize, Off, Stabilizer};
use quatprop::{GyroSample, Propagator, Quat, Real, Vec3};
use std::hint::black_box;

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
    // Every configuration monomorphized (the types a firmware names), as in the lab's studies.
    macro_rules! post_step {
        ($name:literal, $s:expr) => {
            bench_one::<T, _, _>(&mut group, concat!($name, "/Off").into(), $s, Off);
            bench_one::<T, _, _>(
                &mut group,
                concat!($name, "/Normalize").into(),
                $s,
                Normalize,
            );
            bench_one::<T, _, _>(
                &mut group,
                concat!($name, "/FirstOrder").into(),
                $s,
                FirstOrder,
            );
            bench_one::<T, _, _>(&mut group, concat!($name, "/Every16").into(), $s, Every(16));
        };
    }
    macro_rules! rk {
        ($name:literal, $s:expr) => {
            post_step!($name, $s);
            let b = Baumgarte::new($s, T::from_f64(0.5)).unwrap();
            bench_one::<T, _, _>(&mut group, concat!($name, "/Baumgarte").into(), b, Off);
        };
    }
    rk!("Euler", Euler);
    rk!("Rk2", Rk2);
    rk!("Rk3", Rk3);
    rk!("Rk4", Rk4);
    rk!("Rk5", Rk5);
    post_step!("ExpMap", ExpMap);
    post_step!("Magnus4", Magnus4);
    post_step!("Cf4", Cf4);
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_precision::<f32>(c, "f32");
    bench_precision::<f64>(c, "f64");
}

criterion_group!(step, benches);
criterion_main!(step);
