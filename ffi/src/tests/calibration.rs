//! The calibration estimator's block (`calibration.rs`): its encoding fits with room; the C API learns
//! what the Rust `CalibrationEstimator<f32>` learns, bit for bit, on the tumbling body of `c/tumble.c`
//! (its bits are `expected/calibration.txt`, which `ffi/ci` compares with the C host test's);
//! every refusal has its code and changes no byte; every changed bit, byte and 32-bit burst of a block is
//! refused, through the check and through every entry point.

use super::super::calibration::{
    self, quatprop_calibration_estimator_at_rest, quatprop_calibration_estimator_correct,
    quatprop_calibration_estimator_get_bias, quatprop_calibration_estimator_get_calibration,
    quatprop_calibration_estimator_get_gain, quatprop_calibration_estimator_init,
    quatprop_calibration_estimator_update, Block, MAGIC, PAYLOAD, SUM, TAG,
};
use super::super::*;
use super::check::{bit_syndromes, rank, single_bits_and_pairs, Rng};
use quatprop::frontend::CalibrationEstimator;
use quatprop::Vec3;
use std::collections::HashSet;

type Estimator = CalibrationEstimator<f32>;

const SIZE: usize = QUATPROP_CALIBRATION_ESTIMATOR_SIZE;
const BITS: usize = 8 * SIZE;

// ---------------------------------------------------------------------------------------------------------
// The tumbling body (c/tumble.c, the same f32 arithmetic in the same order).

/// Samples of the scene, 2 min at 100 Hz.
const SAMPLES: u32 = 12_000;
const DT: f32 = 0.01;
/// cos and sin of ω·DT for ω = 1, 0.37 and 0.21 rad/s (f32, correctly rounded; the shortest decimals that
/// give them, as c/tumble.c writes them).
const STEP: [[f32; 2]; 3] = [
    [0.99995, 0.009999833],
    [0.99999315, 0.0036999916],
    [0.9999978, 0.0020999985],
];

/// A body tumbling with the rate `(cos t, sin 0.37t, 0.6 cos 0.21t)` (rad/s; each by a rotation
/// recurrence, no sin or cos), its attitude from the identity (each step's quaternion from its rotation
/// vector by Taylor series to the fourth power, exact in f32 at these angles), read by a gyro 1 % high on
/// x and an ideal accelerometer (gravity 9.81 in the body at the sample's end).
struct Tumble {
    c: [f32; 3],
    s: [f32; 3],
    q: [f32; 4],
    k: u32,
}

impl Tumble {
    fn new() -> Self {
        Self {
            c: [1.0; 3],
            s: [0.0; 3],
            q: [1.0, 0.0, 0.0, 0.0],
            k: 0,
        }
    }
}

impl Iterator for Tumble {
    /// The gyro's reading and the accelerometer's.
    type Item = ([f32; 3], [f32; 3]);
    fn next(&mut self) -> Option<Self::Item> {
        if self.k >= SAMPLES {
            return None;
        }
        let w = [self.c[0], self.s[1], 0.6 * self.c[2]];
        let h = 0.5 * DT;
        let v = [w[0] * h, w[1] * h, w[2] * h];
        let x2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        let cp = 1.0 - x2 / 2.0 + x2 * x2 / 24.0;
        let sc = 1.0 - x2 / 6.0 + x2 * x2 / 120.0;
        let d = [cp, v[0] * sc, v[1] * sc, v[2] * sc];
        let q = self.q;
        let p = [
            q[0] * d[0] - q[1] * d[1] - q[2] * d[2] - q[3] * d[3],
            q[0] * d[1] + q[1] * d[0] + q[2] * d[3] - q[3] * d[2],
            q[0] * d[2] - q[1] * d[3] + q[2] * d[0] + q[3] * d[1],
            q[0] * d[3] + q[1] * d[2] - q[2] * d[1] + q[3] * d[0],
        ];
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]).sqrt();
        let q = [p[0] / n, p[1] / n, p[2] / n, p[3] / n];
        self.q = q;
        let g = 9.81_f32;
        let accel = [
            2.0 * (q[1] * q[3] - q[0] * q[2]) * g,
            2.0 * (q[2] * q[3] + q[0] * q[1]) * g,
            (1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2])) * g,
        ];
        for (i, [cs, sn]) in STEP.into_iter().enumerate() {
            let (c, s) = (self.c[i], self.s[i]);
            self.c[i] = c * cs - s * sn;
            self.s[i] = s * cs + c * sn;
        }
        self.k += 1;
        Some(([1.01 * w[0], w[1], w[2]], accel))
    }
}

/// The scene's estimator (`with_motion_noise(0.01, 0.01, 0.0087, 0.001°)`: a still accelerometer).
fn scene_estimator() -> Estimator {
    Estimator::with_motion_noise(0.01, 0.01, 0.0087, 0.001_f64.to_radians()).unwrap()
}

/// What the C host test prints of a learned estimator: the gain and its standard deviations, the bias,
/// the calibration and the correction of (1.01, 0, 0), as bits.
struct Learned {
    gain: [[f32; 3]; 3],
    std_dev: [[f32; 3]; 3],
    bias: [f32; 3],
    offset: [f32; 3],
    sensitivity: [f32; 3],
    misalignment: [[f32; 3]; 3],
    corrected: [f32; 3],
}

impl Learned {
    fn of(e: &Estimator) -> Self {
        let arr = |v: Vec3<f32>| [v.x, v.y, v.z];
        let c = e.calibration();
        Self {
            gain: e.gain(),
            std_dev: e.gain_std_dev(),
            bias: arr(e.bias()),
            offset: arr(c.offset()),
            sensitivity: arr(c.sensitivity()),
            misalignment: c.misalignment(),
            corrected: arr(e.correct(GyroSample::new(Vec3::new(1.01, 0.0, 0.0))).rate),
        }
    }

    /// Through the C API.
    fn of_c(e: &quatprop_calibration_estimator_t) -> Self {
        let mut l = Self {
            gain: [[0.0; 3]; 3],
            std_dev: [[0.0; 3]; 3],
            bias: [0.0; 3],
            offset: [0.0; 3],
            sensitivity: [0.0; 3],
            misalignment: [[0.0; 3]; 3],
            corrected: [0.0; 3],
        };
        let one = [1.01_f32, 0.0, 0.0];
        // SAFETY: every pointer is to a live local of the right size.
        let got = unsafe {
            [
                quatprop_calibration_estimator_get_gain(
                    e,
                    l.gain.as_mut_ptr().cast(),
                    l.std_dev.as_mut_ptr().cast(),
                ),
                quatprop_calibration_estimator_get_bias(e, l.bias.as_mut_ptr()),
                quatprop_calibration_estimator_get_calibration(
                    e,
                    l.offset.as_mut_ptr(),
                    l.sensitivity.as_mut_ptr(),
                    l.misalignment.as_mut_ptr().cast(),
                ),
                quatprop_calibration_estimator_correct(e, one.as_ptr(), l.corrected.as_mut_ptr()),
            ]
        };
        assert_eq!(got, [S::QUATPROP_OK; 4]);
        l
    }

    /// The line `c/host_test.c` prints (its format, `%08x` of each float's bits).
    fn line(&self) -> String {
        let hex = |v: &[f32]| {
            v.iter()
                .map(|x| format!("{:08x}", x.to_bits()))
                .collect::<Vec<_>>()
                .join(" ")
        };
        format!(
            "calibration samples={SAMPLES} gain {} sd {} bias {} offset {} sensitivity {} misalignment {} corrected {}",
            hex(self.gain.as_flattened()),
            hex(self.std_dev.as_flattened()),
            hex(&self.bias),
            hex(&self.offset),
            hex(&self.sensitivity),
            hex(self.misalignment.as_flattened()),
            hex(&self.corrected),
        )
    }
}

fn zeroed() -> quatprop_calibration_estimator_t {
    quatprop_calibration_estimator_t {
        _opaque: [0; QUATPROP_CALIBRATION_ESTIMATOR_WORDS],
    }
}

fn bytes(e: &quatprop_calibration_estimator_t) -> Block {
    // SAFETY: the block is QUATPROP_CALIBRATION_ESTIMATOR_SIZE initialized bytes.
    unsafe { *(e as *const quatprop_calibration_estimator_t).cast::<Block>() }
}

fn block_of(b: &Block) -> quatprop_calibration_estimator_t {
    // SAFETY: any QUATPROP_CALIBRATION_ESTIMATOR_SIZE bytes are a block (plain u64 words).
    unsafe { core::mem::transmute::<Block, quatprop_calibration_estimator_t>(*b) }
}

/// The scene's estimator through the C API after `n` samples.
fn c_after(n: usize) -> quatprop_calibration_estimator_t {
    let mut e = zeroed();
    // SAFETY: pointers to live locals of the right size.
    unsafe {
        let st =
            quatprop_calibration_estimator_init(&mut e, 0.01, 0.01, 0.0087, 0.001_f64.to_radians());
        assert_eq!(st, S::QUATPROP_OK);
        for (r, a) in Tumble::new().take(n) {
            let st = quatprop_calibration_estimator_update(&mut e, r.as_ptr(), a.as_ptr(), 0.01);
            assert_eq!(st, S::QUATPROP_OK);
        }
    }
    e
}

// ---------------------------------------------------------------------------------------------------------

/// The encoding's length, fresh, while the low-pass filters average their first τ and once they filter;
/// the worst case adds what its varints can grow (five `Option<u32>` counts of the low-pass filters, each
/// at most 6 bytes, and the filter's `u32` sample count, at most 5). The block's doc states both.
#[test]
fn the_estimator_fits_its_block_with_room() {
    let mut buf = [0u8; SIZE];
    let mut longest = 0;
    let mut e = scene_estimator();
    for (k, (r, a)) in Tumble::new().take(400).enumerate() {
        if k % 50 == 0 {
            longest = longest.max(postcard::to_slice(&e, &mut buf).unwrap().len());
        }
        e.update(Vec3::new(r[0], r[1], r[2]), Vec3::new(a[0], a[1], a[2]), DT)
            .unwrap();
    }
    let fresh = postcard::to_slice(&scene_estimator(), &mut buf)
        .unwrap()
        .len();
    // A fresh estimator's counts are `Some(0)` (2 bytes each) and its sample count 300 (2 bytes).
    let worst = fresh + 5 * (6 - 2) + (5 - 2);
    assert!(longest <= worst);
    println!(
        "calibration estimator: encoded {fresh} bytes (at most {longest} seen), at most {worst} of {PAYLOAD}; {} in memory",
        core::mem::size_of::<Estimator>()
    );
    assert!(worst <= PAYLOAD, "{worst} > {PAYLOAD}");
    let src = include_str!("../calibration.rs");
    let at = src
        .find("pub const QUATPROP_CALIBRATION_ESTIMATOR_SIZE")
        .unwrap();
    let doc: String = src[..at]
        .lines()
        .rev()
        .take_while(|l| l.starts_with("///"))
        .collect();
    let stated = format!("({fresh} bytes, {worst} at most");
    assert!(doc.contains(&stated), "{stated} not in {doc:?}");
}

/// The C default is the Rust one, the same `double`.
#[test]
fn the_default_motion_noise_is_the_libraries() {
    assert_eq!(
        QUATPROP_DEFAULT_MOTION_NOISE.to_bits(),
        Estimator::DEFAULT_MOTION_NOISE.to_bits()
    );
    let mut e = zeroed();
    // SAFETY: a live local.
    let st = unsafe {
        quatprop_calibration_estimator_init(
            &mut e,
            0.01,
            0.01,
            0.0087,
            QUATPROP_DEFAULT_MOTION_NOISE,
        )
    };
    assert_eq!(st, S::QUATPROP_OK);
    assert!(calibration::load(&bytes(&e)).unwrap() == Estimator::new(0.01, 0.01, 0.0087).unwrap());
}

/// The scene through the C API (an encoded block decoded, updated and sealed again at every sample)
/// learns what the Rust estimator learns, bit for bit, and the bits are `expected/calibration.txt`
/// (QUATPROP_BLESS=1 writes it), which `ffi/ci` compares with the C host test's. The x scale is learned
/// to 2e-4.
#[test]
fn the_c_api_learns_what_rust_learns_bit_for_bit() {
    let mut rust = scene_estimator();
    for (r, a) in Tumble::new() {
        rust.update(Vec3::new(r[0], r[1], r[2]), Vec3::new(a[0], a[1], a[2]), DT)
            .unwrap();
    }
    let c = c_after(SAMPLES as usize);
    assert!(calibration::load(&bytes(&c)).unwrap() == rust);
    let (want, got) = (Learned::of(&rust), Learned::of_c(&c));
    assert_eq!(got.line(), want.line());
    let x = want.gain[0][0];
    println!(
        "tumble: x scale {x} (1/1.01 = {}, error {:.2e})",
        1.0 / 1.01_f32,
        x - 1.0 / 1.01
    );
    assert!((x - 1.0 / 1.01).abs() < 2.0e-4);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("expected/calibration.txt");
    let line = want.line() + "\n";
    if std::env::var_os("QUATPROP_BLESS").is_some() {
        std::fs::write(&path, &line).unwrap();
    }
    assert_eq!(
        std::fs::read_to_string(&path).unwrap_or_default(),
        line,
        "ffi/expected/calibration.txt is stale: QUATPROP_BLESS=1 cargo test calibration (in ffi/)"
    );
}

/// A correction handed to a state (`quatprop_set_calibration`) is the estimator's, bit for bit.
#[test]
fn the_calibration_handed_to_a_state_corrects_as_the_estimator() {
    let e = c_after(3000);
    let l = Learned::of_c(&e);
    let mut s = quatprop_t {
        _opaque: [0; QUATPROP_STATE_WORDS],
    };
    let c = quatprop_config_t {
        scheme: QUATPROP_SCHEME_EULER,
        stabilizer: QUATPROP_STABILIZER_OFF,
        every: 1,
        input: QUATPROP_INPUT_HOLD,
        coning: 0,
        accumulator: QUATPROP_ACCUMULATOR_PLAIN,
        q0: Quat::IDENTITY.into(),
    };
    // SAFETY: pointers to live locals of the right size.
    unsafe {
        assert_eq!(quatprop_init(&mut s, &c), S::QUATPROP_OK);
        let st = quatprop_set_calibration(
            &mut s,
            l.offset.as_ptr(),
            l.sensitivity.as_ptr(),
            l.misalignment.as_ptr().cast(),
        );
        assert_eq!(st, S::QUATPROP_OK);
    }
    let cal = load(&state_bytes(&s)).unwrap().front.calibration.unwrap();
    for r in [[1.01_f32, 0.0, 0.0], [0.3, -0.7, 0.2], [-2.0, 0.5, 1.5]] {
        let mut out = [0.0_f32; 3];
        // SAFETY: live locals.
        let st =
            unsafe { quatprop_calibration_estimator_correct(&e, r.as_ptr(), out.as_mut_ptr()) };
        assert_eq!(st, S::QUATPROP_OK);
        let w = cal.apply(GyroSample::new(vec3(r))).rate;
        assert_eq!([w.x, w.y, w.z].map(f32::to_bits), out.map(f32::to_bits));
    }
}

fn state_bytes(s: &quatprop_t) -> super::super::Block {
    // SAFETY: a `quatprop_t` is QUATPROP_STATE_SIZE initialized bytes.
    unsafe { *(s as *const quatprop_t).cast::<super::super::Block>() }
}

/// Every refusal has its code and leaves the block's bytes as they were; nothing is written to an output
/// of a refused call.
#[test]
fn refusals_have_their_codes_and_change_nothing() {
    let mut e = c_after(500);
    let before = bytes(&e);
    let (ok, nan, inf) = (
        [0.1_f32, 0.2, 0.3],
        [0.0, f32::NAN, 0.0],
        [f32::INFINITY, 0.0, 0.0],
    );
    let g = [0.0_f32, 0.0, 9.81];
    let mut out = [7.0_f32; 9];
    let mut out2 = [7.0_f32; 9];
    let p = &mut e as *mut quatprop_calibration_estimator_t;
    let null = core::ptr::null_mut::<quatprop_calibration_estimator_t>();
    // SAFETY: pointers to live locals of the right size, or NULL, or misaligned (refused, not read).
    let got = unsafe {
        let mis = (out.as_mut_ptr() as *mut u8).add(1).cast::<f32>();
        [
            (
                quatprop_calibration_estimator_update(p, nan.as_ptr(), g.as_ptr(), 0.01),
                S::QUATPROP_NON_FINITE_RATE,
            ),
            (
                quatprop_calibration_estimator_update(p, inf.as_ptr(), g.as_ptr(), 0.01),
                S::QUATPROP_NON_FINITE_RATE,
            ),
            (
                quatprop_calibration_estimator_update(p, ok.as_ptr(), nan.as_ptr(), 0.01),
                S::QUATPROP_NON_FINITE_AUX,
            ),
            (
                quatprop_calibration_estimator_update(p, ok.as_ptr(), g.as_ptr(), 0.0),
                S::QUATPROP_NON_POSITIVE_STEP,
            ),
            (
                quatprop_calibration_estimator_update(p, ok.as_ptr(), g.as_ptr(), -0.01),
                S::QUATPROP_NON_POSITIVE_STEP,
            ),
            (
                quatprop_calibration_estimator_update(p, ok.as_ptr(), g.as_ptr(), f64::NAN),
                S::QUATPROP_NON_FINITE_STEP,
            ),
            (
                quatprop_calibration_estimator_update(p, ok.as_ptr(), g.as_ptr(), 1e300),
                S::QUATPROP_NON_FINITE_STEP,
            ),
            (
                quatprop_calibration_estimator_update(p, core::ptr::null(), g.as_ptr(), 0.01),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_update(p, ok.as_ptr(), core::ptr::null(), 0.01),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_update(p, mis, g.as_ptr(), 0.01),
                S::QUATPROP_MISALIGNED_POINTER,
            ),
            (
                quatprop_calibration_estimator_update(null, ok.as_ptr(), g.as_ptr(), 0.01),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_correct(p, nan.as_ptr(), out.as_mut_ptr()),
                S::QUATPROP_NON_FINITE_RATE,
            ),
            (
                quatprop_calibration_estimator_correct(p, ok.as_ptr(), core::ptr::null_mut()),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_correct(p, core::ptr::null(), out.as_mut_ptr()),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_correct(null, ok.as_ptr(), out.as_mut_ptr()),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_get_gain(p, out.as_mut_ptr(), core::ptr::null_mut()),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_get_gain(
                    p,
                    core::ptr::null_mut(),
                    out2.as_mut_ptr(),
                ),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_get_gain(null, out.as_mut_ptr(), out2.as_mut_ptr()),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_get_bias(p, core::ptr::null_mut()),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_get_bias(null, out.as_mut_ptr()),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_get_calibration(
                    p,
                    out.as_mut_ptr(),
                    out2.as_mut_ptr(),
                    core::ptr::null_mut(),
                ),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_get_calibration(
                    p,
                    core::ptr::null_mut(),
                    out2.as_mut_ptr(),
                    out.as_mut_ptr(),
                ),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_at_rest(null),
                S::QUATPROP_NULL_POINTER,
            ),
            (
                quatprop_calibration_estimator_init(p, 0.0, 0.01, 0.0087, 1e-3),
                S::QUATPROP_NON_POSITIVE_STEP,
            ),
            (
                quatprop_calibration_estimator_init(p, f64::INFINITY, 0.01, 0.0087, 1e-3),
                S::QUATPROP_NON_FINITE_STEP,
            ),
            (
                quatprop_calibration_estimator_init(p, 0.01, -0.01, 0.0087, 1e-3),
                S::QUATPROP_INVALID_ESTIMATOR,
            ),
            (
                quatprop_calibration_estimator_init(p, 0.01, 0.01, f64::NAN, 1e-3),
                S::QUATPROP_INVALID_ESTIMATOR,
            ),
            (
                quatprop_calibration_estimator_init(p, 0.01, 0.051, 0.0087, 1e-3),
                S::QUATPROP_INVALID_ESTIMATOR,
            ),
            (
                quatprop_calibration_estimator_init(p, 0.01, 0.01, 0.0087, 0.0),
                S::QUATPROP_INVALID_ESTIMATOR,
            ),
            (
                quatprop_calibration_estimator_init(p, 0.01, 0.01, 0.0087, f64::INFINITY),
                S::QUATPROP_INVALID_ESTIMATOR,
            ),
            (
                quatprop_calibration_estimator_init(null, 0.01, 0.01, 0.0087, 1e-3),
                S::QUATPROP_NULL_POINTER,
            ),
        ]
    };
    for (i, (got, want)) in got.into_iter().enumerate() {
        assert_eq!(got, want, "call {i}");
    }
    assert!(bytes(&e) == before, "a refused call changed the block");
    assert!(
        out.iter().chain(&out2).all(|&x| x == 7.0),
        "a refused call wrote an output"
    );
    // A block never set up, or one holding another tag, is not an estimator.
    for b in [[0u8; SIZE], {
        let mut b = before;
        b[TAG..TAG + 4].copy_from_slice(&0x5150_4634_u32.to_ne_bytes()); // "QPF4", quatprop_t's
        b
    }] {
        let mut z = block_of(&b);
        // SAFETY: live locals.
        let got = unsafe {
            [
                quatprop_calibration_estimator_update(&mut z, ok.as_ptr(), g.as_ptr(), 0.01),
                quatprop_calibration_estimator_at_rest(&mut z),
                quatprop_calibration_estimator_get_bias(&z, out.as_mut_ptr()),
            ]
        };
        assert_eq!(got, [S::QUATPROP_NOT_INITIALIZED; 3]);
        assert!(bytes(&z) == b);
    }
    // at_rest: the residual bias restarts at zero, the gain stays.
    let mut gain = [[0.0_f32; 3]; 3];
    let mut sd = [[0.0_f32; 3]; 3];
    let mut bias = [1.0_f32; 3];
    let l = Learned::of_c(&e);
    // SAFETY: live locals.
    unsafe {
        assert_eq!(
            quatprop_calibration_estimator_at_rest(&mut e),
            S::QUATPROP_OK
        );
        assert_eq!(
            quatprop_calibration_estimator_get_bias(&e, bias.as_mut_ptr()),
            S::QUATPROP_OK
        );
        let st = quatprop_calibration_estimator_get_gain(
            &e,
            gain.as_mut_ptr().cast(),
            sd.as_mut_ptr().cast(),
        );
        assert_eq!(st, S::QUATPROP_OK);
    }
    assert_eq!(bias, [0.0; 3]);
    assert_eq!(gain, l.gain);
}

// ---------------------------------------------------------------------------------------------------------
// The block's check.

/// What a call must return for a changed block.
fn expected(b: &Block) -> quatprop_status_t {
    if word(b, TAG / 4) != MAGIC {
        S::QUATPROP_NOT_INITIALIZED
    } else {
        S::QUATPROP_CORRUPTED_STATE
    }
}

/// Three blocks: fresh, while the low-pass filters average (150 samples), filtering (3000).
fn blocks() -> [(&'static str, Block); 3] {
    [
        ("fresh", bytes(&c_after(0))),
        ("averaging", bytes(&c_after(150))),
        ("learning", bytes(&c_after(3000))),
    ]
}

/// The block is sealed as `quatprop_t`'s: its checksum is the CRC-32C of every byte before it; it round
/// trips; any changed byte (each changed three ways) is caught by the check.
#[test]
fn a_block_round_trips_and_any_changed_byte_is_caught() {
    let oracle = ::crc::Crc::<u32>::new(&::crc::CRC_32_ISCSI);
    for (name, b) in blocks() {
        assert_eq!(calibration::checksum(&b), Some(oracle.checksum(&b[..SUM])));
        assert_eq!(stored_sum(&b), oracle.checksum(&b[..SUM]));
        let e = calibration::load(&b).unwrap();
        assert!(calibration::encode(&e).unwrap() == b, "{name}");
        for i in 0..SIZE {
            for x in [0x01u8, 0x80, 0xff] {
                let mut c = b;
                c[i] ^= x;
                assert_eq!(
                    calibration::load(&c).err(),
                    Some(expected(&c)),
                    "{name}: byte {i} ^ {x:#x}"
                );
            }
        }
    }
}

/// The CRC over this longer block, from its syndromes (as `check.rs` for `quatprop_t`): every error of 1
/// to 3 bits and every burst within 32 bits changes the syndrome, so none is ever sealed (12 256 data
/// bits: CRC-32C's Hamming distance is still 4).
#[test]
fn the_crc_detects_every_error_of_up_to_3_bits_and_every_32_bit_burst() {
    let (_, b) = blocks()[2];
    let s = bit_syndromes(&b, 6, 5_000);
    let singles: HashSet<u32> = s.iter().copied().collect();
    assert!(!singles.contains(&0));
    assert_eq!(singles.len(), BITS);
    let mut pairs = 0usize;
    for i in 0..BITS {
        for j in i + 1..BITS {
            assert!(
                !singles.contains(&(s[i] ^ s[j])),
                "3 bits: {i}, {j} and another"
            );
            pairs += 1;
        }
    }
    for start in 0..=BITS - 32 {
        assert_eq!(rank(&s[start..start + 32]), 32, "burst from bit {start}");
    }
    println!(
        "calibration estimator block: {BITS} single bits, {pairs} pairs and every third bit, {} bursts of 32 bits: none passes the CRC",
        BITS - 31
    );
}

/// Through the C entry points, on the three blocks: every bit flipped, every byte inverted, 2048 random
/// pairs of bits. Each entry point but init returns the expected code, leaves the bytes as they were and
/// writes no output.
#[test]
fn the_entry_points_refuse_damaged_blocks_and_change_nothing() {
    let mut rng = Rng(7);
    let mut calls = 0usize;
    for (name, b) in blocks() {
        let mut damaged = single_bits_and_pairs(&b, &mut rng, 2048);
        for k in 0..SIZE {
            let mut c = b;
            c[k] ^= 0xff;
            damaged.push(c);
        }
        let (r, a) = ([0.1_f32, 0.2, 0.3], [0.0_f32, 0.0, 9.81]);
        for c in &damaged {
            let want = expected(c);
            let mut e = block_of(c);
            let mut out = [7.0_f32; 9];
            let mut out2 = [7.0_f32; 9];
            let mut out3 = [7.0_f32; 9];
            // SAFETY: pointers to live locals of the right size.
            let got = unsafe {
                [
                    quatprop_calibration_estimator_update(&mut e, r.as_ptr(), a.as_ptr(), 0.01),
                    quatprop_calibration_estimator_correct(&e, r.as_ptr(), out.as_mut_ptr()),
                    quatprop_calibration_estimator_at_rest(&mut e),
                    quatprop_calibration_estimator_get_gain(
                        &e,
                        out.as_mut_ptr(),
                        out2.as_mut_ptr(),
                    ),
                    quatprop_calibration_estimator_get_bias(&e, out.as_mut_ptr()),
                    quatprop_calibration_estimator_get_calibration(
                        &e,
                        out.as_mut_ptr(),
                        out2.as_mut_ptr(),
                        out3.as_mut_ptr(),
                    ),
                ]
            };
            assert_eq!(got, [want; 6], "{name}");
            assert!(bytes(&e) == *c, "{name}: a refused call changed the block");
            assert!(
                out.iter().chain(&out2).chain(&out3).all(|&x| x == 7.0),
                "{name}: a refused call wrote an output"
            );
            calls += 6;
        }
    }
    println!("{calls} calls on damaged calibration estimator blocks: all refused with their code, none changed a byte");
}
