//! Writes the reference attitudes the Python tests compare with bit for bit (`tests/test_reference.py`).
//!
//! Uses the core library directly — concrete types, `push_burst` / `push_burst_timed` / `push` as a Rust
//! user calls them — never the extension, so the comparison is real. Output (little-endian, raw):
//! `inputs.f64` (gyr N×3, t N, gyr_bad N×3, t_bad N), `ticks.u32` (N), `rest.f64` (N×3: a gyro at rest
//! with a bias step, then a slow turn), and per case `<name>.q` (N×4 in the case's precision) and
//! `<name>.mask` (N bytes, 1 = refused); `cases.json` lists the cases, with the bias estimator's final
//! estimate (`"bias"`, rad/s) where one runs.
//!
//! `cargo run --release -p quatprop-reference -- tests/data/reference` (from `python/`).

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use quatprop::accumulate::{Accumulator, Kahan};
use quatprop::frontend::{Alignment, AxisRemap, BiasEstimator, FixedBias, FixedPeriod, TickClock};
use quatprop::input::coning::ThreeSample;
use quatprop::input::{DeltaAngles, GaussPoints, History, Hold, InputModel, Linear, TwiceRate};
use quatprop::noise::GyroNoise;
use quatprop::scheme::{Cf4, ExpMap, Magnus4, Rk3, Rk4, Rk5, Scheme};
use quatprop::stabilize::{Every, FirstOrder, Normalize, Off, Stabilizer};
use quatprop::{DeltaAngle, EulerZyx, GyroSample, Propagator, Quat, Real, Sample, Vec3};

const N: usize = 1200;
const PERIOD: f64 = 1.0e-3;
const TICK_HZ: f64 = 1.0e6;

/// A deterministic stream: a coning motion at incommensurate frequencies plus small noise (an LCG).
/// Rates (rad/s) and timestamps (s), the same with bad samples, and the sensor's ticks.
type Inputs = (Vec<[f64; 3]>, Vec<f64>, Vec<[f64; 3]>, Vec<f64>, Vec<u32>);

fn inputs() -> Inputs {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut noise = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    let mut gyr = Vec::with_capacity(N);
    let mut t = Vec::with_capacity(N);
    let mut ticks = Vec::with_capacity(N);
    // Ticks start just below the 32-bit wrap, so the wrap is inside the stream.
    let mut tick: u32 = u32::MAX - 400_000;
    let mut time = 1000.0_f64;
    for k in 0..N {
        let s = k as f64 * PERIOD;
        gyr.push([
            0.8 * (7.3 * s).sin() + 0.01 * noise(),
            0.8 * (7.3 * s).cos() + 0.3 * (2.0_f64.sqrt() * 3.1 * s).sin() + 0.01 * noise(),
            0.4 + 0.2 * (5.0_f64.sqrt() * s).cos() + 0.01 * noise(),
        ]);
        // Jittered timestamps (±20 % of the period) in seconds, and ticks of the same jitter.
        let jitter = 1.0 + 0.4 * noise();
        time += PERIOD * jitter;
        t.push(time);
        tick = tick.wrapping_add((1000.0 * jitter).round() as u32);
        ticks.push(tick);
    }
    let mut gyr_bad = gyr.clone();
    let mut t_bad = t.clone();
    gyr_bad[300][1] = f64::NAN; // NonFiniteRate
    t_bad[500] = t_bad[499]; // TimestampNotIncreasing (a duplicate)
    t_bad[800] = t_bad[790]; // backwards
    gyr_bad[700] = [1.0e4, 0.0, 0.0]; // a spike: 10 rad in one step, beyond every Runge–Kutta bound
    (gyr, t, gyr_bad, t_bad, ticks)
}

/// A gyro at rest for the bias estimator's cases: a bias plus uniform noise of ±0.001 rad/s (σ = 0.001/√3
/// per sample, so `N = σ·√period` rad/√s), the bias stepping at rest by (0.004, 0, −0.003) rad/s at
/// sample 520 (inside the window from 500), then from sample 900 a turn about z reaching 0.02 rad/s (below
/// the gates) over 30 samples.
const REST_NOISE: f64 = 0.001;

fn rest_inputs() -> Vec<[f64; 3]> {
    let mut state: u64 = 0x2545_F491_4F6C_DD1D;
    let mut noise = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        2.0 * REST_NOISE * (((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5)
    };
    (0..N)
        .map(|k| {
            let mut b = [0.011, -0.007, 0.004];
            if k >= 520 {
                b[0] += 0.004;
                b[2] -= 0.003;
            }
            let turn = 0.02 * ((k as f64 - 900.0) / 30.0).clamp(0.0, 1.0);
            [b[0] + noise(), b[1] + noise(), b[2] + turn + noise()]
        })
        .collect()
}

/// A vector's components as JSON, each printed exactly (Rust's shortest round-trip form).
fn json3<T: Real>(v: Vec3<T>) -> String {
    format!(
        "[{:?}, {:?}, {:?}]",
        v.x.to_f64(),
        v.y.to_f64(),
        v.z.to_f64()
    )
}

trait FromRow<T>: Sample {
    fn from_row(r: [f64; 3]) -> Self;
}
impl<T: Real> FromRow<T> for GyroSample<T> {
    fn from_row(r: [f64; 3]) -> Self {
        GyroSample::new(Vec3::new(
            T::from_f64(r[0]),
            T::from_f64(r[1]),
            T::from_f64(r[2]),
        ))
    }
}
impl<T: Real> FromRow<T> for DeltaAngle<T> {
    fn from_row(r: [f64; 3]) -> Self {
        DeltaAngle::new(Vec3::new(
            T::from_f64(r[0]),
            T::from_f64(r[1]),
            T::from_f64(r[2]),
        ))
    }
}

type Run<T> = (Vec<Quat<T>>, Vec<bool>);

/// Each item through `push` (`true`: the sample was refused), the attitude after each.
fn record<T: Real, S: Scheme<T>, I: InputModel<T>, Z: Stabilizer, A: Accumulator<T>, X>(
    mut p: Propagator<T, S, I, Z, A>,
    items: impl IntoIterator<Item = X>,
    mut push: impl FnMut(&mut Propagator<T, S, I, Z, A>, X) -> bool,
) -> Run<T> {
    let (mut out, mut mask) = (Vec::new(), Vec::new());
    for item in items {
        mask.push(push(&mut p, item));
        out.push(p.attitude());
    }
    (out, mask)
}

/// A fixed period through the core's `push_burst`, one sample per burst (a refused one is skipped).
fn fixed<T: Real, S: Scheme<T>, I: InputModel<T>, Z: Stabilizer, A: Accumulator<T>>(
    p: Propagator<T, S, I, Z, A>,
    samples: &[I::Sample],
) -> Run<T> {
    let mut period = FixedPeriod::<T>::new(PERIOD).expect("period");
    record(p, samples.chunks(1), |p, one| {
        p.push_burst(one, &mut period).is_err()
    })
}

/// The sensor's ticks through the core's `push_burst_timed`, one sample per burst.
fn ticked<T: Real, S: Scheme<T>, I: InputModel<T>, Z: Stabilizer, A: Accumulator<T>>(
    p: Propagator<T, S, I, Z, A>,
    samples: &[I::Sample],
    ticks: &[u32],
) -> Run<T> {
    let mut clock = TickClock::<T>::new(TICK_HZ, 32).expect("clock");
    record(p, samples.iter().zip(ticks), |p, (s, &tick)| {
        p.push_burst_timed(&[(*s, tick)], &mut clock).is_err()
    })
}

/// Timestamps in seconds as `docs/python.md` states: the first accepted sample starts the stream; each
/// later one is pushed with `dt = T(t − t_last + carry)`, `t_last` the last accepted timestamp, the carry
/// (f64) what rounding to `T` left out.
fn timed<T: Real, S: Scheme<T>, I: InputModel<T>, Z: Stabilizer, A: Accumulator<T>>(
    p: Propagator<T, S, I, Z, A>,
    samples: &[I::Sample],
    t: &[f64],
) -> Run<T> {
    let mut last: Option<f64> = None;
    let mut carry = 0.0_f64;
    record(p, samples.iter().zip(t), |p, (s, &tk)| {
        let accepted = match last {
            None => tk.is_finite() && p.start(*s).is_ok(),
            Some(tl) if tk.is_finite() && tk > tl => {
                let exact = tk - tl + carry;
                let dt = T::from_f64(exact);
                let ok = p.push(*s, dt).is_ok();
                if ok {
                    carry = exact - dt.to_f64();
                }
                ok
            }
            Some(_) => false,
        };
        if accepted {
            last = Some(tk);
        }
        !accepted
    })
}

/// The recommended configuration (ExpMap, History, FirstOrder) from the identity.
fn recommended<T: Real>() -> Propagator<T, ExpMap, History<T>, FirstOrder> {
    Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder).unwrap()
}

fn samples<T: Real, X: FromRow<T>>(gyr: &[[f64; 3]]) -> Vec<X> {
    gyr.iter().map(|r| X::from_row(*r)).collect()
}

fn q0<T: Real>() -> Quat<T> {
    Quat::new(
        T::from_f64(0.9),
        T::from_f64(0.1),
        T::from_f64(-0.3),
        T::from_f64(0.2),
    )
}

trait Bytes {
    fn bytes(self) -> Vec<u8>;
}
impl Bytes for f32 {
    fn bytes(self) -> Vec<u8> {
        self.to_le_bytes().to_vec()
    }
}
impl Bytes for f64 {
    fn bytes(self) -> Vec<u8> {
        self.to_le_bytes().to_vec()
    }
}

struct Writer {
    dir: PathBuf,
    json: String,
}

impl Writer {
    /// Writes one case: `options` is the JSON object of `quatprop.integrate`'s keyword arguments.
    fn case<T: Real + Bytes>(
        &mut self,
        name: &str,
        options: &str,
        inputs: &str,
        (q, mask): Run<T>,
        bias: Option<String>,
    ) {
        let q: Vec<u8> = q
            .iter()
            .flat_map(|q| [q.w, q.x, q.y, q.z])
            .flat_map(Bytes::bytes)
            .collect();
        fs::write(self.dir.join(format!("{name}.q")), q).expect("write q");
        fs::write(
            self.dir.join(format!("{name}.mask")),
            mask.iter().map(|&m| u8::from(m)).collect::<Vec<_>>(),
        )
        .expect("write mask");
        let refused: Vec<String> = mask
            .iter()
            .enumerate()
            .filter(|(_, &m)| m)
            .map(|(k, _)| k.to_string())
            .collect();
        let sep = if self.json.is_empty() { "" } else { ",\n" };
        let _ = write!(
            self.json,
            "{sep}  {{\"name\": \"{name}\", \"inputs\": \"{inputs}\", \"options\": {options}, \"refused\": [{}]{}}}",
            refused.join(", "),
            bias.map_or(String::new(), |b| format!(", \"bias\": {b}")),
        );
    }
}

fn main() {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "tests/data/reference".into()),
    );
    fs::create_dir_all(&dir).expect("create the output directory");
    let (gyr, t, gyr_bad, t_bad, ticks) = inputs();
    let mut raw = Vec::new();
    for r in gyr.iter() {
        raw.extend(r.iter().flat_map(|v| v.to_le_bytes()));
    }
    raw.extend(t.iter().flat_map(|v| v.to_le_bytes()));
    for r in gyr_bad.iter() {
        raw.extend(r.iter().flat_map(|v| v.to_le_bytes()));
    }
    raw.extend(t_bad.iter().flat_map(|v| v.to_le_bytes()));
    fs::write(dir.join("inputs.f64"), raw).expect("write inputs");
    fs::write(
        dir.join("ticks.u32"),
        ticks
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<_>>(),
    )
    .expect("write ticks");
    fs::write(
        dir.join("rest.f64"),
        rest_inputs()
            .iter()
            .flat_map(|r| r.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
    )
    .expect("write rest");
    let deltas: Vec<[f64; 3]> = gyr.iter().map(|r| r.map(|v| v * PERIOD)).collect();

    let mut w = Writer {
        dir: dir.clone(),
        json: String::new(),
    };
    let fx = "\"dt\": 0.001";
    // Each case below is written out as a Rust user writes it, with its own propagator type (scheme, input
    // model and stabilizer as static types), options and inputs: so their calls share a shape.

    // The recommended configuration, both precisions.
    let s32 = samples::<f32, GyroSample<f32>>(&gyr);
    let s64 = samples::<f64, GyroSample<f64>>(&gyr);
    let p = recommended();
    w.case(
        "expmap_history_f32",
        &format!("{{{fx}, \"precision\": \"f32\"}}"),
        "gyr",
        fixed(p, &s32),
        None,
    );
    let p = recommended();
    w.case(
        "expmap_history_f64",
        &format!("{{{fx}, \"precision\": \"f64\"}}"),
        "gyr",
        fixed(p, &s64),
        None,
    );
    // RK4 on held rates, normalized, compensated, from q0.
    let p = Propagator::new(q0(), Rk4, Hold, Normalize)
        .unwrap()
        .with_accumulator(Kahan::new());
    w.case(
        "rk4_hold_kahan_f32",
        &format!("{{{fx}, \"precision\": \"f32\", \"scheme\": \"rk4\", \"input\": \"hold\", \"stabilizer\": \"normalize\", \"accumulator\": \"kahan\", \"q0\": [0.9, 0.1, -0.3, 0.2]}}"),
        "gyr",
        fixed(p, &s32),
        None,
    );
    // Timestamps in seconds.
    let p = Propagator::new(Quat::IDENTITY, Magnus4, GaussPoints::new(), Every(7)).unwrap();
    w.case(
        "magnus4_gauss_every7_t_f64",
        "{\"t\": true, \"precision\": \"f64\", \"scheme\": \"magnus4\", \"input\": \"gauss_points\", \"stabilizer\": \"every:7\"}",
        "gyr",
        timed(p, &s64, &t),
        None,
    );
    let p = Propagator::new(Quat::IDENTITY, Cf4, TwiceRate::new(), Off)
        .unwrap()
        .with_accumulator(Kahan::new());
    w.case(
        "cf4_twice_off_kahan_t_f32",
        "{\"t\": true, \"precision\": \"f32\", \"scheme\": \"cf4\", \"input\": \"twice_rate\", \"stabilizer\": \"off\", \"accumulator\": \"kahan\"}",
        "gyr",
        timed(p, &s32, &t),
        None,
    );
    // The sensor's ticks (wrapping 32-bit counter at 1 MHz).
    let p = Propagator::new(Quat::IDENTITY, Rk5, History::new(), FirstOrder).unwrap();
    w.case(
        "rk5_history_ticks_f64",
        "{\"ticks\": true, \"tick_hz\": 1000000.0, \"precision\": \"f64\", \"scheme\": \"rk5\"}",
        "gyr",
        ticked(p, &s64, &ticks),
        None,
    );
    // Delta angles with a three-sample coning correction.
    let d32 = samples::<f32, DeltaAngle<f32>>(&deltas);
    let p = Propagator::new(
        Quat::IDENTITY,
        ExpMap,
        DeltaAngles::new(ThreeSample),
        Normalize,
    )
    .unwrap();
    w.case(
        "expmap_delta3_f32",
        &format!("{{{fx}, \"precision\": \"f32\", \"input\": \"delta_angles\", \"coning\": \"three_sample\", \"stabilizer\": \"normalize\"}}"),
        "deltas",
        fixed(p, &d32),
        None,
    );
    // Refused samples (NaN, duplicate and backward timestamps, a spike), mask mode.
    let b32 = samples::<f32, GyroSample<f32>>(&gyr_bad);
    let b64 = samples::<f64, GyroSample<f64>>(&gyr_bad);
    let p = Propagator::new(Quat::IDENTITY, Rk4, Linear::new(), FirstOrder).unwrap();
    w.case(
        "rk4_linear_bad_t_f32",
        "{\"t\": true, \"precision\": \"f32\", \"scheme\": \"rk4\", \"input\": \"linear\", \"on_refused\": \"mask\"}",
        "bad",
        timed(p, &b32, &t_bad),
        None,
    );
    let p = recommended();
    w.case(
        "expmap_history_bad_f64",
        &format!("{{{fx}, \"precision\": \"f64\", \"on_refused\": \"mask\"}}"),
        "bad",
        fixed(p, &b64),
        None,
    );
    let p = Propagator::new(Quat::IDENTITY, Rk3, Hold, FirstOrder).unwrap();
    w.case(
        "rk3_hold_bad_f64",
        &format!("{{{fx}, \"precision\": \"f64\", \"scheme\": \"rk3\", \"input\": \"hold\", \"on_refused\": \"mask\"}}"),
        "bad",
        fixed(p, &b64),
        None,
    );
    // The front end: an axis remap and a bias estimator (windows of 0.05 s: 50 samples), as Python
    // builds it from seconds; a measured alignment matrix and a fixed bias.
    let remap = AxisRemap::PyNxPz;
    let mut est = BiasEstimator::<f32>::new(0.05, PERIOD, 0.9).unwrap();
    assert_eq!(
        Ok(est),
        BiasEstimator::from_samples(50, PERIOD, 0.9),
        "0.05 s at 1 kHz is 50 samples"
    );
    let fe: Vec<GyroSample<f32>> = s32
        .iter()
        .map(|s| {
            let s = remap.apply(*s);
            est.update(s).unwrap_or(s)
        })
        .collect();
    assert!(
        est.is_learned(),
        "the estimator should learn in this stream"
    );
    let p = recommended();
    w.case(
        "frontend_remap_estimator_f32",
        &format!("{{{fx}, \"precision\": \"f32\", \"alignment\": \"PyNxPz\", \"bias\": {{\"window\": 0.05, \"gate\": 0.9}}}}"),
        "gyr",
        fixed(p, &fe),
        Some(json3(est.bias())),
    );
    // The estimator at rest: a step followed, a slow turn kept; every parameter the Python class has
    // that the stream can take without accelerations (drift, the noise density, a start with its sigma).
    let rest = rest_inputs();
    let r64 = samples::<f64, GyroSample<f64>>(&rest);
    let r32 = samples::<f32, GyroSample<f32>>(&rest);
    let density = REST_NOISE / 3.0_f64.sqrt() * PERIOD.sqrt();
    let noise = GyroNoise::new(density, 0.0).unwrap();
    let mut est = BiasEstimator::<f64>::new(0.05, PERIOD, 0.05)
        .unwrap()
        .with_drift(1e-3)
        .unwrap()
        .with_noise(&noise)
        .unwrap();
    let fe: Vec<GyroSample<f64>> = r64.iter().map(|s| est.update(*s).unwrap_or(*s)).collect();
    // The step at rest (sample 520) followed; the turn (from sample 900) not taken for bias.
    let stepped = Vec3::new(0.015, -0.007, 0.001);
    assert!((est.bias() - stepped).norm() < 5e-4, "{:?}", est.bias());
    let p = recommended();
    w.case(
        "estimator_rest_drift_noise_f64",
        &format!("{{{fx}, \"precision\": \"f64\", \"bias\": {{\"window\": 0.05, \"gate\": 0.05, \"drift\": 0.001, \"noise_density\": {density:?}}}}}"),
        "rest",
        fixed(p, &fe),
        Some(json3(est.bias())),
    );
    let start = Vec3::new(0.0105_f32, -0.0075, 0.0045);
    let mut est = BiasEstimator::<f32>::new(0.05, PERIOD, 0.05)
        .unwrap()
        .with_initial(start, 1e-3)
        .unwrap();
    let fe: Vec<GyroSample<f32>> = r32.iter().map(|s| est.update(*s).unwrap_or(*s)).collect();
    assert!(
        (est.bias().to_f64() - stepped).norm() < 5e-4,
        "{:?}",
        est.bias()
    );
    let p = Propagator::new(Quat::IDENTITY, Rk4, Linear::new(), FirstOrder).unwrap();
    w.case(
        "estimator_rest_initial_rk4_f32",
        &format!("{{{fx}, \"precision\": \"f32\", \"scheme\": \"rk4\", \"input\": \"linear\", \"bias\": {{\"window\": 0.05, \"gate\": 0.05, \"initial\": {}, \"initial_sigma\": 0.001}}}}", json3(start)),
        "rest",
        fixed(p, &fe),
        Some(json3(est.bias())),
    );
    let rq = Quat::<f64>::from_euler_zyx(EulerZyx {
        yaw: 0.3,
        pitch: -0.2,
        roll: 0.1,
    });
    let m = rq.to_rotation_matrix();
    let align = Alignment::from_matrix(m).unwrap();
    let bias = FixedBias::new(Vec3::new(0.01, -0.02, 0.005)).unwrap();
    let fe: Vec<GyroSample<f64>> = s64.iter().map(|s| bias.apply(align.apply(*s))).collect();
    let p = Propagator::new(Quat::IDENTITY, Rk3, History::new(), FirstOrder).unwrap();
    let mut matrix = String::from("[");
    for (i, row) in m.iter().enumerate() {
        let _ = write!(
            matrix,
            "{}[{:?}, {:?}, {:?}]",
            if i > 0 { ", " } else { "" },
            row[0],
            row[1],
            row[2]
        );
    }
    matrix.push(']');
    w.case(
        "frontend_matrix_bias_t_f64",
        &format!("{{\"t\": true, \"precision\": \"f64\", \"scheme\": \"rk3\", \"alignment\": {matrix}, \"bias\": [0.01, -0.02, 0.005]}}"),
        "gyr",
        timed(p, &fe, &t),
        None,
    );

    let json = format!(
        "{{\"n\": {N}, \"period\": {PERIOD:?}, \"cases\": [\n{}\n]}}\n",
        w.json
    );
    fs::write(Path::new(&dir).join("cases.json"), json).expect("write cases.json");
    println!("wrote {}", dir.display());
}
