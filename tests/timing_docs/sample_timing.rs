use quatprop::frontend::{FixedPeriod, SampleTiming};
use quatprop::input::{coning::OnePlusPrevious, DeltaAngles};
use quatprop::{scheme::ExpMap, stabilize::FirstOrder};
use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};

/// The sample period (s): 1 kHz.
const PERIOD: f64 = 1.0e-3;
/// The gyro's group delay (s): its low-pass filter's, from the datasheet.
const DELAY: f64 = 2.0e-3;

/// The body's yaw (rad) at time `t` (s): at rest, then from t = 0 an angular acceleration of 2 rad/s².
fn yaw_at(t: f64) -> f64 {
    if t > 0.0 {
        t * t
    } else {
        0.0
    }
}

fn main() -> Result<(), Error> {
    // The sample stamped t is the mean rate (rad/s) over the interval before it, 2 ms late: over
    // [t − 3 ms, t − 2 ms].
    let timing = SampleTiming::interval_mean().with_group_delay(DELAY as f32)?;
    let mut period = FixedPeriod::<f32>::new(PERIOD)?;
    // Delta angles: one increment per update, its coning correction from the increment before.
    let input = DeltaAngles::new(OnePlusPrevious);
    let mut p = Propagator::new(Quat::IDENTITY, ExpMap, input, FirstOrder)?;
    let mut now = Quat::IDENTITY;
    for k in 1..=1000 {
        // The end of the interval this sample measures (s), and the mean rate over it (rad/s).
        let t = f64::from(k) * PERIOD - DELAY;
        let mean = (yaw_at(t) - yaw_at(t - PERIOD)) / PERIOD;
        let sample = GyroSample::new(Vec3::new(0.0, 0.0, mean as f32));
        // dt (s), and rate × dt: the interval's exact angle (rad).
        let dt = period.next_dt();
        p.push(timing.increment(sample, dt), dt)?;
        // The propagator holds the attitude 2 ms ago; the one at the sample's stamp is carried forward
        // by the group delay at the sample's rate (p itself is not changed).
        now = timing.ahead(p.attitude(), sample.rate);
    }
    // The yaw (rad), read in f64.
    let yaw = |q: Quat<f32>| q.to_f64().to_euler_zyx().yaw;
    // At t = 1 s the propagator has the yaw at 0.998 s (1 rad less 4.0 mrad) to f32 round-off ...
    assert!((yaw(p.attitude()) - yaw_at(1.0 - DELAY)).abs() < 1e-6);
    // ... and carried forward, the yaw at 1 s, short by τ² + τ·dt = 6 µrad (the rate grew over the delay).
    assert!((yaw(now) - 1.0).abs() < 1e-5, "{}", yaw(now));
    Ok(())
}

#[test]
fn runs() -> Result<(), Error> {
    main()
}
