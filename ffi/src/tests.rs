//! Host tests: the state's encoding fits its block; any changed byte is caught before anything is decoded;
//! the block's CRC-32C catches every error of up to 4 bits (all of them tried), every burst of up to 32 bits
//! and every error within two bytes, and no random damage passes it. (The header test is the crate
//! `header/`.)

use super::*;
use quatprop::frontend::{
    Alignment, Aux, BiasEstimator, Calibration, CountScale, FixedPeriod, TickClock,
};
use quatprop::Vec3;

/// The largest state: delta angles with the five-sample correction, the float-float accumulator, and every
/// front-end part (count scale, a matrix alignment, the bias estimator, period and clock), after samples.
fn largest() -> state::Inner {
    let config = quatprop_config_t {
        q0: Quat::new(0.5, 0.5, 0.5, 0.5).into(),
        scheme: QUATPROP_SCHEME_CF4,
        stabilizer: QUATPROP_STABILIZER_EVERY,
        every: u32::MAX,
        input: QUATPROP_INPUT_DELTA_ANGLES,
        coning: QUATPROP_CONING_FIVE_SAMPLE,
        accumulator: QUATPROP_ACCUMULATOR_FLOAT_FLOAT,
    };
    let mut inner = state::Inner::new(&config).unwrap();
    let r = [[0.0, 0.6, 0.8], [-1.0, 0.0, 0.0], [0.0, -0.8, 0.6]];
    inner.front.scale = Some(CountScale::full_scale_dps(2000.0).unwrap());
    inner.front.alignment = Some(Alignment::from_matrix(r).unwrap());
    let m = [[1.0, 0.01, -0.02], [0.003, 1.0, 0.01], [-0.01, 0.02, 1.0]];
    let cal = Calibration::new(Vec3::new(0.01, -0.02, 0.03), Vec3::new(1.01, 0.99, 1.02), m);
    inner.front.calibration = Some(cal.unwrap());
    // The estimator with every option and every optional part of its state present: a level waiting to
    // be confirmed, the temperature line, the window's acceleration sums and reference, a window half
    // summed (windows of 16 samples, blocks of 2).
    let mut est = BiasEstimator::from_samples(16, 1.0e-3, 0.05)
        .and_then(|e| e.with_accel_gate(0.5))
        .and_then(|e| e.with_temperature_model(1.0))
        .and_then(|e| e.with_drift(1.0e-4))
        .unwrap();
    for k in 0..37 {
        let b = if k < 16 { 0.0 } else { 0.01 };
        let n = if k % 2 == 0 { 1e-4 } else { -1e-4 };
        let aux = Aux {
            accel: Some(Vec3::new(0.1 + n, 0.2 - n, 9.8 + n)),
            temperature: Some(25.0 + 0.1 * k as f32),
        };
        est.update_with(GyroSample::new(Vec3::new(b + n, -b - n, b + n)), aux)
            .unwrap();
    }
    inner.front.bias = Bias::Estimator(est);
    inner.front.period = Some(FixedPeriod::new(1.0e-3).unwrap());
    inner.front.clock = Some(TickClock::new(1.0e6, 32).unwrap());
    inner
}

#[test]
fn the_largest_state_fits_its_block_with_room() {
    let inner = largest();
    let mut buf = [0u8; 1024];
    let len = postcard::to_slice(&inner, &mut buf).unwrap().len();
    // Integers are varints: the counters (three u64, 1 → 10 bytes) and up to fourteen u32 fields (pending,
    // the estimator's eight and the clock's counts, 1 → 5 bytes) can grow.
    let worst = len + 3 * 9 + 14 * 4;
    println!("encoded state: {len} bytes, at most {worst} of {PAYLOAD}");
    assert!(worst <= PAYLOAD, "{worst} > {PAYLOAD}");
}

#[test]
fn a_state_round_trips_and_any_changed_byte_is_caught() {
    let b = encode(&largest()).unwrap();
    assert!(load(&b).is_ok());
    let mut caught = 0;
    for i in 0..QUATPROP_STATE_SIZE {
        for flip in [0x01u8, 0x80, 0xff] {
            let mut c = b;
            c[i] ^= flip;
            let expected = if (TAG..TAG + 4).contains(&i) {
                S::QUATPROP_NOT_INITIALIZED
            } else {
                S::QUATPROP_CORRUPTED_STATE
            };
            assert_eq!(load(&c).err(), Some(expected), "byte {i} ^ {flip:#x}");
            caught += 1;
        }
    }
    assert_eq!(caught, 3 * QUATPROP_STATE_SIZE);
}

/// The step-angle bounds the header states for each scheme are the core's.
#[test]
fn the_header_states_each_schemes_step_angle_bound() {
    use quatprop::scheme::SchemeKind;
    let src = include_str!("lib.rs");
    let consts = [
        "EULER", "RK2", "RK3", "RK4", "RK5", "EXPMAP", "MAGNUS4", "CF4",
    ];
    for (kind, name) in SchemeKind::ALL.into_iter().zip(consts) {
        let decl = format!("pub const QUATPROP_SCHEME_{name}: u32");
        let at = src.find(&decl).expect("constant");
        // The doc comment right above the declaration.
        let doc: String = src[..at]
            .lines()
            .rev()
            .take_while(|l| l.starts_with("///"))
            .collect();
        let limit = kind.information().step_angle_limit;
        let stated = if limit.is_finite() {
            format!("{limit:.3}")
        } else {
            "No step-angle bound".to_string()
        };
        assert!(doc.contains(&stated), "{name}: {stated} not in {doc:?}");
    }
}

/// The C default is the Rust one (a `#define` in the header cannot name the Rust constant).
#[test]
fn the_default_drift_is_the_libraries() {
    assert_eq!(
        QUATPROP_DEFAULT_DRIFT,
        BiasEstimator::<f32>::DEFAULT_DRIFT as f32
    );
}

/// `quatprop_status_name` names every status value as the header does (16 and 17 were once missing).
#[test]
fn every_status_has_its_name() {
    use quatprop_status_t as S;
    let all = [
        S::QUATPROP_OK,
        S::QUATPROP_NON_FINITE_RATE,
        S::QUATPROP_NON_FINITE_STEP,
        S::QUATPROP_NON_POSITIVE_STEP,
        S::QUATPROP_STEP_ANGLE_BEYOND_STABILITY,
        S::QUATPROP_GAIN_BEYOND_STABILITY,
        S::QUATPROP_ZERO_QUATERNION,
        S::QUATPROP_NON_FINITE_QUATERNION,
        S::QUATPROP_INVALID_STABILIZER,
        S::QUATPROP_INVALID_GAIN,
        S::QUATPROP_NOT_A_ROTATION,
        S::QUATPROP_TIMESTAMP_NOT_INCREASING,
        S::QUATPROP_INVALID_CLOCK,
        S::QUATPROP_INVALID_ESTIMATOR,
        S::QUATPROP_NON_FINITE_RESULT,
        S::QUATPROP_UNKNOWN_ERROR,
        S::QUATPROP_INVALID_CALIBRATION,
        S::QUATPROP_NON_FINITE_AUX,
        S::QUATPROP_NULL_POINTER,
        S::QUATPROP_MISALIGNED_POINTER,
        S::QUATPROP_BAD_ENUM,
        S::QUATPROP_NOT_INITIALIZED,
        S::QUATPROP_WRONG_INPUT_KIND,
        S::QUATPROP_NOT_CONFIGURED,
        S::QUATPROP_BAD_ARGUMENT,
        S::QUATPROP_CORRUPTED_STATE,
    ];
    // Every variant is listed: the enum's source has as many.
    let src = include_str!("lib.rs");
    let body = &src[src.find("pub enum quatprop_status_t").unwrap()..];
    let body = &body[..body.find("\n}").unwrap()];
    let variants = body
        .lines()
        .filter(|l| l.trim_start().starts_with("QUATPROP_") && l.contains(" = "))
        .count();
    assert_eq!(variants, all.len());
    for s in all {
        // SAFETY: the name is a static NUL-terminated string.
        let name = unsafe { core::ffi::CStr::from_ptr(quatprop_status_name(s as i32)) };
        assert_eq!(name.to_str().unwrap(), format!("{s:?}"));
    }
    // SAFETY: as above.
    let unknown = unsafe { core::ffi::CStr::from_ptr(quatprop_status_name(18)) };
    assert_eq!(unknown.to_str().unwrap(), "unknown status");
}

mod calibration;
mod check;
