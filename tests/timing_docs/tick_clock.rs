use quatprop::frontend::TickClock;
use quatprop::{Error, GyroSample, Propagator, Quat, Vec3};

fn main() -> Result<(), Error> {
    // The gyro stamps each sample with a free-running 32-bit counter of 1 µs ticks (1 MHz), which wraps
    // every 2³² µs (71.6 min). Samples every 1 ms (1 kHz) for 2 s, starting 0.5 s before the counter wraps;
    // the sample due at 1 s was lost (a FIFO overrun) and the one at 1.5 s was read twice.
    let start = u32::MAX - 499_999;
    let stamps = (0..=2000_u32)
        .filter(|&ms| ms != 1000)
        .flat_map(|ms| std::iter::repeat_n(ms, 1 + usize::from(ms == 1500)))
        .map(|ms| start.wrapping_add(ms * 1000));
    let rate = GyroSample::new(Vec3::new(0.0, 0.0, 1.0_f32)); // rad/s: 1 rad/s about body z

    let mut clock = TickClock::<f32>::new(1.0e6, 32)?; // ticks per second, counter width (bits)
    let mut p = Propagator::recommended(Quat::IDENTITY)?;
    let mut refused = 0;
    for stamp in stamps {
        // `advance` gives the dt without moving the clock: it moves only when the sample is taken, so a
        // refused sample's interval goes into the next dt (`push_burst_timed` does this for a FIFO burst).
        let taken = clock.advance(stamp).and_then(|(next, dt)| {
            match dt {
                None => p.start(rate)?, // the first stamp starts the clock: no interval before it
                Some(dt) => p.push(rate, dt)?, // s: ticks since the last accepted stamp × 1 µs
            }
            Ok(next)
        });
        match taken {
            Ok(next) => clock = next,
            Err(_) => refused += 1, // here the repeated stamp: Error::TimestampNotIncreasing
        }
    }
    // The lost sample is a gap: an interval over 1.5 times the one before.
    assert_eq!((refused, clock.gaps()), (1, 1));
    // 2 s from the first stamp to the last, across the wrap and the lost sample: 2 rad. A fixed 1 ms per
    // sample taken would have counted 1.999 s.
    let yaw = p.attitude().to_f64().to_euler_zyx().yaw; // rad
    assert!((yaw - 2.0).abs() < 1e-6, "{yaw}");
    Ok(())
}

#[test]
fn runs() -> Result<(), Error> {
    main()
}
