//! The calibration estimator (`quatprop::frontend::CalibrationEstimator<f32>`) for C: the gyro's 3×3 gain
//! and its residual bias, learned in motion from the accelerometer.
//!
//! Its state lives in a block of its own, `quatprop_calibration_estimator_t`, so that `quatprop_t` (its
//! size and its ABI) stays as it is: the estimator alone takes more than `quatprop_t`'s 1024 bytes (a 12×12
//! covariance and three 12-channel low-pass filters in `float`). The block is sealed as `quatprop_t` is
//! (`lib.rs`): zeros, the estimator encoded with postcard, a tag ("QCE1"), the encoding's length and a
//! CRC-32C of every byte before its last 4; a block the library did not seal is refused before anything is
//! decoded (`QUATPROP_NOT_INITIALIZED` without the tag, `QUATPROP_CORRUPTED_STATE` otherwise). A refused
//! call writes nothing.

use crate::state::{vec3, Fail};
use crate::{
    block, check, crc32c_update, init, open, put, quatprop_status_t, read, seal, sealed_sum,
    status, write, Sealed, S,
};
use core::mem::{align_of, size_of};
use quatprop::frontend::CalibrationEstimator;
use quatprop::{Error, GyroSample, Vec3};

// The block's constants and struct as `quatprop_t`'s in lib.rs, written out: cbindgen reads them as they
// stand (no macro) into the header.

/// `uint64_t` words in `quatprop_calibration_estimator_t`.
pub const QUATPROP_CALIBRATION_ESTIMATOR_WORDS: usize = 192;
/// Size of `quatprop_calibration_estimator_t` in bytes (same on every target): the estimator's encoding
/// (1120 bytes, 1143 at most: `tests/calibration.rs` measures both) and the 12 bytes of tag, length and
/// CRC, with about a quarter of the block to spare for a later version of the estimator.
pub const QUATPROP_CALIBRATION_ESTIMATOR_SIZE: usize = 1536;
/// Alignment of `quatprop_calibration_estimator_t` in bytes.
pub const QUATPROP_CALIBRATION_ESTIMATOR_ALIGN: usize = 8;

/// The default `motion_noise` of `quatprop_calibration_estimator_init` (rad/√s): the Rust
/// `CalibrationEstimator::DEFAULT_MOTION_NOISE` (0.1 °/√s × √3), the same `double`.
pub const QUATPROP_DEFAULT_MOTION_NOISE: f64 = 0.0030229989403903626;

/// The calibration estimator's opaque state. Allocate it anywhere (no heap needed), set it up with
/// `quatprop_calibration_estimator_init`; never read or write `_opaque` (a copy of a whole initialized
/// block is fine). 8-byte aligned.
#[repr(C)]
pub struct quatprop_calibration_estimator_t {
    /// Private.
    pub _opaque: [u64; QUATPROP_CALIBRATION_ESTIMATOR_WORDS],
}

type Estimator = CalibrationEstimator<f32>;

/// "QCE1": the tag `quatprop_calibration_estimator_init` writes (version 1 of this block).
pub(crate) const MAGIC: u32 = 0x5143_4531;

/// The block's layout is `quatprop_t`'s counted from its end: zeros, the encoding, zeros to `PAYLOAD`, the
/// tag `[PAYLOAD, PAYLOAD + 4)`, the length, the CRC-32C `[SUM, SIZE)`.
pub(crate) const PAYLOAD: usize = QUATPROP_CALIBRATION_ESTIMATOR_SIZE - 12;
/// Where the tag starts (the length follows it).
pub(crate) const TAG: usize = PAYLOAD;
/// Where the checksum starts.
pub(crate) const SUM: usize = QUATPROP_CALIBRATION_ESTIMATOR_SIZE - 4;
const _: () = assert!(TAG + 8 == SUM);

/// The block as bytes.
pub(crate) type Block = [u8; QUATPROP_CALIBRATION_ESTIMATOR_SIZE];

const _: () =
    assert!(size_of::<quatprop_calibration_estimator_t>() == QUATPROP_CALIBRATION_ESTIMATOR_SIZE);
const _: () =
    assert!(align_of::<quatprop_calibration_estimator_t>() == QUATPROP_CALIBRATION_ESTIMATOR_ALIGN);
const _: () =
    assert!(QUATPROP_CALIBRATION_ESTIMATOR_WORDS * 8 == QUATPROP_CALIBRATION_ESTIMATOR_SIZE);
const _: () = assert!(size_of::<Block>() == size_of::<quatprop_calibration_estimator_t>());
// The estimator fits its block: postcard writes each `f32` in its 4 bytes, arrays and structs with no
// prefix, an `Option` as one byte before its value (an `Option<u32>` takes 8 bytes in memory, at most 6
// encoded) and a `u32` in at most 5 bytes, so the encoding is at most the estimator's size in memory and a
// byte per bare `u32` (it has one; 16 allowed). `tests/calibration.rs` measures the encoding itself.
const _: () = assert!(size_of::<Estimator>() + 16 <= PAYLOAD);

/// The checksum a block must hold: the CRC-32C of its first `SUM` bytes (`lib.rs`'s `sealed_sum`, the
/// leading zeros run through the CRC here: no table of their registers for this size). Over these 12 256
/// bits CRC-32C still has Hamming distance 4 (`tests/calibration.rs`). Not inlined: one copy serves `load`
/// and `encode`.
#[inline(never)]
pub(crate) fn checksum(b: &Block) -> Option<u32> {
    sealed_sum(b, |zeros| b.get(..zeros).map(|z| crc32c_update(!0, z)))
}

/// The estimator a block holds, checked (`lib.rs`'s `open`).
pub(crate) fn load(b: &Block) -> Result<Estimator, quatprop_status_t> {
    open(b, MAGIC, checksum)
}

/// `est` as a sealed block.
pub(crate) fn encode(est: &Estimator) -> Result<Block, quatprop_status_t> {
    seal(est, MAGIC, checksum)
}

// SAFETY: `Block` is `[u8; QUATPROP_CALIBRATION_ESTIMATOR_SIZE]`, the size of the block (asserted).
unsafe impl Sealed for quatprop_calibration_estimator_t {
    type Bytes = Block;
}

/// Runs `f` on the estimator behind `e` and stores it back sealed if `f` succeeds; a refused call (a bad
/// block, or `f`'s error) writes nothing, so the block keeps its bytes.
///
/// # Safety
/// `e` must be NULL or point to a writable block that nothing else accesses during the call.
unsafe fn modify(
    e: *mut quatprop_calibration_estimator_t,
    f: impl FnOnce(&mut Estimator) -> Result<(), Error>,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    let mut est = match unsafe { block(e) }.and_then(load) {
        Ok(est) => est,
        Err(s) => return s,
    };
    if let Err(err) = f(&mut est) {
        return status(Fail::Core(err));
    }
    match encode(&est) {
        Ok(b) => {
            // SAFETY: checked by `block`; writable and exclusive per the contract.
            unsafe { put(e, &b) };
            S::QUATPROP_OK
        }
        Err(s) => s,
    }
}

/// The estimator behind `e`, read only.
///
/// # Safety
/// `e` must be NULL or point to a readable block.
unsafe fn view(e: *const quatprop_calibration_estimator_t) -> Result<Estimator, quatprop_status_t> {
    // SAFETY: forwarded contract.
    unsafe { block(e) }.and_then(load)
}

/// Sets up `est`: a calibration estimator for samples every `sample_period` s (finite, > 0) that starts
/// from no error, with the prior standard deviations of the scale factors (`sensitivity_sigma`,
/// dimensionless: 0.01 for a datasheet's ±1 %) and of the cross-axis terms (`misalignment_sigma`, rad:
/// 0.0087 for ±0.5°), each 0 to 0.05, and the measurement noise `motion_noise` (rad/√s, finite, > 0: the
/// density of the inclination drift the gyro did not cause, linear acceleration left after the low-pass;
/// larger trusts the accelerometer less and learns slower; `QUATPROP_DEFAULT_MOTION_NOISE` for the
/// default, tuned for a hand-held sensor). The residual bias starts as VQF's motion bias (0.5 °/s).
/// The Rust `CalibrationEstimator::with_motion_noise`: the same `double`s give the same bits.
/// `QUATPROP_NON_FINITE_STEP` / `QUATPROP_NON_POSITIVE_STEP` for a bad period, `QUATPROP_INVALID_ESTIMATOR`
/// for a bad sigma or noise. Any previous content of `est` is ignored; on error `est` is not written.
///
/// # Safety
/// `est` must be NULL or point to a writable `quatprop_calibration_estimator_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_calibration_estimator_init(
    est: *mut quatprop_calibration_estimator_t,
    sample_period: f64,
    sensitivity_sigma: f64,
    misalignment_sigma: f64,
    motion_noise: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        init(est, || {
            Estimator::with_motion_noise(
                sample_period,
                sensitivity_sigma,
                misalignment_sigma,
                motion_noise,
            )
            .map_err(|e| status(Fail::Core(e)))
            .and_then(|x| encode(&x))
        })
    }
}

/// One sample: the rate `rate[3]` (rad/s, before this estimator's correction; a bias measured at rest
/// taken out, if there is one: the residual bias it learns is clipped to ±2 °/s) and the accelerometer
/// `accel[3]` (the same axes; any unit, only its direction is used;
/// all zero: no reading, the rate still turns the estimator's shadow attitude) over `dt` s (finite and
/// positive, at most FLT_MAX; used in single precision; the low-pass filter is designed for the init's
/// period). `QUATPROP_NON_FINITE_RATE`, `QUATPROP_NON_FINITE_AUX` (accelerometer),
/// `QUATPROP_NON_FINITE_STEP`, `QUATPROP_NON_POSITIVE_STEP` for bad input, `QUATPROP_NON_FINITE_RESULT`
/// if the arithmetic overflows; on error nothing changes.
///
/// # Safety
/// `est` must be NULL or point to a `quatprop_calibration_estimator_t` not in use elsewhere; `rate` and
/// `accel` NULL or 3 readable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_calibration_estimator_update(
    est: *mut quatprop_calibration_estimator_t,
    rate: *const f32,
    accel: *const f32,
    dt: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract (each pointer checked for NULL and alignment before it is read).
    let (r, a) = match unsafe {
        (
            read(rate.cast::<[f32; 3]>()),
            read(accel.cast::<[f32; 3]>()),
        )
    } {
        (Ok(r), Ok(a)) => (r, a),
        (Err(e), _) | (_, Err(e)) => return e,
    };
    // SAFETY: forwarded contract.
    unsafe { modify(est, |x| update(x, vec3(r), vec3(a), dt as f32)) }
}

/// `CalibrationEstimator::update`, out of line.
#[inline(never)]
fn update(x: &mut Estimator, rate: Vec3<f32>, accel: Vec3<f32>, dt: f32) -> Result<(), Error> {
    x.update(rate, accel, dt)
}

/// The rate `rate_in[3]` (rad/s, finite: `QUATPROP_NON_FINITE_RATE` otherwise) corrected with what has
/// been learned so far, `(I − G)(rate_in − b)`, into `rate_out[3]` (which may be `rate_in`): integrate
/// this, the correction from before the sample, then give the sample to
/// `quatprop_calibration_estimator_update`. The same bits as `quatprop_set_calibration` with
/// `quatprop_calibration_estimator_get_calibration`'s numbers.
///
/// # Safety
/// `est` must be NULL or point to a readable `quatprop_calibration_estimator_t`; `rate_in` NULL or 3
/// readable floats, `rate_out` NULL or 3 writable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_calibration_estimator_correct(
    est: *const quatprop_calibration_estimator_t,
    rate_in: *const f32,
    rate_out: *mut f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    let r = match unsafe { read(rate_in.cast::<[f32; 3]>()) } {
        Ok(r) => r,
        Err(e) => return e,
    };
    let out = rate_out.cast::<[f32; 3]>();
    if let Err(e) = check(out) {
        return e;
    }
    // SAFETY: forwarded contract.
    let x = match unsafe { view(est) } {
        Ok(x) => x,
        Err(e) => return e,
    };
    let rate = vec3(r);
    if !rate.is_finite() {
        return status(Fail::Core(Error::NonFiniteRate));
    }
    let w = x.correct(GyroSample::new(rate)).rate;
    // SAFETY: forwarded contract (checked above).
    unsafe { write(out, [w.x, w.y, w.z]) }
}

/// A bias has just been measured at rest and is now taken out of the rates given to update: the
/// residual bias restarts at zero with the uncertainty of a rest measurement (0.03 °/s); the gain stays.
///
/// # Safety
/// `est` must be NULL or point to a `quatprop_calibration_estimator_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_calibration_estimator_at_rest(
    est: *mut quatprop_calibration_estimator_t,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        modify(est, |x| {
            x.at_rest();
            Ok(())
        })
    }
}

/// The gain correction `I − G` learned so far (the matrix that multiplies the bias-free rate) into
/// `gain[9]`, and the standard deviation of each of its terms into `std_dev[9]`, both row-major: a term
/// still at its prior (the sigma given to init) has not been observed (a turn about the vertical shows
/// none of its own scale; turns at many attitudes show every term).
///
/// # Safety
/// `est` must be NULL or point to a readable `quatprop_calibration_estimator_t`; `gain` and `std_dev`
/// NULL or 9 writable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_calibration_estimator_get_gain(
    est: *const quatprop_calibration_estimator_t,
    gain: *mut f32,
    std_dev: *mut f32,
) -> quatprop_status_t {
    let (g, s) = (
        gain.cast::<[[f32; 3]; 3]>(),
        std_dev.cast::<[[f32; 3]; 3]>(),
    );
    if let Err(e) = check(g).and_then(|()| check(s)) {
        return e;
    }
    // SAFETY: forwarded contract.
    match unsafe { view(est) } {
        // SAFETY: forwarded contract (checked above).
        Ok(x) => unsafe {
            write(g, x.gain());
            write(s, x.gain_std_dev())
        },
        Err(e) => e,
    }
}

/// The residual bias `b` learned so far (rad/s, the axes of the rates given to update) into `bias[3]`.
///
/// # Safety
/// `est` must be NULL or point to a readable `quatprop_calibration_estimator_t`; `bias` NULL or 3
/// writable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_calibration_estimator_get_bias(
    est: *const quatprop_calibration_estimator_t,
    bias: *mut f32,
) -> quatprop_status_t {
    let out = bias.cast::<[f32; 3]>();
    if let Err(e) = check(out) {
        return e;
    }
    // SAFETY: forwarded contract.
    match unsafe { view(est) } {
        Ok(x) => {
            let b = x.bias();
            // SAFETY: forwarded contract (checked above).
            unsafe { write(out, [b.x, b.y, b.z]) }
        }
        Err(e) => e,
    }
}

/// The correction learned so far as a gyro calibration, `w = M (s ⊙ (r − o))`: offset `o` into
/// `offset[3]` (rad/s; the residual bias), sensitivity `s` into `sensitivity[3]` (the diagonal of
/// `I − G`), misalignment `M` into `misalignment[9]` (row-major: `I − G`'s columns divided by it) —
/// `quatprop_set_calibration`'s arguments, which then apply to a state's rate samples what
/// `quatprop_calibration_estimator_correct` gives, bit for bit:
///
/// ```c
/// float o[3], s[3], m[9];
/// if (quatprop_calibration_estimator_get_calibration(&est, o, s, m) == QUATPROP_OK)
///     quatprop_set_calibration(&att, o, s, m);
/// ```
///
/// The state applies it to its readings in sensor axes, before the alignment and the bias stage: it is the
/// correction for them when the estimator is fed those readings (rad/s in sensor axes, as given to
/// `quatprop_push_rate`, with the accelerometer in the same axes); its offset then takes out the bias it
/// learned, and the state's bias stage sees what is left.
///
/// # Safety
/// `est` must be NULL or point to a readable `quatprop_calibration_estimator_t`; `offset` and
/// `sensitivity` NULL or 3 writable floats, `misalignment` NULL or 9.
#[no_mangle]
pub unsafe extern "C" fn quatprop_calibration_estimator_get_calibration(
    est: *const quatprop_calibration_estimator_t,
    offset: *mut f32,
    sensitivity: *mut f32,
    misalignment: *mut f32,
) -> quatprop_status_t {
    let (o, s, m) = (
        offset.cast::<[f32; 3]>(),
        sensitivity.cast::<[f32; 3]>(),
        misalignment.cast::<[[f32; 3]; 3]>(),
    );
    if let Err(e) = check(o).and_then(|()| check(s)).and_then(|()| check(m)) {
        return e;
    }
    // SAFETY: forwarded contract.
    match unsafe { view(est) } {
        Ok(x) => {
            let c = x.calibration();
            let (v, k) = (c.offset(), c.sensitivity());
            // SAFETY: forwarded contract (checked above).
            unsafe {
                write(o, [v.x, v.y, v.z]);
                write(s, [k.x, k.y, k.z]);
                write(m, c.misalignment())
            }
        }
        Err(e) => e,
    }
}
