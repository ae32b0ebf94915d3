//! The fuzz targets' input decoding and invariants, one module per target. Each `run(bytes)` decodes the
//! bytes (any bytes: a short input reads as zeros) into calls on quatprop's public API and panics if an
//! invariant fails. The fuzz targets (`fuzz/fuzz_targets/*.rs`) call these, and this crate's own test
//! (`tests/replay.rs`) replays every seed and every crash input through exactly the same code on the stable
//! toolchain, with no fuzzing engine: `cargo test -p quatprop-fuzz-checks` in `fuzz/`.
//!
//! Floats come from a tag byte: a raw bit pattern (NaN payloads, ±∞, subnormals, huge values), a special
//! value, or a plausible value of the right scale, so that the propagators take many steps between the
//! adversarial calls and do not only refuse.

// Validation is written `!(x <= bound)` on purpose: NaN fails the comparison and lands in the error branch.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::needless_range_loop)]

pub mod burst;
pub mod calibration;
pub mod conversions;
pub mod delta;
pub mod dispatch;
pub mod estimator;
pub mod frontend;
pub mod kahan;
pub mod model;
pub mod precision;
pub mod push;

use quatprop::{Quat, Real, Vec3};
use std::fmt::Debug;

/// A cursor over the fuzzer's bytes; reads past the end give zeros.
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    /// Reads `data` from the start.
    pub fn new(data: &'a [u8]) -> Self {
        Self { data, pos: 0 }
    }

    /// `true` once every byte has been read.
    pub fn is_empty(&self) -> bool {
        self.pos >= self.data.len()
    }

    /// The next byte (0 past the end).
    pub fn u8(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }

    /// The next two bytes, little-endian.
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }

    /// The next four bytes, little-endian.
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    /// The next eight bytes, little-endian.
    pub fn u64(&mut self) -> u64 {
        u64::from(self.u32()) | (u64::from(self.u32()) << 32)
    }

    /// One bit of the next byte.
    pub fn bool(&mut self) -> bool {
        self.u8() & 1 == 1
    }

    /// `0..n` from the next byte (`n` ≥ 1).
    pub fn below(&mut self, n: usize) -> usize {
        usize::from(self.u8()) % n
    }

    /// A float of the working precision: raw bits (1 in 8), a special value (1 in 16), otherwise
    /// `i16/32768 · scale` with one of four decades of `scales`.
    pub fn real<T: Fz>(&mut self, scales: [f64; 4]) -> T {
        let tag = self.u8();
        match tag {
            0..=31 => T::raw(self),
            32..=47 => T::from_f64(SPECIAL[usize::from(tag - 32)]),
            _ => {
                let v = f64::from(self.u16() as i16) / 32768.0;
                T::from_f64(v * scales[usize::from(tag) % 4])
            }
        }
    }

    /// A time step: raw bits or a special value now and then, otherwise `previous` (so that the sample
    /// spacing is regular for History) or a positive plausible step (0.1 ms to 0.1 s).
    pub fn dt<T: Fz>(&mut self, previous: T) -> T {
        let tag = self.u8();
        match tag {
            0..=15 => T::raw(self),
            16..=31 => T::from_f64(SPECIAL[usize::from(tag - 16)]),
            32..=159 => previous,
            _ => {
                let v = (f64::from(self.u16()) + 1.0) / 65536.0;
                T::from_f64(v * [1e-4, 1e-3, 1e-2, 1e-1][usize::from(tag) % 4])
            }
        }
    }

    /// A vector with `real` components.
    pub fn vec<T: Fz>(&mut self, scales: [f64; 4]) -> Vec3<T> {
        Vec3::new(self.real(scales), self.real(scales), self.real(scales))
    }

    /// A quaternion with `real` components of scale about 1.
    pub fn quat<T: Fz>(&mut self) -> Quat<T> {
        let s = UNIT;
        Quat::new(self.real(s), self.real(s), self.real(s), self.real(s))
    }
}

/// Scales of a unit-sized quantity (quaternion components, matrix entries).
pub const UNIT: [f64; 4] = [1.0, 1.0, 1e-3, 1e3];
/// Scales of a body rate (rad/s).
pub const RATE: [f64; 4] = [1e-3, 0.3, 3.0, 30.0];
/// Scales of a delta angle (rad).
pub const ANGLE: [f64; 4] = [1e-6, 1e-3, 0.05, 0.5];

/// Values that break arithmetic.
pub const SPECIAL: [f64; 16] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    f64::MAX,
    -f64::MAX,
    f64::MIN_POSITIVE,
    5e-324,
    1e-3,
    1.0,
    -1.0,
    1e30,
    1e-30,
    core::f64::consts::PI,
    2.0,
];

/// The two precisions, with what the checks need beyond [`Real`].
pub trait Fz: Real {
    /// A raw bit pattern from the bytes.
    fn raw(b: &mut Bytes<'_>) -> Self;
    /// Machine epsilon as f64.
    const EPS: f64;
    /// Smallest positive subnormal as f64.
    const TINY: f64;
    /// Largest finite value as f64.
    const BIG: f64;
    /// The bit pattern, widened.
    fn bits(self) -> u64;
    /// The spacing of `T` at `|x|` (the ulp of `x` rounded to `T`), as f64.
    fn ulp(x: f64) -> f64;
    /// `i32` to `T` as the library converts counts and ticks.
    fn of_i32(v: i32) -> Self;
    /// Name for messages.
    const NAME: &'static str;
}

impl Fz for f32 {
    fn raw(b: &mut Bytes<'_>) -> Self {
        f32::from_bits(b.u32())
    }
    const EPS: f64 = f32::EPSILON as f64;
    const TINY: f64 = 1.401_298_464_324_817e-45;
    const BIG: f64 = f32::MAX as f64;
    fn bits(self) -> u64 {
        u64::from(self.to_bits())
    }
    fn ulp(x: f64) -> f64 {
        let a = (x as f32).abs();
        if !a.is_finite() {
            return f64::INFINITY;
        }
        f64::from(f32::from_bits(a.to_bits() + 1)) - f64::from(a)
    }
    fn of_i32(v: i32) -> Self {
        v as f32
    }
    const NAME: &'static str = "f32";
}

impl Fz for f64 {
    fn raw(b: &mut Bytes<'_>) -> Self {
        f64::from_bits(b.u64())
    }
    const EPS: f64 = f64::EPSILON;
    const TINY: f64 = 5e-324;
    const BIG: f64 = f64::MAX;
    fn bits(self) -> u64 {
        self.to_bits()
    }
    fn ulp(x: f64) -> f64 {
        let a = x.abs();
        if !a.is_finite() {
            return f64::INFINITY;
        }
        f64::from_bits(a.to_bits() + 1) - a
    }
    fn of_i32(v: i32) -> Self {
        f64::from(v)
    }
    const NAME: &'static str = "f64";
}

/// One input's first choice, the precision (`true`: f32), then the rest of it to `f32` or `f64`: the same
/// check instantiated for each. The start of every target that covers both precisions the same way.
pub fn by_precision(data: &[u8], f32: fn(&mut Bytes<'_>), f64: fn(&mut Bytes<'_>)) {
    let mut b = Bytes::new(data);
    if b.bool() {
        f32(&mut b)
    } else {
        f64(&mut b)
    }
}

/// One input's first choice, which of `checks` checks to run (passed on as `which`), then its precision
/// (`true`: f32), then the rest of it to that check in `f32` or `f64`. The start of every target that
/// groups several checks, each covering both precisions the same way.
pub fn by_check_and_precision(
    data: &[u8],
    checks: usize,
    f32: fn(&mut Bytes<'_>, usize),
    f64: fn(&mut Bytes<'_>, usize),
) {
    let mut b = Bytes::new(data);
    let which = b.below(checks);
    if b.bool() {
        f32(&mut b, which)
    } else {
        f64(&mut b, which)
    }
}

/// The bit patterns of a quaternion's components.
pub fn quat_bits<T: Fz>(q: Quat<T>) -> [u64; 4] {
    [q.w.bits(), q.x.bits(), q.y.bits(), q.z.bits()]
}

/// The bit patterns of a vector's components.
pub fn vec_bits<T: Fz>(v: Vec3<T>) -> [u64; 3] {
    [v.x.bits(), v.y.bits(), v.z.bits()]
}

/// Euclidean norm of a vector, in f64.
pub fn norm64<T: Real>(v: Vec3<T>) -> f64 {
    let v = v.to_f64();
    // Scaled by the largest component first: squaring a rate of 1e-289 rad/s underflows to 0 in f64, and
    // over a step of 1e287 s that rate turns 0.017 rad (found by `push`: the mirror's step-angle bound read
    // 0 rad and the FirstOrder bound was applied to a 0.017 rad Euler step).
    let s = v.x.abs().max(v.y.abs()).max(v.z.abs());
    if !(s > 0.0 && s.is_finite()) {
        return if v.x.is_nan() || v.y.is_nan() || v.z.is_nan() {
            f64::NAN
        } else {
            s
        };
    }
    let (x, y, z) = (v.x / s, v.y / s, v.z / s);
    s * (x * x + y * y + z * z).sqrt()
}

/// The rotation angle between two attitudes, measured in f64 on the widened components (exact widening;
/// the measurement's own error is a few f64 ulps).
pub fn angle64<T: Real>(a: Quat<T>, b: Quat<T>) -> f64 {
    a.to_f64().angle_to(b.to_f64())
}

/// `true` when `a` and `b` have the same `Debug` text: every field equal, bit for bit as far as the text
/// tells (it tells −0 from +0, and a NaN equals a NaN). `format!` on purpose: it runs std's precompiled
/// formatting into a `String`, which the fuzzer's instrumentation does not trace. Writing into a buffer
/// kept across calls (`write!` on a `String`) compiles `String`'s `fmt::Write` into this crate, traced on
/// every byte: measured twice as slow on `burst`.
pub fn same_text(a: &dyn Debug, b: &dyn Debug) -> bool {
    format!("{a:?}") == format!("{b:?}")
}

/// Asserts [`same_text`]; the texts are formatted for the message only when they differ.
#[track_caller]
pub fn assert_same_text(a: &dyn Debug, b: &dyn Debug, what: &dyn Debug) {
    if !same_text(a, b) {
        panic!("{what:?}: Debug texts differ:\n  {a:?}\n  {b:?}");
    }
}

/// `FUZZ_TRACE` is set (read once per process).
pub fn trace() -> bool {
    static TRACE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *TRACE.get_or_init(|| std::env::var_os("FUZZ_TRACE").is_some())
}
