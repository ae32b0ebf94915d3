//! The MPU-6050 driver against scripted I²C transactions: register sequence, byte order, scaling at each
//! full scale, the saturation flag, bus errors surfaced as errors, and saturation counting in the propagator.

use embedded_hal::i2c::ErrorKind;
use embedded_hal_mock::eh1::i2c::{Mock, Transaction};
use quatprop::gyro::{GyroError, GyroRange, Mpu6050, Mpu6050Model};
use quatprop::input::{Hold, Linear};
use quatprop::scheme::Rk4;
use quatprop::stabilize::FirstOrder;
use quatprop::{GyroSample, Propagator, Quat, Vec3};

const ADDR: u8 = 0x68;

fn init(who: u8, fs_sel: u8) -> Vec<Transaction> {
    vec![
        Transaction::write_read(ADDR, vec![0x75], vec![who]),
        Transaction::write(ADDR, vec![0x6B, 0x01]),
        Transaction::write(ADDR, vec![0x1B, fs_sel << 3]),
    ]
}

#[test]
fn init_reads_who_am_i_wakes_and_sets_range() {
    for (range, fs) in [
        (GyroRange::Dps250, 0),
        (GyroRange::Dps500, 1),
        (GyroRange::Dps1000, 2),
        (GyroRange::Dps2000, 3),
    ] {
        let mut bus = Mock::new(&init(0x70, fs));
        let g = Mpu6050::new(bus.clone(), ADDR, range).unwrap();
        assert_eq!(g.model(), Mpu6050Model::Mpu6500);
        assert_eq!(g.range(), range);
        bus.done();
    }
}

#[test]
fn unknown_device_is_refused() {
    let mut bus = Mock::new(&[Transaction::write_read(ADDR, vec![0x75], vec![0x12])]);
    assert_eq!(
        Mpu6050::new(bus.clone(), ADDR, GyroRange::Dps2000).unwrap_err(),
        GyroError::UnknownDevice(0x12)
    );
    bus.done();
}

#[test]
fn burst_read_is_big_endian_and_scaled_to_rad_per_second() {
    let mut t = init(0x68, 3);
    // x = +1640 counts (0x0668) = 100 °/s at ±2000 °/s; y = −164 (0xFF5C) = −10 °/s; z = 0.
    t.push(Transaction::write_read(
        ADDR,
        vec![0x43],
        vec![0x06, 0x68, 0xFF, 0x5C, 0x00, 0x00],
    ));
    let mut bus = Mock::new(&t);
    let mut g = Mpu6050::new(bus.clone(), ADDR, GyroRange::Dps2000).unwrap();
    let s = g.read().unwrap();
    let deg = core::f32::consts::PI / 180.0;
    assert!((s.rate.x - 100.0 * deg).abs() < 1e-6, "{}", s.rate.x);
    assert!((s.rate.y + 10.0 * deg).abs() < 1e-6, "{}", s.rate.y);
    assert_eq!(s.rate.z, 0.0);
    assert!(!s.saturated);
    bus.done();
}

#[test]
fn scale_factors_match_the_datasheet_sensitivities() {
    // One LSB in rad/s at each range: (π/180)/sensitivity.
    for (range, lsb) in [
        (GyroRange::Dps250, 131.0_f64),
        (GyroRange::Dps500, 65.5),
        (GyroRange::Dps1000, 32.8),
        (GyroRange::Dps2000, 16.4),
    ] {
        let s = Mpu6050::<Mock>::convert([1000, 0, 0], range);
        let want = 1000.0 / lsb * core::f64::consts::PI / 180.0;
        assert!((s.rate.x as f64 - want).abs() < 1e-6 * want, "{range:?}");
    }
}

#[test]
fn full_scale_on_any_axis_flags_saturation() {
    for raw in [[i16::MAX, 0, 0], [0, i16::MIN, 0], [0, 0, i16::MAX]] {
        assert!(
            Mpu6050::<Mock>::convert(raw, GyroRange::Dps2000).saturated,
            "{raw:?}"
        );
    }
    assert!(
        !Mpu6050::<Mock>::convert([i16::MAX - 1, i16::MIN + 1, 0], GyroRange::Dps2000).saturated
    );
}

#[test]
fn bus_errors_are_errors_not_panics() {
    let mut bus = Mock::new(&[
        Transaction::write_read(ADDR, vec![0x75], vec![0x68]).with_error(ErrorKind::Other)
    ]);
    assert_eq!(
        Mpu6050::new(bus.clone(), ADDR, GyroRange::Dps250).unwrap_err(),
        GyroError::Bus(ErrorKind::Other)
    );
    bus.done();
    let mut t = init(0x68, 0);
    t.push(Transaction::write_read(ADDR, vec![0x43], vec![0; 6]).with_error(ErrorKind::Other));
    let mut bus = Mock::new(&t);
    let mut g = Mpu6050::new(bus.clone(), ADDR, GyroRange::Dps250).unwrap();
    assert_eq!(g.read().unwrap_err(), GyroError::Bus(ErrorKind::Other));
    bus.done();
}

#[test]
fn saturated_samples_are_integrated_and_counted() {
    let clipped = Mpu6050::<Mock>::convert([i16::MAX, 0, 0], GyroRange::Dps2000);
    assert!(clipped.saturated);
    let full_scale = clipped.rate.x; // 2000 °/s · 32767/32768 ≈ 34.9 rad/s
    let fine = GyroSample::new(Vec3::new(0.1, 0.0, 0.0));
    // Linear input: fine (starts), clipped (a step), fine (a step): the clipped sample is counted once,
    // and integrated in both steps it bounds.
    let mut p = Propagator::new(Quat::<f32>::IDENTITY, Rk4, Linear::new(), FirstOrder).unwrap();
    p.push(fine, 1e-3).unwrap();
    p.push(clipped, 1e-3).unwrap();
    p.push(fine, 1e-3).unwrap();
    assert_eq!((p.saturated_samples(), p.steps()), (1, 2));
    // Integrated, not dropped: the attitude moved about x by the two trapezoids, (0.1 + 34.9)·1e-3 rad.
    let angle = 2.0 * p.attitude().x.atan2(p.attitude().w);
    let want = (0.1 + full_scale) * 1e-3;
    assert!((angle - want).abs() < 1e-5, "{angle} vs {want}");
    // Hold input: each clipped sample is a step of its own, counted.
    let mut h = Propagator::new(Quat::<f32>::IDENTITY, Rk4, Hold, FirstOrder).unwrap();
    h.push(clipped, 1e-3).unwrap();
    h.push(fine, 1e-3).unwrap();
    h.push(clipped, 1e-3).unwrap();
    assert_eq!((h.saturated_samples(), h.steps()), (2, 3));
    // A refused sample counts nothing, even flagged as saturated.
    let nan = GyroSample {
        rate: Vec3::new(f32::NAN, 0.0, 0.0),
        saturated: true,
    };
    let before = p;
    assert!(p.push(nan, 1e-3).is_err());
    assert_eq!(p, before);
    assert_eq!(p.saturated_samples(), 1);
}
