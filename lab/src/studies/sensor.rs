//! Sensor realism: the same scene seen through a gyro with white noise, bias, 16-bit counts, saturation at
//! full scale, dropped samples and sample-time jitter. Each configuration is scored twice: against the exact
//! motion (what the user gets) and against the same sensor stream integrated exactly (what the integrator
//! adds). The stream's exact integral: the cubic through the four samples around each interval at their true
//! times, integrated in f64 by Magnus-4 with 16 substeps per sample interval (checked against 8 in the report).

use crate::configs::{Config, Input, Peer, Stab};
use crate::args::Sweep;
use crate::report::Ctx;
use crate::rng::Rng;
use crate::sample::Sample;
use crate::scene::{attitude_error, gauss_step, Scene};
use crate::scenes;
use crate::study::{CsvFile, Study};
use crate::table::{self, cell, Csv, Table};
use quatprop::input::GaussPoints;
use quatprop::scheme::{Magnus4, SchemeKind};
use quatprop::stabilize::Normalize;
use quatprop::{Propagator, Quat, Vec3};
use serde::{Deserialize, Serialize};

/// Sensor realism (sub-command `sensor`; of the sweep's parameters it takes the first scene, the first
/// rate and the horizon).
pub struct Sensor;

impl Study for Sensor {
    type Args = Sweep;
    const NAME: &'static str = "sensor";
    const ABOUT: &'static str = "Sensor realism: noise, bias, 16-bit counts, saturation, dropped samples, dt jitter";
    const CSV: &'static [CsvFile] = &[CsvFile::table::<SensorRow>()];
    fn run(&self, ctx: &mut Ctx, sweep: &Sweep) {
        // Seconds of the scene: the full 5.37 s cost a fraction of a second.
        let horizon = sweep.horizon.unwrap_or(ctx.scale.pick(1.37, 5.37, 5.37));
        let catalogue = scenes::catalogue(sweep.horizon.unwrap_or(0.0).max(70.0));
        ctx.section("sensor realism", |c| sensor_study(c, &catalogue, sweep, horizon));
    }
}

// Field declarations with their units: alike in form only.

/// What the gyro does to the true rate. Rates in rad/s, times in s.
#[derive(Clone, Copy, Debug)]
pub struct SensorModel {
    pub name: &'static str,
    /// Rate noise density (rad/s/√Hz); per-sample σ = density · √(fs/2).
    pub noise_density: f64,
    /// Constant bias (rad/s).
    pub bias: Vec3<f64>,
    /// Full scale (rad/s): readings clip at ±full scale.
    pub full_scale: Option<f64>,
    /// Quantization to signed 16-bit counts over ±full scale (LSB = full scale / 32768).
    pub counts16: bool,
    /// Probability that a sample is lost (the next one arrives with the gap as its dt).
    pub drop: f64,
    /// Sample interval jitter: dt = h (1 + jitter·u), u uniform in [−1, 1]; timestamps are known.
    pub jitter: f64,
}

const IDEAL: SensorModel = SensorModel {
    name: "ideal (f32 samples)",
    noise_density: 0.0,
    bias: Vec3::new(0.0, 0.0, 0.0),
    full_scale: None,
    counts16: false,
    drop: 0.0,
    jitter: 0.0,
};

/// ±2000 °/s, the drone gyro's widest range.
const FS_2000: f64 = 2000.0 * core::f64::consts::PI / 180.0;
/// ±1000 °/s: a range the 2000 °/s roll exceeds (per axis), so readings clip.
const FS_1000: f64 = 1000.0 * core::f64::consts::PI / 180.0;

/// The sensor models of the study (MPU-6000-class numbers).
pub fn models() -> Vec<SensorModel> {
    let noise = 0.005f64.to_radians(); // 0.005 °/s/√Hz
    let bias = Vec3::new(0.5f64, -0.3, 0.2) * 1f64.to_radians(); // uncalibrated, ~0.6 °/s
    vec![
        IDEAL,
        SensorModel {
            name: "white noise 0.005 °/s/√Hz",
            noise_density: noise,
            ..IDEAL
        },
        SensorModel {
            name: "bias 0.6 °/s",
            bias,
            ..IDEAL
        },
        SensorModel {
            name: "16-bit counts, ±2000 °/s",
            full_scale: Some(FS_2000),
            counts16: true,
            ..IDEAL
        },
        SensorModel {
            name: "saturation at ±1000 °/s",
            full_scale: Some(FS_1000),
            ..IDEAL
        },
        SensorModel {
            name: "1% samples dropped",
            drop: 0.01,
            ..IDEAL
        },
        SensorModel {
            name: "dt jitter ±10%",
            jitter: 0.1,
            ..IDEAL
        },
        SensorModel {
            name: "all of the above (16-bit counts at ±1000 °/s)",
            noise_density: noise,
            bias,
            full_scale: Some(FS_1000),
            counts16: true,
            drop: 0.01,
            jitter: 0.1,
        },
    ]
}

/// A sensor stream: sample times and the readings as f32, plus what happened to it.
pub struct Stream {
    pub times: Vec<f64>,
    pub samples: Vec<Sample<f32>>,
    pub saturated: usize,
    pub dropped: usize,
}

pub fn sensor_stream(
    scene: &dyn Scene,
    m: &SensorModel,
    hz: f64,
    horizon: f64,
    seed: u64,
) -> Stream {
    let mut rng = Rng(seed);
    let h = 1.0 / hz;
    let sigma = m.noise_density * (0.5 * hz).sqrt();
    let (mut times, mut samples) = (Vec::new(), Vec::new());
    let (mut saturated, mut dropped) = (0, 0);
    let mut t = 0.0;
    let mut last_kept = 0.0;
    while t <= horizon {
        // The first sample is never dropped (it starts the stream).
        if !times.is_empty() && rng.uniform() < m.drop {
            dropped += 1;
        } else {
            let w = scene.rate(t) + m.bias;
            let mut r = [w.x, w.y, w.z];
            let mut clipped = false;
            for v in &mut r {
                *v += sigma * rng.normal();
                if let Some(fs) = m.full_scale {
                    if m.counts16 {
                        let lsb = fs / 32768.0;
                        *v = (*v / lsb).round().clamp(-32768.0, 32767.0) * lsb;
                        clipped |= (*v / lsb).abs() >= 32767.0;
                    } else if v.abs() >= fs {
                        *v = v.clamp(-fs, fs);
                        clipped = true;
                    }
                }
            }
            saturated += usize::from(clipped);
            let dt = (t - last_kept) as f32;
            samples.push(Sample {
                w: Vec3::<f32>::from_f64(Vec3::new(r[0], r[1], r[2])),
                dt,
            });
            times.push(t);
            last_kept = t;
        }
        t += h * (1.0 + m.jitter * (2.0 * rng.uniform() - 1.0));
    }
    Stream {
        times,
        samples,
        saturated,
        dropped,
    }
}

/// The rate the stream stands for at time t in sample interval k (t_k ≤ t ≤ t_k+1): the cubic through the four
/// samples around the interval at their true times (one-sided at the ends). Fourth order for a smooth rate, so
/// an ideal stream's own error is far below every integrator's; for a clipped, quantized or noisy stream it is
/// the natural continuous reading of the samples.
fn stream_rate(s: &Stream, k: usize, t: f64) -> Vec3<f64> {
    let n = s.times.len();
    let first = k.saturating_sub(1).min(n.saturating_sub(4));
    let idx = first..(first + 4).min(n);
    let mut w = Vec3::<f64>::ZERO;
    for i in idx.clone() {
        let mut l = 1.0;
        for j in idx.clone() {
            if j != i {
                l *= (t - s.times[j]) / (s.times[i] - s.times[j]);
            }
        }
        w += s.samples[i].w.to_f64() * l;
    }
    w
}

/// The stream integrated "exactly": [`stream_rate`] integrated in f64 by Magnus-4 with `sub` substeps per
/// sample interval; attitudes after each sample index in `at`.
fn stream_reference(q0: Quat<f64>, s: &Stream, at: &[usize], sub: usize) -> Vec<Quat<f64>> {
    let Ok(mut p) = Propagator::new(q0, Magnus4, GaussPoints::new(), Normalize) else {
        return vec![Quat::IDENTITY; at.len()];
    };
    let mut out = Vec::new();
    let mut k = 0;
    for &c in at {
        while k < c {
            let t0 = s.times[k];
            let tau = (s.times[k + 1] - t0) / sub as f64;
            for j in 0..sub {
                let a = t0 + j as f64 * tau;
                let _ = gauss_step(&mut p, |c| stream_rate(s, k, a + c * tau), tau);
            }
            k += 1;
        }
        out.push(p.attitude());
    }
    out
}

fn configs() -> Vec<Config> {
    let mut v = vec![
        Config::qp(SchemeKind::Euler, Stab::FirstOrder, Input::Hold),
        Config::qp(SchemeKind::Rk4, Stab::FirstOrder, Input::Linear),
        Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::Linear),
        Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, Input::History),
        Config::qp(SchemeKind::Magnus4, Stab::FirstOrder, Input::History),
    ];
    v.extend(Peer::ALL.iter().map(|&p| Config::Peer(p)));
    v
}

/// The label of the rows that describe the stream itself.
const STREAM_ROW: &str = "*the stream itself: its exact integral vs the motion*";

/// One configuration under one sensor model (or, with configuration [`STREAM_ROW`], the stream itself).
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SensorRow {
    pub sensor: String,
    pub configuration: String,
    /// Max attitude error against the same stream integrated exactly (rad; empty: not applicable).
    pub max_error_vs_stream_rad: Option<f64>,
    /// Max attitude error against the true motion (rad; empty: the configuration does not exist).
    pub max_error_vs_truth_rad: Option<f64>,
    pub refused_steps: u64,
    /// Samples of this sensor's stream that were saturated / dropped.
    pub saturated_samples: u64,
    pub dropped_samples: u64,
}
// A row type names its file and renders its table through the `Csv` and `Table` impls (alike in each).
impl Csv for SensorRow {
    const FILE: &'static str = "sensor_realism.csv";
}
impl Table for SensorRow {
    /// Configurations down, sensor models across; then the stream's own row and its sample counts.
    fn render(rows: &[Self]) -> String {
        let sensors = table::distinct(rows, |r| r.sensor.as_str());
        let mut configs = table::distinct(rows, |r| r.configuration.as_str());
        configs.retain(|c| *c != STREAM_ROW);
        let titles: Vec<String> = sensors.iter().map(|s| cell(s)).collect();
        let mut t = format!(
            "| configuration | {} |\n|---|{}\n",
            titles.join(" | "),
            "---|".repeat(sensors.len())
        );
        let get = |c: &str, s: &str| rows.iter().find(|r| r.configuration == c && r.sensor == s);
        for c in &configs {
            t += &format!("| {} |", cell(c));
            for s in &sensors {
                t += &match get(c, s) {
                    Some(SensorRow {
                        max_error_vs_stream_rad: Some(a),
                        max_error_vs_truth_rad: Some(b),
                        refused_steps,
                        ..
                    }) => {
                        if *refused_steps > 0 {
                            format!(" {a:.1e} / {b:.1e} | ({refused_steps} refused)")
                        } else {
                            format!(" {a:.1e} / {b:.1e} |")
                        }
                    }
                    _ => " – |".into(),
                };
            }
            t += "\n";
        }
        t += &format!("| {STREAM_ROW} |");
        for s in &sensors {
            t += &get(STREAM_ROW, s)
                .and_then(|r| r.max_error_vs_truth_rad)
                .map_or(" – |".into(), |e| format!(" {e:.2e} |"));
        }
        t += "\n| *samples saturated / dropped* |";
        for s in &sensors {
            t += &get(STREAM_ROW, s).map_or(" – |".into(), |r| {
                format!(" {} / {} |", r.saturated_samples, r.dropped_samples)
            });
        }
        t + "\n"
    }
}

fn sensor_study(ctx: &mut Ctx, scenes: &[Box<dyn Scene>], opt: &Sweep, horizon: f64) -> String {
    let key = opt.scenes.first().map_or("spin2000", String::as_str);
    let Some(scene) = scenes.iter().find(|s| s.key() == key) else {
        return format!("### Sensor realism\n\nNo scene {key}.\n");
    };
    let hz = opt.rates.first().copied().unwrap_or(1000) as f64;
    let configs = configs();
    let models = models();
    let mut rows = Vec::new();
    let mut ref_check = 0.0f64;
    for (mi, m) in models.iter().enumerate() {
        let s = sensor_stream(scene.as_ref(), m, hz, horizon, 0x5EED + mi as u64);
        let n = s.samples.len() - 1;
        let mut cps: Vec<usize> = (1..=32).map(|j| (j * n) / 32).collect();
        cps.dedup();
        let q0 = scene.attitude(0.0);
        let reference = stream_reference(q0, &s, &cps, 16);
        let coarse = stream_reference(q0, &s, &cps, 8);
        for (a, b) in reference.iter().zip(&coarse) {
            ref_check = ref_check.max(a.angle_to(*b));
        }
        let truth: Vec<Quat<f64>> = cps.iter().map(|&c| scene.attitude(s.times[c])).collect();
        let own = reference
            .iter()
            .zip(&truth)
            .map(|(a, b)| a.angle_to(*b))
            .fold(0.0, f64::max);
        let row = |configuration: String| SensorRow {
            sensor: m.name.into(),
            configuration,
            max_error_vs_stream_rad: None,
            max_error_vs_truth_rad: None,
            refused_steps: 0,
            saturated_samples: s.saturated as u64,
            dropped_samples: s.dropped as u64,
        };
        rows.push(SensorRow {
            max_error_vs_truth_rad: Some(own),
            ..row(STREAM_ROW.into())
        });
        for c in &configs {
            ctx.tick();
            let Ok(mut run) = c.build::<f32>(Quat::from_f64(q0), (1.0 / hz) as f32) else {
                rows.push(row(c.label()));
                continue;
            };
            let (mut from, mut vs_stream, mut vs_truth) = (0, 0.0f64, 0.0f64);
            for (j, &cp) in cps.iter().enumerate() {
                run.feed(&s.samples[from..=cp]);
                from = cp + 1;
                vs_stream = vs_stream.max(attitude_error(run.attitude(), reference[j]));
                vs_truth = vs_truth.max(attitude_error(run.attitude(), truth[j]));
            }
            let (refused, _) = run.refused();
            rows.push(SensorRow {
                max_error_vs_stream_rad: Some(vs_stream),
                max_error_vs_truth_rad: Some(vs_truth),
                refused_steps: refused,
                ..row(c.label())
            });
        }
    }
    let table = ctx.table(&rows);
    format!(
        "### Sensor realism: {} at {hz} Hz, f32\n\nMaximum attitude error over {horizon} s (32 checkpoints), \
         **against the same sensor stream integrated exactly / against the true motion** (rad). The stream's exact \
         integral takes the cubic through the four samples around each interval at their true times (fourth order: \
         for ideal samples it is the motion to the first row's second number's precision or better; f64 Magnus-4, \
         16 substeps per interval; 8 substeps agree to {ref_check:.1e} rad). Dropped samples arrive as a longer dt (nothing is \
         skipped by the integrator); jitter perturbs each interval by up to ±10% with known timestamps. The sample \
         history takes the samples at their true times (a cubic in Newton form under jitter and across a dropped \
         sample, still fourth order); only a gap (a dt more than 2.5 times the previous one, or less than its \
         inverse) restarts it, bridging that interval with a linear step over its true length, after which it \
         starts again at fourth order (its quadratic step corrects the linear one before it). `ahrs` has no \
         time argument (a fixed `sample_period`), so gaps and jitter are invisible to it. Noise and bias models are \
         MPU-6000 class; the 2000 °/s roll exceeds a ±1000 °/s range on the roll axis, so those readings clip.\n\n{table}\n\
         Reading: the first number is what the integrator adds to the sensor's own error; the second is what the \
         user gets. A scheme whose first number is far below the stream's own row costs nothing the sensor did not \
         already lose. CSV: `sensor_realism.csv`.\n",
        scene.name(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::Coning;

    #[test]
    fn stream_has_the_requested_statistics() {
        let m = SensorModel {
            noise_density: 0.01,
            drop: 0.05,
            jitter: 0.2,
            ..IDEAL
        };
        let s = sensor_stream(&crate::scenes::EarthRate, &m, 1000.0, 20.0, 7);
        let n = s.samples.len() + s.dropped;
        // ~20 000 samples; 5% dropped within 4σ of the binomial.
        let p = s.dropped as f64 / n as f64;
        assert!(
            (p - 0.05).abs() < 4.0 * (0.05 * 0.95 / n as f64).sqrt(),
            "{p}"
        );
        // Noise σ = 0.01·√500 per axis (Earth rate is negligible against it).
        let v: Vec<f64> = s.samples.iter().map(|x| x.w.x as f64).collect();
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
        assert!((sd / (0.01 * 500f64.sqrt()) - 1.0).abs() < 0.03, "{sd}");
        // Intervals: a kept sample's dt spans its gap; no interval below 0.8 h without a drop.
        let min = s.samples[1..].iter().map(|x| x.dt).fold(f32::MAX, f32::min);
        assert!(min >= 0.8e-3 * 0.9999, "{min}");
        // Time is consistent: the dts sum to the last sample's time.
        let total: f64 = s.samples[1..].iter().map(|x| x.dt as f64).sum();
        assert!((total - s.times[s.times.len() - 1]).abs() < 1e-5);
    }

    #[test]
    fn quantization_and_saturation_follow_the_full_scale() {
        let fs = 1.0;
        let m = SensorModel {
            full_scale: Some(fs),
            counts16: true,
            ..IDEAL
        };
        let s = sensor_stream(&Coning, &m, 1000.0, 2.0, 1);
        let lsb = fs / 32768.0;
        for x in &s.samples {
            for v in [x.w.x, x.w.y, x.w.z] {
                let c = v as f64 / lsb;
                assert!((c - c.round()).abs() < 1e-3 && c.abs() <= 32768.0, "{c}");
            }
        }
        // Coning's body rate reaches 2π·sin(0.3) = 1.86 rad/s on x and y: clipped at 1 rad/s.
        assert!(s.saturated > 0);
    }

    #[test]
    fn stream_reference_of_ideal_samples_converges_to_the_motion_at_fourth_order() {
        // Ideal samples of the coning motion: the cubic reading is fourth order, so halving h divides the
        // reference's own error by ~16.
        // Coarse rates, where truncation dominates the f32 samples' rounding.
        let err = |hz: f64| {
            let s = sensor_stream(&Coning, &IDEAL, hz, 1.0, 3);
            let n = s.times.len() - 1;
            let r = stream_reference(Coning.attitude(0.0), &s, &[n], 8)[0];
            r.angle_to(Coning.attitude(s.times[n]))
        };
        let (e1, e2) = (err(25.0), err(50.0));
        let order = (e1 / e2).log2();
        assert!(
            e1 < 1e-4 && (order - 4.0).abs() < 0.6,
            "{e1:e} {e2:e} order {order}"
        );
    }
}
