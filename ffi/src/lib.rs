//! # quatprop C API
//!
//! Integrates gyroscope samples into an attitude quaternion (single precision, `float`).
//!
//! Conventions: Hamilton quaternions, scalar first (`w, x, y, z`); the attitude maps body to reference;
//! rates are body-frame (after the alignment) in rad/s, angles in rad, times in s.
//!
//! Memory: `quatprop_t` is an opaque block of `QUATPROP_STATE_SIZE` bytes aligned to `QUATPROP_STATE_ALIGN`
//! that the caller allocates (statically, on the stack, anywhere); the library never allocates. It may be
//! copied with `memcpy`. A state that `quatprop_init` did not set up (e.g. a zeroed `static`) is refused
//! with `QUATPROP_NOT_INITIALIZED`. The calibration estimator has a block of its own,
//! `quatprop_calibration_estimator_t` (`QUATPROP_CALIBRATION_ESTIMATOR_SIZE` bytes), kept the same way.
//!
//! Errors: every function returns a `quatprop_status_t`; `QUATPROP_OK` (0) is success. Values 1 to 17
//! mirror the Rust `quatprop::Error` variants, values from 100 are the C boundary's own. A NULL or
//! misaligned pointer and an out-of-range enum value get an error code, never undefined behaviour; on any
//! error the state is unchanged (bursts: see `quatprop_push_counts_burst`). No panic can cross the boundary:
//! the library's panic handler calls the undefined symbol `quatprop_ffi_panic_is_reachable`, so a firmware
//! linked with `--gc-sections` fails to link if any panic path is reachable from what it calls.
//!
//! Not thread-safe per state: one state must not be used from two contexts (e.g. main and an ISR) at once.
//!
//! Each exported function is written out, though many share their shape (read the arguments, forward to
//! `with` or `burst`): cbindgen writes the header from these signatures and their docs as they stand in
//! the source (it does not expand macros), and a C user reads each function's contract there.
#![cfg_attr(not(test), no_std)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(missing_docs, rust_2018_idioms)]
#![allow(non_camel_case_types)]

#[cfg(feature = "rust-baseline")]
mod baseline;
mod calibration;
mod state;
pub use calibration::{
    quatprop_calibration_estimator_t, QUATPROP_CALIBRATION_ESTIMATOR_ALIGN,
    QUATPROP_CALIBRATION_ESTIMATOR_SIZE, QUATPROP_CALIBRATION_ESTIMATOR_WORDS,
    QUATPROP_DEFAULT_MOTION_NOISE,
};
#[cfg(test)]
mod tests;

use core::mem::{align_of, size_of};
use quatprop::frontend::{
    Alignment, BiasEstimator, Calibration, CountScale, FixedBias, FixedPeriod, TickClock,
};
use quatprop::{Error, EulerZxz, EulerZyx, GyroSample, Quat, Vec3};
use state::{remap_of, vec3, Bias, Deltas, Fail, Inner, Rates, Time};

/// Version of this C API (the layout of the structs and the meaning of the values); bumped on any change.
/// 2: every time (`dt`, period) is a `double`; the state is stored encoded and checksummed.
/// 3: the state is 512 bytes (the bias estimator follows changes and can model temperature).
/// 4: the state is 1024 bytes (the bias estimator keeps its window's blocks and a Kalman filter's
/// variance; `quatprop_set_bias_estimator` takes the window in seconds, the period and the drift),
/// and its check is a CRC-32C over the whole block, in its last 4 bytes (tag "QPF4").
/// Added within version 4, changing no layout or value it had: the calibration estimator's own block
/// (`quatprop_calibration_estimator_t`, tag "QCE1") and its functions, and the status value 17.
pub const QUATPROP_ABI_VERSION: u32 = 4;
/// `uint64_t` words in `quatprop_t`.
pub const QUATPROP_STATE_WORDS: usize = 128;
/// Size of `quatprop_t` in bytes (same on every target).
pub const QUATPROP_STATE_SIZE: usize = 1024;
/// Alignment of `quatprop_t` in bytes.
pub const QUATPROP_STATE_ALIGN: usize = 8;

/// The opaque state. Allocate it anywhere (no heap needed), set it up with `quatprop_init`; never read or
/// write `_opaque` (a copy of a whole initialized state is fine). 8-byte aligned: `uint64_t` is, on every
/// supported target (asserted).
#[repr(C)]
pub struct quatprop_t {
    /// Private.
    pub _opaque: [u64; QUATPROP_STATE_WORDS],
}

/// "QPF4": the tag `quatprop_init` writes (version 4: the state stored encoded at the end of the block's
/// data, sealed by a CRC-32C in its last 4 bytes).
const MAGIC: u32 = 0x5150_4634;
/// The tags older versions wrote, "QPF2" (384 bytes) and "QPF3" (512 bytes, a word hash as checksum),
/// both in word 0: such a block, kept in retained RAM across a firmware update, is
/// `QUATPROP_CORRUPTED_STATE`, not taken for a block never set up.
const OLD_MAGICS: [u32; 2] = [0x5150_4632, 0x5150_4633];

/// The block's layout, in bytes: zeros `[0, z)`, the state encoded with postcard (`state::Inner`) in
/// `[z, z + length)` (`z`: the last multiple of 4 that leaves room for it), zeros to `PAYLOAD`, the tag
/// `[1012, 1016)`, the encoding's length `[1016, 1020)` (both native-endian), and the checksum
/// `[SUM, 1024)`: the CRC-32C of the 1020 bytes before it, stored little-endian, so the whole block is one
/// CRC codeword (data, then its CRC) and a burst anywhere in it is a burst of the codeword. The zeros come
/// first so that the CRC can start after them (`START`).
const PAYLOAD: usize = QUATPROP_STATE_SIZE - 12;
/// Where the tag starts (the length follows it).
const TAG: usize = PAYLOAD;
/// Where the checksum starts.
const SUM: usize = QUATPROP_STATE_SIZE - 4;
const _: () = assert!(TAG + 8 == SUM);

/// The block as bytes.
type Block = [u8; QUATPROP_STATE_SIZE];

// The documented size is the block's.
const _: () = assert!(size_of::<quatprop_t>() == QUATPROP_STATE_SIZE);
const _: () = assert!(align_of::<quatprop_t>() == QUATPROP_STATE_ALIGN);
const _: () = assert!(QUATPROP_STATE_WORDS * 8 == QUATPROP_STATE_SIZE);
const _: () = assert!(size_of::<Block>() == size_of::<quatprop_t>());

/// CRC-32C (Castagnoli; polynomial 0x1EDC6F41, reflected 0x82F63B78; initial register and final xor
/// 0xFFFFFFFF), sliced by 8: `TABLES[0]` is the byte-wise table, `TABLES[k][i]` the register change of byte
/// `i` followed by `k` zero bytes. 8 KB of flash, built at compile time.
static TABLES: [[u32; 256]; 8] = {
    let mut t = [[0u32; 256]; 8];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut bit = 0;
        while bit < 8 {
            c = if c & 1 != 0 {
                (c >> 1) ^ 0x82F6_3B78
            } else {
                c >> 1
            };
            bit += 1;
        }
        t[0][i] = c;
        i += 1;
    }
    let mut k = 1;
    while k < 8 {
        let mut i = 0;
        while i < 256 {
            let p = t[k - 1][i];
            t[k][i] = (p >> 8) ^ t[0][(p & 0xFF) as usize];
            i += 1;
        }
        k += 1;
    }
    t
};

/// `START[z]`: the CRC-32C register after `z` zero bytes from its initial value 0xFFFFFFFF (4 KB of flash,
/// built at compile time). A block's leading zeros are not read twice: checked to be zero, then skipped.
static START: [u32; PAYLOAD + 1] = {
    let mut s = [0u32; PAYLOAD + 1];
    s[0] = !0;
    let mut z = 1;
    while z <= PAYLOAD {
        let r = s[z - 1];
        s[z] = TABLES[0][(r & 0xFF) as usize] ^ (r >> 8);
        z += 1;
    }
    s
};

/// The CRC-32C register `crc` advanced over `data`, eight bytes per step. Inlined into each block's
/// `checksum` (one per block type): as the only caller's own code, as it was before a second block type.
#[inline(always)]
fn crc32c_update(mut crc: u32, data: &[u8]) -> u32 {
    let t = &TABLES;
    let at = |k: usize, x: u32| t[k][(x & 0xFF) as usize];
    let mut chunks = data.chunks_exact(8);
    for c in &mut chunks {
        let lo = u32::from_le_bytes([c[0], c[1], c[2], c[3]]) ^ crc;
        let hi = u32::from_le_bytes([c[4], c[5], c[6], c[7]]);
        crc = at(7, lo)
            ^ at(6, lo >> 8)
            ^ at(5, lo >> 16)
            ^ at(4, lo >> 24)
            ^ at(3, hi)
            ^ at(2, hi >> 8)
            ^ at(1, hi >> 16)
            ^ at(0, hi >> 24);
    }
    for &b in chunks.remainder() {
        crc = at(0, crc ^ u32::from(b)) ^ (crc >> 8);
    }
    crc
}

/// The CRC-32C of `data` (`tests.rs` checks it against the `crc` crate's `CRC_32_ISCSI` and the
/// catalogue's check value).
#[cfg(test)]
fn crc32c(data: &[u8]) -> u32 {
    !crc32c_update(!0, data)
}

/// Whether every byte of `bytes` is zero (eight at a time). Inlined as `crc32c_update`.
#[inline(always)]
fn all_zero(bytes: &[u8]) -> bool {
    let mut chunks = bytes.chunks_exact(8);
    let mut any = 0u32;
    for c in &mut chunks {
        any |= u32::from_ne_bytes([c[0], c[1], c[2], c[3]])
            | u32::from_ne_bytes([c[4], c[5], c[6], c[7]]);
    }
    for &b in chunks.remainder() {
        any |= u32::from(b);
    }
    any == 0
}

/// The checksum a block must hold: the CRC-32C of its first `SUM` bytes. Over these 8160 bits CRC-32C has
/// Hamming distance 4 (Koopman: distance 6 only up to 5243 data bits), so a block that differs from a
/// sealed one in 1 to 3 bits never passes, nor one that differs only within 32 consecutive bits (any 4
/// consecutive bytes);
/// other damage passes with probability 2⁻³² (docs/c-api.md, `tests.rs`). `None` if the length is beyond
/// `PAYLOAD` or a byte before the encoding is not zero (no sealed block is so): the CRC is computed from
/// `START` after those zeros. Not inlined: one copy serves `load` and `encode` (4 KB less flash, one call
/// more per use).
#[inline(never)]
fn checksum(b: &Block) -> Option<u32> {
    sealed_sum(b, |zeros| START.get(zeros).copied())
}

/// The checksum of a sealed block of any size (the layout of `PAYLOAD`, `TAG` and `SUM`, counted from
/// its end): `None` if the length is beyond the payload or a byte outside the encoding is not zero,
/// otherwise the CRC-32C of every byte before the last 4, started from `start(z)`, the register after the
/// `z` leading zeros (checked to be zero, then skipped).
#[inline(always)]
fn sealed_sum<const N: usize>(
    b: &[u8; N],
    start: impl FnOnce(usize) -> Option<u32>,
) -> Option<u32> {
    let (start_at, len) = placement(b)?;
    let (lead, rest) = b.split_at_checked(start_at)?;
    let pad = rest.get(len..(N - 12).checked_sub(start_at)?)?;
    let data = rest.get(..(N - 4).checked_sub(start_at)?)?;
    if !all_zero(lead) || !all_zero(pad) {
        return None;
    }
    Some(!crc32c_update(start(start_at)?, data))
}

/// Where the encoding starts and its length: the length is read from the block (`None` beyond
/// `PAYLOAD`), the start is the last multiple of 4 that leaves room for it before `PAYLOAD` (an aligned
/// start makes the copy in `encode` word by word); the 0 to 3 bytes between the encoding and the tag are
/// zeros like those before it. (Any block of this layout: `PAYLOAD = N − 12`.)
fn placement<const N: usize>(b: &[u8; N]) -> Option<(usize, usize)> {
    let payload = N.checked_sub(12)?;
    let len = word(b, payload / 4 + 1) as usize;
    Some((payload.checked_sub(len)? & !3, len))
}

/// The checksum the block holds (its last 4 bytes, little-endian).
fn stored_sum<const N: usize>(b: &[u8; N]) -> u32 {
    match b.get(N.wrapping_sub(4)..) {
        Some(&[x0, x1, x2, x3]) => u32::from_le_bytes([x0, x1, x2, x3]),
        _ => 0,
    }
}

fn word<const N: usize>(b: &[u8; N], i: usize) -> u32 {
    let at = 4 * i;
    match b.get(at..at + 4) {
        Some(&[a, b, c, d]) => u32::from_ne_bytes([a, b, c, d]),
        _ => 0,
    }
}

/// The state a block holds, checked: `QUATPROP_NOT_INITIALIZED` without the tag (`QUATPROP_CORRUPTED_STATE`
/// for an older version's tag), `QUATPROP_CORRUPTED_STATE` if the length, the leading zeros, the checksum
/// or the encoding is wrong. Nothing is decoded before the checksum matches.
fn load(b: &Block) -> Result<Inner, quatprop_status_t> {
    if word(b, TAG / 4) != MAGIC && OLD_MAGICS.contains(&word(b, 0)) {
        return Err(S::QUATPROP_CORRUPTED_STATE);
    }
    open(b, MAGIC, checksum)
}

/// `inner` as a block: zeros, encoding, tag, length, checksum.
fn encode(inner: &Inner) -> Result<Block, quatprop_status_t> {
    seal(inner, MAGIC, checksum)
}

/// What a sealed block of any size holds, checked by `sum` (its `checksum`): `QUATPROP_NOT_INITIALIZED`
/// without the tag `magic`, `QUATPROP_CORRUPTED_STATE` if the length, the zeros, the checksum or the
/// encoding is wrong. Nothing is decoded before the checksum matches.
#[inline(always)]
fn open<const N: usize, T: serde::de::DeserializeOwned>(
    b: &[u8; N],
    magic: u32,
    sum: fn(&[u8; N]) -> Option<u32>,
) -> Result<T, quatprop_status_t> {
    let tag = N.checked_sub(12).ok_or(S::QUATPROP_UNKNOWN_ERROR)? / 4;
    if word(b, tag) != magic {
        return Err(S::QUATPROP_NOT_INITIALIZED);
    }
    if sum(b) != Some(stored_sum(b)) {
        return Err(S::QUATPROP_CORRUPTED_STATE);
    }
    let (start, len) = placement(b).ok_or(S::QUATPROP_CORRUPTED_STATE)?;
    let bytes = b
        .get(start..start + len)
        .ok_or(S::QUATPROP_CORRUPTED_STATE)?;
    postcard::from_bytes(bytes).map_err(|_| S::QUATPROP_CORRUPTED_STATE)
}

/// `value` as a sealed block of `N` bytes (zeros, encoding, tag `magic`, length, checksum `sum`);
/// `QUATPROP_UNKNOWN_ERROR` if it does not fit (the tests show that every value fits its block).
#[inline(always)]
fn seal<const N: usize, T: serde::Serialize>(
    value: &T,
    magic: u32,
    sum: fn(&[u8; N]) -> Option<u32>,
) -> Result<[u8; N], quatprop_status_t> {
    const E: quatprop_status_t = S::QUATPROP_UNKNOWN_ERROR;
    let payload_len = N.checked_sub(12).ok_or(E)?;
    let mut b = [0u8; N];
    let (payload, rest) = b.split_at_mut(payload_len);
    let len = postcard::to_slice(value, payload).map_err(|_| E)?.len();
    let rest = rest.get_mut(..12).ok_or(E)?;
    rest[..4].copy_from_slice(&magic.to_ne_bytes());
    rest[4..8].copy_from_slice(&(len as u32).to_ne_bytes());
    let (start, _) = placement(&b).ok_or(E)?;
    // The encoding moves to `start`, zeros before it (the explicit bounds: no panic path).
    let payload = b.get_mut(..payload_len).ok_or(E)?;
    if len > payload.len() || start > payload.len() - len {
        return Err(E);
    }
    payload.copy_within(..len, start);
    payload.get_mut(..start.min(len)).ok_or(E)?.fill(0);
    let sum = sum(&b).ok_or(E)?;
    b.get_mut(N - 4..)
        .ok_or(E)?
        .copy_from_slice(&sum.to_le_bytes());
    Ok(b)
}

/// which count what it let through, and for the bench (feature `bench-hooks`), which times it beside the CRC.
#[cfg(any(test, feature = "bench-hooks"))]
fn checksum_abi3(b: &Block) -> u32 {
    let mut h: u32 = 0x811C_9DC5;
    for (i, w) in b.chunks_exact(4).enumerate() {
        if i != 2 {
            let word = u32::from_ne_bytes([w[0], w[1], w[2], w[3]]);
            h = (h ^ word).wrapping_mul(0x0100_0193);
        }
    }
    h
}

// include/quatprop.h repeats this enum and every item below: cbindgen generates it from this file.

/// Result of every call. Values are fixed (ABI); 1 to 17 mirror `quatprop::Error`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum quatprop_status_t {
    /// Success.
    QUATPROP_OK = 0,
    /// A rate or angle sample (or a bias, or a rate to correct) is NaN or infinite.
    QUATPROP_NON_FINITE_RATE = 1,
    /// A time step (or period, or clock frequency) is NaN or infinite.
    QUATPROP_NON_FINITE_STEP = 2,
    /// A time step (or period, or clock frequency) is zero or negative.
    QUATPROP_NON_POSITIVE_STEP = 3,
    /// The step angle |w|·dt exceeds the scheme's stability bound.
    QUATPROP_STEP_ANGLE_BEYOND_STABILITY = 4,
    /// Baumgarte gain beyond the scheme's bound (not reachable from C: no Baumgarte scheme here).
    QUATPROP_GAIN_BEYOND_STABILITY = 5,
    /// The quaternion is zero.
    QUATPROP_ZERO_QUATERNION = 6,
    /// The quaternion is NaN or infinite.
    QUATPROP_NON_FINITE_QUATERNION = 7,
    /// Stabilizer EVERY with n = 0.
    QUATPROP_INVALID_STABILIZER = 8,
    /// Invalid Baumgarte gain (not reachable from C).
    QUATPROP_INVALID_GAIN = 9,
    /// The alignment matrix is not a rotation.
    QUATPROP_NOT_A_ROTATION = 10,
    /// A timestamp does not advance (duplicate or backwards).
    QUATPROP_TIMESTAMP_NOT_INCREASING = 11,
    /// Clock counter width outside 1 to 32 bits.
    QUATPROP_INVALID_CLOCK = 12,
    /// Bias estimator: the window must hold 1 to 2^31 − 1 samples, the period be finite and positive, the
    /// gate finite and positive, the drift finite and not negative. Calibration estimator: each sigma 0 to
    /// 0.05, the motion noise finite and positive, and with the period, variances that fit a `float`
    /// (a noise or a period absurdly large).
    QUATPROP_INVALID_ESTIMATOR = 13,
    /// The step overflowed to a non-finite attitude.
    QUATPROP_NON_FINITE_RESULT = 14,
    /// A core error this version of the C API does not name.
    QUATPROP_UNKNOWN_ERROR = 15,
    /// A gyro calibration has a number that is not finite, or `M·diag(sensitivity)` is singular or has
    /// a condition number (∞-norm) above 100.
    QUATPROP_INVALID_CALIBRATION = 16,
    /// An accelerometer reading given beside a rate (`quatprop_calibration_estimator_update`) is NaN or
    /// infinite.
    QUATPROP_NON_FINITE_AUX = 17,
    /// A pointer argument is NULL.
    QUATPROP_NULL_POINTER = 100,
    /// A pointer argument is not aligned for its type.
    QUATPROP_MISALIGNED_POINTER = 101,
    /// An enum argument (scheme, stabilizer, input, coning, accumulator, axis remap) is out of range.
    QUATPROP_BAD_ENUM = 102,
    /// The state was not set up by `quatprop_init` (e.g. a zeroed static).
    QUATPROP_NOT_INITIALIZED = 103,
    /// A rate call on the delta-angle input model, or a delta-angle call on a rate model.
    QUATPROP_WRONG_INPUT_KIND = 104,
    /// The call needs a front-end part that was not set: count scale, fixed period or tick clock.
    QUATPROP_NOT_CONFIGURED = 105,
    /// A numeric argument out of range (count scale not finite and positive).
    QUATPROP_BAD_ARGUMENT = 106,
    /// The state's bytes changed since the library last wrote them (its CRC-32C or its encoding does not
    /// match: retained RAM after a reset, a stray write, a partial copy), or an older version of the library
    /// wrote them. Nothing was read from it.
    QUATPROP_CORRUPTED_STATE = 107,
}

use quatprop_status_t as S;

fn status(f: Fail) -> quatprop_status_t {
    match f {
        Fail::Core(e) => match e {
            Error::NonFiniteRate => S::QUATPROP_NON_FINITE_RATE,
            Error::NonFiniteStep => S::QUATPROP_NON_FINITE_STEP,
            Error::NonPositiveStep => S::QUATPROP_NON_POSITIVE_STEP,
            Error::StepAngleBeyondStability { .. } => S::QUATPROP_STEP_ANGLE_BEYOND_STABILITY,
            Error::GainBeyondStability { .. } => S::QUATPROP_GAIN_BEYOND_STABILITY,
            Error::ZeroQuaternion => S::QUATPROP_ZERO_QUATERNION,
            Error::NonFiniteQuaternion => S::QUATPROP_NON_FINITE_QUATERNION,
            Error::InvalidStabilizer => S::QUATPROP_INVALID_STABILIZER,
            Error::InvalidGain => S::QUATPROP_INVALID_GAIN,
            Error::NotARotation => S::QUATPROP_NOT_A_ROTATION,
            Error::TimestampNotIncreasing => S::QUATPROP_TIMESTAMP_NOT_INCREASING,
            Error::InvalidClock => S::QUATPROP_INVALID_CLOCK,
            Error::InvalidEstimator => S::QUATPROP_INVALID_ESTIMATOR,
            Error::NonFiniteResult => S::QUATPROP_NON_FINITE_RESULT,
            Error::WrongSampleKind => S::QUATPROP_WRONG_INPUT_KIND,
            Error::InvalidCalibration => S::QUATPROP_INVALID_CALIBRATION,
            Error::NonFiniteAux => S::QUATPROP_NON_FINITE_AUX,
            _ => S::QUATPROP_UNKNOWN_ERROR,
        },
        Fail::BadEnum => S::QUATPROP_BAD_ENUM,
        Fail::BadArgument => S::QUATPROP_BAD_ARGUMENT,
        Fail::WrongInputKind => S::QUATPROP_WRONG_INPUT_KIND,
        Fail::NotConfigured => S::QUATPROP_NOT_CONFIGURED,
    }
}

fn done(r: Result<(), Fail>) -> quatprop_status_t {
    match r {
        Ok(()) => S::QUATPROP_OK,
        Err(f) => status(f),
    }
}

/// Explicit Euler (`quatprop_config_t::scheme`), order 1. Step-angle bound (the largest `dt * max|w|` a
/// step may have, rad; a longer step is refused with `QUATPROP_STEP_ANGLE_BEYOND_STABILITY`): 2.000.
pub const QUATPROP_SCHEME_EULER: u32 = 0;
/// Heun's second-order Runge–Kutta. Step-angle bound: 2.828 rad.
pub const QUATPROP_SCHEME_RK2: u32 = 1;
/// Kutta's third-order Runge–Kutta. Step-angle bound: 3.464 rad.
pub const QUATPROP_SCHEME_RK3: u32 = 2;
/// Classical fourth-order Runge–Kutta. Step-angle bound: 5.657 rad.
pub const QUATPROP_SCHEME_RK4: u32 = 3;
/// Fifth-order Runge–Kutta. Step-angle bound: 1.994 rad.
pub const QUATPROP_SCHEME_RK5: u32 = 4;
/// Exponential map of the step's rotation vector (recommended), order 4 with HISTORY. No step-angle bound.
pub const QUATPROP_SCHEME_EXPMAP: u32 = 5;
/// Fourth-order Magnus. No step-angle bound.
pub const QUATPROP_SCHEME_MAGNUS4: u32 = 6;
/// Fourth-order commutator-free. No step-angle bound.
pub const QUATPROP_SCHEME_CF4: u32 = 7;

/// No stabilization (`quatprop_config_t::stabilizer`).
pub const QUATPROP_STABILIZER_OFF: u32 = 0;
/// Exact normalization every step.
pub const QUATPROP_STABILIZER_NORMALIZE: u32 = 1;
/// First-order normalization every step (recommended).
pub const QUATPROP_STABILIZER_FIRST_ORDER: u32 = 2;
/// Exact normalization every `every` steps.
pub const QUATPROP_STABILIZER_EVERY: u32 = 3;

/// Rate held over the step (`quatprop_config_t::input`).
pub const QUATPROP_INPUT_HOLD: u32 = 0;
/// Rate linear between consecutive samples.
pub const QUATPROP_INPUT_LINEAR: u32 = 1;
/// Rate interpolated through the last samples (recommended).
pub const QUATPROP_INPUT_HISTORY: u32 = 2;
/// Two samples per step (sensor at twice the step rate).
pub const QUATPROP_INPUT_TWICE_RATE: u32 = 3;
/// Two samples per step at the Gauss points.
pub const QUATPROP_INPUT_GAUSS_POINTS: u32 = 4;
/// Delta angles (rad per sample) with the coning correction `coning`.
pub const QUATPROP_INPUT_DELTA_ANGLES: u32 = 5;

/// No coning correction (`quatprop_config_t::coning`, delta angles only).
pub const QUATPROP_CONING_UNCORRECTED: u32 = 0;
/// One sample plus the previous one.
pub const QUATPROP_CONING_ONE_PLUS_PREVIOUS: u32 = 1;
/// Two-sample correction.
pub const QUATPROP_CONING_TWO_SAMPLE: u32 = 2;
/// Three-sample correction.
pub const QUATPROP_CONING_THREE_SAMPLE: u32 = 3;
/// Four-sample correction.
pub const QUATPROP_CONING_FOUR_SAMPLE: u32 = 4;
/// Five-sample correction.
pub const QUATPROP_CONING_FIVE_SAMPLE: u32 = 5;

/// Increments added plainly (`quatprop_config_t::accumulator`).
pub const QUATPROP_ACCUMULATOR_PLAIN: u32 = 0;
/// Kahan-compensated sum: a float state that tracks a double one over millions of steps.
pub const QUATPROP_ACCUMULATOR_KAHAN: u32 = 1;
/// Float-float attitude advanced by exact products: the float state's own error stays at its rounding
/// over 10^8 steps (more instructions per step than KAHAN).
pub const QUATPROP_ACCUMULATOR_FLOAT_FLOAT: u32 = 2;

/// Axis remaps (`quatprop_set_axis_remap`): the signed sensor axis that becomes body x, y, z.
/// `PY_NX_PZ`: body x = +sensor y, body y = -sensor x, body z = +sensor z (sensor turned 90 deg about z).
pub const QUATPROP_REMAP_PX_PY_PZ: u32 = 0;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PX_NY_NZ: u32 = 1;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PX_PZ_NY: u32 = 2;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PX_NZ_PY: u32 = 3;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NX_PY_NZ: u32 = 4;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NX_NY_PZ: u32 = 5;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NX_PZ_PY: u32 = 6;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NX_NZ_NY: u32 = 7;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PY_PX_NZ: u32 = 8;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PY_NX_PZ: u32 = 9;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PY_PZ_PX: u32 = 10;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PY_NZ_NX: u32 = 11;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NY_PX_PZ: u32 = 12;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NY_NX_NZ: u32 = 13;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NY_PZ_NX: u32 = 14;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NY_NZ_PX: u32 = 15;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PZ_PX_PY: u32 = 16;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PZ_NX_NY: u32 = 17;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PZ_PY_NX: u32 = 18;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_PZ_NY_PX: u32 = 19;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NZ_PX_NY: u32 = 20;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NZ_NX_PY: u32 = 21;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NZ_PY_PX: u32 = 22;
#[allow(missing_docs)]
pub const QUATPROP_REMAP_NZ_NY_NX: u32 = 23;

/// The propagator's configuration, chosen at run time. `quatprop_config_default` fills the recommended one.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct quatprop_config_t {
    /// A `QUATPROP_SCHEME_*` value.
    pub scheme: u32,
    /// A `QUATPROP_STABILIZER_*` value.
    pub stabilizer: u32,
    /// n of `QUATPROP_STABILIZER_EVERY` (ignored otherwise; must be at least 1).
    pub every: u32,
    /// A `QUATPROP_INPUT_*` value.
    pub input: u32,
    /// A `QUATPROP_CONING_*` value (read only for `QUATPROP_INPUT_DELTA_ANGLES`).
    pub coning: u32,
    /// A `QUATPROP_ACCUMULATOR_*` value.
    pub accumulator: u32,
    /// Initial attitude, body to reference (normalized by init; finite and non-zero).
    pub q0: quatprop_quat_t,
}

/// A quaternion, Hamilton convention, scalar first.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct quatprop_quat_t {
    /// Scalar part.
    pub w: f32,
    /// i component.
    pub x: f32,
    /// j component.
    pub y: f32,
    /// k component.
    pub z: f32,
}

/// One sample: a rate (rad/s) or a delta angle (rad), sensor axes, and whether the sensor clipped.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct quatprop_sample_t {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component.
    pub z: f32,
    /// Non-zero if an axis sat at full scale (counted in `quatprop_counters_t::saturated`).
    pub saturated: u32,
}

/// Aerospace Euler angles Z-Y'-X'' (rad): yaw in (-pi, pi], pitch in [-pi/2, pi/2], roll in (-pi, pi].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct quatprop_euler_zyx_t {
    /// Heading about the reference z axis.
    pub yaw: f32,
    /// Elevation.
    pub pitch: f32,
    /// Bank about the body x axis.
    pub roll: f32,
}

/// Classical Euler angles Z-X'-Z'' (rad): precession psi, nutation theta in [0, pi], spin phi.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct quatprop_euler_zxz_t {
    /// Precession.
    pub psi: f32,
    /// Nutation.
    pub theta: f32,
    /// Spin.
    pub phi: f32,
}

impl From<Quat<f32>> for quatprop_quat_t {
    fn from(q: Quat<f32>) -> Self {
        Self {
            w: q.w,
            x: q.x,
            y: q.y,
            z: q.z,
        }
    }
}

impl From<quatprop_quat_t> for Quat<f32> {
    fn from(q: quatprop_quat_t) -> Self {
        Quat::new(q.w, q.x, q.y, q.z)
    }
}

impl From<EulerZyx<f32>> for quatprop_euler_zyx_t {
    fn from(e: EulerZyx<f32>) -> Self {
        Self {
            yaw: e.yaw,
            pitch: e.pitch,
            roll: e.roll,
        }
    }
}

impl From<EulerZxz<f32>> for quatprop_euler_zxz_t {
    fn from(e: EulerZxz<f32>) -> Self {
        Self {
            psi: e.psi,
            theta: e.theta,
            phi: e.phi,
        }
    }
}

/// The counters of a state.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct quatprop_counters_t {
    /// Steps taken (samples that closed a step and were accepted).
    pub steps: u64,
    /// Corrections applied by the stabilizer.
    pub corrections: u64,
    /// Saturated samples accepted.
    pub saturated: u64,
    /// Timestamp gaps the tick clock saw (0 without a clock).
    pub clock_gaps: u32,
    /// 1 if the bias estimator has learned a bias (or a fixed bias is set), else 0.
    pub bias_learned: u32,
}

// ---------------------------------------------------------------------------------------------------------
// Pointer checks: the only unsafe code. Each turns a C pointer into a Rust reference after checking it.

/// A non-null, aligned pointer, or the status to return.
fn check<T>(p: *const T) -> Result<(), quatprop_status_t> {
    if p.is_null() {
        Err(S::QUATPROP_NULL_POINTER)
    } else if !p.is_aligned() {
        Err(S::QUATPROP_MISALIGNED_POINTER)
    } else {
        Ok(())
    }
}

/// Reads a `T` from C (a plain-data struct with no invalid bit patterns).
///
/// # Safety
/// `p`, if non-null and aligned, must point to a readable `T`.
unsafe fn read<T: Copy>(p: *const T) -> Result<T, quatprop_status_t> {
    check(p)?;
    // SAFETY: non-null and aligned (checked); readable per the caller's contract; T is plain data
    // (f32/u32/i16 fields only), so every bit pattern is valid.
    Ok(unsafe { p.read() })
}

/// Writes a `T` to C.
///
/// # Safety
/// `p`, if non-null and aligned, must point to writable memory for a `T`.
unsafe fn write<T>(p: *mut T, v: T) -> quatprop_status_t {
    if let Err(s) = check(p) {
        return s;
    }
    // SAFETY: non-null and aligned (checked), writable per the caller's contract.
    unsafe { p.write(v) };
    S::QUATPROP_OK
}

/// A C array of `n` `T`s as a slice.
///
/// # Safety
/// `p`, if non-null and aligned, must point to `n` readable `T`s that nothing writes during the call.
unsafe fn slice<'a, T>(p: *const T, n: usize) -> Result<&'a [T], quatprop_status_t> {
    check(p)?;
    // SAFETY: non-null and aligned (checked); `n` readable, unaliased-for-writes elements per the caller's
    // contract; the element types here (i16 triples, u32, quatprop_sample_t) have no invalid bit patterns.
    Ok(unsafe { core::slice::from_raw_parts(p, n) })
}

/// A C block the library seals (`quatprop_t`, `quatprop_calibration_estimator_t`), seen as its bytes.
///
/// # Safety
/// `Bytes` must be a byte array of the block's size: any bytes are then a valid `Bytes`, and its
/// alignment (1) is at most the block's.
unsafe trait Sealed {
    /// The block as bytes.
    type Bytes: Copy;
}

// SAFETY: `Block` is `[u8; QUATPROP_STATE_SIZE]`, the size of `quatprop_t` (asserted).
unsafe impl Sealed for quatprop_t {
    type Bytes = Block;
}

/// The block behind `p`.
///
/// # Safety
/// `p`, if non-null and aligned, must point to a readable block.
unsafe fn block<'a, B: Sealed>(p: *const B) -> Result<&'a B::Bytes, quatprop_status_t> {
    check(p)?;
    // SAFETY: non-null and aligned (checked); the block is readable per the caller's contract, and any
    // bytes of its size are a valid `B::Bytes` (the trait's contract).
    Ok(unsafe { &*p.cast::<B::Bytes>() })
}

/// Writes `b` into the block behind `p` (checked by the caller).
///
/// # Safety
/// `p` must be non-null, aligned and point to a writable block not in use elsewhere.
unsafe fn put<B: Sealed>(p: *mut B, b: &B::Bytes) {
    // SAFETY: per the contract; `B::Bytes` has the block's size and alignment 1 (the trait's contract).
    unsafe { p.cast::<B::Bytes>().write(*b) };
}

/// Sets up the block behind `p` with the sealed bytes `made` returns (an init's work, once `p` is
/// checked); on any error nothing is written.
///
/// # Safety
/// `p` must be NULL or point to a writable block not in use elsewhere; `made` may read only what its
/// caller's contract makes readable.
unsafe fn init<B: Sealed>(
    p: *mut B,
    made: impl FnOnce() -> Result<B::Bytes, quatprop_status_t>,
) -> quatprop_status_t {
    if let Err(e) = check(p) {
        return e;
    }
    match made() {
        Ok(b) => {
            // SAFETY: non-null and aligned (checked), writable per the contract.
            unsafe { put(p, &b) };
            S::QUATPROP_OK
        }
        Err(e) => e,
    }
}

/// Runs `f` on the state behind `s`, then stores the state back (a refused call leaves it unchanged, so
/// its bytes stay the same), and returns `f`'s result.
///
/// # Safety
/// `s` must be NULL or point to a writable `quatprop_t` that nothing else accesses during the call.
unsafe fn modify<R>(
    s: *mut quatprop_t,
    f: impl FnOnce(&mut Inner) -> R,
) -> Result<R, quatprop_status_t> {
    // SAFETY: forwarded contract.
    let mut inner = load(unsafe { block(s) }?)?;
    let r = f(&mut inner);
    let b = encode(&inner)?;
    // SAFETY: checked by `block`; writable and exclusive per the contract.
    unsafe { put(s, &b) };
    Ok(r)
}

/// Runs `f` on the state behind `s`.
///
/// # Safety
/// As [`modify`].
unsafe fn with(
    s: *mut quatprop_t,
    f: impl FnOnce(&mut Inner) -> Result<(), Fail>,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    match unsafe { modify(s, f) } {
        Ok(r) => done(r),
        Err(e) => e,
    }
}

/// Reads a `T` from `p`, then runs `f` on the state behind `s` with it (as [`with`]); a bad `p` is refused
/// before the state is read.
///
/// # Safety
/// As [`with`]; `p` NULL or readable as for [`read`].
unsafe fn with_read<T: Copy>(
    s: *mut quatprop_t,
    p: *const T,
    f: impl FnOnce(&mut Inner, T) -> Result<(), Fail>,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    match unsafe { read(p) } {
        // SAFETY: forwarded contract.
        Ok(v) => unsafe { with(s, |st| f(st, v)) },
        Err(e) => e,
    }
}

/// As [`with_read`] for a vector `p[3]` of C floats.
///
/// # Safety
/// As [`with`]; `p` NULL or 3 readable floats.
unsafe fn with_vec3(
    s: *mut quatprop_t,
    p: *const f32,
    f: impl FnOnce(&mut Inner, Vec3<f32>) -> Result<(), Fail>,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { with_read(s, p.cast::<[f32; 3]>(), |st, v| f(st, vec3(v))) }
}

/// Runs `f` on the state behind `s` (read only) and writes its result to `out`.
///
/// # Safety
/// `s` must be NULL or point to a readable `quatprop_t`; `out` NULL or writable.
unsafe fn get<T>(
    s: *const quatprop_t,
    out: *mut T,
    f: impl FnOnce(&Inner) -> T,
) -> quatprop_status_t {
    if let Err(e) = check(out) {
        return e;
    }
    // SAFETY: forwarded contract.
    match unsafe { block(s) }.and_then(load) {
        // SAFETY: forwarded contract.
        Ok(inner) => unsafe { write(out, f(&inner)) },
        Err(e) => e,
    }
}

// ---------------------------------------------------------------------------------------------------------
// The API.

/// Fills `out` with the recommended configuration: EXPMAP, FIRST_ORDER, HISTORY, PLAIN, identity attitude.
///
/// # Safety
/// `out` must be NULL or point to writable memory for a `quatprop_config_t`.
#[no_mangle]
pub unsafe extern "C" fn quatprop_config_default(out: *mut quatprop_config_t) -> quatprop_status_t {
    let c = quatprop_config_t {
        scheme: QUATPROP_SCHEME_EXPMAP,
        stabilizer: QUATPROP_STABILIZER_FIRST_ORDER,
        every: 1,
        input: QUATPROP_INPUT_HISTORY,
        coning: QUATPROP_CONING_TWO_SAMPLE,
        accumulator: QUATPROP_ACCUMULATOR_PLAIN,
        q0: Quat::IDENTITY.into(),
    };
    // SAFETY: forwarded contract.
    unsafe { write(out, c) }
}

/// Sets up `s` with configuration `config` and an empty front end (no count scale, identity alignment,
/// no bias, no time base). Any previous content of `s` is ignored; on error `s` is not written.
///
/// # Safety
/// `s` must be NULL or point to a writable `quatprop_t` not in use elsewhere; `config` NULL or readable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_init(
    s: *mut quatprop_t,
    config: *const quatprop_config_t,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        init(s, || {
            let c = read(config)?;
            Inner::new(&c)
                .map_err(status)
                .and_then(|inner| encode(&inner))
        })
    }
}

/// Sets the count scale from the gyro's full scale in deg/s (e.g. 2000 for +-2000 dps, 16-bit counts).
/// `QUATPROP_BAD_ARGUMENT` unless finite and positive.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_count_scale_dps(
    s: *mut quatprop_t,
    full_scale_dps: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            let scale =
                CountScale::full_scale_dps(full_scale_dps).map_err(|_| Fail::BadArgument)?;
            st.front.scale = Some(scale);
            Ok(())
        })
    }
}

/// Sets the count scale from the sensitivity in counts per deg/s (e.g. 16.4 for +-2000 dps).
/// `QUATPROP_BAD_ARGUMENT` unless finite and positive.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_count_sensitivity(
    s: *mut quatprop_t,
    counts_per_dps: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            let scale = CountScale::sensitivity(counts_per_dps).map_err(|_| Fail::BadArgument)?;
            st.front.scale = Some(scale);
            Ok(())
        })
    }
}

/// Sets the alignment to a square mounting, a `QUATPROP_REMAP_*` value.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_axis_remap(
    s: *mut quatprop_t,
    remap: u32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.front.alignment = Some(Alignment::Remap(remap_of(remap)?));
            Ok(())
        })
    }
}

/// Sets the alignment to a rotation matrix `R` (row-major, `v_body = R v_sensor`);
/// `QUATPROP_NOT_A_ROTATION` unless orthonormal with det 1 to 1e-4.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `r` NULL or 9 readable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_alignment_matrix(
    s: *mut quatprop_t,
    r: *const f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with_read(s, r.cast::<[[f32; 3]; 3]>(), |st, r| {
            st.front.alignment = Some(Alignment::from_matrix(r)?);
            Ok(())
        })
    }
}

/// Sets the gyro's calibration, applied to every rate sample first (sensor axes, before the alignment):
/// `w = M (s ⊙ (r − o))` for a reading `r` (rad/s), offset `o[3]` (rad/s), per-axis sensitivity `s[3]`
/// and misalignment `M` (`m[9]`, row-major; Fusion's `FusionModelInertial`, the same bits);
/// `QUATPROP_INVALID_CALIBRATION` for a number that is not finite or `M·diag(s)` singular or with a
/// condition number above 100 (the state is then unchanged).
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `offset` and `sensitivity` NULL or
/// 3 readable floats, `m` NULL or 9.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_calibration(
    s: *mut quatprop_t,
    offset: *const f32,
    sensitivity: *const f32,
    m: *const f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract (each pointer checked for NULL and alignment before it is read).
    let read_all = unsafe {
        (
            read(offset.cast::<[f32; 3]>()),
            read(sensitivity.cast::<[f32; 3]>()),
            read(m.cast::<[[f32; 3]; 3]>()),
        )
    };
    let (o, k, m) = match read_all {
        (Ok(o), Ok(k), Ok(m)) => (o, k, m),
        (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => return e,
    };
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.front.calibration = Some(Calibration::new(vec3(o), vec3(k), m)?);
            Ok(())
        })
    }
}

/// Removes the calibration (readings are then taken as calibrated rates).
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_clear_calibration(s: *mut quatprop_t) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.front.calibration = None;
            Ok(())
        })
    }
}

/// Subtracts a fixed bias `b[3]` (rad/s, body axes, finite) from every rate sample; replaces any
/// estimator.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `b` NULL or 3 readable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_fixed_bias(
    s: *mut quatprop_t,
    b: *const f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with_vec3(s, b, |st, b| {
            st.front.bias = Bias::Fixed(FixedBias::new(b)?);
            Ok(())
        })
    }
}

/// The default `drift` of [`quatprop_set_bias_estimator`] (rad/s/√s): the Rust `BiasEstimator`'s.
pub const QUATPROP_DEFAULT_DRIFT: f32 = 2.0e-5;

/// Learns the bias while the body is still, follows it as it drifts and when it steps at rest, and keeps
/// slow turns (the Rust `frontend::BiasEstimator`): windows of `window_seconds` (s) of samples taken every
/// `sample_period` (s), each cut into 8 blocks; a window is still when every axis stays within `gate`
/// rad/s (finite, > 0) of the bias and its block means are flat; the bias walks with density `drift`
/// (rad/s/√s, ≥ 0; `QUATPROP_DEFAULT_DRIFT` for the default): the one knob between following a changing
/// bias and keeping a slow turn. `QUATPROP_INVALID_ESTIMATOR` for a window under one or over 2^31 − 1
/// samples, a period not finite and positive, or a bad gate or drift.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_bias_estimator(
    s: *mut quatprop_t,
    window_seconds: f64,
    sample_period: f64,
    gate: f32,
    drift: f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.front.bias = Bias::Estimator(
                BiasEstimator::new(window_seconds, sample_period, gate)?.with_drift(drift)?,
            );
            Ok(())
        })
    }
}

/// Removes the bias stage.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_clear_bias(s: *mut quatprop_t) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.front.bias = Bias::None;
            Ok(())
        })
    }
}

/// The bias subtracted now (rad/s, body axes; zero without a bias stage) into `out[3]`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `out` NULL or 3 writable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_get_bias(
    s: *const quatprop_t,
    out: *mut f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        get(s, out.cast::<[f32; 3]>(), |st| {
            let b = match &st.front.bias {
                Bias::None => quatprop::Vec3::ZERO,
                Bias::Fixed(f) => f.apply(GyroSample::default()).rate * -1.0,
                Bias::Estimator(e) => e.bias(),
            };
            [b.x, b.y, b.z]
        })
    }
}

/// Sets the fixed sample period (s; finite, > 0) that times the bursts (`quatprop_push_*_burst`); time
/// stays exact over any number of samples (the period's float rounding is carried).
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_fixed_period(
    s: *mut quatprop_t,
    period: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.front.period = Some(FixedPeriod::new(period)?);
            Ok(())
        })
    }
}

/// Sets the tick clock of the timed bursts: a counter at `frequency` Hz (finite, > 0), `bits` wide (1 to
/// 32; it wraps).
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_tick_clock(
    s: *mut quatprop_t,
    frequency: f64,
    bits: u32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.front.clock = Some(TickClock::new(frequency, bits)?);
            Ok(())
        })
    }
}

/// Pushes one rate sample (rad/s, sensor axes: alignment and bias apply) taken `dt` s after the previous
/// one (`dt` finite, > 0, at most FLT_MAX; used in single precision). The step angle `dt * max|w|` must be
/// within the scheme's bound (`QUATPROP_SCHEME_*`). On error nothing changes.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `sample` NULL or readable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_push_rate(
    s: *mut quatprop_t,
    sample: *const quatprop_sample_t,
    dt: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with_read(s, sample, |st, v| {
            one(st.rates(Rates::One(v.rate()), Time::Dt(dt as f32)))
        })
    }
}

/// Pushes one sample of raw counts `counts[3]` (sensor axes: count scale, alignment and bias apply) taken
/// `dt` s after the previous one (as for `quatprop_push_rate`). A count at -32768 or 32767 marks the sample
/// saturated. On error nothing changes.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `counts` NULL or 3 readable int16s.
#[no_mangle]
pub unsafe extern "C" fn quatprop_push_counts(
    s: *mut quatprop_t,
    counts: *const i16,
    dt: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with_read(s, counts.cast::<[i16; 3]>(), |st, c| {
            let scale = st.front.scale.ok_or(Fail::NotConfigured)?;
            one(st.rates(Rates::One(scale.sample(c)), Time::Dt(dt as f32)))
        })
    }
}

/// Pushes one delta angle (rad over one sample, sensor axes: the alignment applies, the bias does not)
/// taken `dt` s after the previous one (as for `quatprop_push_rate`); needs `QUATPROP_INPUT_DELTA_ANGLES`.
/// On error nothing changes.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `sample` NULL or readable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_push_delta(
    s: *mut quatprop_t,
    sample: *const quatprop_sample_t,
    dt: f64,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with_read(s, sample, |st, v| {
            one(st.deltas(Deltas::One(v.delta()), Time::Dt(dt as f32)))
        })
    }
}

/// A one-sample loop's result as a call's.
fn one(r: Result<usize, state::Refusal>) -> Result<(), Fail> {
    r.map(|_| ()).map_err(|(_, f)| f)
}

/// Runs a burst of the `n` samples at `samples` and reports through `integrated`: the samples are
/// checked first, then `integrated`, then the state is read.
///
/// # Safety
/// As [`modify`], [`slice`] and [`write`].
unsafe fn burst<T>(
    s: *mut quatprop_t,
    samples: *const T,
    n: usize,
    integrated: *mut usize,
    f: impl FnOnce(&mut Inner, &[T]) -> Result<usize, state::Refusal>,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    let fifo = match unsafe { slice(samples, n) } {
        Ok(f) => f,
        Err(e) => return e,
    };
    if let Err(e) = check(integrated) {
        return e;
    }
    // SAFETY: forwarded contract.
    let (n, status) = match unsafe { modify(s, |st| f(st, fifo)) } {
        Ok(Ok(n)) => (n, S::QUATPROP_OK),
        Ok(Err((i, fail))) => (i, status(fail)),
        // The state could not be read: nothing is written.
        Err(e) => return e,
    };
    // SAFETY: forwarded contract.
    unsafe { write(integrated, n) };
    status
}

/// Pushes a FIFO burst of `n` raw-count samples `counts[3 * n]` (x, y, z per sample, sensor axes) taken at
/// the fixed period: count scale, alignment and bias apply. Bit for bit the same as the Rust quick start.
///
/// `*integrated` gets the number of samples integrated. On success it is `n`. On an error it is the index of
/// the refused sample: the state is then what it was after the last accepted sample, except that the
/// refused sample's interval is kept by the period (push `counts + 3 * (*integrated + 1)` next and it is
/// covered), as in Rust's `push_burst`. The errors before any sample leave everything unchanged: NULL,
/// NOT_INITIALIZED and CORRUPTED_STATE without writing `*integrated`, NOT_CONFIGURED and WRONG_INPUT_KIND
/// with `*integrated` 0.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `counts` NULL or `3 * n` readable
/// int16s; `integrated` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_push_counts_burst(
    s: *mut quatprop_t,
    counts: *const i16,
    n: usize,
    integrated: *mut usize,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        burst(s, counts.cast::<[i16; 3]>(), n, integrated, |st, fifo| {
            st.counts(fifo, Time::Period)
        })
    }
}

/// As `quatprop_push_counts_burst`, with each sample's timestamp `timestamps[n]` (ticks of the tick clock):
/// each `dt` is the exact time since the last accepted sample; the very first timestamp starts the clock.
/// On a refused sample (`QUATPROP_TIMESTAMP_NOT_INCREASING` among others) the clock stays at the last
/// accepted sample.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `counts` NULL or `3 * n` readable
/// int16s; `timestamps` NULL or `n` readable uint32s; `integrated` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_push_counts_burst_timed(
    s: *mut quatprop_t,
    counts: *const i16,
    timestamps: *const u32,
    n: usize,
    integrated: *mut usize,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    let fifo = match unsafe { slice(counts.cast::<[i16; 3]>(), n) } {
        Ok(f) => f,
        Err(e) => return e,
    };
    // SAFETY: forwarded contract.
    unsafe {
        burst(s, timestamps, n, integrated, |st, times| {
            st.counts(fifo, Time::Ticks(times))
        })
    }
}

/// Pushes a burst of `n` rate samples (rad/s, sensor axes: alignment and bias apply) taken at the fixed
/// period. `*integrated` as for `quatprop_push_counts_burst`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `samples` NULL or `n` readable
/// samples; `integrated` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_push_rate_burst(
    s: *mut quatprop_t,
    samples: *const quatprop_sample_t,
    n: usize,
    integrated: *mut usize,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        burst(s, samples, n, integrated, |st, fifo| {
            st.rates(Rates::Samples(fifo), Time::Period)
        })
    }
}

/// Pushes a burst of `n` delta angles (rad, sensor axes: the alignment applies) taken at the fixed period;
/// needs `QUATPROP_INPUT_DELTA_ANGLES`. `*integrated` as for `quatprop_push_counts_burst`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `samples` NULL or `n` readable
/// samples; `integrated` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_push_delta_burst(
    s: *mut quatprop_t,
    samples: *const quatprop_sample_t,
    n: usize,
    integrated: *mut usize,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        burst(s, samples, n, integrated, |st, fifo| {
            st.deltas(Deltas::Samples(fifo), Time::Period)
        })
    }
}

/// An estimator's attitude correction: rotates the attitude by the small rotation `dtheta[3]` (rotation
/// vector, rad, finite) given in the **body** frame, `q <- q (x) exp(dtheta)`. The input model's samples
/// and the counters stay (they are body rates). On error nothing changes.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `dtheta` NULL or 3 readable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_rotate_body(
    s: *mut quatprop_t,
    dtheta: *const f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { with_vec3(s, dtheta, |st, d| st.rotate(d, true)) }
}

/// An estimator's attitude correction given in the **reference** frame: `q <- exp(dtheta) (x) q`
/// (`dtheta[3]` rad, finite). Otherwise as `quatprop_rotate_body`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `dtheta` NULL or 3 readable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_rotate_reference(
    s: *mut quatprop_t,
    dtheta: *const f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { with_vec3(s, dtheta, |st, d| st.rotate(d, false)) }
}

/// An estimator's bias correction: the bias subtracted from the rate samples grows by `delta[3]` (rad/s,
/// body axes, finite) — the fixed bias or the estimator's estimate moves (a fixed bias of `delta` is set
/// where there was no bias stage) — and the samples the input model keeps for its next steps are lowered
/// by `delta` too, so the next step integrates no jump. Both change or neither.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `delta` NULL or 3 readable floats.
#[no_mangle]
pub unsafe extern "C" fn quatprop_correct_bias(
    s: *mut quatprop_t,
    delta: *const f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { with_vec3(s, delta, |st, d| st.correct_bias(d)) }
}

/// Forgets the samples the input model keeps between steps (after a gap: the next sample starts it
/// afresh). The attitude and counters stay.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_restart_input(s: *mut quatprop_t) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        with(s, |st| {
            st.restart_input();
            Ok(())
        })
    }
}

/// Replaces the attitude (normalized), keeping counters and input samples.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `q` NULL or readable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_set_attitude(
    s: *mut quatprop_t,
    q: *const quatprop_quat_t,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { with_read(s, q, |st, q| st.set_attitude(q.into())) }
}

/// The attitude (body to reference, Hamilton, scalar first) into `out`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_get_attitude(
    s: *const quatprop_t,
    out: *mut quatprop_quat_t,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { get(s, out, |st| st.attitude().into()) }
}

/// The attitude as aerospace Euler angles (yaw, pitch, roll; Z-Y'-X'') into `out`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_get_euler_zyx(
    s: *const quatprop_t,
    out: *mut quatprop_euler_zyx_t,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { get(s, out, |st| st.attitude().to_euler_zyx().into()) }
}

/// The attitude as classical Euler angles (psi, theta, phi; Z-X'-Z'') into `out`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_get_euler_zxz(
    s: *const quatprop_t,
    out: *mut quatprop_euler_zxz_t,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { get(s, out, |st| st.attitude().to_euler_zxz().into()) }
}

/// The normalization error `|q|^2 - 1` of the attitude into `out`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_get_norm_error(
    s: *const quatprop_t,
    out: *mut f32,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe { get(s, out, |st| st.norm_error()) }
}

/// The counters into `out`.
///
/// # Safety
/// `s` must be NULL or point to a `quatprop_t` not in use elsewhere; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_get_counters(
    s: *const quatprop_t,
    out: *mut quatprop_counters_t,
) -> quatprop_status_t {
    // SAFETY: forwarded contract.
    unsafe {
        get(s, out, |st| {
            let (steps, corrections, saturated) = st.counters();
            quatprop_counters_t {
                steps,
                corrections,
                saturated,
                clock_gaps: st.front.clock.map_or(0, |c| c.gaps()),
                bias_learned: match &st.front.bias {
                    Bias::None => 0,
                    Bias::Fixed(_) => 1,
                    Bias::Estimator(e) => u32::from(e.is_learned()),
                },
            }
        })
    }
}

/// The library's version, a static NUL-terminated string (the crate's version, equal to the header's
/// `QUATPROP_VERSION` when library and header match): compare it with what the firmware was built
/// against, e.g. in a boot log. Never NULL.
#[no_mangle]
pub extern "C" fn quatprop_version() -> *const core::ffi::c_char {
    const VERSION: &core::ffi::CStr = match core::ffi::CStr::from_bytes_with_nul(
        concat!(env!("CARGO_PKG_VERSION"), "\0").as_bytes(),
    ) {
        Ok(v) => v,
        Err(_) => c"unknown",
    };
    VERSION.as_ptr()
}

/// The library's `QUATPROP_ABI_VERSION`: a program checks at run time that the library it is linked with
/// has the layout and values of the header it was compiled with
/// (`quatprop_abi_version() == QUATPROP_ABI_VERSION`).
#[no_mangle]
pub extern "C" fn quatprop_abi_version() -> u32 {
    QUATPROP_ABI_VERSION
}

/// A static, NUL-terminated name for a status value (e.g. "QUATPROP_NON_FINITE_RATE"); "unknown status"
/// for a value that names none. Never NULL.
#[no_mangle]
pub extern "C" fn quatprop_status_name(status: i32) -> *const core::ffi::c_char {
    let name: &'static core::ffi::CStr = match status {
        0 => c"QUATPROP_OK",
        1 => c"QUATPROP_NON_FINITE_RATE",
        2 => c"QUATPROP_NON_FINITE_STEP",
        3 => c"QUATPROP_NON_POSITIVE_STEP",
        4 => c"QUATPROP_STEP_ANGLE_BEYOND_STABILITY",
        5 => c"QUATPROP_GAIN_BEYOND_STABILITY",
        6 => c"QUATPROP_ZERO_QUATERNION",
        7 => c"QUATPROP_NON_FINITE_QUATERNION",
        8 => c"QUATPROP_INVALID_STABILIZER",
        9 => c"QUATPROP_INVALID_GAIN",
        10 => c"QUATPROP_NOT_A_ROTATION",
        11 => c"QUATPROP_TIMESTAMP_NOT_INCREASING",
        12 => c"QUATPROP_INVALID_CLOCK",
        13 => c"QUATPROP_INVALID_ESTIMATOR",
        14 => c"QUATPROP_NON_FINITE_RESULT",
        15 => c"QUATPROP_UNKNOWN_ERROR",
        16 => c"QUATPROP_INVALID_CALIBRATION",
        17 => c"QUATPROP_NON_FINITE_AUX",
        100 => c"QUATPROP_NULL_POINTER",
        101 => c"QUATPROP_MISALIGNED_POINTER",
        102 => c"QUATPROP_BAD_ENUM",
        103 => c"QUATPROP_NOT_INITIALIZED",
        104 => c"QUATPROP_WRONG_INPUT_KIND",
        105 => c"QUATPROP_NOT_CONFIGURED",
        106 => c"QUATPROP_BAD_ARGUMENT",
        107 => c"QUATPROP_CORRUPTED_STATE",
        _ => c"unknown status",
    };
    name.as_ptr()
}

/// Bench hook (feature `bench-hooks` only; not in the header): the checksum of the block behind `s` (0 for
/// a NULL or misaligned `s`), so `ffi/ci` can time the state's check on its own.
///
/// # Safety
/// `s` must be NULL or point to a readable `quatprop_t`.
#[cfg(feature = "bench-hooks")]
#[no_mangle]
pub unsafe extern "C" fn quatprop_bench_checksum(s: *const quatprop_t) -> u32 {
    // SAFETY: forwarded contract.
    unsafe { block(s) }.ok().and_then(checksum).unwrap_or(0)
}

/// Bench hook (feature `bench-hooks` only): ABI 3's word hash of the block behind `s`, timed beside
/// `quatprop_bench_checksum` to show what the CRC costs more.
///
/// # Safety
/// As `quatprop_bench_checksum`.
#[cfg(feature = "bench-hooks")]
#[no_mangle]
pub unsafe extern "C" fn quatprop_bench_checksum_abi3(s: *const quatprop_t) -> u32 {
    // SAFETY: forwarded contract.
    unsafe { block(s) }.map_or(0, checksum_abi3)
}

/// Test hook of the link-time proof (feature `panic-selftest` only): a reachable panic.
#[cfg(feature = "panic-selftest")]
#[no_mangle]
pub extern "C" fn quatprop_panic_selftest(i: usize) -> u32 {
    let a = [1u32, 2, 3];
    a[core::hint::black_box(i)]
}

/// Any panic path that survives the optimizer and `--gc-sections` references this undefined symbol, so
/// the firmware link fails: no panic can cross the C boundary (the core's `panic-never` proof, for C).
#[cfg(not(test))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    extern "C" {
        fn quatprop_ffi_panic_is_reachable() -> !;
    }
    // SAFETY: never executed in a linked program: the symbol is defined nowhere, so a program in which
    // this call is reachable does not link.
    unsafe { quatprop_ffi_panic_is_reachable() }
}
